//! Archives with limits (`io::import::archive_limits`, `stream_zip`): a zip inside a zip read as a stream and the same
//! as the folder, and every limit hit by a hostile archive (a deep nest as a zip quine makes, a
//! 2 GiB entry of zeros with an honest, a lying and a deferred header, 100 000 empty entries, a
//! small total budget) refused with a named error while the other files load, within bounded
//! memory.

mod common;
use common::{assert_peak_grew_less, peak_rss};
use flate2::write::DeflateEncoder;
use flate2::{Compression, FlushCompress};
use pdr::io::import::{import_all, ArchiveLimits, Budget, DirSet, Log, MemSet, ZipSet};
use pdr::io::ParseError;
use std::io::{Cursor, Write};
use zip::write::SimpleFileOptions;
use zip::CompressionMethod;

/// A small valid log (a pdr-log), to show that the other files of an upload still load.
fn pdrlog() -> (String, Vec<u8>) {
    let p = common::import::fixtures().join("walk.pdrlog");
    ("walk.pdrlog".into(), std::fs::read(p).unwrap())
}

/// A zip of `files`; `stream` writes it as a streaming zipper does, with data descriptors.
fn zip_of(files: &[(String, Vec<u8>)], method: CompressionMethod, stream: bool) -> Vec<u8> {
    let opts = SimpleFileOptions::default().compression_method(method);
    if stream {
        let mut w = zip::ZipWriter::new_stream(Vec::new());
        for (name, bytes) in files {
            w.start_file(name.as_str(), opts).unwrap();
            w.write_all(bytes).unwrap();
        }
        w.finish().unwrap().into_inner()
    } else {
        let mut w = zip::ZipWriter::new(Cursor::new(Vec::new()));
        for (name, bytes) in files {
            w.start_file(name.as_str(), opts).unwrap();
            w.write_all(bytes).unwrap();
        }
        w.finish().unwrap().into_inner()
    }
}

fn oks(results: &[Result<Log, ParseError>]) -> Vec<&Log> {
    results.iter().filter_map(|r| r.as_ref().ok()).collect()
}

fn errors(results: &[Result<Log, ParseError>]) -> Vec<&ParseError> {
    results.iter().filter_map(|r| r.as_ref().err()).collect()
}

#[test]
fn a_zip_in_a_zip_reads_as_the_folder_whatever_the_zipper() {
    let files = common::import::load("sensor_logger_android", "Recording/");
    let folder = import_all(&mut MemSet::new(files.clone()));
    let folder = oks(&folder)[0].records.clone();
    for inner_method in [CompressionMethod::Deflated, CompressionMethod::Stored] {
        for inner_stream in [false, true] {
            for outer_method in [CompressionMethod::Deflated, CompressionMethod::Stored] {
                let inner = zip_of(&files, inner_method, inner_stream);
                let outer = zip_of(&[("inner.zip".into(), inner)], outer_method, true);
                let got = import_all(&mut MemSet::new(vec![("outer.zip".into(), outer)]));
                let what =
                    format!("inner {inner_method:?} stream {inner_stream}, outer {outer_method:?}");
                if inner_method == CompressionMethod::Stored && inner_stream {
                    // A stored entry whose size comes after its data cannot be streamed.
                    let e = errors(&got);
                    assert_eq!(e.len(), 1, "{what}: {got:#?}");
                    assert_eq!(e[0].file, "outer.zip/inner.zip", "{what}");
                    assert!(
                        e[0].message.contains("cannot be streamed"),
                        "{what}: {}",
                        e[0]
                    );
                    continue;
                }
                assert_eq!(got.len(), 1, "{what}: {got:#?}");
                let log = got[0].as_ref().unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(log.records, folder, "{what}");
                assert_eq!(log.source, "outer.zip/inner.zip/Recording", "{what}");
            }
        }
    }
}

#[test]
fn a_zip_in_a_zip_on_disk_too() {
    let files = common::import::load("phyphox", "");
    let inner = zip_of(&files, CompressionMethod::Deflated, false);
    let dir = std::env::temp_dir().join(format!("pdr-archives-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("outer.zip");
    std::fs::write(
        &path,
        zip_of(
            &[("phyphox.zip".into(), inner)],
            CompressionMethod::Deflated,
            false,
        ),
    )
    .unwrap();
    let got = import_all(&mut DirSet::new(&path).unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(oks(&got).len(), 1, "{got:#?}");
    let direct = import_all(&mut MemSet::new(files));
    assert_eq!(oks(&got)[0].records, oks(&direct)[0].records);
}

/// Archives nested ten deep. A zip quine (a zip that contains itself) is this nest made
/// infinite: the depth is refused before the third archive is looked into, so it cannot
/// behave otherwise.
#[test]
fn a_deep_nest_stops_at_depth_two_and_the_rest_loads() {
    let mut z = zip_of(&[pdrlog()], CompressionMethod::Deflated, false);
    for level in (1..10).rev() {
        z = zip_of(
            &[(format!("level{level}.zip"), z)],
            CompressionMethod::Deflated,
            level % 2 == 0,
        );
    }
    let got = import_all(&mut MemSet::new(vec![("nest.zip".into(), z), pdrlog()]));
    let e = errors(&got);
    assert_eq!(e.len(), 1, "{got:#?}");
    assert_eq!(e[0].file, "nest.zip/level1.zip/level2.zip");
    assert!(e[0].message.contains("archive limit `depth`"), "{}", e[0]);
    assert_eq!(oks(&got).len(), 1, "the pdr-log beside the nest loads");
    // Two deep is read.
    let two = zip_of(
        &[(
            "in.zip".into(),
            zip_of(&[pdrlog()], CompressionMethod::Deflated, true),
        )],
        CompressionMethod::Deflated,
        true,
    );
    let got = import_all(&mut MemSet::new(vec![("two.zip".into(), two)]));
    assert_eq!(oks(&got).len(), 1, "{got:#?}");
}

/// A raw deflate stream of a pdr-log header (so that the import reads on past the head) and
/// then `n_mib` MiB of zeros, made fast: one MiB compressed with a full flush (no
/// back-references across it), repeated, then a final empty block. With its CRC-32.
fn deflated_zeros(n_mib: u64) -> (Vec<u8>, u32) {
    let head = b"# pdr-log 1\n";
    let zeros = vec![0u8; 1 << 20];
    let full = |bytes: &[u8]| {
        let mut enc = flate2::Compress::new(Compression::best(), false);
        let mut out = Vec::with_capacity(8192);
        enc.compress_vec(bytes, &mut out, FlushCompress::Full)
            .unwrap();
        assert_eq!(enc.total_in(), bytes.len() as u64);
        out
    };
    let chunk = full(&zeros);
    let mut data = full(head);
    for _ in 0..n_mib {
        data.extend_from_slice(&chunk);
    }
    let mut end = DeflateEncoder::new(Vec::new(), Compression::best());
    end.flush().unwrap();
    data.extend(end.finish().unwrap());
    let mut mib = crc32fast::Hasher::new();
    mib.update(&zeros);
    let mut crc = crc32fast::Hasher::new();
    crc.update(head);
    for _ in 0..n_mib {
        crc.combine(&mib);
    }
    (data, crc.finalize())
}

/// A one-entry zip written by hand: `declared` is the size the headers state, `descriptor`
/// defers the sizes to a data descriptor after the data.
fn zip_raw(name: &str, data: &[u8], crc: u32, declared: u64, descriptor: bool) -> Vec<u8> {
    let mut out = Vec::new();
    let flags: u16 = if descriptor { 1 << 3 } else { 0 };
    let (c, s) = (data.len() as u32, declared as u32);
    let (hc, hs, hcrc) = if descriptor { (0, 0, 0) } else { (c, s, crc) };
    out.extend(0x0403_4b50u32.to_le_bytes());
    out.extend(20u16.to_le_bytes());
    out.extend(flags.to_le_bytes());
    out.extend(8u16.to_le_bytes());
    out.extend([0u8; 4]);
    out.extend(hcrc.to_le_bytes());
    out.extend(hc.to_le_bytes());
    out.extend(hs.to_le_bytes());
    out.extend((name.len() as u16).to_le_bytes());
    out.extend(0u16.to_le_bytes());
    out.extend(name.as_bytes());
    out.extend(data);
    if descriptor {
        out.extend(0x0807_4b50u32.to_le_bytes());
        out.extend(crc.to_le_bytes());
        out.extend(c.to_le_bytes());
        out.extend(s.to_le_bytes());
    }
    let cd = out.len() as u32;
    out.extend(0x0201_4b50u32.to_le_bytes());
    out.extend(20u16.to_le_bytes());
    out.extend(20u16.to_le_bytes());
    out.extend(flags.to_le_bytes());
    out.extend(8u16.to_le_bytes());
    out.extend([0u8; 4]);
    out.extend(crc.to_le_bytes());
    out.extend(c.to_le_bytes());
    out.extend(s.to_le_bytes());
    out.extend((name.len() as u16).to_le_bytes());
    out.extend([0u8; 12]);
    out.extend(0u32.to_le_bytes()); // local header offset
    out.extend(name.as_bytes());
    let cd_len = out.len() as u32 - cd;
    out.extend(0x0605_4b50u32.to_le_bytes());
    out.extend([0u8; 4]);
    out.extend(1u16.to_le_bytes());
    out.extend(1u16.to_le_bytes());
    out.extend(cd_len.to_le_bytes());
    out.extend(cd.to_le_bytes());
    out.extend(0u16.to_le_bytes());
    out
}

/// A 2 GiB entry of zeros (2 MB compressed) behind a pdr-log header, with an
/// honest header, a header that says 10 MB, and sizes deferred to a data descriptor; each at
/// the top and inside another zip. Each is refused by the limit named, the pdr-log beside it
/// loads, and memory stays bounded.
#[test]
fn two_gibibytes_of_zeros_are_refused_in_bounded_memory() {
    let (data, crc) = deflated_zeros(2048);
    assert!(data.len() < 3 << 20, "{} bytes", data.len());
    let before = peak_rss();
    let cases = [
        ("honest", 2u64 << 30, false, "`ratio`"),
        ("lying", 10 << 20, false, "`declared size`"),
        ("deferred", 2 << 30, true, "`ratio`"),
    ];
    for (what, declared, descriptor, limit) in cases {
        let bomb = zip_raw("x.pdrlog", &data, crc, declared, descriptor);
        let nested = zip_of(
            &[("bomb.zip".into(), bomb.clone())],
            CompressionMethod::Stored,
            false,
        );
        for (top, bytes) in [("bomb.zip", bomb), ("outer.zip", nested)] {
            let got = import_all(&mut MemSet::new(vec![(top.into(), bytes), pdrlog()]));
            let e = errors(&got);
            assert_eq!(e.len(), 1, "{what} {top}: {got:#?}");
            assert!(e[0].message.contains(limit), "{what} {top}: {}", e[0]);
            assert!(e[0].file.starts_with(top), "{what} {top}: {}", e[0]);
            assert_eq!(oks(&got).len(), 1, "{what} {top}: the pdr-log loads");
        }
    }
    assert_peak_grew_less(before, 128 << 20);
}

/// 100 000 empty entries: refused whole, at the top and inside another zip.
#[test]
fn a_hundred_thousand_entries_are_refused() {
    let opts = SimpleFileOptions::default().compression_method(CompressionMethod::Stored);
    let mut w = zip::ZipWriter::new(Cursor::new(Vec::new()));
    for i in 0..100_000 {
        w.start_file(format!("e{i}"), opts).unwrap();
    }
    let many = w.finish().unwrap().into_inner();
    let nested = zip_of(
        &[("many.zip".into(), many.clone())],
        CompressionMethod::Deflated,
        true,
    );
    for (top, bytes, file) in [
        ("many.zip", many, "many.zip"),
        ("outer.zip", nested, "outer.zip/many.zip"),
    ] {
        let got = import_all(&mut MemSet::new(vec![(top.into(), bytes), pdrlog()]));
        let e = errors(&got);
        assert_eq!(e.len(), 1, "{top}: {got:#?}");
        assert_eq!(e[0].file, file);
        assert!(e[0].message.contains("archive limit `entries`"), "{}", e[0]);
        assert_eq!(oks(&got).len(), 1, "{top}: the pdr-log loads");
    }
}

/// A small total budget: the files read before it runs out load, the next one is refused with
/// the limit named.
#[test]
fn the_total_budget_is_shared_by_the_archives_inside() {
    let log = pdrlog();
    let n = log.1.len() as u64;
    let files: Vec<(String, Vec<u8>)> = (0..4)
        .map(|i| (format!("w{i}.pdrlog"), log.1.clone()))
        .collect();
    let inner = zip_of(&files[2..], CompressionMethod::Deflated, true);
    let inner_len = inner.len() as u64;
    let mut all = files[..2].to_vec();
    all.push(("inner.zip".into(), inner));
    let zip = zip_of(&all, CompressionMethod::Deflated, false);
    // Each entry counts once, however often it is read (its head, then whole; the inner
    // archive streamed again for each of its files). Enough for the inner archive, its two
    // files and one more, in name order: `inner.zip`, then `w0`, then not `w1`.
    let limits = ArchiveLimits {
        max_total_bytes: inner_len + 3 * n + n / 2,
        ..ArchiveLimits::default()
    };
    let mut set = ZipSet::within(Cursor::new(zip), "t.zip", 1, Budget::new(limits)).unwrap();
    let got = import_all(&mut set);
    assert!(oks(&got).len() >= 2, "{got:#?}");
    let e = errors(&got);
    assert!(!e.is_empty(), "{got:#?}");
    assert!(
        e.iter()
            .all(|e| e.message.contains("archive limit `total size`")),
        "{e:#?}"
    );
}

/// Damaged archives inside archives (bytes flipped, cut short, junk inserted, in the inner or
/// the outer archive, with and without data descriptors): never a panic, every record read is
/// finite, and every error names the upload.
#[test]
fn damaged_nested_archives_never_panic() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let files = common::import::load("sensor_logger_android", "Recording/");
    let mut outcomes = [0usize; 2];
    for round in 0..600 {
        let stream = round % 2 == 0;
        let mut inner = zip_of(&files, CompressionMethod::Deflated, stream);
        let r = next();
        let mut damage = |b: &mut Vec<u8>| match r % 3 {
            0 => {
                for _ in 0..1 + r % 8 {
                    let i = (next() as usize) % b.len();
                    b[i] ^= 1 << (next() % 8);
                }
            }
            1 => b.truncate((next() as usize) % b.len()),
            _ => {
                let at = (next() as usize) % b.len();
                let junk: Vec<u8> = (0..1 + next() % 64).map(|_| next() as u8).collect();
                b.splice(at..at, junk);
            }
        };
        if round % 5 != 4 {
            damage(&mut inner);
        }
        let method = if round % 3 == 0 {
            CompressionMethod::Stored
        } else {
            CompressionMethod::Deflated
        };
        let mut outer = zip_of(&[("inner.zip".into(), inner)], method, round % 4 < 2);
        if round % 5 == 4 {
            damage(&mut outer);
        }
        for got in import_all(&mut MemSet::new(vec![("outer.zip".into(), outer)])) {
            match got {
                Ok(log) => {
                    outcomes[0] += 1;
                    for rec in &log.records {
                        let ok = match rec {
                            pdr::engine::Record::Imu(s) | pdr::engine::Record::Foot(s) => {
                                s.t.is_finite() && s.accel.iter().all(|v| v.is_finite())
                            }
                            pdr::engine::Record::Gnss(f) => f.check().is_ok(),
                            pdr::engine::Record::Gap(a, b) => a.is_finite() && b.is_finite(),
                            pdr::engine::Record::Pressure(p) => p.check().is_ok(),
                        };
                        assert!(ok, "round {round}: {rec:?}");
                    }
                }
                Err(e) => {
                    outcomes[1] += 1;
                    assert!(e.file.starts_with("outer.zip"), "round {round}: {e}");
                }
            }
        }
    }
    assert!(outcomes[0] > 50 && outcomes[1] > 50, "{outcomes:?}");
}

//! Import of damaged, huge and unusual files: the whole fixture folder at once, every fixture
//! damaged at random, 2 GiB of junk behind a real header, and streams that begin after the
//! accelerometer. Each reader finishes with what it could read and an error or warnings naming
//! the file, never panics, and memory stays bounded.

mod common;
use common::import::*;
use common::{assert_peak_grew_less, peak_rss};
use nalgebra::Vector3;
use pdr::engine::Record;
use pdr::io::import::{import_all, DirSet};

#[test]
fn whole_fixture_folder_on_disk() {
    let mut set = DirSet::new(&fixtures()).unwrap();
    let results = import_all(&mut set);
    let mut formats: Vec<&str> = results
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .map(|l| l.format.as_str())
        .collect();
    formats.sort_unstable();
    assert_eq!(
        formats,
        [
            "get-sensor-data",
            "gnss-logger",
            "ms-indoor",
            "oxford-steps",
            "pdr-log",
            "phyphox",
            "phyphox",
            "sensor-logger",
            "sensor-logger",
            "sensor-logger-json",
            "xio-foot"
        ]
    );
    let errors: Vec<_> = results.iter().filter_map(|r| r.as_ref().err()).collect();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(errors[0].file.contains("phyphox_linear"));
}

/// A deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One damaging change to a file.
fn mutate(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    match rng.below(9) {
        // Truncated.
        0 => b.truncate(rng.below(b.len() + 1)),
        // Binary junk inserted.
        1 => {
            let at = rng.below(b.len() + 1);
            let junk: Vec<u8> = (0..1 + rng.below(64)).map(|_| rng.next() as u8).collect();
            b.splice(at..at, junk);
        }
        // Empty.
        2 => b.clear(),
        // Only junk.
        3 => b = (0..rng.below(3000)).map(|_| rng.next() as u8).collect(),
        // Text, NaN, infinities or huge values where a number belongs.
        4 | 5 => {
            let text = String::from_utf8_lossy(&b).into_owned();
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            for _ in 0..1 + rng.below(4) {
                if lines.is_empty() {
                    break;
                }
                let i = rng.below(lines.len());
                let sep = [',', ';', '\t']
                    .into_iter()
                    .find(|c| lines[i].contains(*c))
                    .unwrap_or(',');
                let mut f: Vec<String> = lines[i].split(sep).map(str::to_string).collect();
                let j = rng.below(f.len());
                f[j] = ["NaN", "abc", "1e999", "-inf", "", "1e308", "\"", "0"][rng.below(8)]
                    .to_string();
                lines[i] = f.join(&sep.to_string());
            }
            b = (lines.join("\n") + "\n").into_bytes();
        }
        // Out-of-order lines.
        6 | 7 => {
            let text = String::from_utf8_lossy(&b).into_owned();
            let mut lines: Vec<&str> = text.lines().collect();
            for _ in 0..1 + rng.below(10) {
                if lines.len() > 1 {
                    let (i, j) = (rng.below(lines.len()), rng.below(lines.len()));
                    lines.swap(i, j);
                }
            }
            b = (lines.join("\n") + "\n").into_bytes();
        }
        // A random byte flipped.
        _ => {
            if !b.is_empty() {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
        }
    }
    b
}

#[test]
fn robust_against_damaged_files() {
    let cases = [
        "sensor_logger_android",
        "sensor_logger_ios",
        "sensor_logger.json",
        "phyphox",
        "phyphox_semicolon",
        "gnss_logger.txt",
        "get_sensor_data.txt",
        "walk.pdrlog",
        "oxford",
        "ms_indoor.txt",
        "xio_foot.csv",
    ];
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut outcomes = [0usize; 2];
    for case in cases {
        let original = load(case, "rec/");
        for round in 0..120 {
            let mut files = original.clone();
            for _ in 0..1 + rng.below(2) {
                let k = rng.below(files.len());
                files[k].1 = mutate(&files[k].1, &mut rng);
            }
            let names: Vec<String> = files.iter().map(|f| f.0.clone()).collect();
            let results = if round % 10 == 0 {
                import_mem(vec![("rec.zip".into(), zip_bytes(&files))])
            } else {
                import_mem(files)
            };
            for r in results {
                match r {
                    Ok(log) => {
                        outcomes[0] += 1;
                        assert_sane(&log);
                    }
                    Err(e) => {
                        outcomes[1] += 1;
                        assert!(
                            names.iter().any(|n| e.file.contains(n.as_str()))
                                || e.file.contains("rec"),
                            "{case}: the error names no file: {e}"
                        );
                    }
                }
            }
        }
    }
    // Both outcomes happen: damage is survived, and fatal damage is reported.
    assert!(outcomes[0] > 100 && outcomes[1] > 10, "{outcomes:?}");
}

/// A file set whose files are a real header followed by a huge generated tail, never held in
/// memory: how a 2 GB recording (or 2 GB of junk behind a plausible first line) reaches a
/// reader.
struct Huge {
    names: Vec<String>,
    heads: Vec<&'static str>,
    tail: u64,
    newlines: bool,
}

/// The generated stream: `head`, then `len` bytes of a fixed pseudo-random pattern (with or
/// without line ends).
struct Junk {
    head: std::io::Cursor<&'static [u8]>,
    left: u64,
    pattern: Vec<u8>,
    at: usize,
}

impl std::io::Read for Junk {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.head.read(buf)?;
        if n > 0 {
            return Ok(n);
        }
        let n = (buf.len() as u64)
            .min(self.left)
            .min((self.pattern.len() - self.at) as u64) as usize;
        buf[..n].copy_from_slice(&self.pattern[self.at..self.at + n]);
        self.at = (self.at + n) % self.pattern.len();
        self.left -= n as u64;
        Ok(n)
    }
}

impl pdr::io::import::FileSet for Huge {
    fn names(&self) -> &[String] {
        &self.names
    }
    fn open(&mut self, name: &str) -> std::io::Result<Box<dyn std::io::BufRead + '_>> {
        let i = self.names.iter().position(|n| n == name).unwrap();
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ i as u64);
        let pattern = (0..65_521)
            .map(|_| {
                let b = rng.next() as u8;
                if !self.newlines && b == b'\n' {
                    b'x'
                } else {
                    b
                }
            })
            .collect();
        Ok(Box::new(std::io::BufReader::with_capacity(
            1 << 16,
            Junk {
                head: std::io::Cursor::new(self.heads[i].as_bytes()),
                left: self.tail,
                pattern,
                at: 0,
            },
        )))
    }
    fn label(&self, name: &str) -> String {
        format!("huge/{name}")
    }
}

/// Every reader gets a plausible first line and then 2 GiB of binary junk (release builds;
/// 64 MiB in debug builds, where reading 20 GB would take minutes): each finishes with an error
/// or warnings naming the file, never panics, and memory stays bounded.
#[test]
fn two_gigabytes_of_junk_behind_a_real_header() {
    let tail: u64 = if cfg!(debug_assertions) {
        64 << 20
    } else {
        2 << 30
    };
    let files: [(&str, &'static str); 9] = [
        ("a.pdrlog", "# pdr-log 1\nimu,0,0,0,9.8,,,,,,,,,,\n"),
        ("ms.txt", "#\tSiteID:x\n1000\tTYPE_ACCELEROMETER\t0\t0\t9.8\t3\n"),
        ("x.csv", "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),Accelerometer Y (g),Accelerometer Z (g)\n"),
        ("g.txt", "# Accel,utcTimeMillis,elapsedRealtimeNanos,AccelXMps2,AccelYMps2,AccelZMps2\n"),
        ("s.txt", "% GetSensorData\nACCE;1.0;1.0;0;0;9.8;3\n"),
        ("j.json", "[{\"sensor\":\"Accelerometer\",\"time\":\"1000000000\",\"x\":\"0\",\"y\":\"0\",\"z\":\"0\"},"),
        ("sl/Accelerometer.csv", "time,seconds_elapsed,z,y,x\n"),
        ("ph/Accelerometer.csv", "\"Time (s)\",\"Acceleration x (m/s^2)\",\"Acceleration y (m/s^2)\",\"Acceleration z (m/s^2)\"\n"),
        ("ox/accelerometer.csv", "1000000000,3,0,0,9.8\n"),
    ];
    let mut names: Vec<String> = files.iter().map(|f| f.0.to_string()).collect();
    let mut heads: Vec<&'static str> = files.iter().map(|f| f.1).collect();
    // The folder formats need their companions (small and valid).
    names.push("sl/Gravity.csv".into());
    heads.push("time,seconds_elapsed,z,y,x\n1000000000,0,9.8,0,0\n");
    names.push("ox/stepcounter.csv".into());
    heads.push("1000000000,1,1\n");
    let mut order: Vec<usize> = (0..names.len()).collect();
    order.sort_by(|&a, &b| names[a].cmp(&names[b]));
    let before = peak_rss();
    for newlines in [false, true] {
        let mut set = Huge {
            names: order.iter().map(|&i| names[i].clone()).collect(),
            heads: order.iter().map(|&i| heads[i]).collect(),
            tail: if newlines { tail / 8 } else { tail },
            newlines,
        };
        let results = import_all(&mut set);
        assert_eq!(results.len(), 9, "one result per log");
        for r in &results {
            match r {
                Ok(log) => {
                    assert!(
                        log.skipped > 0 && !log.warnings.is_empty(),
                        "{}",
                        log.source
                    );
                    assert!(log.warnings.len() <= pdr::io::import::MAX_WARNINGS);
                    assert!(log.warnings.iter().all(|w| w.file.starts_with("huge/")));
                }
                Err(e) => assert!(e.file.starts_with("huge/"), "{e}"),
            }
        }
    }
    assert_peak_grew_less(before, 256 << 20);
}

#[test]
fn streams_that_begin_after_the_accelerometer_are_not_carried_back() {
    use nalgebra::UnitQuaternion;
    use pdr::engine::{replay, OrientationSource, PipelineConfig};
    use pdr::io::import::Streams;
    let imu = |s: Streams| {
        s.into_records()
            .into_iter()
            .filter_map(|r| match r {
                Record::Imu(s) => Some(s),
                _ => None,
            })
            .collect::<Vec<_>>()
    };
    let mut s = Streams::default();
    for k in 0..300 {
        let t = k as f64 * 0.01;
        s.accel.push((t, Vector3::new(0.0, 0.0, 9.81)));
        if k >= 3 {
            s.gyro.push((t + 0.001, Vector3::new(0.1, 0.0, 0.0)));
        }
        if k >= 5 {
            s.orientation.push((t + 0.002, UnitQuaternion::identity()));
        }
    }
    // Every accelerometer sample is kept, each with what had come by its time: nothing is
    // moved earlier than it was measured. The engine's `auto` source moves up as the streams
    // begin (gravity, then Madgwick, then the OS attitude).
    let r = imu(s.clone());
    assert_eq!(r.len(), 300);
    assert_eq!(r[0].t, 0.0);
    assert!(r[..4].iter().all(|x| x.gyro.is_none()));
    assert!(r[..6].iter().all(|x| x.orientation.is_none()));
    assert!(r[6..]
        .iter()
        .all(|x| x.gyro.is_some() && x.orientation.is_some()));
    let records: Vec<Record> = r.into_iter().map(Record::Imu).collect();
    let run = replay(PipelineConfig::default(), &records).unwrap();
    assert!(run.errors.is_empty());
    let o = run.pipeline.orientation_diagnostics().unwrap();
    assert_eq!(o.source, OrientationSource::Os);
    assert_eq!(o.switches, 2);
}

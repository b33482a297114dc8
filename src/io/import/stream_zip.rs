//! A zip inside a zip, read as a stream and never whole, within the
//! [`ArchiveLimits`](super::archive_limits::ArchiveLimits).
//! May import: `engine` and `io`.
//!
//! The archive's bytes come out of a decompressor, which cannot seek, and the zip crate's readers need
//! either a seekable source (`ZipArchive`) or local headers that state the sizes
//! (`read_zipfile_from_stream` refuses entries with a data descriptor, which every archive made
//! by macOS's Finder and most streaming zippers has). So the nested archive is read here from its
//! local headers (PKWARE APPNOTE 6.3.10 §4.3.7, §4.3.9, §4.5.3), as a stream: one pass lists
//! its entries and keeps their first [`HEAD_BYTES`] (to recognise formats); opening an entry
//! streams the archive again up to it. Stored and deflated entries are read, with or without a
//! data descriptor, except a stored entry with a data descriptor, whose end cannot be found
//! without the directory at the end of the archive ("cannot be streamed"). Memory stays at a
//! few buffers whatever the archive's size.

use super::archive_limits::{Budget, LimitHit, Metered};
use super::fileset::{FileSet, HEAD_BYTES};
use std::cell::Cell;
use std::io::{self, BufRead, BufReader, Read};

/// One entry of a streamed archive, from its local header (and data descriptor).
#[derive(Debug, Clone)]
struct Entry {
    name: String,
    method: u16,
    /// Compressed and decompressed size, and CRC-32. From the data descriptor when the local
    /// header defers them (known once the listing pass has read past the data).
    compressed: u64,
    size: u64,
    crc: u32,
    /// The sizes come after the data.
    descriptor: bool,
    /// The sizes in the data descriptor are 8 bytes (zip64).
    zip64: bool,
    /// Bit 0 of the flags.
    encrypted: bool,
    /// The first [`HEAD_BYTES`] of the content (empty for a directory or a refused entry).
    head: Vec<u8>,
    /// Why the entry is not read, when it is not.
    refused: Option<Refusal>,
}

const LOCAL: u32 = 0x0403_4b50;
const CENTRAL: u32 = 0x0201_4b50;
const END: u32 = 0x0605_4b50;
const DESCRIPTOR: u32 = 0x0807_4b50;
const STORED: u16 = 0;
const DEFLATED: u16 = 8;

fn u16_at(b: &[u8], i: usize) -> u16 {
    u16::from_le_bytes([b[i], b[i + 1]])
}

fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

fn u64_at(b: &[u8], i: usize) -> u64 {
    u64::from_le_bytes(b[i..i + 8].try_into().unwrap_or([0; 8]))
}

fn bad(msg: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, msg.into())
}

/// Reads the next local header (APPNOTE §4.3.7); `None` at the central directory or the end.
fn next_header(r: &mut dyn BufRead) -> io::Result<Option<Entry>> {
    let mut sig = [0u8; 4];
    let got = read_full(r, &mut sig)?;
    if got == 0 {
        return Ok(None);
    }
    if got < 4 {
        return Err(bad("archive cut short"));
    }
    match u32::from_le_bytes(sig) {
        LOCAL => {}
        CENTRAL | END => return Ok(None),
        _ => return Err(bad("not a zip local header where one was expected")),
    }
    let mut h = [0u8; 26];
    r.read_exact(&mut h)?;
    let flags = u16_at(&h, 2);
    let method = u16_at(&h, 4);
    let crc = u32_at(&h, 10);
    let mut compressed = u64::from(u32_at(&h, 14));
    let mut size = u64::from(u32_at(&h, 18));
    let mut name = vec![0u8; usize::from(u16_at(&h, 22))];
    r.read_exact(&mut name)?;
    let mut extra = vec![0u8; usize::from(u16_at(&h, 24))];
    r.read_exact(&mut extra)?;
    // The zip64 extra field (§4.5.3): the 8-byte sizes when the 4-byte ones are 0xFFFFFFFF.
    let mut zip64 = false;
    let mut i = 0;
    while i + 4 <= extra.len() {
        let (id, len) = (u16_at(&extra, i), usize::from(u16_at(&extra, i + 2)));
        let body = &extra[i + 4..(i + 4 + len).min(extra.len())];
        if id == 0x0001 {
            zip64 = true;
            let mut k = 0;
            if size == u64::from(u32::MAX) && body.len() >= k + 8 {
                size = u64_at(body, k);
                k += 8;
            }
            if compressed == u64::from(u32::MAX) && body.len() >= k + 8 {
                compressed = u64_at(body, k);
            }
        }
        i += 4 + len;
    }
    Ok(Some(Entry {
        name: String::from_utf8_lossy(&name).into_owned(),
        method,
        compressed,
        size,
        crc,
        descriptor: flags & (1 << 3) != 0,
        zip64,
        encrypted: flags & 1 != 0,
        head: Vec::new(),
        refused: None,
    }))
}

/// Reads until `buf` is full or the input ends; the number of bytes read.
fn read_full(r: &mut dyn BufRead, buf: &mut [u8]) -> io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match r.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}

/// Reads the data descriptor after an entry whose header deferred its sizes (§4.3.9): the
/// signature is optional; the sizes are 8 bytes in a zip64 entry.
fn read_descriptor(r: &mut dyn BufRead, e: &mut Entry) -> io::Result<()> {
    let mut first = [0u8; 4];
    r.read_exact(&mut first)?;
    let crc = if u32::from_le_bytes(first) == DESCRIPTOR {
        r.read_exact(&mut first)?;
        u32::from_le_bytes(first)
    } else {
        u32::from_le_bytes(first)
    };
    let mut sizes = [0u8; 16];
    let sizes = &mut sizes[..if e.zip64 { 16 } else { 8 }];
    r.read_exact(sizes)?;
    e.crc = crc;
    (e.compressed, e.size) = if e.zip64 {
        (u64_at(sizes, 0), u64_at(sizes, 8))
    } else {
        (u64::from(u32_at(sizes, 0)), u64::from(u32_at(sizes, 4)))
    };
    Ok(())
}

/// Counts the bytes read through it (the compressed bytes a decompressor consumed).
struct Counted<'a, R> {
    inner: R,
    count: &'a Cell<u64>,
}

impl<R: Read> Read for Counted<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count.set(self.count.get() + n as u64);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for Counted<'_, R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.inner.fill_buf()
    }
    fn consume(&mut self, n: usize) {
        self.count.set(self.count.get() + n as u64);
        self.inner.consume(n);
    }
}

/// Why an entry cannot be read from the stream, if it cannot.
fn unreadable(e: &Entry) -> Option<String> {
    if e.encrypted {
        return Some("the entry is encrypted".into());
    }
    match (e.method, e.descriptor) {
        (STORED, true) => Some(
            "cannot be streamed: a stored entry whose size comes after its data, inside another archive"
                .into(),
        ),
        (STORED | DEFLATED, _) => None,
        (m, _) => Some(format!("compression method {m} is not supported (only stored and deflate)")),
    }
}

/// Why an entry of a streamed archive is not read: a limit, or something the stream reader
/// cannot do.
#[derive(Debug, Clone)]
enum Refusal {
    Limit(LimitHit),
    Other(String),
}

impl Refusal {
    fn of(e: io::Error) -> Refusal {
        match LimitHit::of(&e) {
            Some(hit) => Refusal::Limit(hit.clone()),
            None => Refusal::Other(e.to_string()),
        }
    }

    fn to_io(&self) -> io::Error {
        match self {
            Refusal::Limit(hit) => hit.clone().into_io(),
            Refusal::Other(why) => bad(why.clone()),
        }
    }
}

/// Skips an entry whose sizes are known, data descriptor included: the stream is left at the
/// next header. Nothing is decompressed.
fn skip_entry(r: &mut dyn BufRead, e: &Entry) -> io::Result<()> {
    io::copy(&mut r.take(e.compressed), &mut io::sink())?;
    if e.descriptor {
        read_descriptor(r, &mut e.clone())?;
    }
    Ok(())
}

/// The entry's decompressed bytes, metered, from a stream at the start of its data, for an
/// entry whose compressed size is known.
fn body<'a>(
    r: impl BufRead + 'a,
    e: &Entry,
    label: &str,
    budget: &Budget,
) -> Metered<Box<dyn Read + 'a>> {
    let limited = r.take(e.compressed);
    let inner: Box<dyn Read + 'a> = if e.method == DEFLATED {
        Box::new(flate2::bufread::DeflateDecoder::new(limited))
    } else {
        Box::new(limited)
    };
    let key = format!("{label}/{}", e.name);
    Metered::new(
        inner,
        budget.clone(),
        key,
        e.compressed,
        e.size,
        Some(e.crc),
    )
}

/// The listing pass over one entry, from the stream at the start of its data: keeps its first
/// [`HEAD_BYTES`], or why it is refused, and leaves the stream at the next header. An entry
/// with a data descriptor is decompressed to find its end (deflate ends itself); one that
/// cannot be, or that hits a limit on the way, ends the listing with an error, since the next
/// header cannot be found.
fn list_entry(r: &mut dyn BufRead, e: &mut Entry, label: &str, budget: &Budget) -> io::Result<()> {
    let dir = e.name.ends_with('/');
    if !e.descriptor {
        let refused = unreadable(e)
            .map(Refusal::Other)
            .or_else(|| budget.admit(e.compressed, e.size).err().map(Refusal::of));
        if refused.is_none() && !dir {
            let consumed = Cell::new(0u64);
            let src = Counted {
                inner: &mut *r,
                count: &consumed,
            };
            let mut head = Vec::new();
            match body(src, e, label, budget)
                .take(HEAD_BYTES as u64)
                .read_to_end(&mut head)
            {
                Ok(_) => e.head = head,
                Err(err) => e.refused = Some(Refusal::of(err)),
            }
            let left = e.compressed.saturating_sub(consumed.get());
            io::copy(&mut r.take(left), &mut io::sink())?;
        } else {
            e.refused = refused;
            io::copy(&mut r.take(e.compressed), &mut io::sink())?;
        }
        return Ok(());
    }
    if let Some(why) = unreadable(e) {
        return Err(bad(format!("{}: {why}", e.name)));
    }
    let consumed = Cell::new(0u64);
    {
        let mut body = LiveRatio {
            inner: flate2::bufread::DeflateDecoder::new(Counted {
                inner: &mut *r,
                count: &consumed,
            }),
            consumed: &consumed,
            budget: budget.clone(),
            key: format!("{label}/{}", e.name),
            out: 0,
        };
        let mut head = Vec::new();
        if !dir {
            (&mut body).take(HEAD_BYTES as u64).read_to_end(&mut head)?;
        }
        io::copy(&mut body, &mut io::sink())?;
        e.head = head;
    }
    read_descriptor(r, e)?;
    if e.compressed != consumed.get() {
        return Err(bad(format!(
            "{}: the data descriptor's compressed size disagrees with the data",
            e.name
        )));
    }
    Ok(())
}

/// A deflate stream of unknown compressed size, with the ratio checked against the compressed
/// bytes consumed so far, and the bytes counted against the budget.
struct LiveRatio<'a, R> {
    inner: R,
    consumed: &'a Cell<u64>,
    budget: Budget,
    key: String,
    out: u64,
}

impl<R: Read> Read for LiveRatio<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.out += n as u64;
        self.budget
            .meter(&self.key, self.out, self.consumed.get())?;
        Ok(n)
    }
}

/// The files of a zip archive that is itself inside a [`FileSet`], read as a stream (see the
/// module documentation).
pub struct StreamZipSet<'a> {
    outer: &'a mut dyn FileSet,
    name: String,
    label: String,
    depth: u32,
    budget: Budget,
    entries: Vec<Entry>,
    names: Vec<String>,
}

impl<'a> StreamZipSet<'a> {
    /// Lists the archive `name` of `outer` (at `depth`), keeping the head of each file.
    pub fn new(
        outer: &'a mut dyn FileSet,
        name: &str,
        depth: u32,
        budget: Budget,
    ) -> io::Result<Self> {
        budget.admit_archive(depth, 0)?;
        let label = outer.label(name);
        let mut entries = Vec::new();
        {
            let mut r = outer.open(name)?;
            while let Some(mut e) = next_header(&mut r)? {
                budget.admit_archive(depth, entries.len() + 1)?;
                list_entry(&mut r, &mut e, &label, &budget)?;
                entries.push(e);
            }
        }
        let mut names: Vec<String> = entries
            .iter()
            .map(|e| e.name.clone())
            .filter(|n| !n.ends_with('/') && !n.starts_with("__MACOSX/"))
            .collect();
        crate::engine::sort::sort(&mut names);
        names.dedup();
        Ok(StreamZipSet {
            outer,
            name: name.to_string(),
            label,
            depth,
            budget,
            entries,
            names,
        })
    }

    /// The entry of a name (the last one, when a name is repeated: as zip tools extract).
    fn entry(&self, name: &str) -> io::Result<usize> {
        self.entries
            .iter()
            .rposition(|e| e.name == name)
            .ok_or_else(|| io::Error::new(io::ErrorKind::NotFound, name.to_string()))
    }
}

impl FileSet for StreamZipSet<'_> {
    fn names(&self) -> &[String] {
        &self.names
    }

    /// Streams the archive again up to the entry, skipping the others without decompressing
    /// them (their sizes are known from the listing pass, data descriptors or not).
    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>> {
        let k = self.entry(name)?;
        if let Some(why) = &self.entries[k].refused {
            return Err(why.to_io());
        }
        let mut r = self.outer.open(&self.name)?;
        let changed = || bad("the archive changed while it was read");
        for e in &self.entries[..k] {
            next_header(&mut r)?.ok_or_else(changed)?;
            skip_entry(&mut r, e)?;
        }
        next_header(&mut r)?.ok_or_else(changed)?;
        let body = body(r, &self.entries[k], &self.label, &self.budget);
        Ok(Box::new(BufReader::with_capacity(1 << 16, body)))
    }

    fn head(&mut self, name: &str) -> io::Result<String> {
        let e = &self.entries[self.entry(name)?];
        if let Some(why) = &e.refused {
            return Err(why.to_io());
        }
        Ok(String::from_utf8_lossy(&e.head).into_owned())
    }

    fn label(&self, name: &str) -> String {
        format!("{}/{name}", self.label)
    }

    fn depth(&self) -> u32 {
        self.depth
    }

    fn budget(&self) -> Option<Budget> {
        Some(self.budget.clone())
    }
}

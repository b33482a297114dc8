//! Archive limits: how deep archives may nest, how many entries one may hold, how many bytes
//! one upload may decompress to and at what ratio; the bytes of an entry metered against them.
//! May import: `engine` and `io`.
//!
//! # The limits ([`ArchiveLimits`])
//! - **Depth 2.** A zip in a folder or an upload is depth 1, a zip inside it depth 2. A deeper
//!   one (a zip quine is infinitely deep) is refused with [`LimitHit::Depth`].
//! - **10 000 entries** per archive ([`LimitHit::Entries`]). A Sensor Logger or phyphox export
//!   holds about 15 files, a zipped data set a few hundred recordings.
//! - **1 GiB decompressed** per top-level archive, nested ones included ([`LimitHit::Total`]).
//!   A one-hour Sensor Logger recording of every sensor at 100 Hz is about 150–250 MB of CSV;
//!   in the page's worker, whose wasm memory cannot exceed 4 GiB, the records of 1 GiB of CSV
//!   take well under 1 GiB.
//! - **Ratio 100** of decompressed to compressed size per entry, past the first 1 MiB
//!   ([`LimitHit::Ratio`]). Deflate compresses the recordings we read 2.5–5 times (IPIN
//!   GetSensorData 3.0, Microsoft Indoor 5.0, Oxford 2.8, x-io 2.5, measured with zlib level 9);
//!   a zip bomb compresses zeros about 1000 times. Apache POI's `ZipSecureFile` uses the same
//!   bound (a minimum inflate ratio of 0.01).
//!
//! The declared sizes in an archive's directory are checked before an entry is read, and the
//! bytes actually decompressed are counted as they come ([`Metered`]): an entry that grows past
//! its declared size is refused ([`LimitHit::Larger`]), so a header that lies cannot get past
//! the limits. Each limit is an error about that file only; the other files still load.

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::fmt;
use std::io::{self, Read};
use std::rc::Rc;

/// The bounds an archive must stay within (see the module documentation for the values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArchiveLimits {
    /// Deepest archive nesting read (1: a zip, 2: a zip in a zip).
    pub max_depth: u32,
    /// Most entries in one archive.
    pub max_entries: usize,
    /// Most bytes decompressed from one top-level archive and those inside it.
    pub max_total_bytes: u64,
    /// Largest ratio of decompressed to compressed size of one entry.
    pub max_ratio: u64,
    /// An entry may decompress to this many bytes before its ratio is checked (small files of
    /// repeated text compress well).
    pub ratio_grace_bytes: u64,
}

impl Default for ArchiveLimits {
    fn default() -> Self {
        ArchiveLimits {
            max_depth: 2,
            max_entries: 10_000,
            max_total_bytes: 1 << 30,
            max_ratio: 100,
            ratio_grace_bytes: 1 << 20,
        }
    }
}

/// Which limit an archive hit. Carried inside the `io::Error` of the read that hit it (find it
/// with [`LimitHit::of`]) and shown in the [`ParseError`](crate::io::ParseError) of the file.
#[derive(Debug, Clone, PartialEq)]
pub enum LimitHit {
    /// An archive nested deeper than `limit`.
    Depth {
        /// The archive's depth.
        depth: u32,
        /// [`ArchiveLimits::max_depth`].
        limit: u32,
    },
    /// An archive with more entries than `limit`.
    Entries {
        /// The number of entries (at least; counting stops past the limit).
        entries: usize,
        /// [`ArchiveLimits::max_entries`].
        limit: usize,
    },
    /// The archive decompresses to more than `limit` bytes in all.
    Total {
        /// [`ArchiveLimits::max_total_bytes`].
        limit: u64,
    },
    /// An entry decompresses to more than `limit` times its compressed size.
    Ratio {
        /// The entry's compressed size, bytes.
        compressed: u64,
        /// [`ArchiveLimits::max_ratio`].
        limit: u64,
    },
    /// An entry decompresses to more than its header says (a damaged or forged archive).
    Larger {
        /// The size in the header, bytes.
        declared: u64,
    },
}

impl fmt::Display for LimitHit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LimitHit::Depth { depth, limit } => write!(
                f,
                "archive limit `depth`: an archive nested {depth} deep; archives are read at most {limit} deep (a zip inside a zip)"
            ),
            LimitHit::Entries { entries, limit } => write!(
                f,
                "archive limit `entries`: {entries} entries or more; at most {limit} are read"
            ),
            LimitHit::Total { limit } => write!(
                f,
                "archive limit `total size`: the archive decompresses to more than {} MiB",
                limit >> 20
            ),
            LimitHit::Ratio { compressed, limit } => write!(
                f,
                "archive limit `ratio`: the entry decompresses to more than {limit} times its compressed size ({compressed} bytes), as a zip bomb does"
            ),
            LimitHit::Larger { declared } => write!(
                f,
                "archive limit `declared size`: the entry decompresses to more than the {declared} bytes its header says (damaged or forged)"
            ),
        }
    }
}

impl std::error::Error for LimitHit {}

impl LimitHit {
    /// The limit inside an `io::Error`, if that is what it carries.
    pub fn of(e: &io::Error) -> Option<&LimitHit> {
        e.get_ref()?.downcast_ref::<LimitHit>()
    }

    pub(super) fn into_io(self) -> io::Error {
        io::Error::other(self)
    }
}

/// The decompressed bytes one top-level archive may still produce, shared with the archives
/// inside it.
#[derive(Debug, Clone)]
pub struct Budget {
    left: Rc<Cell<u64>>,
    /// How far each entry (by label) has been decompressed: reading an entry again (its head to
    /// recognise it, then whole; an archive inside an archive streamed again to reach each of
    /// its entries) spends only what goes past that.
    seen: Rc<RefCell<HashMap<String, u64>>>,
    limits: ArchiveLimits,
}

impl Budget {
    /// A fresh budget of [`ArchiveLimits::max_total_bytes`].
    pub fn new(limits: ArchiveLimits) -> Self {
        Budget {
            left: Rc::new(Cell::new(limits.max_total_bytes)),
            seen: Rc::default(),
            limits,
        }
    }

    /// The limits this budget enforces.
    pub fn limits(&self) -> &ArchiveLimits {
        &self.limits
    }

    /// Counts the bytes of entry `key` up to `out`, decompressed from `compressed` compressed
    /// ones: the ratio (past the grace), then the total, which only the bytes past what was
    /// read of the entry before spend.
    pub(super) fn meter(&self, key: &str, out: u64, compressed: u64) -> io::Result<()> {
        let l = &self.limits;
        if out > l.ratio_grace_bytes && out > compressed.saturating_mul(l.max_ratio) {
            return Err(LimitHit::Ratio {
                compressed,
                limit: l.max_ratio,
            }
            .into_io());
        }
        let mut seen = self.seen.borrow_mut();
        let before = seen.get(key).copied().unwrap_or(0);
        let n = out.saturating_sub(before);
        if n == 0 {
            return Ok(());
        }
        let left = self.left.get();
        if n > left {
            self.left.set(0);
            return Err(LimitHit::Total {
                limit: l.max_total_bytes,
            }
            .into_io());
        }
        self.left.set(left - n);
        seen.insert(key.to_string(), out);
        Ok(())
    }

    /// Checks an entry's declared sizes before it is read.
    pub fn admit(&self, compressed: u64, size: u64) -> io::Result<()> {
        let l = &self.limits;
        if size > l.ratio_grace_bytes && size > compressed.saturating_mul(l.max_ratio) {
            return Err(LimitHit::Ratio {
                compressed,
                limit: l.max_ratio,
            }
            .into_io());
        }
        if size > self.left.get() {
            return Err(LimitHit::Total {
                limit: l.max_total_bytes,
            }
            .into_io());
        }
        Ok(())
    }

    /// Checks an archive's depth and number of entries.
    pub fn admit_archive(&self, depth: u32, entries: usize) -> io::Result<()> {
        let l = &self.limits;
        if depth > l.max_depth {
            return Err(LimitHit::Depth {
                depth,
                limit: l.max_depth,
            }
            .into_io());
        }
        if entries > l.max_entries {
            return Err(LimitHit::Entries {
                entries,
                limit: l.max_entries,
            }
            .into_io());
        }
        Ok(())
    }
}

/// An entry's decompressed bytes, counted against the [`Budget`], its compressed size (the
/// ratio) and its declared size; and checked against its CRC-32 at the end when that is known.
pub struct Metered<R> {
    inner: R,
    budget: Budget,
    key: String,
    compressed: u64,
    declared: u64,
    read: u64,
    crc: Option<(u32, crc32fast::Hasher)>,
}

impl<R: Read> Metered<R> {
    /// Meters `inner`, the entry `key` (its label) of `compressed` bytes that says it holds
    /// `declared` bytes with CRC-32 `crc` (checked at the end when given).
    pub fn new(
        inner: R,
        budget: Budget,
        key: String,
        compressed: u64,
        declared: u64,
        crc: Option<u32>,
    ) -> Self {
        Metered {
            inner,
            budget,
            key,
            compressed,
            declared,
            read: 0,
            crc: crc.map(|c| (c, crc32fast::Hasher::new())),
        }
    }
}

impl<R: Read> Read for Metered<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        if n == 0 {
            if let Some((want, h)) = self.crc.take() {
                if h.finalize() != want {
                    return Err(io::Error::new(
                        io::ErrorKind::InvalidData,
                        "CRC-32 mismatch: the entry is damaged",
                    ));
                }
            }
            return Ok(0);
        }
        self.read += n as u64;
        if self.read > self.declared {
            return Err(LimitHit::Larger {
                declared: self.declared,
            }
            .into_io());
        }
        self.budget.meter(&self.key, self.read, self.compressed)?;
        if let Some((_, h)) = &mut self.crc {
            h.update(&buf[..n]);
        }
        Ok(n)
    }
}

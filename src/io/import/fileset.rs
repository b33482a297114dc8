//! Where the files of a recording come from: a folder, a zip archive (within the limits of
//! [`archive_limits`](super::archive_limits)), or memory (uploads).
//! May import: `engine` and `io`.

use super::archive_limits::{ArchiveLimits, Budget, Metered};
use std::io::{self, BufRead, BufReader, Cursor, Read, Seek};
use std::path::{Path, PathBuf};

/// How many bytes [`FileSet::head`] reads to recognise a format.
pub const HEAD_BYTES: usize = 4096;

/// A set of named files. Names are relative, `/`-separated and sorted.
pub trait FileSet {
    /// Every file name.
    fn names(&self) -> &[String];
    /// Opens one file for streaming.
    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>>;
    /// The name to show in messages (the full path, or `archive.zip/inner/name`).
    fn label(&self, name: &str) -> String;
    /// A file of the set as a seekable stream, for reading it as a zip archive, when the set
    /// can give one without reading the file whole (on disk, in memory, a browser `Blob`).
    /// `None` by default: an archive inside an archive is then read as a stream
    /// ([`StreamZipSet`](super::stream_zip::StreamZipSet)).
    fn open_seekable(&mut self, _name: &str) -> Option<io::Result<Box<dyn ReadSeek + '_>>> {
        None
    }
    /// How many archives deep the set is (0: a folder or an upload).
    fn depth(&self) -> u32 {
        0
    }
    /// The decompression budget the set's archive spends, shared with the archives inside it
    /// (`None` outside archives).
    fn budget(&self) -> Option<Budget> {
        None
    }
    /// The size of a file in bytes, when known cheaply.
    fn size(&mut self, _name: &str) -> Option<u64> {
        None
    }
    /// The first [`HEAD_BYTES`] bytes of a file, as text (invalid UTF-8 replaced).
    fn head(&mut self, name: &str) -> io::Result<String> {
        let mut buf = Vec::with_capacity(HEAD_BYTES);
        self.open(name)?
            .take(HEAD_BYTES as u64)
            .read_to_end(&mut buf)?;
        Ok(String::from_utf8_lossy(&buf).into_owned())
    }
}

/// A byte stream that can seek (a zip archive's source).
pub trait ReadSeek: Read + Seek {}
impl<T: Read + Seek> ReadSeek for T {}

/// The folder part of a name, with its trailing `/` (empty at the top).
pub fn parent(name: &str) -> &str {
    match name.rfind('/') {
        Some(i) => &name[..=i],
        None => "",
    }
}

/// The file part of a name.
pub fn base(name: &str) -> &str {
    &name[parent(name).len()..]
}

/// Files on disk: a folder walked recursively, or a single file.
pub struct DirSet {
    root: PathBuf,
    single: bool,
    names: Vec<String>,
}

impl DirSet {
    /// A folder (every file under it) or a single file.
    pub fn new(path: &Path) -> io::Result<Self> {
        let meta = std::fs::metadata(path)?;
        if meta.is_file() {
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            return Ok(DirSet {
                root: path.to_path_buf(),
                single: true,
                names: vec![name],
            });
        }
        let mut names = Vec::new();
        let mut stack = vec![PathBuf::new()];
        while let Some(rel) = stack.pop() {
            for entry in std::fs::read_dir(path.join(&rel))? {
                let entry = entry?;
                let r = rel.join(entry.file_name());
                if entry.file_type()?.is_dir() {
                    stack.push(r);
                } else {
                    names.push(r.to_string_lossy().replace('\\', "/"));
                }
            }
        }
        crate::engine::sort::sort(&mut names);
        Ok(DirSet {
            root: path.to_path_buf(),
            single: false,
            names,
        })
    }

    fn path(&self, name: &str) -> PathBuf {
        if self.single {
            self.root.clone()
        } else {
            self.root.join(name)
        }
    }
}

impl FileSet for DirSet {
    fn size(&mut self, name: &str) -> Option<u64> {
        std::fs::metadata(self.path(name)).ok().map(|m| m.len())
    }

    fn names(&self) -> &[String] {
        &self.names
    }

    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>> {
        let f = std::fs::File::open(self.path(name))?;
        Ok(Box::new(BufReader::with_capacity(1 << 16, f)))
    }

    fn label(&self, name: &str) -> String {
        self.path(name).display().to_string()
    }

    fn open_seekable(&mut self, name: &str) -> Option<io::Result<Box<dyn ReadSeek + '_>>> {
        Some(
            std::fs::File::open(self.path(name))
                .map(|f| Box::new(BufReader::with_capacity(1 << 16, f)) as Box<dyn ReadSeek>),
        )
    }
}

/// The files of a zip archive read in place (on disk, in memory), decompressed as they are
/// read, within the [`ArchiveLimits`].
pub struct ZipSet<R: Read + Seek> {
    label: String,
    archive: zip::ZipArchive<R>,
    names: Vec<String>,
    depth: u32,
    budget: Budget,
}

impl<R: Read + Seek> ZipSet<R> {
    /// Opens an archive at depth 1 with the default limits; `label` names it in messages.
    pub fn new(reader: R, label: &str) -> io::Result<Self> {
        Self::within(reader, label, 1, Budget::new(ArchiveLimits::default()))
    }

    /// Opens an archive `depth` archives deep that spends `budget`.
    pub fn within(reader: R, label: &str, depth: u32, budget: Budget) -> io::Result<Self> {
        budget.admit_archive(depth, 0)?;
        let archive = zip::ZipArchive::new(reader).map_err(io::Error::other)?;
        budget.admit_archive(depth, archive.len())?;
        let mut names: Vec<String> = archive
            .file_names()
            .filter(|n| !n.ends_with('/') && !n.starts_with("__MACOSX/"))
            .map(str::to_string)
            .collect();
        crate::engine::sort::sort(&mut names);
        Ok(ZipSet {
            label: label.to_string(),
            archive,
            names,
            depth,
            budget,
        })
    }
}

impl<R: Read + Seek> FileSet for ZipSet<R> {
    fn names(&self) -> &[String] {
        &self.names
    }

    /// The entry, once its declared sizes pass [`Budget::admit`], metered as it is read (the
    /// zip crate checks its CRC-32).
    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>> {
        let f = self.archive.by_name(name).map_err(io::Error::other)?;
        let (compressed, size) = (f.compressed_size(), f.size());
        self.budget.admit(compressed, size)?;
        let key = format!("{}/{name}", self.label);
        let body = Metered::new(f, self.budget.clone(), key, compressed, size, None);
        Ok(Box::new(BufReader::with_capacity(1 << 16, body)))
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

/// Files held in memory (a browser upload).
#[derive(Default)]
pub struct MemSet {
    files: Vec<(String, Vec<u8>)>,
    names: Vec<String>,
}

impl MemSet {
    /// A set from `(name, bytes)` pairs.
    pub fn new(mut files: Vec<(String, Vec<u8>)>) -> Self {
        crate::engine::sort::sort_by(&mut files, |a, b| a.0.cmp(&b.0));
        let names = files.iter().map(|f| f.0.clone()).collect();
        MemSet { files, names }
    }

    fn bytes(&self, name: &str) -> io::Result<&[u8]> {
        self.files
            .iter()
            .find(|f| f.0 == name)
            .map(|f| f.1.as_slice())
            .ok_or_else(|| io::Error::new(io::ErrorKind::NotFound, name.to_string()))
    }
}

impl FileSet for MemSet {
    fn names(&self) -> &[String] {
        &self.names
    }

    fn size(&mut self, name: &str) -> Option<u64> {
        self.bytes(name).ok().map(|b| b.len() as u64)
    }

    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>> {
        Ok(Box::new(Cursor::new(self.bytes(name)?)))
    }

    fn open_seekable(&mut self, name: &str) -> Option<io::Result<Box<dyn ReadSeek + '_>>> {
        Some(
            self.bytes(name)
                .map(|b| Box::new(Cursor::new(b)) as Box<dyn ReadSeek + '_>),
        )
    }

    fn label(&self, name: &str) -> String {
        name.to_string()
    }
}

/// Whether bytes start like a zip archive.
pub fn is_zip(head: &[u8]) -> bool {
    head.starts_with(b"PK\x03\x04") || head.starts_with(b"PK\x05\x06")
}

//! The files of an upload, read where they lie: a `File` (a `Blob`) is read a slice at a time
//! with `FileReaderSync` as the parser asks for bytes, so that a 100 MB recording is never held
//! whole in the engine's memory. `FileReaderSync` exists only in workers: this is the upload
//! worker's file set.
//! May import: `io` (the file set it implements).

use crate::io::import::fileset::ReadSeek;
use crate::io::import::FileSet;
use std::cell::Cell;
use std::io::{self, BufRead, BufReader, Read, Seek, SeekFrom};
use std::rc::Rc;
use wasm_bindgen::JsValue;
use web_sys::{Blob, FileReaderSync};

/// Bytes per read from a blob (one `FileReaderSync` call).
const CHUNK: usize = 1 << 20;
/// Progress is reported after every this many bytes read.
const REPORT_EVERY: u64 = 4 << 20;

/// Bytes read so far across the set, and who to tell.
struct Progress {
    read: Cell<u64>,
    reported: Cell<u64>,
    callback: js_sys::Function,
}

impl Progress {
    fn add(&self, n: usize) {
        let read = self.read.get() + n as u64;
        self.read.set(read);
        if read - self.reported.get() >= REPORT_EVERY {
            self.reported.set(read);
            let _ = self.callback.call1(&JsValue::NULL, &(read as f64).into());
        }
    }
}

/// One blob as a seekable byte stream.
struct BlobFile {
    blob: Blob,
    size: u64,
    pos: u64,
    reader: Rc<FileReaderSync>,
    progress: Rc<Progress>,
    release: Rc<Release>,
}

/// Frees each slice's buffer as soon as its bytes are copied. `FileReaderSync` returns a new
/// buffer per read, and the garbage collector frees them only in a major collection, which a
/// worker busy in one long call rarely gets: reading a 99 MB file grew the page's process by
/// 70–104 MB of dead slices. A buffer transferred with `postMessage` to a port whose other end
/// is closed is freed at once (the process then grows by 7 MB).
struct Release {
    port: Option<web_sys::MessagePort>,
}

impl Release {
    fn new() -> Release {
        let port = web_sys::MessageChannel::new().ok().map(|c| {
            c.port2().close();
            c.port1()
        });
        Release { port }
    }

    fn free(&self, buffer: &js_sys::ArrayBuffer) {
        if let Some(port) = &self.port {
            let _ =
                port.post_message_with_transferable(&JsValue::NULL, &js_sys::Array::of1(buffer));
        }
    }
}

fn js_error(e: JsValue) -> io::Error {
    io::Error::other(
        e.as_string()
            .or_else(|| js_sys::Error::from(e).message().as_string())
            .unwrap_or_else(|| "the browser could not read the file".into()),
    )
}

impl Read for BlobFile {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = buf
            .len()
            .min(CHUNK)
            .min(self.size.saturating_sub(self.pos) as usize);
        if n == 0 {
            return Ok(0);
        }
        let slice = self
            .blob
            .slice_with_f64_and_f64(self.pos as f64, (self.pos + n as u64) as f64)
            .map_err(js_error)?;
        let buffer = self.reader.read_as_array_buffer(&slice).map_err(js_error)?;
        let bytes = js_sys::Uint8Array::new(&buffer);
        let got = (bytes.length() as usize).min(n);
        bytes.subarray(0, got as u32).copy_to(&mut buf[..got]);
        self.release.free(&buffer);
        self.pos += got as u64;
        self.progress.add(got);
        Ok(got)
    }
}

impl Seek for BlobFile {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        let pos = match to {
            SeekFrom::Start(p) => Some(p),
            SeekFrom::End(d) => self.size.checked_add_signed(d),
            SeekFrom::Current(d) => self.pos.checked_add_signed(d),
        }
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "seek before the start"))?;
        self.pos = pos;
        Ok(pos)
    }
}

/// A blob read through a window of [`WINDOW`] bytes that a seek inside it keeps. A zip
/// archive's reader seeks to every entry of the directory at the end: through a `BufReader`,
/// which forgets its buffer on every seek, 100 000 entries took 100 000 slice reads and over a
/// minute; through the window they take a few dozen.
struct Window {
    file: BlobFile,
    buf: Vec<u8>,
    start: u64,
    pos: u64,
}

/// See [`Window`].
const WINDOW: usize = 1 << 16;

impl Read for Window {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let end = self.start + self.buf.len() as u64;
        if !(self.start..end).contains(&self.pos) {
            self.buf.resize(WINDOW, 0);
            self.file.pos = self.pos;
            let n = self.file.read(&mut self.buf)?;
            self.buf.truncate(n);
            self.start = self.pos;
            if n == 0 {
                return Ok(0);
            }
        }
        let at = (self.pos - self.start) as usize;
        let n = out.len().min(self.buf.len() - at);
        out[..n].copy_from_slice(&self.buf[at..at + n]);
        self.pos += n as u64;
        Ok(n)
    }
}

impl Seek for Window {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        self.file.pos = self.pos;
        self.pos = self.file.seek(to)?;
        Ok(self.pos)
    }
}

/// The upload's files, by name (with their folder path for a folder upload).
pub struct BlobSet {
    files: Vec<(String, Blob)>,
    names: Vec<String>,
    reader: Rc<FileReaderSync>,
    progress: Rc<Progress>,
    release: Rc<Release>,
}

impl BlobSet {
    /// A set from `(name, blob)` pairs; `progress(bytes_read)` is called as reading goes on.
    pub fn new(
        mut files: Vec<(String, Blob)>,
        progress: js_sys::Function,
    ) -> Result<Self, JsValue> {
        crate::engine::sort::sort_by(&mut files, |a, b| a.0.cmp(&b.0));
        Ok(BlobSet {
            names: files.iter().map(|f| f.0.clone()).collect(),
            files,
            reader: Rc::new(FileReaderSync::new()?),
            progress: Rc::new(Progress {
                read: Cell::new(0),
                reported: Cell::new(0),
                callback: progress,
            }),
            release: Rc::new(Release::new()),
        })
    }

    fn file(&self, name: &str) -> io::Result<BlobFile> {
        let blob = self
            .files
            .iter()
            .find(|f| f.0 == name)
            .map(|f| f.1.clone())
            .ok_or_else(|| io::Error::new(io::ErrorKind::NotFound, name.to_string()))?;
        Ok(BlobFile {
            size: blob.size() as u64,
            blob,
            pos: 0,
            reader: Rc::clone(&self.reader),
            progress: Rc::clone(&self.progress),
            release: Rc::clone(&self.release),
        })
    }
}

impl FileSet for BlobSet {
    fn names(&self) -> &[String] {
        &self.names
    }

    fn size(&mut self, name: &str) -> Option<u64> {
        self.file(name).ok().map(|f| f.size)
    }

    fn open(&mut self, name: &str) -> io::Result<Box<dyn BufRead + '_>> {
        Ok(Box::new(BufReader::with_capacity(CHUNK, self.file(name)?)))
    }

    fn open_seekable(&mut self, name: &str) -> Option<io::Result<Box<dyn ReadSeek + '_>>> {
        Some(self.file(name).map(|f| {
            Box::new(Window {
                file: f,
                buf: Vec::new(),
                start: 0,
                pos: 0,
            }) as Box<dyn ReadSeek>
        }))
    }

    fn label(&self, name: &str) -> String {
        name.to_string()
    }

    fn head(&mut self, name: &str) -> io::Result<String> {
        let mut buf = Vec::with_capacity(crate::io::import::fileset::HEAD_BYTES);
        self.file(name)?
            .take(crate::io::import::fileset::HEAD_BYTES as u64)
            .read_to_end(&mut buf)?;
        Ok(String::from_utf8_lossy(&buf).into_owned())
    }
}

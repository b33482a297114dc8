//! Bounded line reading shared by [`pdrlog`](crate::io::pdrlog) and [`import`](crate::io::import):
//! the line and warning caps, lenient line iteration, record counts estimated from a file's head.
//! May import: `engine`, and `io`'s [`ParseError`]; not `pdrlog` nor `import`, which build on it.

use super::{file_error, ParseError};
use std::io::{self, BufRead};
use std::ops::ControlFlow;

/// Most warnings kept per log; further bad lines are only counted.
pub const MAX_WARNINGS: usize = 100;

/// Longest line kept, bytes. A longer line (binary junk, a file without line ends) is skipped
/// with a warning instead of being held in memory.
pub const MAX_LINE: usize = 1 << 16;

/// Reads one line without its `\n` into `buf`. `Ok(None)` at the end of input; `Ok(Some(true))`
/// when the line was longer than [`MAX_LINE`] (then `buf` is empty).
pub(crate) fn read_line_capped(
    r: &mut impl BufRead,
    buf: &mut Vec<u8>,
) -> io::Result<Option<bool>> {
    buf.clear();
    let mut any = false;
    let mut long = false;
    loop {
        let (used, done) = {
            let avail = match r.fill_buf() {
                Ok(a) => a,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            if avail.is_empty() {
                return Ok(any.then_some(long));
            }
            any = true;
            let (chunk, used, done) = match memchr::memchr(b'\n', avail) {
                Some(i) => (&avail[..i], i + 1, true),
                None => (avail, avail.len(), false),
            };
            if !long {
                if buf.len() + chunk.len() > MAX_LINE {
                    long = true;
                    buf.clear();
                } else {
                    buf.extend_from_slice(chunk);
                }
            }
            (used, done)
        };
        r.consume(used);
        if done {
            return Ok(Some(long));
        }
    }
}

/// Calls `f(line_number, line)` for every line, leniently: a line that is not UTF-8 text or is
/// longer than [`MAX_LINE`] is passed as an error naming the file and line, and reading goes on.
/// `\r` line ends and a byte-order mark on the first line are removed. Only a read failure of
/// the input itself is fatal.
pub(crate) fn each_line(
    r: impl BufRead,
    file: &str,
    mut f: impl FnMut(u64, Result<&str, ParseError>),
) -> Result<(), ParseError> {
    try_each_line(r, file, |n, l| {
        f(n, l);
        ControlFlow::Continue(())
    })
}

/// [`each_line`] that stops when `f` says so.
pub(crate) fn try_each_line(
    mut r: impl BufRead,
    file: &str,
    mut f: impl FnMut(u64, Result<&str, ParseError>) -> ControlFlow<()>,
) -> Result<(), ParseError> {
    let mut buf = Vec::with_capacity(256);
    let mut n = 0u64;
    loop {
        let long = read_line_capped(&mut r, &mut buf)
            .map_err(|e| file_error(file, n + 1, format!("cannot read: {e}")))?;
        let Some(long) = long else {
            return Ok(());
        };
        n += 1;
        let flow = if long {
            f(n, Err(file_error(file, n, "line too long: not a text log")))
        } else {
            match std::str::from_utf8(&buf) {
                Ok(s) => {
                    let s = s.trim_end_matches('\r');
                    let s = if n == 1 {
                        s.trim_start_matches('\u{feff}')
                    } else {
                        s
                    };
                    f(n, Ok(s))
                }
                Err(_) => f(n, Err(file_error(file, n, "not UTF-8 text"))),
            }
        };
        if flow.is_break() {
            return Ok(());
        }
    }
}

/// The number of records a pdr-log of `size` bytes holds, estimated from its first bytes
/// (`head`): the size over the mean length of the record lines there, plus 2 %. A CSV with one
/// record per line after its header (Sensor Logger's) is estimated the same way.
pub fn estimate_records(head: &str, size: u64) -> usize {
    let (mut n, mut bytes) = (0usize, 0usize);
    for l in head.lines().skip(1) {
        if !l.starts_with('#') && !l.is_empty() {
            n += 1;
            bytes += l.len() + 1;
        }
    }
    if n < 3 {
        return 0;
    }
    (size as f64 * n as f64 / bytes as f64 * 1.02) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_lenient() {
        let text = b"a\r\n\xff\xfe\nb\n";
        let mut got = Vec::new();
        each_line(&text[..], "f", |n, l| got.push((n, l.map(str::to_string)))).unwrap();
        assert_eq!(got[0], (1, Ok("a".to_string())));
        assert!(got[1].1.is_err());
        assert_eq!(got[2], (3, Ok("b".to_string())));
    }
}

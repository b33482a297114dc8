//! Sensor Logger's JSON export, read element by element with a streaming deserializer.
//! May import: `engine` and `io`.

use super::{Clock, Fields, Kind, Raw};
use crate::io::import::{field_error, Format, Log};
use crate::io::ParseError;
use std::cell::Cell;
use std::io::{self, BufRead, Read};

struct JsonRow<'a> {
    pairs: Vec<(String, String)>,
    file: &'a str,
    line: u64,
    column: usize,
    index: u64,
}

impl Fields for JsonRow<'_> {
    fn value(&self, key: &str) -> Option<&str> {
        self.pairs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn error(&self, key: &str, message: String) -> ParseError {
        let mut e = field_error(
            self.file,
            self.line,
            self.column,
            key,
            format!("array element {}: {message}", self.index),
        );
        if key.is_empty() {
            e.field = None;
        }
        e
    }
}

/// Whether the first bytes of a file look like Sensor Logger's JSON export: an array whose
/// first object has a `"sensor"` key.
pub fn looks_like_json(head: &str) -> bool {
    let h = head.trim_start_matches('\u{feff}').trim_start();
    h.starts_with('[') && h.contains("\"sensor\"")
}

/// Largest JSON element read, bytes (a reading is about 200 bytes). A larger one (a file
/// that is one huge string, junk) stops the reading instead of being held in memory.
const MAX_ELEMENT: u64 = crate::io::lines::MAX_LINE as u64;

/// A reader that counts lines and columns of the bytes it passes on, and refuses to pass on
/// more than [`MAX_ELEMENT`] bytes after the start of the current element (`element`, a byte
/// offset the visitor moves forward after each element).
struct Counting<'a, R> {
    inner: R,
    pos: &'a Cell<(u64, usize)>,
    read: &'a Cell<u64>,
    element: &'a Cell<u64>,
    too_long: &'a Cell<bool>,
}

impl<R: Read> Read for Counting<'_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let room = (self.element.get() + MAX_ELEMENT).saturating_sub(self.read.get());
        if room == 0 {
            self.too_long.set(true);
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("an element longer than {MAX_ELEMENT} bytes"),
            ));
        }
        let cap = buf.len().min(usize::try_from(room).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..cap])?;
        self.read.set(self.read.get() + n as u64);
        let (mut line, mut col) = self.pos.get();
        for &b in &buf[..n] {
            if b == b'\n' {
                line += 1;
                col = 0;
            } else {
                col += 1;
            }
        }
        self.pos.set((line, col));
        Ok(n)
    }
}

/// Visits the top-level array element by element.
struct Elements<'a> {
    raw: &'a mut Raw,
    label: &'a str,
    pos: &'a Cell<(u64, usize)>,
    count: &'a Cell<u64>,
    element: &'a Cell<u64>,
    read: &'a Cell<u64>,
}

impl<'de> serde::de::Visitor<'de> for Elements<'_> {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("an array of Sensor Logger readings")
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while let Some(v) = seq.next_element::<serde_json::Value>()? {
            // The next element may take MAX_ELEMENT bytes from here (the reader runs ahead by
            // at most its buffer).
            self.element.set(self.read.get());
            let index = self.count.get() + 1;
            self.count.set(index);
            let (line, column) = self.pos.get();
            let mut row = JsonRow {
                pairs: Vec::new(),
                file: self.label,
                line,
                column: column.max(1),
                index,
            };
            let serde_json::Value::Object(map) = v else {
                self.raw
                    .warnings
                    .push(row.error("", "not an object".to_string()));
                continue;
            };
            for (k, v) in map {
                let v = match v {
                    serde_json::Value::String(s) => s,
                    serde_json::Value::Number(n) => n.to_string(),
                    serde_json::Value::Bool(b) => b.to_string(),
                    _ => continue,
                };
                row.pairs.push((k.to_lowercase(), v));
            }
            let Some(sensor) = row.value("sensor") else {
                self.raw
                    .warnings
                    .push(row.error("sensor", "missing".to_string()));
                continue;
            };
            // Sensors we do not use (Pedometer, Microphone, …) are ignored silently.
            let Some(kind) = Kind::from_sensor(sensor) else {
                continue;
            };
            if let Err(e) = self.raw.sample(kind, Clock::EpochNs, &row) {
                self.raw.warnings.push(e);
            }
        }
        Ok(())
    }
}

/// Reads Sensor Logger's JSON export (see the [module documentation](super)).
pub fn read_json(r: impl BufRead, label: &str) -> Result<Log, ParseError> {
    let pos = Cell::new((1u64, 0usize));
    let count = Cell::new(0u64);
    let mut raw = Raw {
        accel_file: label.to_string(),
        ..Raw::default()
    };
    let (read, element, too_long) = (Cell::new(0u64), Cell::new(0u64), Cell::new(false));
    let counting = Counting {
        inner: r,
        pos: &pos,
        read: &read,
        element: &element,
        too_long: &too_long,
    };
    let mut de = serde_json::Deserializer::from_reader(counting);
    let parsed = serde::Deserializer::deserialize_seq(
        &mut de,
        Elements {
            raw: &mut raw,
            label,
            pos: &pos,
            count: &count,
            element: &element,
            read: &read,
        },
    )
    .and_then(|()| de.end());
    if let Err(e) = parsed {
        let err = ParseError {
            file: label.to_string(),
            line: e.line() as u64,
            column: Some(e.column()),
            field: None,
            message: format!("JSON: {e}"),
        };
        if e.is_io() && !too_long.get() {
            return Err(err);
        }
        if count.get() == 0 {
            return Err(ParseError {
                message: format!("not a Sensor Logger JSON export: {e}"),
                ..err
            });
        }
        // Cut short or damaged after some elements: keep what was read.
        raw.warnings.push(ParseError {
            message: format!(
                "JSON damaged after {} element(s), rest ignored: {e}",
                count.get()
            ),
            ..err
        });
    }
    raw.finish(Log::new(label, Format::SensorLoggerJson), label)
}

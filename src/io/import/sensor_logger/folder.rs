//! Sensor Logger's CSV folder (or zip): which files make a recording, and each file read by its
//! column names. May import: `engine` and `io`.

use super::{Clock, Fields, Kind, Raw, FILES};
use crate::io::import::common::{open, split_line, Table, Warnings};
use crate::io::import::{field_error, file_error, fileset, FileSet, Format, Log};
use crate::io::ParseError;
use std::io::BufRead;

struct CsvRow<'a> {
    rec: &'a csv::StringRecord,
    lower: &'a [String],
    header: &'a [String],
    file: &'a str,
    line: u64,
}

impl Fields for CsvRow<'_> {
    fn value(&self, key: &str) -> Option<&str> {
        let i = self.lower.iter().position(|h| h == key)?;
        self.rec.get(i)
    }
    fn error(&self, key: &str, message: String) -> ParseError {
        match self.lower.iter().position(|h| h == key) {
            Some(i) => field_error(self.file, self.line, i + 1, &self.header[i], message),
            None => file_error(self.file, self.line, format!("column `{key}`: {message}")),
        }
    }
}

impl Raw {
    /// Reads one CSV file of kind `kind` into the raw streams.
    fn csv_file(
        &mut self,
        r: impl BufRead,
        label: &str,
        kind: Kind,
        clock: Clock,
    ) -> Result<(), ParseError> {
        let table = match Table::open(r, label, Some(b',')) {
            Ok(t) => t,
            Err(e) if !kind.essential() => {
                self.warnings.push(e);
                return Ok(());
            }
            Err(e) => return Err(e),
        };
        let Some(mut table) = table else {
            if kind.essential() {
                return Err(file_error(label, 0, "empty file"));
            }
            return Ok(());
        };
        let mut missing: Vec<&str> = kind
            .required()
            .iter()
            .copied()
            .filter(|c| table.named(c).is_none())
            .collect();
        if kind != Kind::Metadata && table.named(clock.column()).is_none() {
            missing.insert(0, clock.column());
        }
        if !missing.is_empty() {
            let e = file_error(
                label,
                table.header_line,
                format!(
                    "not a Sensor Logger file: column{} `{}` missing from the header",
                    if missing.len() > 1 { "s" } else { "" },
                    missing.join("`, `")
                ),
            );
            if kind.essential() {
                return Err(e);
            }
            self.warnings.push(e);
            return Ok(());
        }
        let (header, lower) = (table.header.clone(), table.lower.clone());
        let mut warnings = Warnings::default();
        table.rows(label, &mut warnings, |line, rec| {
            let row = CsvRow {
                rec,
                lower: &lower,
                header: &header,
                file: label,
                line,
            };
            if let Err(e) = self.sample(kind, clock, &row) {
                self.warnings.push(e);
            }
        })?;
        self.warnings.extend(warnings);
        Ok(())
    }
}

fn is_csv(name: &str) -> bool {
    name.to_ascii_lowercase().ends_with(".csv")
}

/// Recognises a Sensor Logger folder inside a file set and reads it. `dir` is a folder of
/// `names` (ending with `/`, or empty for the top). Returns the files it consumed (every CSV
/// directly in the folder) and the log, or `None` when the folder is not a Sensor Logger
/// recording: it needs `Accelerometer.csv` or `TotalAcceleration.csv` whose header has a `time`
/// or `seconds_elapsed` column and `x`, `y`, `z`.
pub fn read_dir(
    set: &mut dyn FileSet,
    names: &[String],
    dir: &str,
) -> Option<(Vec<String>, Result<Log, ParseError>)> {
    let in_dir: Vec<&String> = names
        .iter()
        .filter(|n| fileset::parent(n) == dir && is_csv(n))
        .collect();
    let find = |base: &str| {
        in_dir
            .iter()
            .find(|n| fileset::base(n).eq_ignore_ascii_case(base))
            .map(|n| n.to_string())
    };
    let accel = find("TotalAcceleration.csv").or_else(|| find("Accelerometer.csv"))?;
    let head = set.head(&accel).ok()?;
    let first = head
        .lines()
        .next()
        .unwrap_or("")
        .trim_start_matches('\u{feff}');
    let cols: Vec<String> = split_line(first, b',')
        .into_iter()
        .map(|c| c.to_lowercase())
        .collect();
    let has = |c: &str| cols.iter().any(|h| h == c);
    if !((has("time") || has("seconds_elapsed")) && has("x") && has("y") && has("z")) {
        return None;
    }
    let consumed: Vec<String> = in_dir.iter().map(|n| n.to_string()).collect();
    let clock = if has("time") {
        Clock::EpochNs
    } else {
        Clock::Elapsed
    };
    let source = {
        let l = set.label(dir.trim_end_matches('/'));
        let l = l.trim_end_matches('/').to_string();
        if l.is_empty() {
            set.label(&accel)
        } else {
            l
        }
    };
    let log = Log::new(source.clone(), Format::SensorLogger);
    let read = (|| {
        let mut raw = Raw {
            accel_file: set.label(&accel),
            ..Raw::default()
        };
        let has_total = find("TotalAcceleration.csv").is_some();
        for (base, kind) in FILES {
            if kind == Kind::Accel && has_total {
                continue;
            }
            let Some(name) = in_dir
                .iter()
                .find(|n| fileset::base(n).to_ascii_lowercase() == base)
            else {
                continue;
            };
            let label = set.label(name);
            if let (Some(size), Ok(head)) = (set.size(name), set.head(name)) {
                raw.reserve(kind, crate::io::lines::estimate_records(&head, size));
            }
            let r = open(set, name, &label)?;
            raw.csv_file(r, &label, kind, clock)?;
        }
        raw.finish(log, &source)
    })();
    Some((consumed, read))
}

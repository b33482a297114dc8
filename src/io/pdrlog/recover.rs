//! The recovery of a live recording stored in numbered pieces: every good line kept, whatever
//! is missing, cut or not text noted.
//! May import: `engine`, [`lines`](crate::io::lines) and the rest of [`pdrlog`](super).

use super::{read, HEADER};
use crate::engine::Record;
use crate::io::lines::MAX_WARNINGS;
use crate::io::ParseError;
use std::fmt::Write as _;
use std::io::Read as _;

/// What could be read of a live recording stored in numbered pieces (the page appends the log
/// to storage in small batches; see [`recover`]).
#[derive(Debug, Default)]
pub struct Recovered {
    /// Every good record in time order, with a `gap` record where pieces are missing.
    pub records: Vec<Record>,
    /// Whether the pieces, joined in order, are a whole and good log: their text is then the
    /// log as it is; otherwise [`to_string`](crate::io::pdrlog::to_string) of `records` is.
    pub whole: bool,
    /// The IMU samples among `records`.
    pub samples: usize,
    /// Lines that could not be read: bad lines, a line cut at the end of a piece, the lines of
    /// a piece that is not text (counted as one).
    pub skipped_lines: u64,
    /// How many pieces are missing before the last one.
    pub missing_pieces: u64,
    /// What was wrong, the first [`MAX_WARNINGS`]: `piece 12, line 3, column 4, field `ay`:
    /// `x` is not a number`.
    pub notes: Vec<String>,
}

/// Reads a live recording from its pieces `(number, text)` (`None`: what was stored is not
/// text), numbered from 0, each normally a run of whole lines, the first starting with the
/// version tag. Never fails: a piece missing, not text, or cut in the middle of a line (its
/// last line is dropped), a bad line (skipped), and a missing version tag are noted, and every
/// good line is kept; where pieces are missing a `gap` record says that nothing bridges them.
pub fn recover(pieces: &[(u64, Option<&str>)]) -> Recovered {
    let mut out = Recovered {
        whole: true,
        ..Recovered::default()
    };
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    crate::engine::sort::sort_by_key(&mut order, |&i| pieces[i].0);
    if order.iter().enumerate().any(|(k, &i)| k != i) {
        out.whole = false; // the text was joined out of order
    }
    let mut expected = 0u64;
    let mut gap_before = false;
    for &i in &order {
        let (seq, text) = pieces[i];
        if seq < expected {
            out.note(format!(
                "piece {seq} is stored twice: the second copy is ignored"
            ));
            continue;
        }
        if seq > expected {
            let n = seq - expected;
            out.missing_pieces += n;
            gap_before = true;
            out.note(if n == 1 {
                format!("piece {expected} is missing: the walk has a gap there")
            } else {
                format!(
                    "pieces {expected} to {} are missing: the walk has a gap there",
                    seq - 1
                )
            });
        }
        expected = seq + 1;
        let Some(text) = text else {
            out.skipped_lines += 1;
            gap_before = true;
            out.note(format!("piece {seq} is not text: skipped"));
            continue;
        };
        gap_before = out.piece(seq, text, gap_before);
    }
    out.put_in_time_order();
    out.samples = out
        .records
        .iter()
        .filter(|r| matches!(r, Record::Imu(_)))
        .count();
    out
}

impl Recovered {
    /// Notes a problem: the log is then not whole.
    fn note(&mut self, s: String) {
        self.whole = false;
        if self.notes.len() < MAX_WARNINGS {
            self.notes.push(s);
        }
    }

    /// Reads piece `seq`'s text and adds its records, after a `gap` record when `gap_before`
    /// (pieces or records are missing before it). Returns whether a gap is still open after it.
    fn piece(&mut self, seq: u64, text: &str, gap_before: bool) -> bool {
        let body = if text.is_empty() || text.ends_with('\n') {
            text
        } else {
            self.skipped_lines += 1;
            self.note(format!(
                "piece {seq} ends in the middle of a line: that line was dropped"
            ));
            &text[..text.rfind('\n').map_or(0, |k| k + 1)]
        };
        let tagged = body.lines().next() == Some(HEADER);
        if seq == 0 && !tagged {
            self.note(format!(
                "the recording does not start with `{HEADER}`: read as a pdr-log 1"
            ));
        }
        // Each piece is read on its own, so that line numbers are the piece's.
        let prefix = if tagged { "" } else { "# pdr-log 1\n" };
        let shift = u64::from(!tagged);
        let parsed = match read(prefix.as_bytes().chain(body.as_bytes()), "") {
            Ok(p) => p,
            Err(e) => {
                self.skipped_lines += 1;
                self.note(format!("piece {seq}: {}", e.message));
                return gap_before;
            }
        };
        self.skipped_lines += parsed.skipped;
        for e in &parsed.errors {
            self.note(piece_note(seq, e, shift));
        }
        let mut gap_open = gap_before;
        if gap_before {
            let t0 = self.records.last().map(|r| match *r {
                Record::Gap(_, t1) => t1,
                r => r.t(),
            });
            let t1 = parsed.records.first().map(Record::t);
            if let (Some(t0), Some(t1)) = (t0, t1) {
                if t1 > t0 {
                    self.records.push(Record::Gap(t0, t1));
                }
            }
            gap_open = parsed.records.is_empty();
        }
        self.records.extend(parsed.records);
        gap_open
    }

    /// Puts the records in time order, with a note saying how many were out of it.
    fn put_in_time_order(&mut self) {
        let late = self
            .records
            .windows(2)
            .filter(|w| w[1].t() < w[0].t())
            .count();
        if late > 0 {
            crate::engine::sort::sort_by(&mut self.records, |a, b| a.t().total_cmp(&b.t()));
            self.note(format!(
                "{late} record(s) earlier than a record before them, put back in time order"
            ));
        }
    }
}

/// A problem of piece `seq` as a note: `piece 12, line 3, column 4, field `ay`: …`, the line
/// counted in the piece (`shift` lines were added before it to read it).
fn piece_note(seq: u64, e: &ParseError, shift: u64) -> String {
    let mut s = format!("piece {seq}");
    if e.line > 0 {
        let _ = write!(s, ", line {}", e.line - shift);
    }
    if let Some(c) = e.column {
        let _ = write!(s, ", column {c}");
    }
    if let Some(f) = &e.field {
        let _ = write!(s, ", field `{f}`");
    }
    let _ = write!(s, ": {}", e.message);
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::pdrlog::to_string;
    use crate::sim::scenarios;

    #[test]
    fn recover_keeps_every_good_line_of_damaged_pieces() {
        let sim = scenarios::straight_walk(1.8, 3.0).generate();
        let imu: Vec<Record> = sim
            .records
            .iter()
            .filter(|r| matches!(r, Record::Imu(_)))
            .take(40)
            .copied()
            .collect();
        let text = to_string(&imu);
        // Ten pieces of whole lines, as the page writes them.
        let lines: Vec<&str> = text.split_inclusive('\n').collect();
        let head = lines.len() - imu.len();
        let mut pieces: Vec<String> = vec![lines[..head + 4].concat()];
        for k in 1..10 {
            pieces.push(lines[head + 4 * k..head + 4 * (k + 1)].concat());
        }
        let whole: Vec<(u64, Option<&str>)> = pieces
            .iter()
            .enumerate()
            .map(|(i, p)| (i as u64, Some(p.as_str())))
            .collect();
        let r = recover(&whole);
        assert!(r.whole, "{:?}", r.notes);
        assert_eq!((r.samples, r.skipped_lines, r.missing_pieces), (40, 0, 0));
        assert_eq!(r.records, imu);

        // Piece 2 cut in the middle of its last line, piece 4 garbage, piece 6 missing, piece 8
        // not text.
        let cut = &pieces[2][..pieces[2].len() - 30];
        let garbage = format!("{}imu,1,2,x\n\u{1}\u{2}nonsense\n", &pieces[4]);
        let mut damaged: Vec<(u64, Option<&str>)> = whole.clone();
        damaged[2].1 = Some(cut);
        damaged[4].1 = Some(&garbage);
        damaged[8].1 = None;
        damaged.remove(6);
        let r = recover(&damaged);
        assert!(!r.whole);
        // Lost: the cut line, the missing piece's four, the four of the piece that is not text.
        assert_eq!(r.samples, 40 - 1 - 4 - 4);
        assert_eq!(r.missing_pieces, 1);
        assert_eq!(r.skipped_lines, 1 + 2 + 1, "{:?}", r.notes);
        let notes = r.notes.join("\n");
        assert!(
            notes.contains("piece 2 ends in the middle of a line"),
            "{notes}"
        );
        assert!(
            notes.contains("piece 4, line 5: a `imu` record has 15 fields, found 4"),
            "{notes}"
        );
        assert!(
            notes.contains("piece 4, line 6, column 1, field `kind`"),
            "{notes}"
        );
        assert!(notes.contains("piece 6 is missing"), "{notes}");
        assert!(notes.contains("piece 8 is not text"), "{notes}");
        // Every good record is there, in order, with a gap for each hole.
        let kept: Vec<Record> = r
            .records
            .iter()
            .filter(|x| matches!(x, Record::Imu(_)))
            .copied()
            .collect();
        let lost: Vec<usize> = [11].into_iter().chain(24..28).chain(32..36).collect();
        let want: Vec<Record> = imu
            .iter()
            .enumerate()
            .filter(|(i, _)| !lost.contains(i))
            .map(|(_, r)| *r)
            .collect();
        assert_eq!(kept, want);
        assert_eq!(
            r.records
                .iter()
                .filter(|x| matches!(x, Record::Gap(..)))
                .count(),
            2
        );
        // The clean log reads back without a complaint.
        let back = read(to_string(&r.records).as_bytes(), "clean").unwrap();
        assert_eq!((back.skipped, back.records.len()), (0, r.records.len()));

        // The first piece missing: read all the same, without the version tag.
        let r = recover(&whole[3..]);
        assert_eq!(r.samples, 40 - 12);
        assert!(
            r.notes[0].contains("pieces 0 to 2 are missing"),
            "{:?}",
            r.notes
        );
        assert!(recover(&[]).records.is_empty());
        assert_eq!(recover(&[(0, Some("garbage"))]).skipped_lines, 1);
    }
}

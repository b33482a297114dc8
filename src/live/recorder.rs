//! The live recording's bookkeeping: the chunks of pdr-log text not yet in the page's storage,
//! in order, handed out a batch at a time and let go only once written; what was saved; and when
//! to try again after the storage refused. The page only does the writes (IndexedDB) and says
//! whether each succeeded.
//! May import: `io` (the calendar, for the file name).

use std::collections::VecDeque;

/// Chunks per storage transaction when catching up.
pub const WRITE_CHUNKS: usize = 40;
/// The wait before the first retry after the storage refused, ms; it doubles at each refusal.
pub const RETRY_FIRST_MS: f64 = 1000.0;
/// The longest wait between retries, ms.
pub const RETRY_MAX_MS: f64 = 60_000.0;

/// A piece of the recording as the storage keeps it: its number, its pdr-log lines, and the
/// samples and steps counted when it was taken.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Chunk {
    /// Its place in the recording, from 0.
    pub seq: u64,
    /// Its pdr-log lines.
    pub text: String,
    /// Motion samples used when it was taken.
    pub samples: u64,
    /// Steps counted when it was taken.
    pub steps: usize,
}

/// What was written so far, and the text still held in memory (UTF-16 units, as the page
/// counts a string's length).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Saved {
    /// Chunks written.
    pub chunks: u64,
    /// Their text's length.
    pub chars: u64,
    /// The motion samples in them: the last written chunk's count.
    pub samples: u64,
    /// The length of the text not yet written.
    #[serde(rename = "unsavedChars")]
    pub unsaved_chars: u64,
}

/// The queue of a recording's unsaved chunks and the schedule of its writes. A write run goes:
/// [`Recorder::begin`], then [`Recorder::batch`] / [`Recorder::written`] until the batch is
/// empty, then [`Recorder::succeeded`]; or [`Recorder::failed`] when the storage refuses.
#[derive(Debug, Clone)]
pub struct Recorder {
    /// False for a walk that is not recorded: its lines are dropped.
    on: bool,
    next_seq: u64,
    unsaved: VecDeque<Chunk>,
    /// Chunks of the front of `unsaved` handed out by the last [`Recorder::batch`].
    handed: usize,
    writing: bool,
    /// Whether the last run was refused (the page shows a message until a run succeeds).
    refused: bool,
    retry_at_ms: f64,
    retry_ms: f64,
    saved_chunks: u64,
    saved_chars: u64,
    saved_samples: u64,
}

impl Recorder {
    /// A recording whose next chunk is numbered `next_seq` (0 for a new one, the next after the
    /// stored ones for a resumed one).
    pub fn new(next_seq: u64) -> Self {
        Recorder {
            on: true,
            next_seq,
            unsaved: VecDeque::new(),
            handed: 0,
            writing: false,
            refused: false,
            retry_at_ms: f64::NEG_INFINITY,
            retry_ms: RETRY_FIRST_MS,
            saved_chunks: 0,
            saved_chars: 0,
            saved_samples: 0,
        }
    }

    /// A walk that is not recorded (a calibration walk): nothing is kept, nothing written.
    pub fn off() -> Self {
        Recorder {
            on: false,
            ..Recorder::new(0)
        }
    }

    /// Queues `text` (new pdr-log lines; nothing when empty) as the next chunk, with the samples
    /// and steps counted so far.
    pub fn push(&mut self, text: String, samples: u64, steps: usize) {
        if !self.on || text.is_empty() {
            return;
        }
        let seq = self.next_seq;
        self.next_seq += 1;
        self.unsaved.push_back(Chunk {
            seq,
            text,
            samples,
            steps,
        });
    }

    /// Whether to start a write run at `now_ms`: none is running, something is unsaved, and
    /// the wait after a refusal is over (`force`: it need not be, the recording is stopping).
    pub fn begin(&mut self, now_ms: f64, force: bool) -> bool {
        if self.writing || self.unsaved.is_empty() || (!force && now_ms < self.retry_at_ms) {
            return false;
        }
        self.writing = true;
        true
    }

    /// The next chunks to write in one transaction, in order (at most [`WRITE_CHUNKS`]); empty
    /// when all are written.
    pub fn batch(&mut self) -> Vec<Chunk> {
        self.handed = self.unsaved.len().min(WRITE_CHUNKS);
        self.unsaved.iter().take(self.handed).cloned().collect()
    }

    /// The last batch is stored: it leaves the queue and is counted.
    pub fn written(&mut self) {
        for c in self.unsaved.drain(..self.handed) {
            self.saved_chunks += 1;
            self.saved_chars += utf16_len(&c.text);
            self.saved_samples = self.saved_samples.max(c.samples);
        }
        self.handed = 0;
    }

    /// The run ended with everything written: the wait starts again from the shortest. Returns
    /// whether a refusal was being shown (the page clears it).
    pub fn succeeded(&mut self) -> bool {
        self.writing = false;
        self.retry_ms = RETRY_FIRST_MS;
        std::mem::take(&mut self.refused)
    }

    /// The storage refused at `now_ms`: the chunks stay queued, the next run waits, and the
    /// wait after the next refusal doubles (up to [`RETRY_MAX_MS`]).
    pub fn failed(&mut self, now_ms: f64) {
        self.writing = false;
        self.handed = 0;
        self.refused = true;
        self.retry_at_ms = now_ms + self.retry_ms;
        self.retry_ms = (2.0 * self.retry_ms).min(RETRY_MAX_MS);
    }

    /// The chunks not yet written, in order.
    pub fn unsaved(&self) -> impl Iterator<Item = &Chunk> {
        self.unsaved.iter()
    }

    /// How many chunks are not yet written.
    pub fn unsaved_count(&self) -> usize {
        self.unsaved.len()
    }

    /// What was written, and the text still held.
    pub fn saved(&self) -> Saved {
        Saved {
            chunks: self.saved_chunks,
            chars: self.saved_chars,
            samples: self.saved_samples,
            unsaved_chars: self.unsaved.iter().map(|c| utf16_len(&c.text)).sum(),
        }
    }

    /// When the next run may start after a refusal, ms on the page's clock.
    pub fn retry_at_ms(&self) -> f64 {
        self.retry_at_ms
    }
}

/// A string's length as JavaScript counts it (UTF-16 units).
fn utf16_len(s: &str) -> u64 {
    s.encode_utf16().count() as u64
}

/// The name a recording started at `started_ms` (Unix ms) is downloaded under:
/// `pdr-2026-11-28-18-29-01.pdrlog` (UTC); `None` for a time that is no date.
pub fn file_name(started_ms: f64) -> Option<String> {
    let (y, mo, d, h, mi, s) = crate::io::import::date::civil_of_unix(started_ms * 1e-3)?;
    Some(format!(
        "pdr-{y:04}-{mo:02}-{d:02}-{h:02}-{mi:02}-{s:02}.pdrlog"
    ))
}

/// The pieces a closing page saved (`tail`: the JSON text of a list of `{seq, text, samples,
/// steps}`) whose numbers are not among those of the stored pieces, `have`; none without a tail,
/// or when its text is damaged or not a list.
pub fn tail_missing(tail: Option<&str>, have: &[Option<f64>]) -> Vec<serde_json::Value> {
    let Some(Ok(serde_json::Value::Array(pieces))) = tail.map(serde_json::from_str) else {
        return Vec::new();
    };
    pieces
        .into_iter()
        .filter(|p| !have.contains(&p.get("seq").and_then(serde_json::Value::as_f64)))
        .collect()
}

/// The reading order of a recording's stored pieces, given the number of each (`None`: it has
/// none, or not a whole number: damaged): the index of the first piece with each number (the
/// storage's pieces come before those still held in memory, so a written piece wins), by
/// ascending number, then the first piece without one (the reader notes it and skips it); and
/// the next piece's number, one past the largest.
pub fn piece_order(seqs: &[Option<f64>]) -> (Vec<usize>, u64) {
    let whole = |s: &f64| *s >= 0.0 && s.fract() == 0.0 && *s < 9e15;
    let mut numbered: Vec<(u64, usize)> = Vec::new();
    let mut unnumbered = None;
    for (i, s) in seqs.iter().enumerate() {
        match s.filter(whole) {
            Some(s) => numbered.push((s as u64, i)),
            None => unnumbered = unnumbered.or(Some(i)),
        }
    }
    // Stable: of the pieces with one number, the first given stays first.
    numbered.sort_by_key(|&(s, _)| s);
    numbered.dedup_by_key(|&mut (s, _)| s);
    let next = numbered.last().map_or(0, |&(s, _)| s + 1);
    let order = numbered
        .into_iter()
        .map(|(_, i)| i)
        .chain(unnumbered)
        .collect();
    (order, next)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tail_adds_the_pieces_the_storage_lacks() {
        let tail = r#"[{"seq": 3, "text": "a"}, {"seq": 4, "text": "b"}, null]"#;
        let missing = tail_missing(Some(tail), &[Some(2.0), Some(3.0)]);
        assert_eq!(
            missing,
            [
                serde_json::json!({"seq": 4, "text": "b"}),
                serde_json::Value::Null
            ]
        );
        assert!(tail_missing(Some(tail), &[Some(3.0), Some(4.0), None]).is_empty());
        for damaged in [None, Some("[{"), Some("{}"), Some("3")] {
            assert!(tail_missing(damaged, &[]).is_empty(), "{damaged:?}");
        }
    }

    #[test]
    fn pieces_are_read_once_each_in_order_written_ones_first() {
        assert_eq!(piece_order(&[]), (vec![], 0));
        let (order, next) = piece_order(&[Some(2.0), Some(0.0), None, Some(2.0), Some(1.0), None]);
        assert_eq!(
            order,
            [1, 4, 0, 2],
            "each number once, the first given; one damaged piece"
        );
        assert_eq!(next, 3);
        let (order, next) = piece_order(&[Some(-1.0), Some(0.5), Some(f64::NAN), Some(7.0)]);
        assert_eq!(
            (order, next),
            (vec![3, 0], 8),
            "numbers that are no count are damage"
        );
    }

    fn rec(n: usize) -> Recorder {
        let mut r = Recorder::new(5);
        for i in 0..n {
            r.push(format!("line {i}\n"), i as u64 * 10, i);
        }
        r
    }

    #[test]
    fn chunks_are_numbered_in_order_and_empty_text_is_no_chunk() {
        let mut r = rec(3);
        r.push(String::new(), 99, 9);
        let seqs: Vec<u64> = r.unsaved().map(|c| c.seq).collect();
        assert_eq!(seqs, [5, 6, 7]);
        assert_eq!(r.unsaved().last().unwrap().samples, 20);
        let mut off = Recorder::off();
        off.push("x\n".into(), 1, 1);
        assert_eq!(off.unsaved_count(), 0);
        assert!(!off.begin(0.0, true));
    }

    #[test]
    fn batches_of_forty_leave_only_once_written() {
        let mut r = rec(90);
        assert!(r.begin(0.0, false));
        assert!(!r.begin(0.0, false), "one run at a time");
        let b = r.batch();
        assert_eq!((b.len(), b[0].seq, b[39].seq), (40, 5, 44));
        // More lines come while the batch is written: they wait their turn.
        r.push("late\n".into(), 1000, 100);
        r.written();
        assert_eq!(r.unsaved_count(), 51);
        assert_eq!(r.saved().chunks, 40);
        assert_eq!(r.saved().samples, 390);
        assert_eq!(r.batch().len(), 40);
        r.written();
        let last = r.batch();
        assert_eq!(
            (last.len(), last[10].seq, last[10].text.as_str()),
            (11, 95, "late\n")
        );
        r.written();
        assert!(r.batch().is_empty());
        assert!(!r.succeeded());
        let s = r.saved();
        assert_eq!((s.chunks, s.samples, s.unsaved_chars), (91, 1000, 0));
        assert_eq!(
            s.chars,
            (0..90)
                .map(|i| format!("line {i}\n").len() as u64)
                .sum::<u64>()
                + 5
        );
    }

    #[test]
    fn a_refusal_keeps_everything_and_waits_doubling_up_to_a_minute() {
        let mut r = rec(3);
        let mut waits = Vec::new();
        let mut now = 0.0;
        for _ in 0..9 {
            assert!(r.begin(now, false));
            assert_eq!(r.batch().len(), 3);
            r.failed(now);
            assert_eq!(r.unsaved_count(), 3, "nothing lost");
            assert!(!r.begin(now + 1.0, false), "waits");
            waits.push(r.retry_at_ms() - now);
            now = r.retry_at_ms();
        }
        assert_eq!(
            waits,
            [1000.0, 2000.0, 4000.0, 8000.0, 16000.0, 32000.0, 60000.0, 60000.0, 60000.0]
        );
        // Stopping writes at once; a success resets the wait and clears the message.
        assert!(r.begin(now - 5.0, true));
        r.batch();
        r.written();
        assert!(r.batch().is_empty());
        assert!(r.succeeded());
        assert!(!r.succeeded());
        r.push("more\n".into(), 1, 1);
        assert!(r.begin(now, false));
        r.failed(now);
        assert_eq!(r.retry_at_ms() - now, 1000.0);
        assert_eq!(r.saved().unsaved_chars, 5);
    }

    #[test]
    fn file_names_are_the_start_in_utc() {
        assert_eq!(
            file_name(1_764_354_541_000.0).as_deref(),
            Some("pdr-2025-11-28-18-29-01.pdrlog")
        );
        assert_eq!(
            file_name(0.0).as_deref(),
            Some("pdr-1970-01-01-00-00-00.pdrlog")
        );
        assert_eq!(file_name(f64::NAN), None);
    }
}

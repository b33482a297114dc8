//! The recording's bookkeeping for the live page (see `live::recorder`): the page writes the
//! batches it is handed to IndexedDB and says how each went.
//! May import: `live`.

use super::{to_js, to_json_value, to_value};
use wasm_bindgen::prelude::*;

/// The unsaved chunks of a live recording and the schedule of their writes.
#[wasm_bindgen]
pub struct Recorder {
    pub(super) inner: crate::live::Recorder,
}

#[wasm_bindgen]
impl Recorder {
    /// A recording whose next chunk is numbered `next_seq` (a whole number ≥ 0).
    #[wasm_bindgen(constructor)]
    pub fn new(next_seq: f64) -> Result<Recorder, JsError> {
        if !(next_seq >= 0.0 && next_seq.fract() == 0.0 && next_seq < 9e15) {
            return Err(to_js(format!(
                "the next chunk number {next_seq} is not a count"
            )));
        }
        Ok(Recorder {
            inner: crate::live::Recorder::new(next_seq as u64),
        })
    }

    /// A walk that is not recorded (a calibration walk): its lines are dropped.
    pub fn off() -> Recorder {
        Recorder {
            inner: crate::live::Recorder::off(),
        }
    }

    /// Whether to start a write run now (`now_ms`, page clock); `force` ignores the wait after a
    /// refusal.
    pub fn begin(&mut self, now_ms: f64, force: bool) -> bool {
        self.inner.begin(now_ms, force)
    }

    /// The next chunks to write in one transaction, `[{seq, text, samples, steps}]`; empty when
    /// all are written.
    pub fn batch(&mut self) -> Result<JsValue, JsError> {
        to_value(&self.inner.batch())
    }

    /// The last batch is stored.
    pub fn written(&mut self) {
        self.inner.written();
    }

    /// The run wrote everything; returns whether the storage message should be cleared.
    pub fn succeeded(&mut self) -> bool {
        self.inner.succeeded()
    }

    /// The storage refused at `now_ms`: everything stays, and the next run waits.
    pub fn failed(&mut self, now_ms: f64) {
        self.inner.failed(now_ms);
    }

    /// The chunks not yet written, in order, `[{seq, text, samples, steps}]`.
    pub fn unsaved(&self) -> Result<JsValue, JsError> {
        to_value(&self.inner.unsaved().collect::<Vec<_>>())
    }

    /// How many chunks are not yet written.
    pub fn unsaved_count(&self) -> usize {
        self.inner.unsaved_count()
    }

    /// `{chunks, chars, unsavedChars}`: what was written, and the text still held.
    pub fn saved(&self) -> Result<JsValue, JsError> {
        to_value(&self.inner.saved())
    }
}

/// The file name of a recording started at `started_ms` (Unix ms).
#[wasm_bindgen]
pub fn recording_file_name(started_ms: f64) -> Result<String, JsError> {
    crate::live::recorder::file_name(started_ms)
        .ok_or_else(|| to_js(format!("the start {started_ms} is not a date")))
}

/// A stored piece's number (`None`: none, or not a number).
fn seq_of(piece: &JsValue) -> Option<f64> {
    js_sys::Reflect::get(piece, &JsValue::from_str("seq"))
        .ok()?
        .as_f64()
}

/// The pieces a closing page saved in localStorage (`tail`: their JSON text, or `null`) that
/// the stored pieces `stored` (`[{seq, …}]`) lack, `[{seq, text, samples, steps}]` (see
/// `live::recorder::tail_missing`); none when the text is damaged.
#[wasm_bindgen]
pub fn tail_missing(tail: Option<String>, stored: Vec<JsValue>) -> Result<JsValue, JsError> {
    let have: Vec<Option<f64>> = stored.iter().map(seq_of).collect();
    to_json_value(&crate::live::recorder::tail_missing(tail.as_deref(), &have))
}

/// A recording's stored pieces (`[{seq, …}]`: the storage's, then those not yet written) in
/// reading order, `{pieces, nextSeq}`: each number once, the storage's first, ascending, then
/// one piece without a number if any (`recover_recording` notes it), and the next piece's
/// number (see `live::recorder::piece_order`). Pieces that are not objects are dropped.
#[wasm_bindgen]
pub fn pieces_in_order(pieces: Vec<JsValue>) -> Result<JsValue, JsError> {
    let pieces: Vec<JsValue> = pieces.into_iter().filter(JsValue::is_object).collect();
    let seqs: Vec<Option<f64>> = pieces.iter().map(seq_of).collect();
    let (order, next) = crate::live::recorder::piece_order(&seqs);
    let ordered: js_sys::Array = order.into_iter().map(|i| pieces[i].clone()).collect();
    let out = js_sys::Object::new();
    let set = |k: &str, v: &JsValue| js_sys::Reflect::set(&out, &JsValue::from_str(k), v);
    set("pieces", &ordered).map_err(|_| to_js("cannot set the pieces"))?;
    set("nextSeq", &JsValue::from_f64(next as f64)).map_err(|_| to_js("cannot set nextSeq"))?;
    Ok(out.into())
}

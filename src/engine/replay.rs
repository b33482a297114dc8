//! The one replay loop: the records of a log through a pipeline, in order. Replaying a log
//! (`pdr run`, `pdr eval`), upload mode's analysis and live mode's resume after a reload all run
//! it; an [`Observer`] sees the pipeline after each record (the plots' signals, the live view).
//! May import: the rest of `engine`.

use super::pipeline::{Pipeline, PipelineConfig};
use super::types::{ConfigError, InputError, Record};

/// How many refused records a replay keeps for reporting (all are counted).
pub const REPLAY_ERRORS_KEPT: usize = 100;

/// Sees the pipeline after each record of a replay.
pub trait Observer {
    /// Record `index` went through `pipeline`; `accepted` is false when it was refused (the
    /// pipeline is then as it was before the record).
    fn observe(&mut self, pipeline: &Pipeline, index: usize, record: &Record, accepted: bool);
}

impl<F: FnMut(&Pipeline, usize, &Record, bool)> Observer for F {
    fn observe(&mut self, pipeline: &Pipeline, index: usize, record: &Record, accepted: bool) {
        self(pipeline, index, record, accepted)
    }
}

/// The records a replay refused.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Refusals {
    /// The first [`REPLAY_ERRORS_KEPT`] records refused, with their index in the input.
    pub errors: Vec<(usize, InputError)>,
    /// How many records were refused in all.
    pub count: u64,
}

/// Feeds `records` through `pipeline` in order, showing each to `observer`.
pub fn feed<'a>(
    pipeline: &mut Pipeline,
    records: impl IntoIterator<Item = &'a Record>,
    observer: &mut impl Observer,
) -> Refusals {
    let mut out = Refusals::default();
    for (i, r) in records.into_iter().enumerate() {
        let accepted = match pipeline.push(r) {
            Ok(_) => true,
            Err(e) => {
                out.count += 1;
                if out.errors.len() < REPLAY_ERRORS_KEPT {
                    out.errors.push((i, e));
                }
                false
            }
        };
        observer.observe(pipeline, i, r, accepted);
    }
    out
}

/// The result of replaying a log.
pub struct Replay {
    /// The pipeline after the last record, holding the track and the diagnostics.
    pub pipeline: Pipeline,
    /// The first [`REPLAY_ERRORS_KEPT`] records refused, with their index in the input.
    pub errors: Vec<(usize, InputError)>,
    /// How many records were refused in all.
    pub refused: u64,
}

/// Replays records through a new pipeline.
pub fn replay<'a>(
    cfg: PipelineConfig,
    records: impl IntoIterator<Item = &'a Record>,
) -> Result<Replay, ConfigError> {
    replay_observed(cfg, records, &mut |_: &Pipeline, _, _: &Record, _| {})
}

/// Replays records through a new pipeline, showing each to `observer`.
pub fn replay_observed<'a>(
    cfg: PipelineConfig,
    records: impl IntoIterator<Item = &'a Record>,
    observer: &mut impl Observer,
) -> Result<Replay, ConfigError> {
    let mut pipeline = Pipeline::new(cfg)?;
    let r = feed(&mut pipeline, records, observer);
    pipeline.finish();
    Ok(Replay {
        pipeline,
        errors: r.errors,
        refused: r.count,
    })
}

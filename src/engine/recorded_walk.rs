//! A calibration walk from a recording: the records of a walk of known distance through one
//! pipeline, and what the calibration wizard needs of it — each step's frequency (Basso 2016
//! eqs. 1–2), unscaled fuzzy length (Ibarra 2015) and leg pitch amplitude (Munoz Diaz 2015
//! §5.1) — as a live calibration walk gives them ([`crate::engine::calibration::CalibrationWalk`]).
//! May import: the rest of `engine`.

use super::calibration::CalibrationWalk;
use super::fuzzy_step_length::{FuzzyConfig, FuzzyStepLength};
use super::pipeline::{Pipeline, PipelineConfig};
use super::replay::replay_observed;
use super::step_length::fuzzy_step;
use super::types::{ConfigError, Record};

/// The unscaled fuzzy step length (Ibarra 2015, [`crate::engine::fuzzy_step_length`], scale 1)
/// of every step of a pipeline's track, whatever its own step-length model: computed as each
/// step is emitted, from the same buffer and span the step-length stage had
/// ([`Pipeline::step_length_input`], [`crate::engine::step_length::fuzzy_step`]).
#[derive(Debug, Clone)]
pub struct FuzzyLengths {
    model: FuzzyStepLength,
    /// One length per step of the track (and of the steps a bout's opening holds), m.
    pub lengths: Vec<f64>,
}

impl Default for FuzzyLengths {
    fn default() -> Self {
        Self::new()
    }
}

impl FuzzyLengths {
    /// No steps yet; the fuzzy system with its default rules.
    pub fn new() -> Self {
        FuzzyLengths {
            model: FuzzyStepLength::new(FuzzyConfig::default()),
            lengths: Vec::new(),
        }
    }

    /// Catches up with the steps the pipeline emitted since the last call (call it after every
    /// record, before the next one moves the buffer), those a bout's opening holds too: they
    /// follow the track in this order.
    pub fn observe(&mut self, p: &Pipeline) {
        for step in p
            .track()
            .iter()
            .chain(p.held_steps())
            .skip(self.lengths.len())
        {
            let l = fuzzy_step(&self.model, &p.step_length_input(step)).centroid_m;
            self.lengths.push(l);
        }
    }
}

/// What one recorded walk of known distance gives the calibration (serialisable: the upload
/// worker's module reads the recording and the page's module adds the walk).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RecordedWalk {
    /// The walk as the wizard takes it: the distance, the steps' frequencies, Hz, and their
    /// unscaled fuzzy lengths, m.
    pub walk: CalibrationWalk,
    /// Each step's leg pitch amplitude Δθ, degrees, NaN for a step without one.
    pub pitch_amplitudes_deg: Vec<f64>,
    /// The distance the engine measured with the configuration given, m (what `pdr run`
    /// prints).
    pub engine_distance_m: f64,
}

/// Replays `records` through a pipeline configured by `cfg` (the one replay loop `pdr run`
/// uses) and collects the walk's steps, for a walk of `distance_m` metres. The distance is
/// not checked here: [`crate::engine::calibration::Wizard::add`] refuses a walk without one.
pub fn recorded_walk(
    cfg: PipelineConfig,
    records: &[Record],
    distance_m: f64,
) -> Result<RecordedWalk, ConfigError> {
    let mut fuzzy = FuzzyLengths::new();
    let r = replay_observed(
        cfg,
        records,
        &mut |p: &Pipeline, _, _: &Record, accepted| {
            if accepted {
                fuzzy.observe(p);
            }
        },
    )?;
    let p = &r.pipeline;
    fuzzy.observe(p);
    let track = p.track();
    // Held steps the end of the log dropped have lengths but no place in the track.
    fuzzy.lengths.truncate(track.len());
    Ok(RecordedWalk {
        walk: CalibrationWalk {
            distance_m,
            step_freqs_hz: track.iter().map(|s| s.freq_hz).collect(),
            fuzzy_lengths_m: fuzzy.lengths,
        },
        pitch_amplitudes_deg: track
            .iter()
            .map(|s| s.pitch_amplitude_deg.unwrap_or(f64::NAN))
            .collect(),
        engine_distance_m: p.diagnostics().distance_m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The walk crosses from upload mode's wasm module to the page's as postcard bytes of
    /// `Result<RecordedWalk, String>`: every figure comes back bit for bit, a step's NaN pitch
    /// amplitude too, and so does a reason.
    #[test]
    fn a_recorded_walk_and_a_reason_cross_as_bytes() {
        let walk = RecordedWalk {
            walk: CalibrationWalk {
                distance_m: 60.0,
                step_freqs_hz: vec![1.8, 1.81],
                fuzzy_lengths_m: vec![0.7, 0.71],
            },
            pitch_amplitudes_deg: vec![31.5, f64::NAN],
            engine_distance_m: 58.25,
        };
        let ok: Result<RecordedWalk, String> = Ok(walk.clone());
        let back: Result<RecordedWalk, String> =
            postcard::from_bytes(&postcard::to_stdvec(&ok).unwrap()).unwrap();
        let back = back.unwrap();
        assert_eq!(back.walk, walk.walk);
        assert_eq!(back.engine_distance_m, walk.engine_distance_m);
        assert_eq!(back.pitch_amplitudes_deg[0], 31.5);
        assert!(back.pitch_amplitudes_deg[1].is_nan());
        let why: Result<RecordedWalk, String> = Err("walk.csv: too few steps".into());
        let back: Result<RecordedWalk, String> =
            postcard::from_bytes(&postcard::to_stdvec(&why).unwrap()).unwrap();
        assert_eq!(back, why);
    }
}

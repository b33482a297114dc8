//! `pdr calibrate`: the calibration wizard's fit (Basso 2016 §II.D, quick mode with one walk)
//! from recordings of walks of known distance, written as the wizard's profile file.
//! May import: the `pdr` library and `read`; nothing of the other subcommands.

use crate::read::read_one;
use pdr::engine::calibration::{Band, Wizard};
use pdr::engine::recorded_walk::{recorded_walk, RecordedWalk};
use pdr::engine::{replay, PipelineConfig};
use pdr::io::import::recipe::Recipe;
use pdr::io::import::Log;
use pdr::settings::Settings;
use std::path::{Path, PathBuf};

/// What `pdr calibrate` was asked: the recordings, each with its true distance, m.
pub struct Request<'a> {
    /// The recordings, in the order given.
    pub files: &'a [PathBuf],
    /// Their true distances, m, in the same order.
    pub metres: &'a [f64],
    /// Where the profile file goes.
    pub out: &'a Path,
    /// The profile's name (empty: "me").
    pub name: &'a str,
    /// The recipe that reads the recordings, when given.
    pub recipe: Option<&'a Recipe>,
}

/// The pace a recording's walk is filed under in the wizard's walks.
const PACE: &str = "recording";

/// Fits the profile to the recordings, prints the coefficients and each walk's figures, and
/// writes the profile file.
pub fn calibrate(req: &Request, settings: &Settings) -> Result<(), String> {
    let pairs = pair(req.files, req.metres)?;
    let cfg = settings.config().map_err(|e| e.to_string())?;
    let mut wizard = Wizard::default();
    let mut walks = Vec::new();
    let mut pitch_offset = None;
    for (file, metres) in pairs {
        let name = file.display().to_string();
        let log = read_one(file, &name, req.recipe)?;
        let walk = recorded_walk(log.dated(&cfg), &log.records, metres)
            .map_err(|e| format!("{name}: {e}"))?;
        wizard
            .add(Band::Walking, PACE, &walk.walk)
            .map_err(|e| format!("{name}: {e}"))?;
        // As the wizard's normal walk: the leg-pitch offset when most steps had a leg pitch.
        let pitch = pdr::live::wizard::pitch_calibration(metres, &walk.pitch_amplitudes_deg);
        if pitch.offset_m.is_some() {
            pitch_offset = pitch.offset_m;
        }
        walks.push((name, log, walk));
    }
    let file = wizard.profile_file(&pdr::live::wizard::profile_name(req.name), pitch_offset);
    let json = file.to_json().map_err(|e| e.to_string())?;
    let after_cfg = Settings {
        profile: Some(json.clone()),
        ..settings.clone()
    }
    .config()
    .map_err(|e| e.to_string())?;
    let (_, notes) = wizard.profile(&Default::default());
    out!("profile       {}", file.describe());
    for n in &notes {
        out!("fit           {n}");
    }
    if let Some(b) = pitch_offset {
        out!("pitch offset  b = {b:.3} m per stride (leg-pitch step length)");
    }
    for (i, ((name, log, walk), w)) in walks.iter().zip(&wizard.walks).enumerate() {
        let after = engine_distance(log, &after_cfg).map_err(|e| format!("{name}: {e}"))?;
        out!("walk {:<8} {name}", i + 1);
        out!("{}", walk_figures(walk, w.f_mean_hz, w.sl_mean_m, after));
    }
    std::fs::write(req.out, &json).map_err(|e| format!("{}: {e}", req.out.display()))?;
    out!("written       {}", req.out.display());
    Ok(())
}

/// A walk's line of figures: steps, true distance, f̄ and SL̄, and the engine's distance before
/// and after calibration with their ratios to the true distance.
fn walk_figures(walk: &RecordedWalk, f_mean_hz: f64, sl_mean_m: f64, after_m: f64) -> String {
    let d = walk.walk.distance_m;
    format!(
        "              {} steps over {d:.1} m · f̄ = {f_mean_hz:.2} Hz · SL̄ = {sl_mean_m:.3} m · \
         engine {:.1} m before ({:.3}×), {after_m:.1} m after ({:.3}×)",
        walk.walk.step_freqs_hz.len(),
        walk.engine_distance_m,
        walk.engine_distance_m / d,
        after_m / d
    )
}

/// The engine's distance over a log with `cfg`, m: `pdr run`'s replay and its `distance`.
fn engine_distance(log: &Log, cfg: &PipelineConfig) -> Result<f64, String> {
    let r = replay(log.dated(cfg), &log.records).map_err(|e| e.to_string())?;
    Ok(r.pipeline.diagnostics().distance_m)
}

/// Each recording with its distance, in the order given; an error naming the recording whose
/// distance is missing or not a positive number of metres, or a distance without a recording.
pub fn pair<'a>(files: &'a [PathBuf], metres: &[f64]) -> Result<Vec<(&'a Path, f64)>, String> {
    if files.is_empty() {
        return Err("give at least one recording, each followed by --metres DISTANCE".into());
    }
    let mut out = Vec::new();
    for (i, file) in files.iter().enumerate() {
        let name = file.display();
        let Some(&m) = metres.get(i) else {
            return Err(format!(
                "{name}: no distance: give its true length with --metres (one per recording, in order)"
            ));
        };
        if !(m.is_finite() && m > 0.0) {
            return Err(format!(
                "{name}: the distance must be a positive number of metres, not {m}"
            ));
        }
        out.push((file.as_path(), m));
    }
    if metres.len() > files.len() {
        return Err(format!(
            "{} distances for {} recordings: give one --metres per recording",
            metres.len(),
            files.len()
        ));
    }
    Ok(out)
}

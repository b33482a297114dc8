//! `pdr run`: replays one log of any format, prints a summary and writes the track files.
//! May import: the `pdr` library and `read`; nothing of the other subcommands.

use crate::read::read_one;
use pdr::engine::foot::placement::Placement;
use pdr::engine::{replay, Diagnostics, Pipeline, Replay, StepRecord};
use pdr::io::export;
use pdr::io::import::recipe::Recipe;
use pdr::io::import::Log;
use pdr::settings::Settings;
use std::path::Path;

pub fn run(
    file: &Path,
    outputs: Outputs,
    settings: &Settings,
    recipe: Option<&Recipe>,
) -> Result<(), String> {
    let cfg = settings.config().map_err(|e| e.to_string())?;
    let name = file.display().to_string();
    let parsed = read_one(file, &name, recipe)?;
    let shown = parsed.warnings.len().min(10);
    for e in &parsed.warnings[..shown] {
        eprintln!("warning: {e} (line skipped)");
    }
    if parsed.skipped > shown as u64 {
        eprintln!(
            "warning: {} more lines skipped",
            parsed.skipped - shown as u64
        );
    }
    let r = replay(parsed.dated(&cfg), &parsed.records).map_err(|e| e.to_string())?;
    for (i, e) in r.errors.iter().take(10) {
        eprintln!("warning: {name}: record {}: {e} (record skipped)", i + 1);
    }
    if r.refused > 10 {
        eprintln!("warning: {name}: {} more records refused", r.refused - 10);
    }
    let p = &r.pipeline;
    let d = p.diagnostics();
    print_walk(&name, &parsed, &r, &d);
    print_sensors(p, &d);
    print_fusion(p, &d);
    write_outputs(&outputs, &name, p)
}

/// The summary's first part: the log, the orientation source, the steps and their activities,
/// the distance, where the walk ended and how the phone was carried.
fn print_walk(name: &str, parsed: &Log, r: &Replay, d: &Diagnostics) {
    let p = &r.pipeline;
    let track = p.track();
    let (t0, t1) = d.time_span.unwrap_or((0.0, 0.0));
    out!("file          {name}");
    match &parsed.recipe {
        Some(r) => out!("format        {} ({r:?})", parsed.format.as_str()),
        None => out!("format        {}", parsed.format.as_str()),
    }
    out!(
        "records       {} ({} lines skipped, {} records refused)",
        parsed.records.len(),
        parsed.skipped,
        r.refused
    );
    match p.orientation_diagnostics() {
        Some(o) if o.switches > 0 => out!(
            "orientation   {:?} ({} moves of `auto`: a stream began late or stopped)",
            o.source,
            o.switches
        ),
        Some(o) => out!("orientation   {:?}", o.source),
        None => out!("orientation   none (no IMU sample)"),
    }
    out!("duration      {:.1} s", t1 - t0);
    if d.placement == Placement::Foot {
        out!("mode          foot (zero-velocity updates; a stride counts as two steps)");
        out!("strides       {} ({} steps)", d.strides, d.steps);
    } else {
        out!("steps         {}", track.len());
    }
    if d.detector_fallback {
        out!("detector      PLL: the pitch detector needs a gyroscope, which this log has not");
    }
    print_activities(track);
    out!("distance      {:.1} m", d.distance_m);
    if let Some(last) = track.last() {
        out!("final east    {:.1} m", last.east_m);
        out!("final north   {:.1} m", last.north_m);
        // The height and floor (Munoz Diaz 2015 §6, the barometer), once the engine has them.
        if d.vertical.is_some() || last.floor != 0 || last.up_m != 0.0 {
            out!(
                "final height  {:+.1} m, floor {:+} ({})",
                last.up_m,
                last.floor,
                d.vertical.map_or("source not given", |v| v.as_str())
            );
        }
    }
    if d.placement != Placement::Foot {
        if let Some(c) = pdr::analysis::carry_text(track) {
            out!("carried       {c}");
        }
    }
}

/// The activities of the steps (Munoz Diaz 2015 §4.3 where the leg pitch shows a thigh), in
/// the order they first occur, with how many steps showed a thigh's leg pitch.
fn print_activities(track: &[StepRecord]) {
    let mut acts: Vec<(pdr::engine::Activity, usize)> = Vec::new();
    for s in track {
        match acts.iter_mut().find(|a| a.0 == s.activity) {
            Some(a) => a.1 += 1,
            None => acts.push((s.activity, 1)),
        }
    }
    if acts.is_empty() {
        return;
    }
    let on_thigh = track
        .iter()
        .filter(|s| s.pitch_amplitude_deg.is_some())
        .count();
    let words: Vec<String> = acts
        .iter()
        .map(|(a, n)| format!("{n} {}", a.as_str()))
        .collect();
    out!(
        "activities    {} ({on_thigh} steps with a thigh's leg pitch)",
        words.join(", ")
    );
}

/// The summary's sensor lines: the magnetometer's disturbances, the gaps, the handling, the
/// steps without a heading and the GNSS origin.
fn print_sensors(p: &Pipeline, d: &Diagnostics) {
    let track = p.track();
    let m = p.magnetic_diagnostics();
    if let Some((size, dip)) = m.reference {
        let held = track.iter().filter(|s| s.gyro_heading).count();
        out!(
            "magnetometer  disturbed {:.0} % of {:.0} s (reference {size:.1} µT, dip {dip:.1}°): {held} steps followed the gyroscope",
            100.0 * m.disturbed_s / m.tested_s.max(1e-9),
            m.tested_s
        );
    }
    out!("gaps          {} ({:.1} s)", d.gaps, d.gap_time_s);
    if d.handling_s > 0.0 {
        out!(
            "handling      {:.1} s (the phone turned over in the hand: no steps)",
            d.handling_s
        );
    }
    if d.steps_without_heading > 0 {
        out!(
            "no heading    {} steps (orientation source gives no heading)",
            d.steps_without_heading
        );
    }
    if let Some(fr) = p.frame() {
        out!(
            "origin        {:.7}, {:.7} (first usable GNSS fix)",
            fr.lat0_deg,
            fr.lon0_deg
        );
    }
}

/// The summary's fusion lines, for a log with GNSS fixes: the fixes' fates, the learnt
/// corrections and the receiver's on time.
fn print_fusion(p: &Pipeline, d: &Diagnostics) {
    let fused = p.fused();
    let (Some(c), Some(last)) = (d.fix_counts, fused.last()) else {
        return;
    };
    out!(
        "fused         {} steps; fixes used {}, gated {}, too inaccurate {}, stale {}, receiver off {}, resets {}",
        fused.len(),
        c.used,
        c.gated,
        c.too_inaccurate,
        c.stale,
        c.receiver_off,
        c.resets
    );
    out!(
        "corrections   step length × {:.3}, heading {:+.1}° (declination {:+.2}°{})",
        last.scale,
        last.bias_rad.to_degrees(),
        d.declination_deg.unwrap_or(0.0),
        d.declination_note
            .map_or(String::new(), |n| format!("; {n}"))
    );
    if let Some((on, span)) = d.gnss_on_s {
        out!("gnss on       {on:.0} s of {span:.0} s");
    }
}

/// Writes the files asked for: the track (CSV), the track with the fusion's features (GeoJSON)
/// and the fused track (CSV, which needs a GNSS fix).
fn write_outputs(outputs: &Outputs, name: &str, p: &Pipeline) -> Result<(), String> {
    let track = p.track();
    let fused = p.fused();
    let smoothed = p.smoothed();
    if let Some(out) = outputs.track {
        std::fs::write(out, export::track_csv(track, p.frame()))
            .map_err(|e| format!("{}: {e}", out.display()))?;
        out!("track         {}", out.display());
    }
    if let Some(out) = outputs.geojson {
        let mut doc = export::track_geojson(track, p.frame());
        if let (Some(fr), Some(features)) = (p.frame(), doc["features"].as_array_mut()) {
            features.extend(export::fusion_features(p.fixes(), fused, &smoothed, fr));
        }
        let text = serde_json::to_string_pretty(&doc).map_err(|e| e.to_string())?;
        std::fs::write(out, text).map_err(|e| format!("{}: {e}", out.display()))?;
        out!("geojson       {}", out.display());
    }
    if let Some(out) = outputs.fused {
        let fr = p
            .frame()
            .ok_or_else(|| format!("{name}: no usable GNSS fix, so no fused track to write"))?;
        std::fs::write(out, export::fused_csv(fused, &smoothed, fr))
            .map_err(|e| format!("{}: {e}", out.display()))?;
        out!("fused track   {}", out.display());
    }
    Ok(())
}

/// Where `pdr run` writes its files.
pub struct Outputs<'a> {
    pub track: Option<&'a Path>,
    pub geojson: Option<&'a Path>,
    pub fused: Option<&'a Path>,
}

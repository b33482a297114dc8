//! `pdr simulate`: writes a simulated walk as a pdr-log, as an app's recording (with the mapping
//! from `--format` to the import's formats) or as the browser events a phone would fire.
//! May import: the `pdr` library and `cli::{FormatArg, PlatformArg}`; no other subcommand.

use crate::cli::{FootArg, FormatArg, PlatformArg};
use pdr::engine::Record;
use pdr::io::pdrlog;
use pdr::sim::Simulation;
use std::path::Path;

pub fn simulate(
    sc: pdr::sim::Scenario,
    out: Option<&Path>,
    format: FormatArg,
    events: Option<&Path>,
    platform: PlatformArg,
    foot: FootArg,
) -> Result<(), String> {
    let imu = pdr::sim::FootImu::default();
    let sim = match foot {
        FootArg::None => sc.generate(),
        FootArg::Only => sc.generate_foot(&imu).sim,
        FootArg::Two => sc.generate_two_sensor(&imu).0,
    };
    let write = |path: &Path, text: String| {
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    if let Some(out) = out {
        if format == FormatArg::PdrLog {
            write(out, pdrlog::to_string(&sim.records))?;
            out!(
                "wrote {} records, {} true steps, {:.1} m, to {}",
                sim.records.len(),
                sim.truth.steps.len(),
                sim.truth.distance_m,
                out.display()
            );
        } else {
            write_recording(&sim, out, format, platform)?;
        }
    }
    if let Some(path) = events {
        let platform = match platform {
            PlatformArg::Android => pdr::live::Platform::Android,
            PlatformArg::Ios => pdr::live::Platform::Ios,
        };
        let events = pdr::live::browser_events(&sim.records, platform);
        // The true path every half second or so, on the events' clock (ms), east and north (m).
        let mut truth_path: Vec<[f64; 3]> = Vec::new();
        for &(t, e, n) in &sim.truth.path {
            if truth_path.last().map_or(true, |p| t * 1e3 - p[0] >= 500.0) {
                truth_path.push([t * 1e3, e, n]);
            }
        }
        let doc = serde_json::json!({
            "truth_steps": sim.truth.steps.len(),
            "distance_m": sim.truth.distance_m,
            "platform": format!("{platform:?}").to_lowercase(),
            "path": truth_path,
            "events": events,
        });
        write(path, doc.to_string())?;
        out!(
            "wrote {} browser events to {}",
            events.len(),
            path.display()
        );
    }
    Ok(())
}

/// Writes a simulated walk as an app's recording: one file at `out`, or for a folder format the
/// recording's folder inside the directory `out` (created; refused when it exists and is not
/// empty).
fn write_recording(
    sim: &Simulation,
    out: &Path,
    format: FormatArg,
    platform: PlatformArg,
) -> Result<(), String> {
    use pdr::sim::formats;
    let platform = match (format, platform) {
        (FormatArg::SensorLoggerIos, _) | (_, PlatformArg::Ios) => pdr::io::import::Platform::Ios,
        _ => pdr::io::import::Platform::Android,
    };
    let f = format.format();
    let rec = formats::write(sim, f, platform);
    let shown = out.display();
    let written = if formats::is_folder(f) {
        match std::fs::read_dir(out) {
            Ok(mut entries) => {
                if entries.next().is_some() {
                    return Err(format!(
                        "{shown}: exists and is not empty; a folder format needs a new or empty \
                         directory"
                    ));
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(format!("{shown}: {e}")),
        }
        std::fs::create_dir_all(out).map_err(|e| format!("{shown}: {e}"))?;
        for (name, bytes) in &rec.files {
            let path = out.join(name);
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            }
            std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        let top = rec
            .files
            .first()
            .and_then(|(n, _)| n.split('/').next())
            .unwrap_or("");
        let mut written = format!("{} files in {}/", rec.files.len(), out.join(top).display());
        if f == pdr::io::import::Format::Recipe {
            // The plain CSV folder is read by a recipe: written beside the folder.
            let path = out.join("recipe.json");
            std::fs::write(&path, formats::PLAIN_CSV_RECIPE)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            written += &format!(" and its recipe {}", path.display());
        }
        written
    } else {
        let bytes = rec.files.first().map_or(&[][..], |f| f.1.as_slice());
        std::fs::write(out, bytes).map_err(|e| format!("{shown}: {e}"))?;
        shown.to_string()
    };
    let imu = sim
        .records
        .iter()
        .filter(|r| matches!(r, Record::Imu(_)))
        .count();
    let fixes = sim
        .records
        .iter()
        .filter(|r| matches!(r, Record::Gnss(_)))
        .count();
    let flavour = match f {
        pdr::io::import::Format::SensorLogger
        | pdr::io::import::Format::SensorLoggerJson
        | pdr::io::import::Format::Tyrex => {
            format!(" ({})", format!("{platform:?}").to_lowercase())
        }
        _ => String::new(),
    };
    let fixes = match f {
        pdr::io::import::Format::OxfordSteps
        | pdr::io::import::Format::MsIndoor
        | pdr::io::import::Format::XioFoot
        | pdr::io::import::Format::Recipe
        | pdr::io::import::Format::Tyrex
        | pdr::io::import::Format::Ubicomp13
        | pdr::io::import::Format::WeAllWalk
            if fixes > 0 =>
        {
            format!("no fixes (the format has none; the walk has {fixes})")
        }
        _ => format!("{fixes} fixes"),
    };
    out!(
        "wrote {}{flavour}: {imu} IMU samples, {fixes}, {} true steps, {:.1} m, to {written}",
        f.as_str(),
        sim.truth.steps.len(),
        sim.truth.distance_m,
    );
    Ok(())
}

impl FormatArg {
    fn format(self) -> pdr::io::import::Format {
        use pdr::io::import::Format;
        match self {
            FormatArg::PdrLog => Format::PdrLog,
            FormatArg::SensorLogger | FormatArg::SensorLoggerIos => Format::SensorLogger,
            FormatArg::SensorLoggerJson => Format::SensorLoggerJson,
            FormatArg::Phyphox => Format::Phyphox,
            FormatArg::GnssLogger => Format::GnssLogger,
            FormatArg::GetSensorData => Format::GetSensorData,
            FormatArg::Oxford => Format::OxfordSteps,
            FormatArg::MsIndoor => Format::MsIndoor,
            FormatArg::Xio => Format::XioFoot,
            FormatArg::Tyrex => Format::Tyrex,
            FormatArg::Ubicomp13 => Format::Ubicomp13,
            FormatArg::Weallwalk => Format::WeAllWalk,
            FormatArg::PlainCsv => Format::Recipe,
        }
    }
}

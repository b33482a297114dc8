//! The command line: clap's definitions of `pdr` and its subcommands, and `main`, which hands each
//! subcommand to its own module (`run`, `calibrate`, `eval` and `calibrate_loo`, `simulate`,
//! `simcheck`, `bench`, `demo`, `serve`).
//! May import: clap, the `pdr` library and the subcommands' modules.

use crate::settings_args::SettingsArgs;
use crate::{bench, calibrate, calibrate_loo, demo, eval, run, serve, simcheck, simulate};
use clap::{Parser, Subcommand, ValueEnum};
use pdr::sim::scenarios;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "pdr",
    version,
    about = "Pedestrian dead reckoning (Basso 2016/2021)"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Clone, Copy, ValueEnum)]
enum ScenarioArg {
    /// The demo walk of the web page.
    Demo,
    /// A closed 4 × 25 m square.
    Square,
    /// 70 s straight walk at 1.8 Hz.
    Straight,
    /// Eleven minutes through city blocks with GNSS (outliers, an outage), a step length 10 %
    /// off and an 8° heading bias: the fusion's test walk.
    GnssCity,
    /// The same city walk with a real phone's GNSS errors: a multipath bias
    /// correlated over 14 s, an optimistic accuracy, a 90 s urban canyon, a stale first fix
    /// 3 km away, fixes wandering while standing, the receiver holding at walk start.
    CityRealGnss,
    /// A calibration walk: `--metres` straight at `--cadence`, by a walker whose step length is
    /// `--sl-a`·f + `--sl-b`, between two 3 s pauses.
    Calibration,
    /// `--minutes` of walking, turning, pausing and running (the benchmarks' walk).
    Long,
    /// Once round a 400 m athletic track (Strozzi 2017 §5.1's outdoor path), for `--foot`.
    Track,
    /// Phone in the front pocket, with a barometer: three floors up and down stairs, with
    /// landings (Munoz Diaz 2015's walk).
    Stairs,
    /// Phone in the front pocket, with a barometer: standing, walking, sitting, two floors up
    /// and down.
    PocketMixed,
}

/// Which IMUs `pdr simulate` writes.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FootArg {
    /// The pocket phone only.
    None,
    /// Only an IMU on the walker's right foot (as x-io's foot-mounted walks).
    Only,
    /// The phone and the foot IMU (pdr-log `foot` records): a two-sensor walk.
    Two,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum PlatformArg {
    /// Chromium's conventions (specification sign, `interval` in ms).
    Android,
    /// Safari's (acceleration negated, `interval` in s).
    Ios,
}

#[derive(Clone, Copy, PartialEq, ValueEnum)]
pub enum FormatArg {
    /// The project's own log (one file).
    PdrLog,
    /// Sensor Logger's CSV folder, Android (or iOS with `--platform ios`).
    SensorLogger,
    /// Sensor Logger's CSV folder, iOS (g, Core Motion's signs and attitude).
    SensorLoggerIos,
    /// Sensor Logger's JSON export (one file; Android, or iOS with `--platform ios`).
    SensorLoggerJson,
    /// phyphox's CSV export (folder).
    Phyphox,
    /// Google GnssLogger `.txt`.
    GnssLogger,
    /// GetSensorData (IPIN) `.txt`, with `POSI` landmarks.
    GetSensorData,
    /// Oxford Step Counter trace folder, with the true foot contacts.
    Oxford,
    /// Microsoft Indoor Location 2.0 trace, with `TYPE_WAYPOINT` truth.
    MsIndoor,
    /// x-io Gait-Tracking CSV.
    Xio,
    /// TyrEx recording folder with its motion-capture `truth.csv`, Android (or iOS with
    /// `--platform ios`).
    Tyrex,
    /// UbiComp 2013 walk folder with its `truth.json` (step count and walk window).
    Ubicomp13,
    /// WeAllWalk walk folder (iOS Core Motion CSV) with its heel strikes and turns.
    Weallwalk,
    /// A folder of header-less CSVs `acc.csv`, `gyr.csv`, `mag.csv`, `bar.csv` (time in ms,
    /// then x y z), with the recipe that reads it (`recipe.json` beside the folder).
    PlainCsv,
}

#[derive(Subcommand)]
enum Cmd {
    /// Replay a recording: print a summary and write the per-step track.
    Run {
        /// The log: a pdr-log, or any format `pdr eval` reads (file, folder or zip).
        file: PathBuf,
        /// Write the per-step track as CSV.
        #[arg(long)]
        track: Option<PathBuf>,
        /// Write the track as GeoJSON (with the GNSS fixes, fused and smoothed tracks when
        /// there are fixes).
        #[arg(long)]
        geojson: Option<PathBuf>,
        /// Write the fused and smoothed tracks as CSV.
        #[arg(long)]
        fused: Option<PathBuf>,
        /// Read the log with a recipe (column mapping, JSON; see docs/recipes.md): the files it
        /// matches are read by it, whatever their format.
        #[arg(long)]
        recipe: Option<PathBuf>,
        #[command(flatten)]
        settings: SettingsArgs,
    },
    /// Fit your step-length profile (the calibration wizard's line; quick mode with one walk) to
    /// recordings of walks of known distance, and write it for `pdr run --profile` and the
    /// page's profile import: `pdr calibrate WALK --metres 85 [WALK2 --metres 60 …] --out FILE`.
    Calibrate {
        /// The recordings (anything `pdr run` reads: file, folder or zip), each followed by its
        /// `--metres`.
        #[arg(required = true, value_name = "RECORDING")]
        files: Vec<PathBuf>,
        /// The true distance walked in each recording, m, one per recording in their order.
        #[arg(long, value_name = "M", allow_negative_numbers = true)]
        metres: Vec<f64>,
        /// Where to write the profile file (JSON).
        #[arg(long)]
        out: PathBuf,
        /// The profile's name.
        #[arg(long, default_value = "me")]
        name: String,
        /// Read the recordings with a recipe (column mapping, JSON; see docs/recipes.md).
        #[arg(long)]
        recipe: Option<PathBuf>,
        #[command(flatten)]
        settings: SettingsArgs,
    },
    /// Run the embedded demo walk (the one the web page shows) and print its figures.
    Demo {
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Write a simulated walk as a log: a pdr-log, or any format the import reads, written as
    /// the app writes it.
    Simulate {
        /// Which walk.
        #[arg(long, value_enum, default_value = "demo")]
        scenario: ScenarioArg,
        /// The output file; for a folder format (sensor-logger, sensor-logger-ios, phyphox,
        /// oxford, plain-csv) a new or empty directory, which gets the recording's folder.
        #[arg(long, required_unless_present = "events")]
        out: Option<PathBuf>,
        /// The format of `--out`.
        #[arg(long, value_enum, default_value = "pdr-log")]
        format: FormatArg,
        /// Also (or instead) write the walk as the browser events a phone would fire, JSON:
        /// `{truth_steps, distance_m, path: [[t, east, north], …], events: [{type:
        /// "motion"|"orientation", t, …}]}` (t in ms, the path in metres). The end-to-end tests
        /// dispatch these on the live page.
        #[arg(long)]
        events: Option<PathBuf>,
        /// The platform whose event conventions `--events` follows, and whose conventions the
        /// Sensor Logger formats and TyrEx follow.
        #[arg(long, value_enum, default_value = "android")]
        platform: PlatformArg,
        /// Calibration walk: step frequency, Hz.
        #[arg(long, default_value_t = 1.8)]
        cadence: f64,
        /// Calibration walk: distance, m.
        #[arg(long, default_value_t = 40.0)]
        metres: f64,
        /// Calibration walk: the walker's step-length slope, m/Hz.
        #[arg(long, default_value_t = 0.25)]
        sl_a: f64,
        /// Calibration walk: the walker's step-length offset, m.
        #[arg(long, default_value_t = 0.17)]
        sl_b: f64,
        /// Long walk: its duration, minutes.
        #[arg(long, default_value_t = 60.0)]
        minutes: f64,
        /// A foot-mounted IMU on the same walker (`sim::foot`, 400 Hz).
        #[arg(long, value_enum, default_value = "none")]
        foot: FootArg,
    },
    /// Accuracy of every method on simulated walks with known truth.
    Simcheck,
    /// Full-pipeline throughput in IMU samples per second on a long simulated walk.
    Bench {
        /// Minutes of simulated walking.
        #[arg(long, default_value_t = 30.0)]
        minutes: f64,
        /// Replays per configuration (the best is reported).
        #[arg(long, default_value_t = 5)]
        repeats: usize,
    },
    /// Run the engine on every recognisable log under the paths and score it against the truth
    /// the logs carry (steps, waypoints, loop closure).
    Eval {
        /// Files, folders or zip archives.
        #[arg(required_unless_present = "show_config")]
        paths: Vec<PathBuf>,
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        settings: SettingsArgs,
        /// Print the effective configuration as JSON and exit.
        #[arg(long)]
        show_config: bool,
        /// Read the logs with a recipe (column mapping, JSON): each folder it matches is one
        /// log read by it; other files are read as usual.
        #[arg(long, conflicts_with = "compare")]
        recipe: Option<PathBuf>,
        /// Instead of one configuration, run every step detector, heading method, orientation
        /// source and step-length model (each alone over the defaults) on each path as a data
        /// set, and print the comparison table (Markdown, or JSON with `--json`).
        #[arg(long, conflicts_with = "show_config")]
        compare: bool,
        /// Run every log twice, in best performance and in energy saving (the receiver on
        /// `fusion.mode.window_s` every `fusion.mode.period_s`, 10 s every 60 s unless set), with
        /// the other settings as given, and print the median fused and smoothed p75 per group of
        /// logs (IPIN routes by their tens digit), their ratio and the receiver's on time
        /// (Markdown, or JSON with `--json`).
        #[arg(long, conflicts_with_all = ["show_config", "compare"])]
        energy: bool,
        /// Leave one walk out: for each walker (the folder name's first part, TyrEx's naming),
        /// calibrate on each walking walk alone (its truth's path length as the distance) and run
        /// the walker's other walking walks with that profile; print the median distance ratios,
        /// uncalibrated and calibrated, per carrying mode and overall (Markdown, or JSON with
        /// `--json`).
        #[arg(long, conflicts_with_all = ["show_config", "compare", "energy"])]
        calibrate_loo: bool,
    },
    /// Serve the built web app: HTTP on localhost and HTTPS (self-signed) on all interfaces.
    Serve {
        /// Folder holding the built static site.
        #[arg(long, default_value = "dist")]
        root: PathBuf,
        /// HTTP port (localhost only).
        #[arg(long, default_value_t = 8080)]
        http_port: u16,
        /// HTTPS port (all interfaces).
        #[arg(long, default_value_t = 8443)]
        https_port: u16,
        /// Where to keep the self-signed certificate (default: the user's data directory).
        #[arg(long)]
        cert_dir: Option<PathBuf>,
    },
}

pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.cmd {
        Cmd::Run {
            file,
            track,
            geojson,
            fused,
            recipe,
            settings,
        } => settings.settings().and_then(|s| {
            let recipe = load_recipe(recipe.as_deref())?;
            run::run(
                &file,
                run::Outputs {
                    track: track.as_deref(),
                    geojson: geojson.as_deref(),
                    fused: fused.as_deref(),
                },
                &s,
                recipe.as_ref(),
            )
        }),
        Cmd::Calibrate {
            files,
            metres,
            out,
            name,
            recipe,
            settings,
        } => settings.settings().and_then(|s| {
            let recipe = load_recipe(recipe.as_deref())?;
            let req = calibrate::Request {
                files: &files,
                metres: &metres,
                out: &out,
                name: &name,
                recipe: recipe.as_ref(),
            };
            calibrate::calibrate(&req, &s)
        }),
        Cmd::Demo { json } => demo::demo(json),
        Cmd::Simulate {
            scenario,
            out,
            format,
            events,
            platform,
            cadence,
            metres,
            sl_a,
            sl_b,
            minutes,
            foot,
        } => simulate::simulate(
            scenario.scenario(cadence, metres, sl_a, sl_b, minutes),
            out.as_deref(),
            format,
            events.as_deref(),
            platform,
            foot,
        ),
        Cmd::Simcheck => {
            simcheck::simcheck();
            Ok(())
        }
        Cmd::Bench { minutes, repeats } => {
            bench::bench(minutes, repeats);
            Ok(())
        }
        Cmd::Eval {
            compare: true,
            paths,
            json,
            ..
        } => eval::compare(&paths, json),
        Cmd::Eval {
            paths,
            json,
            settings,
            show_config,
            recipe,
            energy,
            calibrate_loo,
            ..
        } => settings.settings().and_then(|s| {
            let recipe = load_recipe(recipe.as_deref())?;
            if calibrate_loo {
                calibrate_loo::calibrate_loo(&paths, json, &s, recipe.as_ref())
            } else if energy {
                eval::energy(&paths, json, &s, recipe.as_ref())
            } else {
                eval::eval(&paths, json, &s, show_config, recipe.as_ref())
            }
        }),
        Cmd::Serve {
            root,
            http_port,
            https_port,
            cert_dir,
        } => serve::serve(serve::ServeOpts {
            root,
            http_port,
            https_port,
            cert_dir,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("pdr: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The recipe of `--recipe`, read, when given.
fn load_recipe(path: Option<&Path>) -> Result<Option<pdr::io::import::recipe::Recipe>, String> {
    path.map(pdr::io::import::recipe::load)
        .transpose()
        .map_err(String::from)
}

impl ScenarioArg {
    /// The walk, with the calibration walk's cadence (Hz), distance (m) and walker's step
    /// length (m/Hz and m), and the long walk's duration (minutes).
    fn scenario(
        self,
        cadence: f64,
        metres: f64,
        sl_a: f64,
        sl_b: f64,
        minutes: f64,
    ) -> pdr::sim::Scenario {
        match self {
            ScenarioArg::Demo => scenarios::demo_walk(),
            ScenarioArg::Square => scenarios::square(25.0),
            ScenarioArg::Straight => scenarios::straight_walk(1.8, 70.0),
            ScenarioArg::GnssCity => scenarios::gnss_city_walk(),
            ScenarioArg::CityRealGnss => scenarios::gnss_city_walk_real(),
            ScenarioArg::Calibration => scenarios::calibration_walk(cadence, metres, sl_a, sl_b),
            ScenarioArg::Long => scenarios::long_walk(minutes),
            ScenarioArg::Track => scenarios::athletic_track(1),
            ScenarioArg::Stairs => scenarios::stairs_walk(pdr::sim::PocketPose::default()),
            ScenarioArg::PocketMixed => scenarios::pocket_mixed(pdr::sim::PocketPose::default()),
        }
    }
}

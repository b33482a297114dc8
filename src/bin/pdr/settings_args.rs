//! The settings every engine run of the CLI takes (`pdr run`, `pdr eval`): the choices of
//! `pdr::settings::CHOICES` as flags by the configuration's own names, any value by its path
//! (`--set`), and a step-length profile file. Through `pdr::settings`, as the page does.
//! May import: clap and the `pdr` library.

use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};
use pdr::settings::{Settings, CHOICES};
use std::path::PathBuf;

/// The settings of one run, as given on the command line.
#[derive(Debug, Clone, Default)]
pub struct SettingsArgs {
    /// (dotted path, value) of each choice given by its flag.
    choices: Vec<(&'static str, String)>,
    /// `--set KEY=VALUE`, in order.
    sets: Vec<String>,
    /// `--profile FILE`.
    profile: Option<PathBuf>,
}

impl SettingsArgs {
    /// The settings: the `--set` values, then the flags, then the profile.
    pub fn settings(&self) -> Result<Settings, String> {
        let mut s = Settings::new()
            .with_args(&self.sets)
            .map_err(|e| format!("--set {e}"))?;
        for (key, value) in &self.choices {
            s = s.with(key, value.as_str());
        }
        if let Some(path) = &self.profile {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            s.profile = Some(text);
        }
        Ok(s)
    }
}

impl Args for SettingsArgs {
    fn augment_args(mut cmd: Command) -> Command {
        for c in CHOICES {
            let values = c
                .options
                .iter()
                .map(|(v, label)| PossibleValue::new(*v).help(*label));
            cmd = cmd.arg(
                Arg::new(c.key)
                    .long(c.flag)
                    .value_name("NAME")
                    .help(format!("{} (`{}`)", c.title, c.key))
                    .value_parser(PossibleValuesParser::new(values)),
            );
        }
        cmd.arg(
            Arg::new("set")
                .long("set")
                .value_name("KEY=VALUE")
                .action(clap::ArgAction::Append)
                .help(
                    "Set any configuration value by its path, e.g. `motion.still_max=1.2`, \
                     `detector.kind=peak` (repeatable; `pdr eval --show-config` lists them)",
                ),
        )
        .arg(
            Arg::new("profile")
                .long("profile")
                .value_name("FILE")
                .value_parser(clap::value_parser!(PathBuf))
                .help("A step-length profile file (the calibration wizard's export)"),
        )
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for SettingsArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut s = SettingsArgs::default();
        s.update_from_arg_matches(m)?;
        Ok(s)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        self.choices = CHOICES
            .iter()
            .filter_map(|c| m.get_one::<String>(c.key).map(|v| (c.key, v.clone())))
            .collect();
        self.sets = m
            .get_many::<String>("set")
            .map_or_else(Vec::new, |v| v.cloned().collect());
        self.profile = m.get_one::<PathBuf>("profile").cloned();
        Ok(())
    }
}

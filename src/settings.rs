//! The one front door for settings: the engine's configuration ([`PipelineConfig`]), with one
//! spelling per choice, built the same way by the CLI, the page and the evaluation bench.
//! May import: `engine`.
//!
//! A [`Settings`] is what a person chooses: values by their dotted path into the configuration
//! over its defaults (`heading.method = closed_form2021`, `fusion.mode.kind = energy_saving`;
//! `pdr eval --show-config` lists every path), and a step-length profile from the calibration
//! wizard. [`Settings::config`] turns it into a validated configuration, or an error that names
//! the setting. The choices the page and the CLI offer by name, with the words shown for them,
//! are [`CHOICES`]; their values are the configuration's own names, so that a `--set` path, a
//! CLI flag and a select on the page say the same thing the same way.

use crate::engine::calibration::ProfileFile;
use crate::engine::step_length::StepLengthModel;
use crate::engine::types::ConfigError;
use crate::engine::PipelineConfig;
use serde_json::Value;
use std::collections::BTreeMap;
use std::fmt;

/// What a person chooses: values by dotted path over the defaults, and a step-length profile.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// Values by dotted path into the configuration's JSON form, e.g. `detector.kind` →
    /// `"peak"`, `motion.still_max` → `1.2`. Setting a `kind` chooses that variant with its
    /// defaults; its own values can be set beside it (kinds are applied first, outer paths
    /// before inner ones).
    pub set: BTreeMap<String, Value>,
    /// A step-length profile file (the calibration wizard's JSON): the line in frequency the
    /// step lengths follow. Refused with a step-length model that has no line.
    pub profile: Option<String>,
}

/// Why settings cannot make a configuration. Each names what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingsError {
    /// A `KEY=VALUE` argument without `=`.
    Syntax {
        /// The argument.
        arg: String,
    },
    /// No setting at this path.
    UnknownKey {
        /// The whole path.
        key: String,
        /// The part of it that names nothing.
        part: String,
    },
    /// The path goes through a value, not a group of settings.
    NotAGroup {
        /// The whole path.
        key: String,
        /// The part that is a value.
        group: String,
    },
    /// The value does not fit the setting (unknown variant, wrong type).
    BadValue {
        /// The path.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// The profile file is unreadable or invalid.
    Profile(ConfigError),
    /// A profile was given, but the step-length model has no line in frequency (nor, for the
    /// fuzzy model, the profile a fuzzy scale).
    ProfileWithoutLine,
    /// A value fails validation.
    Invalid(ConfigError),
}

impl fmt::Display for SettingsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SettingsError::Syntax { arg } => write!(f, "`{arg}`: expected KEY=VALUE"),
            SettingsError::UnknownKey { key, part } => write!(
                f,
                "`{key}`: no setting `{part}` (see `pdr eval --show-config`)"
            ),
            SettingsError::NotAGroup { key, group } => {
                write!(f, "`{key}`: `{group}` is not a group of settings")
            }
            SettingsError::BadValue { key, message } => write!(f, "`{key}`: {message}"),
            SettingsError::Profile(e) => write!(f, "step-length profile: {e}"),
            SettingsError::ProfileWithoutLine => write!(
                f,
                "a step-length profile is a line in frequency (and, when a fuzzy calibration \
                 walk made it, a fuzzy scale): choose `step_length.kind` `frequency`, or \
                 `fuzzy` with a profile that has `fuzzy_scale`"
            ),
            SettingsError::Invalid(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SettingsError {}

impl Settings {
    /// The defaults.
    pub fn new() -> Self {
        Settings::default()
    }

    /// These settings with `key` set to `value`.
    pub fn with(mut self, key: &str, value: impl Into<Value>) -> Self {
        self.set.insert(key.to_string(), value.into());
        self
    }

    /// These settings with `KEY=VALUE` arguments added in order (a later one wins): the value
    /// is JSON (`0.5`, `true`, `{"kind":"peak"}`), or else a string (`closed_form2021`).
    pub fn with_args(mut self, args: &[String]) -> Result<Self, SettingsError> {
        for a in args {
            let (key, value) = a
                .split_once('=')
                .ok_or_else(|| SettingsError::Syntax { arg: a.clone() })?;
            let value =
                serde_json::from_str(value).unwrap_or_else(|_| Value::String(value.to_string()));
            self.set.insert(key.to_string(), value);
        }
        Ok(self)
    }

    /// The validated configuration.
    pub fn config(&self) -> Result<PipelineConfig, SettingsError> {
        let mut cfg = PipelineConfig::default();
        let mut keys: Vec<&String> = self.set.keys().collect();
        // Kinds first and outer paths before inner ones: setting a kind resets its group.
        crate::engine::sort::sort_by_key(&mut keys, |k| {
            (k.split('.').count(), !k.ends_with("kind"), k.as_str())
        });
        for key in keys {
            cfg = set(&cfg, key, &self.set[key])?;
        }
        if let Some(text) = &self.profile {
            let file = ProfileFile::from_json(text).map_err(SettingsError::Profile)?;
            match &mut cfg.step_length {
                StepLengthModel::Frequency(p) => *p = file.profile,
                // The profile's line is the pitch model's line for steps without a pitch.
                StepLengthModel::Pitch(p) => {
                    p.fallback = file.profile;
                    if let Some(b) = file.pitch_offset_m {
                        p.b = b;
                    }
                }
                StepLengthModel::Fuzzy(c) => match file.fuzzy_scale {
                    Some(k) => c.scale = k,
                    None => return Err(SettingsError::ProfileWithoutLine),
                },
                _ => return Err(SettingsError::ProfileWithoutLine),
            }
        }
        cfg.validate().map_err(SettingsError::Invalid)?;
        Ok(cfg)
    }

    /// How the configuration is described to people, one part per choice: "PLL (Basso 2016),
    /// tip-to-tail (2016), built-in step-length line, GNSS: every fix".
    pub fn label(&self) -> Result<String, SettingsError> {
        let cfg = self.config()?;
        let v = serde_json::to_value(&cfg).map_err(|e| SettingsError::BadValue {
            key: String::new(),
            message: e.to_string(),
        })?;
        let shown = |key: &str| {
            let value = key
                .split('.')
                .try_fold(&v, |node, part| node.get(part))
                .and_then(Value::as_str)
                .ok_or_else(|| SettingsError::BadValue {
                    key: key.to_string(),
                    message: "the configuration has no such choice to describe".into(),
                })?;
            Ok::<_, SettingsError>(
                choice(key)
                    .and_then(|c| c.label_of(value))
                    .unwrap_or(value)
                    .to_string(),
            )
        };
        let length = match &cfg.step_length {
            StepLengthModel::Weinberg { k } => format!("Weinberg step length (K = {k})"),
            StepLengthModel::Fuzzy(c) => format!("fuzzy step length (scale {:.3})", c.scale),
            StepLengthModel::Pitch(p) => {
                format!("leg-pitch step length (a = {} m/°, b = {:.3} m)", p.a, p.b)
            }
            StepLengthModel::Frequency(_) => match &self.profile {
                Some(text) => {
                    let file = ProfileFile::from_json(text).map_err(SettingsError::Profile)?;
                    format!("profile {}", file.name)
                }
                None => "built-in step-length line".to_string(),
            },
        };
        Ok(format!(
            "{}, {}, {length}, GNSS: {}",
            shown("detector.kind")?,
            shown("heading.method")?,
            shown("fusion.mode.kind")?
        ))
    }
}

/// `cfg` with the setting at dotted path `key` set to `value`. Setting a `kind` replaces the
/// enclosing group by that variant with its defaults.
fn set(cfg: &PipelineConfig, key: &str, value: &Value) -> Result<PipelineConfig, SettingsError> {
    let bad = |message: String| SettingsError::BadValue {
        key: key.to_string(),
        message,
    };
    let mut v = serde_json::to_value(cfg).map_err(|e| bad(e.to_string()))?;
    let path: Vec<&str> = key.split('.').collect();
    let Some((last, parents)) = path.split_last() else {
        return Err(bad("an empty path".into()));
    };
    let mut node = &mut v;
    for p in parents {
        node = node.get_mut(*p).ok_or_else(|| SettingsError::UnknownKey {
            key: key.to_string(),
            part: p.to_string(),
        })?;
    }
    let obj = node
        .as_object_mut()
        .ok_or_else(|| SettingsError::NotAGroup {
            key: key.to_string(),
            group: parents.join("."),
        })?;
    let kind = *last == "kind";
    if kind {
        obj.clear();
    } else if !obj.contains_key(*last) {
        return Err(SettingsError::UnknownKey {
            key: key.to_string(),
            part: last.to_string(),
        });
    }
    obj.insert(last.to_string(), value.clone());
    serde_json::from_value(v).map_err(|e| bad(e.to_string()))
}

/// One choice the page and the CLI offer by name.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Choice {
    /// The dotted path it sets.
    pub key: &'static str,
    /// What it is, for people.
    pub title: &'static str,
    /// The CLI flag that sets it (`--detector peak`).
    pub flag: &'static str,
    /// Its values, the configuration's own names, each with the words shown for it.
    pub options: &'static [(&'static str, &'static str)],
}

impl Choice {
    /// The words shown for a value.
    pub fn label_of(&self, value: &str) -> Option<&'static str> {
        self.options
            .iter()
            .find(|(v, _)| *v == value)
            .map(|(_, l)| *l)
    }

    /// The values.
    pub fn values(&self) -> impl Iterator<Item = &'static str> {
        self.options.iter().map(|(v, _)| *v)
    }
}

/// The choices offered by name (the page's selects, the CLI's flags), each with the
/// configuration's default first. Every other setting is reached by its path (`--set`).
pub const CHOICES: &[Choice] = &[
    Choice {
        key: "detector.kind",
        title: "Step detector",
        flag: "detector",
        options: &[
            ("pll", "PLL (Basso 2016)"),
            ("peak", "peak counter"),
            ("zero_crossing", "zero crossing + area (Ibarra 2015)"),
            ("pitch", "leg pitch (Munoz Diaz 2015)"),
        ],
    },
    Choice {
        key: "heading.method",
        title: "Heading method",
        flag: "heading",
        options: &[
            ("tip_to_tail2016", "tip-to-tail (2016)"),
            ("closed_form2021", "closed form (2021)"),
            ("pca", "PCA"),
        ],
    },
    Choice {
        key: "step_length.kind",
        title: "Step-length model",
        flag: "step-length",
        options: &[
            ("frequency", "line in frequency (2016)"),
            ("weinberg", "Weinberg"),
            ("fuzzy", "fuzzy (Ibarra 2015)"),
            ("pitch", "leg pitch (Munoz Diaz 2015)"),
        ],
    },
    Choice {
        key: "orientation.kind",
        title: "Orientation source",
        flag: "orientation",
        options: &[
            (
                "auto",
                "per sample: OS quaternion, else Madgwick, else gravity",
            ),
            ("os", "OS quaternion"),
            ("madgwick", "Madgwick filter"),
            ("kf_nfa", "KF-NFA (Ibarra 2015)"),
            ("gravity_low_pass", "gravity low-pass (no heading)"),
        ],
    },
    Choice {
        key: "fusion.mode.kind",
        title: "GNSS fusion",
        flag: "gnss",
        options: &[
            ("best_performance", "every fix"),
            ("energy_saving", "energy saving"),
            ("off", "off"),
        ],
    },
    Choice {
        key: "placement",
        title: "Sensor placement",
        flag: "placement",
        options: &[
            ("auto", "recognised from the signal"),
            ("body", "on the body (steps)"),
            ("foot", "on the foot (strides, ZUPT)"),
        ],
    },
    Choice {
        key: "hybrid.method",
        title: "Stride heading with a foot sensor",
        flag: "hybrid",
        options: &[
            ("mid_swing", "trunk at mid-swing (Strozzi 2017)"),
            ("fir_crossing", "trunk at the FIR crossing (Strozzi 2017)"),
            ("foot", "the foot's own"),
        ],
    },
];

/// The choice that sets `key`.
pub fn choice(key: &str) -> Option<&'static Choice> {
    CHOICES.iter().find(|c| c.key == key)
}

/// Upload mode's second configuration when the page opens: the comparison Basso 2016 argues
/// against (a peak counter) with Basso 2021's closed-form heading.
pub fn compare_preset() -> Settings {
    Settings::new()
        .with("detector.kind", "peak")
        .with("heading.method", "closed_form2021")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::StepDetectorConfig;

    fn with_args(args: &[&str]) -> Result<PipelineConfig, SettingsError> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        Settings::new().with_args(&args)?.config()
    }

    #[test]
    fn settings_name_bad_keys_and_switch_variants() {
        let c = with_args(&["heading.method=closed_form2021"]).unwrap();
        assert_eq!(
            c.heading.method,
            crate::engine::heading::HeadingMethod::ClosedForm2021
        );
        let c = with_args(&["detector.kind=peak"]).unwrap();
        assert!(matches!(c.detector, StepDetectorConfig::Peak(_)));
        // A new kind's own settings can be set beside it, in either order.
        for args in [
            ["detector.kind=peak", "detector.min_interval_s=0.3"],
            ["detector.min_interval_s=0.3", "detector.kind=peak"],
        ] {
            let c = with_args(&args).unwrap();
            let StepDetectorConfig::Peak(p) = c.detector else {
                panic!("not the peak detector: {:?}", c.detector)
            };
            assert_eq!(p.min_interval_s, 0.3);
        }
        // A kind whose setting has no default of its own in the base config (Weinberg's K).
        let c = with_args(&["step_length.kind=weinberg"]).unwrap();
        assert_eq!(
            c.step_length,
            StepLengthModel::Weinberg {
                k: crate::engine::step_length::WEINBERG_K
            }
        );
        let e = with_args(&["motion.nope=1"]).unwrap_err().to_string();
        assert!(e.contains("nope"), "{e}");
        let e = with_args(&["motion.still_max=-1"]).unwrap_err().to_string();
        assert!(e.contains("still_max"), "{e}");
        // An unknown value names its setting.
        let e = with_args(&["heading.method=sideways"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("heading.method") && e.contains("sideways"),
            "{e}"
        );
        let e = with_args(&["detector"]).unwrap_err();
        assert!(matches!(e, SettingsError::Syntax { .. }), "{e}");
    }

    #[test]
    fn every_choice_is_the_configurations_own_name() {
        for c in CHOICES {
            for value in c.values() {
                let cfg = Settings::new().with(c.key, value).config().unwrap();
                let v = serde_json::to_value(&cfg).unwrap();
                let got = c.key.split('.').try_fold(&v, |n, p| n.get(p)).unwrap();
                assert_eq!(got, value, "{}", c.key);
            }
        }
        // And each default comes first (the page's selects start on it).
        let v = serde_json::to_value(PipelineConfig::default()).unwrap();
        for c in CHOICES {
            let got = c.key.split('.').try_fold(&v, |n, p| n.get(p)).unwrap();
            assert_eq!(got, c.options[0].0, "{}", c.key);
        }
    }

    #[test]
    fn energy_saving_window_and_period_are_checked() {
        let s = Settings::new()
            .with("fusion.mode.kind", "energy_saving")
            .with("fusion.mode.window_s", 70.0);
        let e = s.config().unwrap_err().to_string();
        assert!(e.contains("window_s"), "{e}");
        let c = s.with("fusion.mode.window_s", 5.0).config().unwrap();
        assert_eq!(
            c.fusion.mode,
            crate::engine::fusion::GnssMode::EnergySaving {
                period_s: 60.0,
                window_s: 5.0
            }
        );
    }

    #[test]
    fn labels_name_each_choice() {
        assert_eq!(
            Settings::new().label().unwrap(),
            "PLL (Basso 2016), tip-to-tail (2016), built-in step-length line, GNSS: every fix"
        );
        assert_eq!(
            compare_preset()
                .with("step_length.kind", "weinberg")
                .label()
                .unwrap(),
            "peak counter, closed form (2021), Weinberg step length (K = 0.47), GNSS: every fix"
        );
        let profile = crate::engine::calibration::ProfileFile {
            version: crate::engine::calibration::PROFILE_VERSION,
            name: "me".into(),
            profile: Default::default(),
            walking_points: vec![],
            running_points: vec![],
            fuzzy_scale: None,
            pitch_offset_m: None,
        };
        let s = Settings {
            profile: Some(profile.to_json().unwrap()),
            ..Settings::new()
        };
        assert!(s.label().unwrap().contains("profile me"));
        let e = s.with("step_length.kind", "weinberg").config().unwrap_err();
        assert_eq!(e, SettingsError::ProfileWithoutLine);
    }
}

//! The calibration wizard's class and the profile files' functions.
//! May import: `engine`, `plot`.

use super::canvas::on_canvas;
use super::{to_js, to_value};
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// A profile file's JSON, read and checked (the error names the field).
pub(super) fn read_profile(text: &str) -> Result<crate::engine::calibration::ProfileFile, JsError> {
    crate::engine::calibration::ProfileFile::from_json(text).map_err(to_js)
}

/// The calibration wizard's engine side: the walks, the fits, the profile and its chart.
#[wasm_bindgen]
pub struct CalibrationWizard {
    wizard: crate::engine::calibration::Wizard,
}

fn band(name: &str) -> Result<crate::engine::calibration::Band, JsError> {
    match name {
        "walking" => Ok(crate::engine::calibration::Band::Walking),
        "running" => Ok(crate::engine::calibration::Band::Running),
        other => Err(to_js(format!("unknown band `{other}`"))),
    }
}

#[wasm_bindgen]
impl CalibrationWizard {
    /// No walks yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> CalibrationWizard {
        CalibrationWizard {
            wizard: Default::default(),
        }
    }

    /// Adds a walk of `distance_m` whose steps had the frequencies `step_freqs_hz` and, when
    /// given (`Live.fuzzy_lengths()`), the unscaled fuzzy lengths `fuzzy_lengths_m`; returns its
    /// `{band, pace, distance_m, steps, f_mean_hz, sl_mean_m, fuzzy_sum_m, text}` (`text`: the
    /// walk's figures for people, eq. 1 and 2).
    pub fn add_walk(
        &mut self,
        band_name: &str,
        pace: &str,
        distance_m: f64,
        step_freqs_hz: Vec<f64>,
        fuzzy_lengths_m: Option<Vec<f64>>,
    ) -> Result<JsValue, JsError> {
        let walk = crate::engine::calibration::CalibrationWalk {
            distance_m,
            step_freqs_hz,
            fuzzy_lengths_m: fuzzy_lengths_m.unwrap_or_default(),
        };
        let w = self
            .wizard
            .add(band(band_name)?, pace, &walk)
            .map_err(to_js)?;
        #[derive(serde::Serialize)]
        struct Added<'a> {
            #[serde(flatten)]
            walk: &'a crate::engine::calibration::WizardWalk,
            text: String,
        }
        let fuzzy = w
            .fuzzy_sum_m
            .map_or(String::new(), |f| format!(" · fuzzy Σ = {f:.1} m at k = 1"));
        let text = format!(
            "N = {} steps over {:.1} m · f̄ = {:.2} Hz (eq. 1) · SL̄ = D/N = {:.3} m (eq. 2) → one point of your {band_name} line{fuzzy}",
            w.steps, w.distance_m, w.f_mean_hz, w.sl_mean_m
        );
        super::to_json_value(&Added { walk: w, text })
    }

    /// Removes walk `index` (an outlier the user drops).
    pub fn remove_walk(&mut self, index: usize) {
        if index < self.wizard.walks.len() {
            self.wizard.walks.remove(index);
        }
    }

    /// The walks, each band's fit with its warnings (explained, with the walk index of an
    /// outlier), the fuzzy scale when walks measured it, and the profile's notes:
    /// `{walks, walking, running, fuzzy_scale, notes}`.
    pub fn state(&self) -> Result<JsValue, JsError> {
        use crate::engine::calibration::{fit_band, Band, FitWarning};
        #[derive(serde::Serialize)]
        struct Warning {
            kind: &'static str,
            message: String,
            walk: Option<usize>,
        }
        #[derive(serde::Serialize)]
        struct Fit {
            points: usize,
            a: Option<f64>,
            b: Option<f64>,
            r2: Option<f64>,
            se: Option<(f64, f64)>,
            warnings: Vec<Warning>,
        }
        let fit = |b: Band| {
            // Indices of this band's walks among all walks, to name an outlier's walk.
            let idx: Vec<usize> = (0..self.wizard.walks.len())
                .filter(|&i| self.wizard.walks[i].band == b)
                .collect();
            let f = fit_band(&self.wizard.points(b));
            Fit {
                points: f.points.len(),
                a: f.fit.as_ref().map(|x| x.a),
                b: f.fit.as_ref().map(|x| x.b),
                r2: f.fit.as_ref().map(|x| x.r2),
                se: f.se,
                warnings: f
                    .warnings
                    .iter()
                    .map(|w| Warning {
                        kind: match w {
                            FitWarning::TooFewPoints { .. } => "too_few_points",
                            FitWarning::NarrowSpan { .. } => "narrow_span",
                            FitWarning::NegativeSlope { .. } => "negative_slope",
                            FitWarning::Outlier { .. } => "outlier",
                        },
                        message: w.message(),
                        walk: match w {
                            FitWarning::Outlier { index, .. } => idx.get(*index).copied(),
                            _ => None,
                        },
                    })
                    .collect(),
            }
        };
        #[derive(serde::Serialize)]
        struct State<'a> {
            walks: &'a [crate::engine::calibration::WizardWalk],
            walking: Fit,
            running: Fit,
            fuzzy_scale: Option<f64>,
            notes: Vec<String>,
        }
        let (_, notes) = self.wizard.profile(&Default::default());
        to_value(&State {
            walks: &self.wizard.walks,
            walking: fit(Band::Walking),
            running: fit(Band::Running),
            fuzzy_scale: self.wizard.fuzzy_scale(),
            notes,
        })
    }

    /// The profile file (JSON) the walks make, named `name`.
    pub fn profile_json(&self, name: &str) -> Result<String, JsError> {
        use crate::engine::calibration::{Band, ProfileFile, PROFILE_VERSION};
        let (profile, _) = self.wizard.profile(&Default::default());
        ProfileFile {
            version: PROFILE_VERSION,
            name: name.to_string(),
            profile,
            walking_points: self.wizard.points(Band::Walking),
            running_points: self.wizard.points(Band::Running),
            fuzzy_scale: self.wizard.fuzzy_scale(),
            pitch_offset_m: None,
        }
        .to_json()
        .map_err(to_js)
    }

    /// Draws a band's points, line and residuals.
    pub fn draw(
        &self,
        canvas: &HtmlCanvasElement,
        dark: bool,
        dpr: f64,
        band_name: &str,
    ) -> Result<(), JsError> {
        let b = band(band_name)?;
        let (profile, _) = self.wizard.profile(&Default::default());
        let line = match b {
            crate::engine::calibration::Band::Walking => profile.walking,
            crate::engine::calibration::Band::Running => profile.running,
        };
        let fit = crate::engine::calibration::fit_band(&self.wizard.points(b));
        on_canvas(canvas, dark, dpr, |area, theme, scale| {
            crate::plot::draw_calibration(area, &fit, &line, band_name, theme, scale)
        })
    }
}

impl Default for CalibrationWizard {
    fn default() -> Self {
        Self::new()
    }
}

/// Reads a profile file (JSON), or the built-in lines for `undefined`: `{name, walking: [a, b],
/// running: [a, b], walking_points, running_points, fuzzy_scale, text}` (`text` describes the
/// lines for people; `fuzzy_scale` is `null` without one), or an error naming the field that is
/// wrong.
#[wasm_bindgen]
pub fn profile_summary(text: Option<String>) -> Result<JsValue, JsError> {
    use crate::engine::calibration::{describe_builtin, ProfileFile, PROFILE_VERSION};
    let (p, described) = match text {
        Some(t) => {
            let p = read_profile(&t)?;
            let d = p.describe();
            (p, d)
        }
        None => (
            ProfileFile {
                version: PROFILE_VERSION,
                name: String::new(),
                profile: Default::default(),
                walking_points: Vec::new(),
                running_points: Vec::new(),
                fuzzy_scale: None,
                pitch_offset_m: None,
            },
            describe_builtin(),
        ),
    };
    #[derive(serde::Serialize)]
    struct Summary<'a> {
        name: &'a str,
        walking: (f64, f64),
        running: (f64, f64),
        walking_points: usize,
        running_points: usize,
        fuzzy_scale: Option<f64>,
        pitch_offset_m: Option<f64>,
        text: String,
    }
    to_value(&Summary {
        name: &p.name,
        walking: (p.profile.walking.a, p.profile.walking.b),
        running: (p.profile.running.a, p.profile.running.b),
        walking_points: p.walking_points.len(),
        running_points: p.running_points.len(),
        fuzzy_scale: p.fuzzy_scale,
        pitch_offset_m: p.pitch_offset_m,
        text: match p.pitch_offset_m {
            Some(b) => format!(
                "{described} Pitch step length S = {PITCH_SLOPE_M_PER_DEG}·Δθ + {b:.3} m per stride."
            ),
            None => described,
        },
    })
}

/// Automatic refinement (Basso 2021 §2.2.5) after a live walk with GNSS: the profile (JSON)
/// with its walking offset moved by what the walk's `evidence` (`Live.walk_evidence()`) says,
/// `{json, offset_m: [before, after], scale, cadence_hz}`; `{why}` when the walk may not refine
/// it (the filter's verdict not `calibrated`, too few fixes used or steps, the scale uncertain
/// or not different from 1: see `engine::refinement::refine`), `why` for people ("GNSS was not
/// certain enough of your step length: scale 0.81 ± 0.06"). `text` says either to people,
/// naming the profile `name`.
#[wasm_bindgen]
pub fn refine_profile(text: &str, evidence: JsValue, name: &str) -> Result<JsValue, JsError> {
    let p = read_profile(text)?;
    let walk: crate::engine::refinement::WalkEvidence =
        serde_wasm_bindgen::from_value(evidence).map_err(to_js)?;
    let r = match crate::engine::refinement::refine(&p, &walk) {
        Ok(r) => r,
        Err(why) => {
            return super::to_json_value(&serde_json::json!({
                "why": why.to_string(),
                "text": format!("“{name}” not refined: {why}."),
            }))
        }
    };
    #[derive(serde::Serialize)]
    struct Refined {
        json: String,
        offset_m: (f64, f64),
        scale: f64,
        cadence_hz: f64,
        text: String,
    }
    let (before, after) = r.offset_m;
    to_value(&Refined {
        json: r.file.to_json().map_err(to_js)?,
        offset_m: r.offset_m,
        scale: r.scale,
        cadence_hz: r.cadence_hz,
        text: format!(
            "“{name}”: walking offset b {before:.3} → {after:.3} m (the fixes found your steps {:.3}× the profile's at {:.2} Hz). ",
            r.scale, r.cadence_hz
        ),
    })
}

use crate::engine::pitch_step_length::UNIVERSAL_SLOPE_M_PER_DEG as PITCH_SLOPE_M_PER_DEG;

/// Munoz Diaz 2015 §5.1's one-walk calibration of the pitch step length: a walk of
/// `distance_m` whose steps had the leg pitch amplitudes `amplitudes_deg` (`Live.pitch_amplitudes()`,
/// NaN without one). `{ok: true, offset_m, slope_m_per_deg, steps, with_pitch, text}`, or `{ok:
/// false, why, steps, with_pitch, text}` when the walk cannot give one (most steps without a leg
/// pitch: the phone not in a trouser pocket, or no gyroscope; too few steps; no distance);
/// `text` says the outcome to people.
#[wasm_bindgen]
pub fn pitch_calibration(distance_m: f64, amplitudes_deg: Vec<f64>) -> Result<JsValue, JsError> {
    let steps = amplitudes_deg.len();
    let with_pitch = amplitudes_deg
        .iter()
        .filter(|d| d.is_finite() && **d > 0.0)
        .count();
    let v = if 2 * with_pitch < steps || with_pitch == 0 {
        serde_json::json!({
            "ok": false, "steps": steps, "with_pitch": with_pitch,
            "why": format!("only {with_pitch} of the walk's {steps} steps had a leg pitch: the pitch step length needs the phone in a front trouser pocket and a gyroscope (the browser's rotation rate)"),
        })
    } else {
        match crate::engine::calibration::pitch_offset(
            distance_m,
            &amplitudes_deg,
            PITCH_SLOPE_M_PER_DEG,
        ) {
            Ok(b) => serde_json::json!({
                "ok": true, "offset_m": b, "slope_m_per_deg": PITCH_SLOPE_M_PER_DEG,
                "steps": steps, "with_pitch": with_pitch,
                "text": format!("Leg-pitch step length (Munoz Diaz 2015 §5.1): with the universal slope a = {PITCH_SLOPE_M_PER_DEG} m/°, your offset is b = {b:.3} m per stride ({with_pitch} steps with a leg pitch). It is saved with the profile."),
            }),
            Err(e) => serde_json::json!({
                "ok": false, "steps": steps, "with_pitch": with_pitch, "why": e.to_string(),
            }),
        }
    };
    let mut v = v;
    if let Some(why) = v.get("why").and_then(|w| w.as_str()).map(str::to_string) {
        v["text"] = format!("Leg-pitch step length not calibrated: {why}.").into();
    }
    super::to_json_value(&v)
}

/// The profile file (JSON) with the pitch step length's offset b, m, set (`pitch_offset_m`);
/// an error naming the field when the file is not a profile or b is not finite.
#[wasm_bindgen]
pub fn profile_with_pitch_offset(text: &str, offset_m: f64) -> Result<String, JsError> {
    let mut p = read_profile(text)?;
    if !offset_m.is_finite() {
        return Err(to_js(format!(
            "profile.pitch_offset_m: not a number of metres ({offset_m})"
        )));
    }
    p.pitch_offset_m = Some(offset_m);
    p.to_json().map_err(to_js)
}

/// The wizard offers GNSS as a walk's distance while the reported accuracy is this good or
/// better, m; the walk's distance counts fixes this good only.
#[wasm_bindgen]
pub fn gnss_limit_m() -> f64 {
    crate::engine::calibration::GNSS_MAX_ACCURACY_M
}

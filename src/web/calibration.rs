//! The calibration wizard's class and the profile files' functions.
//! May import: `engine`, `plot`.

use super::canvas::on_canvas;
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// A profile file's JSON, read and checked (the error names the field).
pub(super) fn read_profile(text: &str) -> Result<crate::engine::calibration::ProfileFile, JsError> {
    crate::engine::calibration::ProfileFile::from_json(text)
        .map_err(|e| JsError::new(&e.to_string()))
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
        other => Err(JsError::new(&format!("unknown band `{other}`"))),
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

    /// Adds a walk of `distance_m` whose steps had the frequencies `step_freqs_hz`; returns
    /// its `{band, pace, distance_m, steps, f_mean_hz, sl_mean_m}`.
    pub fn add_walk(
        &mut self,
        band_name: &str,
        pace: &str,
        distance_m: f64,
        step_freqs_hz: Vec<f64>,
    ) -> Result<JsValue, JsError> {
        let walk = crate::engine::calibration::CalibrationWalk {
            distance_m,
            step_freqs_hz,
        };
        let w = self
            .wizard
            .add(band(band_name)?, pace, &walk)
            .map_err(|e| JsError::new(&e.to_string()))?;
        serde_wasm_bindgen::to_value(w).map_err(|e| JsError::new(&e.to_string()))
    }

    /// Removes walk `index` (an outlier the user drops).
    pub fn remove_walk(&mut self, index: usize) {
        if index < self.wizard.walks.len() {
            self.wizard.walks.remove(index);
        }
    }

    /// The walks, each band's fit with its warnings (explained, with the walk index of an
    /// outlier), and the profile's notes: `{walks, walking, running, notes}`.
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
            notes: Vec<String>,
        }
        let (_, notes) = self.wizard.profile(&Default::default());
        serde_wasm_bindgen::to_value(&State {
            walks: &self.wizard.walks,
            walking: fit(Band::Walking),
            running: fit(Band::Running),
            notes,
        })
        .map_err(|e| JsError::new(&e.to_string()))
    }

    /// The profile file (JSON) the walks make, named `name`.
    pub fn profile_json(&self, name: &str) -> String {
        use crate::engine::calibration::{Band, ProfileFile, PROFILE_VERSION};
        let (profile, _) = self.wizard.profile(&Default::default());
        ProfileFile {
            version: PROFILE_VERSION,
            name: name.to_string(),
            profile,
            walking_points: self.wizard.points(Band::Walking),
            running_points: self.wizard.points(Band::Running),
        }
        .to_json()
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

/// Reads a profile file (JSON) and returns `{name, walking: {a, b}, running: {a, b}}`, or an
/// error naming the field that is wrong.
#[wasm_bindgen]
pub fn profile_summary(text: &str) -> Result<JsValue, JsError> {
    let p = read_profile(text)?;
    #[derive(serde::Serialize)]
    struct Summary<'a> {
        name: &'a str,
        walking: (f64, f64),
        running: (f64, f64),
        walking_points: usize,
        running_points: usize,
    }
    serde_wasm_bindgen::to_value(&Summary {
        name: &p.name,
        walking: (p.profile.walking.a, p.profile.walking.b),
        running: (p.profile.running.a, p.profile.running.b),
        walking_points: p.walking_points.len(),
        running_points: p.running_points.len(),
    })
    .map_err(|e| JsError::new(&e.to_string()))
}

/// Automatic refinement (Basso 2021 §2.2.5): the profile with its walking offset moved by the
/// fusion filter's step-length scale `k` at the cadence `f_hz`, a fraction `rate` of the way.
#[wasm_bindgen]
pub fn refine_profile(text: &str, k: f64, f_hz: f64, rate: f64) -> Result<String, JsError> {
    let mut p = read_profile(text)?;
    if !(k.is_finite() && k > 0.5 && k < 1.5 && f_hz.is_finite() && f_hz > 0.0) {
        return Err(JsError::new(&format!(
            "no refinement from a scale of {k} at {f_hz} Hz"
        )));
    }
    p.profile.walking.b =
        crate::engine::calibration::refined_offset(&p.profile.walking, k, f_hz, rate);
    p.profile
        .validate()
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(p.to_json())
}

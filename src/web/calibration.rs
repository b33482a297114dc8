//! The calibration wizard's class and the profile files' functions.
//! May import: `engine`, `io`, `live`, `plot`, `settings`.

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
    /// The normal walk's leg-pitch calibration, the last one ([`CalibrationWizard::walked`]).
    pitch: Option<crate::live::wizard::PitchCalibration>,
}

fn band_of(name: &str) -> Result<crate::engine::calibration::Band, String> {
    crate::live::wizard::BANDS
        .iter()
        .find(|(_, n)| *n == name)
        .map(|(b, _)| *b)
        .ok_or_else(|| format!("unknown band `{name}`"))
}

fn band(name: &str) -> Result<crate::engine::calibration::Band, JsError> {
    band_of(name).map_err(to_js)
}

#[wasm_bindgen]
impl CalibrationWizard {
    /// No walks yet.
    #[wasm_bindgen(constructor)]
    pub fn new() -> CalibrationWizard {
        CalibrationWizard {
            wizard: Default::default(),
            pitch: None,
        }
    }

    /// A walk ended: adds the walk `live` made toward `target_m` (measured by GNSS when
    /// `gnss`: see `live::wizard::walk_state`), its steps' frequencies and unscaled fuzzy
    /// lengths; for the comfortable (normal) pace, also calibrates the leg-pitch step length
    /// from the steps' leg pitch amplitudes (Munoz Diaz 2015 §5.1), kept for the profile.
    /// Returns `{text, error, pitch}`: the walk's figures for people (eq. 1 and 2), or why it
    /// was not added (`error` true), and the leg-pitch calibration (`null` for the other
    /// paces).
    pub fn walked(
        &mut self,
        band_name: &str,
        pace: &str,
        live: &super::live::Live,
        target_m: f64,
        gnss: bool,
    ) -> Result<JsValue, JsError> {
        let distance_m = live.walk_state(target_m, gnss).distance_m;
        let session = live.session();
        let walk = crate::engine::calibration::CalibrationWalk {
            distance_m,
            step_freqs_hz: session.step_freqs(),
            fuzzy_lengths_m: session.fuzzy_lengths().to_vec(),
        };
        let added = band_of(band_name).and_then(|b| {
            let w = self.wizard.add(b, pace, &walk).map_err(|e| e.to_string())?;
            Ok(crate::live::wizard::walk_text(w, band_name))
        });
        let pitch = (pace == "normal").then(|| session.pitch_amplitudes());
        self.outcome(added, distance_m, pitch)
    }

    /// A recording of a walk added as a walking walk as a live walk is: `read`, what upload
    /// mode's module made of the file `file_name` with live mode's settings
    /// (`read_recorded_walk`, [`crate::engine::recorded_walk`]); its leg pitch calibrates the
    /// pitch step length as the normal walk's does. Returns `{text, error, pitch}` as
    /// [`Self::walked`] does; `error` with the reason, naming the file, when the distance is
    /// missing, the file is not one recording or the walk has too few steps.
    pub fn recorded(&mut self, file_name: &str, read: &[u8]) -> Result<JsValue, JsError> {
        use crate::live::wizard::{recording_text, RECORDING_PACE};
        let read: Result<crate::engine::recorded_walk::RecordedWalk, String> =
            postcard::from_bytes(read).map_err(to_js)?;
        let r = match read {
            Ok(r) => r,
            Err(text) => return self.outcome(Err(text), f64::NAN, None),
        };
        let added = self
            .wizard
            .add(
                crate::engine::calibration::Band::Walking,
                RECORDING_PACE,
                &r.walk,
            )
            .map(|w| recording_text(file_name, w, r.engine_distance_m))
            .map_err(|e| format!("{file_name}: {e}"));
        let pitch = added.is_ok().then_some(r.pitch_amplitudes_deg);
        self.outcome(added, r.walk.distance_m, pitch)
    }

    /// A walk's outcome for the page, `{text, error, pitch}`: the walk's figures or why it was
    /// not added, and, for a walk whose leg pitch amplitudes are given, the leg-pitch
    /// calibration, kept for the profile.
    fn outcome(
        &mut self,
        added: Result<String, String>,
        distance_m: f64,
        pitch_amplitudes_deg: Option<Vec<f64>>,
    ) -> Result<JsValue, JsError> {
        let (text, error) = match added {
            Ok(text) => (text, false),
            Err(why) => (why, true),
        };
        let pitch =
            pitch_amplitudes_deg.map(|a| crate::live::wizard::pitch_calibration(distance_m, &a));
        if pitch.is_some() {
            self.pitch = pitch.clone();
        }
        super::to_json_value(&serde_json::json!({ "text": text, "error": error, "pitch": pitch }))
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
        use crate::engine::calibration::{fit_band, Band};
        use crate::live::wizard::{warnings, Warning};
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
            let f = fit_band(&self.wizard.points(b));
            Fit {
                points: f.points.len(),
                a: f.fit.as_ref().map(|x| x.a),
                b: f.fit.as_ref().map(|x| x.b),
                r2: f.fit.as_ref().map(|x| x.r2),
                se: f.se,
                warnings: warnings(&self.wizard, b),
            }
        };
        #[derive(serde::Serialize)]
        struct State<'a> {
            walks: &'a [crate::engine::calibration::WizardWalk],
            walking: Fit,
            running: Fit,
            fuzzy_scale: Option<f64>,
            notes: Vec<String>,
            pitch: &'a Option<crate::live::wizard::PitchCalibration>,
        }
        let (_, notes) = self.wizard.profile(&Default::default());
        to_value(&State {
            walks: &self.wizard.walks,
            walking: fit(Band::Walking),
            running: fit(Band::Running),
            fuzzy_scale: self.wizard.fuzzy_scale(),
            notes,
            pitch: &self.pitch,
        })
    }

    /// The fits box and the notes as the page shows them (`crate::live::wizard`): `{fits,
    /// notes}`, view trees; a fit's chart is a canvas `cal-chart-<band>` for [`Self::draw`], an
    /// outlier's button carries its walk's index (`data-walk`) for [`Self::remove_walk`].
    pub fn view(&self) -> Result<JsValue, JsError> {
        use crate::live::wizard::{fits_view, notes_view};
        super::to_json_value(&serde_json::json!({
            "fits": fits_view(&self.wizard),
            "notes": notes_view(&self.wizard),
        }))
    }

    /// The profile the walks make, named by the name field's `field` (trimmed, "me" when
    /// empty): `{name, json, text}`, its name, its file (JSON, checked) and what the page says
    /// when it is saved.
    pub fn profile(&self, field: &str) -> Result<JsValue, JsError> {
        let name = crate::live::wizard::profile_name(field);
        let json = self.profile_json(&name)?;
        read_profile(&json)?;
        let text = crate::live::wizard::message("saved", &name).map_err(to_js)?;
        super::to_json_value(&serde_json::json!({ "name": name, "json": json, "text": text }))
    }

    /// The profile file (JSON) the walks make, named `name`, with the leg-pitch step length's
    /// offset when the normal walk gave one.
    pub fn profile_json(&self, name: &str) -> Result<String, JsError> {
        let pitch = self.pitch.as_ref().and_then(|p| p.offset_m);
        self.wizard
            .profile_file(name, pitch)
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
    let walk: crate::engine::refinement::WalkEvidence = super::from_js(&evidence).map_err(to_js)?;
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

use crate::live::wizard::PITCH_SLOPE_M_PER_DEG;

/// Munoz Diaz 2015 §5.1's one-walk calibration of the pitch step length: a walk of
/// `distance_m` whose steps had the leg pitch amplitudes `amplitudes_deg` (`Live.pitch_amplitudes()`,
/// NaN without one). `{ok: true, offset_m, slope_m_per_deg, steps, with_pitch, text}`, or `{ok:
/// false, why, steps, with_pitch, text}` when the walk cannot give one (most steps without a leg
/// pitch: the phone not in a trouser pocket, or no gyroscope; too few steps; no distance);
/// `text` says the outcome to people.
#[wasm_bindgen]
pub fn pitch_calibration(distance_m: f64, amplitudes_deg: Vec<f64>) -> Result<JsValue, JsError> {
    super::to_json_value(&crate::live::wizard::pitch_calibration(
        distance_m,
        &amplitudes_deg,
    ))
}

/// The title of a calibration walk's screen, `undefined` without a positive distance
/// ([`crate::live::wizard::walk_title`]).
#[wasm_bindgen]
pub fn walk_title(pace: &str, target_m: f64, gnss: bool) -> Result<Option<String>, JsError> {
    crate::live::wizard::walk_title(pace, target_m, gnss).map_err(to_js)
}

/// The wizard's message `key` (`distance`, `busy`, `saved`, `import`), naming the profile `name`.
#[wasm_bindgen]
pub fn wizard_message(key: &str, name: &str) -> Result<String, JsError> {
    crate::live::wizard::message(key, name).map_err(to_js)
}

/// What the GNSS check says in `state` (`missing`, `waiting`, `fix` with `accuracy_m`,
/// `refused`, `failed`): `{text, good}`, `good` when a fix is within
/// `engine::calibration::GNSS_MAX_ACCURACY_M`.
#[wasm_bindgen]
pub fn gnss_state(state: &str, accuracy_m: Option<f64>) -> Result<JsValue, JsError> {
    let (text, good) = crate::live::wizard::gnss_state(
        state,
        accuracy_m.unwrap_or(f64::NAN),
        crate::engine::calibration::GNSS_MAX_ACCURACY_M,
    )
    .map_err(to_js)?;
    super::to_json_value(&serde_json::json!({ "text": text, "good": good }))
}

/// A profile file (`text`, from the file `file_name`) imported beside the saved `profiles`
/// (`{name: json}`): `{name, text}`, the name it is saved under and what the page says of it,
/// or `{error}` for a file that is not a profile ([`crate::live::wizard::import_profile`]).
#[wasm_bindgen]
pub fn import_profile(file_name: &str, text: &str, profiles: JsValue) -> Result<JsValue, JsError> {
    let existing: std::collections::BTreeMap<String, String> =
        super::from_js(&profiles).map_err(to_js)?;
    super::to_json_value(
        &match crate::live::wizard::import_profile(file_name, text, &existing) {
            Ok((name, text)) => serde_json::json!({ "name": name, "text": text }),
            Err(error) => serde_json::json!({ "error": error }),
        },
    )
}

/// The profile panel's choices and the profile in use, for the saved profiles' `names` and the
/// `selected` one (`""`: the built-in lines): `{options, in_use}`, `options` view trees.
#[wasm_bindgen]
pub fn profiles_view(names: Vec<String>, selected: &str) -> Result<JsValue, JsError> {
    use crate::live::wizard::{profile_in_use, profile_options};
    super::to_json_value(&serde_json::json!({
        "options": profile_options(names.iter().map(String::as_str), selected),
        "in_use": profile_in_use(selected),
    }))
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

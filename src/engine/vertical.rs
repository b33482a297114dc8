//! The walker's height: Munoz Diaz 2015 §6's vertical displacement from the leg pitch on stairs,
//! fused with the barometer where the log has one, and the floor changes.
//! May import: the rest of `engine`.

/// Where the height comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VerticalSource {
    /// The leg pitch alone (Munoz Diaz 2015 eqs. 6–7): no barometer.
    Pitch,
    /// The barometer alone: no leg pitch (not in a pocket, or no gyroscope).
    Barometer,
    /// Both, fused.
    PitchAndBarometer,
}

impl VerticalSource {
    /// Lower-case words, as shown.
    pub fn as_str(self) -> &'static str {
        match self {
            VerticalSource::Pitch => "leg pitch",
            VerticalSource::Barometer => "barometer",
            VerticalSource::PitchAndBarometer => "leg pitch + barometer",
        }
    }
}

use super::activity::Activity;
use super::types::{positive, ConfigError};
use nalgebra::{Matrix2, RowVector2, Vector2};

/// Settings of the height stage.
///
/// # The paper's constants
/// Munoz Diaz 2015 eqs. 6–7 are lines V_U = e·Δθ_U + g and V_D = h·Δθ_D + j (cm per stride,
/// degrees) whose fitted constants the paper does not print. It prints one point of each: on
/// the DLR building's stairs of 17 cm steps, Δθ_U = 53.07° and Δθ_D = 26.62° (§6.1); a stride is
/// two stair steps (§7.3: 0.52 m of tread per "step"), 34 cm. With one point per line only a
/// line through the origin is determined: e = 34 / 53.07 = 0.6407 cm/°, h = 34 / 26.62 =
/// 1.2772 cm/°, g = j = 0. Its check against Table 3 (33.2 cm real): this model gives 34.0 cm
/// at the DLR figures by construction; the error a different riser makes is measured on the
/// simulator, whose stair pitch follows a different law (see the tests).
///
/// The paper averages Δθ over a staircase and applies the model once ("the average of the pitch
/// amplitude of all steps"); for a line that is the same as summing the model over the strides,
/// which is what a streaming height does.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct VerticalConfig {
    /// e of eq. 6, cm per degree of Δθ_U (per stride).
    pub up_cm_per_deg: f64,
    /// g of eq. 6, cm per stride.
    pub up_offset_cm: f64,
    /// h of eq. 7, cm per degree of Δθ_D (per stride).
    pub down_cm_per_deg: f64,
    /// j of eq. 7, cm per stride.
    pub down_offset_cm: f64,
    /// Horizontal length of a footfall on stairs, m: the tread. Default 0.26 m, the paper's
    /// "standard depth" (§7.3), within the 25–30 cm of building codes.
    pub stair_tread_m: f64,
    /// Height between floors, m, for counting floors. Default 3.0 m, a common storey (homes
    /// 2.7–3 m, offices 3.5–4 m). Checked, not fitted, on the one multi-floor log of
    /// `../shared/data/ipin2023` (route 51), whose barometer puts its floors 3.2 m and 2.5 m
    /// apart (0.37 and 0.28 hPa at 8.78 m/hPa).
    pub floor_height_m: f64,
    /// A floor is counted once the height passes this share of a floor beyond the current
    /// one's level. Default 0.6 (hysteresis: 0.5 would flip on noise at half a floor).
    pub floor_switch: f64,
    /// σ of a barometric height (1 s mean of the readings), m. Default 0.5 m.
    pub baro_sigma_m: f64,
    /// Random walk of the barometer's offset (weather, ventilation), m/√s. Default 0.07: a
    /// front moves the pressure about 0.5 hPa (≈ 4.2 m) in an hour, 4.2 m/√3600 s.
    pub baro_drift_m_per_sqrt_s: f64,
    /// σ of a level stride's height change, m, when the leg pitch says level. Default 0.005 m:
    /// a floor is level, and this is what tells the barometer's drift from a climb.
    pub level_sigma_m: f64,
    /// σ of a step's height change, m, when nothing says level or stairs (no leg pitch).
    /// Default 0.25 m: a step up a stair is about 0.17 m.
    pub step_sigma_m: f64,
}

impl Default for VerticalConfig {
    fn default() -> Self {
        VerticalConfig {
            up_cm_per_deg: 34.0 / 53.07,
            up_offset_cm: 0.0,
            down_cm_per_deg: 34.0 / 26.62,
            down_offset_cm: 0.0,
            stair_tread_m: 0.26,
            floor_height_m: 3.0,
            floor_switch: 0.6,
            baro_sigma_m: 0.5,
            baro_drift_m_per_sqrt_s: 0.07,
            level_sigma_m: 0.005,
            step_sigma_m: 0.25,
        }
    }
}

impl VerticalConfig {
    /// Checks the values.
    pub fn validate(&self) -> Result<(), ConfigError> {
        for (v, f) in [
            (self.up_cm_per_deg, "vertical.up_cm_per_deg"),
            (self.down_cm_per_deg, "vertical.down_cm_per_deg"),
            (self.stair_tread_m, "vertical.stair_tread_m"),
            (self.floor_height_m, "vertical.floor_height_m"),
            (self.baro_sigma_m, "vertical.baro_sigma_m"),
            (
                self.baro_drift_m_per_sqrt_s,
                "vertical.baro_drift_m_per_sqrt_s",
            ),
            (self.level_sigma_m, "vertical.level_sigma_m"),
            (self.step_sigma_m, "vertical.step_sigma_m"),
        ] {
            positive(f, v)?;
        }
        for (v, f) in [
            (self.up_offset_cm, "vertical.up_offset_cm"),
            (self.down_offset_cm, "vertical.down_offset_cm"),
        ] {
            if !v.is_finite() {
                return Err(ConfigError::new(f, "must be finite"));
            }
        }
        if !(self.floor_switch > 0.5 && self.floor_switch < 1.0) {
            return Err(ConfigError::new(
                "vertical.floor_switch",
                "must lie strictly between 0.5 and 1",
            ));
        }
        Ok(())
    }

    /// Munoz Diaz 2015 eqs. 6–7: the height change of one stride, m (up positive), of a stride
    /// of amplitude Δθ (degrees) classified as `activity`; 0 on the level.
    pub fn stride_height_m(&self, activity: Activity, amplitude_deg: f64) -> f64 {
        match activity {
            Activity::Upstairs => (self.up_cm_per_deg * amplitude_deg + self.up_offset_cm) / 100.0,
            Activity::Downstairs => {
                -(self.down_cm_per_deg * amplitude_deg + self.down_offset_cm) / 100.0
            }
            _ => 0.0,
        }
    }
}

/// Standard-atmosphere height of pressure `hpa` above the level of pressure `ref_hpa`, m
/// (international barometric formula, h = 44330·(1 − (p/p₀)^(1/5.255))).
pub fn pressure_height_m(hpa: f64, ref_hpa: f64) -> f64 {
    44330.0 * (1.0 - libm::pow(hpa / ref_hpa, 1.0 / 5.255))
}

/// What moved the height at a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepHeight {
    /// The leg pitch measured this change over the step, m (0 on the level).
    Pitch(f64),
    /// A step without a leg pitch: any small change is possible.
    Unknown,
}

/// The height stage's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct VerticalDiagnostics {
    /// Height above the start, m.
    pub up_m: f64,
    /// Its σ, m.
    pub up_sd_m: f64,
    /// Floor relative to the start.
    pub floor: i32,
    /// What the height comes from.
    pub source: Option<VerticalSource>,
}

/// The height stage: a two-state Kalman filter [height z, barometer offset β]. Steps predict z
/// (the leg pitch's height change, eqs. 6–7, or an unknown small change); the barometer
/// measures z + β once a second (the mean of its readings over that second). The offset's
/// random walk takes the weather and the building's ventilation; level strides, which say the
/// height did not change, are what makes it observable. Floors count the height's level
/// changes with hysteresis.
#[derive(Debug, Clone)]
pub struct Vertical {
    cfg: VerticalConfig,
    x: Vector2<f64>,
    p: Matrix2<f64>,
    baro_ref: Option<f64>,
    baro_sum: (f64, u32, f64),
    baro_t: Option<f64>,
    pitch_seen: bool,
    floor: i32,
}

/// Seconds of barometer readings averaged into one measurement.
const BARO_WINDOW_S: f64 = 1.0;

impl Vertical {
    /// A stage with validated settings.
    pub fn new(cfg: VerticalConfig) -> Self {
        Vertical {
            cfg,
            x: Vector2::zeros(),
            p: Matrix2::zeros(),
            baro_ref: None,
            baro_sum: (0.0, 0, 0.0),
            baro_t: None,
            pitch_seen: false,
            floor: 0,
        }
    }

    /// A step: its height change by the leg pitch, or unknown. Returns the height after it.
    pub fn push_step(&mut self, h: StepHeight) -> f64 {
        let (dz, sd) = match h {
            StepHeight::Pitch(dz) => {
                self.pitch_seen = true;
                let sd = if dz == 0.0 {
                    self.cfg.level_sigma_m
                } else {
                    0.1 * dz.abs() + self.cfg.level_sigma_m
                };
                (dz, sd)
            }
            StepHeight::Unknown => (0.0, self.cfg.step_sigma_m),
        };
        self.x[0] += dz;
        self.p[(0, 0)] += sd * sd;
        self.update_floor();
        self.x[0]
    }

    /// A barometer reading (time s, hPa).
    pub fn push_pressure(&mut self, t: f64, hpa: f64) {
        let start = *self.baro_t.get_or_insert(t);
        if t - start < BARO_WINDOW_S {
            self.baro_sum.0 += hpa;
            self.baro_sum.1 += 1;
            self.baro_sum.2 = t;
            return;
        }
        if self.baro_sum.1 > 0 {
            let mean = self.baro_sum.0 / f64::from(self.baro_sum.1);
            self.measure(mean, self.baro_sum.2 - start + (t - self.baro_sum.2));
        }
        self.baro_t = Some(t);
        self.baro_sum = (hpa, 1, t);
    }

    fn measure(&mut self, hpa: f64, dt: f64) {
        let r = *self.baro_ref.get_or_insert(hpa);
        // The first measurement is the barometer's zero: β = 0 at the start.
        let y = pressure_height_m(hpa, r);
        let q = self.cfg.baro_drift_m_per_sqrt_s;
        // The offset drifts only where something can tell it from a climb: the leg pitch's
        // level strides. Without them the height is the barometer's, drift and all.
        if self.pitch_seen {
            self.p[(1, 1)] += q * q * dt.max(0.0);
        }
        // y = z + β + v, v ~ N(0, σ²).
        let h = RowVector2::new(1.0, 1.0);
        let sigma = self.cfg.baro_sigma_m;
        let s = (h * self.p * h.transpose())[0] + sigma * sigma;
        let k = self.p * h.transpose() / s;
        let innov = y - (h * self.x)[0];
        self.x += k * innov;
        self.p -= k * (h * self.p);
        self.update_floor();
    }

    fn update_floor(&mut self) {
        let hf = self.cfg.floor_height_m;
        let level = f64::from(self.floor) * hf;
        let d = self.x[0] - level;
        if d.abs() > self.cfg.floor_switch * hf {
            self.floor = libm::round(self.x[0] / hf) as i32;
        }
    }

    /// Height above the start, m.
    pub fn up_m(&self) -> f64 {
        self.x[0]
    }

    /// Whether a barometer reading arrived.
    pub fn has_barometer(&self) -> bool {
        self.baro_ref.is_some()
    }

    /// Floor relative to the start.
    pub fn floor(&self) -> i32 {
        self.floor
    }

    /// The current values.
    pub fn diagnostics(&self) -> VerticalDiagnostics {
        VerticalDiagnostics {
            up_m: self.x[0],
            up_sd_m: libm::sqrt(self.p[(0, 0)].max(0.0)),
            floor: self.floor,
            source: match (self.pitch_seen, self.baro_ref.is_some()) {
                (true, true) => Some(VerticalSource::PitchAndBarometer),
                (true, false) => Some(VerticalSource::Pitch),
                (false, true) => Some(VerticalSource::Barometer),
                (false, false) => None,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_point_and_the_barometric_formula() {
        let c = VerticalConfig::default();
        assert!((c.stride_height_m(Activity::Upstairs, 53.07) - 0.34).abs() < 1e-12);
        assert!((c.stride_height_m(Activity::Downstairs, 26.62) + 0.34).abs() < 1e-12);
        assert_eq!(c.stride_height_m(Activity::Walking, 40.0), 0.0);
        // About 8.3 m per hPa near sea level.
        let h = pressure_height_m(1012.25, 1013.25);
        assert!((h - 8.3).abs() < 0.1, "{h}");
    }

    /// Pitch alone: 4 floors of 3 m, 27 strides of 4/9 m; then the barometer, which drifts,
    /// against level strides that say the height holds.
    #[test]
    fn floors_from_the_pitch_and_a_drifting_barometer() {
        let c = VerticalConfig::default();
        let mut v = Vertical::new(c);
        for _ in 0..27 {
            v.push_step(StepHeight::Pitch(4.0 / 9.0));
        }
        assert!((v.up_m() - 12.0).abs() < 1e-9);
        assert_eq!(v.floor(), 4);
        assert_eq!(v.diagnostics().source, Some(VerticalSource::Pitch));

        // Barometer only (no pitch): the height follows it.
        let mut v = Vertical::new(c);
        let mut t = 0.0;
        let mut z: f64 = 0.0;
        while t < 120.0 {
            if t > 30.0 && t < 60.0 {
                z += 8.0 / 30.0 * 0.04; // 8 m in 30 s
            }
            let hpa = 1000.0 * libm::pow(1.0 - z / 44330.0, 5.255);
            v.push_pressure(t, hpa);
            if (t * 25.0) as u64 % 25 == 0 {
                v.push_step(StepHeight::Unknown);
            }
            t += 0.04;
        }
        assert!((v.up_m() - 8.0).abs() < 0.5, "{}", v.up_m());
        assert_eq!(v.floor(), 3);
        assert_eq!(v.diagnostics().source, Some(VerticalSource::Barometer));
    }
}

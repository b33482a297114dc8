//! Input records and the error types of the engine's boundary.
//! May import: nothing of the crate.
//!
//! Units and frames are those stated in the crate documentation: seconds, m/s² (specific force
//! including gravity, Android sign), rad/s, µT, device frame x-right / y-up-screen / z-out,
//! navigation frame East-North-Up. Missing data is `None`, never a zero vector or a NaN.

use nalgebra::{UnitQuaternion, Vector3};
use std::fmt;

/// A 3-vector in the device frame (x right, y top of screen, z out of screen).
pub type DeviceVec = Vector3<f64>;

/// One inertial sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuSample {
    /// Time, seconds on the log's clock.
    pub t: f64,
    /// Specific force including gravity, m/s², device frame. Face-up at rest: (0, 0, +9.81).
    pub accel: DeviceVec,
    /// Angular rate, rad/s, device frame, right-handed.
    pub gyro: Option<DeviceVec>,
    /// Magnetic field, µT, device frame.
    pub mag: Option<DeviceVec>,
    /// Orientation supplied by the operating system: the rotation taking device-frame vectors to
    /// the East-North-Up frame (`v_enu = q * v_device`).
    pub orientation: Option<UnitQuaternion<f64>>,
}

/// The largest time the engine accepts, in magnitude, s: 2⁴⁰ s, about 35 000 years, so Unix
/// time and any clock since boot fit, with a resolution still finer than 0.25 ms. A larger (yet
/// finite) time is refused as out of range: there the engine's resampling grids (steps of
/// 20–50 ms) no longer change the time when a step is added, and a loop over the grid up to a
/// sample's time would never end (found by the `live` fuzz target).
pub const MAX_TIME_S: f64 = 1_099_511_627_776.0;

/// Whether a time is one the engine accepts: finite and within ±[`MAX_TIME_S`] (NaN is not).
pub fn time_in_range(t: f64) -> bool {
    t.abs() <= MAX_TIME_S
}

impl ImuSample {
    /// A sample with acceleration only.
    pub fn accel_only(t: f64, accel: DeviceVec) -> Self {
        ImuSample {
            t,
            accel,
            gyro: None,
            mag: None,
            orientation: None,
        }
    }

    /// What the engine accepts: every value present finite ([`Self::check_finite`]), the time
    /// within ±[`MAX_TIME_S`] and every sensor component within [`IMU_LIMITS`]; names the
    /// first field that is not.
    pub fn check(&self) -> Result<(), InputError> {
        if self.plausible() {
            return Ok(());
        }
        self.field_by_field()
    }

    /// [`Self::check`]'s tests one by one, for a sample refused: names the first field that
    /// fails.
    fn field_by_field(&self) -> Result<(), InputError> {
        self.check_finite()?;
        let bad = |field: &'static str| Err(InputError::NonFinite { t: self.t, field });
        if !time_in_range(self.t) {
            return bad("t");
        }
        if self.accel.amax() > IMU_LIMITS.accel_m_s2 {
            return bad("accel");
        }
        if self.gyro.is_some_and(|g| g.amax() > IMU_LIMITS.gyro_rad_s) {
            return bad("gyro");
        }
        if self.mag.is_some_and(|m| m.amax() > IMU_LIMITS.mag_ut) {
            return bad("mag");
        }
        Ok(())
    }

    /// Whether [`Self::check`] accepts the sample, all tests at once without naming a field:
    /// |x| ≤ limit is false for NaN and ±∞, so the ranges imply finiteness.
    fn plausible(&self) -> bool {
        let within = |v: &DeviceVec, limit: f64| {
            (v.x.abs() <= limit) & (v.y.abs() <= limit) & (v.z.abs() <= limit)
        };
        time_in_range(self.t)
            & within(&self.accel, IMU_LIMITS.accel_m_s2)
            & self
                .gyro
                .as_ref()
                .map_or(true, |g| within(g, IMU_LIMITS.gyro_rad_s))
            & self
                .mag
                .as_ref()
                .map_or(true, |m| within(m, IMU_LIMITS.mag_ut))
            & self
                .orientation
                .as_ref()
                .map_or(true, |q| all_finite(q.coords.iter()))
    }

    /// Checks that every value present is finite; names the first field that is not.
    pub fn check_finite(&self) -> Result<(), InputError> {
        let bad = |field: &'static str| Err(InputError::NonFinite { t: self.t, field });
        if !self.t.is_finite() {
            return bad("t");
        }
        if !all_finite(self.accel.iter()) {
            return bad("accel");
        }
        if let Some(g) = self.gyro {
            if !all_finite(g.iter()) {
                return bad("gyro");
            }
        }
        if let Some(m) = self.mag {
            if !all_finite(m.iter()) {
                return bad("mag");
            }
        }
        if let Some(q) = self.orientation {
            if !all_finite(q.coords.iter()) {
                return bad("orientation");
            }
        }
        Ok(())
    }
}

/// The largest magnitude of each component an IMU sample may hold. Far beyond any phone's
/// sensor (accelerometers saturate at 8–16 g, gyroscopes at about 35 rad/s, the Earth's field
/// is under 70 µT), and small enough that squares and sums of squares stay far from overflow: a
/// finite 1e308 would otherwise become an infinite norm, then NaN in the vertical acceleration
/// and the PLL (found by the `live` fuzz target and by a damaged recording). A larger value is
/// refused as out of range.
pub struct ImuLimits {
    /// m/s² (about 1000 g).
    pub accel_m_s2: f64,
    /// rad/s.
    pub gyro_rad_s: f64,
    /// µT.
    pub mag_ut: f64,
}

/// See [`ImuLimits`].
pub const IMU_LIMITS: ImuLimits = ImuLimits {
    accel_m_s2: 1e4,
    gyro_rad_s: 1e3,
    mag_ut: 1e5,
};

/// One GNSS position fix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GnssFix {
    /// Time, seconds on the log's clock.
    pub t: f64,
    /// WGS84 latitude, degrees.
    pub lat_deg: f64,
    /// WGS84 longitude, degrees.
    pub lon_deg: f64,
    /// Horizontal accuracy (1σ radius as the platform reports it), metres.
    pub h_accuracy_m: f64,
    /// Altitude above the WGS84 ellipsoid, metres.
    pub altitude_m: Option<f64>,
    /// Ground speed, m/s.
    pub speed_mps: Option<f64>,
    /// Course over ground, degrees clockwise from true north.
    pub bearing_deg: Option<f64>,
}

impl GnssFix {
    /// Checks finiteness and ranges (the time within ±[`MAX_TIME_S`]); names the first bad
    /// field.
    pub fn check(&self) -> Result<(), InputError> {
        let bad = |field: &'static str| Err(InputError::NonFinite { t: self.t, field });
        if !time_in_range(self.t) {
            return bad("t");
        }
        if !self.lat_deg.is_finite() || self.lat_deg.abs() > 90.0 {
            return bad("lat_deg");
        }
        if !self.lon_deg.is_finite() || self.lon_deg.abs() > 180.0 {
            return bad("lon_deg");
        }
        if !self.h_accuracy_m.is_finite() || self.h_accuracy_m < 0.0 {
            return bad("h_accuracy_m");
        }
        for (v, f) in [
            (self.altitude_m, "altitude_m"),
            (self.speed_mps, "speed_mps"),
            (self.bearing_deg, "bearing_deg"),
        ] {
            if matches!(v, Some(x) if !x.is_finite()) {
                return bad(f);
            }
        }
        Ok(())
    }
}

/// One record of a log, in time order: what the pipeline is fed ([`crate::engine::Pipeline::push`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Record {
    /// An inertial sample.
    Imu(ImuSample),
    /// A GNSS fix.
    Gnss(GnssFix),
    /// The recorder noticed that input stopped between two times (s).
    Gap(f64, f64),
    /// A sample of a second, foot-mounted IMU (sensor frame of the foot; Strozzi 2017 §4's
    /// two-sensor walks): fed to foot mode while the first IMU (trunk or pocket) gives the
    /// heading. Its own stream: its times are checked against the previous foot sample.
    Foot(ImuSample),
    /// A barometer reading (Munoz Diaz 2015 §2: the usual aid for the vertical; here fused with
    /// the leg pitch's vertical displacement, [`crate::engine::vertical`]).
    Pressure(PressureSample),
}

impl Record {
    /// The record's time, s (a gap's start).
    pub fn t(&self) -> f64 {
        match self {
            Record::Imu(s) | Record::Foot(s) => s.t,
            Record::Gnss(f) => f.t,
            Record::Gap(t0, _) => *t0,
            Record::Pressure(p) => p.t,
        }
    }
}

/// One barometer reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureSample {
    /// Time, seconds on the log's clock.
    pub t: f64,
    /// Static air pressure, hPa (= mbar).
    pub hpa: f64,
}

/// The range of pressures the engine accepts, hPa: beyond any place a person walks (the Dead
/// Sea's shore is about 1070 hPa, Everest's summit about 330).
pub const PRESSURE_RANGE_HPA: (f64, f64) = (100.0, 1200.0);

impl PressureSample {
    /// Checks finiteness and range (the time within ±[`MAX_TIME_S`], the pressure within
    /// [`PRESSURE_RANGE_HPA`]); names the first bad field.
    pub fn check(&self) -> Result<(), InputError> {
        let bad = |field: &'static str| Err(InputError::NonFinite { t: self.t, field });
        if !time_in_range(self.t) {
            return bad("t");
        }
        if !(self.hpa >= PRESSURE_RANGE_HPA.0 && self.hpa <= PRESSURE_RANGE_HPA.1) {
            return bad("pressure_hpa");
        }
        Ok(())
    }
}

fn all_finite<'a>(mut it: impl Iterator<Item = &'a f64>) -> bool {
    it.all(|v| v.is_finite())
}

/// Why an input record was refused. The engine's state is untouched by a refused record.
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// A field holds NaN or ±∞, or is out of range (GNSS coordinates, [`IMU_LIMITS`]).
    NonFinite {
        /// The record's time (may itself be the bad field).
        t: f64,
        /// The offending field.
        field: &'static str,
    },
    /// The record's time is earlier than the previous accepted record of the same stream.
    TimeWentBackwards {
        /// The record's time.
        t: f64,
        /// The last accepted time.
        last: f64,
    },
    /// The selected orientation source needs a field this sample lacks.
    MissingField {
        /// The record's time.
        t: f64,
        /// The missing field.
        field: &'static str,
    },
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::NonFinite { t, field } => {
                write!(
                    f,
                    "record at t={t}: field `{field}` is not a finite, in-range number"
                )
            }
            InputError::TimeWentBackwards { t, last } => {
                write!(
                    f,
                    "record at t={t}: time went backwards (previous record at t={last})"
                )
            }
            InputError::MissingField { t, field } => {
                write!(f, "record at t={t}: field `{field}` is required by the configured orientation source")
            }
        }
    }
}

impl std::error::Error for InputError {}

/// A configuration value that fails validation; names the field.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigError {
    /// Dotted path of the bad field, e.g. `pll.free_running_walk_hz`.
    pub field: &'static str,
    /// What is wrong with it.
    pub reason: String,
}

impl ConfigError {
    pub(crate) fn new(field: &'static str, reason: impl Into<String>) -> Self {
        ConfigError {
            field,
            reason: reason.into(),
        }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid configuration `{}`: {}", self.field, self.reason)
    }
}

impl std::error::Error for ConfigError {}

/// Returns `Ok` when `v` is finite and strictly positive.
pub(crate) fn positive(field: &'static str, v: f64) -> Result<(), ConfigError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(ConfigError::new(
            field,
            format!("must be a finite positive number, got {v}"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Quaternion, UnitQuaternion};

    #[test]
    fn the_check_at_once_accepts_what_the_tests_one_by_one_do() {
        let values = [0.0, -3.5, 9e2, 2e3, 5e4, 2e5, 2e12, f64::NAN, f64::INFINITY];
        let q = UnitQuaternion::identity();
        let odd = UnitQuaternion::new_unchecked(Quaternion::new(f64::NAN, 0.0, 0.0, 0.0));
        for (i, &x) in values.iter().enumerate() {
            for field in 0..5 {
                let v = |f: usize| DeviceVec::new(1.0, if f == field { x } else { 2.0 }, -1.0);
                let s = ImuSample {
                    t: if field == 0 { x } else { 1.0 },
                    accel: v(1),
                    gyro: (i % 2 == 0).then(|| v(2)),
                    mag: (i % 3 != 0).then(|| v(3)),
                    orientation: Some(if field == 4 && x.is_nan() { odd } else { q }),
                };
                // Debug text: a NaN time is not equal to itself.
                let (fast, slow) = (s.check(), s.field_by_field());
                assert_eq!(
                    format!("{fast:?}"),
                    format!("{slow:?}"),
                    "field {field} value {x}"
                );
            }
        }
    }
}

//! Orientation into the navigation frame (East-North-Up).
//! May import: the rest of `engine`.
//!
//! Four sources:
//! - [`OrientationSource::Os`]: the quaternion the operating system supplies. Basso 2016 §II.A
//!   relies on the phone's built-in AHRS to cast samples into the navigation frame.
//! - [`OrientationSource::Madgwick`]: the Madgwick gradient-descent filter on accelerometer and
//!   gyroscope, with the magnetometer as the optional absolute-yaw reference (Basso 2021 §2.2.1,
//!   eqs. 1–5). The filter itself is the `ahrs` crate; we set its sample period on every sample
//!   from the timestamps.
//! - [`OrientationSource::KfNfa`]: the Kalman filter with fuzzy adaptation of R of Ibarra 2015
//!   ch. 3, in [`kf_nfa`]; accelerometer and gyroscope, magnetometer optional (off).
//! - [`OrientationSource::GravityLowPass`]: acceleration only. Gravity is tracked by a low-pass
//!   filter; this yields vertical acceleration (so steps) but no horizontal axes, so no heading.
//!   The vertical acceleration is taken as |a| − |g_lp| rather than the projection a·ĝ_lp − |g_lp|:
//!   the two agree to first order, but the projection also carries the tilt error of the
//!   low-passed gravity, which in a trouser pocket swings with the thigh at the stride frequency.
//!
//! # `Auto`: the source follows what the stream holds
//! Phones start their sensors one after another (a gyroscope 0.2–0.7 s after the accelerometer
//! is common; a browser may give its first motion events without a rotation rate, or the attitude
//! event a second late). `Auto` is therefore a state of the estimator, not a choice made once:
//! every sample runs on the best source its inputs allow, in the order OS quaternion (on the
//! sample, or the last one at most [`HOLD_S`] old) > Madgwick (a gyroscope on the sample) >
//! gravity low-pass. When a better input first appears the estimator moves up to it; when a
//! sample lacks the current source's input (a stream that stopped, or the first sample after a
//! gap) it moves down to what the sample has, and up again when the input returns. A move hands
//! the attitude over, so the tilt and, where the new source has no absolute yaw of its own, the
//! yaw carry on: Madgwick starts from the OS attitude it replaces, or from the low-passed gravity
//! (and the magnetometer, if any) when it replaces the gravity low-pass; the gravity low-pass
//! starts from the gravity the attitude it replaces implies. Moving up to the OS quaternion takes
//! its absolute yaw as it is. The moves are counted ([`OrientationDiagnostics::switches`]). The
//! explicit sources never move: a sample without the input they need is refused
//! ([`Orientation::check`]).

use super::math::OnePole;
use super::types::{positive, ConfigError, DeviceVec, ImuSample, InputError};
use ahrs::Ahrs;
use kf_nfa::{KfNfa, KfNfaConfig, KfNfaDiagnostics};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

pub mod kf_nfa;

/// Standard gravity, m/s².
pub const G0: f64 = 9.806_65;

/// How long the last OS attitude stands in for a sample that carries none, s. Phones deliver
/// the attitude on its own event stream, often slower than the accelerometer (a browser's
/// `deviceorientation` at 30–60 Hz beside `devicemotion` at 60–100 Hz; a recorder that writes
/// each sensor as it arrives); within 0.2 s a pocketed phone turns by a few degrees at most.
pub const HOLD_S: f64 = 0.2;

/// Which orientation source to use.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum OrientationSource {
    /// Per sample, the best source its inputs allow: the OS quaternion, else Madgwick with a
    /// gyroscope, else the gravity low-pass (see the module documentation).
    #[default]
    Auto,
    /// The OS-supplied quaternion on every sample.
    Os,
    /// Madgwick filter with gain `beta` (rad/s). Uses the magnetometer when the sample has one.
    Madgwick {
        /// Gradient-descent gain β (Madgwick 2010 eq. 50 suggests √(3/4)·gyro error; 0.1 is the
        /// reference implementation's default).
        #[serde(default = "default_beta")]
        beta: f64,
    },
    /// The KF-NFA of Ibarra 2015 ch. 3 (accelerometer and gyroscope; never picked by `Auto`).
    KfNfa(KfNfaConfig),
    /// Gravity from a low-pass filter of the accelerometer with time constant `tau_s`.
    GravityLowPass {
        /// Time constant of the gravity filter, seconds.
        #[serde(default = "default_tau_s")]
        tau_s: f64,
    },
}

const fn default_beta() -> f64 {
    0.1
}

const fn default_tau_s() -> f64 {
    1.0
}

impl OrientationSource {
    /// Default Madgwick configuration.
    pub const MADGWICK: OrientationSource = OrientationSource::Madgwick {
        beta: default_beta(),
    };
    /// Default gravity low-pass configuration (1 s: well below the ~1.8 Hz gait).
    pub const GRAVITY: OrientationSource = OrientationSource::GravityLowPass {
        tau_s: default_tau_s(),
    };

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), ConfigError> {
        match *self {
            OrientationSource::Madgwick { beta } => positive("orientation.beta", beta),
            OrientationSource::GravityLowPass { tau_s } => positive("orientation.tau_s", tau_s),
            OrientationSource::KfNfa(c) => c.validate(),
            _ => Ok(()),
        }
    }
}

/// A sample cast into the navigation frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NavAccel {
    /// Vertical linear acceleration (gravity removed), m/s², up positive.
    pub up: f64,
    /// Horizontal acceleration (east, north), m/s²; `None` when the source has no heading.
    pub horizontal: Option<(f64, f64)>,
    /// The device → ENU attitude used, when the source has one.
    pub attitude: Option<UnitQuaternion<f64>>,
}

/// The running orientation estimator.
pub struct Orientation {
    /// The configured source (`Auto`, or the one explicit source).
    source: OrientationSource,
    /// The estimator running now; `None` before the first sample.
    kind: Option<Kind>,
    switches: u64,
    switched: bool,
}

/// The estimator's current values; read-only.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct OrientationDiagnostics {
    /// The source in use now (with `Auto` configured, the one the last sample ran on).
    pub source: OrientationSource,
    /// Whether it gives horizontal axes (and so a heading).
    pub has_heading: bool,
    /// How often `Auto` moved from one source to another after the first sample.
    pub switches: u64,
    /// The KF-NFA's R scale, mismatch and counts, when it is the source.
    pub kf_nfa: Option<KfNfaDiagnostics>,
}

enum Kind {
    Os {
        last: Option<(f64, UnitQuaternion<f64>)>,
    },
    Madgwick {
        filter: Option<ahrs::Madgwick<f64>>,
        beta: f64,
    },
    Gravity {
        lp: [OnePole; 3],
    },
    KfNfa(Box<KfNfa>),
}

/// `Auto`'s order of preference: a higher rank wins when the sample allows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Rank {
    Gravity,
    Madgwick,
    Os,
}

impl Kind {
    fn new(source: OrientationSource) -> Kind {
        match source {
            OrientationSource::Madgwick { beta } => Kind::Madgwick { filter: None, beta },
            OrientationSource::GravityLowPass { tau_s } => Kind::Gravity {
                lp: [OnePole::new(tau_s); 3],
            },
            OrientationSource::KfNfa(c) => Kind::KfNfa(Box::new(KfNfa::new(c))),
            OrientationSource::Os | OrientationSource::Auto => Kind::Os { last: None },
        }
    }

    fn rank(&self) -> Option<Rank> {
        match self {
            Kind::Os { .. } => Some(Rank::Os),
            Kind::Madgwick { .. } => Some(Rank::Madgwick),
            Kind::Gravity { .. } => Some(Rank::Gravity),
            Kind::KfNfa(_) => None,
        }
    }

    /// Whether a sample at `t` without an attitude of its own can use the last OS attitude.
    fn holds_at(&self, t: f64) -> bool {
        matches!(self, Kind::Os { last: Some((tl, _)) } if t - tl <= HOLD_S)
    }

    /// The source this estimator is.
    fn source(&self) -> OrientationSource {
        match self {
            Kind::Os { .. } => OrientationSource::Os,
            Kind::Madgwick { beta, .. } => OrientationSource::Madgwick { beta: *beta },
            Kind::Gravity { lp } => OrientationSource::GravityLowPass { tau_s: lp[0].tau() },
            Kind::KfNfa(f) => OrientationSource::KfNfa(f.config()),
        }
    }

    /// The gravity the estimator sees in device coordinates, m/s² (specific force at rest,
    /// Android sign), when it has one.
    fn gravity(&self) -> Option<DeviceVec> {
        match self {
            Kind::Gravity { lp } => {
                Some(Vector3::new(lp[0].value()?, lp[1].value()?, lp[2].value()?))
            }
            _ => self
                .attitude()
                .map(|q| q.inverse_transform_vector(&Vector3::new(0.0, 0.0, G0))),
        }
    }

    /// The current device → ENU attitude, if the estimator has one.
    fn attitude(&self) -> Option<UnitQuaternion<f64>> {
        match self {
            Kind::Os { last } => last.map(|(_, q)| q),
            Kind::Madgwick {
                filter: Some(f), ..
            } => Some(nwu_to_enu() * f.quat),
            Kind::KfNfa(f) => f.attitude(),
            _ => None,
        }
    }
}

/// Rotation from Madgwick's earth frame (x magnetic north, y west, z up) to ENU.
fn nwu_to_enu() -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(Matrix3::new(
        0.0, -1.0, 0.0, //
        1.0, 0.0, 0.0, //
        0.0, 0.0, 1.0,
    )))
}

/// Device→ENU attitude from one accelerometer (and optional magnetometer) reading, by TRIAD.
/// Without a magnetometer, yaw is set so that the device's y axis points north.
pub fn attitude_from_vectors(
    accel: &DeviceVec,
    mag: Option<&DeviceVec>,
) -> Option<UnitQuaternion<f64>> {
    let up = accel.try_normalize(1e-9)?;
    let east = match mag.and_then(|m| m.cross(&up).try_normalize(1e-9)) {
        Some(e) => e,
        None => {
            // Yaw reference: the device y axis (or x if y is vertical), projected horizontally.
            let y = Vector3::y();
            let yh = y - up * y.dot(&up);
            let n = yh.try_normalize(1e-3).or_else(|| {
                let x = Vector3::x();
                (x - up * x.dot(&up)).try_normalize(1e-3)
            })?;
            n.cross(&up)
        }
    };
    let north = up.cross(&east);
    // Rows are the ENU axes expressed in device coordinates: v_enu = R v_dev.
    let r = Matrix3::from_rows(&[east.transpose(), north.transpose(), up.transpose()]);
    Some(UnitQuaternion::from_rotation_matrix(
        &Rotation3::from_matrix_unchecked(r),
    ))
}

impl Orientation {
    /// A new estimator for a source; `Auto` settles on its first sample and follows the
    /// stream after that (see the module documentation).
    pub fn new(source: OrientationSource) -> Self {
        Orientation {
            source,
            kind: match source {
                OrientationSource::Auto => None,
                explicit => Some(Kind::new(explicit)),
            },
            switches: 0,
            switched: false,
        }
    }

    /// The current values.
    pub fn diagnostics(&self) -> OrientationDiagnostics {
        OrientationDiagnostics {
            source: self.source_now(),
            has_heading: self.has_heading(),
            switches: self.switches,
            kf_nfa: match &self.kind {
                Some(Kind::KfNfa(f)) => Some(f.diagnostics()),
                _ => None,
            },
        }
    }

    /// The source in use now: the configured one, or with `Auto` the one the last sample ran
    /// on (`Auto` itself before the first sample).
    pub fn source_now(&self) -> OrientationSource {
        self.kind.as_ref().map_or(self.source, Kind::source)
    }

    /// Whether the last sample moved `Auto` to another source (the first sample's choice is
    /// not a move).
    pub fn switched(&self) -> bool {
        self.switched
    }

    /// Whether the source in use provides horizontal axes (and so heading).
    pub fn has_heading(&self) -> bool {
        matches!(
            self.kind,
            Some(Kind::Os { .. } | Kind::Madgwick { .. } | Kind::KfNfa(_))
        )
    }

    /// The current device→ENU attitude, if the source has one.
    pub fn attitude(&self) -> Option<UnitQuaternion<f64>> {
        match &self.kind {
            Some(Kind::Os { .. }) | None => None,
            Some(k) => k.attitude(),
        }
    }

    /// Whether the sample has what an explicit source needs: the OS attitude (its own, or the
    /// last one at most [`HOLD_S`] old) for `Os`, a gyroscope for Madgwick and the KF-NFA.
    /// `Auto` takes every sample.
    pub fn check(&self, s: &ImuSample) -> Result<(), InputError> {
        let missing = |field| Err(InputError::MissingField { t: s.t, field });
        match (self.source, &self.kind) {
            (OrientationSource::Auto, _) => Ok(()),
            (OrientationSource::Os, Some(k)) if s.orientation.is_none() && !k.holds_at(s.t) => {
                missing("orientation")
            }
            (OrientationSource::Madgwick { .. } | OrientationSource::KfNfa(_), _)
                if s.gyro.is_none() =>
            {
                missing("gyro")
            }
            _ => Ok(()),
        }
    }

    /// With `Auto`: the source the sample allows, and the move to it from the one running.
    fn follow(&mut self, s: &ImuSample) {
        self.switched = false;
        if self.source != OrientationSource::Auto {
            return;
        }
        let held = self.kind.as_ref().is_some_and(|k| k.holds_at(s.t));
        let want = if s.orientation.is_some() || held {
            Rank::Os
        } else if s.gyro.is_some() {
            Rank::Madgwick
        } else {
            Rank::Gravity
        };
        let Some(from) = &self.kind else {
            self.kind = Some(Kind::new(match want {
                Rank::Os => OrientationSource::Os,
                Rank::Madgwick => OrientationSource::MADGWICK,
                Rank::Gravity => OrientationSource::GRAVITY,
            }));
            return;
        };
        if from.rank() == Some(want) {
            return;
        }
        let next = match want {
            Rank::Os => Kind::Os { last: None },
            Rank::Madgwick => {
                // The attitude handed over: the OS's as it was, or TRIAD on the low-passed
                // gravity rather than on this one sample's acceleration.
                let q0 = match from {
                    Kind::Gravity { .. } => from
                        .gravity()
                        .and_then(|g| attitude_from_vectors(&g, s.mag.as_ref())),
                    _ => from.attitude(),
                };
                let filter = q0.map(|q| {
                    ahrs::Madgwick::new_with_quat(1e-2, default_beta(), nwu_to_enu().inverse() * q)
                });
                Kind::Madgwick {
                    filter,
                    beta: default_beta(),
                }
            }
            Rank::Gravity => {
                let mut lp = [OnePole::new(default_tau_s()); 3];
                if let Some(g) = from.gravity() {
                    for (f, x) in lp.iter_mut().zip(g.iter()) {
                        f.update(*x, 0.0);
                    }
                }
                Kind::Gravity { lp }
            }
        };
        self.kind = Some(next);
        self.switches += 1;
        self.switched = true;
    }

    /// Feeds one sample taken `dt` seconds after the previous one (0 after a gap) and returns
    /// its acceleration in the navigation frame. A sample [`Self::check`] refuses is an error
    /// and leaves the state as it was (the check is the sources' own, below).
    pub fn push(&mut self, s: &ImuSample, dt: f64) -> Result<NavAccel, InputError> {
        self.follow(s);
        let none = NavAccel {
            up: 0.0,
            horizontal: None,
            attitude: None,
        };
        let Some(kind) = &mut self.kind else {
            return Ok(none);
        };
        let q = match kind {
            Kind::Os { last } => match (s.orientation, *last) {
                (Some(q), _) => {
                    *last = Some((s.t, q));
                    q
                }
                (None, Some((t, q))) if s.t - t <= HOLD_S => q,
                (None, _) => {
                    return Err(InputError::MissingField {
                        t: s.t,
                        field: "orientation",
                    })
                }
            },
            Kind::Madgwick { filter, beta } => {
                let Some(gyro) = s.gyro else {
                    return Err(InputError::MissingField {
                        t: s.t,
                        field: "gyro",
                    });
                };
                match filter {
                    None => {
                        // Start from the attitude the first sample implies, so there is no long
                        // convergence transient from the identity quaternion.
                        if let Some(q0) = attitude_from_vectors(&s.accel, s.mag.as_ref()) {
                            let q_nwu = nwu_to_enu().inverse() * q0;
                            *filter =
                                Some(ahrs::Madgwick::new_with_quat(dt.max(1e-3), *beta, q_nwu));
                        }
                    }
                    Some(f) => {
                        *f.sample_period_mut() = dt;
                        // The crate refuses a zero accelerometer or magnetometer norm; the
                        // attitude is then simply propagated by the previous estimate.
                        let _ = match s.mag {
                            Some(m) => f.update(&gyro, &s.accel, &m),
                            None => f.update_imu(&gyro, &s.accel),
                        };
                    }
                }
                match filter {
                    Some(f) => nwu_to_enu() * f.quat,
                    None => return Ok(none),
                }
            }
            Kind::KfNfa(f) => {
                let Some(gyro) = s.gyro else {
                    return Err(InputError::MissingField {
                        t: s.t,
                        field: "gyro",
                    });
                };
                match f.push(&gyro, &s.accel, s.mag.as_ref(), dt) {
                    Some(q) => q,
                    None => return Ok(none),
                }
            }
            Kind::Gravity { lp } => {
                let g = Vector3::new(
                    lp[0].update(s.accel.x, dt),
                    lp[1].update(s.accel.y, dt),
                    lp[2].update(s.accel.z, dt),
                );
                let n = g.norm();
                if n < 1e-6 {
                    return Ok(none);
                }
                return Ok(NavAccel {
                    up: s.accel.norm() - n,
                    horizontal: None,
                    attitude: None,
                });
            }
        };
        let a = q * s.accel;
        Ok(NavAccel {
            up: a.z - G0,
            horizontal: Some((a.x, a.y)),
            attitude: Some(q),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triad_flat_phone_pointing_north() {
        // Face up, top of the phone towards magnetic north (field points north and down).
        let q = attitude_from_vectors(
            &Vector3::new(0.0, 0.0, G0),
            Some(&Vector3::new(0.0, 20.0, -40.0)),
        )
        .unwrap();
        let y = q * Vector3::y();
        assert!((y - Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-9, "{y}");
    }

    #[test]
    fn madgwick_frame_convention_is_device_to_enu() {
        // Phone face up, top towards east; the field points north and down.
        let accel = Vector3::new(0.0, 0.0, G0);
        // Top (device y) east and face (z) up make device x point south, so north is device −x.
        let mag = Vector3::new(-20.0, 0.0, -40.0);
        let mut o = Orientation::new(OrientationSource::MADGWICK);
        let s = ImuSample {
            t: 0.0,
            accel,
            gyro: Some(Vector3::zeros()),
            mag: Some(mag),
            orientation: None,
        };
        for i in 0..200 {
            o.push(
                &ImuSample {
                    t: i as f64 * 0.01,
                    ..s
                },
                0.01,
            )
            .unwrap();
        }
        let q = o.attitude().unwrap();
        let top = q * Vector3::y();
        assert!(
            (top - Vector3::new(1.0, 0.0, 0.0)).norm() < 0.02,
            "device y should point east, got {top}"
        );
        let face = q * Vector3::z();
        assert!((face - Vector3::z()).norm() < 0.02, "{face}");
    }

    #[test]
    fn gravity_lowpass_gives_vertical_only() {
        let mut o = Orientation::new(OrientationSource::GRAVITY);
        let mut last = None;
        for i in 0..500 {
            let t = i as f64 * 0.01;
            let s = ImuSample::accel_only(t, Vector3::new(0.0, G0, 0.0));
            last = Some(o.push(&s, 0.01).unwrap());
        }
        let n = last.unwrap();
        assert!(n.up.abs() < 1e-9 && n.horizontal.is_none());
    }
}

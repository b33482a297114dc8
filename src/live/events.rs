//! Browser events as the page receives them, in the engine's units and conventions: the one place
//! where the platforms' quirks are converted (see the module documentation of [`crate::live`]),
//! and the inverse, a log as the events a phone would fire.
//! May import: `engine`, `io` (the platform conventions).

use crate::engine::types::{ImuSample, Record};
pub use crate::io::import::Platform;
use nalgebra::{UnitQuaternion, Vector3};
use std::fmt;

/// One `devicemotion` event, fields as the browser gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionEvent {
    /// `event.timeStamp`, ms on the page's clock.
    pub time_stamp_ms: f64,
    /// `accelerationIncludingGravity` (x, y, z), m/s², platform sign.
    pub accel: Option<[f64; 3]>,
    /// `rotationRate` (alpha, beta, gamma), deg/s.
    pub rotation_rate_deg_s: Option<[f64; 3]>,
}

/// One `deviceorientation` or `deviceorientationabsolute` event, fields as the browser gives
/// them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientationEvent {
    /// `event.timeStamp`, ms on the page's clock.
    pub time_stamp_ms: f64,
    /// `alpha`, degrees (W3C).
    pub alpha: Option<f64>,
    /// `beta`, degrees.
    pub beta: Option<f64>,
    /// `gamma`, degrees.
    pub gamma: Option<f64>,
    /// The angles are absolute (a `deviceorientationabsolute` event, or `event.absolute`).
    pub absolute: bool,
    /// iOS's `webkitCompassHeading`, degrees (negative: not calibrated).
    pub compass_heading_deg: Option<f64>,
    /// `screen.orientation.angle`, degrees.
    pub screen_angle_deg: f64,
}

/// A Generic Sensor API reading: `Accelerometer` (m/s², gravity included, the specification's
/// sign on every platform) with the latest `Gyroscope` reading (rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorReading {
    /// The accelerometer's `timestamp`, ms on the page's clock.
    pub timestamp_ms: f64,
    /// Acceleration including gravity, m/s².
    pub accel: [f64; 3],
    /// Angular rate, rad/s.
    pub gyro_rad_s: Option<[f64; 3]>,
}

/// Why an event carries no usable sample.
#[derive(Debug, Clone, PartialEq)]
pub enum EventError {
    /// The event lacks acceleration (the device has no accelerometer, or the browser withholds
    /// it).
    NoAcceleration,
    /// A value is not a finite number.
    NonFinite(&'static str),
}

impl fmt::Display for EventError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EventError::NoAcceleration => write!(f, "the motion event carries no acceleration"),
            EventError::NonFinite(field) => write!(f, "`{field}` is not a finite number"),
        }
    }
}

impl std::error::Error for EventError {}

fn finite(v: &[f64], field: &'static str) -> Result<(), EventError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(EventError::NonFinite(field))
    }
}

/// Converts a `devicemotion` event into a sample at `event.timeStamp` in seconds on the page's
/// clock (see the module documentation of [`crate::live`] for every rule).
pub fn normalise_motion(ev: &MotionEvent, platform: Platform) -> Result<ImuSample, EventError> {
    finite(&[ev.time_stamp_ms], "timeStamp")?;
    let a = ev.accel.ok_or(EventError::NoAcceleration)?;
    finite(&a, "accelerationIncludingGravity")?;
    let gyro = match ev.rotation_rate_deg_s {
        Some(r) => {
            finite(&r, "rotationRate")?;
            Some(Vector3::new(r[0], r[1], r[2]) * (std::f64::consts::PI / 180.0))
        }
        None => None,
    };
    Ok(ImuSample {
        t: ev.time_stamp_ms * 1e-3,
        accel: platform.to_android(Vector3::new(a[0], a[1], a[2])),
        gyro,
        mag: None,
        orientation: None,
    })
}

/// Checks a Generic Sensor reading and gives its sample's acceleration and angular rate.
pub fn sensor_sample(
    r: &SensorReading,
) -> Result<(Vector3<f64>, Option<Vector3<f64>>), EventError> {
    let a = r.accel;
    finite(&[r.timestamp_ms, a[0], a[1], a[2]], "Accelerometer")?;
    if let Some(g) = r.gyro_rad_s {
        finite(&g, "Gyroscope")?;
    }
    Ok((Vector3::from(a), r.gyro_rad_s.map(Vector3::from)))
}

impl OrientationEvent {
    /// A `deviceorientationabsolute` event with its angles, degrees.
    pub fn absolute(time_stamp_ms: f64, alpha: f64, beta: f64, gamma: f64) -> Self {
        OrientationEvent {
            time_stamp_ms,
            alpha: Some(alpha),
            beta: Some(beta),
            gamma: Some(gamma),
            absolute: true,
            compass_heading_deg: None,
            screen_angle_deg: 0.0,
        }
    }

    /// The device → earth attitude the event gives and whether it is absolute: from iOS's
    /// calibrated compass heading when the event carries one, else from `alpha`; `None` when it
    /// carries neither (a device without orientation sensors).
    pub fn attitude(&self) -> Result<Option<(UnitQuaternion<f64>, bool)>, EventError> {
        let compass = self.compass_heading_deg.filter(|h| *h >= 0.0);
        let (alpha, absolute) = match (compass, self.alpha) {
            (Some(h), _) => (ios_compass_alpha(h, self.screen_angle_deg), true),
            (None, Some(a)) => (a, self.absolute),
            (None, None) => return Ok(None),
        };
        let (beta, gamma) = (
            self.beta.unwrap_or(f64::NAN),
            self.gamma.unwrap_or(f64::NAN),
        );
        finite(
            &[self.time_stamp_ms, alpha, beta, gamma],
            "deviceorientation",
        )?;
        Ok(Some((orientation_quaternion(alpha, beta, gamma), absolute)))
    }
}

/// The device → earth attitude of a `deviceorientation` event (degrees), R = Rz(α)·Rx(β)·Ry(γ).
pub fn orientation_quaternion(alpha: f64, beta: f64, gamma: f64) -> UnitQuaternion<f64> {
    let d = std::f64::consts::PI / 180.0;
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), alpha * d)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), beta * d)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), gamma * d)
}

/// The W3C angles (degrees) of a device → earth attitude: the inverse of
/// [`orientation_quaternion`], with β in [−90°, 90°] (an equivalent decomposition to the
/// specification's β in [−180°, 180°), γ in [−90°, 90°)).
pub fn orientation_angles(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    let r = q.to_rotation_matrix();
    let m = r.matrix();
    let beta = libm::asin(m[(2, 1)].clamp(-1.0, 1.0));
    let alpha = libm::atan2(-m[(0, 1)], m[(1, 1)]);
    let gamma = libm::atan2(-m[(2, 0)], m[(2, 2)]);
    let d = 180.0 / std::f64::consts::PI;
    (alpha * d, beta * d, gamma * d)
}

/// The `alpha` (degrees, W3C convention) of an iOS `deviceorientation` event from its
/// `webkitCompassHeading`. Safari's `alpha` is relative to an arbitrary start; the compass
/// heading is degrees clockwise from magnetic north of the top of the *interface*, so the
/// heading of the device's top adds the screen orientation angle (`screen.orientation.angle`,
/// 90 when the interface is turned a quarter counter-clockwise from portrait). The W3C `alpha`
/// grows counter-clockwise: α = 360° − heading. Not verified on a real iPhone here.
pub fn ios_compass_alpha(compass_heading_deg: f64, screen_angle_deg: f64) -> f64 {
    (360.0 - (compass_heading_deg + screen_angle_deg)).rem_euclid(360.0)
}

/// One browser event of a simulated walk, as the page receives it (see [`browser_events`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum BrowserEvent {
    /// A `devicemotion` event.
    Motion {
        /// `timeStamp`, ms.
        t: f64,
        /// `accelerationIncludingGravity`, the platform's sign.
        x: f64,
        /// See `x`.
        y: f64,
        /// See `x`.
        z: f64,
        /// `rotationRate`, deg/s.
        alpha: Option<f64>,
        /// See `alpha`.
        beta: Option<f64>,
        /// See `alpha`.
        gamma: Option<f64>,
        /// `interval` in the platform's unit.
        interval: f64,
    },
    /// A `deviceorientationabsolute` event (absolute `deviceorientation` on iOS).
    Orientation {
        /// `timeStamp`, ms.
        t: f64,
        /// Degrees.
        alpha: f64,
        /// Degrees.
        beta: f64,
        /// Degrees.
        gamma: f64,
    },
}

/// The samples of a log (a simulated walk) as the browser events a phone of `platform` would
/// fire: the inverse of [`normalise_motion`] and [`orientation_quaternion`]. The end-to-end
/// tests dispatch these on the live page.
pub fn browser_events(records: &[Record], platform: Platform) -> Vec<BrowserEvent> {
    let deg = 180.0 / std::f64::consts::PI;
    let mut out = Vec::new();
    let mut last = None;
    for r in records {
        let Record::Imu(s) = r else { continue };
        let t = s.t * 1e3;
        if let Some(q) = s.orientation {
            let (alpha, beta, gamma) = orientation_angles(&q);
            out.push(BrowserEvent::Orientation {
                t,
                alpha: alpha.rem_euclid(360.0),
                beta,
                gamma,
            });
        }
        let a = platform.to_android(s.accel);
        let interval_ms = last.map_or(10.0, |l| t - l);
        last = Some(t);
        out.push(BrowserEvent::Motion {
            t,
            x: a.x,
            y: a.y,
            z: a.z,
            alpha: s.gyro.map(|g| g.x * deg),
            beta: s.gyro.map(|g| g.y * deg),
            gamma: s.gyro.map(|g| g.z * deg),
            interval: match platform {
                Platform::Ios => interval_ms * 1e-3,
                Platform::Android => interval_ms,
            },
        });
    }
    out
}

/// Whether the browser follows iOS's conventions for motion events: every browser on iOS is
/// WebKit. Told from the user agent (iPadOS reports a Mac, with a touch screen:
/// `max_touch_points` > 1), not from `DeviceMotionEvent.requestPermission`, which recent
/// Chromium has too.
pub fn is_ios(user_agent: &str, max_touch_points: f64) -> bool {
    ["iPhone", "iPad", "iPod"]
        .iter()
        .any(|d| user_agent.contains(d))
        || (user_agent.contains("Macintosh") && max_touch_points > 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ios_and_android_events_give_the_same_sample() {
        let android = MotionEvent {
            time_stamp_ms: 1500.0,
            accel: Some([0.3, -0.2, 9.81]),
            rotation_rate_deg_s: Some([57.2958, 0.0, -28.6479]),
        };
        let ios = MotionEvent {
            accel: Some([-0.3, 0.2, -9.81]),
            ..android
        };
        let a = normalise_motion(&android, Platform::Android).unwrap();
        let i = normalise_motion(&ios, Platform::Ios).unwrap();
        assert_eq!(a, i);
        assert_eq!(a.t, 1.5);
        // alpha is about x, gamma about z, in deg/s.
        let g = a.gyro.unwrap();
        assert!((g.x - 1.0).abs() < 1e-5 && g.y == 0.0 && (g.z + 0.5).abs() < 1e-5);
        assert_eq!(
            normalise_motion(
                &MotionEvent {
                    accel: None,
                    ..android
                },
                Platform::Android
            ),
            Err(EventError::NoAcceleration)
        );
        assert!(normalise_motion(
            &MotionEvent {
                accel: Some([f64::NAN, 0.0, 9.8]),
                ..android
            },
            Platform::Android
        )
        .is_err());
    }

    #[test]
    fn angles_round_trip() {
        for (a, b, g) in [(10.0, 20.0, 30.0), (250.0, -60.0, 80.0), (0.0, 89.0, -45.0)] {
            let q = orientation_quaternion(a, b, g);
            let (a2, b2, g2) = orientation_angles(&q);
            assert!(q.angle_to(&orientation_quaternion(a2, b2, g2)) < 1e-9);
        }
    }

    #[test]
    fn orientation_angles_follow_the_specification() {
        // Flat, face up, alpha 90°: the top of the device points west.
        let q = orientation_quaternion(90.0, 0.0, 0.0);
        let top = q * Vector3::y();
        assert!((top - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12);
        // Upright (beta 90°): the screen faces south, the top points up.
        let q = orientation_quaternion(0.0, 90.0, 0.0);
        assert!((q * Vector3::y() - Vector3::z()).norm() < 1e-12);
        assert!((q * Vector3::z() - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-12);
        // Rolled right (gamma 90°): the screen faces east, the device's x axis points down.
        let q = orientation_quaternion(0.0, 0.0, 90.0);
        assert!((q * Vector3::x() - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12);
    }

    #[test]
    fn ios_is_told_from_the_user_agent() {
        let iphone = "Mozilla/5.0 (iPhone; CPU iPhone OS 17_0 like Mac OS X) AppleWebKit/605.1.15";
        let mac = "Mozilla/5.0 (Macintosh; Intel Mac OS X 10_15_7) AppleWebKit/605.1.15";
        let android = "Mozilla/5.0 (Linux; Android 14; Pixel 8) AppleWebKit/537.36 Chrome/120";
        assert!(is_ios(iphone, 5.0));
        assert!(is_ios(mac, 5.0), "an iPad asking for the desktop site");
        assert!(!is_ios(mac, 0.0), "a Mac");
        assert!(!is_ios(android, 5.0));
    }
}

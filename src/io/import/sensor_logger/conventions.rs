//! Sensor Logger's iOS and Android conventions: which platform a recording came from, and its
//! units, signs and frames turned into the import's one convention. May import: `engine` and `io`.

use super::Raw;
use crate::engine::orientation::{G0, HOLD_S};
use crate::io::import::common::{
    add_warnings, core_motion_to_enu, drop_non_finite, pair_nearest, warn_count,
};
use crate::io::import::{file_error, Log, Platform, Streams};
use crate::io::ParseError;
use nalgebra::{UnitQuaternion, Vector3};

impl Raw {
    /// Settles units, signs and frames and builds the log.
    pub(super) fn finish(
        mut self,
        mut log: Log,
        source_for_errors: &str,
    ) -> Result<Log, ParseError> {
        self.sort_by_time();
        let accel_file = if self.accel_file.is_empty() {
            source_for_errors.to_string()
        } else {
            self.accel_file.clone()
        };
        self.check_acceleration(&accel_file)?;
        let (scale, platform) = self.units_and_platform();
        log.platform = platform;
        // Conventions of the values as written.
        let ios_frames = platform == Some(Platform::Ios) && !self.standardised;
        let sign = if ios_frames { -scale } else { scale };
        let (mut s, unpaired) = self.streams(sign, ios_frames);
        let dropped = drop_non_finite(&mut s);
        if s.accel.is_empty() {
            return Err(file_error(
                &accel_file,
                0,
                "no usable accelerometer samples (no gravity sample within 0.2 s of any)",
            ));
        }
        log.records = s.into_records();
        add_warnings(&mut log, std::mem::take(&mut self.warnings));
        warn_count(
            &mut log,
            unpaired,
            file_error(
                &accel_file,
                0,
                format!(
                    "{unpaired} accelerometer sample(s) without a gravity sample within {HOLD_S} s, \
                     skipped"
                ),
            ),
        );
        warn_count(
            &mut log,
            dropped,
            file_error(
                source_for_errors,
                0,
                format!("{dropped} sample(s) overflowed to a non-finite value, skipped"),
            ),
        );
        Ok(log)
    }

    /// Puts every sensor's samples in time order.
    fn sort_by_time(&mut self) {
        for v in [
            &mut self.accel,
            &mut self.gravity,
            &mut self.total,
            &mut self.gyro,
            &mut self.mag,
        ] {
            crate::engine::sort::sort_by(v, |a, b| a.0.total_cmp(&b.0));
        }
        crate::engine::sort::sort_by(&mut self.orientation, |a, b| a.0.total_cmp(&b.0));
    }

    /// Whether the recording has acceleration with gravity, or the parts to make it; if not,
    /// why not (naming `accel_file`, or the gravity file's own problem).
    fn check_acceleration(&self, accel_file: &str) -> Result<(), ParseError> {
        if self.total.is_empty() && self.accel.is_empty() {
            return Err(file_error(
                accel_file,
                0,
                "no accelerometer samples (Accelerometer or TotalAcceleration)",
            ));
        }
        if self.total.is_empty() && self.gravity.is_empty() {
            let gravity_problem = self
                .warnings
                .find(|w| w.column.is_none() && w.file.to_lowercase().ends_with("gravity.csv"));
            if let Some(e) = gravity_problem {
                return Err(e.clone());
            }
            return Err(file_error(
                accel_file,
                0,
                "Accelerometer has gravity removed, and there is no Gravity or TotalAcceleration \
                 to restore it",
            ));
        }
        Ok(())
    }

    /// The factor of acceleration to m/s² (g or m/s², from the size of gravity) and the
    /// platform ([`decide_platform`]).
    fn units_and_platform(&self) -> (f64, Option<Platform>) {
        let reference = if self.gravity.is_empty() {
            &self.total
        } else {
            &self.gravity
        };
        let mean_norm =
            reference.iter().map(|(_, v)| v.norm()).sum::<f64>() / reference.len().max(1) as f64;
        let scale = if mean_norm < 3.0 { G0 } else { 1.0 };
        let platform = decide_platform(
            self.platform,
            !self.total.is_empty(),
            scale != 1.0,
            &self.gravity,
            &self.orientation,
            reference,
        );
        (scale, platform)
    }

    /// The streams in the import's convention: acceleration with gravity times `sign` (total
    /// acceleration, or acceleration paired with the nearest gravity), attitudes turned to ENU
    /// when `ios_frames`. Also how many acceleration samples had no gravity to pair with.
    fn streams(&mut self, sign: f64, ios_frames: bool) -> (Streams, u64) {
        let mut s = Streams::default();
        let mut unpaired = 0u64;
        if !self.total.is_empty() {
            s.accel = self.total.iter().map(|&(t, v)| (t, v * sign)).collect();
        } else {
            let (paired, n) =
                pair_nearest(&self.accel, &self.gravity, HOLD_S, |a, g| (a + g) * sign);
            s.accel = paired;
            unpaired = n;
        }
        s.gyro = std::mem::take(&mut self.gyro);
        s.mag = std::mem::take(&mut self.mag);
        let to_enu = if ios_frames {
            core_motion_to_enu()
        } else {
            UnitQuaternion::identity()
        };
        s.orientation = self
            .orientation
            .iter()
            .map(|&(t, q)| (t, to_enu * q))
            .collect();
        s.fixes = std::mem::take(&mut self.fixes);
        s.pressure = std::mem::take(&mut self.pressure);
        (s, unpaired)
    }
}

/// Decides the platform of a Sensor Logger recording, in this order:
/// 1. `platform` in `Metadata.csv` (`ios` or `android`) when given;
/// 2. a `TotalAcceleration.csv` exists: Android (iOS has no such file);
/// 3. acceleration in g (mean |gravity| < 3): iOS (Android always writes m/s²);
/// 4. gravity and orientation both present: gravity turned into the reference frame by the
///    orientation points up on Android (the reading is the reaction to gravity) and down on iOS
///    (Core Motion's gravity vector), in both cases whatever the pose, because both reference
///    frames have z up. The mean of the vertical component of the unit gravity vector decides
///    when it exceeds 0.5 in size;
/// 5. otherwise [`Platform::guess`] on the mean gravity (or total acceleration): the sign on the
///    axis with the largest mean, positive meaning Android. This last rule fails for a phone
///    carried upside down, which rules 1–4 do not depend on.
///
/// `None` only when nothing is left to decide from.
pub fn decide_platform(
    metadata: Option<Platform>,
    has_total: bool,
    in_g: bool,
    gravity: &[(f64, Vector3<f64>)],
    orientation: &[(f64, UnitQuaternion<f64>)],
    reference: &[(f64, Vector3<f64>)],
) -> Option<Platform> {
    if metadata.is_some() {
        return metadata;
    }
    if has_total {
        return Some(Platform::Android);
    }
    if in_g {
        return Some(Platform::Ios);
    }
    if !gravity.is_empty() && !orientation.is_empty() {
        // The up component of each gravity sample's direction turned by the nearest attitude
        // (none for a gravity sample of no usable size).
        let (up, _) = pair_nearest(gravity, orientation, HOLD_S, |g, q| {
            let norm = g.norm();
            (norm > 0.0 && norm.is_finite()).then(|| (q * g).z / norm)
        });
        let (mut sum, mut n) = (0.0, 0usize);
        for z in up.iter().filter_map(|(_, z)| *z) {
            sum += z;
            n += 1;
        }
        if n > 0 {
            let mean = sum / n as f64;
            if mean > 0.5 {
                return Some(Platform::Android);
            }
            if mean < -0.5 {
                return Some(Platform::Ios);
            }
        }
    }
    if reference.is_empty() {
        return None;
    }
    let mean = reference
        .iter()
        .fold(Vector3::zeros(), |acc, (_, v)| acc + v)
        / reference.len() as f64;
    Platform::guess(mean)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Quaternion;

    #[test]
    fn ios_attitude_to_enu() {
        // Face up, top pointing north: the device's x (right) points east, which is −y of
        // Core Motion's (north, west, up) frame, so the attitude is a −90° turn about z.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q_ios = UnitQuaternion::new_unchecked(Quaternion::new(h, 0.0, 0.0, -h));
        let top = q_ios * Vector3::y();
        assert!(
            (top - Vector3::x()).norm() < 1e-12,
            "top points to ref x = north"
        );
        let q = core_motion_to_enu() * q_ios;
        assert!(q.angle() < 1e-12, "device frame = ENU: {q:?}");
    }

    #[test]
    fn platform_from_gravity_and_orientation() {
        // A phone upside down in a pocket (top pointing down): Android gravity reads −9.8 on y,
        // which the axis rule would take for iOS; the orientation settles it.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // Device → ENU: top (y) pointing down = rotation of −90° about x.
        let q = UnitQuaternion::new_unchecked(Quaternion::new(h, -h, 0.0, 0.0));
        let g = [(0.0, Vector3::new(0.0, -9.8, 0.0))];
        let o = [(0.0, q)];
        assert_eq!(
            decide_platform(None, false, false, &g, &o, &g),
            Some(Platform::Android)
        );
        let g_ios = [(0.0, Vector3::new(0.0, 9.8, 0.0))];
        assert_eq!(
            decide_platform(None, false, false, &g_ios, &o, &g_ios),
            Some(Platform::Ios)
        );
        assert_eq!(
            decide_platform(None, false, false, &g, &[], &g),
            Some(Platform::Ios),
            "the axis rule alone gets this pose wrong"
        );
    }
}

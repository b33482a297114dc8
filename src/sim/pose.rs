//! How the phone sits in the front trouser pocket: eight poses (upright or upside down, screen
//! facing out of the thigh or towards it, aligned with the thigh or turned about the screen
//! normal) in the right or the left pocket.
//! May import: `engine` and `io`.
//!
//! # Frames
//! Body frame: x forward, y left, z up (the thigh swings about y). Device frame: x right, y top
//! of the screen, z out of the screen. A mount is the rotation taking device coordinates to
//! body coordinates with the thigh vertical (standing). The phone's long axis (device y) lies
//! along the thigh, its top towards the hip (upright) or the knee (upside down); its screen
//! normal (device z) points away from the thigh (out) or into it (in); a turned pose is then
//! rotated by [`TURN_DEG`] about the screen normal, as a phone that slid sideways in the pocket.
//! [`PocketPose::UprightOut`] in the right pocket is the simulator's historic mount (device x
//! forward, y up, z to the right).

use nalgebra::{Matrix3, Vector3};

/// How far a turned pose is rotated about the screen normal, degrees (counter-clockwise seen
/// from the screen side).
pub const TURN_DEG: f64 = 25.0;

/// The phone's pose in the pocket.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PocketPose {
    /// Top towards the hip, screen out of the thigh (the historic mount).
    #[default]
    UprightOut,
    /// Top towards the hip, screen towards the thigh.
    UprightIn,
    /// Top towards the knee, screen out of the thigh.
    UpsideDownOut,
    /// Top towards the knee, screen towards the thigh.
    UpsideDownIn,
    /// [`PocketPose::UprightOut`] turned by [`TURN_DEG`] about the screen normal.
    UprightOutTurned,
    /// [`PocketPose::UprightIn`] turned by [`TURN_DEG`] about the screen normal.
    UprightInTurned,
    /// [`PocketPose::UpsideDownOut`] turned by [`TURN_DEG`] about the screen normal.
    UpsideDownOutTurned,
    /// [`PocketPose::UpsideDownIn`] turned by [`TURN_DEG`] about the screen normal.
    UpsideDownInTurned,
}

impl PocketPose {
    /// Every pose, in the order above.
    pub const ALL: [PocketPose; 8] = [
        PocketPose::UprightOut,
        PocketPose::UprightIn,
        PocketPose::UpsideDownOut,
        PocketPose::UpsideDownIn,
        PocketPose::UprightOutTurned,
        PocketPose::UprightInTurned,
        PocketPose::UpsideDownOutTurned,
        PocketPose::UpsideDownInTurned,
    ];

    /// Lower-case name.
    pub fn as_str(self) -> &'static str {
        match self {
            PocketPose::UprightOut => "upright_out",
            PocketPose::UprightIn => "upright_in",
            PocketPose::UpsideDownOut => "upside_down_out",
            PocketPose::UpsideDownIn => "upside_down_in",
            PocketPose::UprightOutTurned => "upright_out_turned",
            PocketPose::UprightInTurned => "upright_in_turned",
            PocketPose::UpsideDownOutTurned => "upside_down_out_turned",
            PocketPose::UpsideDownInTurned => "upside_down_in_turned",
        }
    }

    /// (top towards the hip, screen out of the thigh, turned).
    fn parts(self) -> (bool, bool, bool) {
        match self {
            PocketPose::UprightOut => (true, true, false),
            PocketPose::UprightIn => (true, false, false),
            PocketPose::UpsideDownOut => (false, true, false),
            PocketPose::UpsideDownIn => (false, false, false),
            PocketPose::UprightOutTurned => (true, true, true),
            PocketPose::UprightInTurned => (true, false, true),
            PocketPose::UpsideDownOutTurned => (false, true, true),
            PocketPose::UpsideDownInTurned => (false, false, true),
        }
    }

    /// The mount (device → body, thigh vertical) in the right pocket or the left one.
    pub fn mount(self, left_pocket: bool) -> Matrix3<f64> {
        let (upright, out, turned) = self.parts();
        let y = Vector3::new(0.0, 0.0, if upright { 1.0 } else { -1.0 });
        // Out of the right thigh is the body's −y; out of the left one its +y.
        let outward = if left_pocket { 1.0 } else { -1.0 };
        let z = Vector3::new(0.0, if out { outward } else { -outward }, 0.0);
        let x = y.cross(&z);
        // `+ 0.0` turns the cross product's −0.0 into +0.0: the historic mount, bit for bit.
        let base = Matrix3::from_columns(&[x, y, z]).map(|v| v + 0.0);
        if turned {
            let (s, c) = libm::sincos(TURN_DEG.to_radians());
            base * Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
        } else {
            base
        }
    }
}

/// The body's lateral axis to the walker's right, in device coordinates, for a mount (device →
/// body): thigh flexion (knee forward) is a positive rotation about it. This is the axis a
/// swing-axis finder should recover from the gyroscope (up to sign).
pub fn flexion_axis_device(mount: &Matrix3<f64>) -> Vector3<f64> {
    mount.transpose() * Vector3::new(0.0, -1.0, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_are_rotations_and_the_first_is_the_historic_mount() {
        let historic = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
        let bits = |m: Matrix3<f64>| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(PocketPose::UprightOut.mount(false)), bits(historic));
        for p in PocketPose::ALL {
            for left in [false, true] {
                let m = p.mount(left);
                assert!((m.transpose() * m - Matrix3::identity()).norm() < 1e-12);
                assert!((m.determinant() - 1.0).abs() < 1e-12, "{}", p.as_str());
            }
        }
        // Screen in, upright: the screen normal points to the body's left (into the right thigh).
        let m = PocketPose::UprightIn.mount(false);
        assert_eq!(m.column(2).into_owned(), Vector3::new(0.0, 1.0, 0.0));
    }
}

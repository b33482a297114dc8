//! An Oxford Step Counter trace folder of a simulated walk, with the true foot contacts, as
//! [`crate::io::import::oxford`] reads it. May import: `engine` and `io`.

use super::{fixed, Walk, SWING_SHARE};
use crate::sim::Simulation;
use std::fmt::Write as _;

impl Walk<'_> {
    /// An Oxford Step Counter trace folder, `Pixel_Sim_Hard_FrontPocket_1/` (phone, walker,
    /// surface, placement, take): `accelerometer.csv` (`ns since boot,3,x,y,z`, m/s², 6
    /// decimals) and `stepcounter.csv` (`ns since boot,left,right`, one row per accelerometer
    /// sample; see the module documentation for the contact model).
    pub(super) fn oxford(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let imu = self.imu();
        let dir = "Pixel_Sim_Hard_FrontPocket_1";
        // Each foot's swing windows [lift, land), feet alternating over the true steps.
        let mut windows: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
        for (i, st) in sim.truth.steps.iter().enumerate() {
            if !(st.t.is_finite() && st.freq_hz > 0.0) {
                continue;
            }
            let swing = SWING_SHARE * 2.0 / st.freq_hz;
            windows[i % 2].push((st.t - swing, st.t));
        }
        let mut next = [0usize; 2];
        let mut accel = String::new();
        let mut steps = String::new();
        for s in &imu {
            let ns = self.boot_ns(s.t);
            let _ = writeln!(
                accel,
                "{ns},3,{},{},{}",
                fixed(s.accel.x, 6),
                fixed(s.accel.y, 6),
                fixed(s.accel.z, 6)
            );
            let mut contact = [1u8; 2];
            for foot in 0..2 {
                let w = &windows[foot];
                while next[foot] < w.len() && w[next[foot]].1 <= s.t {
                    next[foot] += 1;
                }
                if w.get(next[foot]).is_some_and(|&(lift, _)| lift <= s.t) {
                    contact[foot] = 0;
                }
            }
            let _ = writeln!(steps, "{ns},{},{}", contact[0], contact[1]);
        }
        vec![
            (format!("{dir}/accelerometer.csv"), accel.into_bytes()),
            (format!("{dir}/stepcounter.csv"), steps.into_bytes()),
        ]
    }
}

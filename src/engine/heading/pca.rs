//! PCA heading baseline (Steinhoff & Schiele 2010, as cited by Basso 2016 §I): the principal axis
//! of the horizontal acceleration over a sliding window (2 s by default), computed at each step.
//! May import: the rest of `engine`.
//!
//! For the 2×2 covariance [[C_ee, C_en], [C_en, C_nn]] the principal axis is at angle
//! ½·atan2(2C_en, C_ee − C_nn) from east. The forward sense along the axis is resolved with the
//! same kinematic rule as the Fourier methods, here in the time domain:
//! sign of ∫ (a_h·u) d a_up, accumulated as Σ ½(a_u,i + a_u,i−1)(a_up,i − a_up,i−1).

use super::NavSample;
use crate::engine::math::heading_of;
use std::collections::VecDeque;

/// Heading of the principal axis of the horizontal acceleration over [t0, t1], radians from north.
pub fn heading(buf: &VecDeque<NavSample>, t0: f64, t1: f64) -> Option<f64> {
    let start = buf.partition_point(|s| s.t < t0);
    let end = buf.partition_point(|s| s.t <= t1);
    let win = buf.range(start..end);
    let n = (end.saturating_sub(start)) as f64;
    if n < 8.0 {
        return None;
    }
    let (mut se, mut sn) = (0.0, 0.0);
    for s in win.clone() {
        se += s.e;
        sn += s.n;
    }
    let (me, mn) = (se / n, sn / n);
    let (mut cee, mut cnn, mut cen) = (0.0, 0.0, 0.0);
    for s in win.clone() {
        let (de, dn) = (s.e - me, s.n - mn);
        cee += de * de;
        cnn += dn * dn;
        cen += de * dn;
    }
    if !(cee + cnn > 1e-12) {
        return None;
    }
    let ang = 0.5 * libm::atan2(2.0 * cen, cee - cnn);
    let (ue, un) = (libm::cos(ang), libm::sin(ang));
    let mut corr = 0.0;
    let mut prev: Option<(f64, f64)> = None;
    for s in win {
        let au = (s.e - me) * ue + (s.n - mn) * un;
        if let Some((pu, pup)) = prev {
            corr += 0.5 * (au + pu) * (s.up - pup);
        }
        prev = Some((au, s.up));
    }
    let sign = if corr >= 0.0 { 1.0 } else { -1.0 };
    Some(heading_of(sign * ue, sign * un))
}

//! The simulated GNSS receiver: fixes of the true path, with the noise their reported accuracy
//! promises, outliers and outages; on request the real phone's error shapes ([`GnssErrors`]).
//! May import: `engine` and `io`.

use super::gnss_errors::{ErrorState, GnssErrors};
use super::{Rng, Scenario, Truth};
use crate::engine::Record;
use std::f64::consts::TAU;

/// The GNSS receiver: fixes of the true path with the noise their reported accuracy promises,
/// outliers that do not, and outages.
#[derive(Debug, Clone, PartialEq)]
pub struct GnssSim {
    /// Where the walk starts, WGS84 degrees, and the height, m.
    pub origin: (f64, f64, f64),
    /// Fixes per second.
    pub rate_hz: f64,
    /// Reported accuracy (68 % radius), m: it wanders between these two values (as a receiver's
    /// does under changing sky view), and each fix's error is drawn from the circular normal
    /// distribution that accuracy describes.
    pub accuracy_m: (f64, f64),
    /// Share of fixes that are outliers: displaced by a distance drawn uniformly from
    /// `outlier_m` in a random direction, with an ordinary reported accuracy.
    pub outlier_share: f64,
    /// Outlier displacement range, m.
    pub outlier_m: (f64, f64),
    /// Intervals without any fix, (start, end) s.
    pub outages: Vec<(f64, f64)>,
    /// Model magnetic north: the OS attitude and the magnetometer point to magnetic north,
    /// turned by the World Magnetic Model's declination at the origin.
    pub magnetic_north: bool,
    /// The real phone's error shapes (all off by default: the error is white, as the accuracy
    /// says).
    pub errors: GnssErrors,
}

impl Default for GnssSim {
    fn default() -> Self {
        GnssSim {
            origin: (43.7696, 11.2558, 50.0),
            rate_hz: 1.0,
            accuracy_m: (3.0, 12.0),
            outlier_share: 0.0,
            outlier_m: (30.0, 80.0),
            outages: Vec::new(),
            magnetic_north: true,
            errors: GnssErrors::default(),
        }
    }
}

impl Scenario {
    /// The receiver's fixes along the true path (times already offset).
    pub(super) fn fixes(&self, g: &GnssSim, truth: &Truth) -> Vec<Record> {
        let mut rng = Rng(self.seed ^ 0x6E55_F1E5);
        let mut shapes = g
            .errors
            .any()
            .then(|| ErrorState::new(&g.errors, truth, self.seed));
        let frame = crate::engine::geo::LocalFrame::new(g.origin.0, g.origin.1, g.origin.2);
        let mut out = Vec::new();
        let dur = self.duration_s();
        let mut t = 0.5 / g.rate_hz;
        while t <= dur {
            let tt = t + self.clock_offset_s;
            if !g.outages.iter().any(|&(a, b)| tt >= a && tt < b) {
                let (e, n) = truth.position_at(tt);
                // The reported accuracy wanders slowly between its bounds.
                let w = 0.5 + 0.5 * libm::sin(TAU * t / 97.0) * libm::cos(TAU * t / 31.0);
                let mut acc = g.accuracy_m.0 + (g.accuracy_m.1 - g.accuracy_m.0) * w;
                let sigma = acc / crate::engine::fusion::ACCURACY_PER_SIGMA;
                let white = g.errors.white_sigma(sigma);
                let (mut de, mut dn) = (white * rng.normal(), white * rng.normal());
                if rng.uniform() < g.outlier_share {
                    let d = g.outlier_m.0 + (g.outlier_m.1 - g.outlier_m.0) * rng.uniform();
                    let (s, c) = libm::sincos(TAU * rng.uniform());
                    de += d * s;
                    dn += d * c;
                }
                let mut at = [e + de, n + dn, 0.0];
                let mut speed_mps = None;
                if let Some(st) = shapes.as_mut() {
                    let sh = st.at(tt, sigma);
                    match sh.replace {
                        Some(p) => at = [p.0, p.1, 0.0],
                        None => {
                            at[0] = sh.truth.0 + sh.error.0 + de;
                            at[1] = sh.truth.1 + sh.error.1 + dn;
                            st.reported((at[0], at[1]));
                        }
                    }
                    acc = sh.accuracy_m.unwrap_or(acc);
                    speed_mps = sh.speed_mps;
                }
                let (lat, lon, h) = frame.to_geodetic(at);
                out.push(Record::Gnss(crate::engine::types::GnssFix {
                    t: tt,
                    lat_deg: lat,
                    lon_deg: lon,
                    h_accuracy_m: acc,
                    altitude_m: Some(h),
                    speed_mps,
                    bearing_deg: None,
                }));
            }
            t += 1.0 / g.rate_hz;
        }
        out
    }
}

/// Merges two time-ordered record lists (a stable merge: at equal times `a` comes first).
pub(super) fn merge_in_time(a: Vec<Record>, b: Vec<Record>) -> Vec<Record> {
    let time = Record::t;
    let mut out = Vec::with_capacity(a.len() + b.len());
    let mut b = b.into_iter().peekable();
    for r in a {
        while let Some(x) = b.next_if(|x| time(x) < time(&r)) {
            out.push(x);
        }
        out.push(r);
    }
    out.extend(b);
    out
}

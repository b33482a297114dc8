//! The track's geodetic origin, chosen so that it is not an outlier: phones often open a log
//! with a cached fix from where the receiver last was, kilometres away, with an ordinary
//! reported accuracy. The origin is the first of [`FusionConfig::consensus_n`] fixes that
//! agree with each other (ours).
//! May import: the rest of `engine`.

use super::config::{FusionConfig, ACCURACY_PER_SIGMA};
use crate::engine::geo::LocalFrame;
use crate::engine::types::GnssFix;

/// The fastest a pedestrian moves between two fixes that agree, m/s.
pub const MAX_SPEED_MPS: f64 = 3.0;

/// Candidates for the origin, waiting for agreement.
#[derive(Debug, Clone, Default)]
pub struct OriginVote {
    candidates: Vec<GnssFix>,
    /// Candidates dropped as disagreeing with the rest.
    pub dropped: u64,
}

impl OriginVote {
    /// Offers a usable fix. Returns the agreeing fixes, oldest first, once there are enough:
    /// two fixes agree when they are within the gate for their summed variances of each other,
    /// plus the distance a walker covers between them at [`MAX_SPEED_MPS`]. At most twice the
    /// needed number wait; the oldest is dropped beyond that.
    pub fn push(&mut self, cfg: &FusionConfig, f: &GnssFix) -> Option<Vec<GnssFix>> {
        let need = cfg.consensus_n as usize;
        self.candidates.push(*f);
        let frame = LocalFrame::new(f.lat_deg, f.lon_deg, 0.0);
        let en: Vec<(f64, f64)> = self.candidates.iter().map(|c| frame.en_of_fix(c)).collect();
        let agree = |i: usize, j: usize| {
            let (a, b) = (&self.candidates[i], &self.candidates[j]);
            let var = (a.h_accuracy_m * a.h_accuracy_m + b.h_accuracy_m * b.h_accuracy_m)
                / (ACCURACY_PER_SIGMA * ACCURACY_PER_SIGMA);
            let reach = (cfg.gate_chi2 * var).sqrt() + MAX_SPEED_MPS * (a.t - b.t).abs();
            libm::hypot(en[i].0 - en[j].0, en[i].1 - en[j].1) <= reach
        };
        let n = self.candidates.len();
        let best = largest_agreeing_group(n, agree);
        if best.len() >= need {
            let group = best.iter().map(|&i| self.candidates[i]).collect();
            self.dropped += (n - best.len()) as u64;
            self.candidates.clear();
            return Some(group);
        }
        if n >= 2 * need {
            self.candidates.remove(0);
            self.dropped += 1;
        }
        None
    }
}

/// The largest group of items `0..n` that all agree with one of them (its index first among
/// equals): the fixes held for a consensus, and the candidates for the origin.
pub(super) fn largest_agreeing_group(n: usize, agree: impl Fn(usize, usize) -> bool) -> Vec<usize> {
    (0..n)
        .map(|i| (0..n).filter(|&j| agree(i, j)).collect::<Vec<_>>())
        .max_by_key(|g| g.len())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fix(t: f64, lat: f64, lon: f64) -> GnssFix {
        GnssFix {
            t,
            lat_deg: lat,
            lon_deg: lon,
            h_accuracy_m: 5.0,
            altitude_m: None,
            speed_mps: None,
            bearing_deg: None,
        }
    }

    #[test]
    fn a_stale_first_fix_is_not_the_origin() {
        let cfg = FusionConfig::default();
        let mut v = OriginVote::default();
        // A cached fix 3 km north, then the walker's fixes a metre apart.
        assert!(v.push(&cfg, &fix(0.0, 43.80, 11.25)).is_none());
        assert!(v.push(&cfg, &fix(1.0, 43.773, 11.25)).is_none());
        assert!(v.push(&cfg, &fix(2.0, 43.77301, 11.25)).is_none());
        let g = v.push(&cfg, &fix(3.0, 43.77302, 11.25)).unwrap();
        assert_eq!(g.len(), 3);
        assert_eq!(g[0].t, 1.0);
        assert_eq!(v.dropped, 1);
    }

    #[test]
    fn agreeing_fixes_start_at_once() {
        let cfg = FusionConfig::default();
        let mut v = OriginVote::default();
        assert!(v.push(&cfg, &fix(0.0, 43.77, 11.25)).is_none());
        assert!(v.push(&cfg, &fix(1.0, 43.77, 11.25)).is_none());
        assert_eq!(v.push(&cfg, &fix(2.0, 43.77, 11.25)).unwrap()[0].t, 0.0);
    }
}

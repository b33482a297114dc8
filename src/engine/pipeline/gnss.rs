//! The pipeline's GNSS side: fixes in, the geodetic origin, and the fusion filter's track out.
//! May import: the rest of `engine`.

use super::{offset_onto, Pipeline};
use crate::engine::fusion::{declination_for, FixInput, FusedStep, Fusion, GnssMode};
use crate::engine::geo::LocalFrame;
use crate::engine::motion::Motion;
use crate::engine::types::{GnssFix, InputError};

impl Pipeline {
    /// Feeds one GNSS fix. The first accepted fix becomes the geodetic origin of the track.
    pub fn push_gnss(&mut self, f: &GnssFix) -> Result<(), InputError> {
        if let Err(e) = f.check() {
            self.diag.rejected_non_finite += 1;
            return Err(e);
        }
        if let Some(last) = self.last_gnss_t {
            if f.t < last {
                self.diag.rejected_backwards += 1;
                return Err(InputError::TimeWentBackwards { t: f.t, last });
            }
        }
        self.last_gnss_t = Some(f.t);
        self.fixes.push(*f);
        self.diag.gnss_fixes += 1;
        // Without fusion the origin is the first fix. With it, the first of a consensus of
        // fixes good enough for the filter (`OriginVote`: a stale cached fix must not be the
        // origin); those fixes are then offered to the filter in order.
        let fusion_on = self.cfg.fusion.mode != GnssMode::Off;
        let at = |f: &GnssFix| LocalFrame::new(f.lat_deg, f.lon_deg, f.altitude_m.unwrap_or(0.0));
        if fusion_on && self.fusion.is_none() {
            if !(f.h_accuracy_m <= self.cfg.fusion.max_accuracy_m) {
                return Ok(());
            }
            // Until a consensus names the origin, the first usable fix places the track on a
            // map (a live walk's first fix draws the base map at once).
            if self.frame.is_none() {
                self.frame = Some(at(f));
            }
            let Some(group) = self.origin.push(&self.cfg.fusion, f) else {
                return Ok(());
            };
            let frame = at(&group[0]);
            let cfg = self.cfg.fusion;
            let (d, note) = declination_for(&cfg, &frame, group[0].t);
            self.diag.declination_deg = Some(d.to_degrees());
            self.diag.declination_note = note;
            self.fusion = Some(Fusion::new(cfg, d));
            self.frame = Some(frame);
            for g in &group {
                self.offer_fix(g);
            }
            return Ok(());
        }
        if self.frame.is_none() {
            self.frame = Some(at(f));
            return Ok(());
        }
        self.offer_fix(f);
        Ok(())
    }

    /// Offers a fix to the fusion filter, in the local frame.
    fn offer_fix(&mut self, f: &GnssFix) {
        if let (Some(frame), Some(fusion)) = (&self.frame, &mut self.fusion) {
            let (e, n) = frame.en_of_fix(f);
            let fix = FixInput {
                t: f.t,
                east_m: e,
                north_m: n,
                accuracy_m: f.h_accuracy_m,
                still: self.prev_state == Motion::Still,
            };
            // While steps are held, the fix waits behind them.
            if self.held.is_empty() {
                fusion.push_fix(&fix);
            } else {
                self.held.push(super::Held::Fix(fix));
            }
        }
    }

    /// The fused track: one record per step from the first usable fix on (empty without
    /// fusion or fixes).
    pub fn fused(&self) -> &[FusedStep] {
        self.fusion.as_ref().map_or(&[], |f| f.steps())
    }

    /// What to add to the PDR track to draw it in the frame of the fixes: the fused estimate at
    /// the first fused step minus the track's position then (zero without fusion).
    pub fn pdr_offset(&self) -> (f64, f64) {
        offset_onto(&self.steps, self.fused().first())
    }

    /// The fused track smoothed backwards over the whole log (Rauch–Tung–Striebel).
    pub fn smoothed(&self) -> Vec<FusedStep> {
        self.fusion.as_ref().map_or_else(Vec::new, Fusion::smoothed)
    }

    /// The fusion filter, once it exists.
    pub fn fusion(&self) -> Option<&Fusion> {
        self.fusion.as_ref()
    }

    /// Whether the GNSS receiver should be on at time `t` (energy-saving mode switches it off
    /// between windows; live mode stops the geolocation watch then).
    pub fn gnss_wanted(&self, t: f64) -> bool {
        self.fusion.as_ref().map_or(true, |f| f.gnss_wanted(t))
    }

    /// The geodetic origin of the track, once a fix has been accepted. The walk is assumed to
    /// start at the first fix.
    pub fn frame(&self) -> Option<&LocalFrame> {
        self.frame.as_ref()
    }
}

//! The pipeline's GNSS stage: fixes in, the geodetic origin, and the fusion filter's track out.
//! May import: the rest of `engine`.

use super::{offset_onto, Pipeline};
use crate::engine::fusion::{self, declination_for, DeclinationNote, FixCounts, FixInput};
use crate::engine::fusion::{FusedStep, Fusion, FusionConfig, GnssMode, OriginVote};
use crate::engine::geo::LocalFrame;
use crate::engine::types::{GnssFix, InputError};

/// The GNSS stage's current values.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct GnssDiagnostics {
    /// Fixes accepted.
    pub fixes: u64,
    /// Magnetic declination applied by the fusion, degrees.
    pub declination_deg: Option<f64>,
    /// Why the declination may be off.
    pub declination_note: Option<DeclinationNote>,
    /// What happened to the fixes in the fusion.
    pub fix_counts: Option<FixCounts>,
    /// Time the receiver was (or would have been) on, s, and the whole span, s.
    pub gnss_on_s: Option<(f64, f64)>,
}

/// The accepted fixes, the track's geodetic origin and the fusion filter once it has one.
pub(super) struct Gnss {
    cfg: FusionConfig,
    last_t: Option<f64>,
    fixes: Vec<GnssFix>,
    frame: Option<LocalFrame>,
    fusion: Option<Fusion>,
    origin: OriginVote,
    declination: Option<(f64, Option<DeclinationNote>)>,
}

impl Gnss {
    /// A stage with validated fusion settings.
    pub(super) fn new(cfg: FusionConfig) -> Self {
        Gnss {
            cfg,
            last_t: None,
            fixes: Vec::new(),
            frame: None,
            fusion: None,
            origin: OriginVote::default(),
            declination: None,
        }
    }

    /// Feeds one fix (`still`: the walker is standing). Returns the fixes now due to the fusion
    /// filter, in the local frame: usually this one; none before the origin is known; the
    /// consensus that named the origin when it does. Refused (state untouched) when not finite
    /// or earlier than the previous fix.
    pub(super) fn push(&mut self, f: &GnssFix, still: bool) -> Result<Vec<FixInput>, InputError> {
        f.check()?;
        if let Some(last) = self.last_t {
            if f.t < last {
                return Err(InputError::TimeWentBackwards { t: f.t, last });
            }
        }
        self.last_t = Some(f.t);
        self.fixes.push(*f);
        // Without fusion the origin is the first fix. With it, the first of a consensus of
        // fixes good enough for the filter (`OriginVote`: a stale cached fix must not be the
        // origin); those fixes are then offered to the filter in order.
        let fusion_on = self.cfg.mode != GnssMode::Off;
        let at = |f: &GnssFix| LocalFrame::new(f.lat_deg, f.lon_deg, f.altitude_m.unwrap_or(0.0));
        if fusion_on && self.fusion.is_none() {
            if !(f.h_accuracy_m <= self.cfg.max_accuracy_m) {
                return Ok(Vec::new());
            }
            // Until a consensus names the origin, the first usable fix places the track on a
            // map (a live walk's first fix draws the base map at once).
            if self.frame.is_none() {
                self.frame = Some(at(f));
            }
            let Some(group) = self.origin.push(&self.cfg, f) else {
                return Ok(Vec::new());
            };
            let frame = at(&group[0]);
            let (d, note) = declination_for(&self.cfg, &frame, group[0].t);
            self.declination = Some((d.to_degrees(), note));
            self.fusion = Some(Fusion::new(self.cfg, d));
            self.frame = Some(frame);
            return Ok(group
                .iter()
                .filter_map(|g| self.fix_input(g, still))
                .collect());
        }
        if self.frame.is_none() {
            self.frame = Some(at(f));
            return Ok(Vec::new());
        }
        Ok(self.fix_input(f, still).into_iter().collect())
    }

    /// A fix for the fusion filter, in the local frame, once both exist.
    fn fix_input(&self, f: &GnssFix, still: bool) -> Option<FixInput> {
        let (frame, _) = self.frame.as_ref().zip(self.fusion.as_ref())?;
        let (e, n) = frame.en_of_fix(f);
        Some(FixInput {
            t: f.t,
            east_m: e,
            north_m: n,
            accuracy_m: f.h_accuracy_m,
            still,
        })
    }

    /// Gives the fusion filter a fix, in the order of the steps.
    pub(super) fn fuse_fix(&mut self, fix: &FixInput) {
        if let Some(fusion) = &mut self.fusion {
            fusion.push_fix(fix);
        }
    }

    /// Gives the fusion filter a step.
    pub(super) fn fuse_step(&mut self, step: &fusion::StepInput) {
        if let Some(f) = &mut self.fusion {
            f.push_step(step);
        }
    }

    /// A bout of walking ended (a stop or a gap).
    pub(super) fn end_bout(&mut self) {
        if let Some(f) = &mut self.fusion {
            f.end_bout();
        }
    }

    /// The current values.
    pub(super) fn diagnostics(&self) -> GnssDiagnostics {
        let f = self.fusion.as_ref().map(Fusion::diagnostics);
        GnssDiagnostics {
            fixes: self.fixes.len() as u64,
            declination_deg: self.declination.map(|d| d.0),
            declination_note: self.declination.and_then(|d| d.1),
            fix_counts: f.as_ref().map(|f| f.counts),
            gnss_on_s: f.and_then(|f| f.gnss_on_s),
        }
    }
}

impl Pipeline {
    /// Feeds one GNSS fix. The first accepted fix becomes the geodetic origin of the track.
    pub(super) fn push_gnss(&mut self, f: &GnssFix) -> Result<(), InputError> {
        let still = self.prev_state == crate::engine::motion::Motion::Still;
        for fix in self.gnss.push(f, still)? {
            self.offer_fix(fix);
        }
        Ok(())
    }

    /// Offers a fix to the fusion filter; while steps are held, the fix waits behind them.
    fn offer_fix(&mut self, fix: FixInput) {
        if self.bout.holding() {
            self.bout.hold(super::bout::Held::Fix(fix));
        } else {
            self.gnss.fuse_fix(&fix);
        }
    }

    /// Accepted GNSS fixes.
    pub fn fixes(&self) -> &[GnssFix] {
        &self.gnss.fixes
    }

    /// The fused track: one record per step from the first usable fix on (empty without
    /// fusion or fixes).
    pub fn fused(&self) -> &[FusedStep] {
        self.gnss.fusion.as_ref().map_or(&[], |f| f.steps())
    }

    /// What to add to the PDR track to draw it in the frame of the fixes: the fused estimate at
    /// the first fused step minus the track's position then (zero without fusion).
    pub fn pdr_offset(&self) -> (f64, f64) {
        offset_onto(self.track.steps(), self.fused().first())
    }

    /// The fused track smoothed backwards over the whole log (Rauch–Tung–Striebel).
    pub fn smoothed(&self) -> Vec<FusedStep> {
        self.gnss
            .fusion
            .as_ref()
            .map_or_else(Vec::new, Fusion::smoothed)
    }

    /// The fusion filter, once it exists.
    pub fn fusion(&self) -> Option<&Fusion> {
        self.gnss.fusion.as_ref()
    }

    /// Whether the GNSS receiver should be on at time `t` (energy-saving mode switches it off
    /// between windows; live mode stops the geolocation watch then).
    pub fn gnss_wanted(&self, t: f64) -> bool {
        self.gnss.fusion.as_ref().map_or(true, |f| f.gnss_wanted(t))
    }

    /// The geodetic origin of the track, once a fix has been accepted. The walk is assumed to
    /// start at the first fix.
    pub fn frame(&self) -> Option<&LocalFrame> {
        self.gnss.frame.as_ref()
    }
}

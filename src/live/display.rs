//! Live mode's display tick: whether the page redraws now (at most ten times a second, only
//! after something changed, never behind the pocket guard), what it writes (the readouts in
//! words, the GNSS notice, the messages about a missing sensor, compass or geolocation), and
//! whether the geolocation watch should run (energy saving stops it between its windows). Also the page's
//! bookkeeping around it: when it was hidden (a gap in the input), and a refused location.
//! May import: `engine` (the GNSS verdict), [`super::session`], [`super::readout_text`].

use super::readout_text::readout_texts;
use super::session::{Readouts, NO_MOTION_MS};
use crate::engine::fusion::GnssVerdict;

/// The shortest time between two redraws, ms (at most ten a second).
pub const DRAW_MS: f64 = 100.0;

/// The display's state between ticks. Times are on the page's clock (`performance.now()`), ms.
#[derive(Debug, Clone, PartialEq)]
pub struct Display {
    /// When the page last drew (−∞: draw at the next tick).
    last_draw_ms: f64,
    /// Something changed since the last draw.
    dirty: bool,
    /// When the session started.
    started_ms: f64,
    /// The session has ended: ticks only for a change.
    ended: bool,
    /// The session is recorded (a calibration walk draws no plots).
    recorded: bool,
    /// The fusion mode the walk runs (`off`, `energy_saving`, …).
    gnss_mode: String,
    /// The browser has geolocation.
    geolocation: bool,
    /// The user refused location: the watch is not started again.
    location_refused: bool,
    /// When the page was hidden, while it is.
    hidden_at_ms: Option<f64>,
}

impl Default for Display {
    fn default() -> Self {
        Display {
            last_draw_ms: f64::NEG_INFINITY,
            dirty: true,
            started_ms: 0.0,
            ended: false,
            recorded: false,
            gnss_mode: String::new(),
            geolocation: false,
            location_refused: false,
            hidden_at_ms: None,
        }
    }
}

/// What the page does at a display tick.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Tick {
    /// `(element id, text)` of the readouts (see [`readout_texts`]).
    pub texts: Vec<(&'static str, String)>,
    /// `(element id, tooltip)`.
    pub titles: Vec<(&'static str, String)>,
    /// Whether the GNSS notice shows.
    pub notice: bool,
    /// The filter's verdict on the GNSS, the notice's `data-verdict` (none: empty).
    pub verdict: Option<GnssVerdict>,
    /// `(message key, shown, kind)` of the messages a tick decides (see `super::messages`).
    pub messages: [(&'static str, bool, &'static str); 3],
    /// `on` or `off`: where the geolocation watch should be now; none: leave it as it is (GNSS
    /// off, refused, missing, or the session has ended).
    pub gnss: Option<&'static str>,
    /// Whether to draw the map and the scope now.
    pub draw: bool,
}

impl Display {
    /// The session starts at `now_ms`, running `gnss_mode`, `recorded` or not (a calibration
    /// walk), in a browser with or without geolocation.
    pub fn start(&mut self, now_ms: f64, gnss_mode: &str, recorded: bool, geolocation: bool) {
        self.started_ms = now_ms;
        self.gnss_mode = gnss_mode.to_string();
        self.recorded = recorded;
        self.geolocation = geolocation;
    }

    /// Something to show has come (a sample, a fix, a gap).
    pub fn changed(&mut self) {
        self.dirty = true;
    }

    /// Draw at the next tick, however recent the last draw (a resize, the guard unlocked).
    pub fn redraw(&mut self) {
        self.dirty = true;
        self.last_draw_ms = f64::NEG_INFINITY;
    }

    /// The session has ended: no more messages about missing motion, nor a watch started.
    pub fn end(&mut self) {
        self.ended = true;
    }

    /// The geolocation watch failed, `denied` by the user or not: the message to show
    /// (`locationDenied`, and no watch any more; else `locationUnavailable`, fixes may come).
    pub fn location_failed(&mut self, denied: bool) -> &'static str {
        self.location_refused |= denied;
        if denied {
            "locationDenied"
        } else {
            "locationUnavailable"
        }
    }

    /// The page was hidden (`hidden`) or shown at `now_ms`: when it comes back from hidden, the
    /// span it was hidden (its events stopped), `(t0, t1)` ms, for the engine to mark as a gap.
    pub fn visibility(&mut self, hidden: bool, now_ms: f64) -> Option<(f64, f64)> {
        if hidden {
            self.hidden_at_ms = Some(now_ms);
            return None;
        }
        let span = self.hidden_at_ms.take().map(|t0| (t0, now_ms));
        if span.is_some() {
            self.dirty = true;
        }
        span
    }

    /// The tick at `now_ms` with the readouts `r`, the motion `source` in words, and whether
    /// the pocket guard is hidden; none when there is nothing to do (too soon after the last,
    /// or the session has ended and nothing changed).
    pub fn tick(
        &mut self,
        now_ms: f64,
        r: &Readouts,
        source: &str,
        guard_hidden: bool,
    ) -> Option<Tick> {
        if (self.ended && !self.dirty) || now_ms - self.last_draw_ms < DRAW_MS {
            return None;
        }
        self.last_draw_ms = now_ms;
        let gnss = self.gnss_mode != "off";
        let watch = gnss && self.geolocation && !self.location_refused;
        let no_motion = !self.ended && r.samples == 0 && now_ms - self.started_ms > NO_MOTION_MS;
        let draw = self.dirty && self.recorded;
        if draw {
            self.dirty = false;
        }
        let words = readout_texts(r, source, &self.gnss_mode);
        Some(Tick {
            texts: words.texts,
            titles: words.titles,
            notice: r.gnss_notice.is_some(),
            verdict: r.gnss_verdict,
            messages: [
                ("noSensor", no_motion, "error"),
                ("noCompass", r.samples > 0 && !r.absolute_heading, "warn"),
                ("noGeolocation", gnss && !self.geolocation, "warn"),
            ],
            gnss: (watch && !self.ended).then_some(if r.gnss_wanted { "on" } else { "off" }),
            draw: draw && guard_hidden,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::PipelineConfig;
    use crate::live::{LiveSession, Platform};

    /// The readouts of a session that has had no sample, then with `samples` and a compass.
    fn readouts(samples: u64, absolute_heading: bool, gnss_wanted: bool) -> Readouts {
        let s = LiveSession::new(PipelineConfig::default(), Platform::Android, 0.0).unwrap();
        Readouts {
            samples,
            absolute_heading,
            gnss_wanted,
            ..s.readouts()
        }
    }

    fn recorded(gnss_mode: &str) -> Display {
        let mut d = Display::default();
        d.start(1000.0, gnss_mode, true, true);
        d
    }

    #[test]
    fn draws_at_most_ten_times_a_second_and_only_after_a_change() {
        let mut d = recorded("off");
        let r = readouts(10, true, true);
        assert!(d.tick(1000.0, &r, "events", true).unwrap().draw);
        assert_eq!(d.tick(1050.0, &r, "events", true), None, "too soon");
        assert!(
            !d.tick(1100.0, &r, "events", true).unwrap().draw,
            "nothing changed"
        );
        d.changed();
        assert!(d.tick(1200.0, &r, "events", true).unwrap().draw);
        d.redraw();
        assert!(
            d.tick(1201.0, &r, "events", true).unwrap().draw,
            "a redraw waits for nothing"
        );
    }

    #[test]
    fn nothing_is_drawn_behind_the_guard_nor_for_a_calibration_walk() {
        let mut d = recorded("off");
        let r = readouts(10, true, true);
        assert!(!d.tick(1000.0, &r, "events", false).unwrap().draw);
        // The change was taken: the plots wait for the next one once the guard is unlocked.
        d.redraw();
        assert!(d.tick(1000.0, &r, "events", true).unwrap().draw);
        let mut walk = Display::default();
        walk.start(0.0, "off", false, true);
        walk.changed();
        assert!(!walk.tick(0.0, &r, "events", true).unwrap().draw);
    }

    #[test]
    fn an_ended_session_ticks_only_for_a_change() {
        let mut d = recorded("best_performance");
        let r = readouts(0, false, true);
        d.end();
        d.redraw();
        let t = d.tick(9000.0, &r, "events", true).unwrap();
        assert_eq!(
            t.messages[0],
            ("noSensor", false, "error"),
            "no motion message once ended"
        );
        assert_eq!(t.gnss, None, "the watch stays stopped");
        assert_eq!(d.tick(10_000.0, &r, "events", true), None);
    }

    #[test]
    fn messages_about_motion_compass_and_geolocation() {
        let mut d = recorded("off");
        let none = readouts(0, false, true);
        let t = d
            .tick(1000.0 + NO_MOTION_MS, &none, "events", true)
            .unwrap();
        assert_eq!(
            t.messages,
            [
                ("noSensor", false, "error"),
                ("noCompass", false, "warn"),
                ("noGeolocation", false, "warn")
            ]
        );
        let t = d
            .tick(1001.0 + NO_MOTION_MS + DRAW_MS, &none, "events", true)
            .unwrap();
        assert_eq!(
            t.messages[0],
            ("noSensor", true, "error"),
            "3 s without a sample"
        );
        let relative = readouts(5, false, true);
        let t = d.tick(9000.0, &relative, "events", true).unwrap();
        assert_eq!(t.messages.map(|m| m.1), [false, true, false]);
        assert_eq!(t.texts[0], ("r-steps", "0".to_string()));
    }

    #[test]
    fn the_watch_follows_the_engine_unless_off_refused_or_missing() {
        let wanted = readouts(1, true, true);
        let resting = readouts(1, true, false);
        let mut d = recorded("energy_saving");
        assert_eq!(
            d.tick(0.0, &wanted, "events", true).unwrap().gnss,
            Some("on")
        );
        assert_eq!(
            d.tick(200.0, &resting, "events", true).unwrap().gnss,
            Some("off")
        );
        assert_eq!(d.location_failed(false), "locationUnavailable");
        assert_eq!(
            d.tick(400.0, &wanted, "events", true).unwrap().gnss,
            Some("on")
        );
        assert_eq!(d.location_failed(true), "locationDenied");
        assert_eq!(d.tick(600.0, &wanted, "events", true).unwrap().gnss, None);
        assert_eq!(
            recorded("off")
                .tick(0.0, &wanted, "events", true)
                .unwrap()
                .gnss,
            None
        );
        let mut no_geo = Display::default();
        no_geo.start(0.0, "best_performance", true, false);
        let t = no_geo.tick(0.0, &wanted, "events", true).unwrap();
        assert_eq!(t.gnss, None);
        assert_eq!(t.messages[2], ("noGeolocation", true, "warn"));
    }

    #[test]
    fn a_hidden_page_is_a_gap_when_it_comes_back() {
        let mut d = recorded("off");
        assert_eq!(
            d.visibility(false, 500.0),
            None,
            "shown without having been hidden"
        );
        assert_eq!(d.visibility(true, 2000.0), None);
        let _ = d.tick(2000.0, &readouts(1, true, true), "events", true);
        assert_eq!(d.visibility(false, 7000.0), Some((2000.0, 7000.0)));
        assert!(
            d.tick(7000.0, &readouts(1, true, true), "events", true)
                .unwrap()
                .draw
        );
        assert_eq!(d.visibility(false, 8000.0), None);
    }
}

//! The diagnostics plots' shared time axis: pixels to times, and the spans that wheel, pinch and
//! drag give (the page's gestures, computed here so that both builds agree).
//! May import: nothing of the project.

/// The diagnostics plots' shared time axis as the page shows it: the span drawn, the whole log,
/// and where the axis lies. Wheel, pinch and drag give the next span to draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeAxis {
    /// The span shown, s (the log's clock): first, last.
    pub span: (f64, f64),
    /// The whole log, s: zoom and pan stay inside it.
    pub full: (f64, f64),
    /// Where the axis lies, pixels from the canvas's left edge (in the pointer's pixels): the
    /// columns [`draw_plot_area`](super::plots::draw_plot_area) returns, left and right.
    pub px: (f64, f64),
}

impl TimeAxis {
    /// The fraction of the time axis at pixel `x`, from where the plot drew the axis (below 0
    /// left of it, above 1 right of it).
    pub fn fraction(&self, x: f64) -> f64 {
        (x - self.px.0) / (self.px.1 - self.px.0).max(1.0)
    }

    /// The time (s) at pixel `x`, within the span shown.
    pub fn time_at(&self, x: f64) -> f64 {
        self.span.0 + self.fraction(x).clamp(0.0, 1.0) * (self.span.1 - self.span.0)
    }

    /// The pixel at time `t` (s): where the axis shows it, left or right of the axis outside the
    /// span.
    pub fn x_at(&self, t: f64) -> f64 {
        self.px.0 + (t - self.span.0) / (self.span.1 - self.span.0) * (self.px.1 - self.px.0)
    }

    /// The span zoomed by `k` (above 1 out, below 1 in) keeping time `t` at the fraction `f` of
    /// the axis: at least 1 s, at most the whole log, and inside it.
    pub fn zoom(&self, t: f64, f: f64, k: f64) -> (f64, f64) {
        let span = (self.full.1 - self.full.0).min(((self.span.1 - self.span.0) * k).max(1.0));
        let t0 = (t - f * span).max(self.full.0).min(self.full.1 - span);
        (t0, t0 + span)
    }

    /// The span zoomed by `k` about the pointer at pixel `x` (the wheel).
    pub fn zoomed_at(&self, x: f64, k: f64) -> (f64, f64) {
        self.zoom(self.time_at(x), self.fraction(x).clamp(0.0, 1.0), k)
    }

    /// Pinch: one finger moved from pixel `prev` to `x` while the other stays at `other`. The
    /// time under the two fingers' middle stays put; the span scales with their distance. None
    /// while the fingers are within 4 pixels of each other.
    pub fn pinched(&self, prev: f64, x: f64, other: f64) -> Option<(f64, f64)> {
        let d0 = (prev - other).abs();
        let d1 = (x - other).abs();
        let mid = (prev + other) / 2.0;
        (d0 > 4.0 && d1 > 4.0).then(|| {
            self.zoom(
                self.time_at(mid),
                self.fraction((x + other) / 2.0).clamp(0.0, 1.0),
                d0 / d1,
            )
        })
    }

    /// A drag from pixel `from` to `x`: this span (the one shown when the drag began) moved with
    /// the pointer, inside the whole log.
    pub fn panned(&self, from: f64, x: f64) -> (f64, f64) {
        let w = self.span.1 - self.span.0;
        let dt = -(self.fraction(x) - self.fraction(from)) * w;
        let t0 = (self.span.0 + dt).max(self.full.0).min(self.full.1 - w);
        (t0, t0 + w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 100 s of a 400 s log on an axis from pixel 46 to 554 of a canvas whose left edge is at
    /// client x 8 (pixel 292 is client x 300). The expected spans are what the page's own
    /// JavaScript computed for the same gestures.
    fn axis(span: (f64, f64)) -> TimeAxis {
        TimeAxis {
            span,
            full: (1000.0, 1400.0),
            px: (46.0, 554.0),
        }
    }

    #[test]
    fn maps_pixels_to_times() {
        let a = axis((1100.0, 1200.0));
        assert_eq!(a.fraction(292.0), 0.484251968503937);
        assert_eq!(a.time_at(292.0), 1148.4251968503936);
        assert_eq!(a.time_at(12.0), 1100.0);
        assert_eq!(a.time_at(592.0), 1200.0);
        assert_eq!(a.x_at(1100.0), 46.0);
        assert_eq!(a.x_at(1150.0), 300.0);
        assert_eq!(a.x_at(1200.0), 554.0);
    }

    #[test]
    fn wheel_zooms_about_the_pointer_within_the_log() {
        let wheel = |span, x, delta_y| axis(span).zoomed_at(x, crate::plot::wheel_factor(delta_y));
        assert_eq!(
            wheel((1100.0, 1200.0), 292.0, 100.0),
            (1087.8937007874015, 1212.8937007874015)
        );
        assert_eq!(
            wheel((1100.0, 1200.0), 292.0, -100.0),
            (1109.6850393700786, 1189.6850393700786)
        );
        assert_eq!(wheel((1000.0, 1400.0), 292.0, 100.0), (1000.0, 1400.0));
        // Never below 1 s.
        assert_eq!(
            wheel((1100.0, 1101.2), 292.0, -100.0),
            (1100.0968503937008, 1101.0968503937008)
        );
        assert_eq!(wheel((1000.0, 1100.0), 12.0, 100.0), (1000.0, 1125.0));
        assert_eq!(
            wheel((1300.0, 1390.0), 492.0, 100.0),
            (1280.246062992126, 1392.746062992126)
        );
    }

    #[test]
    fn pinch_scales_the_span_about_the_fingers() {
        let a = axis((1100.0, 1200.0));
        assert_eq!(
            a.pinched(192.0, 172.0, 392.0),
            Some((1106.1918396564065, 1197.1009305654975))
        );
        assert_eq!(
            a.pinched(192.0, 252.0, 392.0),
            Some((1070.8098987626545, 1213.6670416197974))
        );
        assert_eq!(a.pinched(394.0, 372.0, 392.0), None);
    }

    #[test]
    fn drag_pans_within_the_log() {
        assert_eq!(
            axis((1100.0, 1200.0)).panned(292.0, 242.0),
            (1109.8425196850394, 1209.8425196850394)
        );
        assert_eq!(
            axis((1100.0, 1200.0)).panned(92.0, 532.0),
            (1013.3858267716536, 1113.3858267716537)
        );
        assert_eq!(
            axis((1010.0, 1110.0)).panned(292.0, 532.0),
            (1000.0, 1100.0)
        );
        assert_eq!(axis((1300.0, 1390.0)).panned(532.0, 52.0), (1310.0, 1400.0));
    }
}

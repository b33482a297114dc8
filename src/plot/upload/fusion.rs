//! The fusion plot's series: the step-length scale and the heading correction the filter
//! learnt at each fused step, each with its ±1σ band, and the axes that hold them (the scale in
//! the upper part, the correction in the lower, so that they do not overlap). Each band stays in
//! its value's own part: a σ wider than the part (a prior, or a scale only baselines can teach)
//! is cut there, so that a band never covers more than [`REGION_SHARE`] of the plot.
//! May import: `analysis`.

use crate::analysis::Analysis;

/// How wide a band may make an axis: the filter's prior σ is wide before the first fixes, and
/// an axis spanning it would flatten what the walk learnt. The band is cut at its part there.
/// The plot's caption names both caps (`plots.rs`).
const SCALE_SD_AXIS_MAX: f64 = 0.05;
/// See [`SCALE_SD_AXIS_MAX`], degrees.
const CORRECTION_SD_AXIS_MAX_DEG: f64 = 5.0;

/// The share of the plot's height each value's part (its values ± their capped σ) takes: a band
/// as wide as its part for the whole walk covers this much of the plot, under the legibility
/// bound (35 %, `legibility.rs`). The rest is margin above, between and below.
pub const REGION_SHARE: f64 = 1.0 / 3.5;

/// A line of (t, value) points.
pub type Line = Vec<(f64, f64)>;

/// The fusion plot's series between two times, on the plot's time axis (s from `origin`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FusionSeries {
    /// (t, scale, σ) of each fused step in the span.
    pub scale: Vec<(f64, f64, f64)>,
    /// (t, correction, σ) of each fused step in the span, degrees.
    pub correction: Vec<(f64, f64, f64)>,
    /// The scale's axis (left).
    pub scale_axis: (f64, f64),
    /// The correction's axis (right), degrees.
    pub correction_axis: (f64, f64),
    /// The scale's part of its axis: its values ± their capped σ; the band is cut at it.
    pub scale_region: (f64, f64),
    /// The correction's part of its axis, degrees.
    pub correction_region: (f64, f64),
}

impl FusionSeries {
    /// The fused steps between `t0` and `t1` (the log's clock), with times from `origin`.
    pub fn new(a: &Analysis, t0: f64, t1: f64, origin: f64) -> Self {
        let mut s = FusionSeries::default();
        for (i, f) in a.fused.iter().enumerate() {
            if f[0] < t0 || f[0] > t1 {
                continue;
            }
            let sd = a.fused_sd.get(i).copied().unwrap_or([0.0, 0.0]);
            let ok = |x: f64| if x.is_finite() { x.max(0.0) } else { 0.0 };
            s.scale.push((f[0] - origin, f[3], ok(sd[0])));
            s.correction
                .push((f[0] - origin, f[4].to_degrees(), ok(sd[1].to_degrees())));
        }
        // Each axis spans the values ± their σ (capped) and the neutral value (1, 0°).
        let span = |v: &[(f64, f64, f64)], neutral: f64, cap: f64| {
            v.iter()
                .filter(|p| p.1.is_finite())
                .fold((neutral, neutral), |(lo, hi), p| {
                    (lo.min(p.1 - p.2.min(cap)), hi.max(p.1 + p.2.min(cap)))
                })
        };
        let k = span(&s.scale, 1.0, SCALE_SD_AXIS_MAX);
        let b = span(&s.correction, 0.0, CORRECTION_SD_AXIS_MAX_DEG);
        // At least 0.02 and 2° tall, about the middle; then the scale's part in the upper, the
        // correction's in the lower part of the plot, each REGION_SHARE of it, with half a part
        // of margin at the edge and two parts' room for the other.
        let widen = |(lo, hi): (f64, f64), min: f64| {
            let pad = 0.5 * (min - (hi - lo)).max(0.0);
            (lo - pad, hi + pad)
        };
        s.scale_region = widen(k, 0.02);
        s.correction_region = widen(b, 2.0);
        let (k, b) = (s.scale_region, s.correction_region);
        let (ks, bs) = (k.1 - k.0, b.1 - b.0);
        let room = 1.0 / REGION_SHARE - 1.5;
        s.scale_axis = (k.0 - room * ks, k.1 + 0.5 * ks);
        s.correction_axis = (b.0 - 0.5 * bs, b.1 + room * bs);
        s
    }

    /// The scale's ±1σ edges, cut at its part of the axis: (upper, lower) lines.
    pub fn scale_edges(&self) -> [Line; 2] {
        edges(&self.scale, self.scale_region)
    }

    /// The correction's ±1σ edges, cut at its part of the axis, degrees.
    pub fn correction_edges(&self) -> [Line; 2] {
        edges(&self.correction, self.correction_region)
    }

    /// The scale's ±1σ band as one polygon, cut at its part of the axis.
    pub fn scale_band(&self) -> Vec<(f64, f64)> {
        band(&self.scale, self.scale_region)
    }

    /// The correction's ±1σ band as one polygon, cut at its part of the axis, degrees.
    pub fn correction_band(&self) -> Vec<(f64, f64)> {
        band(&self.correction, self.correction_region)
    }
}

/// The polygon of value ± σ: along the top forwards, along the bottom back; nothing with fewer
/// than two points.
fn band(v: &[(f64, f64, f64)], (lo, hi): (f64, f64)) -> Vec<(f64, f64)> {
    let pts: Vec<&(f64, f64, f64)> = v.iter().filter(|p| p.1.is_finite()).collect();
    if pts.len() < 2 {
        return Vec::new();
    }
    let clamp = |y: f64| y.clamp(lo, hi);
    pts.iter()
        .map(|p| (p.0, clamp(p.1 + p.2)))
        .chain(pts.iter().rev().map(|p| (p.0, clamp(p.1 - p.2))))
        .collect()
}

/// The band's upper and lower edges (see [`band`]).
fn edges(v: &[(f64, f64, f64)], axis: (f64, f64)) -> [Line; 2] {
    let mut b = band(v, axis);
    let lower = b.split_off(b.len() / 2);
    [b, lower]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn analysis(fused: Vec<[f64; 5]>, sd: Vec<[f64; 2]>) -> Analysis {
        let mut a = crate::analysis::three_floor_analysis();
        a.fused = fused;
        a.fused_sd = sd;
        a
    }

    #[test]
    fn bands_are_the_values_plus_and_minus_their_sigma_and_fit_the_axes() {
        let r = 2f64.to_radians();
        let a = analysis(
            vec![
                [10.0, 0.0, 0.0, 0.95, -r],
                [11.0, 0.0, 0.0, 0.94, -r],
                [12.0, 0.0, 0.0, 0.93, -2.0 * r],
            ],
            vec![[0.03, r], [0.02, r], [0.01, 0.5 * r]],
        );
        let s = FusionSeries::new(&a, 10.0, 12.0, 10.0);
        let band = s.scale_band();
        assert_eq!(band.len(), 6);
        for (got, want) in band.iter().zip([
            (0.0, 0.98),
            (1.0, 0.96),
            (2.0, 0.94),
            (2.0, 0.92),
            (1.0, 0.92),
            (0.0, 0.92),
        ]) {
            assert!(
                (got.0 - want.0).abs() < 1e-9 && (got.1 - want.1).abs() < 1e-9,
                "{band:?}"
            );
        }
        // The axes hold the bands and the neutral values.
        assert!(s.scale_axis.0 < 0.92 && s.scale_axis.1 > 1.0);
        let [upper, lower] = s.scale_edges();
        assert_eq!((upper[1], lower[1]), (band[1], band[4]));
        let c = s.correction_band();
        assert!(
            (c[2].1 - -3.0).abs() < 1e-9 && (c[3].1 - -5.0).abs() < 1e-9,
            "{c:?}"
        );
        assert!(s.correction_axis.0 < -5.0 && s.correction_axis.1 > 0.0);
        // The scale's part in the upper half of its axis, the correction's in the lower half of
        // its, each REGION_SHARE of the height.
        let at = |y: f64, (lo, hi): (f64, f64)| (y - lo) / (hi - lo);
        let (k, b) = (s.scale_region, s.correction_region);
        assert!(at(k.0, s.scale_axis) > 0.5 && at(b.1, s.correction_axis) < 0.5);
        assert!((at(k.1, s.scale_axis) - at(k.0, s.scale_axis) - REGION_SHARE).abs() < 1e-9);
        assert!(
            (at(b.1, s.correction_axis) - at(b.0, s.correction_axis) - REGION_SHARE).abs() < 1e-9
        );
    }

    #[test]
    fn a_wide_prior_is_cut_at_its_part_of_the_axis_and_not_a_number_is_left_out() {
        let a = analysis(
            vec![
                [0.0, 0.0, 0.0, 1.0, 0.0],
                [1.0, 0.0, 0.0, 0.97, 0.0],
                [2.0, 0.0, 0.0, f64::NAN, 0.0],
            ],
            vec![[0.5, 1.0], [0.01, 0.01], [f64::NAN, f64::NAN]],
        );
        let s = FusionSeries::new(&a, 0.0, 2.0, 0.0);
        // The 0.5 σ does not make the scale's part ±0.5: it is capped at 0.05 (1.0 ± 0.05), and
        // the band is cut there, so it covers no more than its part of the plot.
        assert!(
            (s.scale_region.0 - 0.95).abs() < 1e-9 && (s.scale_region.1 - 1.05).abs() < 1e-9,
            "{:?}",
            s.scale_region
        );
        assert!((s.scale_axis.1 - s.scale_axis.0 - 0.35).abs() < 1e-9);
        let band = s.scale_band();
        assert_eq!(band.len(), 4);
        assert!(band
            .iter()
            .all(|p| p.1 >= s.scale_region.0 && p.1 <= s.scale_region.1));
        assert_eq!(s.correction.len(), 3);
        assert!(s.correction_band().iter().all(|p| p.1.is_finite()));
        // One step: no band.
        let one = FusionSeries::new(&a, 0.5, 1.5, 0.0);
        assert!(one.scale_band().is_empty());
    }
}

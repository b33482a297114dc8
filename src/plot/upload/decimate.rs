//! Long signals decimated to the pixel columns of a plot, so that a whole walk and a one-second
//! window both draw in time linear in the samples shown: the samples themselves, a zig-zag
//! through each column's min and max, the upper and lower envelopes, or a band.
//! May import: nothing beyond `std`; never `web`, `live` or `eval`.

/// Columns wider than this (s) cannot show a step's wave (a step takes about half a second):
/// there [`envelope`] draws the signal's highest and lowest value per column as two lines
/// rather than a zig-zag between them, which would fill the plot with one colour.
pub const COARSE_COLUMN_S: f64 = 0.125;

/// Samples further apart than this (s) are not joined.
pub const GAP_S: f64 = 0.5;

/// A pixel column of [`envelope`]: its middle (s from the origin), min, max, and whether a gap
/// comes before it.
pub type Column = (f64, f64, f64, bool);

/// A long signal drawn at any zoom without losing its peaks, as the runs of a line (broken
/// where there is no finite value for more than [`GAP_S`]): the samples themselves when there
/// are at most two per pixel column; else the min and max per column between `t0` and `t1`, as
/// a zig-zag between them while a column is narrower than [`COARSE_COLUMN_S`], and as two lines
/// (the upper and the lower envelope) beyond. `value(i)` is sample `i`'s value (NaN for none),
/// asked in time order. The work is linear in the samples in the span.
pub fn envelope(
    t: &[f64],
    mut value: impl FnMut(usize) -> f64,
    t0: f64,
    t1: f64,
    cols: usize,
    origin: f64,
) -> Vec<Vec<(f64, f64)>> {
    let i0 = t.partition_point(|&x| x < t0);
    let i1 = t.partition_point(|&x| x <= t1);
    let mut runs = Vec::new();
    if i1 <= i0 {
        return runs;
    }
    let n = i1 - i0;
    let mut run: Vec<(f64, f64)> = Vec::new();
    if n <= 2 * cols {
        let mut last = f64::NEG_INFINITY;
        for (i, &ti) in t.iter().enumerate().take(i1).skip(i0) {
            let v = value(i);
            if !v.is_finite() {
                continue;
            }
            if ti - last > GAP_S && !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
            last = ti;
            run.push((ti - origin, v));
        }
        if !run.is_empty() {
            runs.push(run);
        }
        return runs;
    }
    let width = (t1 - t0) / cols as f64;
    let columns = per_column(t, value, (i0, i1), t0, width, cols, origin);
    // Coarse: the lows as one line, the highs as another. Fine: a zig-zag through both.
    let passes: &[(bool, bool)] = if width > COARSE_COLUMN_S {
        &[(true, false), (false, true)]
    } else {
        &[(true, true)]
    };
    for &(low, high) in passes {
        for c in &columns {
            if c.3 && !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
            if low {
                run.push((c.0, c.1));
            }
            if high {
                run.push((c.0, c.2));
            }
        }
        if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    runs
}

/// The min and max of samples `i0..i1` per pixel column `width` s wide from `t0` (linear in
/// the samples).
pub fn per_column(
    t: &[f64],
    mut value: impl FnMut(usize) -> f64,
    (i0, i1): (usize, usize),
    t0: f64,
    width: f64,
    cols: usize,
    origin: f64,
) -> Vec<Column> {
    let mut columns: Vec<Column> = Vec::with_capacity(cols);
    let mut i = i0;
    let mut last = f64::NEG_INFINITY;
    for c in 0..cols {
        let end = t0 + (c + 1) as f64 * width;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut gap = false;
        while i < i1 && t[i] <= end {
            let v = value(i);
            if v.is_finite() {
                gap |= t[i] - last > GAP_S + width;
                last = t[i];
                lo = lo.min(v);
                hi = hi.max(v);
            }
            i += 1;
        }
        if lo.is_finite() {
            columns.push((t0 + (c as f64 + 0.5) * width - origin, lo, hi, gap));
        }
    }
    columns
}

/// Columns wider than this (s) cannot draw the PLL's wave (about 1 Hz, a stride) as a line
/// that reads: there [`band`] gives its range per column, drawn as a faint band.
pub const BAND_COLUMN_S: f64 = 0.05;

/// The min and max of a signal per pixel column (half a column wide each side of its middle)
/// when its columns are wider than [`BAND_COLUMN_S`] and hold more than two samples each; else
/// None, and [`envelope`] draws it.
pub fn band(
    t: &[f64],
    value: impl FnMut(usize) -> f64,
    t0: f64,
    t1: f64,
    cols: usize,
    origin: f64,
) -> Option<(f64, Vec<Column>)> {
    let i0 = t.partition_point(|&x| x < t0);
    let i1 = t.partition_point(|&x| x <= t1);
    let width = (t1 - t0) / cols as f64;
    if i1 <= i0 + 2 * cols || width <= BAND_COLUMN_S {
        return None;
    }
    let columns = per_column(t, value, (i0, i1), t0, width, cols, origin);
    // Each column spans the signal's range over the half second either side (about a stride,
    // a whole swing of the wave), within its run: a column narrower than the wave catches only
    // part of a swing, and its neighbours' parts would read as noise.
    let k = (0.5 / width).ceil() as usize;
    let spread = (0..columns.len())
        .map(|i| {
            let mut c = columns[i];
            for j in i.saturating_sub(k)..(i + k + 1).min(columns.len()) {
                let between = if j < i { j + 1..=i } else { i + 1..=j };
                let near = (columns[j].0 - c.0).abs() <= 0.5 + width;
                if near && !columns[between].iter().any(|b| b.3) {
                    c.1 = c.1.min(columns[j].1);
                    c.2 = c.2.max(columns[j].2);
                }
            }
            c
        })
        .collect();
    Some((width, spread))
}

/// Sample `i` of a signal, for [`envelope`].
pub fn of(v: &[f32]) -> impl FnMut(usize) -> f64 + '_ {
    move |i| f64::from(v[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ten minutes of a 2 Hz wave at 100 Hz with a 20 s hole in the middle.
    fn wave() -> (Vec<f64>, Vec<f32>) {
        let t: Vec<f64> = (0..60_000)
            .map(|i| i as f64 * 0.01)
            .filter(|t| !(300.0..320.0).contains(t))
            .collect();
        let v = t
            .iter()
            .map(|&t| libm::sin(2.0 * std::f64::consts::PI * 2.0 * t) as f32)
            .collect();
        (t, v)
    }

    #[test]
    fn a_whole_walk_is_two_envelopes_a_window_a_zigzag_a_second_the_samples() {
        let (t, v) = wave();
        // Whole: 1.2 s per column. The lows and the highs, each broken at the hole.
        let runs = envelope(&t, of(&v), 0.0, 600.0, 500, 0.0);
        assert_eq!(
            runs.len(),
            4,
            "{:?}",
            runs.iter().map(Vec::len).collect::<Vec<_>>()
        );
        assert!(runs[..2].iter().flatten().all(|p| p.1 < -0.99));
        assert!(runs[2..].iter().flatten().all(|p| p.1 > 0.99));
        // 16 columns of 1.2 s lie wholly in the hole.
        assert_eq!(runs.iter().map(Vec::len).sum::<usize>(), 2 * (500 - 16));
        // 60 s on 500 columns (0.12 s each): a zig-zag through each column's min and max.
        let runs = envelope(&t, of(&v), 0.0, 60.0, 500, 0.0);
        assert_eq!((runs.len(), runs[0].len()), (1, 1000));
        // 1 s: the 101 samples themselves, in time from the origin.
        let runs = envelope(&t, of(&v), 100.0, 101.0, 500, 90.0);
        assert_eq!(runs[0].len(), 101);
        assert!((runs[0][0].0 - 10.0).abs() < 1e-9);
    }

    #[test]
    fn a_band_spans_a_whole_swing_per_column_and_only_over_long_spans() {
        let (t, v) = wave();
        let (w, columns) = band(&t, of(&v), 0.0, 60.0, 1000, 0.0).unwrap();
        assert!((w - 0.06).abs() < 1e-12);
        // Each column alone holds an eighth of a swing; spread over ±0.5 s, all of it.
        assert!(columns.iter().all(|c| c.1 < -0.99 && c.2 > 0.99));
        assert!(band(&t, of(&v), 0.0, 10.0, 1000, 0.0).is_none());
        // The hole breaks the band.
        let (_, columns) = band(&t, of(&v), 280.0, 340.0, 500, 0.0).unwrap();
        // (The first column's flag says nothing came before it.)
        assert_eq!(columns[1..].iter().filter(|c| c.3).count(), 1);
    }
}

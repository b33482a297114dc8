//! Upload mode's colours for the activities (Munoz Diaz 2015 §4.3), the carrying modes and the
//! floors, a plot's title, and the key that names the colours on a line under it.
//! May import: `engine` (the activities), `analysis`, the theme; never `web`, `live` or `eval`.

use crate::engine::activity::Activity;
use crate::engine::carry::CarryMode;
use crate::plot::theme::Theme;
use plotters::coord::Shift;
use plotters::prelude::*;

/// An activity's colour in the timeline's band; none for `Still` (no band, as before the
/// activities: the walking and running colours are the motion state's).
pub fn activity_colour(a: Activity, t: &Theme) -> Option<RGBColor> {
    match a {
        Activity::Still => None,
        Activity::Standing => Some(t.reference),
        Activity::Sitting => Some(t.pdr),
        Activity::Walking => Some(t.start),
        Activity::Upstairs => Some(t.gnss),
        Activity::Downstairs => Some(t.smoothed),
        Activity::Running => Some(t.end),
        Activity::Handling => Some(t.track),
    }
}

/// The activities of `a`'s samples between `t0` and `t1` that have a colour, named and
/// coloured: the timeline band's key, in `Activity::ALL`'s order.
pub fn activity_key(
    a: &crate::analysis::Analysis,
    t0: f64,
    t1: f64,
    theme: &Theme,
) -> Vec<(String, RGBColor)> {
    let tr = &a.trace;
    let i1 = tr.t.partition_point(|&x| x <= t1).min(tr.activity.len());
    let i0 = tr.t.partition_point(|&x| x < t0).min(i1);
    let mut seen = [false; Activity::ALL.len()];
    for &c in &tr.activity[i0..i1] {
        if let Some(x) = seen.get_mut(usize::from(c)) {
            *x = true;
        }
    }
    Activity::ALL
        .iter()
        .zip(seen)
        .filter(|(_, s)| *s)
        .filter_map(|(&act, _)| {
            activity_colour(act, theme)
                .map(|c| (crate::analysis::activity_words(act).to_lowercase(), c))
        })
        .collect()
}

/// A carrying mode's colour in the heading plot's band: none of the plot's own
/// (single steps `gnss`, the average `track`, the device and the gyroscope band `reference`).
pub fn carry_colour(m: CarryMode, t: &Theme) -> RGBColor {
    match m {
        CarryMode::Pocket => t.start,
        CarryMode::Hand => t.pdr,
        CarryMode::Swinging => t.end,
        CarryMode::Ear => t.smoothed,
        CarryMode::Bag => t.foreground,
    }
}

/// The carrying modes of `steps` that were decided, named and coloured in
/// `CarryMode::ALL`'s order, and the grey strip's entry when a step's heading followed the
/// gyroscope (`engine::magnetic`): the heading plot's key.
pub fn carry_key(steps: &[&crate::engine::StepRecord], theme: &Theme) -> Vec<(String, RGBColor)> {
    let mut key: Vec<(String, RGBColor)> = CarryMode::ALL
        .iter()
        .filter(|&&m| steps.iter().any(|s| s.carry == Some(m)))
        .map(|&m| (m.words().to_lowercase(), carry_colour(m, theme)))
        .collect();
    if steps.iter().any(|s| s.gyro_heading) {
        key.push(("magnetometer bent: gyroscope".to_string(), theme.reference));
    }
    key
}

/// A floor's colour on the map: the start's floor the track's own colour, the floors above
/// warm, below cool; repeating beyond three either way.
pub fn floor_colour(floor: i32, t: &Theme) -> RGBColor {
    let up = [t.gnss, t.end, t.pdr];
    let down = [t.smoothed, t.start, t.reference];
    match floor {
        0 => t.track,
        f if f > 0 => up[((f - 1) % 3) as usize],
        f => down[((-f - 1) % 3) as usize],
    }
}

/// Draws a key, coloured squares with their names, from the left of `area` at text line
/// `line` (15 px each, under the title's lines), wrapping onto the next lines when the width
/// ends. Returns the number of lines used (0 without entries).
pub fn draw_key<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor)],
    line: usize,
    font: &TextStyle,
    scale: f64,
) -> Result<usize, DrawingAreaErrorKind<DB::ErrorType>> {
    if entries.is_empty() {
        return Ok(0);
    }
    let px = |v: f64| (v * scale).round() as i32;
    let width = area.dim_in_pixel().0 as i32 - px(8.0);
    let (mut x, mut lines) = (px(8.0), 1);
    for (name, colour) in entries {
        let w = area
            .estimate_text_size(name, font)
            .map_or(px(60.0), |(w, _)| w as i32);
        let need = px(14.0) + w + px(12.0);
        if x + need > width && x > px(8.0) {
            x = px(8.0);
            lines += 1;
        }
        let y = px(4.0 + 15.0 * (line + lines - 1) as f64);
        area.draw(&Rectangle::new(
            [(x, y + px(2.0)), (x + px(10.0), y + px(12.0))],
            colour.filled(),
        ))?;
        area.draw(&Text::new(name.clone(), (x + px(14.0), y), font.clone()))?;
        x += need;
    }
    Ok(lines)
}

/// Draws a plot's title at its top left, on as many lines as it needs (a phone), broken after
/// commas. Returns the number of lines.
pub fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    font: &TextStyle,
    scale: f64,
) -> Result<usize, DrawingAreaErrorKind<DB::ErrorType>> {
    let px = |v: f64| (v * scale).round().max(1.0) as u32;
    let width = area.dim_in_pixel().0.saturating_sub(px(16.0));
    let fits = |t: &str| {
        area.estimate_text_size(t, font)
            .is_ok_and(|(w, _)| w <= width)
    };
    // Greedy: each line takes as many ", "-separated parts as fit (at least one).
    let mut lines: Vec<&str> = Vec::new();
    let mut rest = title;
    while !fits(rest) {
        let Some(i) = rest
            .match_indices(", ")
            .map(|(i, _)| i)
            .take_while(|&i| fits(&rest[..=i]))
            .last()
            .or_else(|| rest.find(", "))
        else {
            break;
        };
        lines.push(&rest[..=i]);
        rest = &rest[i + 2..];
    }
    lines.push(rest);
    for (k, line) in lines.iter().enumerate() {
        area.draw(&Text::new(
            *line,
            (px(8.0) as i32, px(4.0 + 15.0 * k as f64) as i32),
            font.clone(),
        ))?;
    }
    Ok(lines.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_activity_but_still_and_the_first_floors_have_colours_of_their_own() {
        for t in [Theme::LIGHT, Theme::DARK] {
            let acts: Vec<RGBColor> = Activity::ALL
                .iter()
                .filter_map(|&a| activity_colour(a, &t))
                .collect();
            assert_eq!(acts.len(), Activity::ALL.len() - 1);
            let floors: Vec<RGBColor> = (-3..=3).map(|f| floor_colour(f, &t)).collect();
            for set in [&acts, &floors] {
                for (i, a) in set.iter().enumerate() {
                    for b in &set[i + 1..] {
                        assert_ne!((a.0, a.1, a.2), (b.0, b.1, b.2));
                    }
                    assert_ne!(
                        (a.0, a.1, a.2),
                        (t.background.0, t.background.1, t.background.2)
                    );
                }
            }
            assert_eq!(floor_colour(4, &t), floor_colour(1, &t));
            let carry: Vec<RGBColor> = CarryMode::ALL
                .iter()
                .map(|&m| carry_colour(m, &t))
                .collect();
            for (i, a) in carry.iter().enumerate() {
                let plot = [&t.reference, &t.background, &t.gnss, &t.track];
                for b in carry[i + 1..].iter().chain(plot) {
                    assert_ne!((a.0, a.1, a.2), (b.0, b.1, b.2));
                }
            }
        }
    }
}

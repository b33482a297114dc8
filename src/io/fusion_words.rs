//! The fusion filter's learnt corrections and what it did with the fixes, in words for people:
//! upload mode's figures and live mode's readouts say them the same way (as
//! [`super::export::activity_words`] does for activities).
//! May import: `engine` only.
//!
//! "step-length scale 0.93 ± 0.02 · heading correction −4.1° ± 1.2°": the scale with two
//! decimals, the correction in degrees with one, each with its standard deviation (1σ), a minus
//! sign (U+2212) for negative corrections.

use crate::engine::fusion::{FixCounts, FusedStep};

/// A number with `d` decimals and a minus sign (U+2212), never "−0.0"; "–" when not finite.
fn signed(x: f64, d: usize) -> String {
    if !x.is_finite() {
        return "–".to_string();
    }
    let s = format!("{:.*}", d, x.abs());
    if x < 0.0 && s.bytes().any(|b| (b'1'..=b'9').contains(&b)) {
        format!("\u{2212}{s}")
    } else {
        s
    }
}

/// The step-length scale and its standard deviation: "0.93 ± 0.02".
pub fn scale_text(scale: f64, sd: f64) -> String {
    format!("{} ± {}", signed(scale, 2), signed(sd, 2))
}

/// The heading correction and its standard deviation, both in radians: "−4.1° ± 1.2°".
pub fn correction_text(bias_rad: f64, sd_rad: f64) -> String {
    format!(
        "{}° ± {}°",
        signed(bias_rad.to_degrees(), 1),
        signed(sd_rad.to_degrees(), 1)
    )
}

/// The corrections: "step-length scale 0.93 ± 0.02 · heading correction −4.1° ± 1.2°"
/// (`scale_sd` the scale's standard deviation, the correction and its own in radians).
pub fn corrections_text(scale: f64, scale_sd: f64, bias_rad: f64, bias_sd_rad: f64) -> String {
    format!(
        "step-length scale {} · heading correction {}",
        scale_text(scale, scale_sd),
        correction_text(bias_rad, bias_sd_rad)
    )
}

/// A fused step's corrections ([`corrections_text`]).
pub fn step_corrections_text(f: &FusedStep) -> String {
    corrections_text(f.scale, f.scale_bias_sd[0], f.bias_rad, f.scale_bias_sd[1])
}

/// What the filter did with the fixes: "112 used, 9 refused by the gate, 1 position reset",
/// then the other refusals that happened ("3 too inaccurate", "2 stale", "40 while the receiver
/// was off", "4 superseded"). The used count is always there.
pub fn fix_counts_text(c: &FixCounts) -> String {
    let mut parts = vec![format!("{} used", c.used)];
    let plural = |n: u64, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    for (n, text) in [
        (
            c.gated,
            plural(c.gated, "refused by the gate", "refused by the gate"),
        ),
        (
            c.resets,
            plural(c.resets, "position reset", "position resets"),
        ),
        (
            c.too_inaccurate,
            format!("{} too inaccurate", c.too_inaccurate),
        ),
        (c.stale, format!("{} stale", c.stale)),
        (
            c.receiver_off,
            format!("{} while the receiver was off", c.receiver_off),
        ),
        (c.superseded, format!("{} superseded", c.superseded)),
    ] {
        if n > 0 {
            parts.push(text);
        }
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(scale: f64, bias_deg: f64, sd: [f64; 2]) -> FusedStep {
        FusedStep {
            t: 0.0,
            east_m: 0.0,
            north_m: 0.0,
            cov: [1.0, 0.0, 1.0],
            scale,
            bias_rad: bias_deg.to_radians(),
            scale_bias_sd: [sd[0], sd[1].to_radians()],
            innovation: None,
            fix: None,
        }
    }

    #[test]
    fn corrections_are_said_with_their_uncertainty() {
        assert_eq!(
            step_corrections_text(&step(0.93, -4.1, [0.02, 1.2])),
            "step-length scale 0.93 ± 0.02 · heading correction \u{2212}4.1° ± 1.2°"
        );
        assert_eq!(
            step_corrections_text(&step(1.07, 12.34, [0.004, 0.05])),
            "step-length scale 1.07 ± 0.00 · heading correction 12.3° ± 0.1°"
        );
        // No "−0.0", and no NaN: a dash.
        assert_eq!(correction_text((-0.01f64).to_radians(), 0.0), "0.0° ± 0.0°");
        assert_eq!(scale_text(f64::NAN, 0.1), "– ± 0.10");
    }

    #[test]
    fn fix_counts_name_only_what_happened() {
        let mut c = FixCounts {
            used: 112,
            ..FixCounts::default()
        };
        assert_eq!(fix_counts_text(&c), "112 used");
        c.gated = 9;
        c.resets = 1;
        c.receiver_off = 40;
        assert_eq!(
            fix_counts_text(&c),
            "112 used, 9 refused by the gate, 1 position reset, 40 while the receiver was off"
        );
        c.resets = 2;
        c.stale = 3;
        assert!(fix_counts_text(&c).contains("2 position resets, 3 stale"));
    }
}

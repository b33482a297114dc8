//! The recipe form's words and first guesses: how a file, its columns, sensors and units are
//! named to people, how its preview writes numbers, and which columns a sensor's fields start on.
//! May import: [`super::check`] and `super::schema`.

use super::check::FileGuess;
use super::schema::{Delimiter, Sensor, TimeUnit, ValueUnit};

/// A sensor as the form names it ("linear accelerometer").
pub fn sensor_label(s: Sensor) -> String {
    s.as_str().replace('-', " ")
}

/// A unit as people write it (m/s², µT, °/s).
pub fn unit_label(u: ValueUnit) -> String {
    u.as_str()
        .replace("m/s2", "m/s²")
        .replace("uT", "µT")
        .replace("deg/s", "°/s")
}

/// A time unit as people write it (µs).
pub fn time_unit_label(u: TimeUnit) -> &'static str {
    match u {
        TimeUnit::Us => "µs",
        u => u.as_str(),
    }
}

/// What the form says of a file under its name: its separator, its header or none, and its
/// first row ("comma-separated, header: t, x, y, z · first row: 0, 0.1, 9.8, 0.2").
pub fn file_hint(g: &FileGuess) -> String {
    let delimiter = match g.delimiter {
        Delimiter::Comma => "comma-separated",
        Delimiter::Tab => "tab-separated",
        Delimiter::Semicolon => "semicolon-separated",
        Delimiter::Whitespace => "space-separated",
        Delimiter::Auto => "auto",
    };
    let header = if g.header {
        format!("header: {}", g.columns.join(", "))
    } else {
        "no header".into()
    };
    let first = g.first.first().map(|r| r.join(", ")).unwrap_or_default();
    if first.is_empty() {
        format!("{delimiter}, {header}")
    } else {
        format!("{delimiter}, {header} · first row: {first}")
    }
}

/// The form's choices of a column of the file: `(value, label)`, the value as the recipe
/// writes it (the header name, or the 1-based number) and the label with the first row's
/// value for a file without a header ("column 2 (0.13)").
pub fn column_options(g: &FileGuess) -> Vec<(String, String)> {
    g.columns
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if g.header {
                return (c.clone(), c.clone());
            }
            let first = g.first.first().and_then(|r| r.get(i));
            let label = match first {
                Some(v) => format!("column {c} ({v})"),
                None => format!("column {c}"),
            };
            (format!("{}", i + 1), label)
        })
        .collect()
}

/// The first guess of the columns of the `index`-th sensor of a file (a file may hold several:
/// `t, ax, ay, az, gx, gy, gz`): `(field, 0-based column)` for `t` (the first column) and each
/// field the sensor needs, in the columns after the time, three on from the sensor before,
/// within the file's `columns`.
pub fn guess_columns(columns: usize, sensor: Sensor, index: usize) -> Vec<(&'static str, usize)> {
    std::iter::once("t")
        .chain(sensor.needs().iter().copied())
        .enumerate()
        .map(|(i, k)| {
            let at = if i == 0 { 0 } else { i + 3 * index };
            (k, at.min(columns.saturating_sub(1)))
        })
        .collect()
}

/// A number of the preview as the form shows it: six significant digits without trailing
/// zeros ("9.80665", "0.0123", "1.5e-7"), and three decimals from a million up (times in ms or
/// µs since an epoch: "1712345678.123"). A tie rounds away from zero, as the page's numbers
/// always did; `NaN` and infinities are named.
pub fn preview_number(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "Infinity" } else { "-Infinity" }.into();
    }
    let sign = if v < 0.0 { "-" } else { "" };
    if v.abs() >= 1e6 {
        return format!("{sign}{}", rounded(v.abs(), 3, false));
    }
    let r: f64 = rounded(v.abs(), 5, true).parse().unwrap_or(0.0);
    if r == 0.0 {
        "0".into()
    } else if r < 1e-6 {
        format!("{sign}{r:e}")
    } else {
        format!("{sign}{r}")
    }
}

/// `a` (≥ 0, finite) with `digits` decimals, of the mantissa when `sci`; a tie (the exact
/// value half-way) rounds up, where Rust's formatter would round to even.
fn rounded(a: f64, digits: usize, sci: bool) -> String {
    // 1100 digits hold any f64 exactly.
    let exact = if sci {
        format!("{a:.1100e}")
    } else {
        format!("{a:.1100}")
    };
    let mantissa = exact.split('e').next().unwrap_or_default();
    let after = mantissa.split_once('.').map_or("", |(_, f)| f);
    let tie = after
        .get(digits..)
        .is_some_and(|rest| rest.trim_end_matches('0') == "5");
    // The next f64 up (a > 0 here: zero is never a tie) is past the tie, so it rounds up.
    let a = if tie {
        f64::from_bits(a.to_bits() + 1)
    } else {
        a
    };
    if sci {
        format!("{a:.digits$e}")
    } else {
        format!("{a:.digits$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_sensor_starts_three_columns_on() {
        let cols = guess_columns(7, Sensor::Gyroscope, 1);
        assert_eq!(cols, vec![("t", 0), ("x", 4), ("y", 5), ("z", 6)]);
        assert_eq!(guess_columns(2, Sensor::Accelerometer, 0)[3], ("z", 1));
        assert_eq!(unit_label(ValueUnit::MS2), "m/s²");
        assert_eq!(time_unit_label(TimeUnit::Us), "µs");
    }

    #[test]
    fn preview_numbers_read_as_the_page_always_showed_them() {
        // What `Number(v.toPrecision(6)).toString()` and `v.toFixed(3)` give in a browser.
        for (v, shown) in [
            (9.80665, "9.80665"),
            (9.806649, "9.80665"),
            (0.1 + 0.2, "0.3"),
            (100.0, "100"),
            (-0.5, "-0.5"),
            (0.0, "0"),
            (-0.0, "0"),
            (123456.5, "123457"),
            (-123456.5, "-123457"),
            (999999.5, "1000000"),
            (0.000_012_345_67, "0.0000123457"),
            (1.5e-7, "1.5e-7"),
            (1_712_345_678.123_4, "1712345678.123"),
            (1_000_000.062_5, "1000000.063"),
            (-2_000_000.0, "-2000000.000"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-Infinity"),
        ] {
            assert_eq!(preview_number(v), shown, "{v}");
        }
    }
}

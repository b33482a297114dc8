//! The recipe form's words and first guesses: how a file, its columns, sensors and units are
//! named to people, and which columns a sensor's fields start on.
//! May import: [`super::check`] and [`super::schema`].

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
}

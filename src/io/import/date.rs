//! When a recording was made: the calendar dates and Unix clocks the formats carry, as Unix
//! seconds, for [`Log::date_unix_s`](super::Log::date_unix_s) (the World Magnetic Model needs
//! the date of the walk for the declination). May import: `engine` and `io`.

use crate::engine::fusion::declination::is_unix_time_s;

/// Unix seconds of a UTC calendar date and time, `None` for a date that does not exist.
pub fn unix_of_civil(y: i64, month: u32, day: u32, h: u32, mi: u32, s: u32) -> Option<f64> {
    if !(1..=12).contains(&month) || !(1..=31).contains(&day) || h > 23 || mi > 59 || s > 60 {
        return None;
    }
    // Howard Hinnant's civil date → days.
    let y = y - i64::from(month <= 2);
    let era = y.div_euclid(400);
    let yoe = y.rem_euclid(400);
    let m = i64::from(month);
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(day) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    Some((days * 86_400 + i64::from(h) * 3600 + i64::from(mi) * 60 + i64::from(s)) as f64)
}

/// The UTC calendar date and time `(year, month, day, hour, minute, second)` of Unix seconds
/// `t` (the fraction dropped, as JavaScript's dates do); `None` outside JavaScript's dates
/// (±8.64e12 s) or for a non-finite `t`.
pub fn civil_of_unix(t: f64) -> Option<(i64, u32, u32, u32, u32, u32)> {
    if !t.is_finite() || t.abs() > 8.64e12 {
        return None;
    }
    let secs = t.floor() as i64;
    let (days, sod) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let (year, month, day) = civil_of_days(days);
    let sod = sod as u32;
    Some((year, month, day, sod / 3600, sod / 60 % 60, sod % 60))
}

/// The calendar date `(year, month, day)` of `days` since 1970-01-01 (Howard Hinnant's
/// algorithm, exact over the whole `i64` range used here).
pub fn civil_of_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = (if mp < 10 { mp + 3 } else { mp - 9 }) as u32;
    (yoe + era * 400 + i64::from(month <= 2), month, day)
}

const MONTHS: [&str; 12] = [
    "jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec",
];

/// A date as Java's `Date.toString` writes it (GetSensorData's `% Date of creation:` line):
/// `Wed Jun 14 10:00:58 GMT+02:00 2023`, as Unix seconds. The zone is read when it is `UTC`,
/// `GMT` or `GMT±hh:mm`; another name (`CEST`) is taken for UTC, which errs by hours at most,
/// nothing for the declination. `None` when the text is not such a date.
pub fn java_date(text: &str) -> Option<f64> {
    let f: Vec<&str> = text.split_whitespace().collect();
    // weekday, month, day, time, [zone,] year
    let (mon, day, time, zone, year) = match f.as_slice() {
        [_, mon, day, time, zone, year] => (*mon, *day, *time, Some(*zone), *year),
        [_, mon, day, time, year] => (*mon, *day, *time, None, *year),
        _ => return None,
    };
    let month = MONTHS
        .iter()
        .position(|m| mon.get(..3).is_some_and(|p| p.eq_ignore_ascii_case(m)))?
        + 1;
    let hms: Vec<u32> = time
        .split(':')
        .map(|x| x.parse().ok())
        .collect::<Option<_>>()?;
    let [h, mi, s] = hms.as_slice() else {
        return None;
    };
    let t = unix_of_civil(
        year.parse().ok()?,
        month as u32,
        day.parse().ok()?,
        *h,
        *mi,
        *s,
    )?;
    Some(t - zone.map_or(0.0, zone_offset_s))
}

/// The offset of a Java time-zone text from UTC, s: `GMT+02:00` → 7200; 0 for a name.
fn zone_offset_s(zone: &str) -> f64 {
    let Some(rest) = zone
        .strip_prefix("GMT")
        .or_else(|| zone.strip_prefix("UTC"))
    else {
        return 0.0;
    };
    let (sign, rest) = match rest.as_bytes().first() {
        Some(b'+') => (1.0, &rest[1..]),
        Some(b'-') => (-1.0, &rest[1..]),
        _ => return 0.0,
    };
    let mut it = rest.split(':');
    let h: f64 = it.next().and_then(|x| x.parse().ok()).unwrap_or(0.0);
    let m: f64 = it.next().and_then(|x| x.parse().ok()).unwrap_or(0.0);
    if h > 14.0 || m > 59.0 {
        return 0.0;
    }
    sign * (h * 3600.0 + m * 60.0)
}

/// The date of a log whose clock is Unix time: its first time, when that looks like one
/// ([`is_unix_time_s`]); `None` for a clock counted from boot or from the start.
pub fn from_clock(first_t: Option<f64>) -> Option<f64> {
    first_t.filter(|&t| is_unix_time_s(t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn civil_dates() {
        assert_eq!(unix_of_civil(1970, 1, 1, 0, 0, 0), Some(0.0));
        assert_eq!(unix_of_civil(2026, 1, 1, 0, 0, 0), Some(1_767_225_600.0));
        assert_eq!(unix_of_civil(2024, 2, 29, 12, 0, 0), Some(1_709_208_000.0));
        assert_eq!(unix_of_civil(2023, 13, 1, 0, 0, 0), None);
        for t in [
            0.0,
            1_709_208_000.0,
            1_767_225_599.5,
            -86_401.0,
            951_782_400.0,
        ] {
            let (y, mo, d, h, mi, s) = civil_of_unix(t).unwrap();
            assert_eq!(unix_of_civil(y, mo, d, h, mi, s), Some(t.floor()), "{t}");
        }
        assert_eq!(
            civil_of_unix(1_709_208_000.0),
            Some((2024, 2, 29, 12, 0, 0))
        );
        assert_eq!(civil_of_unix(-1.0), Some((1969, 12, 31, 23, 59, 59)));
        assert_eq!(civil_of_unix(f64::INFINITY), None);
    }

    #[test]
    fn java_dates() {
        // IPIN 2023 route 01: the first fix's Unix time is 1686729678 (08:01:18 UTC).
        assert_eq!(
            java_date("Wed Jun 14 10:00:58 GMT+02:00 2023"),
            Some(1_686_729_658.0)
        );
        assert_eq!(
            java_date("Thu Jan 01 00:00:00 UTC 2026"),
            Some(1_767_225_600.0)
        );
        assert_eq!(
            java_date("Mon Mar 03 09:00:00 GMT-05:30 2025"),
            unix_of_civil(2025, 3, 3, 14, 30, 0)
        );
        assert_eq!(
            java_date("Wed Jun 14 10:00:58 CEST 2023"),
            Some(1_686_736_858.0)
        );
        assert_eq!(java_date("Wed Jun 14 2023"), None);
        assert_eq!(java_date("Wed Foo 14 10:00:58 UTC 2023"), None);
        assert_eq!(java_date("Wed Jun 14 10:00 UTC 2023"), None);
    }

    #[test]
    fn unix_clocks() {
        assert_eq!(from_clock(Some(1_686_729_678.0)), Some(1_686_729_678.0));
        assert_eq!(from_clock(Some(65_093.5)), None);
        assert_eq!(from_clock(None), None);
    }
}

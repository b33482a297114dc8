//! The magnetic declination at the track's origin from the World Magnetic Model, for the log's
//! date (Basso 2021 Remark 2).
//! May import: the rest of `engine`.

use super::config::{Declination, FusionConfig};
use crate::engine::geo::LocalFrame;

/// The magnetic declination at a point, degrees (positive east), from the World Magnetic Model
/// (WMM2020 for 2020–2024, WMM2025 for 2025–2029; dates outside are clamped into that span), and
/// whether the date was inside it. `unix_s` is the date as Unix seconds; `None` takes
/// 2025-01-01.
pub fn wmm_declination_deg(
    lat_deg: f64,
    lon_deg: f64,
    h_m: f64,
    unix_s: Option<f64>,
) -> Option<(f64, bool)> {
    use world_magnetic_model::time::{Date, Month, OffsetDateTime};
    use world_magnetic_model::uom::si::angle::degree;
    use world_magnetic_model::uom::si::f32::{Angle, Length};
    use world_magnetic_model::uom::si::length::meter;
    let first = Date::from_calendar_date(2020, Month::January, 1).ok()?;
    let last = Date::from_calendar_date(2029, Month::December, 31).ok()?;
    let default = Date::from_calendar_date(2025, Month::January, 1).ok()?;
    let date = unix_s
        .filter(|s| s.is_finite())
        .and_then(|s| OffsetDateTime::from_unix_timestamp(s as i64).ok())
        .map_or(default, |d| d.date());
    let inside = date >= first && date <= last;
    let date = date.clamp(first, last);
    let field = world_magnetic_model::GeomagneticField::new(
        Length::new::<meter>(h_m as f32),
        Angle::new::<degree>(lat_deg as f32),
        Angle::new::<degree>(lon_deg as f32),
        date,
    )
    .ok()?;
    let d = f64::from(field.declination().get::<degree>());
    d.is_finite().then_some((d, inside && unix_s.is_some()))
}

/// Why the declination applied may be off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DeclinationNote {
    /// The World Magnetic Model's value without a known date in 2020–2029 (degrees).
    NoDate {
        /// The declination used, degrees.
        deg: f64,
    },
    /// The model gave none: headings are used as they are.
    Unavailable,
}

impl std::fmt::Display for DeclinationNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DeclinationNote::NoDate { deg } => write!(
                f,
                "declination {deg:.2}° from the World Magnetic Model without a known date in 2020–2029"
            ),
            DeclinationNote::Unavailable => {
                write!(f, "declination unavailable; headings used as they are")
            }
        }
    }
}

impl serde::Serialize for DeclinationNote {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Whether a time, s, is taken for Unix time: between 2017-07 and 2096 (a clock counted from
/// boot or from the start of a recording reads far less).
pub fn is_unix_time_s(t: f64) -> bool {
    (1.5e9..4.0e9).contains(&t)
}

/// The declination a configuration asks for at a frame's origin, radians, and a note when the
/// model was used without a known date.
pub fn declination_for(
    cfg: &FusionConfig,
    frame: &LocalFrame,
    fix_t: f64,
) -> (f64, Option<DeclinationNote>) {
    match cfg.declination {
        Declination::None => (0.0, None),
        Declination::Fixed { deg } => (deg.to_radians(), None),
        Declination::Wmm => {
            let date = if is_unix_time_s(fix_t) {
                Some(fix_t)
            } else {
                cfg.date_unix_s
            };
            match wmm_declination_deg(frame.lat0_deg, frame.lon0_deg, frame.h0_m, date) {
                Some((d, true)) => (d.to_radians(), None),
                Some((d, false)) => (d.to_radians(), Some(DeclinationNote::NoDate { deg: d })),
                None => (0.0, Some(DeclinationNote::Unavailable)),
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // expected values from std are fine in tests
mod tests {
    use super::*;

    #[test]
    fn declination_from_the_world_magnetic_model() {
        // Florence, 2021: Basso 2021 Remark 2 gives +3.20° (magnetic-declination.com).
        let unix_2021 = 1_639_526_400.0; // 2021-12-15
        let (d, known) = wmm_declination_deg(43.77, 11.25, 50.0, Some(unix_2021)).unwrap();
        assert!(known);
        assert!((d - 3.2).abs() < 0.4, "{d}");
        // Seattle is about 15° east.
        let (d, _) = wmm_declination_deg(47.6, -122.3, 0.0, Some(1.75e9)).unwrap();
        assert!((d - 15.0).abs() < 1.5, "{d}");
    }
}

//! Track exports: per-step CSV and GeoJSON.
//! May import: `engine` only (its tests also run the demo walk).
//!
//! CSV columns (stable; other tools read them): `t_s,east_m,north_m,heading_deg,length_m,freq_hz,
//! motion`, then `lat,lon` when the track has a geodetic origin (the first GNSS fix), then
//! `activity,up_m,floor`, then `carry`, then `gyro_heading` (each new group last, so that readers
//! of the older columns by position still work).
//! `t_s` is the log's own time base in seconds. `heading_deg` is empty for steps without a
//! heading. `motion` is the motion detector's `still`/`walking`/`running`; `activity` the step's
//! activity (Munoz Diaz 2015 §4.3: `walking`, `upstairs`, `downstairs`, `running`, …, as
//! `engine::activity::Activity::as_str` writes it); `up_m` the height after the step above the
//! walk's start, m; `floor` the floor after the step relative to the start (0, 1, −1, …);
//! `carry` where the phone was carried (`pocket`, `hand`, `swinging`, `ear`, `bag`, as
//! `engine::carry::CarryMode::as_str` writes it; empty before the detector decided, and for a
//! foot-mounted IMU); `gyro_heading` 1 where the magnetometer was disturbed and the heading
//! followed the gyroscope (`engine::magnetic`), else 0.
//!
//! Fused-track CSV (`pdr run --fused`), one row per fused step: `t_s,east_m,north_m,sd_east_m,
//! sd_north_m,scale,heading_correction_deg,fix,innovation_east_m,innovation_north_m,
//! smoothed_east_m,smoothed_north_m,lat,lon,smoothed_lat,smoothed_lon`. Positions are in the
//! local tangent plane of the first usable fix; `fix` is what happened to the fix offered at the
//! step (empty when none).
//!
//! GeoJSON: one `LineString` feature, one point per step, and the start as a `Point`. The
//! coordinates are 3D. With a geodetic origin they are WGS84 `[lon, lat, alt]` as RFC 7946
//! requires, `alt` being the origin's height plus the step's `up_m` when the first fix had an
//! altitude (`properties.altitude` = `"ellipsoidal_m"`), else `up_m` alone
//! (`"above_start_m"`); without a geodetic origin they are local `[east_m, north_m, up_m]`
//! metres, and `properties.coordinates` says `"local_enu_metres"` so that no reader mistakes
//! them for degrees. Each point's activity, floor and height are in the feature's properties
//! `activities`, `floors` and `up_m`, arrays parallel to the coordinates: one feature keeps the
//! track one line (split into a line per floor it would break at each staircase, and readers
//! that take the first feature as the track would see a part of it), and GeoJSON has no
//! per-coordinate properties. `floors_visited` lists the floors in the order first reached.
//!
//! GPX: `<ele>` (the origin's height plus `up_m`) when the first fix had an altitude.
//!
//! The origin's altitude counts as known when the frame's height is not exactly 0 m (the engine
//! sets it to 0 when the first fix has none).

use crate::engine::fusion::{FixOutcome, FusedStep};
use crate::engine::geo::LocalFrame;
use crate::engine::types::GnssFix;
use crate::engine::StepRecord;
use std::fmt::Write as _;

/// The CSV header without and with geodetic columns.
pub fn csv_header(geodetic: bool) -> &'static str {
    if geodetic {
        "t_s,east_m,north_m,heading_deg,length_m,freq_hz,motion,lat,lon,activity,up_m,floor,carry,gyro_heading"
    } else {
        "t_s,east_m,north_m,heading_deg,length_m,freq_hz,motion,activity,up_m,floor,carry,gyro_heading"
    }
}

/// The per-step track as CSV text.
pub fn track_csv(track: &[StepRecord], frame: Option<&LocalFrame>) -> String {
    let mut s = String::with_capacity(64 * (track.len() + 1));
    s.push_str(csv_header(frame.is_some()));
    s.push('\n');
    for r in track {
        let heading = r
            .heading_rad
            .map(|h| format!("{:.2}", h.to_degrees()))
            .unwrap_or_default();
        let _ = write!(
            s,
            "{:.3},{:.3},{:.3},{heading},{:.3},{:.3},{}",
            r.t,
            r.east_m,
            r.north_m,
            r.length_m,
            r.freq_hz,
            r.motion.as_str()
        );
        if let Some(f) = frame {
            let (lat, lon, _) = f.to_geodetic([r.east_m, r.north_m, 0.0]);
            let _ = write!(s, ",{lat:.8},{lon:.8}");
        }
        let carry = r.carry.map_or("", |c| c.as_str());
        let _ = write!(
            s,
            ",{},{:.3},{},{carry},{}",
            r.activity.as_str(),
            r.up_m,
            r.floor,
            u8::from(r.gyro_heading)
        );
        s.push('\n');
    }
    s
}

/// The fused and smoothed tracks as CSV text (see the module documentation).
pub fn fused_csv(fused: &[FusedStep], smoothed: &[FusedStep], frame: &LocalFrame) -> String {
    let mut s = String::with_capacity(160 * (fused.len() + 1));
    s.push_str("t_s,east_m,north_m,sd_east_m,sd_north_m,scale,heading_correction_deg,fix,innovation_east_m,innovation_north_m,smoothed_east_m,smoothed_north_m,lat,lon,smoothed_lat,smoothed_lon\n");
    for (f, m) in fused.iter().zip(smoothed) {
        let fix = f.fix.map_or("", FixOutcome::as_str);
        let (ie, inn) = f
            .innovation
            .map_or((String::new(), String::new()), |[e, n]| {
                (format!("{e:.3}"), format!("{n:.3}"))
            });
        let (lat, lon, _) = frame.to_geodetic([f.east_m, f.north_m, 0.0]);
        let (slat, slon, _) = frame.to_geodetic([m.east_m, m.north_m, 0.0]);
        let _ = writeln!(
            s,
            "{:.3},{:.3},{:.3},{:.3},{:.3},{:.5},{:.3},{fix},{ie},{inn},{:.3},{:.3},{lat:.8},{lon:.8},{slat:.8},{slon:.8}",
            f.t,
            f.east_m,
            f.north_m,
            f.cov[0].max(0.0).sqrt(),
            f.cov[2].max(0.0).sqrt(),
            f.scale,
            f.bias_rad.to_degrees(),
            m.east_m,
            m.north_m,
        );
    }
    s
}

/// The GNSS fixes, the fused and the smoothed tracks as GeoJSON features (WGS84), to go beside
/// the PDR track: a `MultiPoint` of fixes (with their accuracies) and two `LineString`s.
pub fn fusion_features(
    fixes: &[GnssFix],
    fused: &[FusedStep],
    smoothed: &[FusedStep],
    frame: &LocalFrame,
) -> Vec<serde_json::Value> {
    let line = |s: &[FusedStep]| -> Vec<[f64; 2]> {
        s.iter()
            .map(|x| {
                let (lat, lon, _) = frame.to_geodetic([x.east_m, x.north_m, 0.0]);
                [lon, lat]
            })
            .collect()
    };
    vec![
        serde_json::json!({
            "type": "Feature",
            "geometry": { "type": "MultiPoint", "coordinates": fixes.iter().map(|f| [f.lon_deg, f.lat_deg]).collect::<Vec<_>>() },
            "properties": { "name": "GNSS fixes", "accuracy_m": fixes.iter().map(|f| f.h_accuracy_m).collect::<Vec<_>>() }
        }),
        serde_json::json!({
            "type": "Feature",
            "geometry": { "type": "LineString", "coordinates": line(fused) },
            "properties": { "name": "fused track", "steps": fused.len() }
        }),
        serde_json::json!({
            "type": "Feature",
            "geometry": { "type": "LineString", "coordinates": line(smoothed) },
            "properties": { "name": "smoothed track", "steps": smoothed.len() }
        }),
    ]
}

/// The origin's altitude, m, when the first fix had one (see the module documentation).
fn known_altitude(frame: Option<&LocalFrame>) -> Option<f64> {
    frame.map(|f| f.h0_m).filter(|&h| h != 0.0)
}

/// The track as a GeoJSON FeatureCollection: a LineString with one point per step (where the
/// step ended) and the start as a Point, in 3D. WGS84 longitude/latitude/altitude when the log
/// has a GNSS origin (`frame`), else local east/north/up metres from the start
/// (`properties.coordinates` says which; GeoJSON readers take them for degrees, so such a file
/// is for plotting in metres, not for maps). The steps' activities, floors and heights are
/// arrays in the line's properties, one entry per coordinate (see the module documentation).
pub fn track_geojson(track: &[StepRecord], frame: Option<&LocalFrame>) -> serde_json::Value {
    let h0 = known_altitude(frame).unwrap_or(0.0);
    let at = |e: f64, n: f64, up: f64| match frame {
        Some(f) => {
            let (lat, lon, _) = f.to_geodetic([e, n, 0.0]);
            [lon, lat, h0 + up]
        }
        None => [e, n, up],
    };
    let coords: Vec<[f64; 3]> = track
        .iter()
        .map(|r| at(r.east_m, r.north_m, r.up_m))
        .collect();
    let distance: f64 = track
        .iter()
        .filter(|r| r.heading_rad.is_some())
        .map(|r| r.length_m)
        .sum();
    let kind = if frame.is_some() {
        "wgs84"
    } else {
        "local_enu_metres"
    };
    let altitude = match (frame, known_altitude(frame)) {
        (None, _) => "up_m",
        (Some(_), Some(_)) => "ellipsoidal_m",
        (Some(_), None) => "above_start_m",
    };
    let mut floors_visited: Vec<i32> = vec![0];
    for r in track {
        if !floors_visited.contains(&r.floor) {
            floors_visited.push(r.floor);
        }
    }
    serde_json::json!({
        "type": "FeatureCollection",
        "features": [{
            "type": "Feature",
            "geometry": { "type": "LineString", "coordinates": coords },
            "properties": {
                "name": "PDR track",
                "steps": track.len(),
                "distance_m": distance,
                "coordinates": kind,
                "altitude": altitude,
                "activities": track.iter().map(|r| r.activity.as_str()).collect::<Vec<_>>(),
                "floors": track.iter().map(|r| r.floor).collect::<Vec<_>>(),
                "up_m": track.iter().map(|r| (r.up_m * 1000.0).round() / 1000.0).collect::<Vec<_>>(),
                "floors_visited": floors_visited,
            }
        }, {
            "type": "Feature",
            "geometry": { "type": "Point", "coordinates": at(0.0, 0.0, 0.0) },
            "properties": { "name": "start", "coordinates": kind, "altitude": altitude }
        }]
    })
}

/// The track as GPX 1.1: one track point per step, with its time when the log's clock is Unix
/// time, and its `<ele>` (the origin's altitude plus the step's height) when the first fix had
/// an altitude. GPX is geodetic only: without a GNSS origin the track is placed at 0° N 0° E
/// (its shape and size in metres are right, its place is not), and the description says so.
pub fn track_gpx(track: &[StepRecord], frame: Option<&LocalFrame>) -> String {
    use std::fmt::Write as _;
    let placed = frame.copied().unwrap_or(LocalFrame::new(0.0, 0.0, 0.0));
    let desc = if frame.is_some() {
        "PDR track, placed by the log's first GNSS fix"
    } else {
        "PDR track without a GNSS origin: placed at 0 N 0 E; only its shape and size are meaningful"
    };
    let mut out = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<gpx version=\"1.1\" creator=\"pdr\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n",
    );
    let _ = write!(
        out,
        "  <metadata><desc>{desc}</desc></metadata>\n  <trk><name>PDR track</name><trkseg>\n"
    );
    for r in track {
        let (lat, lon, _) = placed.to_geodetic([r.east_m, r.north_m, 0.0]);
        let _ = write!(out, "    <trkpt lat=\"{lat:.8}\" lon=\"{lon:.8}\">");
        if let Some(h0) = known_altitude(frame) {
            let _ = write!(out, "<ele>{:.2}</ele>", h0 + r.up_m);
        }
        if (1.0e9..4.0e9).contains(&r.t) {
            let _ = write!(out, "<time>{}</time>", iso8601(r.t));
        }
        out.push_str("</trkpt>\n");
    }
    out.push_str("  </trkseg></trk>\n</gpx>\n");
    out
}

/// An activity in words for people ("Walking upstairs"), as the live readout, the pocket guard
/// and upload mode show it (both may import `io`; the files keep `Activity::as_str`).
pub fn activity_words(a: crate::engine::activity::Activity) -> &'static str {
    use crate::engine::activity::Activity;
    match a {
        Activity::Still => "Still",
        Activity::Standing => "Standing",
        Activity::Sitting => "Sitting",
        Activity::Walking => "Walking",
        Activity::Upstairs => "Walking upstairs",
        Activity::Downstairs => "Walking downstairs",
        Activity::Running => "Running",
        Activity::Handling => "Handling the phone",
    }
}

/// A floor relative to the start as a label: "floor 0", "floor +1", "floor −2" (a minus sign).
pub fn floor_label(floor: i32) -> String {
    match floor {
        0 => "floor 0".to_string(),
        f if f > 0 => format!("floor +{f}"),
        f => format!("floor \u{2212}{}", f.unsigned_abs()),
    }
}

/// A floor change for people: "+1 floor", "−2 floors" (a minus sign), nothing when 0.
pub fn floor_change(floor: i32) -> Option<String> {
    let n = floor.unsigned_abs();
    let unit = if n == 1 { "floor" } else { "floors" };
    match floor {
        0 => None,
        f if f > 0 => Some(format!("+{n} {unit}")),
        _ => Some(format!("\u{2212}{n} {unit}")),
    }
}

/// Unix seconds as an ISO 8601 UTC time with milliseconds.
fn iso8601(t: f64) -> String {
    let ms = (t * 1000.0).round() as i64;
    let (days, rem) = (ms.div_euclid(86_400_000), ms.rem_euclid(86_400_000));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}.{:03}Z",
        rem / 3_600_000,
        rem / 60_000 % 60,
        rem / 1000 % 60,
        rem % 1000
    )
}

#[cfg(test)]
mod gpx_tests {
    use super::*;

    #[test]
    fn iso_times_and_gpx_points() {
        assert_eq!(iso8601(0.0), "1970-01-01T00:00:00.000Z");
        assert_eq!(iso8601(1_795_424_328.439_6), "2026-11-23T08:58:48.440Z");
        assert_eq!(iso8601(951_782_400.0), "2000-02-29T00:00:00.000Z");
        let demo = crate::demo::run_demo();
        let gpx = track_gpx(&demo.track, None);
        assert_eq!(gpx.matches("<trkpt ").count(), demo.track.len());
        assert!(gpx.contains("0 N 0 E"));
        let j = track_geojson(&demo.track, None);
        let n = j["features"][0]["geometry"]["coordinates"]
            .as_array()
            .unwrap()
            .len();
        assert_eq!(n, demo.track.len());
    }
}

#[cfg(test)]
mod height_tests {
    use super::*;
    use crate::engine::activity::Activity;
    use crate::engine::motion::Motion;

    /// A hand-made walk: 4 level steps east, 4 steps up a staircase (+0.7 m each, floor 1
    /// from the third), 2 level steps on floor 1.
    fn stair_walk() -> Vec<StepRecord> {
        let mut out = Vec::new();
        let (mut e, mut up) = (0.0, 0.0);
        for k in 0..10 {
            let stairs = (4..8).contains(&k);
            e += if stairs { 0.3 } else { 0.7 };
            if stairs {
                up += 0.7;
            }
            out.push(StepRecord {
                t: 100.0 + 0.5 * k as f64,
                east_m: e,
                north_m: 0.0,
                heading_rad: Some(std::f64::consts::FRAC_PI_2),
                step_heading_rad: Some(std::f64::consts::FRAC_PI_2),
                length_m: if stairs { 0.3 } else { 0.7 },
                freq_hz: 2.0,
                motion: Motion::Walking,
                activity: if stairs {
                    Activity::Upstairs
                } else {
                    Activity::Walking
                },
                up_m: up,
                floor: i32::from(up > 2.0),
                pitch_amplitude_deg: Some(40.0),
                carry: Some(crate::engine::carry::CarryMode::Pocket),
                gyro_heading: k == 3,
            });
        }
        out
    }

    #[test]
    fn csv_ends_with_activity_height_floor_carry_and_gyro_heading() {
        let track = stair_walk();
        for frame in [None, Some(LocalFrame::new(45.0, 9.0, 120.0))] {
            let csv = track_csv(&track, frame.as_ref());
            let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
            let head = &rows[0];
            assert_eq!(head[6], "motion", "the old columns keep their places");
            assert_eq!(
                head[head.len() - 5..],
                ["activity", "up_m", "floor", "carry", "gyro_heading"]
            );
            assert_eq!(rows.len(), track.len() + 1);
            for (r, row) in track.iter().zip(&rows[1..]) {
                assert_eq!(row.len(), head.len());
                let n = row.len() - 2;
                assert_eq!(row[n + 1], if r.gyro_heading { "1" } else { "0" });
                assert_eq!(row[6], "walking");
                assert_eq!(row[n], "pocket");
                assert_eq!(row[n - 3], r.activity.as_str());
                assert!((row[n - 2].parse::<f64>().unwrap() - r.up_m).abs() < 1e-3);
                assert_eq!(row[n - 1].parse::<i32>().unwrap(), r.floor);
            }
            assert_eq!(
                rows[10][head.len() - 5..],
                ["walking", "2.800", "1", "pocket", "0"]
            );
            assert_eq!(
                rows[4][head.len() - 5..],
                ["walking", "0.000", "0", "pocket", "1"]
            );
        }
    }

    #[test]
    fn geojson_is_3d_with_activities_and_floors() {
        let track = stair_walk();
        // Local metres: [east, north, up].
        let j = track_geojson(&track, None);
        let p = &j["features"][0]["properties"];
        let c = j["features"][0]["geometry"]["coordinates"]
            .as_array()
            .unwrap();
        assert_eq!(c.len(), track.len());
        for (r, (x, i)) in track.iter().zip(c.iter().zip(0..)) {
            assert_eq!(x.as_array().unwrap().len(), 3);
            assert!((x[0].as_f64().unwrap() - r.east_m).abs() < 1e-12);
            assert!((x[2].as_f64().unwrap() - r.up_m).abs() < 1e-12);
            assert_eq!(p["activities"][i], r.activity.as_str());
            assert_eq!(p["floors"][i], r.floor);
            assert!((p["up_m"][i].as_f64().unwrap() - r.up_m).abs() < 1e-3);
        }
        assert_eq!(p["altitude"], "up_m");
        assert_eq!(p["floors_visited"], serde_json::json!([0, 1]));
        assert_eq!(
            j["features"][1]["geometry"]["coordinates"],
            serde_json::json!([0.0, 0.0, 0.0])
        );
        // Geodetic with a known altitude: the origin's height plus the step's.
        let f = LocalFrame::new(45.0, 9.0, 120.0);
        let j = track_geojson(&track, Some(&f));
        let last = &j["features"][0]["geometry"]["coordinates"][9];
        assert!((last[2].as_f64().unwrap() - 122.8).abs() < 1e-9, "{last}");
        assert!((last[1].as_f64().unwrap() - 45.0).abs() < 1e-3);
        assert_eq!(j["features"][0]["properties"]["altitude"], "ellipsoidal_m");
        // Without one (the engine's 0 m): the height above the start, said so.
        let j = track_geojson(&track, Some(&LocalFrame::new(45.0, 9.0, 0.0)));
        let last = &j["features"][0]["geometry"]["coordinates"][9];
        assert!((last[2].as_f64().unwrap() - 2.8).abs() < 1e-9, "{last}");
        assert_eq!(j["features"][0]["properties"]["altitude"], "above_start_m");
    }

    #[test]
    fn gpx_has_elevations_only_with_a_known_altitude() {
        let track = stair_walk();
        let gpx = track_gpx(&track, Some(&LocalFrame::new(45.0, 9.0, 120.0)));
        let ele: Vec<f64> = gpx
            .split("<ele>")
            .skip(1)
            .map(|s| s.split('<').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(ele.len(), track.len());
        for (e, r) in ele.iter().zip(&track) {
            assert!((e - (120.0 + r.up_m)).abs() < 0.006, "{e} vs {}", r.up_m);
        }
        assert!(!track_gpx(&track, None).contains("<ele>"));
        assert!(!track_gpx(&track, Some(&LocalFrame::new(45.0, 9.0, 0.0))).contains("<ele>"));
    }

    #[test]
    fn words_for_people() {
        assert_eq!(activity_words(Activity::Upstairs), "Walking upstairs");
        assert_eq!(activity_words(Activity::Sitting), "Sitting");
        assert_eq!(floor_change(0), None);
        assert_eq!(floor_change(1).as_deref(), Some("+1 floor"));
        assert_eq!(floor_change(-2).as_deref(), Some("\u{2212}2 floors"));
        assert_eq!(floor_change(3).as_deref(), Some("+3 floors"));
        assert_eq!(floor_label(0), "floor 0");
        assert_eq!(floor_label(2), "floor +2");
        assert_eq!(floor_label(-1), "floor \u{2212}1");
    }
}

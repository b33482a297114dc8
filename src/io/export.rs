//! Track exports: per-step CSV and GeoJSON.
//! May import: `engine` only (its tests also run the demo walk).
//!
//! CSV columns (stable; other tools read them): `t_s,east_m,north_m,heading_deg,length_m,freq_hz,
//! motion`, then `lat,lon` when the track has a geodetic origin (the first GNSS fix). `t_s` is the
//! log's own time base in seconds. `heading_deg` is empty for steps without a heading.
//!
//! Fused-track CSV (`pdr run --fused`), one row per fused step: `t_s,east_m,north_m,sd_east_m,
//! sd_north_m,scale,heading_correction_deg,fix,innovation_east_m,innovation_north_m,
//! smoothed_east_m,smoothed_north_m,lat,lon,smoothed_lat,smoothed_lon`. Positions are in the
//! local tangent plane of the first usable fix; `fix` is what happened to the fix offered at the
//! step (empty when none).
//!
//! GeoJSON: one `LineString` feature starting at the origin. With a geodetic origin the
//! coordinates are WGS84 `[lon, lat]` as RFC 7946 requires; without one they are local
//! `[east_m, north_m]` metres, and the feature's `properties.coordinates` says
//! `"local_enu_metres"` so that no reader mistakes them for degrees.

use crate::engine::fusion::FusedStep;
use crate::engine::geo::LocalFrame;
use crate::engine::types::GnssFix;
use crate::engine::StepRecord;
use std::fmt::Write as _;

/// The CSV header without and with geodetic columns.
pub fn csv_header(geodetic: bool) -> &'static str {
    if geodetic {
        "t_s,east_m,north_m,heading_deg,length_m,freq_hz,motion,lat,lon"
    } else {
        "t_s,east_m,north_m,heading_deg,length_m,freq_hz,motion"
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
        s.push('\n');
    }
    s
}

/// The fused and smoothed tracks as CSV text (see the module documentation).
pub fn fused_csv(fused: &[FusedStep], smoothed: &[FusedStep], frame: &LocalFrame) -> String {
    let mut s = String::with_capacity(160 * (fused.len() + 1));
    s.push_str("t_s,east_m,north_m,sd_east_m,sd_north_m,scale,heading_correction_deg,fix,innovation_east_m,innovation_north_m,smoothed_east_m,smoothed_north_m,lat,lon,smoothed_lat,smoothed_lon\n");
    for (f, m) in fused.iter().zip(smoothed) {
        let fix = f.fix.map_or(String::new(), |o| {
            serde_json::to_value(o)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default()
        });
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

/// The track as a GeoJSON FeatureCollection: a LineString with one point per step (where the
/// step ended) and the start as a Point. WGS84 longitude/latitude when the log has a GNSS
/// origin (`frame`), else local east/north metres from the start (`properties.coordinates`
/// says which; GeoJSON readers take them for degrees, so such a file is for plotting in
/// metres, not for maps).
pub fn track_geojson(track: &[StepRecord], frame: Option<&LocalFrame>) -> serde_json::Value {
    let at = |e: f64, n: f64| match frame {
        Some(f) => {
            let (lat, lon, _) = f.to_geodetic([e, n, 0.0]);
            [lon, lat]
        }
        None => [e, n],
    };
    let coords: Vec<[f64; 2]> = track.iter().map(|r| at(r.east_m, r.north_m)).collect();
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
            }
        }, {
            "type": "Feature",
            "geometry": { "type": "Point", "coordinates": at(0.0, 0.0) },
            "properties": { "name": "start", "coordinates": kind }
        }]
    })
}

/// The track as GPX 1.1: one track point per step, with its time when the log's clock is Unix
/// time. GPX is geodetic only: without a GNSS origin the track is placed at 0° N 0° E (its
/// shape and size in metres are right, its place is not), and the description says so.
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
        if (1.0e9..4.0e9).contains(&r.t) {
            let _ = write!(out, "<time>{}</time>", iso8601(r.t));
        }
        out.push_str("</trkpt>\n");
    }
    out.push_str("  </trkseg></trk>\n</gpx>\n");
    out
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

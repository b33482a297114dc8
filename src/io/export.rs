//! Track exports: per-step CSV and GeoJSON.
//!
//! CSV columns (stable; other tools read them): `t_s,east_m,north_m,heading_deg,length_m,freq_hz,
//! motion`, then `lat,lon` when the track has a geodetic origin (the first GNSS fix). `t_s` is the
//! log's own time base in seconds. `heading_deg` is empty for steps without a heading.
//!
//! GeoJSON: one `LineString` feature starting at the origin. With a geodetic origin the
//! coordinates are WGS84 `[lon, lat]` as RFC 7946 requires; without one they are local
//! `[east_m, north_m]` metres, and the feature's `properties.coordinates` says
//! `"local_enu_metres"` so that no reader mistakes them for degrees.

use crate::engine::geo::LocalFrame;
use crate::engine::pipeline::StepRecord;
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

/// The track as a GeoJSON FeatureCollection.
pub fn track_geojson(track: &[StepRecord], frame: Option<&LocalFrame>) -> serde_json::Value {
    let points = std::iter::once((0.0, 0.0)).chain(track.iter().map(|r| (r.east_m, r.north_m)));
    let coords: Vec<[f64; 2]> = match frame {
        Some(f) => points
            .map(|(e, n)| {
                let (lat, lon, _) = f.to_geodetic([e, n, 0.0]);
                [lon, lat]
            })
            .collect(),
        None => points.map(|(e, n)| [e, n]).collect(),
    };
    let distance: f64 = track
        .iter()
        .filter(|r| r.heading_rad.is_some())
        .map(|r| r.length_m)
        .sum();
    serde_json::json!({
        "type": "FeatureCollection",
        "features": [{
            "type": "Feature",
            "geometry": { "type": "LineString", "coordinates": coords },
            "properties": {
                "name": "PDR track",
                "steps": track.len(),
                "distance_m": distance,
                "coordinates": if frame.is_some() { "wgs84" } else { "local_enu_metres" },
            }
        }]
    })
}

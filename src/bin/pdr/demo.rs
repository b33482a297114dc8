//! `pdr demo`: runs the web page's demo walk and its GNSS walk and prints their figures.
//! May import: the `pdr` library; nothing of the other subcommands.

pub fn demo(json: bool) -> Result<(), String> {
    let s = pdr::demo::run_demo();
    let f = pdr::demo::run_fusion_demo();
    if json {
        let mut v = serde_json::to_value(&s).map_err(|e| e.to_string())?;
        v["fusion"] = serde_json::to_value(&f).map_err(|e| e.to_string())?;
        out!("{v}");
    } else {
        out!(
            "steps {} (truth {}), distance {:.1} m (truth {:.1} m), end error {:.2} m",
            s.steps,
            s.truth_steps,
            s.distance_m,
            s.truth_distance_m,
            s.end_error_m
        );
        out!(
            "GNSS walk: p75 error GNSS {:.2} m, PDR {:.2} m, fused {:.2} m, smoothed {:.2} m; step length × {:.3}, heading {:+.1}°",
            f.gnss_p75_m,
            f.pdr_p75_m,
            f.fused_p75_m,
            f.smoothed_p75_m,
            f.scale,
            f.heading_correction_deg
        );
    }
    Ok(())
}

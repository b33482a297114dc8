//! What an analysis says to people: the figures under the map, the corrections, a step's
//! line, where the phone was carried, and numbers written as the page's scripts write them.

use super::{Analysis, StepRecord};

/// `x` with `d` decimals as JavaScript's `toFixed` writes it: an exact tie rounds away from zero
/// (Rust's formatting rounds it to even), so the page's figures match what scripts compute.
pub fn fixed(x: f64, d: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    // The exact decimal expansion: ties at digit d + 1 are `5` followed by zeros only.
    let exact = format!("{:.*}", d + 80, x.abs());
    let cut = exact.find('.').map_or(exact.len(), |p| p + 1 + d);
    let tie = exact[cut..].starts_with('5') && exact[cut + 1..].bytes().all(|b| b == b'0');
    if tie {
        let step = libm::pow(10.0, -(d as f64));
        let up = x.abs() + step / 2.0;
        let s = format!("{:.*}", d, up);
        return if x < 0.0 { format!("-{s}") } else { s };
    }
    format!("{:.*}", d, x)
}

/// [`fixed`] with one or no decimals, or "–" without a value.
fn opt(v: Option<f64>, d: usize) -> String {
    v.map_or("–".to_string(), |v| fixed(v, d))
}

/// Where the phone was carried over a track, as shares of the steps, most first ("in a pocket
/// 97 %, not yet known 3 %"); `None` without steps. Upload mode's figures and `pdr run` say it.
pub fn carry_text(steps: &[StepRecord]) -> Option<String> {
    use crate::engine::carry::CarryMode;
    if steps.is_empty() {
        return None;
    }
    let n = steps.len() as f64;
    let mut shares: Vec<(usize, &str)> = CarryMode::ALL
        .iter()
        .map(|&m| Some(m))
        .chain([None])
        .map(|m| {
            let k = steps.iter().filter(|s| s.carry == m).count();
            (k, m.map_or("not yet known", |m| m.words()))
        })
        .filter(|(k, _)| *k > 0)
        .collect();
    crate::engine::sort::sort_by_key(&mut shares, |s| std::cmp::Reverse(s.0));
    Some(
        shares
            .iter()
            .map(|(k, w)| format!("{} {} %", w.to_lowercase(), fixed(100.0 * *k as f64 / n, 0)))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// The figures' rows as they are made: (label, text).
struct Rows(Vec<(String, String)>);

impl Rows {
    fn row(&mut self, k: &str, v: String) {
        self.0.push((k.to_string(), v));
    }
}

impl Analysis {
    /// The figures shown under the map, for people: (label, text) rows, then up to three of
    /// the reader's warnings as notes.
    pub fn figures(&self) -> Vec<(String, String)> {
        let mut rows = Rows(Vec::new());
        self.count_rows(&mut rows);
        self.heading_rows(&mut rows);
        self.truth_rows(&mut rows);
        self.gnss_rows(&mut rows);
        self.height_rows(&mut rows);
        for w in self.warnings.iter().take(3) {
            rows.row("Note", w.clone());
        }
        rows.0
    }

    /// The steps (or strides) with the truth's count, the distance and where the phone was
    /// carried.
    fn count_rows(&self, rows: &mut Rows) {
        let sc = &self.score;
        let n = self.steps.len();
        let truth = sc.truth_steps.map_or(String::new(), |t| {
            let debounced = sc.step_error_debounced_pct.map_or(String::new(), |d| {
                format!("; {} % against debounced truth", fixed(d, 1))
            });
            format!(
                " (true {t}, error {} %{debounced})",
                opt(sc.step_error_pct, 1)
            )
        });
        match sc.strides {
            // Foot mode: one record per stride, each two steps.
            Some(strides) => rows.row(
                "Strides",
                format!(
                    "{strides} ({} steps{truth}): foot mode, zero-velocity updates",
                    sc.steps
                ),
            ),
            None => match sc.steps_in_window {
                Some(inside) => rows.row(
                    "Steps",
                    format!("{n}; {inside} inside the truth's counted walk{truth}"),
                ),
                None => rows.row("Steps", format!("{n}{truth}")),
            },
        }
        rows.row(
            "Distance",
            format!(
                "{} m in {} min",
                fixed(sc.distance_m, 1),
                fixed(sc.duration_s / 60.0, 1)
            ),
        );
        if let Some(c) = self.carry_text() {
            rows.row("Carried", c);
        }
    }

    /// The steps whose heading followed the gyroscope, and those without a heading.
    fn heading_rows(&self, rows: &mut Rows) {
        let n = self.steps.len();
        // Where the magnetometer was bent, the heading followed the gyroscope (engine::magnetic).
        let held = self.steps.iter().filter(|s| s.gyro_heading).count();
        if held > 0 {
            rows.row(
                "Gyroscope heading",
                format!("{held} of {n} steps: the magnetometer was bent there"),
            );
        }
        let without = self
            .steps
            .iter()
            .filter(|s| s.heading_rad.is_none())
            .count();
        if without > 0 {
            let all: f64 = self.steps.iter().map(|s| s.length_m).sum();
            let why = match self.no_heading_why() {
                Some(why) => format!("{why}, so the track cannot be drawn"),
                None => "left out of the track".to_string(),
            };
            rows.row(
                "No heading",
                format!(
                    "{without} of {n} steps ({} m of steps in all): {why}",
                    fixed(all, 1)
                ),
            );
        }
    }

    /// The scores against the truth: waypoints, motion capture, turns, floors and loop
    /// closure.
    fn truth_rows(&self, rows: &mut Rows) {
        let sc = &self.score;
        if let Some(w) = sc.waypoint_error_m {
            rows.row(
                "Waypoints",
                format!(
                    "error p75 {} m, max {} m over {} waypoints",
                    fixed(w.p75, 1),
                    fixed(w.max, 1),
                    sc.waypoints
                ),
            );
        }
        if let Some(t) = &sc.trajectory {
            rows.row(
                "Against the motion capture",
                format!(
                    "heading error median {}° over {} steps (p75 {}°, one offset of {}° removed); distance {} m of {} m (ratio {}); position p75 {} m, pinned at the start and turned",
                    opt(t.heading_error_deg, 1),
                    t.headings_scored,
                    opt(t.heading_error_p75_deg, 1),
                    opt(t.heading_offset_deg, 0),
                    fixed(t.track_distance_m, 1),
                    fixed(t.truth_distance_m, 1),
                    opt(t.distance_ratio, 2),
                    opt(t.position_p75_m, 1)
                ),
            );
        }
        if let Some(t) = &sc.turns {
            rows.row(
                "Turns",
                format!(
                    "{} of {} true turns scored, median error {}°",
                    t.scored.len(),
                    t.turns,
                    opt(t.median_error_deg, 1)
                ),
            );
        }
        if let Some(f) = sc.floors.as_ref().filter(|f| f.landmarks > 0) {
            rows.row(
                "Floors",
                format!(
                    "{} of {} landmarks on the right relative floor",
                    f.right, f.landmarks
                ),
            );
        }
        if let Some(l) = sc.loop_closure_m {
            match sc.strides.filter(|_| sc.distance_m > 0.0) {
                Some(_) => rows.row(
                    "Loop closure",
                    format!(
                        "{} m ({} % of the distance)",
                        fixed(l, 2),
                        fixed(100.0 * l / sc.distance_m, 2)
                    ),
                ),
                None => rows.row("Loop closure", format!("{} m", fixed(l, 1))),
            }
        }
    }

    /// The GNSS's and the fusion's errors, the fixes' fate, the corrections and the verdict.
    fn gnss_rows(&self, rows: &mut Rows) {
        let sc = &self.score;
        for (e, name) in [
            (sc.gnss_error_m, "GNSS alone"),
            (sc.fused_error_m, "Fused"),
            (sc.smoothed_error_m, "Smoothed"),
        ] {
            if let Some(e) = e {
                rows.row(
                    name,
                    format!("p75 {} m, max {} m", fixed(e.p75, 1), fixed(e.max, 1)),
                );
            }
        }
        if !self.fixes.is_empty() {
            let n = self.fixes.len();
            match &self.fix_counts {
                Some(c) => rows.row(
                    "GNSS",
                    format!("{n} fixes: {}", crate::io::fusion_words::fix_counts_text(c)),
                ),
                None => rows.row("GNSS", format!("{n} fixes")),
            }
        }
        if let Some(text) = self.corrections_text() {
            rows.row("Corrections", text);
        }
        if let Some(v) = self.verdict {
            rows.row("Fusion", v.text().to_string());
        }
    }

    /// The height at the end with the floors visited, and the barometer's readings.
    fn height_rows(&self, rows: &mut Rows) {
        if self.has_height() {
            let end = self.steps.last().map_or((0.0, 0), |s| (s.up_m, s.floor));
            let floors = self.floors();
            let source = match self.vertical {
                Some(v) => format!("from {}", v.as_str()),
                None => "source not given".to_string(),
            };
            rows.row(
                "Height",
                format!(
                    "{} m at the end ({}), {} floor{} visited ({}); {source}",
                    fixed(end.0, 1),
                    crate::io::export::floor_label(end.1),
                    floors.len(),
                    if floors.len() == 1 { "" } else { "s" },
                    floors
                        .iter()
                        .map(|&f| crate::io::export::floor_label(f).replace("floor ", ""))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            );
        }
        if self.pressure_samples > 0 {
            rows.row("Barometer", format!("{} readings", self.pressure_samples));
        }
    }

    /// The fusion's corrections at the last fused step, ± 1σ: "step-length scale 0.93 ± 0.02 ·
    /// heading correction −4.1° ± 1.2°"; none without fusion.
    pub fn corrections_text(&self) -> Option<String> {
        let (f, sd) = (self.fused.last()?, self.fused_sd.last()?);
        Some(crate::io::fusion_words::corrections_text(
            f[3], sd[0], f[4], sd[1],
        ))
    }

    /// Step `i` for people: "Step 12: t = 5.43 s · length 0.68 m · frequency 1.83 Hz · heading
    /// 91° (single step 88°) · walking upstairs", then " · height 2.10 m, floor +1" when the
    /// log has a height.
    pub fn step_text(&self, i: usize) -> Option<String> {
        let s = self.steps.get(i)?;
        let t0 = self.trace.t.first().copied().unwrap_or(s.t);
        let deg = |r: Option<f64>| {
            r.map_or("–".to_string(), |r| {
                format!("{}°", fixed(r.to_degrees().rem_euclid(360.0), 0))
            })
        };
        let height = if self.has_height() {
            format!(
                " · height {} m, {}",
                fixed(s.up_m, 2),
                crate::io::export::floor_label(s.floor)
            )
        } else {
            String::new()
        };
        Some(format!(
            "Step {}: t = {} s · length {} m · frequency {} Hz · heading {} (single step {}) · {}{height}",
            i + 1,
            fixed(s.t - t0, 2),
            fixed(s.length_m, 2),
            fixed(s.freq_hz, 2),
            deg(s.heading_rad),
            deg(s.step_heading_rad),
            crate::io::export::activity_words(s.activity).to_lowercase()
        ))
    }

    /// Where the phone was carried ([`carry_text`]); `None` in foot mode.
    pub fn carry_text(&self) -> Option<String> {
        carry_text(&self.steps).filter(|_| self.score.strides.is_none())
    }
}

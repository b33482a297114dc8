//! Energy saving against best performance on real walks: every log run twice, once with every
//! fix and once with the receiver on `window_s` every `period_s` (Basso 2021 §3.1.2), scored by
//! the absolute error at the truth's geodetic waypoints, per group of logs. `pdr eval --energy`
//! prints it. May import: `engine`, `io`, and the rest of `eval`.
//!
//! Groups: a log's own group ([`Log::group`]), else its route group from an IPIN file name
//! (`…TrainingTrialNN…`: the tens digit of the route number is the kind of route, see
//! [`route_group`]), else `other`. A last row, `all`, pools every log.

use super::{evaluate, percentile, summarise, ErrorSummary, LogResult, Summary};
use crate::engine::fusion::{GnssMode, DEFAULT_PERIOD_S, DEFAULT_WINDOW_S};
use crate::engine::PipelineConfig;
use crate::io::import::Log;
use serde::Serialize;

/// One mode's figures over a group of logs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModeFigures {
    /// Median over the logs of each log's 75th percentile of the absolute error of GNSS alone,
    /// m (the fixes the mode kept are not filtered: this is every fix).
    pub gnss_p75_m: Option<f64>,
    /// The same for the fused track, m.
    pub fused_p75_m: Option<f64>,
    /// The same for the smoothed track, m.
    pub smoothed_p75_m: Option<f64>,
    /// The receiver's on time over its span, pooled over the group's logs.
    pub gnss_on_share: Option<f64>,
}

impl ModeFigures {
    fn of(s: &Summary) -> Self {
        ModeFigures {
            gnss_p75_m: s.gnss_p75_m,
            fused_p75_m: s.fused_p75_m,
            smoothed_p75_m: s.smoothed_p75_m,
            gnss_on_share: s.gnss_on_share,
        }
    }
}

/// One group's row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupRow {
    /// The group (see the module documentation).
    pub group: String,
    /// Logs in it.
    pub logs: u64,
    /// With every fix.
    pub best_performance: ModeFigures,
    /// With the receiver on `window_s` every `period_s`.
    pub energy_saving: ModeFigures,
    /// Energy saving's fused median p75 over best performance's.
    pub fused_ratio: Option<f64>,
    /// Energy saving's smoothed median p75 over best performance's.
    pub smoothed_ratio: Option<f64>,
    /// The median over the logs of each log's fused p75 in energy saving over its p75 in best
    /// performance (steadier than the ratio of medians, which jumps when one log crosses the
    /// median).
    pub fused_log_ratio: Option<f64>,
    /// The same for the smoothed track.
    pub smoothed_log_ratio: Option<f64>,
}

/// The whole comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnergyReport {
    /// Energy saving's period, s.
    pub period_s: f64,
    /// Energy saving's window, s.
    pub window_s: f64,
    /// One row per group, in name order, then `all`.
    pub groups: Vec<GroupRow>,
    /// Every log's result in best performance, then in energy saving (the rows of `pdr eval
    /// --json` for each mode).
    pub logs: [Vec<LogResult>; 2],
}

/// The route group of an IPIN 2023 log from its name: `…TrainingTrial23…` → `trials 2x`. In that
/// data set the tens digit is the kind of route (0: mostly open sky, 2: courtyards, roofs and
/// indoors, 5: floors; `../shared/data/README.md`). `None` for another name.
pub fn route_group(source: &str) -> Option<String> {
    let (_, rest) = source.rsplit_once("Trial")?;
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    let tens = digits
        .len()
        .checked_sub(2)
        .and_then(|i| digits.get(i..=i))?;
    Some(format!("trials {tens}x"))
}

fn group_of(log: &Log) -> String {
    log.group
        .clone()
        .or_else(|| route_group(&log.source))
        .unwrap_or_else(|| "other".into())
}

/// Runs every log in best performance and in energy saving, with everything else as `cfg`
/// says. Energy saving takes `cfg`'s period and window when `cfg` is in energy saving, else the
/// defaults (60 s, 10 s).
pub fn energy_report(logs: &[Log], cfg: &PipelineConfig) -> EnergyReport {
    let saving = match cfg.fusion.mode {
        m @ GnssMode::EnergySaving { .. } => m,
        _ => GnssMode::EnergySaving {
            period_s: DEFAULT_PERIOD_S,
            window_s: DEFAULT_WINDOW_S,
        },
    };
    let (period_s, window_s) = match saving {
        GnssMode::EnergySaving { period_s, window_s } => (period_s, window_s),
        _ => (DEFAULT_PERIOD_S, DEFAULT_WINDOW_S),
    };
    let run = |mode: GnssMode| -> Vec<LogResult> {
        let mut c = cfg.clone();
        c.fusion.mode = mode;
        logs.iter().map(|l| evaluate(l, &c)).collect()
    };
    let results = [run(GnssMode::BestPerformance), run(saving)];
    let groups: Vec<String> = logs.iter().map(group_of).collect();
    let mut names: Vec<&String> = groups.iter().collect();
    crate::engine::sort::sort(&mut names);
    names.dedup();
    let row = |name: &str, keep: &dyn Fn(usize) -> bool| {
        let pick = |r: &[LogResult]| -> Vec<LogResult> {
            r.iter()
                .enumerate()
                .filter(|(i, _)| keep(*i))
                .map(|(_, l)| l.clone())
                .collect()
        };
        let best = ModeFigures::of(&summarise(&pick(&results[0])));
        let energy = ModeFigures::of(&summarise(&pick(&results[1])));
        let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) if b > 0.0 => Some(a / b),
            _ => None,
        };
        let log_ratio = |get: fn(&LogResult) -> Option<ErrorSummary>| {
            let v: Vec<f64> = (0..logs.len())
                .filter(|&i| keep(i))
                .filter_map(|i| {
                    ratio(
                        get(&results[1][i]).map(|e| e.p75),
                        get(&results[0][i]).map(|e| e.p75),
                    )
                })
                .collect();
            (!v.is_empty()).then(|| percentile(&v, 50.0))
        };
        GroupRow {
            group: name.to_string(),
            logs: (0..logs.len()).filter(|&i| keep(i)).count() as u64,
            fused_ratio: ratio(energy.fused_p75_m, best.fused_p75_m),
            smoothed_ratio: ratio(energy.smoothed_p75_m, best.smoothed_p75_m),
            fused_log_ratio: log_ratio(|l| l.fused_error_m),
            smoothed_log_ratio: log_ratio(|l| l.smoothed_error_m),
            best_performance: best,
            energy_saving: energy,
        }
    };
    let mut rows: Vec<GroupRow> = names
        .iter()
        .map(|n| row(n, &|i| &groups[i] == *n))
        .collect();
    rows.push(row("all", &|_| true));
    EnergyReport {
        period_s,
        window_s,
        groups: rows,
        logs: results,
    }
}

/// The report as a Markdown table.
pub fn markdown(r: &EnergyReport) -> String {
    let m = |v: Option<f64>| v.map_or("–".into(), |x| format!("{x:.1}"));
    let x = |v: Option<f64>| v.map_or("–".into(), |x| format!("{x:.2}"));
    let xx = |a: Option<f64>, b: Option<f64>| format!("{} ({})", x(a), x(b));
    let pct = |v: Option<f64>| v.map_or("–".into(), |x| format!("{:.0} %", 100.0 * x));
    let mut s = format!(
        "Energy saving ({:.0} s every {:.0} s) against best performance: median over the logs of \
         each log's p75 absolute error, m; ratio: energy saving over best performance, of the \
         medians (and the median of the logs' own ratios)\n\n\
         | group | logs | GNSS | fused best | fused saving | ratio | smoothed best | smoothed saving | ratio | receiver on (saving) |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
        r.window_s, r.period_s
    );
    for g in &r.groups {
        let (b, e) = (&g.best_performance, &g.energy_saving);
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            g.group,
            g.logs,
            m(b.gnss_p75_m),
            m(b.fused_p75_m),
            m(e.fused_p75_m),
            xx(g.fused_ratio, g.fused_log_ratio),
            m(b.smoothed_p75_m),
            m(e.smoothed_p75_m),
            xx(g.smoothed_ratio, g.smoothed_log_ratio),
            pct(e.gnss_on_share),
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn route_groups_from_ipin_names() {
        assert_eq!(
            route_group("ipin2023/IPIN2023_T3_TrainingTrial23_repetition04.txt").as_deref(),
            Some("trials 2x")
        );
        assert_eq!(
            route_group("IPIN2023_T3_TrainingTrial01_repetition01.txt").as_deref(),
            Some("trials 0x")
        );
        assert_eq!(route_group("Trial5_x.txt"), None);
        assert_eq!(route_group("walk.pdrlog"), None);
    }
}

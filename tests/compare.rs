//! The comparison table (`pdr eval --compare`) on simulated data sets: each set is scored by the
//! truth it carries, a method that cannot run on a set says why, and the default is marked.

use pdr::compare::{compare, markdown, Cell, DataSet, Metric, COMPARED};
use pdr::io::import::{import_all, Format, Log, MemSet, Platform};
use pdr::settings::choice;
use pdr::sim::{formats, scenarios};

fn log_of(format: Format) -> Log {
    let sim = scenarios::square(15.0).generate();
    let rec = formats::write(&sim, format, Platform::Android);
    let mut logs = import_all(&mut MemSet::new(rec.files));
    assert_eq!(logs.len(), 1);
    logs.pop().unwrap().unwrap()
}

#[test]
fn every_method_on_every_set_or_why_not() {
    // Oxford: accelerometer only, step truth. x-io: accelerometer and gyroscope, loop closure.
    let sets = vec![
        DataSet {
            name: "oxford".into(),
            logs: vec![log_of(Format::OxfordSteps)],
        },
        DataSet {
            name: "xio".into(),
            logs: vec![log_of(Format::XioFoot)],
        },
    ];
    let mut started = Vec::new();
    let t = compare(&sets, |k, v| started.push(format!("{k}={v}")));
    assert_eq!(
        t.sets,
        vec![
            ("oxford".to_string(), Some(Metric::StepMaePct)),
            ("xio".to_string(), Some(Metric::LoopClosurePct)),
        ]
    );
    // One row per option of each compared choice, in order, each reported as it starts.
    let expected: Vec<String> = COMPARED
        .iter()
        .flat_map(|k| {
            choice(k)
                .unwrap()
                .options
                .iter()
                .map(move |o| format!("{k}={}", o.0))
        })
        .collect();
    assert_eq!(started, expected);
    assert_eq!(t.rows.len(), expected.len());
    // Exactly one default per choice.
    for k in COMPARED {
        let defaults = t.rows.iter().filter(|r| r.key == *k && r.default).count();
        assert_eq!(defaults, 1, "{k}");
    }
    let row = |k: &str, v: &str| t.rows.iter().find(|r| r.key == k && r.value == v).unwrap();
    // No gyroscope in Oxford: Madgwick cannot run there, and says why; it runs on x-io.
    let madgwick = row("orientation.kind", "madgwick");
    assert!(
        matches!(&madgwick.cells[0], Cell::CannotRun { why } if why.contains("gyro")),
        "{:?}",
        madgwick.cells[0]
    );
    assert!(matches!(madgwick.cells[1], Cell::Figure { skipped: 0, .. }));
    // The simulated x-io walk is a pocket phone's signal: foot mode is not recognised on it, and
    // forced on it finds no stride.
    assert!(matches!(
        row("placement", "auto").cells[1],
        Cell::Figure { foot: 0, .. }
    ));
    assert!(
        matches!(&row("placement", "foot").cells[0], Cell::CannotRun { why } if why.contains("no step"))
    );
    // Neither has an OS orientation.
    let os = row("orientation.kind", "os");
    assert!(os
        .cells
        .iter()
        .all(|c| matches!(c, Cell::CannotRun { why } if why.contains("orientation"))));
    // The default detector counts the simulated square within a few per cent.
    let Cell::Figure { value, .. } = row("detector.kind", "pll").cells[0] else {
        panic!("no figure")
    };
    assert!(value < 3.0, "step MAE {value} %");
    let md = markdown(&t);
    assert_eq!(md.lines().count(), 2 + t.rows.len());
    assert!(md.contains("cannot run: the logs have no `gyro`"), "{md}");
}

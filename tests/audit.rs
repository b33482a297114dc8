//! The locked dependencies (`Cargo.lock`, and `fuzz/Cargo.lock`) against the RustSec advisory database: a known
//! vulnerability in any locked crate fails; an informational advisory (unmaintained, unsound,
//! notice) is listed with the note in [`NOTES`] that says why the crate is still there, and
//! fails without one, so that a new one is noticed. Skipped with a message when the database is
//! absent (a user's clone): it is read from `PDR_ADVISORY_DB`, else from `../shared/advisory-db`
//! beside the repository.
//!
//! A small checker of our own rather than cargo-audit or cargo-deny: those are minutes of
//! install and build on a bare 2-core machine whose whole `./dev test` has to stay under 20
//! minutes, while this reads the lock and each advisory's TOML front matter with `toml` and
//! matches versions with `semver` (two small dev-dependencies) in well under a second. It follows
//! the database's format: `[versions] patched` and `unaffected` (semver requirements; a version
//! matching neither is affected, and with both empty every version is), `withdrawn` (ignored
//! then), `informational` (a warning, not a vulnerability), and `[affected] os` / `arch` (an
//! advisory limited to platforms we never build for — Linux on x86-64 or aarch64, and wasm32 —
//! does not count). `[affected] functions` is shown, not checked: a vulnerable version fails
//! whether or not we call the function.

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The lock files checked: the app's, and the fuzz targets' (built by `./dev test`).
const LOCKS: &[&str] = &["Cargo.lock", "fuzz/Cargo.lock"];

/// The environment variable that names the advisory database's folder.
const DB_ENV: &str = "PDR_ADVISORY_DB";

/// Informational advisories of crates that stay in the lock: (advisory id, crate, why).
const NOTES: &[(&str, &str, &str)] = &[(
    "RUSTSEC-2024-0436",
    "paste",
    "a proc-macro used at build time by simba, nalgebra's scalar traits; it generates code and is \
     not in the app. Not ours to change: it goes when simba drops it.",
)];

/// The platforms we build for: (target_os, target_arch), as in an advisory's `[affected]`.
const PLATFORMS: &[(&str, &str)] = &[
    ("linux", "x86_64"),
    ("linux", "aarch64"),
    ("unknown", "wasm32"),
];

#[derive(Debug, Deserialize)]
struct Lock {
    #[serde(default)]
    package: Vec<Locked>,
}

/// One package of `Cargo.lock`.
#[derive(Debug, Deserialize)]
struct Locked {
    name: String,
    version: String,
    /// `None` for the workspace's own packages (never in the database).
    source: Option<String>,
}

/// An advisory's front matter (fields not read here are ignored).
#[derive(Debug, Deserialize)]
struct Advisory {
    advisory: Head,
    #[serde(default)]
    versions: Versions,
    #[serde(default)]
    affected: Affected,
}

#[derive(Debug, Deserialize)]
struct Head {
    id: String,
    package: String,
    /// "unmaintained", "unsound", "notice": not a vulnerability.
    informational: Option<String>,
    /// The date it was withdrawn (a string, or a TOML date).
    withdrawn: Option<toml::Value>,
    /// The title (older advisories; newer ones have it as the Markdown's first heading).
    title: Option<String>,
}

#[derive(Debug, Default, Deserialize)]
struct Versions {
    #[serde(default)]
    patched: Vec<String>,
    #[serde(default)]
    unaffected: Vec<String>,
}

#[derive(Debug, Default, Deserialize)]
struct Affected {
    #[serde(default)]
    os: Vec<String>,
    #[serde(default)]
    arch: Vec<String>,
    #[serde(default)]
    functions: BTreeMap<String, Vec<String>>,
}

/// An advisory that hits a locked crate.
#[derive(Debug, PartialEq)]
struct Finding {
    id: String,
    krate: String,
    version: String,
    title: String,
    /// The informational kind; `None` for a vulnerability.
    informational: Option<String>,
    /// The functions `[affected]` names (shown: a vulnerable version fails whether or not we
    /// call them).
    functions: Vec<String>,
}

/// Reads one advisory file: Markdown with a TOML front matter in a ```toml fence (or, in the
/// database's older layout, a whole `.toml` file). Returns it and its title.
fn parse_advisory(text: &str) -> Result<(Advisory, String), String> {
    let (toml_text, rest) = match text.trim_start().strip_prefix("```toml") {
        Some(body) => body
            .split_once("\n```")
            .ok_or("the ```toml front matter has no end")?,
        None => (text, ""),
    };
    let adv: Advisory = toml::from_str(toml_text).map_err(|e| e.to_string())?;
    let title = adv.advisory.title.clone().unwrap_or_else(|| {
        rest.lines()
            .find_map(|l| l.strip_prefix("# "))
            .unwrap_or("(no title)")
            .trim()
            .to_string()
    });
    Ok((adv, title))
}

/// The requirements of a `[versions]` list, parsed.
fn requirements(list: &[String]) -> Result<Vec<semver::VersionReq>, String> {
    list.iter()
        .map(|r| semver::VersionReq::parse(r).map_err(|e| format!("version range {r:?}: {e}")))
        .collect()
}

/// Whether `version` of the advisory's crate is affected: not withdrawn, on a platform we build
/// for, and matching neither a patched nor an unaffected range.
fn affects(adv: &Advisory, version: &semver::Version) -> Result<bool, String> {
    if adv.advisory.withdrawn.is_some() {
        return Ok(false);
    }
    let a = &adv.affected;
    let ours = PLATFORMS.iter().any(|(os, arch)| {
        (a.os.is_empty() || a.os.iter().any(|o| o == os))
            && (a.arch.is_empty() || a.arch.iter().any(|x| x == arch))
    });
    if !ours {
        return Ok(false);
    }
    let safe = requirements(&adv.versions.patched)?
        .into_iter()
        .chain(requirements(&adv.versions.unaffected)?)
        .any(|r| r.matches(version));
    Ok(!safe)
}

/// The advisories that hit the crates of `lock` (Cargo.lock's text), from `advisories` (each
/// file's text, as read by [`parse_advisory`]).
fn audit(lock: &str, advisories: &[(Advisory, String)]) -> Result<Vec<Finding>, String> {
    let lock: Lock = toml::from_str(lock).map_err(|e| format!("Cargo.lock: {e}"))?;
    let mut found = Vec::new();
    for p in lock.package.iter().filter(|p| p.source.is_some()) {
        let version = semver::Version::parse(&p.version)
            .map_err(|e| format!("Cargo.lock: {} {}: {e}", p.name, p.version))?;
        for (adv, title) in advisories
            .iter()
            .filter(|(a, _)| a.advisory.package == p.name)
        {
            if affects(adv, &version).map_err(|e| format!("{}: {e}", adv.advisory.id))? {
                found.push(Finding {
                    id: adv.advisory.id.clone(),
                    krate: p.name.clone(),
                    version: p.version.clone(),
                    title: title.clone(),
                    informational: adv.advisory.informational.clone(),
                    functions: adv.affected.functions.keys().cloned().collect(),
                });
            }
        }
    }
    Ok(found)
}

/// The report of the findings: `Ok(listing)` when there is no vulnerability and every
/// informational finding has its note in `notes`, `Err(listing)` otherwise. A note whose
/// advisory no longer hits the lock is an error too, so the list stays true.
fn verdict(found: &[Finding], notes: &[(&str, &str, &str)]) -> Result<String, String> {
    let mut out = String::new();
    let mut failed = false;
    let vulnerable: Vec<&Finding> = found.iter().filter(|f| f.informational.is_none()).collect();
    out += &format!("{} vulnerabilities\n", vulnerable.len());
    for f in &vulnerable {
        failed = true;
        out += &format!(
            "  VULNERABLE {} {}: {} {}\n",
            f.krate, f.version, f.id, f.title
        );
        if !f.functions.is_empty() {
            out += &format!("    in: {}\n", f.functions.join(", "));
        }
    }
    for f in found.iter().filter(|f| f.informational.is_some()) {
        let kind = f.informational.as_deref().unwrap_or_default();
        out += &format!("  {kind} {} {}: {} {}\n", f.krate, f.version, f.id, f.title);
        match notes.iter().find(|(id, k, _)| *id == f.id && *k == f.krate) {
            Some((_, _, why)) => out += &format!("    kept: {why}\n"),
            None => {
                failed = true;
                out +=
                    "    no note: replace the crate, or say in tests/audit.rs NOTES why it stays\n";
            }
        }
    }
    for (id, krate, _) in notes {
        if !found.iter().any(|f| f.id == *id && f.krate == *krate) {
            failed = true;
            out += &format!("  the note on {krate} ({id}) is stale: the lock no longer has it\n");
        }
    }
    if failed {
        Err(out)
    } else {
        Ok(out)
    }
}

/// The advisory database's folder, or `None` when `../shared/advisory-db` is absent. A folder
/// named by `PDR_ADVISORY_DB` must be a database: a wrong path there is an error, not a skip.
fn database() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os(DB_ENV).map(PathBuf::from) {
        assert!(
            dir.join("crates").is_dir(),
            "{DB_ENV}={}: no advisory database there (no crates/ folder)",
            dir.display()
        );
        return Some(dir);
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/advisory-db");
    dir.join("crates").is_dir().then_some(dir)
}

/// Every advisory in `db/crates/<name>/` for the names of the locked crates.
fn advisories_of(db: &Path, names: &[String]) -> Vec<(Advisory, String)> {
    let mut out = Vec::new();
    for name in names {
        let Ok(dir) = std::fs::read_dir(db.join("crates").join(name)) else {
            continue;
        };
        for entry in dir {
            let path = entry.expect("the advisory folder lists").path();
            let ext = path.extension().and_then(|e| e.to_str());
            if !matches!(ext, Some("md") | Some("toml")) {
                continue;
            }
            let text = std::fs::read_to_string(&path).expect("an advisory reads");
            let adv = parse_advisory(&text)
                .unwrap_or_else(|e| panic!("{}: unreadable advisory: {e}", path.display()));
            out.push(adv);
        }
    }
    out
}

#[test]
fn locked_dependencies_have_no_known_vulnerability() {
    let Some(db) = database() else {
        eprintln!(
            "skipped: no advisory database (set {DB_ENV}, or put it in ../shared/advisory-db)"
        );
        return;
    };
    let mut found: Vec<Finding> = Vec::new();
    for file in LOCKS {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
        let lock = std::fs::read_to_string(&path).expect("the lock file reads");
        let parsed: Lock = toml::from_str(&lock).expect("the lock file parses");
        let mut names: Vec<String> = parsed.package.into_iter().map(|p| p.name).collect();
        names.sort();
        names.dedup();
        let advisories = advisories_of(&db, &names);
        println!(
            "audit: {file}: {} locked crates against {} advisories of theirs in {}",
            names.len(),
            advisories.len(),
            db.display()
        );
        for f in audit(&lock, &advisories).unwrap() {
            if !found.contains(&f) {
                found.push(f);
            }
        }
    }
    match verdict(&found, NOTES) {
        Ok(listing) => print!("{listing}"),
        Err(listing) => panic!("dependency audit failed:\n{listing}"),
    }
}

/// A lock of two crates from the registry and the workspace's own package.
const LOCK: &str = r#"
version = 4

[[package]]
name = "pdr"
version = "0.1.0"

[[package]]
name = "ring"
version = "0.16.20"
source = "registry+https://github.com/rust-lang/crates.io-index"

[[package]]
name = "tiny"
version = "1.2.3"
source = "registry+https://github.com/rust-lang/crates.io-index"
"#;

/// An advisory of `package` with the given extra front matter.
fn advisory(id: &str, package: &str, extra: &str) -> (Advisory, String) {
    let text = format!(
        "```toml\n[advisory]\nid = \"{id}\"\npackage = \"{package}\"\ndate = \"2025-03-06\"\n\
         {extra}\n```\n\n# A title for {id}\n\nWords.\n"
    );
    parse_advisory(&text).unwrap()
}

fn ids(found: &[Finding]) -> Vec<&str> {
    found.iter().map(|f| f.id.as_str()).collect()
}

#[test]
fn a_planted_vulnerable_version_fails() {
    let advs = [advisory(
        "RUSTSEC-0000-0001",
        "ring",
        "[versions]\npatched = [\">= 0.17.12\"]",
    )];
    let found = audit(LOCK, &advs).unwrap();
    assert_eq!(
        found,
        [Finding {
            id: "RUSTSEC-0000-0001".into(),
            krate: "ring".into(),
            version: "0.16.20".into(),
            title: "A title for RUSTSEC-0000-0001".into(),
            informational: None,
            functions: vec![],
        }]
    );
    let e = verdict(&found, &[]).unwrap_err();
    assert!(
        e.contains("1 vulnerabilities") && e.contains("VULNERABLE ring 0.16.20"),
        "{e}"
    );
}

#[test]
fn patched_and_unaffected_ranges_clear_a_version() {
    let cases = [
        ("[versions]\npatched = [\">= 0.16.20\"]", false),
        (
            "[versions]\npatched = [\">= 0.17.0\", \">= 0.16.21, < 0.17.0\"]",
            true,
        ),
        (
            "[versions]\npatched = [\">= 0.17.0\", \">= 0.16.20, < 0.17.0\"]",
            false,
        ),
        (
            "[versions]\npatched = []\nunaffected = [\"< 0.16.0\"]",
            true,
        ),
        ("[versions]\npatched = []\nunaffected = [\"0.16\"]", false),
        (
            "[versions]\npatched = [\"^0.15\"]\nunaffected = [\"=0.16.20\"]",
            false,
        ),
        // No range at all: every version.
        ("[versions]\npatched = []", true),
        ("", true),
    ];
    for (extra, hit) in cases {
        let found = audit(LOCK, &[advisory("RUSTSEC-0000-0002", "ring", extra)]).unwrap();
        assert_eq!(found.len(), usize::from(hit), "{extra}");
    }
}

#[test]
fn a_withdrawn_advisory_and_another_platforms_do_not_count() {
    let advs = [
        advisory(
            "RUSTSEC-0000-0003",
            "ring",
            "withdrawn = \"2025-04-01\"\n[versions]\npatched = []",
        ),
        advisory(
            "RUSTSEC-0000-0004",
            "ring",
            "[versions]\npatched = []\n[affected]\nos = [\"windows\"]",
        ),
        advisory(
            "RUSTSEC-0000-0005",
            "ring",
            "[versions]\npatched = []\n[affected]\narch = [\"wasm32\"]\n\
             functions = { \"ring::aead::seal\" = [\"< 0.17\"] }",
        ),
        advisory(
            "RUSTSEC-0000-0006",
            "ring",
            "[versions]\npatched = []\n[affected]\nos = [\"linux\", \"macos\"]\narch = [\"mips\"]",
        ),
    ];
    let found = audit(LOCK, &advs).unwrap();
    assert_eq!(ids(&found), ["RUSTSEC-0000-0005"]);
    let e = verdict(&found, &[]).unwrap_err();
    assert!(e.contains("    in: ring::aead::seal\n"), "{e}");
}

#[test]
fn informational_advisories_are_listed_with_their_note_or_fail_without_one() {
    let advs = [
        advisory(
            "RUSTSEC-0000-0007",
            "tiny",
            "informational = \"unmaintained\"\n[versions]\npatched = []",
        ),
        advisory(
            "RUSTSEC-0000-0008",
            "tiny",
            "informational = \"unsound\"\n[versions]\npatched = [\">= 1.2.4\"]",
        ),
        // Another crate's advisory, and one for a version we do not have.
        advisory("RUSTSEC-0000-0009", "other", "[versions]\npatched = []"),
        advisory(
            "RUSTSEC-0000-0010",
            "tiny",
            "[versions]\nunaffected = [\">= 1\"]",
        ),
    ];
    let found = audit(LOCK, &advs).unwrap();
    assert_eq!(ids(&found), ["RUSTSEC-0000-0007", "RUSTSEC-0000-0008"]);
    let notes = [
        ("RUSTSEC-0000-0007", "tiny", "used only by the build script"),
        (
            "RUSTSEC-0000-0008",
            "tiny",
            "we never call the unsound function",
        ),
    ];
    let listing = verdict(&found, &notes).unwrap();
    assert!(listing.starts_with("0 vulnerabilities\n"), "{listing}");
    assert!(listing.contains("unmaintained tiny 1.2.3: RUSTSEC-0000-0007"));
    assert!(listing.contains("kept: used only by the build script"));
    let e = verdict(&found, &notes[..1]).unwrap_err();
    assert!(e.contains("no note"), "{e}");
    // A note whose advisory is gone is stale.
    let e = verdict(&found[..1], &notes).unwrap_err();
    assert!(e.contains("stale"), "{e}");
}

#[test]
fn bad_advisories_and_ranges_are_errors() {
    assert!(parse_advisory("```toml\n[advisory]\nid = \"X\"\n").is_err());
    assert!(parse_advisory("```toml\n[versions]\npatched = []\n```\n").is_err());
    let advs = [advisory(
        "RUSTSEC-0000-0011",
        "ring",
        "[versions]\npatched = [\"newer than 1\"]",
    )];
    let e = audit(LOCK, &advs).unwrap_err();
    assert!(
        e.contains("RUSTSEC-0000-0011") && e.contains("newer than 1"),
        "{e}"
    );
    // The old layout: a whole TOML file, its title in the front matter.
    let (adv, title) = parse_advisory(
        "[advisory]\nid = \"RUSTSEC-2017-0001\"\npackage = \"ring\"\ntitle = \"Old\"\n\
         [versions]\npatched = [\">= 0.17\"]\n",
    )
    .unwrap();
    assert_eq!(
        (adv.advisory.id.as_str(), title.as_str()),
        ("RUSTSEC-2017-0001", "Old")
    );
}

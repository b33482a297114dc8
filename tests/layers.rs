//! The layers point down, and no two modules import each other: read from the crate's own
//! sources (`src/`, outside the binary), every `use` and every path through `crate::`,
//! `super::` or `self::` in non-test code is resolved to the module it names.
//!
//! - Each top-level module may import only the layers below it ([`ALLOWED`]): `engine` nothing
//!   above it, `io` only `engine`, and so on (each module's first lines say the same).
//! - No circle between modules: an edge goes from a file's module to the module a path names
//!   (the longest module prefix of the path); edges between a module and its own ancestors
//!   (a child using an item its parent declares or re-exports) are not counted.
//!
//! Native only (it reads the source tree).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// What each top-level module may import, besides itself.
const ALLOWED: &[(&str, &[&str])] = &[
    ("engine", &[]),
    ("view", &[]),
    ("settings", &["engine"]),
    ("io", &["engine", "view"]),
    ("sim", &["engine", "io"]),
    ("eval", &["engine", "io"]),
    ("compare", &["engine", "io", "eval", "settings"]),
    ("live", &["engine", "io", "view"]),
    ("analysis", &["engine", "io", "eval", "view"]),
    ("plot", &["engine", "analysis"]),
    ("demo", &["engine", "sim", "eval", "analysis"]),
    (
        "web",
        &[
            "engine", "settings", "io", "sim", "eval", "live", "analysis", "plot", "demo", "view",
        ],
    ),
];

type Module = Vec<String>;

/// The module of each source file under `src/` (the binary excluded), and its text.
fn sources() -> BTreeMap<Module, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p: PathBuf = e.unwrap().path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n != "bin") {
                    stack.push(p);
                }
                continue;
            }
            if p.extension().map_or(true, |x| x != "rs") {
                continue;
            }
            let rel = p.strip_prefix(&root).unwrap();
            let mut m: Module = rel
                .iter()
                .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
                .collect();
            if m.last().is_some_and(|l| l == "mod" || l == "lib") {
                m.pop();
            }
            out.insert(m, std::fs::read_to_string(&p).unwrap());
        }
    }
    out
}

/// The code before the file's tests, without comments and string literals.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            // A character literal ('"', '\'', 'x'), not a lifetime: skipped whole.
            '\'' if matches!(chars.clone().nth(1), Some('\'')) => {
                chars.nth(1);
            }
            '\'' if chars.peek() == Some(&'\\') => {
                chars.next();
                chars.next();
                while chars.next().is_some_and(|c| c != '\'') {}
            }
            '"' => {
                let mut escaped = false;
                for c in chars.by_ref() {
                    if c == '"' && !escaped {
                        break;
                    }
                    escaped = c == '\\' && !escaped;
                }
                out.push_str("\"\"");
            }
            _ => out.push(c),
        }
    }
    out
}

/// Expands a `use` tree (`super::{a, b::{c, d}}`) into its paths.
fn expand(tree: &str) -> Vec<String> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or(tree).trim();
        return vec![path.to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.trim().is_empty())
        .flat_map(expand)
        .map(|p| {
            if p == "self" {
                prefix.trim_end_matches("::").to_string()
            } else {
                format!("{prefix}{p}")
            }
        })
        .collect()
}

/// Every path a file's code names through `crate::`, `super::` or `self::`.
fn paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("use ") {
        let before = rest[..i].chars().last();
        let after = &rest[i + 4..];
        let end = after.find(';').unwrap_or(after.len());
        if before.map_or(true, |c| !c.is_alphanumeric() && c != '_') {
            out.extend(expand(&after[..end]));
        }
        rest = &after[end.min(after.len())..];
    }
    let bytes: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < bytes.len() {
        let starts = ["crate::", "super::", "self::"]
            .iter()
            .find(|s| code_at(&bytes, i, s));
        let boundary = i == 0 || !(bytes[i - 1].is_alphanumeric() || bytes[i - 1] == '_');
        if let (Some(_), true) = (starts, boundary) {
            let mut j = i;
            while j < bytes.len()
                && (bytes[j].is_alphanumeric() || bytes[j] == '_' || bytes[j] == ':')
            {
                j += 1;
            }
            out.push(
                bytes[i..j]
                    .iter()
                    .collect::<String>()
                    .trim_end_matches(':')
                    .into(),
            );
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

fn code_at(chars: &[char], i: usize, s: &str) -> bool {
    s.chars()
        .enumerate()
        .all(|(k, c)| chars.get(i + k) == Some(&c))
}

/// The module a path names from `from`: resolved to absolute segments, then cut to the longest
/// prefix that is a module. `None` for paths outside the crate.
fn target(from: &Module, path: &str, modules: &BTreeSet<Module>) -> Option<Module> {
    let mut segs = path.split("::").map(str::trim).filter(|s| !s.is_empty());
    let mut abs: Module = match segs.next()? {
        "crate" => Vec::new(),
        "self" => from.clone(),
        "super" => from[..from.len().saturating_sub(1)].to_vec(),
        _ => return None,
    };
    for s in segs {
        if s == "super" {
            abs.pop();
        } else {
            abs.push(s.to_string());
        }
    }
    while !modules.contains(&abs) {
        abs.pop()?;
    }
    Some(abs)
}

fn edges() -> BTreeMap<Module, BTreeSet<Module>> {
    let src = sources();
    let modules: BTreeSet<Module> = src.keys().cloned().collect();
    let mut out: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (m, text) in &src {
        for p in paths(&code(text)) {
            if let Some(t) = target(m, &p, &modules) {
                let related = t.starts_with(m) || m.starts_with(&t);
                if !related {
                    out.entry(m.clone()).or_default().insert(t);
                }
            }
        }
    }
    out
}

#[test]
fn each_layer_imports_only_the_layers_below_it() {
    let allowed: BTreeMap<&str, &[&str]> = ALLOWED.iter().copied().collect();
    let mut wrong = Vec::new();
    for (from, targets) in edges() {
        let Some(top) = from.first() else { continue };
        let ok = allowed
            .get(top.as_str())
            .unwrap_or_else(|| panic!("no layer rule for `{top}`: add it to ALLOWED"));
        for t in targets {
            let Some(tt) = t.first() else { continue };
            if tt != top && !ok.contains(&tt.as_str()) {
                wrong.push(format!("{} imports {}", from.join("::"), t.join("::")));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_two_modules_import_each_other() {
    let e = edges();
    // Depth-first search for a circle.
    fn visit(
        m: &Module,
        e: &BTreeMap<Module, BTreeSet<Module>>,
        path: &mut Vec<Module>,
        done: &mut BTreeSet<Module>,
    ) -> Option<Vec<Module>> {
        if let Some(i) = path.iter().position(|p| p == m) {
            let mut circle = path[i..].to_vec();
            circle.push(m.clone());
            return Some(circle);
        }
        if done.contains(m) {
            return None;
        }
        path.push(m.clone());
        for t in e.get(m).into_iter().flatten() {
            if let Some(c) = visit(t, e, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(m.clone());
        None
    }
    let mut done = BTreeSet::new();
    for m in e.keys() {
        if let Some(c) = visit(m, &e, &mut Vec::new(), &mut done) {
            let shown: Vec<String> = c.iter().map(|m| m.join("::")).collect();
            panic!("an import circle: {}", shown.join(" → "));
        }
    }
}

#[test]
fn the_checks_see_imports() {
    // The parser itself: grouped and nested `use` trees, `super` and `self`.
    let mut got = expand("super::{a, b::{c, d as e}, self}");
    got.sort();
    assert_eq!(got, ["super", "super::a", "super::b::c", "super::b::d"]);
    let modules: BTreeSet<Module> = [vec![], vec!["engine".into()], vec!["io".into()]]
        .into_iter()
        .collect();
    let from: Module = vec!["io".into()];
    assert_eq!(
        target(&from, "super::engine::types::Record", &modules),
        Some(vec!["engine".to_string()])
    );
    assert_eq!(target(&from, "std::fmt", &modules), None);
    // And the real tree has edges to check: io's readers import the engine's records.
    let e = edges();
    let from_io_to_engine = e.iter().any(|(m, t)| {
        m.first().is_some_and(|f| f == "io")
            && t.iter().any(|t| t.first().is_some_and(|f| f == "engine"))
    });
    assert!(
        from_io_to_engine,
        "no edge found from io to engine: the parser sees nothing"
    );
}

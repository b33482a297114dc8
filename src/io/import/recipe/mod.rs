//! Recipes: logs from any recorder, read by a column mapping the user writes once.
//! May import: `engine`, `io` and `view`.
//!
//! Many research and hobby loggers write one CSV per sensor, with or without a header, in their
//! own column order, separator and units (`acc.csv`: `time in ms, x, y, z`, no header). No
//! format sniffing can know which column is what, so the user says it once in a [`Recipe`]: for
//! each file (matched by name), the sensor it holds, where its time and values are, and their
//! units. The page builds it with a form; `pdr run --recipe FILE` and `pdr eval --recipe FILE`
//! read the same JSON. The schema is in the README ("Logs from any recorder (recipes)").
//!
//! - [`Recipe::from_json`]: the JSON, checked (unknown fields, columns the sensor needs, units
//!   that fit it) with an error naming the file entry and field.
//! - [`Recipe::match_dir`]: which files of a folder the recipe reads (by name).
//! - [`read_dir`]: the files read into one [`Log`](super::Log) (through the same
//!   [`Streams`](super::Streams) merge as every other per-sensor folder), with a
//!   [`check::Report`]: the first rows as parsed, in SI units, and sanity warnings.
//! - [`check::describe`]: a first guess (columns, separator, header, sensor, time unit) of the
//!   files of an unrecognised upload, for the page's form; [`form`]: the form's words and its
//!   guess of the columns; [`form_view`]: the form and the preview as the page shows them, and
//!   the recipe the form's values make.

pub mod check;
mod error;
pub mod form;
pub mod form_view;
mod merge;
pub mod read;
mod schema;

pub use check::{describe, Description, FileReport, Report};
pub use error::RecipeError;
pub use merge::{read_dir, read_set, RecipeLog};
pub use schema::{
    Column, Columns, Delimiter, FileRule, Recipe, Sensor, TimeUnit, ValueUnit, RECIPE_VERSION,
};

/// Reads a recipe file (`pdr run --recipe FILE`); errors name the file.
pub fn load(path: &std::path::Path) -> Result<Recipe, RecipeError> {
    let file = |why: String| RecipeError::File {
        path: path.display().to_string(),
        why,
    };
    let text = std::fs::read_to_string(path).map_err(|e| file(e.to_string()))?;
    Recipe::from_json(&text).map_err(|e| file(e.to_string()))
}

/// Why a recipe reads no folder of a file set: for the folder with the most files, the reason
/// [`Recipe::match_dir`] gives (e.g. `no file matches "acc.csv"`).
pub fn why_not(set: &dyn super::FileSet, recipe: &Recipe) -> String {
    let names = set.names();
    let mut dirs: Vec<&str> = names.iter().map(|n| super::fileset::parent(n)).collect();
    dirs.sort_unstable();
    dirs.dedup();
    let count = |d: &str| {
        names
            .iter()
            .filter(|n| super::fileset::parent(n) == d)
            .count()
    };
    let Some(dir) = dirs.iter().copied().max_by_key(|d| count(d)) else {
        return "there are no files".into();
    };
    match recipe.match_dir(names, dir) {
        Err(e) if dir.is_empty() => e.to_string(),
        Err(e) => format!("in {dir}: {e}"),
        Ok(_) => "it matches".into(),
    }
}

/// Whether a file name matches a pattern: the whole base name, case-insensitive, `*` standing
/// for any run of characters and `?` for one. A pattern holds no folder: it is compared with
/// the file's base name.
pub fn glob(pattern: &str, name: &str) -> bool {
    let p: Vec<char> = pattern.to_lowercase().chars().collect();
    let n: Vec<char> = name.to_lowercase().chars().collect();
    // Iterative wildcard matching with one backtrack point (the last `*`): linear in practice,
    // never exponential.
    let (mut i, mut j) = (0usize, 0usize);
    let mut star: Option<(usize, usize)> = None;
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some((i, j));
            i += 1;
        } else if let Some((si, sj)) = star {
            i = si + 1;
            j = sj + 1;
            star = Some((si, sj + 1));
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::glob;

    #[test]
    fn globs_match_whole_names() {
        assert!(glob("acc.csv", "ACC.csv"));
        assert!(glob("acc*.csv", "acc_2024.csv"));
        assert!(glob("acc*.csv", "acc.csv"));
        assert!(!glob("acc*.csv", "gyr.csv"));
        assert!(!glob("acc.csv", "acc.csv.bak"));
        assert!(glob("?yr.*", "gyr.txt"));
        assert!(glob("*", "anything"));
        assert!(!glob("a*b*c", "aXbY"));
        assert!(glob("a*b*c", "aXbYc"));
    }
}

//! Why a recipe cannot be used, in the words the page, the CLI and the tests show.
//! May import: nothing.

use std::fmt;

/// Why a recipe cannot be read, written or applied. Each message names what is wrong (the file
/// entry and field, the pattern, the file) so that the user can fix the recipe.
#[derive(Debug, Clone, PartialEq)]
pub enum RecipeError {
    /// The text is not a recipe's JSON (syntax, a missing or unknown field): serde's words.
    Json(String),
    /// The JSON reads but breaks a rule of [`Recipe::check`](super::Recipe::check): the
    /// message names the entry and field.
    Invalid(String),
    /// The recipe reads no folder of the files ([`Recipe::match_dir`](super::Recipe::match_dir)):
    /// which entry matches no file, or several.
    NoMatch(String),
    /// The recipe could not be written as JSON.
    Write(String),
    /// A recipe file could not be read or is not a recipe: its path and why.
    File {
        /// The file's path as given.
        path: String,
        /// Why (the file system's words, or the recipe's error).
        why: String,
    },
}

impl fmt::Display for RecipeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RecipeError::Json(e) => write!(f, "recipe: {e}"),
            RecipeError::Invalid(m) | RecipeError::NoMatch(m) => f.write_str(m),
            RecipeError::Write(e) => write!(f, "recipe: cannot be written as JSON: {e}"),
            RecipeError::File { path, why } => write!(f, "{path}: {why}"),
        }
    }
}

impl std::error::Error for RecipeError {}

/// The CLI reports errors as text.
impl From<RecipeError> for String {
    fn from(e: RecipeError) -> String {
        e.to_string()
    }
}

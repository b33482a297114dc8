//! Helpers of the recipe tests (`tests/recipe.rs`, `tests/recipe_walks.rs`).

use pdr::io::import::recipe::{self, Recipe, Report};
use pdr::io::import::{Log, MemSet};

/// The one log `recipe` reads from `files`, with its report.
pub fn read(files: Vec<(String, Vec<u8>)>, recipe: &Recipe) -> (Log, Report) {
    let mut set = MemSet::new(files);
    let mut r = recipe::read_set(&mut set, recipe);
    assert_eq!(r.len(), 1, "one log");
    r.pop().unwrap().expect("reads")
}

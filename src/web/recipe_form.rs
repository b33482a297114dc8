//! The recipe form's engine side: the form, a sensor row and its fields as view trees, and the
//! recipe the form's values make ([`crate::io::import::recipe::form_view`]), and a recipe
//! file's check ([`recipe_in`], [`recipe_normalise`]).
//! May import: `io`.

use super::{to_js, to_json_value};
use crate::io::import::recipe::form_view::{Form, RowValues};
use crate::io::import::recipe::{check::FileGuess, Recipe};
use wasm_bindgen::prelude::*;

/// The recipe form for the files of an unrecognised upload (`Upload.describe()`).
#[wasm_bindgen]
pub struct RecipeForm {
    form: Form,
}

#[wasm_bindgen]
impl RecipeForm {
    /// The form for `description` (`{files, draft}`, as `Upload.describe()` gives it).
    #[wasm_bindgen(constructor)]
    pub fn new(description: JsValue) -> Result<RecipeForm, JsError> {
        #[derive(serde::Deserialize)]
        struct Description {
            files: Vec<FileGuess>,
            draft: Option<serde_json::Value>,
        }
        let d: Description = super::from_js(&description).map_err(to_js)?;
        let draft = match d.draft {
            Some(r) => Some(serde_json::from_str::<Recipe>(&r.to_string()).map_err(to_js)?),
            None => None,
        };
        Ok(RecipeForm {
            form: Form::new(d.files, draft),
        })
    }

    /// The form's elements, in order (view trees).
    pub fn view(&self) -> Result<JsValue, JsError> {
        to_json_value(&self.form.view())
    }

    /// Row `index` of file `file` (its name), a new one without a draft rule (a view tree).
    pub fn row(&self, file: &str, index: usize) -> Result<JsValue, JsError> {
        to_json_value(&self.form.row(file, index).map_err(to_js)?)
    }

    /// The fields of row `index` of file `file` for `sensor` (`""`: not used), a view tree.
    pub fn fields(&self, file: &str, index: usize, sensor: &str) -> Result<JsValue, JsError> {
        to_json_value(&self.form.fields(file, index, sensor).map_err(to_js)?)
    }

    /// The recipe (JSON) the form's values make: the name field's `name` and each sensor row's
    /// `{file, selects: [{k or col, value}]}`.
    pub fn recipe(&self, name: &str, rows: JsValue) -> Result<String, JsError> {
        let rows: Vec<RowValues> = super::from_js(&rows).map_err(to_js)?;
        self.form.recipe(name, &rows).map_err(to_js)
    }
}

/// A file's text as a recipe, normalised ([`recipe_normalise`]), or `undefined` when it is not
/// one (a recording's JSON uploaded beside the recipes): a recipe uploaded with its files is
/// applied to them.
#[wasm_bindgen]
pub fn recipe_in(text: &str) -> Option<String> {
    Recipe::from_json(text).ok()?.to_json().ok()
}

/// Checks a recipe's JSON and returns it normalised (pretty, as the CLI reads it), or the error.
#[wasm_bindgen]
pub fn recipe_normalise(json: &str) -> Result<String, JsError> {
    Recipe::from_json(json)
        .map_err(to_js)?
        .to_json()
        .map_err(to_js)
}

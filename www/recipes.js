// Recipes (README, "Logs from any recorder"): the form upload mode offers when no recording is
// recognised, and the recipes saved on this device (localStorage). The parsing, the preview and
// the sanity checks are the engine's (src/io/import/recipe, through the worker), and so are the
// form, its preview and the recipe its values make (form_view.rs); this file only wires the
// form's events, keeps the saved recipes and hands the recipe JSON around.
// The recipes' functions are upload mode's wasm module's (loaded when files are opened, before
// the form shows).
import {
  $, download, editStored, readStored, render, safeName, uploadExports as wasm, uploadWasm,
} from './util.js';

const LIST = 'pdr-recipes';

/** `{name: json}` of every saved recipe. */
export const saved = () => readStored(LIST, 'recipes') ?? {};

/** Saves a recipe (its JSON, checked by the engine) under its own name; refused while the
 * stored recipes cannot be read. */
export function save(json) {
  const text = wasm.recipe_normalise(json);
  editStored(LIST, 'recipes', (all) => { all[JSON.parse(text).name] = text; });
}

/**
 * Whether uploaded files may hold recipes: small `.json` files, which the engine may read as a
 * recipe; a recipe uploaded beside its files is applied to them, without saving it.
 */
export function mayHoldRecipes(files) {
  return files.some((f) => /\.json$/i.test(f.name) && f.file.size < 65536);
}

/** See [`mayHoldRecipes`]: the recipes among the files, and the other files. */
export async function splitUploaded(files) {
  const { recipe_in } = await uploadWasm();
  const recipes = [];
  const rest = [];
  for (const f of files) {
    // A JSON file that is not a recipe is a recording's.
    const recipe = mayHoldRecipes([f]) ? recipe_in(await f.file.text()) : undefined;
    if (recipe) recipes.push(recipe);
    else rest.push(f);
  }
  return { files: rest, recipes };
}

let form = null; // {engine: RecipeForm, preview(json), run(json)}
let timer = 0;

/** The form's values for the engine (`RecipeForm.recipe`): each sensor row's file, and its
 * selects' `{k or col, value}` (their `data-k` or `data-col`). */
const values = () => [...$('recipe-form').querySelectorAll('.recipe-sensor')].map((row) => ({
  file: row.closest('fieldset').dataset.file,
  selects: [...row.querySelectorAll('select')].map((s) => ({ ...s.dataset, value: s.value })),
}));

/**
 * The recipe (JSON) the form describes now: an entry for each sensor of each file (a file may
 * hold several, e.g. `t, ax, ay, az, gx, gy, gz`); sensors marked "not used" left out.
 */
const current = () => form.engine.recipe($('recipe-name').value, values());

function changed() {
  clearTimeout(timer);
  timer = setTimeout(() => form.preview(current()), 150);
}

/** A change in the files' selects: another sensor gets its fields (the engine's first guess). */
function fileChanged(e) {
  if (e.target.dataset.k === 'sensor') {
    const row = e.target.closest('.recipe-sensor');
    const index = [...row.parentNode.children].indexOf(row);
    const file = row.closest('fieldset').dataset.file;
    row.querySelector('.recipe-fields').replaceWith(render(form.engine.fields(file, index, e.target.value)));
  }
  changed();
}

/** "+ another sensor in this file": a row after the file's others. */
function moreClicked(e) {
  if (!e.target.matches('.recipe-more')) return;
  const rows = e.target.closest('fieldset').querySelector('.recipe-sensors');
  rows.append(render(form.engine.row(e.target.closest('fieldset').dataset.file, rows.children.length)));
  changed();
}

/** Saves the form's recipe, and says so (or why not). */
function saveClicked() {
  const msg = $('recipe-saved');
  try {
    save(current());
    msg.className = 'hint';
    msg.textContent = `Saved as recipe "${JSON.parse(current()).name}" on this device: files that match it are read with it from now on.`;
  } catch (err) {
    msg.className = 'error';
    msg.textContent = String(err?.message ?? err);
  }
}

/**
 * Shows the form for the files of `description` (`Upload.describe`, made a form by the
 * engine's `RecipeForm`): `preview(json)` asks the worker for a preview, `run(json)` reads the
 * files with the recipe.
 */
export function showForm(description, { preview, run }) {
  const box = $('recipe-form');
  form?.engine.free();
  form = { engine: new wasm.RecipeForm(description), preview, run };
  box.replaceChildren(...form.engine.view().map(render));
  box.querySelector('.recipe-files').addEventListener('change', fileChanged);
  box.querySelector('.recipe-files').addEventListener('click', moreClicked);
  $('recipe-run').addEventListener('click', () => form.run(current()));
  $('recipe-save').addEventListener('click', saveClicked);
  $('recipe-download').addEventListener('click', () => {
    try {
      const text = wasm.recipe_normalise(current());
      download(text, `${safeName(JSON.parse(text).name)}.recipe.json`, 'application/json');
    } catch (err) { $('recipe-saved').textContent = String(err?.message ?? err); }
  });
  box.hidden = false;
  preview(current());
}

/** Hides the form (a new upload). */
export function hideForm() {
  $('recipe-form').hidden = true;
  $('recipe-form').replaceChildren();
  form?.engine.free();
  form = null;
}

/** Shows the worker's preview (`Upload.preview`): its messages and tables as the engine made
 * them; the mapping cannot run while the preview is an error. */
export function showPreview(result) {
  if (!form) return;
  $('recipe-run').disabled = !!result.error;
  $('recipe-warnings').replaceChildren(...result.messages.map(render));
  $('recipe-preview').replaceChildren(...result.tables.map(render));
}

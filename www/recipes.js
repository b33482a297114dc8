// Recipes (README, "Logs from any recorder"): the form upload mode offers when no recording is
// recognised, and the recipes saved on this device (localStorage). The parsing, the preview and
// the sanity checks are the engine's (src/io/import/recipe, through the worker); this file only
// builds the form, keeps the saved recipes and hands the recipe JSON around.
import { recipe_choices, recipe_guess_columns, recipe_normalise } from './pkg/pdr.js';
import { $, download, el, readStored, safeName } from './util.js';

const LIST = 'pdr-recipes';

/** `{name: json}` of every saved recipe. */
export const saved = () => readStored(LIST, 'recipes') ?? {};

/** Saves a recipe (its JSON, checked by the engine) under its own name; refused while the
 * stored recipes cannot be read. */
export function save(json) {
  const text = recipe_normalise(json);
  const all = readStored(LIST, 'recipes');
  if (!all) throw new Error('The stored recipes cannot be read and cannot be kept aside: nothing was saved.');
  all[JSON.parse(text).name] = text;
  localStorage.setItem(LIST, JSON.stringify(all));
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
  const recipes = [];
  const rest = [];
  for (const f of files) {
    if (mayHoldRecipes([f])) {
      try {
        recipes.push(recipe_normalise(await f.file.text()));
        continue;
      } catch { /* not a recipe: a recording's JSON */ }
    }
    rest.push(f);
  }
  return { files: rest, recipes };
}

const base = (name) => name.split('/').pop();

let form = null; // {files: [{guess, rules}], preview(json), run(json)}
let timer = 0;

/**
 * The recipe the form describes now: an entry for each sensor of each file (a file may hold
 * several, e.g. `t, ax, ay, az, gx, gy, gz`); sensors marked "not used" left out.
 */
function current() {
  const box = $('recipe-form');
  const files = [];
  for (const f of form.files) {
    const fs = box.querySelector(`fieldset[data-file="${CSS.escape(f.guess.name)}"]`);
    for (const row of fs.querySelectorAll('.recipe-sensor')) {
      const get = (k) => row.querySelector(`[data-k="${k}"]`)?.value;
      const sensor = get('sensor');
      if (!sensor) continue;
      const columns = {};
      for (const s of row.querySelectorAll('[data-col]')) {
        columns[s.dataset.col] = f.guess.header ? s.value : Number(s.value);
      }
      const rule = { match: base(f.guess.name), sensor, delimiter: f.guess.delimiter, header: f.guess.header, columns, time_unit: get('time_unit') };
      const unit = get('unit');
      if (unit) rule.unit = unit;
      files.push(rule);
    }
  }
  return JSON.stringify({ recipe: 1, name: $('recipe-name').value.trim() || 'my logger', files });
}

/** A select named `key` (`data-k`) of `[value, label]` choices, set to `value`. */
function choice(key, pairs, value) {
  const s = el('select', {}, ...pairs.map(([v, label]) => new Option(label, v)));
  s.dataset.k = key;
  s.value = value;
  return s;
}

/**
 * The column and unit selects of one sensor row of a file, for its sensor: the rule's, else the
 * engine's first guess for the file's `index`-th sensor (`recipe_guess_columns`).
 */
function fields(row, f, rule, index) {
  const choices = recipe_choices();
  const sensor = row.querySelector('[data-k="sensor"]').value;
  const box = row.querySelector('.recipe-fields');
  box.replaceChildren();
  if (!sensor) return;
  const spec = choices.sensors.find((c) => c.sensor === sensor);
  for (const [k, at] of recipe_guess_columns(f.guess.columns.length, sensor, index)) {
    const sel = el('select', {}, ...f.guess.options.map(([value, label]) => new Option(label, value)));
    sel.dataset.col = k;
    sel.value = rule?.columns?.[k] != null ? String(rule.columns[k]) : f.guess.options[at]?.[0];
    box.append(el('label', {}, k === 't' ? 'time ' : `${k} `, sel));
  }
  box.append(el('label', {}, 'time in ', choice('time_unit', choices.time_units, rule?.time_unit ?? 'ms')));
  if (spec.units.length) {
    box.append(el('label', {}, 'unit ', choice('unit', spec.units, rule?.sensor === sensor && rule?.unit ? rule.unit : spec.units[0][0])));
  }
}

function changed() {
  clearTimeout(timer);
  timer = setTimeout(() => form.preview(current()), 150);
}

/**
 * Shows the form for the files of `description` (`Upload.describe`): `preview(json)` asks the
 * worker for a preview, `run(json)` reads the files with the recipe.
 */
export function showForm(description, { preview, run }) {
  const box = $('recipe-form');
  const draft = description.draft ?? { files: [] };
  form = {
    files: description.files.map((guess) => ({ guess, rules: draft.files.filter((r) => r.match === base(guess.name)) })),
    preview,
    run,
  };
  const sensors = recipe_choices().sensors;
  const list = el('div', { className: 'recipe-files' });
  for (const f of form.files) {
    const g = f.guess;
    const fs = el('fieldset', { className: 'recipe-file' });
    fs.dataset.file = g.name;
    const rows = el('div', { className: 'recipe-sensors' });
    const addRow = (rule) => {
      const index = rows.children.length;
      const sensor = choice('sensor', [['', 'not used'], ...sensors.map((s) => [s.sensor, s.label])], rule?.sensor ?? '');
      const row = el('div', { className: 'recipe-sensor controls' }, el('label', {}, 'sensor ', sensor), el('span', { className: 'recipe-fields controls' }));
      sensor.addEventListener('change', () => { fields(row, f, rule, index); changed(); });
      rows.append(row);
      fields(row, f, rule, index);
    };
    const more = el('button', { type: 'button', className: 'small recipe-more', textContent: '+ another sensor in this file' });
    more.addEventListener('click', () => { addRow(null); changed(); });
    fs.append(el('legend', { textContent: base(g.name) }),
      el('p', { className: 'hint', textContent: g.hint }),
      rows, more);
    list.append(fs);
    for (const rule of f.rules.length ? f.rules : [null]) addRow(rule);
  }
  list.addEventListener('change', (e) => { if (e.target.dataset.k !== 'sensor') changed(); });
  const name = el('input', { id: 'recipe-name', type: 'text', value: 'my logger', maxLength: 100 });
  name.setAttribute('aria-label', 'Recipe name');
  const runB = el('button', { id: 'recipe-run', type: 'button', className: 'primary', textContent: 'Read with this mapping' });
  const saveB = el('button', { id: 'recipe-save', type: 'button', textContent: 'Save as recipe' });
  const dlB = el('button', { id: 'recipe-download', type: 'button', className: 'small', textContent: 'Download recipe (JSON)' });
  runB.addEventListener('click', () => form.run(current()));
  saveB.addEventListener('click', () => {
    const msg = $('recipe-saved');
    try {
      save(current());
      msg.className = 'hint';
      msg.textContent = `Saved as recipe "${JSON.parse(current()).name}" on this device: files that match it are read with it from now on.`;
    } catch (err) {
      msg.className = 'error';
      msg.textContent = String(err?.message ?? err);
    }
  });
  dlB.addEventListener('click', () => {
    try {
      const text = recipe_normalise(current());
      download(text, `${safeName(JSON.parse(text).name)}.recipe.json`, 'application/json');
    } catch (err) { $('recipe-saved').textContent = String(err?.message ?? err); }
  });
  box.replaceChildren(
    el('h3', { textContent: 'Describe these files' }),
    el('p', { className: 'hint', textContent: 'No known recorder wrote these files. Say what each holds: the preview below shows the first rows as they will be read, in SI units, and warns when a unit looks wrong. The same mapping works with pdr run --recipe FILE.' }),
    list,
    el('div', { className: 'controls' }, el('label', {}, 'name ', name), runB, saveB, dlB),
    el('p', { id: 'recipe-saved', className: 'hint' }),
    el('ul', { id: 'recipe-warnings', className: 'messages', ariaLive: 'polite' }),
    el('div', { id: 'recipe-preview' }),
  );
  box.hidden = false;
  preview(current());
}

/** Hides the form (a new upload). */
export function hideForm() {
  $('recipe-form').hidden = true;
  $('recipe-form').replaceChildren();
  form = null;
}

const fmt = (v) => (Math.abs(v) >= 1e6 ? v.toFixed(3) : Number(v.toPrecision(6)).toString());

/** Shows the worker's preview: `{report}` or `{error}`. */
export function showPreview(result) {
  if (!form) return;
  const warnings = $('recipe-warnings');
  const box = $('recipe-preview');
  warnings.replaceChildren();
  box.replaceChildren();
  $('recipe-run').disabled = !!result.error;
  if (result.error) {
    warnings.append(el('li', { className: 'error', textContent: result.error }));
    return;
  }
  const r = result.report;
  for (const w of r.warnings) warnings.append(el('li', { className: 'warn', textContent: w }));
  for (const n of r.notes) warnings.append(el('li', { className: 'note', textContent: n }));
  for (const f of r.files) {
    const head = el('tr', {}, ...f.columns.map((c) => el('th', { textContent: c })));
    const rows = f.rows.map((row) => el('tr', {}, ...row.map((v) => el('td', { textContent: fmt(v) }))));
    const facts = [`${f.sensor}`, `${f.samples.toLocaleString('en')} samples previewed`];
    if (f.rate_hz != null) facts.push(`${fmt(f.rate_hz)} Hz`);
    if (f.median != null) facts.push(`median |v| ${fmt(f.median)}`);
    if (f.skipped) facts.push(`${f.skipped} lines skipped (${f.errors[0]?.message ?? ''})`);
    box.append(el('div', { className: 'recipe-table' },
      el('h4', { textContent: `${base(f.file)} — ${facts.join(' · ')}` }),
      el('table', {}, el('thead', {}, head), el('tbody', {}, ...rows))));
  }
}

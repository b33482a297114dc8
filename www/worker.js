// Upload mode's worker: the files are read, parsed and run through the engine here, off the
// page's thread. Messages in: {type: 'load', files: [{name, file}], configs: {a, b}} and
// {type: 'rerun', indices, configs} and {type: 'pdrlog', index}, a config being
// {settings, label}; 'load' may carry recipes: [json], and {type: 'preview', recipe} asks what a
// recipe makes of the loaded files. Out: 'progress', 'parsed', 'describe' (when nothing was
// recognised), 'preview', 'analysis' (bytes, transferred), 'pdrlog', 'done', 'failed'.
// Upload mode's wasm module (the importers, zip, csv, the analysis), not the page's.
import init, { Upload } from './pkg-upload/pdr.js';

let upload = null;
const ready = init();

/** The engine's linear memory, MB (it grows and never shrinks: its high-water mark). */
let memoryMb = () => 0;
ready.then((w) => { memoryMb = () => w.memory.buffer.byteLength / 1e6; });

function analyse(index, config, tag) {
  let last = 0;
  const t0 = performance.now();
  const bytes = upload.analyse(index, config.settings, (done, total) => {
    const now = performance.now();
    if (now - last > 50 || done === total) {
      last = now;
      postMessage({ type: 'progress', phase: 'engine', index, done, total });
    }
  });
  // The whole call (configuration, engine, serialisation, copy out) and the engine alone.
  const totalMs = performance.now() - t0;
  postMessage({ type: 'analysis', index, tag, label: config.label, bytes, analyse_ms: totalMs, engine_ms: upload.engine_ms, memory_mb: memoryMb() }, [bytes.buffer]);
}

/** Runs the logs `indices` with each configuration of `configs` (`{a, b}`), then says it is done. */
function analyseAll(indices, configs) {
  for (const index of indices) for (const [tag, config] of Object.entries(configs)) analyse(index, config, tag);
  postMessage({ type: 'done' });
}

onmessage = async ({ data }) => {
  try {
    await ready;
    if (data.type === 'load') {
      upload = new Upload();
      upload.set_recipes(data.recipes ?? []);
      // The files stay where they are: the parser reads them a slice at a time.
      const total = data.files.reduce((s, f) => s + f.file.size, 0);
      for (const { name, file } of data.files) upload.add_file(name, file);
      postMessage({ type: 'progress', phase: 'read', done: 0, total });
      const t0 = performance.now();
      const parsed = upload.parse((read) => postMessage({ type: 'progress', phase: 'read', done: Math.min(read, total), total }));
      postMessage({ type: 'parsed', parsed, parse_ms: performance.now() - t0, bytes: total });
      // Nothing recognised: the files described for the recipe form.
      if (!parsed.logs.length) postMessage({ type: 'describe', description: upload.describe(() => {}) });
      analyseAll(parsed.logs.map((log) => log.index), data.configs);
    } else if (data.type === 'rerun') {
      analyseAll(data.indices, data.configs);
    } else if (data.type === 'preview') {
      postMessage({ type: 'preview', result: upload.preview(data.recipe, () => {}) });
    } else if (data.type === 'pdrlog') {
      postMessage({ type: 'pdrlog', index: data.index, text: upload.pdrlog(data.index) });
    }
  } catch (err) {
    postMessage({ type: 'failed', message: String(err?.message ?? err) });
  }
};

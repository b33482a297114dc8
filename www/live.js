// Live mode: sensors in, readouts and plots out, the recording into IndexedDB.
// Event plumbing only. Every number goes to the engine (Live, in wasm) as the browser gives it;
// the conversions (iOS sign, deg/s, angles, iOS's compass) are in src/live/events.rs.
import {
  Live, Recorder, is_ios, live_controls, live_message, recording_file_name as fileName,
  live_messages_cleared, recover_recording, recovery_offer,
} from './pkg/pdr.js';
import * as store from './store.js';
import * as profiles from './profiles.js';
import { $, dark, download, fill, note, paint, test, values } from './util.js';

// The page's own timers (browser plumbing, not engine rules).
const FLUSH_MS = 250; // recording batches: a crash loses at most this much
const HOLD_MS = 2000; // press-and-hold to unlock the pocket guard

/** Shows or clears a message; `kind` is 'error' or 'warn'. */
let messageList = 'live-messages';
function message(key, show, kind = 'warn', extra = '') {
  note(messageList, key, show && live_message(key) + extra, kind);
}

/** The settings of live mode's controls: each enabled control named by its setting's path, and
 * the selected step-length profile. */
export const settings = () => ({ set: values($('live-settings'), '[name]:enabled'), profile: profiles.selected() });

/** The live session with everything around it. One at a time. */
class Session {
  constructor(live, rec, ios, onTick) {
    this.live = live;
    this.rec = rec; // { id, started }, or null: not recorded (a calibration walk)
    this.onTick = onTick;
    this.ios = ios;
    this.ended = false;
    this.source = 'events';
    this.sensors = [];
    this.geoWatch = null;
    this.wakeLock = null;
    this.writes = Promise.resolve();
    // The chunks not yet in IndexedDB, in order (written, or kept until downloaded), and when to write them.
    this.recorder = rec ? new Recorder(rec.nextSeq ?? 0) : Recorder.off();
    this.handlers = [];
  }

  on(target, type, fn) {
    target.addEventListener(type, fn);
    this.handlers.push(() => target.removeEventListener(type, fn));
  }

  refused(err) {
    message('engine', true, 'warn', String(err?.message ?? err));
  }

  // --- sensors -------------------------------------------------------------------------
  listenEvents() {
    this.on(window, 'devicemotion', (e) => {
      try {
        this.live.push_motion(e);
      } catch (err) { this.refused(err); }
    });
    this.listenOrientation();
  }

  listenOrientation() {
    // Chromium: the absolute stream; its `deviceorientation` is relative to an arbitrary start.
    const absolute = 'ondeviceorientationabsolute' in window;
    this.on(window, absolute ? 'deviceorientationabsolute' : 'deviceorientation',
      (e) => this.live.push_orientation(e, absolute, screen.orientation?.angle ?? 0));
  }

  /** The Generic Sensor API at the highest rate it grants, if it delivers within a second. */
  async tryGenericSensors() {
    if (!('Accelerometer' in window && 'Gyroscope' in window) || this.ios) return false;
    try {
      const states = await Promise.all(['accelerometer', 'gyroscope']
        .map((name) => navigator.permissions.query({ name }).then((p) => p.state)));
      if (states.includes('denied')) return false;
    } catch { /* the Permissions API may not know these names: try anyway */ }
    let acc;
    let gyr;
    try {
      acc = new Accelerometer({ frequency: 200 });
      gyr = new Gyroscope({ frequency: 200 });
    } catch { return false; }
    const ok = await new Promise((resolve) => {
      const timer = setTimeout(() => resolve(false), 1000);
      acc.addEventListener('error', () => { clearTimeout(timer); resolve(false); }, { once: true });
      acc.addEventListener('reading', () => { clearTimeout(timer); resolve(true); }, { once: true });
      acc.start();
      gyr.start();
    });
    if (!ok || this.ended) { acc.stop(); gyr.stop(); return false; }
    acc.addEventListener('reading', () => {
      try { this.live.push_sensor(acc, gyr); } catch (err) { this.refused(err); }
    });
    this.sensors.push(acc, gyr);
    if ('AbsoluteOrientationSensor' in window) {
      try {
        const ori = new AbsoluteOrientationSensor({ frequency: 60 });
        ori.addEventListener('reading', () => this.live.push_quaternion(ori));
        ori.addEventListener('error', () => this.listenOrientation(), { once: true });
        ori.start();
        this.sensors.push(ori);
      } catch { this.listenOrientation(); }
    } else {
      this.listenOrientation();
    }
    return true;
  }

  async startSensors() {
    this.source = (await this.tryGenericSensors()) ? 'Generic Sensor API' : 'devicemotion events';
    if (this.ended) return;
    if (this.source === 'devicemotion events') this.listenEvents();
    document.documentElement.dataset.source = this.source === 'Generic Sensor API' ? 'sensors' : 'events';
  }

  // --- GNSS ----------------------------------------------------------------------------
  geoOn() {
    if (this.geoWatch != null || !navigator.geolocation) return;
    this.geoWatch = navigator.geolocation.watchPosition((p) => {
      try {
        this.live.push_fix(performance.now(), p);
        message('locationUnavailable', false);
      } catch (err) { this.refused(err); }
    }, (err) => {
      // Refused: the watch stops, and the engine does not start it again. Else fixes may still come.
      const denied = err.code === err.PERMISSION_DENIED;
      message(this.live.location_failed(denied), true);
      if (denied) this.geoOff();
    }, { enableHighAccuracy: true, maximumAge: 0, timeout: 60_000 });
  }

  geoOff() {
    if (this.geoWatch != null) navigator.geolocation.clearWatch(this.geoWatch);
    this.geoWatch = null;
  }

  // --- screen ----------------------------------------------------------------------------
  async keepAwake() {
    if (!('wakeLock' in navigator)) { message('noWakeLock', true); return; }
    try {
      this.wakeLock = await navigator.wakeLock.request('screen');
      message('noWakeLock', false);
    } catch {
      message('noWakeLock', true);
    }
  }

  /** Events stop while the page is hidden: the engine marks the gap when it comes back. */
  onVisibility() {
    const hidden = document.visibilityState === 'hidden';
    if (this.live.visibility(hidden, performance.now())) this.keepAwake();
    else if (hidden) this.flush();
  }

  // --- recording -----------------------------------------------------------------------
  /** Takes the engine's new log lines as the next chunk, and writes the chunks not yet saved. */
  flush() {
    this.live.log_to(this.recorder);
    return this.save();
  }

  /**
   * Writes the batches of unsaved chunks the recorder hands out, in order, one per transaction
   * (all or none of each), and tells it how each went. It lets a chunk go only once written;
   * when storage refuses, the page says so and the recorder says when to try again
   * (src/live/recorder.rs). `force`: now, the recording stops.
   */
  save(force = false) {
    const rec = this.recorder;
    if (!rec.begin(performance.now(), force)) return this.writes;
    this.writes = (async () => {
      try {
        for (let batch = rec.batch(); batch.length; batch = rec.batch()) {
          await store.append(this.rec.id, batch);
          rec.written();
        }
        if (rec.succeeded()) message('storage', false);
      } catch (err) {
        rec.failed(performance.now());
        message('storage', true, 'error', `(${err?.name ?? 'Error'}: ${err?.message ?? err})`);
      }
    })();
    return this.writes;
  }

  /**
   * The whole recording so far: what IndexedDB holds and the chunks it does not. Read by the
   * engine only when it continues a damaged one (the engine then holds it all for a moment);
   * else its own chunks are joined as they are.
   */
  async recording() {
    const unsaved = this.recorder.unsaved();
    let stored;
    try {
      stored = await store.pieces(this.rec.id, unsaved);
    } catch { stored = { pieces: unsaved }; } // no IndexedDB at all: memory holds it all
    if (this.rec.damaged) return readRecording(stored.pieces);
    return { text: stored.pieces.map((c) => c.text).join('') };
  }

  /**
   * The page is going away: IndexedDB writes started now may not finish, so the chunks not yet
   * written are also put in localStorage, synchronously; recovery adds those IndexedDB lacks.
   */
  onPageHide() {
    if (this.ended || !this.rec) return;
    this.flush();
    try {
      const tail = this.recorder.unsaved();
      if (tail.length) localStorage.setItem(store.tailKey(this.rec.id), JSON.stringify(tail));
    } catch { /* storage full or refused: the last batch is lost */ }
  }

  // --- display -------------------------------------------------------------------------
  /** A display tick: the engine decides what to do now (src/live/display.rs). Energy saving's
   * watch is really stopped while the engine does not want fixes; the words are the engine's. */
  tick(now) {
    const t = this.live.tick(now, this.source, $('guard').hidden);
    if (!t) return;
    if (t.gnss === 'on') this.geoOn(); else if (t.gnss === 'off') this.geoOff();
    for (const [key, show, kind] of t.messages) message(key, show, kind);
    fill(t.texts);
    for (const [id, title] of t.titles) $(id).title = title;
    $('gnss-notice').hidden = !t.notice;
    $('gnss-notice').dataset.verdict = t.verdict ?? '';
    this.onTick?.(this);
    if (t.draw) this.draw();
  }

  /** Draws the map and the scope. */
  draw() {
    paint($('live-map'), (...a) => this.live.draw(...a));
    paint($('live-scope'), (...a) => this.live.draw_scope(...a));
  }

  async start(gnssMode) {
    this.live.start(performance.now(), gnssMode, !!this.rec, !!navigator.geolocation);
    this.on(document, 'visibilitychange', () => this.onVisibility());
    this.on(window, 'pagehide', () => this.onPageHide());
    this.flushTimer = setInterval(() => this.flush(), FLUSH_MS);
    // Ticks until the end (then the last one comes from stop()); the first starts the watch.
    const loop = (t) => { this.tick(t); if (!this.ended) requestAnimationFrame(loop); };
    requestAnimationFrame(loop);
    this.keepAwake();
    await this.startSensors();
  }

  /** Ends the session (a recording or a calibration walk; once) and unlocks the pocket guard. */
  async stop() {
    if (this.ended) return;
    this.ended = true;
    for (const off of this.handlers) off();
    for (const s of this.sensors) s.stop();
    this.geoOff();
    this.live.finish();
    clearInterval(this.flushTimer);
    this.wakeLock?.release().catch(() => {});
    this.wakeLock = null;
    this.flush();
    await this.save(true);
    if (this.rec && !this.recorder.unsaved_count()) await store.setState(this.rec.id, 'done').catch(() => {});
    this.live.redraw(); // the last tick: the final figures, the messages about motion cleared
    this.tick(performance.now());
    unlock();
  }
}

// --- pocket guard ------------------------------------------------------------------------
function lock() {
  $('guard').hidden = false;
  document.documentElement.dataset.guard = 'on';
}

function unlock() {
  $('guard').hidden = true;
  document.documentElement.dataset.guard = 'off';
  current?.live.redraw();
}

function setupGuard() {
  const guard = $('guard');
  const button = $('unlock');
  let timer = null;
  const cancel = () => {
    clearTimeout(timer);
    timer = null;
    button.classList.remove('holding');
  };
  const hold = () => {
    button.classList.add('holding');
    timer = setTimeout(() => { cancel(); unlock(); }, HOLD_MS);
  };
  // Touches anywhere else do nothing.
  for (const type of ['click', 'dblclick', 'contextmenu', 'touchstart', 'touchmove', 'wheel']) {
    guard.addEventListener(type, (e) => { if (e.cancelable) e.preventDefault(); }, { passive: false });
  }
  button.addEventListener('pointerdown', (e) => {
    e.preventDefault();
    button.setPointerCapture?.(e.pointerId);
    hold();
  });
  for (const type of ['pointerup', 'pointercancel', 'pointerleave', 'lostpointercapture']) button.addEventListener(type, cancel);
  // Keyboard users: hold Space or Enter.
  button.addEventListener('keydown', (e) => {
    if ((e.key === ' ' || e.key === 'Enter') && !timer && !e.repeat) hold();
  });
  button.addEventListener('keyup', cancel);
}

// --- start, stop, recovery -----------------------------------------------------------------
let current = null;
let lastFinished = null;
let starting = false; // between a tap on Start and its session: the permission prompt may be open

function controls(state) {
  for (const [id, hidden] of live_controls(state)) $(id).hidden = hidden;
  $('live-settings').disabled = state === 'recording';
  document.documentElement.dataset.live = state;
}

/** Asks for motion permission where the browser wants it asked (iOS, recent Chromium), from the tap. */
async function askMotionPermission() {
  const dm = window.DeviceMotionEvent;
  const dor = window.DeviceOrientationEvent;
  if (typeof dm?.requestPermission !== 'function') return true;
  try {
    // Both prompts from the same tap (a second await would lose the user activation).
    const [m] = await Promise.all([dm.requestPermission(),
      typeof dor?.requestPermission === 'function' ? dor.requestPermission() : Promise.resolve('granted')]);
    return m === 'granted';
  } catch {
    return false;
  }
}

/**
 * Starts a session: permissions, the engine, the guard, the sensors. `rec` is the recording
 * (null: none, a calibration walk); `opts.onTick(session)` runs at each display tick,
 * `opts.messages` is the message list's id, `opts.title` the guard's title.
 */
async function begin(makeLive, rec, opts = {}) {
  if (busy()) return false; // a session runs or starts (its permission prompt may be open)
  starting = true;
  try {
    return await beginSession(makeLive, rec, opts);
  } finally {
    starting = false;
  }
}

async function beginSession(makeLive, rec, opts) {
  delete document.documentElement.dataset.source; // set again once the sensors listen
  const live = !opts.onTick;
  messageList = opts.messages ?? 'live-messages';
  $('guard-title').textContent = opts.title ?? live_message('guardTitle');
  const ios = is_ios(navigator.userAgent, navigator.maxTouchPoints); // motion events follow iOS's conventions
  const refuse = (key, detail = '') => {
    message(key, true, 'error', detail);
    if (live) controls('idle');
    return false;
  };
  if (!(await askMotionPermission())) return refuse('motionDenied');
  for (const key of live_messages_cleared()) message(key, false);
  let engine;
  try {
    engine = makeLive(ios);
  } catch (err) {
    return refuse('cannotStart', String(err?.message ?? err));
  }
  current = new Session(engine, rec, ios, opts.onTick);
  const session = current;
  // For the end-to-end tests and the curious: the session's state now.
  test.live = {
    get readouts() { return session.live.readouts(); },
    get source() { return session.source; },
    get unsaved() { return session.recorder.unsaved_count(); },
    get saved() { return session.recorder.saved(); },
    draw: () => session.draw(),
  };
  if (live) {
    $('live-view').hidden = false;
    controls('recording');
  }
  lock();
  if (rec) {
    try {
      if (!rec.resumed) await store.create({ id: rec.id, started: rec.started, ios });
      else await store.setState(rec.id, 'recording');
    } catch (err) {
      message('storage', true, 'error', String(err?.message ?? err));
    }
  }
  await session.start(opts.gnss ?? $('gnss-mode').value);
  return true;
}

/**
 * A calibration walk: the live mode's sensors, pocket guard and wake lock, without recording.
 * `onTick(session)` runs at each display tick. Returns the session, or null when it
 * could not start (the reason is in the list `messages`).
 */
export async function startWalk({ onTick, gnss, messages, title }) {
  const ok = await begin((ios) => new Live({ set: { 'fusion.mode.kind': gnss } }, ios, performance.timeOrigin), null,
    { onTick, gnss, messages, title });
  return ok ? current : null;
}

/** Whether a live recording or a calibration walk is running, or starting. */
export const busy = () => starting || (!!current && !current.ended);

async function stop() {
  const s = current;
  if (!s) return;
  await s.stop();
  if (s.rec) {
    lastFinished = s;
    controls('stopped');
    // The profile's opt-in refinement listens (wizard.js).
    window.dispatchEvent(new CustomEvent('pdr-walk-ended', { detail: { evidence: s.live.walk_evidence() } }));
  }
}

/**
 * What the engine reads of a recording's stored pieces: `{text, samples, steps, skipped_lines,
 * missing_pieces, notes, damage}`; `text` is the pieces as they are when they are whole, else
 * every good line (see `recover_recording`).
 */
function readRecording(pieces) {
  const r = recover_recording(pieces);
  return { ...r, text: r.text ?? pieces.map((c) => c.text).join('') };
}

async function offerRecovery() {
  let open;
  try {
    open = (await store.list()).filter((r) => r.state === 'recording');
  } catch {
    return; // no IndexedDB: nothing to recover
  }
  if (!open.length) return;
  const rec = open.sort((a, b) => b.started - a.started)[0];
  // Read now: on iOS the permission prompt must come straight from the Resume tap.
  let stored;
  let read;
  try {
    stored = await store.pieces(rec.id);
    read = readRecording(stored.pieces);
  } catch (err) {
    message('unreadable', true, 'error', String(err?.message ?? err));
    return;
  }
  const { text, samples, steps } = read;
  const started = new Date(Number.isFinite(rec.started) ? rec.started : Date.now());
  $('recovery-text').textContent = recovery_offer(started.toLocaleString(), samples, steps, read.damage);
  $('recovery').hidden = false;
  document.documentElement.dataset.recovery = 'offered';
  test.recovery = { id: rec.id, samples, steps, skipped_lines: read.skipped_lines, missing_pieces: read.missing_pieces, notes: read.notes };
  const done = () => { $('recovery').hidden = true; document.documentElement.dataset.recovery = 'done'; };
  $('recover-resume').onclick = () => {
    done();
    const config = settings();
    begin((ios) => Live.resume(config, ios, performance.timeOrigin, text),
      { id: rec.id, started: started.getTime(), resumed: true, nextSeq: stored.nextSeq, damaged: read.damage !== '' });
  };
  $('recover-save').onclick = async () => {
    download(text, fileName(started.getTime()));
    await store.setState(rec.id, 'done').catch(() => {});
    done();
  };
  $('recover-discard').onclick = async () => { await store.remove(rec.id).catch(() => {}); done(); };
}

/** Wires up the live section. */
export function setupLive() {
  setupGuard();
  controls('idle');
  if (!window.isSecureContext) {
    message('insecure', true, 'error');
    $('start').disabled = true;
    return;
  }
  $('start').addEventListener('click', () => {
    const started = Date.now();
    const config = settings();
    begin((ios) => new Live(config, ios, performance.timeOrigin), { id: `rec-${started}`, started });
  });
  // Energy saving's window and period are settings of that mode only.
  const duty = () => {
    const on = $('gnss-mode').value === 'energy_saving';
    $('duty').hidden = !on;
    for (const el of $('duty').querySelectorAll('input')) el.disabled = !on;
  };
  $('gnss-mode').addEventListener('change', duty);
  duty();
  $('stop').addEventListener('click', stop);
  $('lock').addEventListener('click', lock);
  $('download').addEventListener('click', async () => {
    if (lastFinished) download((await lastFinished.recording()).text, fileName(lastFinished.rec.started));
  });
  const redraw = () => { current?.live.redraw(); current?.tick(performance.now()); };
  new ResizeObserver(redraw).observe($('live-map'));
  dark.addEventListener('change', redraw);
  window.addEventListener('pdr-basemap', redraw);
  offerRecovery();
}

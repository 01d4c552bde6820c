// formsim_page.js: the page side of formsim's WebAssembly build (issue 29).
//
// Defines the emcc `Module` (canvas, arguments from the URL, print/printErr, preRun writing
// ?script=, progress, errors), the calls formsim makes into the page (Module.formsimDownload,
// Module.formsimPickFile) and the page's API `window.formsim` for users and tests:
//   ready                 Promise, resolved when the first frame is drawn
//   action(line)          queues a script action (`ACTION ARGS`, as after the frame number of a
//                         --script line); Promise of "" or the refusal text, once it ran
//   frames(), busy()      frames drawn so far; whether pins / Monte Carlo / timeline work runs
//   frameMs()             the CPU time of formsim's last frame, in ms
//   runHeadless(s, seed)  runs a shipped scenario to its end without drawing; Promise of
//                         {csv (the timeseries text), csvPath, dir, steps, sim_time, wall_ms}
//   readFile(path)        a file of the wasm's file system, as a Uint8Array
//   listDir(path)         the names in a folder of the wasm's file system, sorted
//   remove(path)          deletes a file or a folder tree of the wasm's file system
//   version()             formsim's version text
//   downloads, uploads    what was offered as a download / picked for File/Open
//   stderr, errors        the last lines formsim printed to stderr; the errors shown
// Then it loads formsim.js (the emcc output, a global Module) itself, so that Module exists
// first and a formsim.js that cannot be loaded is said on the page.
'use strict';

(function () {
  const params = window.formsimParams.parseParams(window.location.search);
  const $ = (id) => document.getElementById(id);
  const STDERR_LINES = 60;  // kept for the error banner
  const UPLOADS = '/home/web_user/uploads';

  // ---- banners: errors stop the page; warnings can be closed ----
  function banner(kind, title, detail) {
    const box = document.createElement('div');
    box.className = 'banner ' + kind;
    if (kind === 'warning') {
      const close = document.createElement('button');
      close.type = 'button';
      close.textContent = '×';
      close.setAttribute('aria-label', 'Close');
      close.onclick = () => box.remove();
      box.appendChild(close);
    }
    const h = document.createElement('h2');
    h.textContent = title;
    box.appendChild(h);
    if (detail) {
      const pre = document.createElement('pre');
      pre.textContent = detail;
      box.appendChild(pre);
    }
    $('banners').appendChild(box);
    return box;
  }

  const api = {
    downloads: [],
    uploads: [],
    stderr: [],
    errors: [],
  };
  let failed = null;  // the Error that stopped the page, once it stopped
  let settleReady;
  api.ready = new Promise((resolve, reject) => {
    settleReady = {resolve, reject};
  });
  api.ready.catch(() => {});  // the banner says it; no "uncaught in promise" on top

  /// Stops the page: a red banner with `title`, the reason and the last lines of stderr; every
  /// pending promise is rejected with the same text.
  function fail(title, reason) {
    const tail = api.stderr.slice(-20).filter((l) => !reason || !l.includes(reason)).join('\n');
    const text = [reason, tail].filter((s) => s && String(s).trim() !== '').join('\n');
    if (failed) return;
    failed = new Error(title + (text ? ': ' + text : ''));
    api.errors.push(failed.message);
    banner('error', title, text);
    $('loading').classList.add('done');
    console.error(failed.message);
    settleReady.reject(failed);
    for (const [, p] of pending) p.reject(failed);
    pending.clear();
  }

  // ---- the emcc runtime's functions (exported by -sEXPORTED_RUNTIME_METHODS) ----
  function runtime(name) {
    // With ASSERTIONS, emcc puts an aborting getter on Module for a method it did not export:
    // take only plain values, else the top-level function of the non-modularized formsim.js.
    const own = Object.getOwnPropertyDescriptor(window.Module, name);
    if (own && 'value' in own && own.value) return own.value;
    if (typeof window[name] !== 'undefined') return window[name];
    throw new Error(`formsim.js does not export ${name} (emcc -sEXPORTED_RUNTIME_METHODS=${name})`);
  }
  const call = (fn, ret, types, args) => runtime('ccall')(fn, ret, types, args);
  const cString = (ptr) => (ptr ? runtime('UTF8ToString')(ptr) : null);
  function started() {
    if (failed) throw failed;
    if (!runtimeReady) throw new Error('formsim is still loading: wait for formsim.ready');
  }

  // ---- actions: queued to run before the next frame, results polled once per frame ----
  const pending = new Map();  // ticket -> {resolve, reject}
  let runtimeReady = false;
  let polling = false;
  function poll() {
    polling = false;
    if (failed) return;
    for (const [ticket, p] of pending) {
      let text;
      try {
        text = cString(call('formsim_web_result', 'number', ['number'], [ticket]));
      } catch (e) {
        pending.delete(ticket);
        p.reject(e);
        continue;
      }
      if (text === null) continue;
      pending.delete(ticket);
      p.resolve(text);
    }
    schedulePoll();
  }
  function schedulePoll() {
    if (polling || pending.size === 0) return;
    polling = true;
    window.requestAnimationFrame(poll);
  }

  api.action = function (line) {
    return new Promise((resolve, reject) => {
      started();
      if (typeof line !== 'string' || line.trim() === '' || /[\r\n]/.test(line)) {
        throw new Error('formsim.action takes one script action, e.g. "edit KEY=VALUE": got ' +
                        JSON.stringify(line));
      }
      const ticket = call('formsim_web_queue', 'number', ['string'], [line.trim()]);
      if (!(ticket >= 1)) throw new Error(`formsim_web_queue refused ${JSON.stringify(line)}`);
      pending.set(ticket, {resolve, reject});
      schedulePoll();
    });
  };
  api.frames = () => (started(), call('formsim_web_frames', 'number', [], []));
  /// The CPU time of formsim's last frame in ms (its own measure, as the Run panel shows).
  api.frameMs = () => (started(), call('formsim_web_frame_ms', 'number', [], []));
  api.busy = () => (started(), call('formsim_web_busy', 'number', [], []) !== 0);
  api.version = () => (started(), cString(call('formsim_web_version', 'number', [], [])));
  api.readFile = (path) => (started(), runtime('FS').readFile(path));
  api.listDir = (path) =>
    (started(), runtime('FS').readdir(path).filter((n) => n !== '.' && n !== '..').sort());
  api.remove = function (path) {
    started();
    const FS = runtime('FS');
    const walk = (p) => {
      if (FS.isDir(FS.stat(p).mode)) {
        for (const name of FS.readdir(p)) if (name !== '.' && name !== '..') walk(p + '/' + name);
        FS.rmdir(p);
      } else {
        FS.unlink(p);
      }
    };
    walk(path);
  };

  /// Runs `scenario` (a shipped name) to its end without drawing, seed "" (or omitted) for the
  /// file's, as `formsim run SCENARIO --seed SEED --out DIR`. Blocks the page while it runs.
  api.runHeadless = function (scenario, seed) {
    return new Promise((resolve, reject) => {
      started();
      if (seed === undefined || seed === null) seed = '';
      if (typeof seed === 'number' && Number.isSafeInteger(seed) && seed >= 0) seed = String(seed);
      if (typeof seed !== 'string' || !/^[0-9]*$/.test(seed)) {
        throw new Error('runHeadless: the seed is a whole number 0 ... 2^64-1 (as a string ' +
                        'above 2^53), or "" for the file\'s: got ' + JSON.stringify(seed));
      }
      const json = cString(call('formsim_web_run_headless', 'number', ['string', 'string'],
                                [String(scenario), seed]));
      const out = JSON.parse(json);
      if (out.error) {
        reject(new Error(out.error));
        return;
      }
      const text = runtime('FS').readFile(out.csv, {encoding: 'utf8'});
      resolve({csv: text, csvPath: out.csv, dir: out.dir, steps: out.steps,
               sim_time: out.sim_time, wall_ms: out.wall_ms});
    });
  };
  window.formsim = api;

  // ---- files formsim hands to the browser, and files the user picks ----
  function download(path, mime) {
    try {
      const data = runtime('FS').readFile(path);
      const name = String(path).split('/').pop();
      const url = URL.createObjectURL(new Blob([data], {type: mime || 'application/octet-stream'}));
      const a = document.createElement('a');
      a.href = url;
      a.download = name;
      a.style.display = 'none';
      document.body.appendChild(a);
      a.click();
      a.remove();
      setTimeout(() => URL.revokeObjectURL(url), 60000);
      api.downloads.push({name, mime, size: data.length, path});
    } catch (e) {
      // Never throw back into the wasm frame that called us.
      banner('warning', `The download of ${path} failed`, String(e && e.message || e));
      console.warn('formsimDownload', path, e);
    }
  }

  function pickFile() {
    const input = document.createElement('input');
    input.type = 'file';
    input.accept = '.yaml,.yml';
    input.addEventListener('change', async () => {
      const file = input.files && input.files[0];
      if (!file) return;
      // A script action's argument: a plain name (spaces would split it).
      const path = UPLOADS + '/' + file.name.replace(/[^A-Za-z0-9._-]/g, '_');
      try {
        const FS = runtime('FS');
        FS.mkdirTree(UPLOADS);
        FS.writeFile(path, new Uint8Array(await file.arrayBuffer()));
      } catch (e) {
        banner('warning', `${file.name} could not be read`, String(e && e.message || e));
        return;
      }
      const upload = {name: file.name, path, result: api.action('open ' + path)};
      api.uploads.push(upload);
      upload.result.catch(() => {});
    });
    input.click();
  }

  // ---- ?script=: fetched first; Module.preRun writes it to the wasm's file system ----
  // formsim.js is loaded once the file is here, so that preRun can write it synchronously
  // (no run dependency needed) and a script that cannot be fetched stops nothing half-way.
  let scriptBytes = null;
  async function fetchScript() {
    const url = new URL(params.script, window.location.href);
    let response;
    try {
      response = await fetch(url);
    } catch (e) {
      throw new Error(`?script=${params.script}: ${url} could not be fetched (${e.message})`);
    }
    if (!response.ok) {
      throw new Error(`?script=${params.script}: ${url} answered ${response.status} ` +
                      `${response.statusText}`);
    }
    scriptBytes = new Uint8Array(await response.arrayBuffer());
  }
  function preRunScript() {
    if (scriptBytes !== null) runtime('FS').writeFile(window.formsimParams.SCRIPT_PATH, scriptBytes);
  }

  // ---- loading line ----
  function setStatus(text) {
    if (failed) return;
    const m = /\((\d+(?:\.\d+)?)\/(\d+(?:\.\d+)?)\)/.exec(text || '');
    const progress = $('progress');
    if (m && Number(m[2]) > 0) {
      progress.max = Number(m[2]);
      progress.value = Number(m[1]);
      const mb = (x) => (Number(x) / 1048576).toFixed(1);
      $('status').textContent = `Loading formsim… ${mb(m[1])} of ${mb(m[2])} MB`;
    } else if (text) {
      progress.removeAttribute('value');
      $('status').textContent = text.replace(/\.\.\./g, '…');
    }
  }

  function waitFirstFrame() {
    if (failed) return;
    let frames = 0;
    try {
      frames = call('formsim_web_frames', 'number', [], []);
    } catch (e) {
      fail('formsim could not start', e.message);
      return;
    }
    if (frames >= 1) {
      $('loading').classList.add('done');
      settleReady.resolve();
      return;
    }
    window.requestAnimationFrame(waitFirstFrame);
  }

  // ---- the emcc Module ----
  window.Module = {
    canvas: $('canvas'),
    arguments: params.args,
    print: (text) => console.log(text),
    printErr: (text) => {
      api.stderr.push(text);
      if (api.stderr.length > STDERR_LINES) api.stderr.shift();
      console.warn(text);
    },
    preRun: [preRunScript],
    setStatus,
    monitorRunDependencies: (left) => {
      if (left === 0) setStatus('Starting formsim…');
    },
    onRuntimeInitialized: () => {
      runtimeReady = true;
      window.requestAnimationFrame(waitFirstFrame);
    },
    onAbort: (what) => fail('formsim stopped', what === undefined ? '' : String(what)),
    onExit: (code) => {
      if (code !== 0) fail(`formsim exited with status ${code}`, '');
      else banner('warning', 'formsim has quit', 'Reload the page to start it again.');
    },
    formsimDownload: download,
    formsimPickFile: pickFile,
    // formsim could not start (a scenario or lesson it does not ship, a bad argument, no
    // WebGL 2): its reason, also printed to stderr.
    formsimFatal: (text) => fail('formsim could not start', String(text)),
  };

  window.addEventListener('error', (e) => {
    if (!failed) fail('The page met an error', e.message || String(e.error));
  });
  window.addEventListener('unhandledrejection', (e) => {
    if (!failed) fail('The page met an error', String(e.reason && e.reason.message || e.reason));
  });

  // ---- the note, warnings about the URL, then formsim.js ----
  $('note-close').onclick = () => $('note').classList.add('hidden');
  if (params.present) $('note').classList.add('hidden');
  for (const w of params.warnings) banner('warning', 'Ignored a URL parameter', w);
  if (window.location.protocol === 'file:') {
    banner('warning', 'Opened from a file',
           'Browsers do not load WebAssembly from file:// pages: serve this folder over http ' +
           '(for example `python3 -m http.server` in it) and open http://127.0.0.1:8000/.');
  }
  if (params.errors.length > 0) {
    fail('The page\'s address asks for something formsim cannot do', params.errors.join('\n'));
    return;
  }
  setStatus('Loading formsim…');
  const load = () => {
    const script = document.createElement('script');
    script.src = 'formsim.js';
    script.async = true;
    script.onerror = () => fail('formsim.js could not be loaded',
                                'It should be beside index.html (scripts/web.sh writes out/web/).');
    document.body.appendChild(script);
  };
  if (params.script === null) load();
  else fetchScript().then(load, (e) => fail('The script could not be loaded', e.message));
})();

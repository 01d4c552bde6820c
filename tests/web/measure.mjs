// Size and speed of formsim's WebAssembly page (issue 29, item 5), for docs/benchmarks.md: a
// measurement, not a test (it prints the figures against the limits and writes
// OUT/measure.{json,md}; it fails only when it cannot measure).
//   node measure.mjs [--web DIR] [--out DIR]   (--native is not used)
//   1. formsim.wasm + formsim.data, raw and gzip -9 (zlib.gzipSync): limits 8 MB and 3 MB.
//   2. formation_traj2_ukf run to its end in the page without drawing (formsim.runHeadless),
//      5 times: simulated time / wall time (formsim's own clock, and the page's around the call);
//      limit >= 1000x real time.
//   3. formation_cascade7 playing in the window: the CPU time of a frame, as formsim measures it
//      (formsim.frameMs(), the main thread from the start to the end of its frame) over 300
//      frames, less the time blocked in WebGL getParameter waiting for the GPU process, and
//      chromium's own main-thread task time per frame (DevTools Performance metrics); limit
//      <= 16 ms.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';

import {launch, open} from './browser.mjs';
import {within} from './checks.mjs';
import {options} from './options.mjs';
import {serve} from './serve.mjs';

const o = options();
const MB = 1e6;
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const quantile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1,
                                                                   Math.floor(q * xs.length))];
const load = () => os.loadavg().map((x) => x.toFixed(2)).join(' ');
const report = {when: new Date().toISOString(), machine: `${os.cpus().length} cores`, load: {}};

// ---- 1. sizes ----
const sizes = {};
for (const f of ['formsim.wasm', 'formsim.data', 'formsim.js']) {
  const bytes = fs.readFileSync(path.join(o.web, f));
  sizes[f] = {raw: bytes.length, gzip: zlib.gzipSync(bytes, {level: 9}).length};
}
const both = {raw: sizes['formsim.wasm'].raw + sizes['formsim.data'].raw,
              gzip: sizes['formsim.wasm'].gzip + sizes['formsim.data'].gzip};
report.sizes = {...sizes, 'wasm+data': both};
console.log('sizes (bytes, raw / gzip -9):');
for (const [f, s] of Object.entries(report.sizes)) {
  console.log(`  ${f.padEnd(14)} ${String(s.raw).padStart(10)} / ${String(s.gzip).padStart(10)}`);
}
console.log(`  wasm+data: ${(both.raw / MB).toFixed(2)} MB (limit 8) / ${(both.gzip / MB).toFixed(2)} ` +
            `MB gzip (limit 3)`);

const server = await serve({'/': o.web});
const {browser, close} = await launch({width: 1280, height: 800});
report.chromium = await browser.version();
try {
  // ---- 2. the paper scenario, headless in the page ----
  report.load.before_headless = load();
  const tab = await open(browser, server.url + '?scenario=formation_traj2_ukf&paused=1');
  const t0 = Date.now();
  await within(300000, 'formsim.ready', tab.page.evaluate(() => window.formsim.ready));
  report.ready_ms = Date.now() - t0;
  const runs = [];
  for (let i = 0; i < 5; ++i) {
    runs.push(await tab.page.evaluate(async () => {
      const t = performance.now();
      const r = await window.formsim.runHeadless('formation_traj2_ukf', '');
      const js_ms = performance.now() - t;
      window.formsim.remove(r.dir);
      // The simulation alone (rows kept as numbers, no CSV text), as `formsim run` times its loop.
      const sim_ms = Module.ccall('formsim_web_time_simulation', 'number', ['string'],
                                 ['formation_traj2_ukf']);
      return {steps: r.steps, sim_time: r.sim_time, wall_ms: r.wall_ms, js_ms, sim_ms};
    }));
  }
  const ratio = runs.map((r) => (1000 * r.sim_time) / r.wall_ms);
  const ratioJs = runs.map((r) => (1000 * r.sim_time) / r.js_ms);
  const ratioSim = runs.map((r) => (1000 * r.sim_time) / r.sim_ms);
  report.headless = {scenario: 'formation_traj2_ukf', runs, realtime_median: median(ratio),
                     realtime_js_median: median(ratioJs), realtime_sim_median: median(ratioSim),
                     load: load()};
  console.log(`\nformation_traj2_ukf headless in the page (${runs[0].steps} steps, ` +
              `${runs[0].sim_time} s simulated), 5 runs, load ${report.headless.load}:`);
  console.log(`  wall ms (formsim's clock): ${runs.map((r) => r.wall_ms.toFixed(1)).join(' ')}`);
  console.log(`  median ${median(ratio).toFixed(0)}x real time with the CSV written (limit >= 1000x); ` +
              `around the call ${median(ratioJs).toFixed(0)}x; the simulation alone ` +
              `${median(ratioSim).toFixed(0)}x (${runs.map((r) => r.sim_ms.toFixed(1)).join(' ')} ms)`);
  await tab.page.close();

  // ---- 3. a frame of formation_cascade7 ----
  const win = await open(browser, server.url + '?scenario=formation_cascade7', {
    // Time spent inside WebGL's getParameter: a state query the GPU process must answer makes the
    // page wait until it has drawn what was queued (SwiftShader draws on the CPU, in another
    // process), so that wait is the renderer's time, not the frame's own CPU time.
    beforeLoad: () => {
      window.__glWaitMs = 0;
      const get = WebGL2RenderingContext.prototype.getParameter;
      WebGL2RenderingContext.prototype.getParameter = function (p) {
        const t = performance.now();
        try {
          return get.call(this, p);
        } finally {
          window.__glWaitMs += performance.now() - t;
        }
      };
    },
  });
  await within(300000, 'formsim.ready', win.page.evaluate(() => window.formsim.ready));
  await win.page.evaluate(() => window.formsim.action('play'));
  await win.page.evaluate(() => new Promise((r) => {  // 60 frames to settle
    const until = window.formsim.frames() + 60;
    const tick = () => (window.formsim.frames() >= until ? r() : requestAnimationFrame(tick));
    tick();
  }));
  const cdp = await win.page.createCDPSession();
  await cdp.send('Performance.enable');
  const metrics = async () => Object.fromEntries(
      (await cdp.send('Performance.getMetrics')).metrics.map((m) => [m.name, m.value]));
  const m0 = await metrics();
  const f0 = await win.page.evaluate(() => window.formsim.frames());
  const sampled = await win.page.evaluate(() => new Promise((resolve) => {
    const ms = [];
    const waits = [];
    const gaps = [];
    let seen = window.formsim.frames();
    let last = performance.now();
    const tick = (t) => {
      const f = window.formsim.frames();
      if (f > seen) {  // one value per frame formsim drew
        ms.push(window.formsim.frameMs());
        waits.push(window.__glWaitMs);
        window.__glWaitMs = 0;
        gaps.push(t - last);
        seen = f;
        last = t;
      }
      if (ms.length >= 300) resolve({ms, waits, gaps});
      else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }));
  const m1 = await metrics();
  const f1 = await win.page.evaluate(() => window.formsim.frames());
  const frames = f1 - f0;
  report.frame = {
    scenario: 'formation_cascade7', viewport: '1280x800', frames,
    frame_ms_median: median(sampled.ms), frame_ms_p90: quantile(sampled.ms, 0.9),
    frame_ms_max: Math.max(...sampled.ms),
    gl_wait_ms_median: median(sampled.waits),
    cpu_ms_median: median(sampled.ms.map((m, i) => m - sampled.waits[i])),
    cpu_ms_p90: quantile(sampled.ms.map((m, i) => m - sampled.waits[i]), 0.9),
    task_ms_per_frame: (1000 * (m1.TaskDuration - m0.TaskDuration)) / frames,
    script_ms_per_frame: (1000 * (m1.ScriptDuration - m0.ScriptDuration)) / frames,
    interval_ms_median: median(sampled.gaps), load: load(),
  };
  const fr = report.frame;
  console.log(`\nformation_cascade7 playing, 1280x800, ${frames} frames, load ${fr.load}:`);
  console.log(`  formsim's frame time: median ${fr.frame_ms_median.toFixed(2)} ms, p90 ` +
              `${fr.frame_ms_p90.toFixed(2)} ms, max ${fr.frame_ms_max.toFixed(2)} ms (limit 16)`);
  console.log(`  of which waiting in WebGL getParameter for the GPU process: median ` +
              `${fr.gl_wait_ms_median.toFixed(2)} ms; the rest (the frame's own CPU time): median ` +
              `${fr.cpu_ms_median.toFixed(2)} ms, p90 ${fr.cpu_ms_p90.toFixed(2)} ms`);
  console.log(`  chromium main-thread task time per frame ${fr.task_ms_per_frame.toFixed(2)} ms ` +
              `(script ${fr.script_ms_per_frame.toFixed(2)} ms); frame interval median ` +
              `${fr.interval_ms_median.toFixed(1)} ms`);
  const problems = [...win.problems()];
  if (problems.length) console.log('console errors: ' + JSON.stringify(problems));
  await win.page.close();
} finally {
  await close();
  await server.close();
}

fs.writeFileSync(path.join(o.out, 'measure.json'), JSON.stringify(report, null, 1) + '\n');
const h = report.headless;
const f = report.frame;
const md = [
  '| measure | value | limit (issue 29) |', '|---|---|---|',
  `| formsim.wasm + formsim.data | ${(both.raw / MB).toFixed(2)} MB (${both.raw} bytes) | <= 8 MB |`,
  `| ... gzip -9 | ${(both.gzip / MB).toFixed(2)} MB (${both.gzip} bytes) | <= 3 MB |`,
  `| formation_traj2_ukf headless in the page | ${h.realtime_median.toFixed(0)}x real time ` +
      `(median of 5; ${median(h.runs.map((r) => r.wall_ms)).toFixed(1)} ms for ` +
      `${h.runs[0].sim_time} s) | >= 1000x |`,
  `| formation_cascade7 frame CPU time (formsim's, 1280x800) | median ` +
      `${f.frame_ms_median.toFixed(2)} ms, p90 ${f.frame_ms_p90.toFixed(2)} ms | <= 16 ms |`,
  `| ... of which waiting in WebGL getParameter for the GPU process (SwiftShader) | median ` +
      `${f.gl_wait_ms_median.toFixed(2)} ms | |`,
  `| ... the rest: the frame's own CPU time | median ${f.cpu_ms_median.toFixed(2)} ms, p90 ` +
      `${f.cpu_ms_p90.toFixed(2)} ms | <= 16 ms |`,
  `| ... chromium main-thread task time per frame | ${f.task_ms_per_frame.toFixed(2)} ms | |`,
  '', `${report.chromium}, headless, SwiftShader; ${report.machine}; load average ` +
      `${h.load} (headless) and ${f.load} (frames).`,
];
fs.writeFileSync(path.join(o.out, 'measure.md'), md.join('\n') + '\n');
console.log(`\n${path.join(o.out, 'measure.md')}`);

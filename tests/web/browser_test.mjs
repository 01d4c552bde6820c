// The browser test of formsim's WebAssembly page (issue 29, item 4): Debian's chromium,
// headless, drives the page built into out/web/ through window.formsim with the same script
// actions as --script; checks the edit took effect, the world is drawn, no console error, the
// page's URL handling, and that every shipped scenario run in the page gives the native run's
// timeseries (item 3; the table goes to OUT/equality.{json,md}). Exit status 0 when all passed.
//   node browser_test.mjs [--web DIR] [--native FILE] [--out DIR] [--scenarios A,B] [--skip-equality]
import {execFileSync} from 'node:child_process';
import fs from 'node:fs';
import {createRequire} from 'node:module';
import path from 'node:path';

import {launch, open} from './browser.mjs';
import {Checks, within} from './checks.mjs';
import {compareCsv, compareResults} from './csv_compare.mjs';
import {equalityRows, writeEqualityTable, TOLERANCE} from './equality.mjs';
import {measureWorld} from './pixels.mjs';
import {options, shippedLessons, shippedScenarios} from './options.mjs';
import {serve} from './serve.mjs';

const o = options();
const checks = new Checks();
const SCENARIO = 'formation_traj2_ukf';
const LESSON = 'noise_and_ukf';
const LOAD_MS = 300000;  // compiling the wasm on a loaded 2-core machine under SwiftShader
const ACTION_MS = 60000;

// Native runs go where the page can fetch them: /native/<scenario>/timeseries.csv.
const nativeDir = path.join(o.out, 'native');
fs.mkdirSync(nativeDir, {recursive: true});
const testFiles = path.join(o.out, 'served');
fs.mkdirSync(testFiles, {recursive: true});
fs.writeFileSync(path.join(testFiles, 'script.txt'),
                 '# a ?script= file: FRAME ACTION ARGS\n2 screenshot /home/web_user/from_script.png\n');
const server = await serve({'/': o.web, '/native/': nativeDir, '/test/': testFiles});
const {browser, close} = await launch({width: 1280, height: 800});
console.log(`page: ${server.url}  (from ${o.web})\nchromium: ${await browser.version()}`);

const action = (page, line) =>
  within(ACTION_MS, `formsim.action(${line})`, page.evaluate((l) => window.formsim.action(l), line));

/// Opens the page at `query` and waits for formsim.ready; returns the open() record.
async function openReady(query, openOptions = {}) {
  const t0 = Date.now();
  const tab = await open(browser, server.url + query, openOptions);
  await within(LOAD_MS, `formsim.ready at ${query}`, tab.page.evaluate(() => window.formsim.ready));
  tab.loadMs = Date.now() - t0;
  return tab;
}

const bannerText = (page) =>
  page.evaluate(() => [...document.querySelectorAll('.banner')].map((b) => b.innerText).join('\n'));

await checks.section('URL parameters -> program arguments (formsim_params.js, in node)', () => {
  const {parseParams} = createRequire(import.meta.url)(path.join(o.web, 'formsim_params.js'));
  const p = parseParams('?scenario=formation_cascade7&lesson=ll_singularity&theme=dark&present=1' +
                        '&script=s.txt&paused=0');
  checks.check('all parameters become arguments', JSON.stringify(p.args) === JSON.stringify(
      ['formation_cascade7', '--lesson', 'll_singularity', '--theme', 'dark', '--present',
       '--script', '/home/web_user/page_script.txt']) && p.errors.length === 0, JSON.stringify(p));
  const flagLike = parseParams('?scenario=--set');
  checks.check('a value that reads as a flag is refused, naming the parameter',
               flagLike.errors.length === 1 && flagLike.errors[0].includes('?scenario='),
               JSON.stringify(flagLike.errors));
  const twice = parseParams('?theme=dark&theme=light');
  checks.check('a parameter given twice is refused', twice.errors.length === 1,
               JSON.stringify(twice.errors));
  const typo = parseParams('?scenaro=formation_traj2');
  checks.check('an unknown parameter is a warning, not an error',
               typo.errors.length === 0 && typo.warnings.length === 1 &&
               typo.warnings[0].includes('?scenaro='), JSON.stringify(typo));
});

let main = null;
await checks.section(`The window: ?scenario=${SCENARIO}, driven through formsim.action`, async () => {
  const downloadDir = path.join(o.out, 'downloads');
  fs.rmSync(downloadDir, {recursive: true, force: true});
  fs.mkdirSync(downloadDir, {recursive: true});
  main = await openReady(`?scenario=${SCENARIO}`, {downloads: downloadDir});
  const {page} = main;
  checks.check('formsim.ready (first frame drawn)', true, `${main.loadMs} ms from navigation`);
  const version = await page.evaluate(() => window.formsim.version());
  checks.check('formsim.version()', typeof version === 'string' && version.length > 0, version);

  const listed = await page.evaluate(() => ({
    scenarios: window.formsim.listDir('/formsim/assets/scenarios'),
    lessons: window.formsim.listDir('/formsim/assets/lessons'),
  }));
  const missing = [...shippedScenarios().map((s) => `scenarios/${s}.yaml`).filter(
                       (f) => !listed.scenarios.includes(path.basename(f))),
                   ...shippedLessons().map((s) => `lessons/${s}.yaml`).filter(
                       (f) => !listed.lessons.includes(path.basename(f)))];
  checks.check('every shipped scenario and lesson is preloaded', missing.length === 0,
               missing.length ? 'missing: ' + missing.join(', ') :
                                `${listed.scenarios.length} scenarios, ${listed.lessons.length} lessons`);

  const note = await page.evaluate(() => document.getElementById('note').innerText);
  checks.check('the note says what needs the desktop build',
               /sweep.*tune.*headless video and threads need the desktop build/s.test(note), note);

  // The page has no floating-point to_chars: its numbers must still be to_chars' text.
  const expected = JSON.parse(fs.readFileSync(path.join(path.dirname(new URL(import.meta.url).pathname),
                                                        'shortest_doubles.json')));
  const wrong = await page.evaluate((pairs) => pairs.filter(([bits, text]) => {
    const view = new DataView(new ArrayBuffer(8));
    view.setBigUint64(0, BigInt('0x' + bits));
    return Module.ccall('formsim_web_format_double', 'string', ['number'], [view.getFloat64(0)]) !== text;
  }), expected);
  checks.check(`numbers are written as std::to_chars writes them (${expected.length} doubles)`,
               wrong.length === 0, JSON.stringify(wrong.slice(0, 5)));
  const frames0 = await page.evaluate(() => window.formsim.frames());
  checks.check('play', (await action(page, 'play')) === '');
  checks.check('edit robots.R2.follow.k_l=0.2 (a live tunable): accepted',
               (await action(page, 'edit robots.R2.follow.k_l=0.2')) === '');

  // The loader's reason, as the native CLI gives it for the same value through --set.
  let cli = '';
  try {
    execFileSync(o.native, ['run', SCENARIO, '--set', 'robots.R2.follow.l_des=-1', '-q', '--out',
                            path.join(o.out, 'refused')], {stdio: 'pipe'});
  } catch (e) {
    cli = String(e.stderr);
  }
  const reason = (/': (.*)$/m.exec(cli) || [])[1];
  const refusal = await action(page, 'edit robots.R2.follow.l_des=-1');
  checks.check('edit robots.R2.follow.l_des=-1: refused with the loader\'s reason',
               !!reason && refusal.includes('robots.R2.follow.l_des') && refusal.endsWith(reason),
               `page: "${refusal}"; native --set: "${cli.trim()}"`);

  const saved = '/home/web_user/tuned.yaml';
  checks.check(`save ${saved}`, (await action(page, `save ${saved}`)) === '');
  const yaml = Buffer.from(await page.evaluate((p) => Array.from(window.formsim.readFile(p)),
                                               saved)).toString();
  const r2 = yaml.split('\n').find((l) => /follow: \{law: l_phi/.test(l)) || '';
  checks.check('the edit took effect: the saved scenario has R2\'s k_l 0.2, l_des unchanged',
               /k_l: 0\.2[,}]/.test(r2) && /l_des: 0\.3[,}]/.test(r2), r2.trim());
  const downloads = await page.evaluate(() => window.formsim.downloads);
  checks.check('save is offered as a download (Module.formsimDownload)',
               downloads.length === 1 && downloads[0].name === 'tuned.yaml' &&
               downloads[0].size === yaml.length, JSON.stringify(downloads));
  const got = path.join(downloadDir, 'tuned.yaml');
  await within(ACTION_MS, 'the browser\'s download', (async () => {
    while (!fs.existsSync(got)) await new Promise((r) => setTimeout(r, 100));
  })());
  checks.check('... and the browser saved it, byte for byte', fs.readFileSync(got).toString() === yaml);

  // File/Open: formsim calls Module.formsimPickFile; the user picks a file (a name with a space).
  const picked = path.join(o.out, 'served', 'my tuned.yaml');
  fs.writeFileSync(picked, yaml.replace(/k_l: 0\.2([,}])/, 'k_l: 0.25$1'));
  const badPick = path.join(o.out, 'served', 'broken.yaml');
  fs.writeFileSync(badPick, 'type: formation\nrobots: [\n');
  for (const [file, good] of [[picked, true], [badPick, false]]) {
    const [chooser] = await Promise.all([
      page.waitForFileChooser({timeout: ACTION_MS}),
      // A click first: browsers open a file dialog only right after a user's gesture, as after
      // the click on File/Open in the window.
      page.click('#note span').then(() => page.evaluate(() => window.Module.formsimPickFile())),
    ]);
    await chooser.accept([file]);
    const upload = await within(ACTION_MS, 'the upload', page.waitForFunction(
        (n) => window.formsim.uploads[n - 1], {timeout: 0, polling: 100}, good ? 1 : 2)
        .then(() => page.evaluate((n) => window.formsim.uploads[n - 1].result.then((r) => ({
                                     path: window.formsim.uploads[n - 1].path, result: r})),
                                  good ? 1 : 2)));
    if (good) {
      checks.check('File/Open: the picked file is written to /home/web_user/uploads and opened',
                   upload.path === '/home/web_user/uploads/my_tuned.yaml' && upload.result === '',
                   JSON.stringify(upload));
    } else {
      checks.check('File/Open of a broken file: refused with the loader\'s reason',
                   upload.result.includes('broken.yaml'), JSON.stringify(upload));
    }
  }
  await action(page, `save ${saved}`);
  const reopened = Buffer.from(await page.evaluate((p) => Array.from(window.formsim.readFile(p)),
                                                   saved)).toString();
  checks.check('... the window runs the picked scenario (saved again: k_l 0.25)',
               /k_l: 0\.25[,}]/.test(reopened));

  checks.check('pin', (await action(page, 'pin')) === '');
  checks.check('wait (until the pin\'s work is done)', (await action(page, 'wait')) === '');
  checks.check('not busy after wait', (await page.evaluate(() => window.formsim.busy())) === false);
  checks.check(`lesson ${LESSON}`, (await action(page, `lesson ${LESSON}`)) === '');
  checks.check('lesson-step 2', (await action(page, 'lesson-step 2')) === '');
  const unknown = await action(page, 'bogus-action');
  checks.check('an unknown action is refused with the closest names',
               unknown.startsWith('unknown action \'bogus-action\''), unknown);

  // Let the lesson's run move a little, then the window's own screenshot.
  const played = await action(page, 'play');
  checks.check('play (the lesson\'s run)', played === '', played);
  await within(ACTION_MS, '60 more frames', page.waitForFunction(
      (n) => window.formsim.frames() >= n, {timeout: 0, polling: 100},
      (await page.evaluate(() => window.formsim.frames())) + 60));
  const shot = '/home/web_user/s.png';
  checks.check(`screenshot ${shot}`, (await action(page, `screenshot ${shot}`)) === '');
  const png = Buffer.from(await page.evaluate((p) => Array.from(window.formsim.readFile(p)), shot));
  fs.writeFileSync(path.join(o.out, 'page_screenshot_action.png'), png);
  const world = measureWorld(png);
  checks.check('the screenshot is the canvas\'s size', world.width === 1280 &&
               world.height >= 700, `${world.width}x${world.height}`);
  checks.check('the world view is drawn (>= 2 % of it not background)', world.nonBackground >= 0.02,
               `${(100 * world.nonBackground).toFixed(1)} % not ${JSON.stringify(world.background)}`);
  checks.check('the robots\' colours are in the world view (>= 40 pixels each of R1, R2, R3)',
               Object.values(world.robots).every((n) => n >= 40), JSON.stringify(world.robots));
  await page.screenshot({path: path.join(o.out, 'page_lesson.png')});
  const frames1 = await page.evaluate(() => window.formsim.frames());
  checks.check('frames go on', frames1 > frames0 + 60, `${frames0} -> ${frames1}`);
  checks.check('no console error, page error or failed request', main.problems().length === 0,
               JSON.stringify(main.problems()));
  fs.writeFileSync(path.join(o.out, 'console_main.json'), JSON.stringify(main.log, null, 1));
});

await checks.section('?lesson=ll_singularity&theme=dark opens the lesson', async () => {
  const tab = await openReady('?lesson=ll_singularity&theme=dark');
  await within(ACTION_MS, '30 frames', tab.page.waitForFunction(
      () => window.formsim.frames() >= 30, {timeout: 0, polling: 100}));
  const shot = path.join(o.out, 'page_lesson_url.png');
  await tab.page.screenshot({path: shot});
  const world = measureWorld(fs.readFileSync(shot));
  checks.check('the world view is drawn', world.nonBackground >= 0.02,
               `${(100 * world.nonBackground).toFixed(1)} % not ${JSON.stringify(world.background)}`);
  checks.check('dark theme: the world\'s background is dark',
               world.background.every((c) => c < 96), JSON.stringify(world.background));
  checks.check('no console error there', tab.problems().length === 0,
               JSON.stringify(tab.problems()));
  await tab.page.close();
});

await checks.section('?script= is fetched and run; bad addresses are said on the page', async () => {
  const tab = await openReady(`?scenario=${SCENARIO}&script=test/script.txt`);
  const found = await within(ACTION_MS, 'the ?script= screenshot', tab.page.waitForFunction(() => {
    try {
      return window.formsim.readFile('/home/web_user/from_script.png').length > 0;
    } catch {
      return false;
    }
  }, {timeout: 0, polling: 200}).then(() => true));
  checks.check('?script=test/script.txt ran (its screenshot exists)', found);
  checks.check('no console error there', tab.problems().length === 0, JSON.stringify(tab.problems()));
  await tab.page.close();

  const loads = () => server.requests.filter((r) => r.url.startsWith('/formsim.js')).length;
  const before = loads();
  const bad = await open(browser, server.url + '?scenario=formation_traj2_ukf&present=maybe');
  const text = await bannerText(bad.page);
  checks.check('?present=maybe: a banner names the parameter', text.includes('?present='), text);
  checks.check('?present=maybe: formsim.js is not even loaded', loads() === before,
               `${loads() - before} requests`);
  await bad.page.close();

  const missing = await open(browser, server.url + '?scenario=formation_traj2_ukf&script=nope.txt');
  await missing.page.waitForFunction(() => document.querySelector('.banner.error'),
                                     {timeout: LOAD_MS});
  const t2 = await bannerText(missing.page);
  checks.check('?script=nope.txt: the banner says the address answered 404', t2.includes('404'), t2);
  await missing.page.close();

  const unknown = await open(browser, server.url + '?scenario=no_such_scenario');
  const rejected = await within(LOAD_MS, 'formsim.ready to fail', unknown.page.evaluate(
      () => window.formsim.ready.then(() => 'started', (e) => e.message)));
  const t3 = await bannerText(unknown.page);
  checks.check('?scenario=no_such_scenario: refused, formsim.ready rejects', rejected !== 'started',
               rejected);
  checks.check('... and the banner shows formsim\'s own error naming it',
               t3.includes('no_such_scenario') && unknown.log.some(
                   (l) => ['warn', 'warning'].includes(l.type) && l.text.includes('no_such_scenario')), t3);
  checks.check('... with no page error', !unknown.log.some((l) => l.type === 'pageerror'),
               JSON.stringify(unknown.log));
  await unknown.page.close();
});

if (!o.skipEquality) {
  await checks.section('Same results: every shipped scenario, page against native', async () => {
    const page = main.page;
    await page.bringToFront();
    await action(page, 'pause');
    await page.addScriptTag({content: `window.compareCsv = ${compareCsv.toString()};\n` +
                                      `window.compareResults = ${compareResults.toString()};`});
    const scenarios = o.scenarios || shippedScenarios();
    const results = [];
    for (const s of scenarios) {
      const out = path.join(nativeDir, s);
      fs.rmSync(out, {recursive: true, force: true});
      const t0 = Date.now();
      execFileSync(o.native, ['run', s, '-q', '--out', out], {stdio: 'pipe',
                   env: {...process.env, DISPLAY: ''}});
      const nativeMs = Date.now() - t0;
      const r = await within(LOAD_MS * 2, `runHeadless(${s})`, page.evaluate(async (name) => {
        const t = performance.now();
        const run = await window.formsim.runHeadless(name, '');
        const js_ms = performance.now() - t;
        const native = await (await fetch(`native/${name}/timeseries.csv`)).text();
        const cmp = window.compareCsv(run.csv, native);
        const summary = JSON.parse(new TextDecoder().decode(
            window.formsim.readFile(`${run.dir}/summary.json`)));
        const nativeSummary = await (await fetch(`native/${name}/summary.json`)).json();
        const results = window.compareResults(summary.results, nativeSummary.results);
        window.formsim.remove(run.dir);  // keep the wasm's memory for the next ones
        return {steps: run.steps, sim_time: run.sim_time, wall_ms: run.wall_ms, js_ms, cmp,
                results, summary, kind: nativeSummary.type, bytes: run.csv.length};
      }, s));
      // The page's summary.json beside the native one, for a look at what differs.
      fs.mkdirSync(path.join(o.out, 'page', s), {recursive: true});
      fs.writeFileSync(path.join(o.out, 'page', s, 'summary.json'),
                       JSON.stringify(r.summary, null, 1) + '\n');
      delete r.summary;
      results.push({scenario: s, native_ms: nativeMs, ...r});
      const c = r.cmp;
      const what = c.identical ? 'identical' : c.worst ?
          `max |diff| ${c.worst.abs.toExponential(2)} in ${c.worst.column} (row ${c.worst.row})` :
          `${c.text_mismatches} cells differ as text, rows ${c.rows.join(' vs ')}`;
      const res = r.results.worst ? `results: worst rel ${r.results.worst.rel.toExponential(2)} ` +
          `in ${r.results.worst.key}` : 'results: identical';
      console.log(`  ${s.padEnd(32)} ${what}; ${res}   page ${Math.round(r.wall_ms)} ms, ` +
                  `native ${nativeMs} ms`);
    }
    const rows = equalityRows(results);
    writeEqualityTable(o.out, rows);
    for (const row of rows) {
      checks.check(`${row.scenario}: ${row.verdict}`, row.ok, row.detail);
    }
    console.log(`  table: ${path.join(o.out, 'equality.md')} (tolerance: ${TOLERANCE.text})`);
  });
}

await close();
await server.close();
process.exit(checks.finish());

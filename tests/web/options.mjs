// Command-line options shared by browser_test.mjs and measure.mjs.
import fs from 'node:fs';
import path from 'node:path';
import {fileURLToPath} from 'node:url';

export const REPO = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

const HELP = `options (each also from the environment):
  --web DIR       the built page: formsim.{js,wasm,data} + web/'s files (FORMSIM_WEB_DIR;
                  default REPO/out/web, as scripts/web.sh writes it)
  --native FILE   the native formsim binary (FORMSIM_NATIVE; default REPO/build/formsim)
  --out DIR       where pictures, tables and logs go (FORMSIM_WEB_OUT; default REPO/out/web_test)
  --scenarios A,B only these scenarios in the equality check (default: every shipped one)
  --skip-equality the window checks only`;

/// Parses process.argv; exits 2 with the help on a bad option.
export function options() {
  const o = {
    web: process.env.FORMSIM_WEB_DIR || path.join(REPO, 'out/web'),
    native: process.env.FORMSIM_NATIVE || path.join(REPO, 'build/formsim'),
    out: process.env.FORMSIM_WEB_OUT || path.join(REPO, 'out/web_test'),
    scenarios: null,
    skipEquality: false,
  };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) usage(`${a} needs a value`);
      return argv[++i];
    };
    if (a === '--web') o.web = value();
    else if (a === '--native') o.native = value();
    else if (a === '--out') o.out = value();
    else if (a === '--scenarios') o.scenarios = value().split(',').filter(Boolean);
    else if (a === '--skip-equality') o.skipEquality = true;
    else if (a === '--help' || a === '-h') usage(null);
    else usage(`unknown option ${a}`);
  }
  o.web = path.resolve(o.web);
  o.native = path.resolve(o.native);
  o.out = path.resolve(o.out);
  for (const f of ['index.html', 'formsim_page.js', 'formsim_params.js', 'formsim.js',
                   'formsim.wasm', 'formsim.data']) {
    if (!fs.existsSync(path.join(o.web, f))) {
      usage(`--web ${o.web}: ${f} is missing (bash scripts/web.sh builds out/web/)`);
    }
  }
  fs.mkdirSync(o.out, {recursive: true});
  return o;
}

function usage(error) {
  if (error) console.error(`error: ${error}`);
  console.error(HELP);
  process.exit(error ? 2 : 0);
}

/// The shipped scenarios' names (assets/scenarios/*.yaml), sorted.
export function shippedScenarios() {
  return fs.readdirSync(path.join(REPO, 'assets/scenarios'))
      .filter((f) => f.endsWith('.yaml')).map((f) => f.slice(0, -5)).sort();
}

/// The shipped lessons' names (assets/lessons/*.yaml), sorted.
export function shippedLessons() {
  return fs.readdirSync(path.join(REPO, 'assets/lessons'))
      .filter((f) => f.endsWith('.yaml')).map((f) => f.slice(0, -5)).sort();
}

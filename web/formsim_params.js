// formsim_params.js: turns the page's URL parameters into formsim's program arguments
// (issue 29: ?scenario= ?lesson= ?theme= ?present=1 ?script=, and ?paused=1). Pure: no DOM,
// no Module, so node can load it too (tests/web/browser_test.mjs checks it directly).
//
// The C++ side checks what only it knows (is the scenario shipped, is the theme one it has);
// this file refuses what would be misread before it gets there: a value that would read as a
// flag, a parameter given twice, a yes/no that is neither. Unknown parameters are only warned
// about, since the page still opens as asked without them.
'use strict';

(function (root) {
  /// Where the page writes a fetched ?script= file in the wasm's file system (MEMFS).
  const SCRIPT_PATH = '/home/web_user/page_script.txt';

  /// Every parameter the page reads, with what it accepts (the text of the error message).
  const PARAMETERS = {
    scenario: 'a shipped scenario\'s name, e.g. formation_traj2_ukf',
    lesson: 'a shipped lesson\'s name (formsim list lists them)',
    theme: 'light, dark, print or high-contrast',
    present: '1 or 0 (presentation mode: the world view fills the window)',
    paused: '1 or 0 (open paused)',
    script: 'the address of a script file (FRAME ACTION per line), relative to this page',
  };

  // A name as the C++ side spells its shipped scenarios, lessons and themes; never a flag.
  const NAME = /^[A-Za-z0-9_][A-Za-z0-9_.-]{0,199}$/;
  const YES = ['1', 'true', 'yes', 'on'];
  const NO = ['0', 'false', 'no', 'off'];

  /// Reads a URL query string (`location.search`). Returns
  /// `{args: [...], script: URL text or null, errors: [...], warnings: [...], present: bool}`:
  /// with errors non-empty the program must not start (each error names the parameter).
  function parseParams(search) {
    const query = new URLSearchParams(search || '');
    const seen = new Map();
    const errors = [];
    const warnings = [];
    for (const [key, value] of query) {
      if (!Object.prototype.hasOwnProperty.call(PARAMETERS, key)) {
        warnings.push(`?${key}= is not a parameter of this page and was ignored (it reads ` +
                      `${Object.keys(PARAMETERS).map((k) => '?' + k + '=').join(' ')})`);
        continue;
      }
      if (seen.has(key)) {
        errors.push(`?${key}= is given twice ("${seen.get(key)}" and "${value}"): give it once`);
        continue;
      }
      seen.set(key, value);
    }

    const name = (key) => {
      if (!seen.has(key)) return null;
      const value = seen.get(key);
      if (NAME.test(value)) return value;
      errors.push(`?${key}=${JSON.stringify(value)} is not a name: ${key} takes ${PARAMETERS[key]}`);
      return null;
    };
    const flag = (key) => {
      if (!seen.has(key)) return false;
      const value = seen.get(key).toLowerCase();
      if (YES.includes(value)) return true;
      if (NO.includes(value)) return false;
      errors.push(`?${key}=${JSON.stringify(seen.get(key))} is neither yes nor no: ${key} takes ` +
                  PARAMETERS[key]);
      return false;
    };

    const args = [];
    const scenario = name('scenario');
    const lesson = name('lesson');
    const theme = name('theme');
    const present = flag('present');
    const paused = flag('paused');
    let script = null;
    if (seen.has('script')) {
      script = seen.get('script');
      if (script.trim() === '') {
        errors.push(`?script= is empty: it takes ${PARAMETERS.script}`);
        script = null;
      }
    }

    if (scenario !== null) args.push(scenario);
    if (lesson !== null) args.push('--lesson', lesson);
    if (theme !== null) args.push('--theme', theme);
    if (present) args.push('--present');
    if (paused) args.push('--paused');
    if (script !== null) args.push('--script', SCRIPT_PATH);
    return {args, script, errors, warnings, present};
  }

  const api = {parseParams, SCRIPT_PATH, PARAMETERS};
  if (typeof module !== 'undefined' && module.exports) module.exports = api;
  else root.formsimParams = api;
})(typeof window !== 'undefined' ? window : globalThis);

// A small check list for the browser test: each check prints one line; the closing line is
// "N passed, N failed" (the plain line CI reads), and the exit status follows it.

export class Checks {
  constructor() {
    this.passed = 0;
    this.failed = [];
  }

  /// Records `ok` under `name`; `detail` is printed with a failure (and with a pass if given).
  check(name, ok, detail = '') {
    if (ok) {
      ++this.passed;
      console.log(`  ok    ${name}${detail ? ' (' + detail + ')' : ''}`);
    } else {
      this.failed.push(name);
      console.log(`  FAIL  ${name}${detail ? ': ' + detail : ''}`);
    }
    return ok;
  }

  /// Runs `fn` (async) as one section; an exception fails the section with its message.
  async section(title, fn) {
    console.log(`\n${title}`);
    try {
      await fn();
    } catch (e) {
      this.check(`${title}: no exception`, false, e && e.stack || String(e));
    }
  }

  /// Prints the closing line; returns the exit status.
  finish() {
    console.log(`\n${this.passed} passed, ${this.failed.length} failed`);
    if (this.failed.length) console.log('failed: ' + this.failed.join('; '));
    return this.failed.length ? 1 : 0;
  }
}

/// `promise`, or a rejection naming `what` after `ms` milliseconds.
export function within(ms, what, promise) {
  let timer;
  return Promise.race([
    promise.finally(() => clearTimeout(timer)),
    new Promise((_, reject) => {
      timer = setTimeout(() => reject(new Error(`${what}: no answer in ${ms / 1000} s`)), ms);
    }),
  ]);
}

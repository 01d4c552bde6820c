// Issue 29, item 3: a scenario run in the page gives the native build's timeseries. The verdict
// per scenario and the table for the closing note (OUT/equality.json and OUT/equality.md).
//
// Byte-identical is out of reach for every shipped scenario: each calls sin, cos or atan2, and
// glibc's and emscripten's musl's differ in the last bit on some arguments (tests/web/
// libm_probe.sh, 2000 arguments in [-10, 10): sin 3.4 %, cos 2.9 %, atan2 18 %, hypot 12 %,
// exp 0.1 %; sqrt never). So the tolerance applies to all, by kind:
// - formation, agv, inspection: continuous dynamics carry a last-bit difference along without
//   growing it much: every numeric cell within 1e-9 (scaled as below; measured <= 7.5e-12).
// - velocity: its sliding-window estimator makes discrete choices (which landmarks, how many),
//   and a last-bit difference flips some (the kind keeps libm's sine in its noise on purpose,
//   sim/core/rng.cpp), so the run is another realisation: same header and rows, and the
//   paper's tables (every RMSE in summary.json's results) within 15 % (measured <= 10.5 %).
import fs from 'node:fs';
import path from 'node:path';

export const TOLERANCE = {
  scaled: 1e-9,
  rmse_rel: 0.15,
  text: 'formation, agv, inspection: |a - b| <= 1e-9 * max(1, |a|, |b|) in every cell; ' +
        'velocity (discrete sliding-window choices flip on a last-bit difference): same header ' +
        'and rows, every RMSE of summary.json within 15 %',
};

/// One row per run: {scenario, kind, verdict ("identical" / "max |diff| ... in COLUMN"), ok,
/// detail, ...measures}.
export function equalityRows(results) {
  return results.map((r) => {
    const c = r.cmp;
    const base = {scenario: r.scenario, kind: r.kind, steps: r.steps, sim_time: r.sim_time,
                  page_wall_ms: r.wall_ms, native_ms: r.native_ms, csv_bytes: r.bytes,
                  results: r.results};
    if (c.identical) return {...base, verdict: 'identical', ok: true, detail: `${c.rows[0]} rows`};
    if (!c.header_equal || c.rows[0] !== c.rows[1] || c.text_mismatches) {
      return {...base, verdict: 'differs in shape', ok: false,
              detail: `header equal ${c.header_equal}, rows ${c.rows.join(' vs ')}, ` +
                      `${c.text_mismatches} cells differ as text`};
    }
    const w = c.worst;
    const verdict = `max |diff| ${w.abs.toExponential(2)} in ${w.column}`;
    if (r.kind === 'velocity') {
      const rmse = r.results.rmse_worst;
      return {
        ...base, verdict: verdict + (rmse ? `; RMSEs within ${(100 * rmse.rel).toPrecision(2)} %` : ''),
        ok: r.results.missing.length === 0 && (!rmse || rmse.rel <= TOLERANCE.rmse_rel),
        detail: `${c.cells_differing} cells differ; worst RMSE ${rmse ? rmse.key + ': page ' +
                 rmse.a + ', native ' + rmse.b : 'none differs'} (tolerance ` +
                `${100 * TOLERANCE.rmse_rel} %)${r.results.missing.length ? '; only on one side: ' +
                r.results.missing.join(', ') : ''}`,
      };
    }
    return {
      ...base, verdict,
      ok: w.scaled <= TOLERANCE.scaled,
      detail: `${c.cells_differing} cells differ; worst at row ${w.row}: page ${w.a}, ` +
              `native ${w.b} (scaled ${w.scaled.toExponential(2)}, tolerance ` +
              `${TOLERANCE.scaled})`,
      columns: c.columns,
    };
  });
}

/// Writes OUT/equality.json (every row) and OUT/equality.md (the closing note's table).
export function writeEqualityTable(out, rows) {
  fs.writeFileSync(path.join(out, 'equality.json'),
                   JSON.stringify({tolerance: TOLERANCE, rows}, null, 1) + '\n');
  const md = ['| scenario | page vs native timeseries.csv | steps | page run (ms) |',
              '|---|---|---|---|'];
  for (const r of rows) {
    const verdict = r.verdict.replace(/\|/g, '\\|');  // |diff| inside a Markdown cell
    md.push(`| ${r.scenario} | ${verdict}${r.ok ? '' : ' (FAILS)'} | ${r.steps ?? ''} | ` +
            `${r.page_wall_ms === undefined ? '' : Math.round(r.page_wall_ms)} |`);
  }
  md.push('', `Tolerance: ${TOLERANCE.text}.`);
  fs.writeFileSync(path.join(out, 'equality.md'), md.join('\n') + '\n');
}

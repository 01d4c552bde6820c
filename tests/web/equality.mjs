// Issue 29, item 3: a scenario run in the page gives the native build's timeseries. The verdict
// per scenario and the table for the closing note (OUT/equality.json and OUT/equality.md).
import fs from 'node:fs';
import path from 'node:path';

/// Where the page's CSV is not byte-identical, every numeric cell must agree within this
/// (|a - b| / max(1, |a|, |b|)), with the same header, rows and text cells (empty, nan).
export const TOLERANCE = {
  scaled: 1e-9,
  text: '|a - b| <= 1e-9 * max(1, |a|, |b|) per cell; same header, rows, empty and nan cells',
};

/// One row per run: {scenario, verdict ("identical" / "max |diff| ... in COLUMN" / why not),
/// ok, detail, ...measures}.
export function equalityRows(results) {
  return results.map((r) => {
    const c = r.cmp;
    const base = {scenario: r.scenario, steps: r.steps, sim_time: r.sim_time,
                  page_wall_ms: r.wall_ms, native_ms: r.native_ms, csv_bytes: r.bytes};
    if (c.identical) return {...base, verdict: 'identical', ok: true, detail: `${c.rows[0]} rows`};
    if (!c.header_equal || c.rows[0] !== c.rows[1] || c.text_mismatches > 0) {
      return {...base, verdict: 'differs in shape', ok: false,
              detail: `header equal ${c.header_equal}, rows ${c.rows.join(' vs ')}, ` +
                      `${c.text_mismatches} cells differ as text`};
    }
    const w = c.worst;
    return {
      ...base,
      verdict: `max |diff| ${w.abs.toExponential(2)} in ${w.column}`,
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
  const md = ['| scenario | page vs native timeseries.csv | rows | page run (ms) |',
              '|---|---|---|---|'];
  for (const r of rows) {
    md.push(`| ${r.scenario} | ${r.verdict}${r.ok ? '' : ' (FAILS)'} | ${r.steps ?? ''} | ` +
            `${r.page_wall_ms === undefined ? '' : Math.round(r.page_wall_ms)} |`);
  }
  md.push('', `Tolerance where not identical: ${TOLERANCE.text}.`);
  fs.writeFileSync(path.join(out, 'equality.md'), md.join('\n') + '\n');
}

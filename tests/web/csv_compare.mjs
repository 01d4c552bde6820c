// Compares two timeseries CSVs (formsim's: a header line, then one row per recorded step;
// empty cells are unsampled values, `nan` a computed NaN). Self-contained on purpose: the test
// also runs it inside the page (page.addScriptTag with its source), next to a CSV too large to
// carry over the DevTools protocol.

/// Returns {identical, rows: [na, nb], header_equal, cells_differing, text_mismatches,
/// worst: {column, row, a, b, abs, scaled} or null, columns: {name: {abs, scaled}} for every
/// column that differs}. `scaled` is |a - b| / max(1, |a|, |b|): an absolute difference for
/// values up to 1, a relative one above.
export function compareCsv(textA, textB) {
  const result = {
    identical: textA === textB, rows: [0, 0], header_equal: true, cells_differing: 0,
    text_mismatches: 0, worst: null, columns: {},
  };
  const linesA = textA.split('\n');
  const linesB = textB.split('\n');
  if (linesA[linesA.length - 1] === '') linesA.pop();
  if (linesB[linesB.length - 1] === '') linesB.pop();
  result.rows = [linesA.length - 1, linesB.length - 1];
  if (result.identical) return result;
  const header = (linesA[0] || '').split(',');
  result.header_equal = linesA[0] === linesB[0];
  const n = Math.min(linesA.length, linesB.length);
  for (let r = 1; r < n; ++r) {
    if (linesA[r] === linesB[r]) continue;
    const a = linesA[r].split(',');
    const b = linesB[r].split(',');
    for (let c = 0; c < Math.max(a.length, b.length); ++c) {
      const x = a[c];
      const y = b[c];
      if (x === y) continue;
      ++result.cells_differing;
      const name = header[c] || `column ${c + 1}`;
      const fx = Number(x);
      const fy = Number(y);
      if (x === undefined || y === undefined || x === '' || y === '' ||
          !Number.isFinite(fx) || !Number.isFinite(fy)) {
        ++result.text_mismatches;  // one side empty, nan, inf or not a number
        continue;
      }
      const abs = Math.abs(fx - fy);
      const scaled = abs / Math.max(1, Math.abs(fx), Math.abs(fy));
      const col = result.columns[name] || (result.columns[name] = {abs: 0, scaled: 0});
      col.abs = Math.max(col.abs, abs);
      col.scaled = Math.max(col.scaled, scaled);
      if (!result.worst || scaled > result.worst.scaled) {
        result.worst = {column: name, row: r, a: x, b: y, abs, scaled};
      }
    }
  }
  return result;
}

/// Compares the numbers of two summary.json `results` objects (the run's tables: RMSEs, errors,
/// counts), leaf by leaf. Returns {leaves, differing, worst: {key, a, b, rel} or null,
/// rmse_worst: the same among keys naming an RMSE, missing: [keys on one side only]}; `rel` is
/// |a - b| / max(|a|, |b|).
export function compareResults(a, b) {
  const out = {leaves: 0, differing: 0, worst: null, rmse_worst: null, missing: []};
  const walk = (x, y, key) => {
    if (typeof x === 'number' && typeof y === 'number') {
      ++out.leaves;
      if (x === y) return;
      ++out.differing;
      const rel = Math.abs(x - y) / Math.max(Math.abs(x), Math.abs(y));
      if (!out.worst || rel > out.worst.rel) out.worst = {key, a: x, b: y, rel};
      if (/rmse/i.test(key) && (!out.rmse_worst || rel > out.rmse_worst.rel)) {
        out.rmse_worst = {key, a: x, b: y, rel};
      }
    } else if (x && y && typeof x === 'object' && typeof y === 'object') {
      for (const k of new Set([...Object.keys(x), ...Object.keys(y)])) {
        if (!(k in x) || !(k in y)) out.missing.push(`${key}.${k}`);
        else walk(x[k], y[k], `${key}.${k}`);
      }
    } else if (x !== y) {
      ++out.differing;
      out.missing.push(`${key} (${JSON.stringify(x)} vs ${JSON.stringify(y)})`);
    }
  };
  walk(a, b, 'results');
  return out;
}

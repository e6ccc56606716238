#!/usr/bin/env node
// Makes the accuracy tables of README.md, docs/*.md and the models' rustdoc from the test
// suite's own measurements: the `[maxerr]` lines every accuracy test prints (one per model,
// backend, case set and regime: the largest absolute error over its cases), and the scene
// cost lines of the QEMU budget harness.
//
//   cargo test --workspace -- --nocapture > target/test-output.txt 2>&1   # or any subset
//   node boards/test-tables.mjs target/test-output.txt                    # writes target/accuracy/*.md
//   node boards/readme-tables.mjs                                         # puts them into the docs
//
// .ci/run does the three on every run and fails if a committed block differs. The errors are
// deterministic: seeded inputs, the `libm` crate's own functions, the same code on every run.
// The suites that draw random inputs per run (proptest's properties, the bit-pattern fuzzing)
// are left out.
//
// Written (each a markdown fragment):
//   target/accuracy/all.md         every measured line, grouped by model (docs/accuracy.md)
//   target/accuracy/models.md      per model: f64 against its reference; f32, Fast32, Fixed22 against f64
//   target/accuracy/fixed.md       the Fixed22 table of the README
//   target/accuracy/hermite.md     Snyder's Hermite cap against the exact model, per sigma
//   target/accuracy/peak.md        Picott's peak against the Phong integral, per m
//   target/accuracy/large-exponents.md  the Phong models up to m = 1001 (STABILITY.md)
//   target/accuracy/scene-cost.md  the QEMU scene cost (prepared 16 lights against the 2 alone)
//   target/accuracy/model-ID.md    one line per model, for its rustdoc and docs/models.md

import { mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const logPath = process.argv[2];
if (!logPath) {
  console.error('usage: node boards/test-tables.mjs LOG (the output of cargo test -- --nocapture)');
  process.exit(2);
}
// Under --nocapture the test threads share stdout, so libtest's `test NAME ... ` status can
// land in front of a line another test prints: a `[maxerr]` line is read from its tag on
// (measured: 1 of 695 lines in a CI run, which dropped that line from the tables).
const log = readFileSync(logPath, 'utf8')
  .split('\n')
  .map((l) => {
    const i = l.indexOf('[maxerr] ');
    return i > 0 ? l.slice(i) : l;
  });
const outDir = join(root, 'target/accuracy');
mkdirSync(outDir, { recursive: true });
// No file of an earlier run stays behind (a block whose source vanished must fail the check).
for (const f of readdirSync(outDir)) if (f.endsWith('.md')) rmSync(join(outDir, f));

// Suites whose inputs change from run to run (not tabulated).
const RANDOM_PER_RUN = new Set(['properties', 'fuzz_bits']);
// The models, in the order of docs/models.md.
const MODELS = [
  'hemi_const', 'hemi_cos', 'sky_overcast', 'sky_ground', 'cap_lambert', 'cap_lambert_hermite',
  'sphere_lambert', 'sphere_lambert_hermite', 'polygon_lambert', 'line_lambert',
  'phong_hemi_const', 'phong_hemi_cos', 'phong_cap', 'phong_sphere', 'phong_polygon',
  'line_phong_peak', 'rect_phong_peak', 'axial_moment', 'double_axis_moment',
  'directional_luminaire', 'glossy_reflection', 'glossy_transmission', 'lune_normalization',
  'sh9_irradiance', 'sh9_disc_irradiance', 'superellipse_shape', 'distance_falloff',
];
const BACKENDS = ['f64', 'f32', 'Fast32', 'Fixed22'];

// ---------------------------------------------------------------------------------------------
// Parsing
// ---------------------------------------------------------------------------------------------

/** One `[maxerr]` line: { suite, text, name, err, ratio, cases, model, m, backend, against, set, regime }. */
const lines = [];
let suite = '';
const seen = new Set();
const byKey = new Map();
for (const raw of log) {
  const run = raw.match(/^\s*Running (?:tests\/)?(\S+?)(?:\.rs)? \(/);
  if (run) {
    // (A suite in a directory, `tests/line/main.rs`, is named by its directory.)
    suite = run[1].replace(/\/main$/, '').replace(/^.*\//, '');
    continue;
  }
  if (!raw.startsWith('[maxerr] ') || RANDOM_PER_RUN.has(suite)) continue;
  const text = raw.slice(9);
  const m = text.match(/^(.*?)\s+max abs err (\S+?)(?:, max err\/bound (\S+))? over (\d+) cases/);
  if (!m) {
    // A line of its own shape (kernel LSB errors, scaling checks): kept as printed, up to
    // the worst case's description.
    const short = text.replace(/;? ?worst.*$/, '').trim();
    if (!seen.has(short)) lines.push({ suite, text: short });
    seen.add(short);
    continue;
  }
  const name = m[1].trim();
  const key = `${suite}|${name}`;
  const err = Number(m[2]);
  const ratio = m[3] === undefined ? null : Number(m[3]);
  const cases = Number(m[4]);
  const prior = byKey.get(key);
  if (prior) {
    // Printed twice (report, then check: the same figures), or by two tests of one file: the
    // largest of each, whatever order the test threads printed them in.
    prior.err = Math.max(prior.err, err);
    if (ratio !== null) prior.ratio = Math.max(prior.ratio ?? 0, ratio);
    prior.cases = Math.max(prior.cases, cases);
    continue;
  }
  const entry = { suite, text: name, name, err, ratio, cases };
  byKey.set(key, entry);
  // "<model>[ m=K] <backend>[ vs <reference>][ (<case set>)][, m=K][ [<regime>]]..."
  const p = name.match(/^(\w+)(?: m=(\d+))? (f64|f32|Fast32|Fixed22)(?: vs ([\w-]+))?(?: \(([^)]*)\))?(?:,? m=(\d+))?(?: \[([^\]]+)\])?/);
  if (p && MODELS.includes(p[1])) {
    Object.assign(entry, {
      model: p[1],
      m: p[2] ?? p[6] ?? null,
      backend: p[3],
      against: p[4] ?? 'reference',
      set: p[5] ?? null,
      // Fixed22's lines (one bound for every case) and f64's have no regime tag: "main".
      // An untagged f32/Fast32 line mixes the regimes ("all").
      regime: p[7] ?? (p[3] === 'f32' || p[3] === 'Fast32' ? 'all' : 'main'),
      // What the line measured beyond model and backend, for the f64 column.
      what: name.slice(p[1].length).replace(/^ (?:m=\d+ )?f64 ?(?:vs )?/, '').trim(),
    });
  }
  lines.push(entry);
}

// The test threads print in any order: sort (by test file, then text) so that the tables are
// the same on every run.
lines.sort((a, b) => (a.suite === b.suite ? (a.text < b.text ? -1 : a.text > b.text ? 1 : 0) : a.suite < b.suite ? -1 : 1));

// ---------------------------------------------------------------------------------------------
// Formatting
// ---------------------------------------------------------------------------------------------

/** `1.2e-7`, as the README writes errors (two significant digits). */
const e2 = (x) => {
  if (x === 0) return '0';
  if (!Number.isFinite(x)) return String(x);
  const [mant, exp] = x.toExponential(1).split('e');
  return `${mant}e${Number(exp)}`;
};
/** `text` broken into lines of at most 90 characters (for the rustdoc blocks). */
const wrap = (text) => {
  const out = [];
  let line = '';
  for (const w of text.split(' ')) {
    if (line && line.length + 1 + w.length > 90) {
      out.push(line);
      line = w;
    } else line = line ? `${line} ${w}` : w;
  }
  if (line) out.push(line);
  return out.join('\n') + '\n';
};
const thousands = (n) => String(n).replace(/\B(?=(\d{3})+(?!\d))/g, ' ');

/** The largest of `rows` (or null), with where it was measured. */
function worst(rows) {
  let w = null;
  for (const r of rows) if (w === null || r.err > w.err) w = r;
  return w;
}
const at = (r) => (r.m !== null ? ` at m = ${r.m}` : '');
/** "quadrature (adversarial), m=255" -> "quadrature, adversarial, m = 255". */
const what = (r) =>
  r.what.replace(/ \(([^)]*)\)/g, ', $1').replace(/^\[([^\]]*)\]$/, '$1').replace(/m=(\d+)/g, 'm = $1');
const of = (model, backend, pred = () => true) =>
  lines.filter((l) => l.model === model && l.backend === backend && pred(l));

/** "x (m = K)" for the main regime; "regime x (m = K); ..." for the others. */
function cellMain(model, backend) {
  const w = worst(of(model, backend, (l) => l.regime === 'main'));
  return w ? `${e2(w.err)}${at(w)}` : '';
}
function cellOthers(model, backend) {
  // Untagged lines ("all") only where the model has no tagged lines of this backend.
  const tagged = of(model, backend, (l) => l.regime !== 'all').length > 0;
  const regimes = [...new Set(of(model, backend, (l) => l.regime !== 'main' && !(tagged && l.regime === 'all')).map((l) => l.regime))].sort();
  return regimes
    .map((g) => {
      const w = worst(of(model, backend, (l) => l.regime === g));
      return `${g}: ${e2(w.err)}${at(w)}`;
    })
    .join('; ');
}
function cellF64(model) {
  const w = worst(of(model, 'f64'));
  if (!w) return '';
  return w.what && w.what !== 'quadrature' ? `${e2(w.err)} (${what(w)})` : e2(w.err);
}

// ---------------------------------------------------------------------------------------------
// The tables
// ---------------------------------------------------------------------------------------------

const files = {};

// Per model: the summary.
{
  const t = [
    '| model id | f64 vs reference | f32 vs f64 (main) | f32, other regimes | Fast32 vs f64 (main) | Fast32, other regimes | Fixed22 vs f64 |',
    '|---|---|---|---|---|---|---|',
  ];
  for (const id of MODELS) {
    if (!lines.some((l) => l.model === id)) continue;
    t.push(`| \`${id}\` | ${cellF64(id)} | ${cellMain(id, 'f32')} | ${cellOthers(id, 'f32')} | ${cellMain(id, 'Fast32')} | ${cellOthers(id, 'Fast32')} | ${cellMain(id, 'Fixed22')} |`);
  }
  files['models.md'] = t.join('\n') + '\n';
}

// Fixed22.
{
  const t = ['| model id | max abs error | at m = 255 | cases |', '|---|---|---|---|'];
  for (const id of MODELS) {
    const rows = of(id, 'Fixed22');
    if (!rows.length) continue;
    const w = worst(rows);
    const m255 = rows.filter((r) => r.m === '255');
    const cases = [...new Set(rows.map((r) => r.cases))];
    const perM = rows.some((r) => r.m !== null);
    t.push(`| \`${id}\` | ${e2(w.err)}${at(w)} | ${m255.length ? e2(worst(m255).err) : ''} | ${cases.map(thousands).join(', ')}${perM ? ' per m' : ''} |`);
  }
  files['fixed.md'] = t.join('\n') + '\n';
}

// Everything, by model.
{
  const t = [];
  const row = (l) =>
    `| ${l.text.replace(/\|/g, '\\|')} | ${l.err === undefined ? '' : e2(l.err)} | ${l.ratio === null || l.ratio === undefined ? '' : l.ratio.toFixed(3)} | ${l.cases === undefined ? '' : thousands(l.cases)} | \`${l.suite}\` |`;
  const head = ['| measured | max abs err | max err/bound | cases | test |', '|---|---|---|---|---|'];
  for (const id of MODELS) {
    const rows = lines.filter((l) => l.model === id);
    if (!rows.length) continue;
    t.push(`### \`${id}\``, '', ...head, ...rows.map(row), '');
  }
  const rest = lines.filter((l) => !l.model);
  if (rest.length) {
    t.push('### Other measurements', '', '| measured | max abs err | max err/bound | cases | test |', '|---|---|---|---|---|');
    t.push(...rest.map(row), '');
  }
  files['all.md'] = t.join('\n');
}

// Per model, one paragraph (rustdoc and docs/models.md).
for (const id of MODELS) {
  if (!lines.some((l) => l.model === id)) continue;
  const parts = [];
  const f64 = worst(of(id, 'f64'));
  if (f64) parts.push(`f64 within ${e2(f64.err)} of its reference (${what(f64).replace(/^quadrature/, 'the independent quadrature') || 'the independent quadrature'})`);
  const low = [];
  for (const b of ['f32', 'Fast32', 'Fixed22']) {
    const main = cellMain(id, b);
    if (!main) continue;
    const others = cellOthers(id, b);
    low.push(`${b} ${main}${others ? ` (${others})` : ''}`);
  }
  if (low.length) parts.push(`against f64, ${low.join(', ')}`);
  const n = lines.filter((l) => l.model === id && l.cases).reduce((s, l) => s + l.cases, 0);
  files[`model-${id}.md`] = wrap(`Measured: ${parts.join('; ')}; ${thousands(n)} cases in all (\`docs/accuracy.md\`).`);
}

// Snyder's Hermite approximation, per sigma (tests/fixtures.rs).
{
  const t = ['| sigma | Snyder (cubics in w) | cubics in cos w (`lambert_hermite_cos`) |', '|---|---|---|'];
  const rows = [];
  for (const l of log) {
    const h = l.match(/^\[maxerr\] cap_lambert_hermite_cos vs exact, sigma=(\S+)\s+max abs err (\S+) \(Snyder (\S+)\)/);
    if (h) rows.push([h[1], `| ${h[1]} | ${e2(Number(h[3]))} | ${e2(Number(h[2]))} |`]);
  }
  // In increasing sigma ("k pi/d"), whatever order the lines came in.
  const sigma = (label) => {
    const q = label.match(/^(\d*)pi\/(\d+)$/);
    return q ? Number(q[1] || 1) / Number(q[2]) : Infinity;
  };
  rows.sort((a, b) => sigma(a[0]) - sigma(b[0]));
  t.push(...rows.map((r) => r[1]));
  if (t.length > 2) files['hermite.md'] = t.join('\n') + '\n';
}

// Picott's peak against the true integral (tests/line/).
{
  const t = ['| m | max abs(peak - I) | mean | median I/peak |', '|---|---|---|---|'];
  const peaks = [];
  for (const l of log) {
    const h = l.match(/^\[maxerr\] rect_phong_peak vs phong_polygon, m=(\d+)\s*: max \|peak - I\| (\S+), mean (\S+); I\/peak median (\S+?) \(/);
    if (h) peaks.push([Number(h[1]), `| ${h[1]} | ${Number(h[2]).toFixed(3)} | ${Number(h[3]).toFixed(3)} | ${Number(h[4]).toPrecision(2)} |`]);
  }
  peaks.sort((a, b) => a[0] - b[0]);
  t.push(...peaks.map((r) => r[1]));
  if (t.length > 2) files['peak.md'] = t.join('\n') + '\n';
}

// The large-exponent table (tests/large_exponents.rs prints it as `[table]` lines).
{
  const rows = log.filter((l) => l.startsWith('[table] ')).map((l) => `| ${l.slice(8).trim()} |`);
  if (rows.length > 1) {
    const cols = rows[0].split('|').length - 2;
    files['large-exponents.md'] = [rows[0], `|${'---|'.repeat(cols)}`, ...rows.slice(1)].join('\n') + '\n';
  }
}

// The QEMU scene cost (host-sim/tests/qemu_budget.rs).
{
  const t = ['| target, backend | 16 lights, prepared | the 2 lights alone | ratio | frames |', '|---|---:|---:|---:|---|'];
  for (const l of log) {
    const h = l.match(/^(\w+) (\S+): one sphere, 16 lights of which 2 reach it, prepared: (\d+) instructions; the 2 alone: (\d+) \(([\d.]+)x; bound 1.25x\); frames (\w+)/);
    if (h) t.push(`| ${h[1] === 'm4f' ? 'Cortex-M4F' : h[1] === 'm0' ? 'Cortex-M0' : h[1]} ${h[2]} | ${thousands(h[3])} | ${thousands(h[4])} | ${h[5]}x | ${h[6]} |`);
  }
  if (t.length > 2) files['scene-cost.md'] = t.join('\n') + '\n';
}

for (const [name, text] of Object.entries(files)) writeFileSync(join(outDir, name), text);
const measured = lines.filter((l) => l.model).length;
console.error(`target/accuracy: ${Object.keys(files).length} files from ${lines.length} [maxerr] lines (${measured} of the models)`);
if (measured === 0) {
  console.error(`${logPath}: no [maxerr] lines of the models (was the suite run with --nocapture?)`);
  process.exit(1);
}

#!/usr/bin/env node
// Puts measured tables into README.md, STABILITY.md, docs/*.md and the rustdoc of src/, each
// between its markers:
//
//   <!-- BEGIN m4f-frames: target/qemu-frame/frames.md -->
//   ...
//   <!-- END m4f-frames -->
//
// The file after the colon (relative to the repository) is the output of the command that
// measures the table; the block is that file's text. The blocks and their commands:
//
//   rp2040-frames    target/rp2040-emu/frames.md      boards/rp2040-emu/check.sh 2 (rp2040js cycles)
//   m4f-frames       target/qemu-frame/frames.md      cargo test -p host-sim --test qemu_frame
//   frames-compared  target/frames-compared.md        this script, from the two files above
//   budget           target/budget/budget-table.md    cargo run --release -p host-sim -- budget --out target/budget
//                                                     (after cargo test -p host-sim --test qemu_budget)
//   budget-unit      target/budget/budget-unit.md     the same command (the calls with a UnitVec3)
//   budget-world     target/budget/budget-world.md    the same command (the world-coordinate lights)
//   budget-bar       target/budget/budget-bar.md      the same command (phong_polygon at m = 15)
//   sizes            boards/size-probe/sizes.md       boards/size-probe/measure.sh boards/size-probe/sizes.md
//   scene-budget     target/scene-budget/demo-rp2040-answer.md
//   scene-checks     target/scene-budget/checks.md    .ci/run's scene budget step (host-sim budget
//                                                     --scene ... --check, after the emulators)
//   accuracy-*, acc-*, scene-cost, large-exponents
//                    target/accuracy/*.md             node boards/test-tables.mjs LOG, from the log of
//                                                     cargo test --workspace -- --nocapture (the
//                                                     suite's `[maxerr]` lines, the QEMU scene cost)
//
// All of them, in order (what .ci/run does, then `--check`; about 20 minutes on two cores):
//
//   cargo test --workspace -- --nocapture > target/test-output.txt 2>&1   # QEMU harnesses too
//   bash boards/rp2040-emu/check.sh 2
//   bash boards/size-probe/measure.sh boards/size-probe/sizes.md
//   cargo run --release -p host-sim -- budget --out target/budget
//   node boards/test-tables.mjs target/test-output.txt
//   node boards/readme-tables.mjs
//
// Every one of them is deterministic: exact instruction and cycle counts of firmware built the
// same way from any clone (the board workspaces compile through boards/rustc-remap.sh), code
// sizes, and errors over seeded inputs. Host timings, which are not, are kept out of the blocks.
//
//   node boards/readme-tables.mjs          # rewrite the blocks from the files
//   node boards/readme-tables.mjs --check  # exit 1 if a block differs from its file or the
//                                          # file is missing (CI, after measuring)
//   node boards/readme-tables.mjs --from DIR  # the files from another checkout (a clean clone)

import { existsSync, readdirSync, readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const check = process.argv.includes('--check');
// `--from DIR`: read the measurements from another checkout of the repository (a clean clone
// of the commit measured), writing the blocks here.
const fromAt = process.argv.indexOf('--from');
const from = fromAt > 0 ? process.argv[fromAt + 1] : root;

// The before/after comparison of the frames: the "now" column from the two frame tables,
// "before" the measurements of commit 5ceefe3 with the same harnesses (fixed numbers).
function framesCompared() {
  const rpPath = join(from, 'target/rp2040-emu/frames.md');
  const m4Path = join(from, 'target/qemu-frame/frames.md');
  if (!existsSync(rpPath) || !existsSync(m4Path)) return null;
  const rows = (text) =>
    text
      .split('\n')
      .filter((l) => l.startsWith('|') && !l.startsWith('|---'))
      .map((l) => l.split('|').slice(1, -1).map((c) => c.trim()));
  const table = (text) => {
    const [head, ...body] = rows(text);
    return body.map((r) => Object.fromEntries(head.map((h, i) => [h, r[i]])));
  };
  const m4 = table(readFileSync(m4Path, 'utf8'));
  const m4frame = (mode) => {
    const r = m4.find((x) => x.mode === mode && x.frame === '0');
    if (!r) throw new Error(`target/qemu-frame/frames.md: no ${mode} frame 0`);
    return Number(r.total);
  };
  // rp2040-emu/frames.md's first table: firmware | cores | frame | cycles | ...; frame 1 (the
  // first steady-state frame, "1 (from the end of frame 0)") is compared.
  const rp = table(readFileSync(rpPath, 'utf8').split('\n\n')[0]);
  const rpFrame = (binary) => {
    const r = rp.find((x) => x.firmware === binary && /^1\b/.test(x.frame ?? ''));
    if (!r) throw new Error(`target/rp2040-emu/frames.md: no ${binary} frame 1`);
    return Number(r.cycles);
  };
  const M = (x) => `${(x / 1e6).toPrecision(3)} M`;
  const line = (what, before, now) =>
    `| ${what} | ${M(before)} | ${M(now)} | ${(before / now).toFixed(1)}x |`;
  return [
    '| board, mode | before | now | factor |',
    '|---|---:|---:|---:|',
    line('RP2040 single core (rp2040js cycles, frame 1)', 240.0e6, rpFrame('lit_scene')),
    line('RP2040 both cores (rp2040js cycles, frame 1)', 152.0e6, rpFrame('lit_scene_dual_core')),
    line('STM32F411 firmware frame (QEMU instructions, frame 0): per pixel then, Gouraud now', 101.3e6, m4frame('gouraud')),
    line('STM32F411 Gouraud against Gouraud (QEMU instructions, frame 0)', 33.5e6, m4frame('gouraud')),
    line('STM32F411 per pixel against per pixel (QEMU instructions, frame 0)', 101.3e6, m4frame('per_pixel')),
  ].join('\n') + '\n';
}

const generated = { 'target/frames-compared.md': framesCompared };

// Markdown files, and the Rust sources whose doc comments hold blocks (each line of such a
// block carries the comment's prefix, `/// ` or `//! `, as the markers do).
const rustFiles = (dir) =>
  readdirSync(join(root, dir), { withFileTypes: true }).flatMap((e) =>
    e.isDirectory() ? rustFiles(`${dir}/${e.name}`) : e.name.endsWith('.rs') ? [`${dir}/${e.name}`] : [],
  );
const files = [
  'README.md',
  'STABILITY.md',
  ...readdirSync(join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`),
  ...rustFiles('src'),
];
const mdBlock = /<!-- BEGIN ([\w-]+): (\S+) -->\n([\s\S]*?)<!-- END \1 -->/g;
const rsBlock = /^([ \t]*\/\/[/!] )<!-- BEGIN ([\w-]+): (\S+) -->\n([\s\S]*?)^\1<!-- END \2 -->/gm;
let differ = 0;
let missing = 0;
for (const doc of files) {
  const docPath = join(root, doc);
  const text = readFileSync(docPath, 'utf8');
  const rs = doc.endsWith('.rs');
  let changed = 0;
  const replacer = (whole, prefix, name, file, comment) => {
    // In a Rust file the block's lines carry the comment prefix: compared without it.
    const body = rs
      ? comment.split('\n').slice(0, -1).map((l) => (l.startsWith(prefix) ? l.slice(prefix.length) : l.replace(/^[ \t]*\/\/[/!] ?/, ''))).join('\n') + (comment ? '\n' : '')
      : comment;
    let fresh;
    if (generated[file]) {
      try {
        const t = generated[file]();
        if (t !== null) {
          mkdirSync(dirname(join(from, file)), { recursive: true });
          writeFileSync(join(from, file), t);
          fresh = t;
        }
      } catch (e) {
        console.error(`${doc}: ${name}: ${e.message}`);
      }
    } else if (existsSync(join(from, file))) {
      fresh = readFileSync(join(from, file), 'utf8').trimEnd() + '\n';
    }
    if (fresh === undefined) {
      missing++;
      console.error(`${doc}: ${name}: ${file} is missing (run its command first); left as it is`);
      return whole;
    }
    if (fresh !== body) {
      changed++;
      console.error(`${doc}: ${name}: differs from ${file}`);
      if (check) {
        const a = body.split('\n');
        const b = fresh.split('\n');
        for (let i = 0, shown = 0; i < Math.max(a.length, b.length) && shown < 6; i++) {
          if (a[i] !== b[i]) {
            console.error(`  committed: ${a[i] ?? '(none)'}\n  measured:  ${b[i] ?? '(none)'}`);
            shown++;
          }
        }
      }
    }
    if (rs) {
      const lines = fresh.split('\n').slice(0, -1).map((l) => (l ? prefix + l : prefix.trimEnd()));
      return `${prefix}<!-- BEGIN ${name}: ${file} -->\n${lines.map((l) => l + '\n').join('')}${prefix}<!-- END ${name} -->`;
    }
    return `<!-- BEGIN ${name}: ${file} -->\n${fresh}<!-- END ${name} -->`;
  };
  const out = rs
    ? text.replace(rsBlock, replacer)
    : text.replace(mdBlock, (whole, name, file, body) => replacer(whole, '', name, file, body));
  differ += changed;
  if (!check && changed) writeFileSync(docPath, out);
}
if (check) {
  if (differ || missing) {
    console.error(`${differ} block(s) differ from their measurement, ${missing} measurement(s) missing: ` +
      'run the commands listed in boards/readme-tables.mjs, then `node boards/readme-tables.mjs`, and commit');
    process.exit(1);
  }
  console.error('every measured block matches its measurement');
} else {
  console.error(`${differ} block(s) updated${missing ? `, ${missing} left as they are (measurement missing)` : ''}`);
}

#!/usr/bin/env node
// Puts the frame tables measured on the emulated boards into README.md, each between its
// markers:
//
//   <!-- BEGIN rp2040-frames: target/rp2040-emu/frames.md -->
//   ...
//   <!-- END rp2040-frames -->
//
// Tables: `rp2040-frames` (written by boards/rp2040-emu/check.sh: rp2040js cycles per frame
// and per stage) and `m4f-frames` (written by `cargo test -p host-sim --test qemu_frame`: exact
// QEMU instruction counts per frame and stage). Both are deterministic for a checkout; they move
// by a fraction of a percent with its path (panic locations embed it), so CI reports a difference
// without failing.
//
//   node boards/readme-tables.mjs          # rewrite README.md's blocks from the files
//   node boards/readme-tables.mjs --check  # exit 1 if a block differs from its file

import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const readme = join(root, 'README.md');
const check = process.argv.includes('--check');

let text = readFileSync(readme, 'utf8');
let differ = 0;
const block = /<!-- BEGIN ([\w-]+): (\S+) -->\n([\s\S]*?)<!-- END \1 -->/g;
text = text.replace(block, (whole, name, file, body) => {
  const path = join(root, file);
  if (!existsSync(path)) {
    console.error(`${name}: ${file} is missing (run its command first); left as it is`);
    return whole;
  }
  const fresh = readFileSync(path, 'utf8').trimEnd() + '\n';
  if (fresh !== body) {
    differ++;
    console.error(`${name}: README.md differs from ${file}`);
  }
  return `<!-- BEGIN ${name}: ${file} -->\n${fresh}<!-- END ${name} -->`;
});
if (check) process.exit(differ ? 1 : 0);
writeFileSync(readme, text);
console.error(`README.md: ${differ} block(s) updated`);

#!/usr/bin/env node
// Helpers of check.sh:
//
//   node report.mjs compare REF_DIR DUMP_DIR N   # frames 0..N-1, byte for byte; exit 1 if not
//   node report.mjs table LOG...                 # markdown table of run.mjs summaries
//
// `compare` prints, per frame, "identical" or the number of differing pixels and the first
// one (x, y, reference and emulated RGB565). `table` reads the JSON summary (the last line) of
// each run.mjs log and prints cycles per frame and milliseconds at 125 and 133 MHz, then the
// firmware's defmt lines.

import { existsSync, readFileSync } from 'node:fs';
import { basename, join } from 'node:path';

const WIDTH = 240;

function compare(refDir, dumpDir, count) {
  let failed = false;
  for (let n = 0; n < count; n++) {
    const name = `frame_${String(n).padStart(3, '0')}.rgb565`;
    const [a, b] = [join(refDir, name), join(dumpDir, name)];
    if (!existsSync(a) || !existsSync(b)) {
      console.log(`  ${name}: missing (${existsSync(a) ? b : a})`);
      failed = true;
      continue;
    }
    const ref = readFileSync(a);
    const emu = readFileSync(b);
    if (ref.length !== emu.length) {
      console.log(`  ${name}: ${emu.length} bytes, the reference has ${ref.length}`);
      failed = true;
      continue;
    }
    let differ = 0;
    let first = -1;
    for (let i = 0; i < ref.length; i += 2) {
      if (ref[i] !== emu[i] || ref[i + 1] !== emu[i + 1]) {
        if (first < 0) first = i / 2;
        differ++;
      }
    }
    if (!differ) {
      console.log(`  ${name}: identical to the host render`);
      continue;
    }
    failed = true;
    const hex = (buf, p) => `0x${buf.readUInt16BE(2 * p).toString(16).padStart(4, '0')}`;
    console.log(
      `  ${name}: ${differ} pixels differ; the first at (${first % WIDTH}, ${Math.floor(first / WIDTH)}): ` +
        `host ${hex(ref, first)}, emulator ${hex(emu, first)}`,
    );
  }
  return failed ? 1 : 0;
}

function summaryOf(log) {
  const lines = readFileSync(log, 'utf8').trim().split('\n');
  for (let i = lines.length - 1; i >= 0; i--) {
    if (lines[i].startsWith('{')) return JSON.parse(lines[i]);
  }
  throw new Error(`${log}: no JSON summary`);
}

function table(logs) {
  const ms = (cycles, mhz) => (cycles / (mhz * 1e3)).toFixed(1);
  const out = [];
  out.push('| firmware | cores | frame | cycles | ms at 125 MHz | ms at 133 MHz |');
  out.push('|---|---|---|---:|---:|---:|');
  const notes = [];
  for (const log of logs) {
    const s = summaryOf(log);
    const name = basename(s.elf);
    const cores = s.dual ? 2 : 1;
    out.push(`| ${name} | ${cores} | boot to first pixel sent | ${s.boot_cycles ?? '-'} | ${s.boot_cycles ? ms(s.boot_cycles, 125) : '-'} | ${s.boot_cycles ? ms(s.boot_cycles, 133) : '-'} |`);
    for (const f of s.frames) {
      const what = f.n === 0 ? '0 (from its first RAMWR)' : `${f.n} (from the end of frame ${f.n - 1})`;
      out.push(`| ${name} | ${cores} | ${what} | ${f.cycles} | ${ms(f.cycles, 125)} | ${ms(f.cycles, 133)} |`);
    }
    if (s.errors.length) notes.push(`${name}: ${s.errors.join('; ')}`);
    notes.push(`${name}: ${(s.cycles_per_cpu_second / 1e6).toFixed(1)} M emulated cycles per host CPU second`);
  }
  const first = summaryOf(logs[0]);
  out.push('');
  out.push(`Cycles: ${first.cycle_model}. SPI: ${first.spi_model}.`);
  out.push('A frame ends when its last pixel has been sent. Frame 0 counts from its first RAMWR, so it leaves out');
  out.push('the work done before band 0 is sent; frames n > 0 (the steady state) count from the end of frame n - 1.');
  out.push('"Boot" is reset to the first RAMWR. ms at 133 MHz scale the whole frame, SPI included.');
  out.push('');
  // The emulator's own speed varies from host to host: stderr, not the table.
  for (const n of notes) console.error(`- ${n}`);
  out.push(...stageTable(logs));
  out.push('');
  out.push('The firmware\'s defmt log (emulated cycle at which it was read):');
  out.push('');
  out.push('```text');
  for (const log of logs) {
    const s = summaryOf(log);
    for (const l of s.defmt) {
      out.push(`${basename(s.elf)} @${l.cycle} ${l.error ? `undecodable: ${l.raw}` : `${(l.level || '').toUpperCase()} ${l.text}`}`);
    }
  }
  out.push('```');
  console.log(out.join('\n'));
  return 0;
}

/**
 * The per-stage table: the stages of the last frame each run measured, from the firmware's own defmt
 * line (`frame N: T us (setup a, transform b, ...)`, timed with the RP2040's 1 MHz timer), in
 * microseconds and in cycles at 125 MHz.
 */
function stageTable(logs) {
  const rows = [];
  const names = [];
  for (const log of logs) {
    const s = summaryOf(log);
    const frames = s.defmt.filter((l) => /^frame \d+: \d+ us/.test(l.text ?? ''));
    // The last frame the run measured (a faster firmware may log one more before it stops).
    const measured = s.frames.length ? s.frames[s.frames.length - 1].n : null;
    const last = frames.filter((l) => Number(l.text.match(/^frame (\d+)/)[1]) === measured).pop() ?? frames[frames.length - 1];
    if (!last) continue;
    const [, n, total, inner] = last.text.match(/^frame (\d+): (\d+) us[^(]*\(([^)]*)\)/) ?? [];
    if (!inner) continue;
    const stages = new Map(
      inner.split(', ').map((part) => {
        const m = part.match(/^(.*) (\d+)$/);
        return m ? [m[1], Number(m[2])] : [part, NaN];
      }),
    );
    for (const k of stages.keys()) if (!names.includes(k)) names.push(k);
    rows.push({ name: basename(s.elf), n, total: Number(total), stages });
  }
  if (!rows.length) return [];
  const out = ['', 'Per stage, frame by frame (the firmware\'s own timing: `Demo::render_frame`, or core 0\'s', 'loop in the dual-core firmware), microseconds and cycles at 125 MHz:', ''];
  out.push(`| firmware | frame | ${names.join(' | ')} | total |`);
  out.push(`|---|---:|${names.map(() => '---:').join('|')}|---:|`);
  for (const r of rows) {
    const cell = (us) => (Number.isFinite(us) ? `${us} us (${(us * 125 / 1e6).toFixed(2)} M)` : '-');
    out.push(`| ${r.name} | ${r.n} | ${names.map((k) => cell(r.stages.get(k))).join(' | ')} | ${cell(r.total)} |`);
  }
  return out;
}

/**
 * The frames as CSV (for `host-sim budget --scene --check`): one row per frame the firmware
 * logged, its stages in cycles (the firmware's microseconds times 125), its counts, and the
 * emulator's whole-frame cycles.
 */
function csv(logs) {
  const out = ['firmware,cores,frame,cycles,setup,transform,shade,raster,flush,wait,shader_calls,pixels,triangle_setups'];
  for (const log of logs) {
    const s = summaryOf(log);
    const name = basename(s.elf);
    for (const l of s.defmt) {
      // `frame N: ...` (the demo firmwares) or `scene NAME frame N: ...` (scene_file: one
      // frame of each scene file, named `scene:NAME` here).
      const m = (l.text ?? '').match(/^(?:scene (\S+) )?frame (\d+): (\d+) us[^(]*\(([^)]*)\), (\d+) shader calls[^,]*, (\d+) pixels, (\d+) triangle setups/);
      if (!m) continue;
      const scene = m[1];
      const n = Number(m[2]);
      const stages = new Map(m[4].split(', ').map((part) => {
        const p = part.match(/^(.*) (\d+)$/);
        return p ? [p[1], Number(p[2]) * 125] : [part, 0];
      }));
      const frame = scene ? undefined : s.frames.find((f) => f.n === n);
      const get = (k) => stages.get(k) ?? 0;
      out.push([scene ? `scene:${scene}` : name, s.dual ? 2 : 1, n, frame ? frame.cycles : '', get('setup'), get('transform'), get('shade'),
        get('raster'), get('flush'), get('waiting for core 1'), m[5], m[6], m[7]].join(','));
    }
  }
  console.log(out.join('\n'));
  return 0;
}

/** The calibration's `cost` lines as CSV: item,count,setups,calls,cycles. */
function costs(log) {
  const s = summaryOf(log);
  const out = ['item,count,setups,calls,ticks'];
  for (const l of s.defmt) {
    const m = (l.text ?? '').match(/^cost (\S+) (\d+) (\d+) (\d+) (\d+)$/);
    if (m) out.push(m.slice(1).join(','));
  }
  if (out.length === 1) {
    console.error(`${log}: no cost lines`);
    return 1;
  }
  console.log(out.join('\n'));
  return 0;
}

const [cmd, ...args] = process.argv.slice(2);
if (cmd === 'csv' && args.length > 0) process.exit(csv(args));
if (cmd === 'costs' && args.length === 1) process.exit(costs(args[0]));
if (cmd === 'compare' && args.length === 3) process.exit(compare(args[0], args[1], Number(args[2])));
if (cmd === 'table' && args.length > 0) process.exit(table(args));
console.error('usage: node report.mjs compare REF_DIR DUMP_DIR N | table LOG... | csv LOG... | costs LOG');
process.exit(2);

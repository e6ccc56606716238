#!/usr/bin/env node
// Runs the rp2040-st7789 firmware (an ELF built with `--features emulator`) in rp2040js and
// measures it: the ST7789 frames it sends (rebuilt from the SPI bytes), the emulated cycles per
// frame, and its defmt log (from RTT). See README.md.
//
//   node run.mjs --elf PATH [--frames N] [--dual] [--dump-frames DIR] [--max-cycles C]
//                [--profile] [--profile-every K] [--profile-from C] [--profile-pcs FILE] [--until TEXT]
//                [--stack]
//
// --profile-from C samples only from core 0's cycle C on (e.g. the start of frame 1, from a
// first run's `end_cycle` of frame 0); --profile-pcs FILE also writes every sampled PC with
// its count (hex address, count), for a per-instruction look at a function inlined into another.
//
// --until TEXT runs until a defmt line contains TEXT (a firmware that sends no frames, e.g.
// `calibrate`), instead of until N frames.
//
// --stack paints core 0's stack (the RAM between the statics' end, `__euninit`, and
// `_stack_start`) with 0xA5 bytes before the reset and reports in the summary how much of it
// the run used (`stack_used`, bytes from the top down to the deepest byte written; the
// cortex-m-rt start-up touches only the statics), and the region's size (`stack_region`).
// With --dual also core 1's (`core1_stack_used`, `core1_stack_region`): the `CORE1_STACK`
// static below the stack pointer core 1 is launched with, painted at the launch.
//
// Exits non-zero on a fault (BKPT/UDF, e.g. panic-probe; unimplemented instruction; unmapped
// memory), a defmt error line, a malformed ST7789 stream, or the cycle budget running out
// before N frames. The last line of the output is a JSON summary.

import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseArgs } from 'node:util';
import { DefmtDecoder, DefmtStream, RttReader, defmtTable } from './defmt.mjs';
import { parseElf } from './elf.mjs';
import { Machine } from './machine.mjs';
import { rgb565ToPng } from './png.mjs';
import { Profile } from './profile.mjs';
import { St7789 } from './st7789.mjs';
import { CORE_HZ, NS_PER_CYCLE } from './clock.mjs';

const WIDTH = 240;
const HEIGHT = 240;
const DC_PIN = 8;
const CS_PIN = 9;
/** RTT is drained (and the budget checked) every this many cycles. */
const CHUNK = 100_000;
/** After the last frame, run at most this long for its defmt line. */
const TAIL = 10_000_000;

const { values: opts } = parseArgs({
  options: {
    elf: { type: 'string' },
    frames: { type: 'string', default: '1' },
    dual: { type: 'boolean', default: false },
    'dump-frames': { type: 'string' },
    'max-cycles': { type: 'string' },
    profile: { type: 'boolean', default: false },
    'profile-every': { type: 'string', default: '997' },
    'profile-from': { type: 'string', default: '0' },
    'profile-pcs': { type: 'string' },
    quiet: { type: 'boolean', default: false },
    until: { type: 'string' },
    stack: { type: 'boolean', default: false },
  },
});
if (!opts.elf) {
  console.error('usage: node run.mjs --elf PATH [--frames N] [--dual] [--dump-frames DIR] [--max-cycles C] [--profile]');
  process.exit(2);
}
const wanted = Number(opts.frames);
const maxCycles = opts['max-cycles'] ? Number(opts['max-cycles']) : 100_000_000 + wanted * 600_000_000;
const log = (line) => opts.quiet || console.log(line);

const elf = parseElf(readFileSync(opts.elf));
const machine = new Machine(elf, { cores: opts.dual ? 2 : 1 });
const RAM_BASE = 0x20000000;
const PAINT = 0xa5;
const stackRegion = (() => {
  if (!opts.stack) return null;
  const lo = elf.symbol('__euninit');
  const hi = elf.symbol('_stack_start');
  if (!lo || !hi) {
    console.error('--stack: the ELF has no __euninit or _stack_start symbol');
    process.exit(2);
  }
  machine.rp2040.sram.fill(PAINT, lo.value - RAM_BASE, hi.value - RAM_BASE);
  return { lo: lo.value, hi: hi.value };
})();
// With --dual, core 1's stack too: the firmware's `CORE1_STACK` static (zeroed at start-up)
// below the stack pointer core 1 is launched with, painted at the launch.
const core1Stack = (() => {
  if (!opts.stack || !opts.dual) return null;
  const sym = elf.symbols.find((s) => s.name.includes('CORE1_STACK') && s.size > 0);
  if (!sym) return null;
  const region = { lo: sym.value, hi: null };
  machine.multicore.onLaunch = (sp) => {
    if (sp > sym.value && sp <= sym.value + sym.size) {
      machine.rp2040.sram.fill(PAINT, sym.value - RAM_BASE, sp - RAM_BASE);
      region.hi = sp;
    }
  };
  return region;
})();
const { rp2040, clock } = machine;
const errors = [];

// --- The display: SPI1 bytes with DC and CS, each taking 8 SPI clocks. ---
const frames = [];
let firstRamwr = null;
let initEnd = null;
const spiRates = new Set();
const display = new St7789({
  width: WIDTH,
  height: HEIGHT,
  onFrame({ pixels, written }) {
    const n = frames.length;
    const end = machine.now;
    const prev = n === 0 ? firstRamwr : frames[n - 1].end_cycle;
    frames.push({ n, cycles: end - prev, end_cycle: end, pixels });
    if (written !== WIDTH * HEIGHT) {
      errors.push(`frame ${n}: ${written} of ${WIDTH * HEIGHT} pixels written since the previous frame`);
    }
    log(`[frame] ${n} complete at cycle ${end} (${end - prev} cycles${n === 0 ? ' since the first RAMWR' : ''})`);
    if (opts['dump-frames']) {
      const base = join(opts['dump-frames'], `frame_${String(n).padStart(3, '0')}`);
      writeFileSync(`${base}.rgb565`, pixels);
      writeFileSync(`${base}.png`, rgb565ToPng(pixels, WIDTH, HEIGHT));
    }
  },
});
if (opts['dump-frames']) mkdirSync(opts['dump-frames'], { recursive: true });

const spi = rp2040.spi[1];
let inflight = null;
const spiDone = clock.createAlarm(() => {
  const { value, bits, dc, cs } = inflight;
  inflight = null;
  // A frame of more than 8 bits (16-bit pixels) goes out most significant byte first: the
  // display sees its bytes in that order.
  const bytes = bits > 8 ? [(value >> 8) & 0xff, value & 0xff] : [value & 0xff];
  for (const byte of bytes) {
    const isCommand = !dc && !cs;
    if (isCommand && byte === 0x2c && firstRamwr === null) firstRamwr = machine.now;
    if (isCommand && byte !== 0x00 && byte !== 0x2a && byte !== 0x2b && byte !== 0x2c && firstRamwr === null) initEnd = machine.now;
    display.byte(byte, dc, cs);
  }
  spi.completeTransmit(0);
});
spi.onTransmit = (value) => {
  const gpio = rp2040.sio.gpioValue;
  const bits = spi.dataBits;
  inflight = { value, bits, dc: (gpio >> DC_PIN) & 1, cs: (gpio >> CS_PIN) & 1 };
  const hz = spi.clockFrequency;
  spiRates.add(`${bits}/${hz}`);
  spiDone.schedule(hz > 0 ? (bits * 1e9) / hz : 0);
};
const spiModel = () =>
  [...spiRates]
    .map((k) => {
      const [bits, hz] = k.split('/').map(Number);
      return `${bits} SPI clocks per ${bits}-bit frame at ${hz / 1e6} MHz (${(bits * CORE_HZ) / hz} core cycles/frame)`;
    })
    .join('; ') || 'no SPI bytes';

// --- The defmt log. ---
const rttSymbol = elf.symbol('_SEGGER_RTT');
const rtt = rttSymbol ? new RttReader(rp2040, rttSymbol.value) : null;
const defmt = new DefmtStream(new DefmtDecoder(defmtTable(elf)));
const defmtLines = [];
function drainLog() {
  if (!rtt) return 0;
  const lines = defmt.push(rtt.drain());
  for (const l of lines) {
    const at = machine.cycles;
    if (l.error) {
      log(`[defmt] @${at} (undecodable: ${l.error}) ${l.raw}`);
      defmtLines.push({ cycle: at, raw: l.raw, error: l.error });
      continue;
    }
    const level = l.level ? `${l.level.toUpperCase()} ` : '';
    log(`[defmt] @${at} ${level}${l.text}`);
    defmtLines.push({ cycle: at, level: l.level, text: l.text });
    if (l.level === 'error') errors.push(`defmt error: ${l.text}`);
    if (opts.until && (l.text ?? '').includes(opts.until)) untilSeen = true;
  }
  return lines.length;
}

// --- Run. ---
const profile = opts.profile ? new Profile(elf) : null;
const every = Number(opts['profile-every']);
const profileFrom = Number(opts['profile-from']);
const sampler = profile ? (pc) => machine.cycles >= profileFrom && profile.sample(pc) : null;
const started = process.hrtime.bigint();
const cpuStarted = process.cpuUsage();
let tailEnd = null;
let untilSeen = false;
while (!errors.length && !display.errors.length) {
  const end = Math.min(machine.cycles + CHUNK, maxCycles, tailEnd ?? Infinity);
  const ok = machine.runTo(end, sampler, every);
  const newLines = drainLog();
  if (!ok) break;
  if (untilSeen) break;
  if (!opts.until && frames.length >= wanted) {
    // The firmware logs a frame's time after sending it: wait a little for that line.
    if (tailEnd === null) tailEnd = machine.cycles + TAIL;
    else if (newLines || machine.cycles >= tailEnd) break;
  }
  if (machine.cycles >= maxCycles) {
    if (opts.until) errors.push(`cycle budget (${maxCycles}) ran out before a defmt line with ${JSON.stringify(opts.until)}`);
    else if (frames.length < wanted) errors.push(`cycle budget (${maxCycles}) ran out after ${frames.length} of ${wanted} frames`);
    break;
  }
}
drainLog();
const seconds = Number(process.hrtime.bigint() - started) / 1e9;
const cpu = process.cpuUsage(cpuStarted);
const cpuSeconds = (cpu.user + cpu.system) / 1e6;

for (const f of machine.faults) errors.push(`fault: ${f}`);
for (const e of display.errors) errors.push(`ST7789: ${e}`);
const cores = machine.multicore;
if (opts.dual && cores.launches === 0) errors.push('core 1 was never launched');

log(`[display] commands: ${display.summary()}; window origin ${JSON.stringify(display.origin)}`);
log(`[spi] ${spiModel()}`);
log(
  `[emulator] ${machine.cycles} cycles of core 0 in ${seconds.toFixed(1)} s (${cpuSeconds.toFixed(1)} s CPU): ` +
    `${(machine.cycles / cpuSeconds / 1e6).toFixed(1)} M cycles per CPU second`,
);
if (profile) profile.print((l) => console.log(l));
if (profile && opts['profile-pcs']) writeFileSync(opts['profile-pcs'], profile.pcLines());
for (const e of errors) console.error(`error: ${e}`);

const summary = {
  elf: opts.elf,
  dual: opts.dual,
  frames: frames.map(({ n, cycles, end_cycle }) => ({
    n,
    cycles,
    end_cycle,
    ms_at_125mhz: +((cycles * NS_PER_CYCLE) / 1e6).toFixed(3),
  })),
  boot_cycles: firstRamwr,
  display_init_end_cycle: initEnd,
  frame0_since_reset: frames.length ? frames[0].end_cycle : null,
  spi_model: spiModel(),
  cycle_model: 'rp2040js 1.4.1 instruction timings; flash (XIP) reads cost like SRAM, no cache misses',
  core1_launches: cores.launches,
  total_cycles: machine.cycles,
  host_seconds: +seconds.toFixed(2),
  cpu_seconds: +cpuSeconds.toFixed(2),
  cycles_per_cpu_second: Math.round(machine.cycles / cpuSeconds),
  defmt: defmtLines,
  errors,
};
// A painted stack [lo, hi): its size and the bytes from the top down to the deepest one written.
const stackUse = ({ lo, hi }) => {
  const ram = machine.rp2040.sram;
  let deepest = lo;
  while (deepest < hi && ram[deepest - RAM_BASE] === PAINT) deepest += 1;
  return [hi - lo, hi - deepest];
};
if (stackRegion) {
  [summary.stack_region, summary.stack_used] = stackUse(stackRegion);
}
if (core1Stack && core1Stack.hi !== null) {
  [summary.core1_stack_region, summary.core1_stack_used] = stackUse(core1Stack);
}
console.log(JSON.stringify(summary));
process.exit(errors.length ? 1 : 0);

// The emulated Raspberry Pi Pico: rp2040js's RP2040 with what this firmware needs on top.
//
// - No boot ROM or second-stage bootloader runs: the ELF's PT_LOAD segments are copied to
//   flash/RAM at their physical addresses, and core 0 starts at the vector table at 0x10000100
//   (SP from word 0, PC from word 1, VTOR set), as boot2 would leave it. cortex-m-rt copies
//   .data from flash and zeroes .bss itself.
// - The boot ROM is a fake: its header ('M' 'u', version 1, at 0x10) points to empty function
//   and data tables and a working `table_lookup` (the ROM's own 10 instructions), so a HAL that
//   looks up a ROM function gets 0; every other ROM word is BKPT, so calling into the ROM stops
//   the run with a fault instead of running zeros. (Built with rp2040-hal's
//   `disable-intrinsics`, the firmware never calls the ROM's float and integer routines.)
// - VREG_AND_CHIP_RESET (0x40064000), unimplemented in rp2040js (reads all ones), reads 0.
// - Faults: rp2040js has no HardFault. A BKPT or UDF (panic-probe ends in one), an
//   unimplemented instruction, an access to unmapped memory, or an rp2040js error stops the run.
// - Time: see clock.mjs; the cores: see multicore.mjs.

import { BasePeripheral, RP2040 } from 'rp2040js';
import { CycleClock } from './clock.mjs';
import { Multicore } from './multicore.mjs';

const VECTOR_TABLE = 0x10000100;
const FLASH_START = 0x10000000;
const RAM_START = 0x20000000;
const ROM_WORDS = 4096;
const ROM_LOOKUP = 0x100; // table_lookup code
const ROM_FUNC_TABLE = 0x120; // an empty table: one 0 halfword
const ROM_DATA_TABLE = 0x124;
// The RP2040 ROM's `table_lookup` (bootrom_rt0.S), Thumb: movs r3,#0; ldrh r2,[r0]; cmp r2,r3;
// beq 1f; ldrh r3,[r0,#2]; adds r0,#4; cmp r1,r2; bne table_lookup; 1: movs r0,r3; bx lr.
const TABLE_LOOKUP_CODE = [0x2300, 0x8802, 0x429a, 0xd003, 0x8843, 0x3004, 0x4291, 0xd1f7, 0x0018, 0x4770];
/** Cycles per lockstep slice of the two cores. */
const SLICE = 32;

/** VREG_AND_CHIP_RESET: every register reads 0, writes are ignored. */
class ZeroPeripheral extends BasePeripheral {
  readUint32() {
    return 0;
  }
  writeUint32() {}
}

function fakeBootrom() {
  const rom = new Uint32Array(ROM_WORDS).fill(0xbe00be00); // BKPT #0 everywhere
  const view = new DataView(rom.buffer);
  view.setUint32(0x10, 0x01017525, true); // 'M', 'u', compatibility 1, version 1
  view.setUint16(0x14, ROM_FUNC_TABLE, true);
  view.setUint16(0x16, ROM_DATA_TABLE, true);
  view.setUint16(0x18, ROM_LOOKUP + 1, true);
  TABLE_LOOKUP_CODE.forEach((op, i) => view.setUint16(ROM_LOOKUP + 2 * i, op, true));
  view.setUint32(ROM_FUNC_TABLE, 0, true);
  view.setUint32(ROM_DATA_TABLE, 0, true);
  return rom;
}

/** rp2040js's logger, made quiet; its warnings about bad accesses are faults. */
class Logger {
  constructor(machine) {
    this.machine = machine;
    this.seen = new Set();
  }
  debug() {}
  info(component, message) {
    if (message === 'SEV') this.machine.multicore.sev();
  }
  warn(component, message) {
    if (/not implemented yet|invalid memory address|undefined address/i.test(message)) {
      this.machine.fault(`${component}: ${message}`);
    } else if (!this.seen.has(message) && this.seen.size < 50) {
      this.seen.add(message);
      this.machine.warn(`[rp2040js] ${component}: ${message}`);
    }
  }
  error(component, message) {
    this.machine.fault(`${component}: ${message}`);
  }
}

export class Machine {
  /** `elf`: a parsed ELF (elf.mjs); `cores`: 1 or 2. */
  constructor(elf, { cores = 1, warn = (m) => console.error(m) } = {}) {
    this.warn = warn;
    this.faults = [];
    this.limit = 0; // the run loop's cycle limit (0 stops it at once)
    this.clock = new CycleClock();
    const rp2040 = new RP2040(this.clock);
    this.rp2040 = rp2040;
    rp2040.logger = new Logger(this);
    rp2040.loadBootrom(fakeBootrom()); // (resets the core and erases the flash)
    rp2040.peripherals[0x40064] = new ZeroPeripheral(rp2040, 'VREG_AND_CHIP_RESET_BASE');
    rp2040.onBreak = (code) => {
      const pc = (rp2040.core.PC - 2) >>> 0;
      const where = pc < ROM_WORDS * 4 ? ' (a call into the boot ROM, which is not emulated)' : '';
      this.fault(`core ${this.multicore.current}: BKPT/UDF #${code} at 0x${pc.toString(16)}${where}`);
    };
    this.multicore = new Multicore(rp2040, cores, (m) => this.fault(m));
    this.clock.now = () => rp2040.core.cycles;
    this.load(elf);
  }

  fault(message) {
    if (this.faults.length < 10) this.faults.push(message);
    this.limit = 0;
  }

  load(elf) {
    const { rp2040 } = this;
    for (const seg of elf.segments) {
      if (seg.filesz === 0) continue;
      const data = elf.segmentData(seg);
      if (seg.paddr >= FLASH_START && seg.paddr + data.length <= FLASH_START + rp2040.flash.length) {
        rp2040.flash.set(data, seg.paddr - FLASH_START);
      } else if (seg.paddr >= RAM_START && seg.paddr + data.length <= RAM_START + rp2040.sram.length) {
        rp2040.sram.set(data, seg.paddr - RAM_START);
      } else {
        throw new Error(`PT_LOAD segment at 0x${seg.paddr.toString(16)} is neither in flash nor in RAM`);
      }
    }
    const core = this.multicore.cores[0];
    core.VTOR = VECTOR_TABLE;
    core.SP = rp2040.readUint32(VECTOR_TABLE);
    core.PC = rp2040.readUint32(VECTOR_TABLE + 4) & ~1;
    core.cycles = 0;
  }

  /** Core 0's cycle counter: the wall time. */
  get cycles() {
    return this.multicore.cores[0].cycles;
  }

  /** The time as the peripherals see it (an alarm's due cycle while it fires). */
  get now() {
    return this.clock.cycles();
  }

  /** Runs until core 0's cycle counter reaches `end` or a fault. `sample(pc)`, if given, is
   * called every `every` cycles of core 0 with its PC. Returns false after a fault.
   *
   * One core: it runs to `end` (or the next sample). Two cores: in lockstep slices of SLICE
   * cycles, core 0 then core 1, each running until its counter reaches the slice's end (a core
   * asleep in WFE/WFI, or core 1 in the ROM's holding pen, just moves to it). */
  runTo(end, sample = null, every = 0) {
    const { multicore } = this;
    const cores = multicore.cores;
    const dual = cores.length > 1;
    let nextSample = sample ? Math.ceil((cores[0].cycles + 1) / every) * every : Infinity;
    while (cores[0].cycles < end && !this.faults.length) {
      let sliceEnd = Math.min(end, nextSample);
      if (dual) sliceEnd = Math.min(sliceEnd, cores[0].cycles + SLICE);
      if (cores[0].waiting) this.checkDeadlock();
      this.runCore(0, sliceEnd);
      if (dual) {
        this.runCore(1, sliceEnd);
        multicore.select(0);
      }
      if (cores[0].cycles >= nextSample) {
        sample(cores[0].PC);
        nextSample += every;
      }
    }
    return this.faults.length === 0;
  }

  /** Runs core `k` until its cycle counter reaches `sliceEnd` (or a fault). */
  runCore(k, sliceEnd) {
    const { multicore, clock } = this;
    const core = multicore.cores[k];
    multicore.select(k);
    if (multicore.inRom[k]) {
      multicore.romStep();
      if (core.cycles < sliceEnd) core.cycles = sliceEnd;
      return;
    }
    this.limit = sliceEnd;
    while (core.cycles < this.limit) {
      if (core.waiting) {
        // WFE/WFI: the core sleeps to the end of the slice (or to the next alarm).
        core.cycles = Math.min(this.limit, Math.max(core.cycles, clock.dueCycles));
      } else {
        while (core.cycles < this.limit && core.cycles < clock.dueCycles && !core.waiting) {
          core.executeInstruction();
        }
      }
      if (core.cycles >= clock.dueCycles) clock.fire(core.cycles);
    }
  }

  /** With every core asleep and nothing scheduled, nothing can ever happen: a fault. */
  checkDeadlock() {
    const { cores, inRom } = this.multicore;
    const asleep = cores.every((c, k) => c.waiting && !inRom[k]);
    if (asleep && this.clock.alarms.length === 0) {
      this.fault('deadlock: every core waits (WFE/WFI) and no event or alarm is pending');
    }
  }
}

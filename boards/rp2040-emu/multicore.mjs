// The second Cortex-M0+ of the RP2040, which rp2040js 1.4.1 does not emulate (its SIO CPUID
// reads 0, it has no inter-core FIFOs, and `RP2040` owns a single `core`).
//
// Both cores are `CortexM0Core`s of the same `RP2040` (memory, peripherals and spinlocks are
// shared). Whichever core is being stepped is made `rp2040.core`, so that everything rp2040js
// routes through `rp2040.core` (the PPB: VTOR, NVIC, the divider's cycle cost) is that core's.
// On top of that, per core: the SIO CPUID, the SIO hardware divider's state (loaded into
// rp2040js's divider for each access), the two 8-deep SIO FIFOs (FIFO_ST, FIFO_WR, FIFO_RD; no FIFO IRQ), the MPU
// registers (rp2040-hal's core-1 start-up checks MPU_CTRL and installs a stack guard; they are
// stored, not enforced), and SEV, which sets the event flag of both cores (rp2040js only logs it).
//
// Core 1 starts in the boot ROM's holding pen (`wait_for_vector` in the RP2040 boot ROM),
// emulated here as a state machine over the FIFOs rather than run as ROM code: drain the FIFO,
// send 0, wait for a word; 0 restarts, 1 is echoed, then the vector table, the stack pointer and
// the entry point are each echoed, and core 1 jumps to the entry with VTOR and MSP set. Any
// other word restarts the handshake, as in the ROM. Resetting core 1 through PSM FRCE_OFF
// (as `multicore::Core::spawn` does) puts it back in the holding pen.

const SIO_CPUID = 0x000;
const SIO_FIFO_ST = 0x050;
const SIO_FIFO_WR = 0x054;
const SIO_FIFO_RD = 0x058;
const FIFO_VLD = 1;
const FIFO_RDY = 2;
const FIFO_WOF = 4;
const FIFO_ROE = 8;
const FIFO_DEPTH = 8;
const PSM_FRCE_OFF = 0x04;
const PSM_PROC1 = 1 << 16;
// MPU: TYPE, CTRL, RNR, RBAR, RASR.
const MPU_TYPE = 0xd90;
const MPU_LAST = 0xda0;
const MPU_TYPE_VALUE = 0x800; // 8 regions, unified
// The hardware divider's registers (DIV_UDIVIDEND .. DIV_CSR) and rp2040js's state for them.
const DIV_FIRST = 0x060;
const DIV_LAST = 0x078;
const DIVIDER_FIELDS = ['divDividend', 'divDivisor', 'divQuotient', 'divRemainder', 'divCSR'];

export class Multicore {
  /** `count`: 1 or 2 cores. `onFault(msg)` stops the run. */
  constructor(rp2040, count, onFault) {
    this.rp2040 = rp2040;
    this.onFault = onFault;
    const Core = rp2040.core.constructor;
    this.cores = [rp2040.core];
    if (count > 1) this.cores.push(new Core(rp2040));
    this.current = 0;
    // FIFO k is read by core k and written by the other core.
    this.fifos = this.cores.map(() => []);
    this.fifoStatus = this.cores.map(() => 0); // sticky WOF/ROE bits
    this.dividers = this.cores.map(() => ({ divDividend: 0, divDivisor: 1, divQuotient: 0, divRemainder: 0, divCSR: 0 }));
    this.mpu = this.cores.map(() => new Uint32Array(5));
    this.inRom = this.cores.map((_, k) => k > 0); // core 1 waits in the boot ROM
    this.rom = { stage: 'handshake', pending: null, vtor: 0, sp: 0 };
    this.launches = 0;
    this.hookSio();
    this.hookPpb();
    this.hookPsm();
    // Interrupts from peripherals go to core 0 (the firmware enables none on core 1).
    rp2040.setInterrupt = (irq, value) => this.cores[0].setInterrupt(irq, value);
  }

  /** Makes core `k` the one rp2040js sees as `rp2040.core`. */
  select(k) {
    this.current = k;
    this.rp2040.core = this.cores[k];
  }

  /** Runs an access to rp2040js's divider with the current core's divider state in it. */
  withDivider(access) {
    const sio = this.rp2040.sio;
    const state = this.dividers[this.current];
    for (const f of DIVIDER_FIELDS) sio[f] = state[f];
    const result = access();
    for (const f of DIVIDER_FIELDS) state[f] = sio[f];
    return result;
  }

  /** SEV: the event flag of every core is set; a core waiting in WFE wakes (and consumes it). */
  sev() {
    for (const core of this.cores) {
      if (core.waiting) core.waiting = false;
      else core.eventRegistered = true;
    }
  }

  hookSio() {
    const sio = this.rp2040.sio;
    const read = sio.readUint32.bind(sio);
    const write = sio.writeUint32.bind(sio);
    sio.readUint32 = (offset) => {
      if (offset >= DIV_FIRST && offset <= DIV_LAST) return this.withDivider(() => read(offset));
      switch (offset) {
        case SIO_CPUID:
          return this.current;
        case SIO_FIFO_ST:
          return this.fifoSt(this.current);
        case SIO_FIFO_RD:
          return this.fifoRead(this.current);
        default:
          return read(offset);
      }
    };
    sio.writeUint32 = (offset, value) => {
      if (offset >= DIV_FIRST && offset <= DIV_LAST) return this.withDivider(() => write(offset, value));
      switch (offset) {
        case SIO_FIFO_ST:
          this.fifoStatus[this.current] &= ~(value & (FIFO_WOF | FIFO_ROE));
          return;
        case SIO_FIFO_WR:
          this.fifoWrite(this.current, value >>> 0);
          return;
        default:
          write(offset, value);
      }
    };
  }

  fifoSt(k) {
    const rx = this.fifos[k];
    const tx = this.fifos[1 - k];
    return (rx.length ? FIFO_VLD : 0) | (tx && tx.length < FIFO_DEPTH ? FIFO_RDY : 0) | this.fifoStatus[k];
  }

  fifoRead(k) {
    const rx = this.fifos[k];
    if (!rx.length) {
      this.fifoStatus[k] |= FIFO_ROE;
      return 0;
    }
    return rx.shift();
  }

  /** Core `k` writes to the other core's FIFO (lost, with WOF set, when full or absent). */
  fifoWrite(k, value) {
    const tx = this.fifos[1 - k];
    if (!tx) {
      this.onFault('core 0 wrote to the inter-core FIFO, so this firmware starts core 1: run it with --dual');
      return;
    }
    if (tx.length >= FIFO_DEPTH) {
      this.fifoStatus[k] |= FIFO_WOF;
      return;
    }
    tx.push(value);
  }

  hookPpb() {
    const ppb = this.rp2040.ppb;
    const read = ppb.readUint32.bind(ppb);
    const write = ppb.writeUint32.bind(ppb);
    ppb.readUint32 = (offset) => {
      if (offset === MPU_TYPE) return MPU_TYPE_VALUE;
      if (offset > MPU_TYPE && offset <= MPU_LAST) return this.mpu[this.current][(offset - MPU_TYPE) / 4];
      return read(offset);
    };
    ppb.writeUint32 = (offset, value) => {
      if (offset > MPU_TYPE && offset <= MPU_LAST) this.mpu[this.current][(offset - MPU_TYPE) / 4] = value;
      else if (offset !== MPU_TYPE) write(offset, value);
    };
  }

  hookPsm() {
    const psm = this.rp2040.findPeripheral(0x40010000);
    const write = psm.writeUint32.bind(psm);
    psm.writeUint32 = (offset, value) => {
      const wasOff = offset === PSM_FRCE_OFF && psm.frceOff & PSM_PROC1;
      write(offset, value);
      // Releasing core 1 from a forced power-off restarts it in the boot ROM.
      if (wasOff && !(psm.frceOff & PSM_PROC1) && this.cores.length > 1) this.resetCore1();
    };
  }

  resetCore1() {
    const core = this.cores[1];
    core.registers.fill(0);
    core.waiting = false;
    core.eventRegistered = false;
    core.VTOR = 0;
    this.mpu[1].fill(0);
    this.fifos[1].length = 0;
    this.fifoStatus[1] = 0;
    this.inRom[1] = true;
    this.rom = { stage: 'handshake', pending: null, vtor: 0, sp: 0 };
  }

  /** One look at the FIFOs by core 1's boot ROM holding pen (`wait_for_vector`). */
  romStep() {
    const rom = this.rom;
    const rx = this.fifos[1];
    const tx = this.fifos[0];
    // A word waiting to be sent (the ROM waits for FIFO space with WFE).
    if (rom.pending !== null) {
      if (tx.length >= FIFO_DEPTH) return;
      tx.push(rom.pending);
      rom.pending = null;
      this.sev();
      if (rom.stage === 'launch') this.launchCore1(rom.entry);
      return;
    }
    if (rom.stage === 'handshake') {
      rx.length = 0; // drain, then send 0
      rom.stage = 0;
      rom.pending = 0;
      return this.romStep();
    }
    if (!rx.length) return;
    const word = rx.shift();
    if (word === 0) {
      rom.stage = 'handshake';
      return this.romStep();
    }
    switch (rom.stage) {
      case 0:
        if (word !== 1) {
          rom.stage = 'handshake';
          return this.romStep();
        }
        rom.stage = 1;
        break;
      case 1:
        rom.vtor = word;
        rom.stage = 2;
        break;
      case 2:
        rom.sp = word;
        rom.stage = 3;
        break;
      case 3:
        rom.entry = word;
        rom.stage = 'launch';
        break;
    }
    rom.pending = word; // the echo
    return this.romStep();
  }

  launchCore1(entry) {
    const core = this.cores[1];
    const { vtor, sp } = this.rom;
    core.VTOR = vtor >>> 0;
    core.SP = sp;
    core.PC = entry & ~1;
    core.LR = 0xfffffffe; // returning from the entry point would fault (the ROM would sleep)
    this.inRom[1] = false;
    this.launches++;
    if (this.onLaunch) this.onLaunch(sp >>> 0);
  }
}

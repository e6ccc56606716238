// The emulator's time base: core cycles at 125 MHz (the firmware's clk_sys), 8 ns each.
//
// rp2040js's own SimulationClock is advanced by its Simulator after each instruction; here the
// time is the cycle counter of the core being stepped (`now`), so nothing needs ticking, and
// the run loop only compares the cycle count with `dueCycles` (the earliest alarm) to know when
// to call `fire`. The peripherals (timer, SPI completions) see `nanos` and `createAlarm`, the
// IClock interface of rp2040js.

export const CORE_HZ = 125_000_000;
export const NS_PER_CYCLE = 1e9 / CORE_HZ;

class CycleAlarm {
  constructor(clock, callback) {
    this.clock = clock;
    this.callback = callback;
    this.due = 0;
    this.scheduled = false;
  }

  schedule(deltaNanos) {
    this.clock.unlink(this);
    this.due = this.clock.cycles() + Math.max(0, Math.ceil(deltaNanos / NS_PER_CYCLE - 1e-9));
    this.clock.link(this);
  }

  cancel() {
    this.clock.unlink(this);
  }
}

export class CycleClock {
  constructor() {
    /** The current core's cycle counter; set by the machine. */
    this.now = () => 0;
    this.alarms = []; // scheduled alarms, earliest first
    this.dueCycles = Infinity;
    this.firing = -1; // while an alarm's callback runs: its due cycle (the time it sees)
  }

  cycles() {
    return this.firing >= 0 ? this.firing : this.now();
  }

  get nanos() {
    return this.cycles() * NS_PER_CYCLE;
  }

  createAlarm(callback) {
    return new CycleAlarm(this, callback);
  }

  link(alarm) {
    let i = this.alarms.length;
    while (i > 0 && this.alarms[i - 1].due > alarm.due) i--;
    this.alarms.splice(i, 0, alarm);
    alarm.scheduled = true;
    this.dueCycles = this.alarms[0].due;
  }

  unlink(alarm) {
    if (!alarm.scheduled) return;
    const i = this.alarms.indexOf(alarm);
    if (i >= 0) this.alarms.splice(i, 1);
    alarm.scheduled = false;
    this.dueCycles = this.alarms.length ? this.alarms[0].due : Infinity;
  }

  /** Runs the callbacks of every alarm due at or before `cycles`, in order, each at its time. */
  fire(cycles) {
    while (this.alarms.length && this.alarms[0].due <= cycles) {
      const alarm = this.alarms.shift();
      alarm.scheduled = false;
      this.dueCycles = this.alarms.length ? this.alarms[0].due : Infinity;
      this.firing = alarm.due;
      try {
        alarm.callback();
      } finally {
        this.firing = -1;
      }
    }
  }
}

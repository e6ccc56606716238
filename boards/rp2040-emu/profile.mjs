// A PC-sampling profile of core 0: every K cycles its PC is attributed to the ELF function
// symbol (STT_FUNC, with its size) that contains it. With fat LTO much is inlined, so a
// function's share includes what was inlined into it.

export class Profile {
  constructor(elf) {
    this.functions = elf.functions();
    this.starts = this.functions.map((f) => f.start);
    this.counts = new Map();
    this.pcs = new Map();
    this.total = 0;
  }

  /** The function containing `pc`, or null. Binary search over the sorted start addresses. */
  lookup(pc) {
    let lo = 0;
    let hi = this.starts.length - 1;
    let found = -1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (this.starts[mid] <= pc) {
        found = mid;
        lo = mid + 1;
      } else {
        hi = mid - 1;
      }
    }
    const f = found >= 0 ? this.functions[found] : null;
    return f && pc < f.end ? f : null;
  }

  sample(pc) {
    this.pcs.set(pc, (this.pcs.get(pc) ?? 0) + 1);
    const name = this.lookup(pc)?.name ?? `?? 0x${pc.toString(16)}`;
    this.counts.set(name, (this.counts.get(name) ?? 0) + 1);
    this.total++;
  }

  /** Every sampled PC and its count, one `hex count` line each, by address. */
  pcLines() {
    return [...this.pcs]
      .sort((a, b) => a[0] - b[0])
      .map(([pc, n]) => `${pc.toString(16)} ${n}\n`)
      .join('');
  }

  /** The top `n` functions by share of the samples. */
  print(out, n = 30) {
    out(`[profile] ${this.total} samples of core 0's PC; top ${n} functions:`);
    const rows = [...this.counts].sort((a, b) => b[1] - a[1]).slice(0, n);
    for (const [name, count] of rows) {
      const share = ((100 * count) / this.total).toFixed(2).padStart(6);
      out(`[profile] ${share}%  ${count.toString().padStart(9)}  ${name}`);
    }
  }
}

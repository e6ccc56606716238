// A minimal reader for 32-bit little-endian ELF files (what the Rust toolchain links for
// thumbv6m-none-eabi): section headers, PT_LOAD program headers and the .symtab symbols.
// Only what the emulator needs; it rejects anything else with a clear error.

const PT_LOAD = 1;
const SHT_SYMTAB = 2;
const STT_FUNC = 2;

/** Parses `buf` (a Buffer with a whole ELF file). */
export function parseElf(buf) {
  if (buf.readUInt32BE(0) !== 0x7f454c46) throw new Error('not an ELF file');
  if (buf[4] !== 1 || buf[5] !== 1) throw new Error('not a 32-bit little-endian ELF file');
  const u16 = (o) => buf.readUInt16LE(o);
  const u32 = (o) => buf.readUInt32LE(o);
  const phoff = u32(0x1c);
  const shoff = u32(0x20);
  const phentsize = u16(0x2a);
  const phnum = u16(0x2c);
  const shentsize = u16(0x2e);
  const shnum = u16(0x30);
  const shstrndx = u16(0x32);

  // NUL-terminated string at `offset` of the string table section at file offset `base`.
  const cstr = (base, offset) => {
    const start = base + offset;
    const end = buf.indexOf(0, start);
    return buf.toString('utf8', start, end < 0 ? buf.length : end);
  };

  const segments = [];
  for (let i = 0; i < phnum; i++) {
    const o = phoff + i * phentsize;
    if (u32(o) !== PT_LOAD) continue;
    segments.push({
      offset: u32(o + 4),
      vaddr: u32(o + 8),
      paddr: u32(o + 12),
      filesz: u32(o + 16),
      memsz: u32(o + 20),
      flags: u32(o + 24),
    });
  }

  const rawSections = [];
  for (let i = 0; i < shnum; i++) {
    const o = shoff + i * shentsize;
    rawSections.push({
      nameOffset: u32(o),
      type: u32(o + 4),
      addr: u32(o + 12),
      offset: u32(o + 16),
      size: u32(o + 20),
      link: u32(o + 24),
      entsize: u32(o + 36),
    });
  }
  const shstr = rawSections[shstrndx];
  const sections = rawSections.map((s, index) => ({
    ...s,
    index,
    name: shstr ? cstr(shstr.offset, s.nameOffset) : '',
  }));

  // Symbols: name, value, size, type (STT_*), section index.
  const symbols = [];
  for (const s of sections) {
    if (s.type !== SHT_SYMTAB) continue;
    const strtab = sections[s.link];
    const entsize = s.entsize || 16;
    for (let o = s.offset; o + entsize <= s.offset + s.size; o += entsize) {
      const info = buf[o + 12];
      symbols.push({
        name: cstr(strtab.offset, u32(o)),
        value: u32(o + 4),
        size: u32(o + 8),
        type: info & 0xf,
        shndx: u16(o + 14),
      });
    }
  }

  return {
    entry: u32(0x18),
    segments,
    sections,
    symbols,
    /** The bytes of a segment's file image. */
    segmentData: (seg) => buf.subarray(seg.offset, seg.offset + seg.filesz),
    section: (name) => sections.find((s) => s.name === name),
    symbol: (name) => symbols.find((s) => s.name === name),
    /** Function symbols (STT_FUNC, size > 0), sorted by address, Thumb bit cleared. */
    functions: () =>
      symbols
        .filter((s) => s.type === STT_FUNC && s.size > 0)
        .map((s) => ({ name: s.name, start: s.value & ~1, end: (s.value & ~1) + s.size }))
        .sort((a, b) => a.start - b.start),
  };
}

// The defmt log of the firmware: read from the RTT up-buffer 0 in emulated RAM, split into
// frames (rzCOBS, 0x00-separated: defmt 1.x's default encoding) and decoded with the format
// strings interned in the ELF's `.defmt` section (each a symbol whose name is a JSON object
// with `tag` and `data`, and whose address is the string's index on the wire).
//
// Wire format (defmt 1.x, `defmt::export`): a frame is the u16 LE index of the log statement's
// format string, then its arguments in argument order: integers, floats and `char` little
// endian at their size (`usize`/`isize` as 4 bytes), `bool` one byte, `{=str}` and `{=[u8]}` a
// u32 length then the bytes, `{=[u8; N]}` N bytes, `{=istr}` a u16 index, `{}`/`{=?}` a nested
// format (u16 index of its format string, then its data), `{=[?]}` a u32 length, one u16 index
// and the elements' data, `{=__internal_Debug}`/`Display` UTF-8 text ended by 0xFF. Derived
// enums' format strings list the variants separated by `|`, and their data starts with the
// variant's discriminant (none for one variant, u8 up to 255 variants, then u16, u32). A
// user `Format` impl's format is `{=__internal_FormatSequence}`: nested formats until index 0.
// Decoding errors throw; the caller prints the raw bytes instead.

/** rzCOBS decoding of one frame (without its 0x00 separator). The result may carry up to a
 * few extra trailing zero bytes (the encoding pads its last group); the parser ignores them. */
export function rzcobsDecode(data) {
  const out = [];
  let i = data.length - 1;
  const next = () => {
    if (i < 0) throw new Error('rzCOBS: truncated frame');
    return data[i--];
  };
  while (i >= 0) {
    const x = next();
    if (x === 0) throw new Error('rzCOBS: zero byte inside a frame');
    if (x < 0x80) {
      // Seven bytes, the MSB first (we read backwards): 1 = a zero, 0 = a byte of the stream.
      for (let b = 6; b >= 0; b--) out.push(x & (1 << b) ? 0 : next());
    } else if (x < 0xff) {
      out.push(0);
      for (let n = (x & 0x7f) + 7; n > 0; n--) out.push(next());
    } else {
      for (let n = 134; n > 0; n--) out.push(next());
    }
  }
  return Uint8Array.from(out.reverse());
}

/** The interned strings of an ELF: index -> { tag, data }. */
export function defmtTable(elf) {
  const section = elf.section('.defmt');
  const table = new Map();
  if (!section) return table;
  for (const s of elf.symbols) {
    if (s.shndx !== section.index || !s.name.startsWith('{')) continue;
    try {
      const { tag, data } = JSON.parse(s.name);
      table.set(s.value, { tag, data });
    } catch {
      // not a defmt string symbol
    }
  }
  return table;
}

/** Splits a format string into literal text and parameters `{[index][=type][:hint]}`. */
function parseFormat(fmt) {
  const parts = [];
  let text = '';
  let next = 0;
  for (let i = 0; i < fmt.length; i++) {
    const c = fmt[i];
    if ((c === '{' || c === '}') && fmt[i + 1] === c) {
      text += c;
      i++;
    } else if (c === '{') {
      const end = fmt.indexOf('}', i);
      if (end < 0) throw new Error(`unterminated parameter in ${JSON.stringify(fmt)}`);
      const m = /^(\d*)(?:=([^:]*))?(?::(.*))?$/.exec(fmt.slice(i + 1, end));
      if (!m) throw new Error(`bad parameter in ${JSON.stringify(fmt)}`);
      if (text) parts.push(text);
      text = '';
      const index = m[1] === '' ? next++ : Number(m[1]);
      parts.push({ index, type: m[2] ?? '?', hint: m[3] ?? '' });
      i = end;
    } else {
      text += c;
    }
  }
  if (text) parts.push(text);
  return parts;
}

/** Splits a derived enum's format string at its top-level `|`s. */
function splitVariants(fmt) {
  const variants = [];
  let depth = 0;
  let start = 0;
  for (let i = 0; i < fmt.length; i++) {
    if (fmt[i] === '{') depth++;
    else if (fmt[i] === '}') depth--;
    else if (fmt[i] === '|' && depth === 0) {
      variants.push(fmt.slice(start, i));
      start = i + 1;
    }
  }
  variants.push(fmt.slice(start));
  return variants;
}

/** A cursor over a decoded frame. */
class Reader {
  constructor(bytes) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.pos = 0;
  }
  take(n) {
    if (this.pos + n > this.bytes.length) throw new Error('frame too short for its format');
    const at = this.pos;
    this.pos += n;
    return at;
  }
  u8() { return this.view.getUint8(this.take(1)); }
  u16() { return this.view.getUint16(this.take(2), true); }
  u32() { return this.view.getUint32(this.take(4), true); }
  bytesN(n) { const at = this.take(n); return this.bytes.subarray(at, at + n); }
  /** Little-endian unsigned integer of `n` bytes, as a BigInt. */
  uint(n) {
    let v = 0n;
    const b = this.bytesN(n);
    for (let k = n - 1; k >= 0; k--) v = (v << 8n) | BigInt(b[k]);
    return v;
  }
}

const UTF8 = new TextDecoder();
const INT_BYTES = { u8: 1, u16: 2, u32: 4, u64: 8, u128: 16, usize: 4, i8: 1, i16: 2, i32: 4, i64: 8, i128: 16, isize: 4 };

/** Renders an integer (BigInt or number) with a display hint (`x`, `#010x`, `b`, ...). */
function renderInt(v, hint) {
  const m = /^(#)?(0(\d+))?([xXbo])$/.exec(hint);
  if (!m) return v.toString();
  const radix = { x: 16, X: 16, b: 2, o: 8 }[m[4]];
  let s = BigInt(v).toString(radix);
  if (m[4] === 'X') s = s.toUpperCase();
  const prefix = m[1] ? { x: '0x', X: '0x', b: '0b', o: '0o' }[m[4]] : '';
  const width = m[3] ? Number(m[3]) - prefix.length : 0;
  return prefix + s.padStart(width, '0');
}

export class DefmtDecoder {
  constructor(table) {
    this.table = table;
  }

  /** Decodes one rzCOBS-decoded frame: { level, text }. Throws on malformed data. */
  decodeFrame(bytes) {
    const r = new Reader(bytes);
    const entry = this.entry(r.u16());
    const level = /^defmt_(trace|debug|info|warn|error)$/.exec(entry.tag)?.[1] ?? '';
    return { level, text: this.format(entry.data, r) };
  }

  entry(index) {
    const e = this.table.get(index);
    if (!e) throw new Error(`unknown string index ${index}`);
    return e;
  }

  /** Decodes the arguments of `fmt` from `r` and renders it. */
  format(fmt, r) {
    const parts = parseFormat(fmt);
    const params = parts.filter((p) => typeof p !== 'string');
    // Each argument once, in argument order; bitfields (`{0=0..4}`) of one argument share it.
    const types = new Map();
    for (const p of params) {
      const range = /^(\d+)\.\.(\d+)$/.exec(p.type);
      const prev = types.get(p.index);
      if (range) {
        const hi = Math.max(Number(range[2]), prev?.bits ?? 0);
        types.set(p.index, { type: 'bits', bits: hi });
      } else if (!prev) {
        types.set(p.index, { type: p.type });
      }
    }
    const values = new Map();
    for (const index of [...types.keys()].sort((a, b) => a - b)) {
      const t = types.get(index);
      if (t.type === 'bits') {
        const n = t.bits <= 8 ? 1 : t.bits <= 16 ? 2 : t.bits <= 32 ? 4 : t.bits <= 64 ? 8 : 16;
        values.set(index, r.uint(n));
      } else {
        values.set(index, this.value(t.type, r));
      }
    }
    return parts
      .map((p) => {
        if (typeof p === 'string') return p;
        const v = values.get(p.index);
        const range = /^(\d+)\.\.(\d+)$/.exec(p.type);
        if (range) {
          const lo = BigInt(range[1]);
          const mask = (1n << (BigInt(range[2]) - lo)) - 1n;
          return renderInt((v >> lo) & mask, p.hint);
        }
        return this.render(v, p.hint);
      })
      .join('');
  }

  /** Renders a decoded value with a display hint. */
  render(v, hint) {
    if (typeof v === 'bigint' || typeof v === 'number') return renderInt(v, hint);
    if (v instanceof Uint8Array) {
      if (hint === 'a') return `b"${[...v].map((b) => (b >= 32 && b < 127 ? String.fromCharCode(b) : `\\x${b.toString(16).padStart(2, '0')}`)).join('')}"`;
      return `[${[...v].map((b) => renderInt(b, hint)).join(', ')}]`;
    }
    if (typeof v === 'string') return v; // a nested format, already rendered
    if (Array.isArray(v)) return `[${v.join(', ')}]`;
    if (v && typeof v === 'object' && 'str' in v) return hint === '?' ? JSON.stringify(v.str) : v.str;
    return String(v);
  }

  /** Decodes one argument of type `type` (the part after `=` in a parameter). */
  value(type, r) {
    if (type in INT_BYTES) {
      const n = INT_BYTES[type];
      let v = r.uint(n);
      if (type[0] === 'i' && v >= 1n << BigInt(8 * n - 1)) v -= 1n << BigInt(8 * n);
      return v;
    }
    switch (type) {
      case 'bool':
        return r.u8() !== 0;
      case 'f32':
        return r.view.getFloat32(r.take(4), true);
      case 'f64':
        return r.view.getFloat64(r.take(8), true);
      case 'char':
        return { str: String.fromCodePoint(r.u32()) };
      case 'str':
        return { str: UTF8.decode(r.bytesN(r.u32())) };
      case 'istr':
        return { str: this.entry(r.u16()).data };
      case '[u8]':
        return r.bytesN(r.u32());
      case '__internal_Debug':
      case '__internal_Display': {
        const start = r.pos;
        while (r.bytes[r.take(1)] !== 0xff);
        return UTF8.decode(r.bytes.subarray(start, r.pos - 1));
      }
      case '__internal_FormatSequence': {
        let s = '';
        for (let index = r.u16(); index !== 0; index = r.u16()) s += this.format(this.entry(index).data, r);
        return s;
      }
      case '?':
        return this.nested(r.u16(), r);
      case '[?]': {
        const len = r.u32();
        const tag = r.u16();
        return Array.from({ length: len }, () => this.nested(tag, r));
      }
    }
    let m = /^\[u8; *(\d+)\]$/.exec(type);
    if (m) return r.bytesN(Number(m[1]));
    m = /^\[\?; *(\d+)\]$/.exec(type);
    if (m) {
      const tag = r.u16();
      return Array.from({ length: Number(m[1]) }, () => this.nested(tag, r));
    }
    throw new Error(`unsupported parameter type {=${type}}`);
  }

  /** The data of a value whose format string has index `tag` (a `Format` value). */
  nested(tag, r) {
    const { tag: kind, data } = this.entry(tag);
    if (kind === 'defmt_derived') {
      const variants = splitVariants(data);
      if (variants.length > 1) {
        const n = variants.length;
        const d = Number(r.uint(n <= 255 ? 1 : n <= 65535 ? 2 : 4));
        if (d >= n) throw new Error(`enum discriminant ${d} out of range in ${JSON.stringify(data)}`);
        return this.format(variants[d], r);
      }
    }
    if (data === '{=__internal_FormatSequence}') return this.value('__internal_FormatSequence', r);
    return this.format(data, r);
  }
}

/** Reads the defmt bytes out of the RTT up-buffer 0 of `_SEGGER_RTT` (defmt-rtt's control
 * block: "SEGGER RTT\0...", max up/down buffer counts, then the up buffers {name, buffer,
 * size, write, read, flags}), advancing the read offset as a probe does. */
export class RttReader {
  constructor(rp2040, address) {
    this.rp2040 = rp2040;
    this.address = address;
    this.pending = [];
  }

  /** The up buffer 0 descriptor's address, or null while the block is not initialised. */
  channel() {
    const m = this.rp2040;
    const id = [];
    for (let i = 0; i < 10; i++) id.push(m.readUint8(this.address + i));
    if (String.fromCharCode(...id) !== 'SEGGER RTT') return null;
    if (m.readUint32(this.address + 16) < 1) return null;
    return this.address + 24;
  }

  /** Moves the bytes written since the last call out of emulated RAM; returns them. */
  drain() {
    const ch = this.channel();
    if (ch === null) return [];
    const m = this.rp2040;
    const buffer = m.readUint32(ch + 4);
    const size = m.readUint32(ch + 8);
    const write = m.readUint32(ch + 12);
    let read = m.readUint32(ch + 16);
    if (size === 0 || write >= size || read >= size) return [];
    const out = [];
    while (read !== write) {
      out.push(m.readUint8(buffer + read));
      read = (read + 1) % size;
    }
    m.writeUint32(ch + 16, read);
    return out;
  }
}

/** Collects RTT bytes into 0x00-separated frames and decodes each. */
export class DefmtStream {
  constructor(decoder) {
    this.decoder = decoder;
    this.partial = [];
  }

  /** Feeds bytes; returns the lines completed: { level, text } or { raw, error }. */
  push(bytes) {
    const lines = [];
    for (const b of bytes) {
      if (b !== 0) {
        this.partial.push(b);
        continue;
      }
      if (this.partial.length === 0) continue;
      const frame = Uint8Array.from(this.partial);
      this.partial = [];
      let decoded;
      try {
        decoded = rzcobsDecode(frame);
        lines.push(this.decoder.decodeFrame(decoded));
      } catch (e) {
        const raw = [...(decoded ?? frame)].map((x) => x.toString(16).padStart(2, '0')).join(' ');
        lines.push({ raw, error: e.message });
      }
    }
    return lines;
  }
}

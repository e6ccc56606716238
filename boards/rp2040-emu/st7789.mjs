// An ST7789 on the SPI bus, as far as the firmware drives it: each byte the SPI sends comes
// with the state of DC (low: command, high: parameter or pixel data) and CS (active low).
// CASET (0x2A) and RASET (0x2B) set the address window (start and end, 16 bits each, big
// endian), RAMWR (0x2C) writes RGB565 pixels (two bytes each, big endian) into it, column by
// column then row by row. Other commands (the init sequence: SWRESET, SLPOUT, COLMOD, MADCTL,
// INVON, DISPON, ...) are counted and their parameters skipped.
//
// Frames: the display shows a `width` x `height` window of the controller's 240x320 memory
// starting at (x0, y0) (mipidsi's offsets; learned from the first RAMWR window). A frame is
// complete when a RAMWR has written the window's last pixel (bottom-right); the frame is then a
// copy of the window's pixels, as the big-endian bytes the display received.

const CASET = 0x2a;
const RASET = 0x2b;
const RAMWR = 0x2c;
const GRAM_WIDTH = 240;
const GRAM_HEIGHT = 320;

export class St7789 {
  /** `onFrame(frame)` is called with { pixels: Uint8Array (big-endian RGB565), written }. */
  constructor({ width = 240, height = 240, onFrame }) {
    this.width = width;
    this.height = height;
    this.onFrame = onFrame;
    this.gram = new Uint8Array(GRAM_WIDTH * GRAM_HEIGHT * 2);
    this.command = -1;
    this.params = [];
    this.window = { xs: 0, xe: GRAM_WIDTH - 1, ys: 0, ye: GRAM_HEIGHT - 1 };
    this.caset = [0, GRAM_WIDTH - 1];
    this.raset = [0, GRAM_HEIGHT - 1];
    this.x = 0;
    this.y = 0;
    this.half = -1; // the first byte of a pixel, or -1
    this.origin = null; // (x0, y0) of the displayed window, from the first RAMWR
    this.written = 0; // pixels of the displayed window written since the last frame
    this.commands = new Map(); // command byte -> count
    this.errors = [];
    this.bytes = 0;
  }

  error(msg) {
    if (this.errors.length < 20) this.errors.push(`byte ${this.bytes}: ${msg}`);
  }

  /** One byte on the bus, with DC and CS as they were while it was sent. */
  byte(value, dc, cs) {
    this.bytes++;
    if (cs) {
      this.error(`0x${value.toString(16)} sent with CS high`);
      return;
    }
    if (!dc) {
      this.endCommand();
      this.command = value;
      this.params = [];
      this.commands.set(value, (this.commands.get(value) ?? 0) + 1);
      if (value === RAMWR) this.startWrite();
      return;
    }
    if (this.command < 0) {
      this.error(`data byte 0x${value.toString(16)} before any command`);
    } else if (this.command === RAMWR) {
      this.pixelByte(value);
    } else {
      this.params.push(value);
    }
  }

  /** Checks the parameters of the command that ends (a new command byte follows). */
  endCommand() {
    if (this.command === CASET || this.command === RASET) {
      const p = this.params;
      const name = this.command === CASET ? 'CASET' : 'RASET';
      const limit = this.command === CASET ? GRAM_WIDTH : GRAM_HEIGHT;
      if (p.length !== 4) {
        this.error(`${name} with ${p.length} parameter bytes (4 expected)`);
      } else {
        const start = (p[0] << 8) | p[1];
        const end = (p[2] << 8) | p[3];
        if (start > end || end >= limit) this.error(`${name} ${start}..${end} outside 0..${limit - 1}`);
        else if (this.command === CASET) this.caset = [start, end];
        else this.raset = [start, end];
      }
    } else if (this.command === RAMWR && this.half >= 0) {
      this.error('RAMWR ended in the middle of a pixel');
    }
    this.half = -1;
  }

  startWrite() {
    this.window = { xs: this.caset[0], xe: this.caset[1], ys: this.raset[0], ye: this.raset[1] };
    this.x = this.window.xs;
    this.y = this.window.ys;
    this.half = -1;
    if (!this.origin) {
      this.origin = { x: this.window.xs, y: this.window.ys };
      if (this.origin.x + this.width > GRAM_WIDTH || this.origin.y + this.height > GRAM_HEIGHT) {
        this.error(`first window at (${this.origin.x}, ${this.origin.y}) leaves no room for ${this.width}x${this.height}`);
      }
    }
  }

  pixelByte(value) {
    if (this.half < 0) {
      this.half = value;
      return;
    }
    const w = this.window;
    if (this.y > w.ye) {
      this.error('RAMWR data past the end of its window');
      this.half = -1;
      return;
    }
    const at = (this.y * GRAM_WIDTH + this.x) * 2;
    this.gram[at] = this.half;
    this.gram[at + 1] = value;
    this.half = -1;
    const o = this.origin;
    const inside = this.x >= o.x && this.x < o.x + this.width && this.y >= o.y && this.y < o.y + this.height;
    if (inside) this.written++;
    const last = this.x === o.x + this.width - 1 && this.y === o.y + this.height - 1;
    if (++this.x > w.xe) {
      this.x = w.xs;
      this.y++;
    }
    if (last) this.frameDone();
  }

  frameDone() {
    const { x, y } = this.origin;
    const pixels = new Uint8Array(this.width * this.height * 2);
    for (let row = 0; row < this.height; row++) {
      const from = ((y + row) * GRAM_WIDTH + x) * 2;
      pixels.set(this.gram.subarray(from, from + this.width * 2), row * this.width * 2);
    }
    const written = this.written;
    this.written = 0;
    this.onFrame({ pixels, written });
  }

  /** The command counts, e.g. "0x2a x31, 0x2c x16". */
  summary() {
    return [...this.commands].map(([c, n]) => `0x${c.toString(16).padStart(2, '0')} x${n}`).join(', ');
  }
}

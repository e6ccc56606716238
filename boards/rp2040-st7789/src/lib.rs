//! What both firmware binaries share: sending finished bands to the ST7789 by DMA, so that
//! the SPI transfer of one band overlaps the drawing of the next.
//!
//! Why not through `mipidsi` (which initializes the display): its pixel path converts every
//! pixel through an iterator into a 512-byte buffer and writes the bytes one blocking SPI
//! transfer at a time, about 56 core cycles per byte measured in rp2040js (6.5 M cycles per
//! frame, while the CPU could be drawing). Here a band costs the CPU its three address
//! commands: its pixel buffer goes to the DMA transfer whole and the band is drawn next into
//! the buffer sent before ([`BandSender::send_swapping`], `arealight`'s `bytemuck` feature
//! seeing the `Rgb565` pixels as the DMA's `u16` words; [`BandSender::send`] copies instead,
//! about 2.5 cycles per pixel); the DMA channel then feeds SPI1 by itself at the bus's pace
//! (62.5 MHz: 32 core cycles per pixel), while the next band is drawn.
//!
//! The SPI runs 16-bit frames, most significant bit first: an RGB565 pixel goes out
//! big-endian, as the ST7789 wants it, with no byte swapping. A command byte goes out as the
//! 16-bit word `0x00cc`: the display sees a NOP (0x00, no parameters) and then the command;
//! the column and row addresses of CASET and RASET are 16-bit big-endian words already.
#![no_std]
#![deny(unsafe_code)]

use arealight::raster::{Band, Rgb565};
use demo_scene::{BAND_PIXELS, WIDTH};
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use rp2040_hal as hal;

use hal::dma::{single_buffer, SingleChannel, WriteTarget};

/// Column address set.
const CASET: u16 = 0x2A;
/// Row address set.
const RASET: u16 = 0x2B;
/// Memory write: the pixels follow.
const RAMWR: u16 = 0x2C;

/// The DMA buffer of one band of `N` pixels (by default the scene's 240 x 16): the pixels SPI1
/// sends, each as one 16-bit word (`bytemuck`'s view of an [`Rgb565`] slice).
pub type DmaBuffer<const N: usize = BAND_PIXELS> = [Rgb565; N];

/// The sender's resources, either idle or lent to a DMA transfer in flight (which reads the
/// buffer's pixels as `u16` words).
enum State<CH: SingleChannel, SPI: WriteTarget<TransmittedWord = u16>> {
    Idle(CH, &'static mut [Rgb565], SPI),
    Sending(single_buffer::Transfer<CH, &'static mut [u16], SPI>),
    /// Only while moving between the two (never observed outside `send`).
    Moving,
}

/// Sends bands of up to `N` pixels to an ST7789 over a 16-bit SPI (`SPI`) by DMA channel
/// `CH`, with the data / command pin `DC` and the chip select `CS` (held low from the first
/// band on).
pub struct BandSender<CH, SPI, DC, CS, const N: usize = BAND_PIXELS>
where
    CH: SingleChannel,
    SPI: WriteTarget<TransmittedWord = u16>,
{
    state: State<CH, SPI>,
    /// The colour every pixel of the sender's buffer holds, if one does (after
    /// [`BandSender::send_uniform`]; `None` after [`BandSender::send`] or
    /// [`BandSender::send_swapping`]).
    uniform: Option<u16>,
    dc: DC,
    cs: CS,
}

impl<CH, SPI, DC, CS, const N: usize> BandSender<CH, SPI, DC, CS, N>
where
    CH: SingleChannel,
    SPI: SpiBus<u16> + WriteTarget<TransmittedWord = u16>,
    DC: OutputPin,
    CS: OutputPin,
{
    /// A sender over `spi` (configured for 16-bit frames), DMA channel `ch`, the band buffer
    /// `buffer` and the display's control pins.
    pub fn new(ch: CH, spi: SPI, buffer: &'static mut DmaBuffer<N>, dc: DC, cs: CS) -> Self {
        BandSender {
            state: State::Idle(ch, buffer, spi),
            uniform: None,
            dc,
            cs,
        }
    }

    /// Waits for the band in flight (if any) to leave the SPI completely; returns the idle
    /// resources.
    fn finish(&mut self) -> (CH, &'static mut [Rgb565], SPI) {
        let (ch, buffer, mut spi) = match core::mem::replace(&mut self.state, State::Moving) {
            State::Idle(ch, buffer, spi) => (ch, buffer, spi),
            State::Sending(transfer) => {
                let (ch, words, spi) = transfer.wait();
                // (The same size and alignment: bytemuck's checks are constants that pass.)
                (ch, bytemuck::cast_slice_mut(words), spi)
            }
            // Unreachable: `send` always puts a state back. Nothing to recover from here.
            State::Moving => loop {
                cortex_m::asm::wfe();
            },
        };
        // The DMA is done when the last word is in the FIFO: wait until it has been shifted
        // out before touching DC.
        let _ = spi.flush();
        (ch, buffer, spi)
    }

    /// Whether the band in flight (if any) has left the DMA channel: then [`BandSender::send`]
    /// and [`BandSender::send_uniform`] start at once (after the SPI's last few words).
    pub fn is_idle(&self) -> bool {
        match &self.state {
            State::Idle(..) => true,
            State::Sending(transfer) => transfer.is_done(),
            State::Moving => false,
        }
    }

    /// Sends `band` (all of its rows, [`WIDTH`] wide) to the display rows `band.y0()..`:
    /// waits for the previous band to finish, sends the address window, copies the pixels
    /// into the DMA buffer and starts the transfer, which goes on after this returns.
    pub fn send(&mut self, band: &Band<'_, Rgb565>) -> Result<(), DC::Error> {
        let pixels = band.pixels();
        self.uniform = None;
        self.send_with(band.y0(), band.rows(), |buffer| {
            copy_pixels(buffer, pixels);
            buffer
        })
    }

    /// [`BandSender::send`] without the copy: the band's pixel buffer goes to the DMA
    /// transfer as it is, and the band takes the sender's buffer instead, whose transfer has
    /// ended ([`Band::replace_pixels`]; its contents are the band sent before: clear the band
    /// before drawing into it). A band whose buffer is not `N` pixels is copied, as by `send`.
    /// Saves the copy, about 2.5 cycles a pixel on the Cortex-M0+: rp2040js frames 1 to 15,
    /// 8 772 859 -> 8 627 742 cycles on average with one core (six 240 x 40 bands),
    /// 4 971 717 -> 4 896 673 with two (fifteen 240 x 16 bands, the buffers passing between
    /// the cores and the sender).
    pub fn send_swapping(&mut self, band: &mut Band<'static, Rgb565>) -> Result<(), DC::Error> {
        self.uniform = None;
        let (y0, rows) = (band.y0(), band.rows());
        self.send_with(y0, rows, |buffer| {
            if buffer.len() != N {
                return buffer;
            }
            match band.replace_pixels(buffer) {
                Ok(drawn) => drawn,
                Err(buffer) => {
                    copy_pixels(buffer, band.pixels());
                    buffer
                }
            }
        })
    }

    /// Sends a band of `rows` rows from display row `y0` all of one `colour` (an empty band:
    /// the background), as [`BandSender::send`] does a drawn one, but with no band to draw or
    /// copy: the DMA buffer is filled with `colour`, unless the last band sent was this
    /// colour too (then it holds it already: only the address window is sent).
    pub fn send_uniform(&mut self, y0: u16, rows: u16, colour: Rgb565) -> Result<(), DC::Error> {
        let refill = self.uniform != Some(colour.0);
        let result = self.send_with(y0, rows, |buffer| {
            if refill {
                buffer.fill(colour);
            }
            buffer
        });
        // (On an error nothing was written: the buffer's content is not known.)
        self.uniform = result.is_ok().then_some(colour.0);
        result
    }

    /// [`BandSender::send`] of the band of `rows` rows from `y0` whose pixels `fill` puts in
    /// the DMA buffer it is given, returning the buffer to send (that one, or another of the
    /// same length, which the sender then keeps).
    fn send_with(
        &mut self,
        y0: u16,
        rows: u16,
        fill: impl FnOnce(&'static mut [Rgb565]) -> &'static mut [Rgb565],
    ) -> Result<(), DC::Error> {
        let (ch, buffer, mut spi) = self.finish();
        let y1 = y0 + rows - 1;
        let command = |spi: &mut SPI, cmd: u16, params: &[u16], dc: &mut DC| {
            dc.set_low()?;
            let _ = spi.write(&[cmd]);
            let _ = spi.flush();
            dc.set_high()?;
            let _ = spi.write(params);
            let _ = spi.flush();
            Ok(())
        };
        self.cs.set_low().ok();
        let result = command(&mut spi, CASET, &[0, WIDTH - 1], &mut self.dc)
            .and_then(|()| command(&mut spi, RASET, &[y0, y1], &mut self.dc))
            .and_then(|()| command(&mut spi, RAMWR, &[], &mut self.dc));
        if let Err(e) = result {
            self.state = State::Idle(ch, buffer, spi);
            return Err(e);
        }
        let buffer = fill(buffer);
        // A band shorter than the buffer (the last one, if the height were not a multiple
        // of the band's rows) sends only its own pixels: there is none here (240 = 12 x 20 with two
        // cores, 4 x 60 with one).
        let words: &'static mut [u16] = bytemuck::cast_slice_mut(buffer);
        self.state = State::Sending(single_buffer::Config::new(ch, words, spi).start());
        Ok(())
    }

    /// Waits until the last band has been sent (the end of a frame, for timing).
    pub fn flush(&mut self) {
        let (ch, buffer, spi) = self.finish();
        self.state = State::Idle(ch, buffer, spi);
    }
}

/// Copies the pixels `from` into the start of `to` (as many as fit).
fn copy_pixels(to: &mut [Rgb565], from: &[Rgb565]) {
    for (t, p) in to.iter_mut().zip(from) {
        *t = *p;
    }
}

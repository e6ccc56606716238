//! A frame of the [`Demo`] in its [`Stage`]s, timed by the board's clock: the driver that
//! [`Demo::render_frame`] (and `spec::Player`'s) run, with the band handed to the display
//! after each is drawn ([`Output`]).

use super::*;

/// The stages of a frame, as the boards time them (each firmware reads its own cycle counter
/// between them: SysTick on the RP2040, DWT on the STM32F411, TIM2 instructions under QEMU).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The frame's lights and transforms ([`Demo::frame`]).
    Setup = 0,
    /// Vertices through the model transform and the camera, once per frame.
    Transform = 1,
    /// The light models at the vertices (Gouraud), once per frame.
    Shade = 2,
    /// Scan conversion, interpolation, depth test, per-pixel shading (if chosen) and encoding,
    /// band by band.
    Raster = 3,
    /// Sending the bands to the display.
    Flush = 4,
}

impl Stage {
    /// Every stage, in frame order.
    pub const ALL: [Stage; 5] = [
        Stage::Setup,
        Stage::Transform,
        Stage::Shade,
        Stage::Raster,
        Stage::Flush,
    ];
    /// The stage's name in logs and tables.
    pub const fn name(self) -> &'static str {
        match self {
            Stage::Setup => "setup",
            Stage::Transform => "transform",
            Stage::Shade => "shade",
            Stage::Raster => "raster",
            Stage::Flush => "flush",
        }
    }
}

/// What [`Demo::render_frame`] measured: the clock's ticks per [`Stage`] (indexed by
/// `Stage as usize`) and the draw calls' statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameReport {
    /// Clock ticks spent in each stage.
    pub ticks: [u32; 5],
    /// What the draw calls did.
    pub stats: DrawStats,
}

impl FrameReport {
    /// The sum of all stages.
    pub fn total(&self) -> u32 {
        self.ticks.iter().fold(0u32, |a, &t| a.wrapping_add(t))
    }
}

/// Why a frame failed: the rasterizer refused something or the display did not answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError<E> {
    /// The rasterizer's error.
    Raster(RasterError),
    /// The flush callback's error (the display's).
    Flush(E),
}

impl<E> From<RasterError> for FrameError<E> {
    fn from(e: RasterError) -> Self {
        FrameError::Raster(e)
    }
}

/// The stages of a frame, as [`render_stages`] runs them: what a scene does per frame (the
/// demo, and the scene-file player of [`spec`]).
pub(crate) trait Stages {
    /// What the setup computes for the frame (lights, transforms).
    type Frame;
    /// The frame's setup ([`Stage::Setup`]).
    fn setup(&self, n: u32) -> Result<Self::Frame, RasterError>;
    /// Every vertex transformed ([`Stage::Transform`]).
    fn transform(&mut self, frame: &Self::Frame);
    /// The Gouraud vertices shaded ([`Stage::Shade`]); the shader calls.
    fn shade(&mut self, frame: &Self::Frame) -> u32;
    /// One band drawn (cleared by the caller) ([`Stage::Raster`]).
    fn draw_band(
        &self,
        frame: &Self::Frame,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError>;
    /// The frame's height in pixels.
    fn height(&self) -> u16;
    /// The clear colour.
    fn background(&self) -> Rgb565;
    /// Whether no object reaches rows `y0..y0 + rows` this frame (after the transform); `false`
    /// when not known.
    fn band_is_empty(&self, _y0: u16, _rows: u16) -> bool {
        false
    }
}

/// What [`Demo::render_frame_carrying`] hands its caller.
#[derive(Debug)]
pub enum Output<'a, 'b> {
    /// A finished band, to send (mutable: a sender may swap its pixel buffer for another,
    /// [`Band::replace_pixels`], instead of copying it).
    Band(&'a mut Band<'b, Rgb565>),
    /// The frame's last band, `rows` rows from `y0`, which no object reaches: not drawn; the
    /// caller sends it as [`BACKGROUND`] at the next [`Output::Carried`] (or now), instead of
    /// waiting for its turn at the display.
    Keep {
        /// Its first row.
        y0: u16,
        /// Its rows.
        rows: u16,
    },
    /// The frame's transform is done (the last frame's bands long handed to the display): a
    /// band [`Output::Keep`] left can be sent now, while this frame is shaded.
    Carried,
}

/// Renders frame `n` of `scene` through `band`, calling `flush` with each finished band, top to
/// bottom, and `clock` between the stages, whose ticks it returns (the one frame loop of
/// [`Demo::render_frame`] and `spec::Player::render_frame`).
pub(crate) fn render_stages<S: Stages, E>(
    scene: &mut S,
    n: u32,
    band: &mut Band<'_, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    mut flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
) -> Result<FrameReport, FrameError<E>> {
    render_stages_carrying(scene, n, band, clock, false, |out| match out {
        Output::Band(b) => flush(&*b),
        Output::Keep { .. } | Output::Carried => Ok(()),
    })
}

/// [`render_stages`] handing the caller [`Output`]s: with `carry`, the last band is kept
/// when no object reaches it, and [`Output::Carried`] follows every transform.
pub(crate) fn render_stages_carrying<'b, S: Stages, E>(
    scene: &mut S,
    n: u32,
    band: &mut Band<'b, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    carry: bool,
    mut flush: impl FnMut(Output<'_, 'b>) -> Result<(), E>,
) -> Result<FrameReport, FrameError<E>> {
    let mut report = FrameReport::default();
    let mut last = clock();
    let mut lap = |stage: Stage, ticks: &mut [u32; 5]| {
        let now = clock();
        let t = &mut ticks[stage as usize];
        *t = t.wrapping_add(now.wrapping_sub(last));
        last = now;
    };
    let frame = scene.setup(n)?;
    lap(Stage::Setup, &mut report.ticks);
    scene.transform(&frame);
    lap(Stage::Transform, &mut report.ticks);
    if carry {
        flush(Output::Carried).map_err(FrameError::Flush)?;
        lap(Stage::Flush, &mut report.ticks);
    }
    let mut stats = DrawStats {
        shaded: scene.shade(&frame),
        ..DrawStats::default()
    };
    lap(Stage::Shade, &mut report.ticks);
    let rows = band.rows().max(1);
    let (height, background) = (scene.height(), scene.background());
    let mut y0: u16 = 0;
    while y0 < height {
        let out = if carry && y0.saturating_add(rows) >= height && scene.band_is_empty(y0, rows) {
            Output::Keep { y0, rows }
        } else {
            band.move_to(y0);
            band.clear(background);
            scene.draw_band(&frame, band, &mut stats)?;
            lap(Stage::Raster, &mut report.ticks);
            Output::Band(band)
        };
        flush(out).map_err(FrameError::Flush)?;
        lap(Stage::Flush, &mut report.ticks);
        y0 = y0.saturating_add(rows);
    }
    report.stats = stats;
    Ok(report)
}

impl<T: Real> Stages for Demo<'_, T> {
    type Frame = Frame<T>;
    fn setup(&self, n: u32) -> Result<Frame<T>, RasterError> {
        self.frame(n)
    }
    fn transform(&mut self, frame: &Frame<T>) {
        Demo::transform(self, frame);
    }
    fn shade(&mut self, frame: &Frame<T>) -> u32 {
        Demo::shade(self, frame)
    }
    fn draw_band(
        &self,
        frame: &Frame<T>,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError> {
        Demo::draw_band(self, frame, band, stats)
    }
    fn height(&self) -> u16 {
        HEIGHT
    }
    fn background(&self) -> Rgb565 {
        BACKGROUND
    }
    fn band_is_empty(&self, y0: u16, rows: u16) -> bool {
        Demo::band_is_empty(self, y0, rows)
    }
}

impl<'a, T: Real> Demo<'a, T> {
    /// Renders frame `n` through `band` (a [`WIDTH`]-wide band of any height), calling `flush`
    /// with each finished band, top to bottom, and `clock` (any free-running tick counter:
    /// core cycles, instructions, microseconds; wrapping) between the stages, whose ticks it
    /// returns. This is the whole frame of every board and of the host reference.
    ///
    /// # Errors
    /// The first error of the rasterizer or of `flush`.
    pub fn render_frame<E>(
        &mut self,
        n: u32,
        band: &mut Band<'_, Rgb565>,
        clock: &mut impl FnMut() -> u32,
        flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
    ) -> Result<FrameReport, FrameError<E>> {
        render_stages(self, n, band, clock, flush)
    }

    /// [`Demo::render_frame`] for a display that keeps what it was sent and a sender that
    /// need not wait: a last band that no object reaches is not drawn but handed to `flush` as
    /// [`Output::Keep`], and after each frame's transform `flush` gets [`Output::Carried`], when
    /// the caller sends such a band as [`BACKGROUND`] (its turn at the display has long come:
    /// the frame before it ended during the transform). So the frame's end does not wait for
    /// the transfer of the band before the last, and the last band's transfer overlaps the next
    /// frame's shading; the display still receives each frame whole before the next one. The
    /// one-core RP2040 firmware's loop (`boards/rp2040-st7789/src/bin/lit_scene.rs`).
    ///
    /// # Errors
    /// The first error of the rasterizer or of `flush`.
    pub fn render_frame_carrying<'b, E>(
        &mut self,
        n: u32,
        band: &mut Band<'b, Rgb565>,
        clock: &mut impl FnMut() -> u32,
        flush: impl FnMut(Output<'_, 'b>) -> Result<(), E>,
    ) -> Result<FrameReport, FrameError<E>> {
        render_stages_carrying(self, n, band, clock, true, flush)
    }
}

//! The one typeface the pictures are lettered in: DejaVu Sans, embedded in the binary.
//!
//! `plotters` draws text with fonts registered by name; [`ready`] registers the embedded
//! font as the `sans-serif` family once per process, so a plot or a gallery label looks
//! the same on every machine and needs no system font. Invariant: every text the back end
//! draws names [`FAMILY`], the only family registered.

use std::sync::OnceLock;

/// The family name every text style uses.
pub const FAMILY: &str = "sans-serif";

/// DejaVu Sans (assets/fonts; its licence is beside it).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the embedded font, once; an error when the font cannot be read.
pub fn ready() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font(FAMILY, plotters::style::FontStyle::Normal, FONT)
            .map_err(|_| "the embedded font DejaVu Sans cannot be read".to_string())
    })
    .clone()
}

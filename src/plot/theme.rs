//! The colour schemes every plot draws with.
//! May import: plotters' colours and text styles only; never `web`, `live` or `eval`.

use plotters::prelude::*;

/// Colours of one scheme.
#[derive(Debug, Clone, Copy)]
pub struct Theme {
    /// Background.
    pub background: RGBColor,
    /// Text, axes and the north arrow.
    pub foreground: RGBColor,
    /// Grid lines.
    pub grid: RGBColor,
    /// The estimated track.
    pub track: RGBColor,
    /// The reference (true) path.
    pub reference: RGBColor,
    /// Start mark.
    pub start: RGBColor,
    /// End mark.
    pub end: RGBColor,
    /// GNSS fixes.
    pub gnss: RGBColor,
    /// The PDR-only track beside a fused one.
    pub pdr: RGBColor,
    /// The smoothed track.
    pub smoothed: RGBColor,
}

impl Theme {
    /// Light scheme.
    pub const LIGHT: Theme = Theme {
        background: RGBColor(0xfb, 0xfb, 0xf8),
        foreground: RGBColor(0x22, 0x26, 0x2e),
        grid: RGBColor(0xe3, 0xe4, 0xe0),
        track: RGBColor(0x1f, 0x6f, 0xd1),
        reference: RGBColor(0xa8, 0xab, 0xb2),
        start: RGBColor(0x1a, 0x9e, 0x55),
        end: RGBColor(0xd1, 0x3b, 0x2f),
        gnss: RGBColor(0xe0, 0x8a, 0x1e),
        pdr: RGBColor(0x9b, 0x59, 0xb6),
        smoothed: RGBColor(0x13, 0x9c, 0x8a),
    };
    /// Dark scheme.
    pub const DARK: Theme = Theme {
        background: RGBColor(0x15, 0x18, 0x1d),
        foreground: RGBColor(0xe6, 0xe8, 0xeb),
        grid: RGBColor(0x2a, 0x2f, 0x37),
        track: RGBColor(0x5a, 0xa9, 0xff),
        reference: RGBColor(0x5d, 0x63, 0x6d),
        start: RGBColor(0x3c, 0xc7, 0x7a),
        end: RGBColor(0xff, 0x6b, 0x5e),
        gnss: RGBColor(0xf0, 0xa4, 0x3a),
        pdr: RGBColor(0xc3, 0x8b, 0xe0),
        smoothed: RGBColor(0x3f, 0xd0, 0xbb),
    };

    /// The plots' text: sans-serif of 12 CSS pixels in the foreground colour, at `scale`
    /// device pixels per CSS pixel.
    pub fn text(&self, scale: f64) -> TextStyle<'static> {
        ("sans-serif", 12.0 * scale)
            .into_font()
            .color(&self.foreground)
    }
}

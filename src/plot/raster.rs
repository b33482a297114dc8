//! An in-memory raster for the drawing tests (compiled for tests only).
//! May import: plotters and its backend trait only; never `web`, `live` or `eval`.

use plotters::prelude::*;

/// The raster's pixels, shared with the test that reads them.
pub(crate) type Pixels = std::rc::Rc<std::cell::RefCell<Vec<(u8, u8, u8)>>>;
use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};

/// An in-memory RGB raster that ignores text (no font engine natively).
pub(crate) struct Raster {
    pub(crate) w: u32,
    pub(crate) h: u32,
    pub(crate) px: Pixels,
}

impl DrawingBackend for Raster {
    type ErrorType = std::io::Error;
    fn get_size(&self) -> (u32, u32) {
        (self.w, self.h)
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }
    fn draw_pixel(
        &mut self,
        p: BackendCoord,
        c: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        if p.0 >= 0 && p.1 >= 0 && (p.0 as u32) < self.w && (p.1 as u32) < self.h {
            // Blended over what is there, as a canvas does ("source-over"), so that a faint
            // fill counts in the legibility test as it shows on the page.
            let a = c.alpha.clamp(0.0, 1.0);
            let mix =
                |new: u8, old: u8| (a * f64::from(new) + (1.0 - a) * f64::from(old)).round() as u8;
            let mut px = self.px.borrow_mut();
            let old = &mut px[(p.1 as u32 * self.w + p.0 as u32) as usize];
            *old = (
                mix(c.rgb.0, old.0),
                mix(c.rgb.1, old.1),
                mix(c.rgb.2, old.2),
            );
        }
        Ok(())
    }
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        _: &str,
        _: &S,
        _: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        _: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        Ok((7 * text.len() as u32, 13))
    }
}

/// A raster of `w` × `h` and its shared pixels.
#[allow(clippy::type_complexity)]
pub(crate) fn new(w: u32, h: u32) -> (Raster, Pixels) {
    let px = std::rc::Rc::new(std::cell::RefCell::new(vec![(0, 0, 0); (w * h) as usize]));
    (
        Raster {
            w,
            h,
            px: px.clone(),
        },
        px,
    )
}

/// Pixels of exactly colour `c`.
pub(crate) fn count(px: &Pixels, c: RGBColor) -> usize {
    px.borrow()
        .iter()
        .filter(|p| **p == (c.0, c.1, c.2))
        .count()
}

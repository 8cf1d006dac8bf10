//! The `lens APERTURE FOCUS` record: the port's extension where the thesis
//! stops (its `depthoffield`, OCR lines 2187–2202, is "not completed" and
//! the main program's call is commented out, lines 3135–3141).

use super::{Builder, DeckError};
use crate::scene::{LensRecord, Pos};

impl Builder<'_> {
    /// `lens APERTURE FOCUS`: APERTURE ≥ 0 (0: the pinhole), FOCUS > 0,
    /// both in the deck's range; at most once.
    pub(super) fn lens(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("lens");
        if let Some(first) = &self.lens {
            return Err(self.second(pos, "lens", first.pos.clone()));
        }
        let aperture = self.p.number_where("for APERTURE", ">= 0", |v| v >= 0.0)?.value;
        let focus = self.p.size("for FOCUS")?.value;
        self.p.end_of_line()?;
        self.lens = Some(LensRecord { pos, aperture, focus });
        Ok(())
    }
}

//! The `film FRAMES [shutter S] [rate FPS]` record: the port's extension
//! (the thesis renders one still; see [`crate::film`]).

use super::{Builder, DeckError};
use crate::scene::Pos;
use crate::scene::{FilmRecord, DEFAULT_RATE, DEFAULT_SHUTTER, MAX_FRAMES, MAX_RATE};

impl Builder<'_> {
    /// `film FRAMES [shutter S] [rate FPS]`: FRAMES an integer
    /// 1..10000, S in (0, 1], FPS an integer 1..60; at most once.
    pub(super) fn film(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("film");
        if let Some(first) = &self.film {
            return Err(self.p.error_at(
                pos,
                format!("a second 'film' record (the first is on line {})", first.pos.line),
            ));
        }
        let (frames, _) = self.p.integer("for FRAMES", 1, i64::from(MAX_FRAMES))?;
        let mut shutter = DEFAULT_SHUTTER;
        let mut rate = DEFAULT_RATE;
        let mut seen = Vec::new();
        while let Some((field, _)) = self.p.field(&["shutter", "rate"], &mut seen)? {
            match field {
                "shutter" => {
                    shutter = self
                        .p
                        .number_where("after 'shutter'", "in (0, 1]", |s| s > 0.0 && s <= 1.0)?
                        .value
                }
                _ => rate = self.p.integer("after 'rate'", 1, i64::from(MAX_RATE))?.0 as u32,
            }
        }
        self.p.end_of_line()?;
        // The ranges above make the casts exact.
        self.film = Some(FilmRecord {
            pos,
            frames: frames as u32,
            shutter,
            rate,
        });
        Ok(())
    }
}

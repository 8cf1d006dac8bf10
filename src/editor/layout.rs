//! Where each part of the editor's screen lies, 1024×864 like the PS 390's:
//! the rectangles the screen draws into ([`super::screen`]) and the session
//! reads the mouse in ([`super::session`]). Both take them from here, so
//! neither imports the other's module for them.

use super::draw::Rect;

/// The (U, V) plane.
pub const PLANE: Rect = Rect {
    x: 0,
    y: 0,
    w: 576,
    h: 800,
};

/// The time slider of a key-frame chain, under the plane.
pub const SLIDER: Rect = Rect {
    x: 72,
    y: 808,
    w: 480,
    h: 20,
};

/// The rendered preview.
pub(crate) const PREVIEW: Rect = Rect {
    x: 608,
    y: 16,
    w: 384,
    h: 384,
};

/// The text beside the plane, under the preview.
pub(crate) const INFO: Rect = Rect {
    x: 592,
    y: 424,
    w: 432,
    h: 400,
};

/// The message line at the bottom.
pub(crate) const STATUS: Rect = Rect {
    x: 0,
    y: 836,
    w: 1024,
    h: 28,
};

/// The whole screen, for text.
pub const SCREEN: Rect = Rect {
    x: 0,
    y: 0,
    w: 1024,
    h: 864,
};

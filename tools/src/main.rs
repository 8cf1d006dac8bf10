//! Tools of the port: the texture raster the decks use, and (later) the
//! speed–accuracy chart and the stability report.
fn main() {}

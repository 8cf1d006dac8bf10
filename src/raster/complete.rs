//! Whether a raster file is there and whole, for `raytrace --resume` (the
//! port's extension, docs/farm.md): a re-run task of a farm skips the
//! outputs an earlier run finished and renders again the ones it did not.
//! A file that is merely present is not enough: a node that died while a
//! file was copied back, or a folder filled up, leaves a file that starts
//! right and stops short.

use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

use super::{parse_header, HEADER_LEN, RMT_NONE, RT_STANDARD};

/// The length of the file [`super::write_sun_raster`] writes for a
/// `width`×`height` raster: the header and the rows padded to 16 bits.
pub fn sun_raster_len(width: usize, height: usize) -> usize {
    HEADER_LEN + (width * 3).div_ceil(2) * 2 * height
}

/// Checks that `path` holds a whole `width`×`height` raster as
/// [`super::write_sun_raster`] writes it (RT_STANDARD, 24 bits, no colour
/// map, `ras_length` the padded rows), followed by exactly `trailer` and
/// nothing else: the header's fields and the file's length are checked,
/// and the trailer's bytes, not the pixels. The error says what is wrong
/// (it does not name the file: callers do).
pub fn check_complete(path: &Path, width: usize, height: usize, trailer: &[u8]) -> Result<(), String> {
    let mut file = File::open(path).map_err(|e| e.to_string())?;
    let found = file.metadata().map_err(|e| e.to_string())?.len();
    let mut head = Vec::with_capacity(HEADER_LEN);
    (&mut file)
        .take(HEADER_LEN as u64)
        .read_to_end(&mut head)
        .map_err(|e| e.to_string())?;
    let h = parse_header(&head).map_err(|e| e.to_string())?;
    let data = sun_raster_len(width, height) - HEADER_LEN;
    let fields = [
        ("width", h.width as usize, width),
        ("height", h.height as usize, height),
        ("depth", h.depth as usize, 24),
        ("type", h.ras_type as usize, RT_STANDARD as usize),
        ("colour map type", h.maptype as usize, RMT_NONE as usize),
        ("colour map length", h.maplength as usize, 0),
        ("length", h.length as usize, data),
    ];
    if let Some((field, got, want)) = fields.iter().find(|(_, got, want)| got != want) {
        return Err(format!("its header's {field} is {got}, not {want}"));
    }
    let expected = (HEADER_LEN + data + trailer.len()) as u64;
    if found != expected {
        return Err(format!("it is {found} bytes long, not {expected}"));
    }
    let mut end = vec![0; trailer.len()];
    file.seek(SeekFrom::Start(expected - trailer.len() as u64))
        .and_then(|_| file.read_exact(&mut end))
        .map_err(|e| e.to_string())?;
    if end != trailer {
        return Err(format!(
            "it does not end in '{}'",
            String::from_utf8_lossy(trailer).trim_end()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::{encode_raster, Raster};
    use super::*;

    fn raster(width: usize, height: usize) -> Raster {
        Raster {
            width,
            height,
            pixels: vec![[1, 2, 3]; width * height],
        }
    }

    #[test]
    fn a_whole_file_is_complete_and_every_shortfall_is_said() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.ras");
        let mut bytes = encode_raster(&raster(5, 3));
        assert_eq!(bytes.len(), sun_raster_len(5, 3));
        bytes.extend_from_slice(b"end\n");
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(check_complete(&path, 5, 3, b"end\n"), Ok(()));
        let says = |w, h, trailer: &[u8]| check_complete(&path, w, h, trailer).unwrap_err();
        assert!(says(5, 3, b"").contains("bytes long"));
        assert!(says(5, 3, b"END\n").contains("does not end in 'END'"));
        assert!(says(4, 3, b"end\n").contains("width is 5, not 4"));
        assert!(says(5, 4, b"end\n").contains("height is 3, not 4"));
        // Cut short: the header is right, the length is not.
        std::fs::write(&path, &bytes[..bytes.len() - 5]).unwrap();
        assert!(
            says(5, 3, b"end\n").contains("79 bytes long, not 84"),
            "{}",
            says(5, 3, b"end\n")
        );
        std::fs::write(&path, &bytes[..20]).unwrap();
        assert!(says(5, 3, b"end\n").contains("truncated"));
        std::fs::write(&path, b"").unwrap();
        assert!(!says(5, 3, b"").is_empty());
        assert!(check_complete(&dir.path().join("none.ras"), 5, 3, b"").is_err());
        // Another kind of raster (a colour map) is not one of ours.
        let mut mapped = encode_raster(&raster(5, 3));
        mapped[27] = 1;
        std::fs::write(&path, &mapped).unwrap();
        assert!(says(5, 3, b"").contains("colour map type is 1"));
    }
}

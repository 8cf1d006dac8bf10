//! Bose's orthogonal arrays of strength 2 (the port's, D48): how the grid
//! samplers tie the first pair of further dimensions (the lens, when a
//! deck has one) to the subpixel's place in its pixel.
//!
//! A pixel's M² subpixels form an M×M grid (column i, row j). Dealing the
//! lens's M×M cells to them at random (Cook 1984) stratifies the lens and
//! the screen each alone, but not the two together, and a defocused
//! surface is seen at about screen + c · lens for a c of either sign: where
//! the blur is about a pixel wide, the randomly paired sums are hardly
//! better than random ones. Cell (i + j, i + 2j) over the field of M
//! elements instead is a bijection of the cells that also takes every
//! (screen column, lens column), (screen column, lens row), (screen row,
//! lens column) and (screen row, lens row) once (Owen 1992, orthogonal
//! array-based Latin hypercubes).

/// The field of M elements the cells can use: M prime (sums and products
/// mod M) or a power of two from 4 to 32 (polynomials over GF(2) modulo
/// the irreducible one given, its top bit M).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Field {
    Prime(usize),
    Binary(usize, usize),
}

impl Field {
    /// The field of `m` elements, `None` where there is no such field with
    /// an element other than 0 and 1 (M = 2: no array of four columns) or
    /// this module does not make it (M = 9, 25, 27).
    pub fn of(m: usize) -> Option<Field> {
        match m {
            4 => Some(Field::Binary(4, 0b111)),
            8 => Some(Field::Binary(8, 0b1011)),
            16 => Some(Field::Binary(16, 0b1_0011)),
            32 => Some(Field::Binary(32, 0b10_0101)),
            _ if m >= 3 && (2..m).all(|p| !m.is_multiple_of(p)) => Some(Field::Prime(m)),
            _ => None,
        }
    }

    /// The cell (i + j, i + 2j) of the subpixel in column `i`, row `j`.
    pub fn cell(self, i: usize, j: usize) -> (usize, usize) {
        match self {
            Field::Prime(m) => ((i + j) % m, (i + 2 * j) % m),
            Field::Binary(m, poly) => {
                let twice = j << 1;
                let twice = if twice & m != 0 { twice ^ poly } else { twice };
                (i ^ j, i ^ twice)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For every M up to 32 with a field: the cells are a bijection of the
    /// subpixels, and each coordinate of the cell with each of the
    /// subpixel's takes every pair once (strength 2).
    #[test]
    fn cells_are_an_orthogonal_array() {
        let fields: Vec<usize> = (2..=32).filter(|&m| Field::of(m).is_some()).collect();
        assert_eq!(fields, [3, 4, 5, 7, 8, 11, 13, 16, 17, 19, 23, 29, 31, 32]);
        for m in fields {
            let f = Field::of(m).unwrap();
            let mut seen = vec![[false; 4]; m * m];
            let mut cells = vec![false; m * m];
            for i in 0..m {
                for j in 0..m {
                    let (c, r) = f.cell(i, j);
                    assert!(c < m && r < m, "m {m}");
                    assert!(!cells[r * m + c], "m {m}: cell ({c}, {r}) twice");
                    cells[r * m + c] = true;
                    for (k, (a, b)) in [(i, c), (i, r), (j, c), (j, r)].into_iter().enumerate() {
                        assert!(!seen[a * m + b][k], "m {m}: projection {k} ({a}, {b}) twice");
                        seen[a * m + b][k] = true;
                    }
                }
            }
        }
    }
}

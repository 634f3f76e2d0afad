//! Height fields: a regular grid of elevations, the input of terrain
//! rendering (`zline_scenes::terrain`), read from files by `zline_io`.
//!
//! Contract: a [`HeightField`] holds `columns × rows` finite heights, row
//! by row from the north edge to the south edge, each row from west to
//! east, with the same horizontal spacing (`cell_size`, > 0) along both
//! axes. [`HeightField::new`] checks all of it and says what is wrong.
//! Normals come from central differences of the grid (one-sided at the
//! border), not from any mesh made of it.

use glam::Vec3;
use thiserror::Error;

/// The most samples a height field may hold (2^26, 8192 × 8192): the
/// terrain mesh builder keeps about 12 bytes per sample of its padded
/// power-of-two grid.
pub const MAX_HEIGHTFIELD_SAMPLES: usize = 1 << 26;

/// Why arrays do not make a valid [`HeightField`].
#[derive(Clone, Debug, PartialEq, Error)]
pub enum HeightFieldError {
    /// Fewer than 2 columns or rows, or more samples than
    /// [`MAX_HEIGHTFIELD_SAMPLES`].
    #[error(
        "a height field of {columns} x {rows} samples is not allowed: it needs at least 2 x 2 and at most \
         {MAX_HEIGHTFIELD_SAMPLES} samples"
    )]
    Size {
        /// Number of columns.
        columns: usize,
        /// Number of rows.
        rows: usize,
    },
    /// The number of heights is not columns × rows.
    #[error("{count} heights given for {columns} x {rows} samples")]
    Count {
        /// Heights given.
        count: usize,
        /// Number of columns.
        columns: usize,
        /// Number of rows.
        rows: usize,
    },
    /// A height is NaN or infinite.
    #[error("the height at column {column}, row {row} is not finite ({value})")]
    NonFinite {
        /// 0-based column.
        column: usize,
        /// 0-based row (from the north).
        row: usize,
        /// The value.
        value: f32,
    },
    /// The cell size is not a finite number > 0.
    #[error("the cell size must be a finite number greater than 0, got {0}")]
    CellSize(f32),
}

/// A grid of heights (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    columns: usize,
    rows: usize,
    heights: Vec<f32>,
    cell_size: f32,
    /// The lowest and highest height, found once.
    range: (f32, f32),
}

impl HeightField {
    /// A height field of `columns × rows` heights, row by row from the
    /// north, with `cell_size` world units between neighbouring samples.
    pub fn new(
        columns: usize,
        rows: usize,
        heights: Vec<f32>,
        cell_size: f32,
    ) -> Result<HeightField, HeightFieldError> {
        let samples = columns.checked_mul(rows);
        if columns < 2 || rows < 2 || samples.is_none_or(|n| n > MAX_HEIGHTFIELD_SAMPLES) {
            return Err(HeightFieldError::Size { columns, rows });
        }
        if heights.len() != columns * rows {
            return Err(HeightFieldError::Count { count: heights.len(), columns, rows });
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(HeightFieldError::NonFinite {
                column: i % columns,
                row: i / columns,
                value: heights[i],
            });
        }
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(HeightFieldError::CellSize(cell_size));
        }
        let range =
            heights.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| (lo.min(h), hi.max(h)));
        Ok(HeightField { columns, rows, heights, cell_size, range })
    }

    /// Number of samples per row (west to east).
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Number of rows (north to south).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The spacing between neighbouring samples, in world units.
    pub fn cell_size(&self) -> f32 {
        self.cell_size
    }

    /// Every height, row by row from the north.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// The height at `column`, `row` (panics outside the grid).
    #[inline]
    pub fn at(&self, column: usize, row: usize) -> f32 {
        self.heights[row * self.columns + column]
    }

    /// The lowest and highest height.
    pub fn range(&self) -> (f32, f32) {
        self.range
    }

    /// The same grid with every height multiplied by `factor` (a vertical
    /// exaggeration, or sample values to world units). Errors when a
    /// product is not finite.
    pub fn scaled(self, factor: f32) -> Result<HeightField, HeightFieldError> {
        let heights = self.heights.iter().map(|h| h * factor).collect();
        HeightField::new(self.columns, self.rows, heights, self.cell_size)
    }

    /// The same grid with another cell size.
    pub fn with_cell_size(self, cell_size: f32) -> Result<HeightField, HeightFieldError> {
        HeightField::new(self.columns, self.rows, self.heights, cell_size)
    }

    /// The unit surface normal at a sample, in the terrain's frame (x east,
    /// y up, z south), from the central differences of the heights
    /// (one-sided on the border): (−∂h/∂x, 1, −∂h/∂z), normalized.
    pub fn normal(&self, column: usize, row: usize) -> Vec3 {
        let (c0, c1) = (column.saturating_sub(1), (column + 1).min(self.columns - 1));
        let (r0, r1) = (row.saturating_sub(1), (row + 1).min(self.rows - 1));
        let dx = (self.at(c1, row) - self.at(c0, row)) / ((c1 - c0) as f32 * self.cell_size);
        let dz = (self.at(column, r1) - self.at(column, r0)) / ((r1 - r0) as f32 * self.cell_size);
        let n = Vec3::new(-dx, 1.0, -dz);
        // Slopes too steep for f32 (dx of 1e38) still give a direction.
        let n = n / n.abs().max_element();
        n.normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_checks_size_count_values_and_cell_size() {
        assert!(HeightField::new(2, 2, vec![0.0; 4], 1.0).is_ok());
        assert_eq!(
            HeightField::new(1, 5, vec![0.0; 5], 1.0),
            Err(HeightFieldError::Size { columns: 1, rows: 5 })
        );
        assert_eq!(
            HeightField::new(2, 3, vec![0.0; 5], 1.0),
            Err(HeightFieldError::Count { count: 5, columns: 2, rows: 3 })
        );
        let mut h = vec![0.0; 6];
        h[5] = f32::NAN;
        assert!(matches!(
            HeightField::new(2, 3, h, 1.0),
            Err(HeightFieldError::NonFinite { column: 1, row: 2, .. })
        ));
        assert_eq!(HeightField::new(2, 2, vec![0.0; 4], 0.0), Err(HeightFieldError::CellSize(0.0)));
    }

    #[test]
    fn normals_are_central_differences() {
        // h = 2x − z (x = column·2, z = row·2): slope 2 east, −1 south.
        let (c, r) = (4, 3);
        let heights =
            (0..r).flat_map(|j| (0..c).map(move |i| 2.0 * (2 * i) as f32 - (2 * j) as f32)).collect();
        let field = HeightField::new(c, r, heights, 2.0).unwrap();
        let expect = Vec3::new(-2.0, 1.0, 1.0).normalize();
        for (i, j) in [(0, 0), (1, 1), (3, 2)] {
            assert!(field.normal(i, j).abs_diff_eq(expect, 1e-6), "{:?}", field.normal(i, j));
        }
    }
}

//! Reference values of planes at samples, computed independently of the
//! crate's `PlaneBasis`: barycentric evaluation from the three vertices with
//! exact integer weights.
//!
//! For a sample s the weights w_k are the edge functions of the edges
//! opposite each vertex, exact in i128; they sum to twice the triangle's
//! area, and inside the triangle they are all ≥ 0, so the value is a convex
//! combination of the vertex values and its evaluation loses almost nothing.

use crate::oracle::{points, sample, side, P};
use crate::shapes::Tri;

/// Exact barycentric weights for one triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Barycentric {
    p: [P; 3],
    /// Twice the signed area, with the sign that makes weights ≥ 0 inside.
    area: i128,
}

/// 2^50: depths are generated as multiples of 2^-50 (see [`Barycentric::depth`]).
pub(crate) const DEPTH_SCALE: f64 = (1u64 << 50) as f64;

impl Barycentric {
    /// `None` for zero area.
    pub(crate) fn new(t: Tri) -> Option<Barycentric> {
        let p = points(t);
        let area = side(p[0], p[1], p[2]);
        (area != 0).then_some(Barycentric { p, area })
    }

    /// The weights of the sample of pixel (col, row), summing to `area`.
    pub(crate) fn weights(&self, col: i32, row: i32) -> [i128; 3] {
        let [a, b, c] = self.p;
        let s = sample(col.into(), row.into());
        let w = [side(b, c, s), side(c, a, s), side(a, b, s)];
        if self.area < 0 {
            w.map(|v| -v)
        } else {
            w
        }
    }

    /// Twice the area, positive.
    pub(crate) fn area(&self) -> i128 {
        self.area.abs()
    }

    /// The depth plane through vertex depths `k[i]`·2^-50 at a sample.
    /// The numerator is exact in i128 (|w| < 2^62, |k| ≤ 2^50), so only the
    /// two conversions to f64 and the division round: the result is within
    /// [`DEPTH_REFERENCE_ERROR`]·|z| of the exact value.
    pub(crate) fn depth(&self, k: [i64; 3], col: i32, row: i32) -> f64 {
        let w = self.weights(col, row);
        let num: i128 = (0..3).map(|i| w[i] * i128::from(k[i])).sum();
        num as f64 / self.area() as f64 / DEPTH_SCALE
    }

    /// An attribute plane through f32 vertex values at a sample, in f64.
    /// Inside the triangle the weights are ≥ 0: the error is a few f64
    /// roundings of max |v|, negligible against f32 error bounds.
    pub(crate) fn value(&self, v: [f32; 3], col: i32, row: i32) -> f64 {
        let w = self.weights(col, row);
        let sum: f64 = (0..3).map(|i| w[i] as f64 * f64::from(v[i])).sum();
        sum / self.area() as f64
    }
}

/// Relative error of [`Barycentric::depth`]: three roundings of 2^-53.
pub(crate) const DEPTH_REFERENCE_ERROR: f64 = 4.0 / (1u64 << 53) as f64;

//! Fog (SPEC §8) for the opaque pass, applied per sample after the tile's
//! opaque pass has settled which surface each sample shows.
//!
//! The fog factor depends only on the fragment's own position, and the
//! opaque pass keeps exactly one fragment per sample — the nearest — so
//! fogging the survivors afterwards gives the same colours as fogging every
//! fragment as it is shaded, without paying for the hidden ones. The eye
//! position is recovered from the stored NC depth and the sample's position
//! through the inverse projection. A scene without fog never runs this.
//!
//! Precision: the stored depth is f32, so near the far plane of a
//! perspective projection the recovered distance carries a relative error of
//! about 2^-24·far/near — 6·10^-5 at far/near = 1000, which moves a fog
//! factor by far less than the 8-bit step. The exponential uses `wide`'s
//! polynomial `exp` (relative error ~10^-7).
//!
//! Samples no fragment reached keep the background: OpenGL fogs fragments,
//! not the clear colour.

use glam::{Mat4, Vec4};
use wide::f32x8;
use zline_scene::{Fog, FogCoordinate, FogMode};

use crate::setup::DepthEncoding;

/// Everything the fog pass needs for one frame.
#[derive(Clone, Copy, Debug)]
pub struct FogPass {
    fog: Fog,
    /// Rows of eye_from_clip (the inverse projection).
    rows: [Vec4; 4],
    /// NC x of column x is x·sx + ox, NC y of row y is y·sy + oy (sample
    /// centres).
    scale: (f32, f32, f32, f32),
}

impl FogPass {
    /// The pass for a frame with this projection, window size (in
    /// samples) and depth encoding. For reversed depth, whose buffer holds
    /// d = (z_nc − 1)/2, the rows take z_nc = 2d + 1, which costs nothing
    /// per sample.
    pub fn new(fog: Fog, clip_from_eye: Mat4, width: u32, height: u32, depth: DepthEncoding) -> FogPass {
        let m = clip_from_eye.inverse().transpose();
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        let mut rows = [m.x_axis, m.y_axis, m.z_axis, m.w_axis];
        if let DepthEncoding::Reversed { .. } = depth {
            for r in &mut rows {
                // z_nc·r.z + r.w = d·(2·r.z) + (r.z + r.w)
                *r = Vec4::new(r.x, r.y, 2.0 * r.z, r.z + r.w);
            }
        }
        FogPass { fog, rows, scale: (2.0 / w, 1.0 / w - 1.0, -2.0 / h, 1.0 - 1.0 / h) }
    }

    /// The fog colour.
    pub fn color(&self) -> glam::Vec3 {
        self.fog.color
    }

    /// Fog factors for eight samples of row `y` starting at column `x`, with
    /// stored depths `z`.
    #[inline]
    pub fn factors(&self, x: i32, y: i32, z: f32x8) -> f32x8 {
        let (sx, ox, sy, oy) = self.scale;
        let lanes = f32x8::from([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let xn = (f32x8::splat(x as f32) + lanes) * f32x8::splat(sx) + f32x8::splat(ox);
        let yn = f32x8::splat(y as f32 * sy + oy);
        let row = |r: Vec4| {
            xn * f32x8::splat(r.x) + yn * f32x8::splat(r.y) + z * f32x8::splat(r.z) + f32x8::splat(r.w)
        };
        let [rx, ry, rz, rw] = self.rows;
        let w = row(rw);
        let distance = match self.fog.coordinate {
            FogCoordinate::EyePlane => -row(rz) / w,
            FogCoordinate::Radial => {
                let (ex, ey, ez) = (row(rx), row(ry), row(rz));
                (ex * ex + ey * ey + ez * ez).sqrt() / w.abs()
            }
        };
        let f = match self.fog.mode {
            FogMode::Linear { start, end } if end == start => {
                use wide::CmpLt;
                distance.cmp_lt(f32x8::splat(start)).blend(f32x8::ONE, f32x8::ZERO)
            }
            FogMode::Linear { start, end } => (f32x8::splat(end) - distance) / f32x8::splat(end - start),
            FogMode::Exponential { density } => (-f32x8::splat(density) * distance).exp(),
            FogMode::SquaredExponential { density } => {
                let d = f32x8::splat(density) * distance;
                (-(d * d)).exp()
            }
        };
        // NaN (a degenerate projection) becomes full fog, as in `Fog::factor`.
        use wide::CmpEq;
        let f = f.cmp_eq(f).blend(f, f32x8::ZERO);
        f.fast_max(f32x8::ZERO).fast_min(f32x8::ONE)
    }
}

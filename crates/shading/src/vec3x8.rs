//! Three coordinates of eight vectors (`Vec3x8`), the lane type the
//! eight-sample lighting (`simd`, `simd_pbr`) works in.

use std::ops::{Add, Mul};

use zline_simd::lanes::{f32x8, Baseline, Level};

/// Three coordinates of eight vectors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3x8<L: Level = Baseline> {
    /// x of each lane.
    pub x: f32x8<L>,
    /// y of each lane.
    pub y: f32x8<L>,
    /// z of each lane.
    pub z: f32x8<L>,
}

impl<L: Level> Vec3x8<L> {
    /// The same lanes at level `M`.
    #[inline(always)]
    pub fn at<M: Level>(self) -> Vec3x8<M> {
        Vec3x8 { x: self.x.at(), y: self.y.at(), z: self.z.at() }
    }

    /// Every lane set to `v`.
    #[inline(always)]
    pub fn splat(v: glam::Vec3) -> Vec3x8<L> {
        Vec3x8 { x: f32x8::splat(v.x), y: f32x8::splat(v.y), z: f32x8::splat(v.z) }
    }

    #[inline(always)]
    pub(crate) fn dot(self, o: Vec3x8<L>) -> f32x8<L> {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    pub(crate) fn scale(self, s: f32x8<L>) -> Vec3x8<L> {
        Vec3x8 { x: self.x * s, y: self.y * s, z: self.z * s }
    }

    /// Every lane clamped to [0, 1] (NaN becomes 0, as `Vec3::clamp` after
    /// `max`).
    #[inline(always)]
    pub fn clamp01(self) -> Vec3x8<L> {
        let clamp = zline_simd::inlined(
            #[inline(always)]
            |c: f32x8<L>| c.clamp(f32x8::ZERO, f32x8::ONE),
        );
        Vec3x8 { x: clamp(self.x), y: clamp(self.y), z: clamp(self.z) }
    }

    /// Every lane clamped to [0, `ceiling`] (NaN becomes 0); with a
    /// ceiling of 1 the same operations as [`Self::clamp01`]. `ceiling`
    /// must not be NaN (`f32x8::clamp`'s bounds; the kernels pass
    /// `PreparedLights::ceiling`, 1 or `f32::MAX`).
    #[inline(always)]
    pub fn clamp_to(self, ceiling: f32) -> Vec3x8<L> {
        debug_assert!(!ceiling.is_nan(), "a NaN ceiling");
        let top = f32x8::splat(ceiling);
        let clamp = zline_simd::inlined(
            #[inline(always)]
            |c: f32x8<L>| c.clamp(f32x8::ZERO, top),
        );
        Vec3x8 { x: clamp(self.x), y: clamp(self.y), z: clamp(self.z) }
    }

    #[inline(always)]
    pub(crate) fn sub(self, o: Vec3x8<L>) -> Vec3x8<L> {
        Vec3x8 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }

    #[inline(always)]
    pub(crate) fn div(self, s: f32x8<L>) -> Vec3x8<L> {
        Vec3x8 { x: self.x / s, y: self.y / s, z: self.z / s }
    }

    /// glam's `normalize_or_zero`: v / |v|, or 0 where 1/|v| is not a
    /// finite positive number.
    #[inline(always)]
    pub fn normalize_or_zero(self) -> Vec3x8<L> {
        let rcp = f32x8::ONE / self.dot(self).sqrt();
        let ok = rcp.is_finite() & rcp.cmp_gt(f32x8::ZERO);
        let n = self.scale(rcp);
        Vec3x8 { x: ok.blend(n.x, f32x8::ZERO), y: ok.blend(n.y, f32x8::ZERO), z: ok.blend(n.z, f32x8::ZERO) }
    }

    /// `where mask { self } else { 0 }` per lane.
    #[inline(always)]
    pub(crate) fn keep(self, mask: f32x8<L>) -> Vec3x8<L> {
        Vec3x8 {
            x: mask.blend(self.x, f32x8::ZERO),
            y: mask.blend(self.y, f32x8::ZERO),
            z: mask.blend(self.z, f32x8::ZERO),
        }
    }

    /// The lanes as three arrays (x, y, z).
    #[inline(always)]
    pub(crate) fn to_lanes(self) -> [[f32; 8]; 3] {
        [self.x.to_array(), self.y.to_array(), self.z.to_array()]
    }

    /// Eight vectors from three arrays of coordinates.
    #[inline(always)]
    pub(crate) fn from_arrays([x, y, z]: [[f32; 8]; 3]) -> Vec3x8<L> {
        Vec3x8 { x: f32x8::from(x), y: f32x8::from(y), z: f32x8::from(z) }
    }

    /// Lane `i` as a glam vector.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> glam::Vec3 {
        glam::Vec3::new(self.x.as_array_ref()[i], self.y.as_array_ref()[i], self.z.as_array_ref()[i])
    }
}

impl<L: Level> Add for Vec3x8<L> {
    type Output = Vec3x8<L>;

    /// Lane-wise sum.
    #[inline(always)]
    fn add(self, o: Vec3x8<L>) -> Vec3x8<L> {
        Vec3x8 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
}

impl<L: Level> Mul for Vec3x8<L> {
    type Output = Vec3x8<L>;

    /// Lane-wise product.
    #[inline(always)]
    fn mul(self, o: Vec3x8<L>) -> Vec3x8<L> {
        Vec3x8 { x: self.x * o.x, y: self.y * o.y, z: self.z * o.z }
    }
}

/// A mask with every lane set.
#[inline(always)]
pub(crate) fn all_lanes<L: Level>() -> f32x8<L> {
    f32x8::from([f32::from_bits(u32::MAX); 8])
}

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

use std::marker::PhantomData;

use glam::{Mat4, Vec4};
use zline_scene::{Fog, FogCoordinate, FogMode};
use zline_simd::lanes::{f32x8, Level};

use crate::setup::DepthEncoding;

/// Everything the fog pass needs for one frame.
#[derive(Clone, Copy, Debug)]
pub struct FogPass {
    fog: Fog,
    /// The falloff of `fog.mode`, decided once per frame (not per block).
    falloff: Falloffs,
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
        FogPass {
            fog,
            falloff: Falloffs::new(fog.mode),
            rows,
            scale: (2.0 / w, 1.0 / w - 1.0, -2.0 / h, 1.0 - 1.0 / h),
        }
    }

    /// The fog colour.
    pub fn color(&self) -> glam::Vec3 {
        self.fog.color
    }

    /// Fog factors for eight samples of row `y` starting at column `x`, with
    /// stored depths `z` (the coordinate and falloff tested per call; a pass
    /// over many blocks uses [`Self::specialized`] instead).
    #[inline(always)]
    pub fn factors<S: Level>(&self, x: i32, y: i32, z: f32x8<S>) -> f32x8<S> {
        match self.fog.coordinate {
            FogCoordinate::EyePlane => self.factors_with::<EyePlane, _>(self.falloff, x, y, z),
            FogCoordinate::Radial => self.factors_with::<Radial, _>(self.falloff, x, y, z),
        }
    }

    /// Runs `visitor` with this fog's factors as a type: the coordinate and
    /// the mode are decided here, once, not per block.
    pub fn specialized<V: FogVisitor>(&self, visitor: V) -> V::Output {
        let falloff = self.falloff;
        match self.fog.coordinate {
            FogCoordinate::EyePlane => self.specialized_with::<EyePlane, V>(falloff, visitor),
            FogCoordinate::Radial => self.specialized_with::<Radial, V>(falloff, visitor),
        }
    }

    /// [`Self::specialized`] once the coordinate is a type: the falloff
    /// becomes one too.
    fn specialized_with<C: Coordinate, V: FogVisitor>(&self, falloff: Falloffs, visitor: V) -> V::Output {
        fn visit<C: Coordinate, M: Falloff, V: FogVisitor>(
            pass: &FogPass,
            falloff: M,
            visitor: V,
        ) -> V::Output {
            visitor.visit(Specialized::<C, M> { pass, falloff, coordinate: PhantomData })
        }
        match falloff {
            Falloffs::Step(f) => visit::<C, _, V>(self, f, visitor),
            Falloffs::Linear(f) => visit::<C, _, V>(self, f, visitor),
            Falloffs::Exp(f) => visit::<C, _, V>(self, f, visitor),
            Falloffs::Exp2(f) => visit::<C, _, V>(self, f, visitor),
        }
    }

    /// The factors with the coordinate `C` and the falloff `falloff`.
    #[inline(always)]
    fn factors_with<C: Coordinate, S: Level>(
        &self,
        falloff: impl Falloff,
        x: i32,
        y: i32,
        z: f32x8<S>,
    ) -> f32x8<S> {
        let (sx, ox, sy, oy) = self.scale;
        let lanes = f32x8::from([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let xn = (f32x8::splat(x as f32) + lanes) * f32x8::splat(sx) + f32x8::splat(ox);
        let yn = f32x8::splat(y as f32 * sy + oy);
        let row = zline_simd::inlined(
            #[inline(always)]
            |r: Vec4| {
                xn * f32x8::splat(r.x) + yn * f32x8::splat(r.y) + z * f32x8::splat(r.z) + f32x8::splat(r.w)
            },
        );
        let f = falloff.factor(C::distance(&self.rows, row));
        // NaN (a degenerate projection) becomes full fog, as in
        // `Fog::factor`: `clamp` turns it into its lower bound, 0.
        f.clamp(f32x8::ZERO, f32x8::ONE)
    }
}

/// Fog factors with the coordinate and mode fixed by type.
pub trait FogFactors {
    /// Factors for eight samples of row `y` from column `x` with depths `z`.
    fn at<S: Level>(&self, x: i32, y: i32, z: f32x8<S>) -> f32x8<S>;
}

/// Work generic over a fog's [`FogFactors`] (see [`FogPass::specialized`]).
pub trait FogVisitor {
    /// What the work returns.
    type Output;
    /// Does the work with `factors`.
    fn visit<F: FogFactors>(self, factors: F) -> Self::Output;
}

/// A [`FogPass`] with its coordinate `C` and falloff `M` as types.
struct Specialized<'a, C, M> {
    pass: &'a FogPass,
    falloff: M,
    coordinate: PhantomData<C>,
}

impl<C: Coordinate, M: Falloff> FogFactors for Specialized<'_, C, M> {
    #[inline(always)]
    fn at<S: Level>(&self, x: i32, y: i32, z: f32x8<S>) -> f32x8<S> {
        self.pass.factors_with::<C, _>(self.falloff, x, y, z)
    }
}

/// How the fog coordinate comes from the recovered eye position.
trait Coordinate {
    /// The distance, given the rows of eye_from_clip and `row(r)` = r·(x, y, z, 1).
    fn distance<S: Level>(rows: &[Vec4; 4], row: impl Fn(Vec4) -> f32x8<S>) -> f32x8<S>;
}

/// The eye-plane distance −z_eye.
struct EyePlane;

/// The radial distance |p_eye|.
struct Radial;

impl Coordinate for EyePlane {
    #[inline(always)]
    fn distance<S: Level>(rows: &[Vec4; 4], row: impl Fn(Vec4) -> f32x8<S>) -> f32x8<S> {
        let w = row(rows[3]);
        -row(rows[2]) / w
    }
}

impl Coordinate for Radial {
    #[inline(always)]
    fn distance<S: Level>(rows: &[Vec4; 4], row: impl Fn(Vec4) -> f32x8<S>) -> f32x8<S> {
        let w = row(rows[3]);
        let (ex, ey, ez) = (row(rows[0]), row(rows[1]), row(rows[2]));
        (ex * ex + ey * ey + ez * ez).sqrt() / w.abs()
    }
}

/// The fog factor as a function of distance (SPEC §8), before the clamp.
trait Falloff: Copy {
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S>;
}

/// Linear fog with start = end: a step.
#[derive(Clone, Copy, Debug)]
struct Step {
    start: f32,
}

/// Linear fog.
#[derive(Clone, Copy, Debug)]
struct Linear {
    start: f32,
    end: f32,
}

/// Exponential fog.
#[derive(Clone, Copy, Debug)]
struct Exp {
    density: f32,
}

/// Squared exponential fog.
#[derive(Clone, Copy, Debug)]
struct Exp2 {
    density: f32,
}

/// Any of the four, chosen per call.
#[derive(Clone, Copy, Debug)]
enum Falloffs {
    Step(Step),
    Linear(Linear),
    Exp(Exp),
    Exp2(Exp2),
}

impl Falloffs {
    #[inline(always)]
    fn new(mode: FogMode) -> Falloffs {
        match mode {
            FogMode::Linear { start, end } if end == start => Falloffs::Step(Step { start }),
            FogMode::Linear { start, end } => Falloffs::Linear(Linear { start, end }),
            FogMode::Exponential { density } => Falloffs::Exp(Exp { density }),
            FogMode::SquaredExponential { density } => Falloffs::Exp2(Exp2 { density }),
        }
    }
}

impl Falloff for Step {
    #[inline(always)]
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S> {
        distance.cmp_lt(f32x8::splat(self.start)).blend(f32x8::ONE, f32x8::ZERO)
    }
}

impl Falloff for Linear {
    #[inline(always)]
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S> {
        (f32x8::splat(self.end) - distance) / f32x8::splat(self.end - self.start)
    }
}

impl Falloff for Exp {
    #[inline(always)]
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S> {
        (-f32x8::splat(self.density) * distance).exp()
    }
}

impl Falloff for Exp2 {
    #[inline(always)]
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S> {
        let d = f32x8::splat(self.density) * distance;
        (-(d * d)).exp()
    }
}

impl Falloff for Falloffs {
    #[inline(always)]
    fn factor<S: Level>(self, distance: f32x8<S>) -> f32x8<S> {
        match self {
            Falloffs::Step(f) => f.factor(distance),
            Falloffs::Linear(f) => f.factor(distance),
            Falloffs::Exp(f) => f.factor(distance),
            Falloffs::Exp2(f) => f.factor(distance),
        }
    }
}

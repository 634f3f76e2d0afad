//! Setup's output: the primitives of a frame in typed tables, one table per
//! kernel, and the draw list that says which kernel draws each primitive.
//!
//! Every kernel has its own plane set (the [`layout`] constants name each
//! plane's index), so a primitive carries exactly the attributes its kernel
//! reads: a flat triangle none, a Gouraud one four planes, a textured flat
//! one three.

use glam::Vec3;
use zline_raster::{AttributePlanes, DepthPlane, EdgeTable, Rect};
use zline_scene::{GouraudClamp, Interpolation, NormalEncoding};

/// The plane sets of the kernels: the index of each attribute in a
/// primitive's [`AttributePlanes`], and their count. Plane `Q` is 1/w when
/// interpolation is perspective-correct (every other plane then holds a/w)
/// and 1 when it is screen-linear.
pub mod layout {
    /// Gouraud: the lit colour (clamped at the vertices or not, as
    /// [`super::Kernel::Gouraud`]'s `clamp` says).
    pub mod gouraud {
        /// 1/w.
        pub const Q: usize = 0;
        /// Colour r, g, b.
        pub const COLOR: usize = 1;
        /// Planes.
        pub const LEN: usize = 4;
    }
    /// Phong: the normal and the eye-space position, and for meshes with
    /// vertex colours the colour after them.
    pub mod phong {
        /// 1/w.
        pub const Q: usize = 0;
        /// Normal x, y, z.
        pub const NORMAL: usize = 1;
        /// Eye position x, y, z.
        pub const EYE: usize = 4;
        /// Planes without vertex colours.
        pub const LEN: usize = 7;
        /// Vertex colour r, g, b.
        pub const COLOR: usize = 7;
        /// Planes with vertex colours.
        pub const COLORED_LEN: usize = 10;
    }
    /// Textured kernels: texture coordinates first, then what the lighting
    /// interpolates.
    pub mod textured {
        /// 1/w.
        pub const Q: usize = 0;
        /// Texture coordinate s.
        pub const S: usize = 1;
        /// Texture coordinate t.
        pub const T: usize = 2;
        /// Planes of textured flat (lit once: nothing else).
        pub const FLAT_LEN: usize = 3;
        /// Textured Gouraud: ambient+diffuse part r, g, b.
        pub const AMBIENT_DIFFUSE: usize = 3;
        /// Textured Gouraud: specular part r, g, b.
        pub const SPECULAR: usize = 6;
        /// Planes of textured Gouraud.
        pub const GOURAUD_LEN: usize = 9;
        /// Textured Phong: normal x, y, z.
        pub const NORMAL: usize = 3;
        /// Textured Phong: eye position x, y, z.
        pub const EYE: usize = 6;
        /// Planes of textured Phong.
        pub const PHONG_LEN: usize = 9;
        /// Textured Phong with vertex colours: colour r, g, b.
        pub const COLOR: usize = 9;
        /// Planes of textured Phong with vertex colours.
        pub const COLORED_PHONG_LEN: usize = 12;
    }
    /// Phong with a bump or normal map, textured or not: the textured
    /// Phong planes (the map's coordinates are s and t), then the tangent
    /// frame.
    pub mod perturbed {
        pub use super::textured::{EYE, NORMAL, Q, S, T};
        /// Eye-space tangent T x, y, z.
        pub const TANGENT: usize = 9;
        /// Eye-space bitangent B = w·(N × T) x, y, z (formed per vertex).
        pub const BITANGENT: usize = 12;
        /// Planes.
        pub const LEN: usize = 15;
    }
}

/// A triangle ready for any tile: coverage, depth, and the data of the
/// kernel that shades it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Primitive<S> {
    /// Coverage.
    pub edges: EdgeTable,
    /// Depth, as [`super::DepthEncoding`] encodes it.
    pub depth: DepthPlane,
    /// What the kernel reads.
    pub shader: S,
}

/// Flat: one colour for the whole triangle (lit at the centroid, SPEC §6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flat {
    /// The clamped colour.
    pub color: Vec3,
}

/// Gouraud: interpolated vertex colours ([`layout::gouraud`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gouraud {
    /// The planes.
    pub planes: AttributePlanes<{ layout::gouraud::LEN }>,
}

/// Phong: the lighting model per sample ([`layout::phong`]); `N` is
/// [`layout::phong::LEN`], or [`layout::phong::COLORED_LEN`] with vertex
/// colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phong<const N: usize> {
    /// The planes.
    pub planes: AttributePlanes<N>,
    /// Index into the frame's material table.
    pub material: u32,
}

/// Textured flat: the parts lit once at the centroid, the texel per sample
/// (SPEC §7: c = texel ⊙ (ambient+diffuse) + specular).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturedFlat {
    /// The planes ([`layout::textured`], texture coordinates only).
    pub planes: AttributePlanes<{ layout::textured::FLAT_LEN }>,
    /// The ambient+diffuse part.
    pub ambient_diffuse: Vec3,
    /// The specular part.
    pub specular: Vec3,
    /// Index into the frame's texture table.
    pub texture: u32,
}

/// Textured Gouraud: the parts lit at the vertices and interpolated apart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturedGouraud {
    /// The planes ([`layout::textured`]).
    pub planes: AttributePlanes<{ layout::textured::GOURAUD_LEN }>,
    /// Index into the frame's texture table.
    pub texture: u32,
}

/// Textured Phong: the parts lit per sample; `N` is
/// [`layout::textured::PHONG_LEN`], or
/// [`layout::textured::COLORED_PHONG_LEN`] with vertex colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturedPhong<const N: usize> {
    /// The planes ([`layout::textured`]).
    pub planes: AttributePlanes<N>,
    /// Index into the frame's texture table.
    pub texture: u32,
    /// Index into the frame's material table.
    pub material: u32,
}

/// Phong with a bump or normal map (`zline_scene::NormalMap`), with or
/// without a diffuse texture ([`layout::perturbed`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perturbed {
    /// The planes.
    pub planes: AttributePlanes<{ layout::perturbed::LEN }>,
    /// Index into the frame's material table.
    pub material: u32,
    /// The map's index in the frame's texture table.
    pub map: u32,
    /// The map's scale k.
    pub scale: f32,
    /// The diffuse texture's index in the frame's texture table (unread
    /// by the untextured kernel).
    pub texture: u32,
}

/// How a textured kernel finds its level of detail: decided by the
/// texture's filter, once per primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelOfDetail {
    /// Level 0 always (nearest and bilinear filtering).
    Base,
    /// From the exact per-sample derivatives of s and t (trilinear).
    Derivatives,
}

/// What a textured kernel does with the texel's alpha: decided by the
/// texture's alpha mode, once per primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlphaUse {
    /// Ignored (glTF OPAQUE, OBJ).
    Ignore,
    /// Samples below the texture's cutoff are discarded before they write
    /// depth (glTF MASK).
    Mask,
    /// Multiplies the material's opacity in the transparency pass (glTF
    /// BLEND).
    Blend,
}

/// Which lighting a textured kernel combines with the texel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexturedLighting {
    /// [`TexturedFlat`].
    Flat,
    /// [`TexturedGouraud`].
    Gouraud,
    /// [`TexturedPhong`] without vertex colours.
    Phong,
    /// [`TexturedPhong`] with vertex colours.
    ColoredPhong,
}

/// The kernel that draws a primitive: every per-sample decision, made once
/// in setup. Each variant names the table its primitive lives in
/// ([`KernelTables`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// [`Flat`] (no attributes, so no interpolation).
    Flat,
    /// [`Gouraud`].
    Gouraud {
        /// How attributes are interpolated.
        interpolation: Interpolation,
        /// [`GouraudClamp::PerVertex`]: the colours were clamped at the
        /// vertices and are drawn as interpolated;
        /// [`GouraudClamp::PerSample`]: each sample's colour is clamped.
        clamp: GouraudClamp,
    },
    /// [`Phong`] without vertex colours.
    Phong(Interpolation),
    /// [`Phong`] with vertex colours.
    ColoredPhong(Interpolation),
    /// A textured kernel.
    Textured {
        /// The lighting combined with the texel.
        lighting: TexturedLighting,
        /// How attributes are interpolated.
        interpolation: Interpolation,
        /// How the level of detail is found.
        lod: LevelOfDetail,
        /// What the texel's alpha does.
        alpha: AlphaUse,
    },
    /// [`Perturbed`]: Phong (without vertex colours) with a bump or normal
    /// map.
    Perturbed {
        /// What the map holds.
        encoding: NormalEncoding,
        /// How attributes are interpolated.
        interpolation: Interpolation,
        /// The diffuse texture's level of detail and alpha use, or `None`
        /// untextured.
        texture: Option<(LevelOfDetail, AlphaUse)>,
    },
}

/// One table per kernel (see [`Kernel`]); a [`Draw`] indexes the table its
/// kernel names.
#[derive(Clone, Debug, Default)]
pub struct KernelTables {
    /// [`Kernel::Flat`].
    pub flat: Vec<Primitive<Flat>>,
    /// [`Kernel::Gouraud`].
    pub gouraud: Vec<Primitive<Gouraud>>,
    /// [`Kernel::Phong`].
    pub phong: Vec<Primitive<Phong<{ layout::phong::LEN }>>>,
    /// [`Kernel::ColoredPhong`].
    pub colored_phong: Vec<Primitive<Phong<{ layout::phong::COLORED_LEN }>>>,
    /// [`TexturedLighting::Flat`].
    pub textured_flat: Vec<Primitive<TexturedFlat>>,
    /// [`TexturedLighting::Gouraud`].
    pub textured_gouraud: Vec<Primitive<TexturedGouraud>>,
    /// [`TexturedLighting::Phong`].
    pub textured_phong: Vec<Primitive<TexturedPhong<{ layout::textured::PHONG_LEN }>>>,
    /// [`TexturedLighting::ColoredPhong`].
    pub textured_colored_phong: Vec<Primitive<TexturedPhong<{ layout::textured::COLORED_PHONG_LEN }>>>,
    /// [`Kernel::Perturbed`].
    pub perturbed: Vec<Primitive<Perturbed>>,
}

impl KernelTables {
    /// Asks for the cache lines of primitive `index` of `kernel`'s table
    /// (a hint, `zline_simd::prefetch`; nothing when there is none).
    #[inline(always)]
    pub(crate) fn prefetch(&self, kernel: Kernel, index: u32) {
        let i = index as usize;
        match kernel {
            Kernel::Flat => self.flat.get(i).map(zline_simd::prefetch),
            Kernel::Gouraud { .. } => self.gouraud.get(i).map(zline_simd::prefetch),
            Kernel::Phong(_) => self.phong.get(i).map(zline_simd::prefetch),
            Kernel::ColoredPhong(_) => self.colored_phong.get(i).map(zline_simd::prefetch),
            Kernel::Textured { lighting, .. } => match lighting {
                TexturedLighting::Flat => self.textured_flat.get(i).map(zline_simd::prefetch),
                TexturedLighting::Gouraud => self.textured_gouraud.get(i).map(zline_simd::prefetch),
                TexturedLighting::Phong => self.textured_phong.get(i).map(zline_simd::prefetch),
                TexturedLighting::ColoredPhong => {
                    self.textured_colored_phong.get(i).map(zline_simd::prefetch)
                }
            },
            Kernel::Perturbed { .. } => self.perturbed.get(i).map(zline_simd::prefetch),
        };
    }

    /// The edge table of primitive `index` of `kernel`'s table.
    pub(crate) fn edges(&self, kernel: Kernel, index: u32) -> &zline_raster::EdgeTable {
        self.coverage(kernel, index).0
    }

    /// The edge table and depth plane of primitive `index` of `kernel`'s
    /// table.
    pub(crate) fn coverage(&self, kernel: Kernel, index: u32) -> (&zline_raster::EdgeTable, &DepthPlane) {
        fn of<S>(p: &Primitive<S>) -> (&zline_raster::EdgeTable, &DepthPlane) {
            (&p.edges, &p.depth)
        }
        let i = index as usize;
        match kernel {
            Kernel::Flat => of(&self.flat[i]),
            Kernel::Gouraud { .. } => of(&self.gouraud[i]),
            Kernel::Phong(_) => of(&self.phong[i]),
            Kernel::ColoredPhong(_) => of(&self.colored_phong[i]),
            Kernel::Textured { lighting, .. } => match lighting {
                TexturedLighting::Flat => of(&self.textured_flat[i]),
                TexturedLighting::Gouraud => of(&self.textured_gouraud[i]),
                TexturedLighting::Phong => of(&self.textured_phong[i]),
                TexturedLighting::ColoredPhong => of(&self.textured_colored_phong[i]),
            },
            Kernel::Perturbed { .. } => of(&self.perturbed[i]),
        }
    }

    fn clear(&mut self) {
        self.flat.clear();
        self.gouraud.clear();
        self.phong.clear();
        self.colored_phong.clear();
        self.textured_flat.clear();
        self.textured_gouraud.clear();
        self.textured_phong.clear();
        self.textured_colored_phong.clear();
        self.perturbed.clear();
    }
}

/// One primitive in draw order: its kernel and its index in that kernel's
/// table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draw {
    /// The kernel.
    pub kernel: Kernel,
    /// Index in the kernel's table.
    pub index: u32,
    /// The mean NC depth of the vertices: the back-to-front sort key of the
    /// transparency pass.
    pub sort_depth: f32,
    /// The largest NC depth of the vertices: the back-to-front sort key of
    /// the painter's algorithm (`tile::painter`).
    pub far_depth: f32,
}

/// Which pass draws a chunk's primitives (a chunk holds one object's
/// triangles).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PassKind {
    /// The opaque pass: depth written, colour replaced.
    #[default]
    Opaque,
    /// The transparency pass (SPEC §9): blended with opacity 1 − kt
    /// (times the texel's alpha for textures whose alpha blends), depth
    /// tested but not written.
    Transparent {
        /// The material's transparency kt = 1 − opacity.
        kt: f32,
    },
    /// A planar shadow (`crate::shadow`): not drawn, but rasterized into
    /// the tile's shadow mask before the opaque pass, setting `bit`.
    Shadow {
        /// The mask bit of its (receiving plane, light) pair, below 32.
        bit: u32,
    },
}

/// The primitives set up by one task, in draw order, with their bounds kept
/// apart so binning reads 16 bytes per primitive instead of the whole
/// primitive.
#[derive(Clone, Debug, Default)]
pub struct PrimitiveChunk {
    /// The primitives in draw order.
    pub draws: Vec<Draw>,
    /// `draws[i]`'s bounds.
    pub bounds: Vec<Rect>,
    /// The pass that draws them.
    pub pass: PassKind,
    /// The kernels' data.
    pub tables: KernelTables,
    /// The object whose triangles these are (its index in the scene).
    pub object: u32,
    /// The mesh's index of the chunk's first triangle.
    pub first_triangle: u32,
    /// Only when the pixel inspector asks (empty otherwise): per triangle
    /// of the chunk, `draws.len()` after it was set up, so that draw `d`
    /// came from the first triangle whose end is above `d`.
    pub triangle_ends: Vec<u32>,
}

impl PrimitiveChunk {
    /// Empties the chunk for a new frame, keeping its capacity.
    pub fn reset(&mut self, pass: PassKind) {
        self.draws.clear();
        self.bounds.clear();
        self.tables.clear();
        self.triangle_ends.clear();
        self.pass = pass;
    }

    /// Appends a primitive to `table`, to the draw list and its bounds
    /// (inlined so the primitive is built in place, not copied).
    #[inline(always)]
    pub(crate) fn push<S>(
        (draws, bounds): (&mut Vec<Draw>, &mut Vec<Rect>),
        table: &mut Vec<Primitive<S>>,
        kernel: Kernel,
        primitive: Primitive<S>,
        (sort_depth, far_depth): (f32, f32),
    ) {
        draws.push(Draw { kernel, index: table.len() as u32, sort_depth, far_depth });
        bounds.push(primitive.edges.bounds());
        table.push(primitive);
    }
}

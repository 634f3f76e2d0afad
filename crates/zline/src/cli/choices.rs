//! The named choices of the command line's flags (`--shading`,
//! `--filter`, `--shadows`, …) as clap value enums, and the built-in
//! scenes of `zline demo`.

use clap::ValueEnum;
use zline::scene::{Scene, ShadowMode};
use zline::shading::{Distribution, ModelChoice};

/// The built-in scenes of `zline demo --scene`.
#[derive(Clone, Copy, PartialEq, Eq, Debug, ValueEnum)]
pub(crate) enum BuiltIn {
    /// The demo scene (the default).
    Demo,
    /// The room lit by a lamp, with planar shadows on the floor.
    Room,
    /// Whitted's scene: a checkerboard floor, a mirror sphere and a glass
    /// sphere (made for --renderer raytrace).
    Whitted,
}

impl BuiltIn {
    pub(crate) fn scene(self) -> Scene {
        match self {
            BuiltIn::Demo => zline::scenes::demo_scene(),
            BuiltIn::Room => zline::scenes::room_scene(),
            BuiltIn::Whitted => zline::scenes::whitted_scene(),
        }
    }

    pub(crate) fn name(self) -> &'static str {
        match self {
            BuiltIn::Demo => "demo",
            BuiltIn::Room => "room",
            BuiltIn::Whitted => "whitted",
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Shading {
    Flat,
    Gouraud,
    Phong,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum TexFilter {
    /// The nearest texel.
    Nearest,
    /// Bilinear on the full-size texture.
    Bilinear,
    /// Bilinear on the two nearest mip levels, blended.
    Trilinear,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum FogCoord {
    /// −z in eye space (the default).
    EyePlane,
    /// |p| in eye space.
    Radial,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Depth {
    /// Normalized depth in [−1, 1], as OpenGL's classic depth buffer (the default).
    Normalized,
    /// Reversed depth in f32: far more precise far from the camera.
    Reversed,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Clamp {
    /// At each vertex, then interpolated (fixed-function GL; the default).
    Vertex,
    /// The unclamped colour interpolated, clamped per sample.
    Sample,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Sides {
    /// Normals turned towards the viewer (the default).
    TwoSided,
    /// Normals as given.
    OneSided,
}

/// The names are [`ShadowMode::name`]'s.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Shadows {
    /// No shadows (the default).
    None,
    /// Projected onto the scene's shadow planes from each light.
    Planar,
    /// Shadow maps: a depth image from each light; every object casts and
    /// receives.
    Map,
}

/// `--shadow-filter`: [`zline::scene::Shadows::pcf`].
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum ShadowFilter {
    /// 3×3 percentage-closer filtering: soft-edged (the default).
    Pcf,
    /// The one nearest texel: hard-edged.
    Nearest,
}

impl From<Shadows> for ShadowMode {
    fn from(s: Shadows) -> ShadowMode {
        match s {
            Shadows::None => ShadowMode::None,
            Shadows::Planar => ShadowMode::Planar,
            Shadows::Map => ShadowMode::Map,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Interp {
    /// Perspective-correct (a/w and 1/w).
    Perspective,
    /// Screen-linear: attributes interpolated in the window without perspective correction.
    Linear,
}

/// `--tonemap`: the operator before quantization (SPEC §10).
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum Tonemap {
    /// Clamp to [0, 1], as without the flag.
    None,
    /// Khronos PBR Neutral, then sRGB (the glTF Sample Viewer's default).
    KhrPbrNeutral,
    /// ACES filmic (Hill's fit), then sRGB.
    Aces,
}

impl From<Tonemap> for zline::shading::ToneMap {
    fn from(t: Tonemap) -> zline::shading::ToneMap {
        match t {
            Tonemap::None => zline::shading::ToneMap::None,
            Tonemap::KhrPbrNeutral => zline::shading::ToneMap::KhrPbrNeutral,
            Tonemap::Aces => zline::shading::ToneMap::Aces,
        }
    }
}

/// `--model`: the reflection model forced on every material
/// ([`zline::shading::Material::with_model`]).
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum LightModel {
    /// The basic model (SPEC §5.1); a Cook–Torrance material keeps kd and
    /// takes the closest ks and ns.
    Basic,
    /// Cook–Torrance with the GGX distribution (SPEC §5.2); a basic
    /// material becomes a dielectric with the roughness closest to its ns,
    /// a Cook–Torrance one keeps its metallic and roughness.
    CookTorrance,
    /// Cook–Torrance with the Beckmann distribution, likewise.
    Beckmann,
}

impl From<LightModel> for ModelChoice {
    fn from(m: LightModel) -> ModelChoice {
        match m {
            LightModel::Basic => ModelChoice::Basic,
            LightModel::CookTorrance => ModelChoice::CookTorrance(Distribution::Ggx),
            LightModel::Beckmann => ModelChoice::CookTorrance(Distribution::Beckmann),
        }
    }
}

/// `--projection`.
#[derive(Clone, Copy, PartialEq, Eq, Debug, ValueEnum)]
pub(crate) enum ProjectionName {
    /// Perspective.
    Perspective,
    /// Orthographic (parallel).
    Ortho,
}

//! The lighting model of zline (SPEC §5–6): pure functions of one sample's
//! inputs — position, normal, material, lights — returning a colour.
//!
//! This crate knows nothing of triangles, screens, files or threads. All
//! vectors handed to [`LightingModel::shade`] must be in one space; the
//! pipeline uses eye space, where the viewer sits at the origin.

mod environment;
mod fog;
mod light;
mod material;
mod model;
mod pbr;
mod prepared;
mod simd;
mod simd_pbr;
mod split_sum_data;
mod texture;
mod tonemap;
mod vec3x8;

pub use environment::{
    octahedral_decode, octahedral_encode, sh_basis, sky_radiance, texel_solid_angles, Environment,
    EnvironmentLight, OctahedralMap, Panorama, PanoramaError, PreparedEnvironment, MAX_PANORAMA_SIDE,
    PREFILTER_LEVELS, SH_COEFFICIENTS, SKY_SUN,
};
pub use fog::{Fog, FogCoordinate, FogMode};
pub use light::{Attenuation, Cone, Light};
pub use material::{Material, Model, ModelChoice};
pub use model::{LightingModel, LitParts};
pub use pbr::{
    directional_albedo, split_sum, split_sum_entries, split_sum_entry, split_sum_table, Distribution,
    Microfacet, DIELECTRIC_F0, MIN_ALPHA2, SPLIT_SUM_SIZE,
};
pub use prepared::{PreparedLights, PreparedMaterial, Shininess, Surface, SPECULAR_CUTOFF};
pub use simd::Vec3x8;
pub use simd_pbr::MapTexels;
pub use texture::{lod, Filter, Sampler, Texture, TextureError, Wrap, MAX_TEXTURE_SIZE};
pub use tonemap::{ToneMap, ToneMapping};

/// How a triangle's colour is spread over its samples (SPEC §6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ShadingMode {
    /// One colour per triangle: the lighting model at the centroid with the
    /// face normal.
    Flat,
    /// Lighting at the vertices, colours interpolated.
    Gouraud,
    /// Normals and positions interpolated, lighting per sample.
    #[default]
    Phong,
}

impl ShadingMode {
    /// Every mode, in order of increasing cost.
    pub const ALL: [ShadingMode; 3] = [ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong];

    /// The lower-case name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            ShadingMode::Flat => "flat",
            ShadingMode::Gouraud => "gouraud",
            ShadingMode::Phong => "phong",
        }
    }
}

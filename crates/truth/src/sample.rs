//! The inputs a caller-supplied shading function receives per sample
//! ([`crate::render_truth_shaded`]).

use glam::DVec3;

/// What a caller-supplied shading function ([`crate::render_truth_shaded`])
/// sees at one Phong-shaded sample, in eye space: the geometry and the
/// material's parameters as the truth's own lighting would take them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleShading {
    /// The surface point: the eye-space position interpolated with the
    /// scene's interpolation.
    pub point: DVec3,
    /// The unit normal (or zero): interpolated, renormalized, perturbed
    /// by the mesh's bump or normal map, turned around on a back face lit
    /// two-sided.
    pub normal: DVec3,
    /// The unit vector towards the viewer at the eye-space origin,
    /// −point/|point| (the truth's convention for every camera).
    pub view: DVec3,
    /// The base colour kd ⊙ texel ⊙ vertex colour.
    pub base: DVec3,
    /// A Cook–Torrance material's metallic and perceptual roughness, its
    /// metallic–roughness map applied; `None` for the basic model.
    pub metallic_roughness: Option<(f64, f64)>,
    /// The occlusion map's factor on the ambient light, 1 + strength·(R −
    /// 1); 1 without one (or for the basic model).
    pub occlusion: f64,
    /// The emission ke ⊙ the emissive texel (ke without a map).
    pub emission: DVec3,
}

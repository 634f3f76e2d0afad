//! Light from an environment map (SPEC §5.3): radiance arriving from every
//! direction, stored as an equirectangular [`Panorama`], prepared once into
//! what shading reads per sample:
//!
//! - the diffuse lobe's irradiance E(N)/π as nine spherical-harmonic
//!   coefficients per channel (Ramamoorthi and Hanrahan 2001), so a sample
//!   pays nine products, not an integral;
//! - the specular lobe's prefiltered radiance, a chain of octahedral maps at
//!   roughness r = k/10 (k = 0..=10), each the GGX lobe around the reflected
//!   direction (N = V = R, the split-sum assumption) averaged over the
//!   environment with filtered importance sampling (Křivánek and Colbert
//!   2008), as the Khronos glTF Sample Viewer prefilters its cube maps.
//!
//! [`EnvironmentLight`] holds that preparation (tens of milliseconds for a
//! 1k panorama); [`Environment`] shares it behind an `Arc` with the cheap
//! per-scene settings (intensity, rotation, drawn as the background), so a
//! turntable or a change of intensity never prepares it again.

mod octahedral;
mod panorama;
mod prefilter;
mod sh;
mod sky;
#[cfg(test)]
mod tests;

use std::sync::Arc;

use glam::{Mat3, Vec3};

pub use octahedral::{octahedral_decode, octahedral_encode, texel_solid_angles, OctahedralMap};
pub use panorama::{Panorama, PanoramaError, MAX_PANORAMA_SIDE};
pub use prefilter::PREFILTER_LEVELS;
pub use sh::{sh_basis, SH_COEFFICIENTS};
pub use sky::{sky_radiance, SKY_SUN};

/// An environment prepared for shading: the irradiance coefficients, the
/// prefiltered chain, and the panorama itself (for the background).
#[derive(Debug)]
pub struct EnvironmentLight {
    panorama: Panorama,
    /// E(N)/π = Σ sh[i]·Y_i(N), in the panorama's frame.
    sh: [Vec3; SH_COEFFICIENTS],
    /// Level k: radiance prefiltered for roughness k/(LEVELS − 1).
    levels: Vec<OctahedralMap>,
}

/// Two prepared environments are equal when they are the same one: the
/// preparation is costly and shared, and its identity is what a scene
/// compares.
impl PartialEq for EnvironmentLight {
    fn eq(&self, o: &EnvironmentLight) -> bool {
        std::ptr::eq(self, o)
    }
}

impl EnvironmentLight {
    /// Prepares `panorama` (SH projection and the prefiltered chain).
    pub fn new(panorama: Panorama) -> EnvironmentLight {
        let sh = sh::irradiance_sh(&panorama);
        let levels = prefilter::prefiltered_levels(&panorama);
        EnvironmentLight { panorama, sh, levels }
    }

    /// The panorama.
    pub fn panorama(&self) -> &Panorama {
        &self.panorama
    }

    /// The irradiance coefficients: E(N)/π = Σ c_i·Y_i(N) (see [`sh_basis`]).
    pub fn sh(&self) -> &[Vec3; SH_COEFFICIENTS] {
        &self.sh
    }

    /// The prefiltered chain, roughness k/(LEVELS − 1) at level k.
    pub fn levels(&self) -> &[OctahedralMap] {
        &self.levels
    }

    /// E(n)/π for unit `n` in the panorama's frame: the radiance a white
    /// Lambertian surface facing `n` reflects. Clamped at 0 (nine
    /// coefficients ring below a bright, small source).
    #[inline]
    pub fn irradiance(&self, n: Vec3) -> Vec3 {
        let y = sh_basis(n);
        let mut e = Vec3::ZERO;
        for (c, y) in self.sh.iter().zip(y) {
            e += *c * y;
        }
        e.max(Vec3::ZERO)
    }

    /// The radiance prefiltered for `roughness` around unit direction `r`
    /// (panorama frame): bilinear in the two nearest levels, linear
    /// between them.
    #[inline]
    pub fn prefiltered(&self, r: Vec3, roughness: f32) -> Vec3 {
        let last = (PREFILTER_LEVELS - 1) as f32;
        let x = if roughness.is_nan() { 0.0 } else { roughness.clamp(0.0, 1.0) * last };
        let k = (x.floor() as usize).min(PREFILTER_LEVELS - 2);
        let t = x - k as f32;
        let uv = octahedral_encode(r);
        let a = self.levels[k].sample(uv);
        if t == 0.0 {
            return a;
        }
        a.lerp(self.levels[k + 1].sample(uv), t)
    }
}

/// Environment settings of a scene: the prepared light, shared, with its
/// intensity, its rotation about +y and whether it is drawn behind the
/// scene. Like a light, it lives in a coordinate frame: world space when
/// made, another after [`Environment::transformed`].
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// The prepared environment.
    pub light: Arc<EnvironmentLight>,
    /// Multiplies the panorama's radiance.
    pub intensity: f32,
    /// Rotation of the panorama about world +y, in degrees
    /// (counter-clockwise seen from above).
    pub rotation_degrees: f32,
    /// Draw the panorama where no surface covers a sample.
    pub background: bool,
    /// Directions of the current frame into world space (unit columns).
    frame_to_world: Mat3,
}

impl Environment {
    /// `light` in world space at intensity 1, unrotated, not drawn.
    pub fn new(light: Arc<EnvironmentLight>) -> Environment {
        Environment {
            light,
            intensity: 1.0,
            rotation_degrees: 0.0,
            background: false,
            frame_to_world: Mat3::IDENTITY,
        }
    }

    /// The same environment in the frame reached by `to` (rigid or
    /// uniformly scaled; view matrices are), as [`crate::Light::transformed`].
    pub fn transformed(&self, to: &glam::Mat4) -> Environment {
        let mut back = Mat3::from_mat4(*to).inverse();
        // A uniform scale in `to` would scale the directions: undo it so
        // the lookups see unit vectors.
        let scale = back.x_axis.length();
        if scale.is_finite() && scale > 0.0 {
            back *= 1.0 / scale;
        }
        Environment { frame_to_world: self.frame_to_world * back, ..self.clone() }
    }

    /// The rotation taking world directions into the panorama's frame.
    pub fn world_to_panorama(&self) -> Mat3 {
        Mat3::from_rotation_y(-self.rotation_degrees.to_radians())
    }

    /// The radiance seen along unit direction `d` of the current frame, for
    /// the background: the panorama's bilinear texel times the intensity.
    pub fn background_radiance(&self, d: Vec3) -> Vec3 {
        self.light.panorama.sample(self.world_to_panorama() * (self.frame_to_world * d)) * self.intensity
    }

    /// Prepared for shading in its frame, with the scene's uniform ambient
    /// `ambient` added to what it gives.
    pub fn prepare(&self, ambient: Vec3) -> PreparedEnvironment {
        PreparedEnvironment {
            light: self.light.clone(),
            to_panorama: self.world_to_panorama() * self.frame_to_world,
            intensity: self.intensity,
            ambient,
        }
    }
}

/// An environment ready for per-sample shading in one frame: the rotation
/// into the panorama's frame, the intensity and the uniform ambient folded
/// into its two lookups.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedEnvironment {
    light: Arc<EnvironmentLight>,
    to_panorama: Mat3,
    intensity: f32,
    ambient: Vec3,
}

impl PreparedEnvironment {
    /// Ia + intensity·E(n)/π for unit normal `n` in the shading frame: the
    /// radiance of a uniform environment that lights a Lambertian surface
    /// the same way.
    #[inline]
    pub fn diffuse(&self, n: Vec3) -> Vec3 {
        self.ambient + self.light.irradiance(self.to_panorama * n) * self.intensity
    }

    /// Ia + intensity·(prefiltered radiance) along unit `r` (shading frame)
    /// for `roughness`.
    #[inline]
    pub fn specular(&self, r: Vec3, roughness: f32) -> Vec3 {
        self.ambient + self.light.prefiltered(self.to_panorama * r, roughness) * self.intensity
    }
}

/// Eight lanes of coordinates (x, y, z), as the kernels hand them over.
type Lanes = [[f32; 8]; 3];

/// The lane `k` of `lanes` as a vector.
#[inline]
fn lane(lanes: &Lanes, k: usize) -> Vec3 {
    Vec3::new(lanes[0][k], lanes[1][k], lanes[2][k])
}

/// Vectors into lanes.
#[inline]
fn to_lanes(v: [Vec3; 8]) -> Lanes {
    [v.map(|c| c.x), v.map(|c| c.y), v.map(|c| c.z)]
}

/// ka ⊙ D per lane for the basic model's ambient term (SPEC §5.3), the
/// scalar path's code lane by lane. One compiled copy for every kernel and
/// SIMD level (lanes as plain arrays): the kernels call it, out of line,
/// only when the frame has an environment.
#[inline(never)]
pub(crate) fn ambient_lanes(e: &PreparedEnvironment, ka: Vec3, normals: Lanes) -> Lanes {
    to_lanes(std::array::from_fn(|k| ka * e.diffuse(lane(&normals, k))))
}

/// (D, S) per lane for Cook–Torrance (SPEC §5.3): the environment's
/// radiance for the diffuse lobe at N and for the specular lobe along
/// R = 2(N·V)N − V at the lane's roughness; one compiled copy, as
/// [`ambient_lanes`].
#[inline(never)]
pub(crate) fn environment_lanes(
    e: &PreparedEnvironment,
    (normals, views): (Lanes, Lanes),
    roughness: [f32; 8],
) -> (Lanes, Lanes) {
    let diffuse = std::array::from_fn(|k| e.diffuse(lane(&normals, k)));
    let specular = std::array::from_fn(|k| {
        let (n, v) = (lane(&normals, k), lane(&views, k));
        e.specular(crate::pbr::reflect(v, n), roughness[k])
    });
    (to_lanes(diffuse), to_lanes(specular))
}

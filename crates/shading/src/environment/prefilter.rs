//! The prefiltered chain: for roughness r_k = k/(LEVELS − 1), the radiance
//! around each direction R averaged over GGX's lobe with N = V = R,
//!
//! ```text
//! L_k(R) = Σ_s L(l_s)·(N·l_s) / Σ_s (N·l_s),   l_s = reflect(−V, h_s),  h_s ~ D_GGX(α = r_k²)
//! ```
//!
//! with 256 to 1,024 half vectors of a Hammersley set per texel, each read from the
//! source's mip level whose texel matches the sample's share of the lobe,
//! lod = ½·log2(Ω_sample/Ω_texel) (filtered importance sampling, Křivánek and
//! Colbert 2008, as the Khronos Sample Viewer's `ibl_filtering.frag`; without
//! their +1 bias, which blurred the sky's sun over the horizon and doubled
//! the error the tests measure), so a bright texel does not stand out.

use glam::{Vec2, Vec3};

use super::octahedral::{octahedral_decode, octahedral_encode, OctahedralMap};
use super::panorama::Panorama;

/// Roughness levels of the prefiltered chain: level k holds r = k/(LEVELS − 1).
/// Eleven, a level every 0.1: between two levels the radiance is linear in
/// r, and near a small bright source (a sun) the lobe's peak changes as
/// 1/α² = 1/r⁴, so the levels must be close for the interpolation to hold.
pub const PREFILTER_LEVELS: usize = 11;

/// (side, half vectors per texel) of level k ≥ 1, by the lobe's width
/// α = r²: a texel about a third of the lobe across, and more samples for
/// wider lobes (narrow ones read fine mip levels that are already smooth
/// at their scale). The same whatever the panorama's size.
fn level_plan(k: usize) -> (u32, u32) {
    match k {
        1 | 2 => (128, 256),
        3 | 4 => (64, 512),
        5..=7 => (32, 1024),
        _ => (16, 1024),
    }
}

/// The largest side of the source (and of level 0, the mirror's).
const MAX_SOURCE_SIZE: u32 = 256;

/// The smallest side of the source.
const MIN_SOURCE_SIZE: u32 = 16;

/// The side of the octahedral source for a panorama of `w × h` texels:
/// about as many texels, a power of two in 16..=256.
fn source_size(w: u32, h: u32) -> u32 {
    let texels = (f64::from(w) * f64::from(h)).sqrt().ceil() as u32;
    texels.next_power_of_two().clamp(MIN_SOURCE_SIZE, MAX_SOURCE_SIZE)
}

/// The panorama resampled onto an octahedral map: each texel the mean of
/// n × n bilinear panorama samples spread over it (n = 1 to 4, by how many
/// panorama texels a map texel covers).
fn source(panorama: &Panorama) -> OctahedralMap {
    let size = source_size(panorama.width(), panorama.height());
    let density = (f64::from(panorama.width()) * f64::from(panorama.height())).sqrt() / f64::from(size);
    let n = (density.ceil() as u32).clamp(1, 4);
    let s = size as f32;
    let mut texels = Vec::with_capacity(size as usize * size as usize);
    for j in 0..size {
        for i in 0..size {
            let mut sum = Vec3::ZERO;
            for b in 0..n {
                for a in 0..n {
                    let uv = Vec2::new(
                        (i as f32 + (a as f32 + 0.5) / n as f32) / s,
                        (j as f32 + (b as f32 + 0.5) / n as f32) / s,
                    );
                    sum += panorama.sample(octahedral_decode(uv));
                }
            }
            texels.push(sum / (n * n) as f32);
        }
    }
    OctahedralMap::from_texels(size, texels)
}

/// An orthonormal pair spanning the plane normal to unit `n` (Duff et al.
/// 2017, branchless).
fn tangents(n: Vec3) -> (Vec3, Vec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}

/// The chain for `panorama`: level 0 the source itself (a mirror), level k
/// the lobe of roughness k/(LEVELS − 1) at the side [`level_plan`] gives.
pub(super) fn prefiltered_levels(panorama: &Panorama) -> Vec<OctahedralMap> {
    let mut mips = vec![source(panorama)];
    while mips.last().is_some_and(|m| m.size() > 1) {
        let half = mips.last().map(OctahedralMap::halved);
        mips.extend(half);
    }
    let size0 = mips[0].size();
    let texel_solid_angle = 4.0 * std::f32::consts::PI / (size0 * size0) as f32;
    let mut levels = vec![mips[0].clone()];
    for k in 1..PREFILTER_LEVELS {
        let roughness = k as f32 / (PREFILTER_LEVELS - 1) as f32;
        let alpha2 = (roughness * roughness).powi(2);
        let (size, samples) = level_plan(k);
        let lobe = lobe_samples(alpha2, samples, texel_solid_angle, (mips.len() - 1) as f32);
        levels.push(OctahedralMap::from_fn_parallel(size, |n| lobe_average(&mips, n, &lobe)));
    }
    levels
}

/// One half vector of a level's set, in the frame of N (z along N): its
/// tangent-frame coordinates, the weight N·L of the light direction it
/// reflects, and the mip level that direction is read from. The same for
/// every texel of a level, so computed once per level.
#[derive(Clone, Copy)]
struct LobeSample {
    h: Vec3,
    nl: f32,
    lod: f32,
}

/// The half vectors of GGX α² = `alpha2` (a Hammersley set of `samples`
/// points) with N·L > 0, each with its mip level for sources whose level 0
/// texel covers `texel_solid_angle` and whose last level is `last`.
fn lobe_samples(alpha2: f32, samples: u32, texel_solid_angle: f32, last: f32) -> Vec<LobeSample> {
    let mut out = Vec::with_capacity(samples as usize);
    for s in 0..samples {
        let u1 = (s as f32 + 0.5) / samples as f32;
        let u2 = s.reverse_bits() as f32 / 4_294_967_296.0;
        let cos_h = ((1.0 - u1) / (1.0 + (alpha2 - 1.0) * u1)).sqrt();
        let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
        let (sin_p, cos_p) = (std::f32::consts::TAU * u2).sin_cos();
        let nl = 2.0 * cos_h * cos_h - 1.0;
        if nl <= 0.0 {
            continue;
        }
        // pdf(l) = D·(N·H)/(4·V·H) = D/4 with V = N.
        let q = cos_h * cos_h * (alpha2 - 1.0) + 1.0;
        let pdf = alpha2 / (std::f32::consts::PI * q * q) / 4.0;
        let sample_solid_angle = 1.0 / (samples as f32 * pdf);
        let lod = (0.5 * (sample_solid_angle / texel_solid_angle).log2()).clamp(0.0, last);
        out.push(LobeSample { h: Vec3::new(sin_h * cos_p, sin_h * sin_p, cos_h), nl, lod });
    }
    out
}

/// The lobe average around unit `n` over the half vectors `lobe`.
fn lobe_average(mips: &[OctahedralMap], n: Vec3, lobe: &[LobeSample]) -> Vec3 {
    let (t, b) = tangents(n);
    let (mut sum, mut weight) = (Vec3::ZERO, 0.0f32);
    for s in lobe {
        let h = t * s.h.x + b * s.h.y + n * s.h.z;
        let l = h * (2.0 * s.h.z) - n;
        let uv = octahedral_encode(l);
        let m = (s.lod.floor() as usize).min(mips.len() - 1);
        let f = s.lod - m as f32;
        let mut radiance = mips[m].sample(uv);
        if f > 0.0 && m + 1 < mips.len() {
            radiance = radiance.lerp(mips[m + 1].sample(uv), f);
        }
        sum += radiance * s.nl;
        weight += s.nl;
    }
    if weight > 0.0 {
        sum / weight
    } else {
        mips[0].sample(octahedral_encode(n))
    }
}

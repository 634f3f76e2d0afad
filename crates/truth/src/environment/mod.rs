//! Light from an environment map (SPEC §5.3) in f64, written from SPEC
//! alone: `zline_shading`'s preparation (its SH coefficients, its
//! octahedral prefiltered chain, `Panorama::sample`) is not called; only
//! the panorama's texels and the environment's public settings are read.
//!
//! Directions. The truth shades in eye space; a direction d there is
//! world_from_eye·d in the world and R_y(−θ)·world_from_eye·d in the
//! panorama's frame (θ the rotation about world +y). Panorama position
//! (u, v) ↔ direction: φ = 2π(u − ½) from −z towards +x, polar angle
//! πv from +y. The panorama is read bilinearly (u wraps, v clamps).
//!
//! E(N)/π (SPEC §5.3): the texels projected on the real SH basis of bands
//! 0–2, each weighted by its exact solid angle (2π/W)(cos θ_top −
//! cos θ_bottom), band l scaled by Â_l/π = 1, 2/3, 1/4; the sum clamped at
//! 0 per channel. Computed once per frame.
//!
//! L_pre(R, r): GGX's lobe average with N = V = R, by direct integration
//! over the panorama's cells ([`lobe`] states the rule and its accuracy).
//!
//! Cost: every cell of the panorama per lookup (four Gauss points each,
//! more near R), nothing cached: meant for small panoramas. With a 64 × 32
//! one, 0.1 to 0.5 ms a lookup for r ≥ 0.3 (a busy two-core machine), a
//! few ms for the sharpest lobes the split resolves (r ≈ 0.06); the cost
//! grows with the texel count.
//!
//! Background: k·L(ω) along each sample's ray, bilinear at full
//! resolution, without Ia.

mod lobe;

use std::f64::consts::{PI, TAU};

use glam::{DMat3, DMat4, DVec3};
use zline_shading::Environment;

use lobe::{direction, DualGrid};
pub(crate) use lobe::{KAPPA, MAX_SPLIT};

/// SH coefficients per channel (bands 0, 1, 2).
const SH: usize = 9;

/// Â_l/π for each coefficient's band.
const BAND_SCALE: [f64; SH] = [1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25];

/// An environment prepared for the truth in one frame (eye space).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EnvironmentF64 {
    /// Eye-space directions into the panorama's frame.
    to_panorama: DMat3,
    /// The intensity k.
    intensity: f64,
    /// The texels in f64, rows from the top.
    texels: Vec<DVec3>,
    /// The cells L_pre integrates over.
    grid: DualGrid,
    /// E(N)/π = max(0, Σ_i sh_i·Y_i(N)), N in the panorama's frame.
    sh: [DVec3; SH],
    /// Drawn behind the scene.
    pub(crate) background: bool,
}

impl EnvironmentF64 {
    /// `environment` (world space) for shading in the eye space reached by
    /// `eye_from_world` (a rigid view matrix).
    pub(crate) fn new(environment: &Environment, eye_from_world: &DMat4) -> EnvironmentF64 {
        let panorama = environment.light.panorama();
        let (width, height) = (panorama.width() as usize, panorama.height() as usize);
        let world_from_eye = DMat3::from_mat4(*eye_from_world).inverse();
        let rotation = DMat3::from_rotation_y(-f64::from(environment.rotation_degrees).to_radians());
        let texels: Vec<DVec3> = panorama.texels().iter().map(|t| t.as_dvec3()).collect();
        EnvironmentF64 {
            to_panorama: rotation * world_from_eye,
            intensity: f64::from(environment.intensity),
            sh: project(&texels, width, height),
            texels,
            grid: DualGrid::new(width, height),
            background: environment.background,
        }
    }

    /// k·E(n)/π for the eye-space normal `n` (unit or zero, evaluated as
    /// given): the environment's share of the diffuse light D.
    pub(crate) fn diffuse(&self, n: DVec3) -> DVec3 {
        self.intensity * self.irradiance(self.to_panorama * n)
    }

    /// E(n)/π for `n` in the panorama's frame, clamped at 0.
    pub(crate) fn irradiance(&self, n: DVec3) -> DVec3 {
        let y = sh_basis(n);
        let e: DVec3 = (0..SH).map(|i| self.sh[i] * y[i]).sum();
        e.max(DVec3::ZERO)
    }

    /// k·L_pre(r, ·) for the eye-space unit mirror direction `r` and GGX
    /// α² = `alpha2`: the environment's share of the specular light S.
    pub(crate) fn specular(&self, r: DVec3, alpha2: f64) -> DVec3 {
        self.intensity * self.lobe_average(self.to_panorama * r, alpha2, (KAPPA, MAX_SPLIT))
    }

    /// k·L(d) along the eye-space unit direction `d`: the background.
    pub(crate) fn radiance(&self, d: DVec3) -> DVec3 {
        self.intensity * self.bilinear_along(self.to_panorama * d)
    }

    /// The bilinear panorama along unit `d` (panorama frame).
    pub(crate) fn bilinear_along(&self, d: DVec3) -> DVec3 {
        self.grid.bilinear_along(&self.texels, d)
    }

    /// L_pre around unit `r` (panorama frame) for GGX α² = `alpha2`, cells
    /// split beyond `kappa`·ℓ into at most `max_split` parts a side
    /// ([`lobe`]); the bilinear read along `r` where no direction has
    /// N·l > 0 (a zero `r`).
    pub(crate) fn lobe_average(&self, r: DVec3, alpha2: f64, split: (f64, u32)) -> DVec3 {
        self.grid.lobe_average(&self.texels, r, alpha2, split).unwrap_or_else(|| self.bilinear_along(r))
    }
}

/// The SH coefficients of E/π for a `width × height` panorama: Σ over
/// texels of L·Y_i(centre)·dω, dω = (2π/W)(cos θ_top − cos θ_bottom), times
/// Â_l/π.
fn project(texels: &[DVec3], width: usize, height: usize) -> [DVec3; SH] {
    let mut sum = [DVec3::ZERO; SH];
    for j in 0..height {
        let theta = |k: usize| PI * k as f64 / height as f64;
        let d_omega = (TAU / width as f64) * (theta(j).cos() - theta(j + 1).cos());
        for i in 0..width {
            let d = direction((i as f64 + 0.5) / width as f64, (j as f64 + 0.5) / height as f64);
            let radiance = texels[j * width + i] * d_omega;
            for (s, y) in sum.iter_mut().zip(sh_basis(d)) {
                *s += radiance * y;
            }
        }
    }
    std::array::from_fn(|i| sum[i] * BAND_SCALE[i])
}

/// The real SH basis of bands 0–2 at `n` (z the polar axis):
/// Y00 = 1/(2√π); Y1m = √(3/4π)·(y, z, x); Y2−2 = ½√(15/π)·xy,
/// Y2−1 = ½√(15/π)·yz, Y20 = ¼√(5/π)·(3z² − 1), Y21 = ½√(15/π)·xz,
/// Y22 = ¼√(15/π)·(x² − y²).
fn sh_basis(n: DVec3) -> [f64; SH] {
    let c0 = 0.5 / PI.sqrt();
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    let c2 = 0.5 * (15.0 / PI).sqrt();
    let c20 = 0.25 * (5.0 / PI).sqrt();
    let c22 = 0.25 * (15.0 / PI).sqrt();
    let (x, y, z) = (n.x, n.y, n.z);
    [
        c0,
        c1 * y,
        c1 * z,
        c1 * x,
        c2 * x * y,
        c2 * y * z,
        c20 * (3.0 * z * z - 1.0),
        c2 * x * z,
        c22 * (x * x - y * y),
    ]
}

#[cfg(test)]
mod tests;

//! A procedural sky, so tests, the demo and users without an HDR file have
//! an environment: a blue zenith fading to a pale horizon, a warm ground,
//! and a sun of Gaussian profile, all smooth functions of the direction
//! (made by zline; no licence beyond the project's).

use glam::Vec3;

use super::panorama::{Panorama, MAX_PANORAMA_SIDE};

/// Unit direction towards the sky's sun: 40° above the horizon, 30° from
/// straight ahead (−z) towards +x.
pub const SKY_SUN: Vec3 = Vec3::new(0.383_022_22, 0.642_787_6, -0.663_414);

/// Peak radiance of the sun, and its angular spread σ (radians).
const SUN_PEAK: f32 = 200.0;
const SUN_SIGMA: f32 = 0.03;

/// The sky's radiance along unit direction `d`.
pub fn sky_radiance(d: Vec3) -> Vec3 {
    let zenith = Vec3::new(0.18, 0.35, 0.85);
    let horizon = Vec3::new(0.85, 0.9, 1.0);
    let ground = Vec3::new(0.25, 0.21, 0.17);
    let up = d.y.max(0.0);
    let sky = horizon.lerp(zenith, 1.0 - (1.0 - up).powi(3));
    // A soft edge a few degrees wide between ground and sky.
    let t = ((d.y + 0.05) / 0.1).clamp(0.0, 1.0);
    let t = t * t * (3.0 - 2.0 * t);
    let base = ground.lerp(sky, t);
    let cos_gamma = d.dot(SKY_SUN).clamp(-1.0, 1.0);
    let sun = SUN_PEAK * (-(1.0 - cos_gamma) / (SUN_SIGMA * SUN_SIGMA)).exp();
    base + Vec3::new(1.0, 0.95, 0.85) * sun
}

impl Panorama {
    /// The procedural sky as a `width × height` panorama, each texel the
    /// radiance at its centre.
    pub fn sky(width: u32, height: u32) -> Panorama {
        let (w, h) = (width.clamp(1, MAX_PANORAMA_SIDE), height.clamp(1, MAX_PANORAMA_SIDE));
        let mut texels = Vec::with_capacity(w as usize * h as usize);
        for j in 0..h {
            for i in 0..w {
                let (u, v) = ((i as f32 + 0.5) / w as f32, (j as f32 + 0.5) / h as f32);
                texels.push(sky_radiance(Panorama::direction(u, v)));
            }
        }
        Panorama::new(w, h, texels).map(|(p, _)| p).unwrap_or_else(|_| unreachable!("the sides are checked"))
    }
}

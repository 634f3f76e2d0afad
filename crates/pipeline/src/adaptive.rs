//! The adaptive mode ("model only what the scene needs", SPEC §6): given a
//! tolerance τ in 8-bit units (`RenderSettings::adaptive_tolerance`), each
//! triangle takes the cheapest evaluation whose colour provably stays within
//! τ/255 of what the full evaluation of the same shading mode gives. The
//! 8-bit output then moves by at most ⌊τ⌋ + 1 steps (a shift below one step
//! can still cross one rounding boundary).
//!
//! The shortcuts and the bounds they rest on (all values are colours in
//! [0, 1] per channel before the final clamp, which only shrinks
//! differences):
//!
//! 1. **Gouraud → flat.** Interpolated colours are convex combinations of
//!    the three vertex colours (perspective-correct or not), so each channel
//!    lies in [min, max] of its vertex values; the midpoint is within
//!    (max − min)/2 of every one. Taken when (max − min)/2 ≤ τ/255 in every
//!    channel: the triangle is drawn as flat, with no attribute planes.
//! 2. **Perspective-correct → screen-linear** (Gouraud). With q = 1/w at
//!    the vertices and ρ = q_max/q_min, the perspective weights λᵢ and the
//!    screen-linear weights bᵢ satisfy λᵢ/bᵢ ∈ [1/ρ, ρ], so Σ|λᵢ − bᵢ| ≤
//!    ρ − 1, split equally between positive and negative parts (both sums
//!    are 1); hence |Σ(λᵢ − bᵢ)aᵢ| ≤ (ρ − 1)/2 · (max a − min a). Taken when
//!    that is ≤ τ/255 in every channel: the kernel skips the per-sample
//!    divide.
//! 3. **No specular** (Phong, textured or not). The specular term of a light
//!    is ks·f(d)·Il·max(0, N·H)^ns ≤ ks·f(d)·Il, and every point of a
//!    triangle lies within its longest edge ℓ of each vertex, so its distance
//!    to a point light is at least d_min = minᵢ|Lpos − pᵢ| − ℓ and f(d) ≤
//!    f(max(d_min, 0)) (f does not increase with d when a1, a2 ≥ 0; other
//!    coefficients count as f = 1). Taken when Σ over lights of
//!    max(ks)·max(Il)·f bound ≤ τ/255: the triangle uses its material
//!    without specular.
//!
//! Phong's normal and position interpolation keeps its perspective divide
//! and textured triangles keep their texture coordinates' divide: a bound
//! on how a shifted normal or texture coordinate moves the lit colour or the
//! texel (nearest filtering jumps a whole texel) would need the lights' and
//! the texture's Lipschitz constants, and these shortcuts are not taken.
//!
//! The bounds are evaluated in f32; their own rounding (relative ~10⁻⁷) is
//! far below any useful τ.

use glam::Vec3;
use zline_shading::{Attenuation, Light, LightingModel};

/// The frame's adaptive-mode data: the tolerance and the lights as the
/// specular bound needs them.
#[derive(Clone, Debug, PartialEq)]
pub struct Adaptive {
    /// τ/255: the tolerance in colour units.
    tolerance: f32,
    /// Σ of the largest channel of each directional light (f = 1).
    directional: f32,
    /// Point lights in eye space: position, largest channel, attenuation.
    point: Vec<(Vec3, f32, Attenuation)>,
}

/// What a Gouraud triangle can be drawn as.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GouraudChoice {
    /// One colour, within the tolerance of every interpolated one.
    Flat(Vec3),
    /// Screen-linear interpolation, within the tolerance of
    /// perspective-correct.
    Linear,
    /// The full evaluation.
    Full,
}

impl Adaptive {
    /// The adaptive data for `tolerance` (8-bit units) and the lighting
    /// model in eye space. `None` when the tolerance is not a finite
    /// number ≥ 0.
    pub fn new(tolerance: f32, eye_lighting: &LightingModel) -> Option<Adaptive> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return None;
        }
        let mut directional = 0.0;
        let mut point = Vec::new();
        for light in &eye_lighting.lights {
            match *light {
                Light::Directional { color, .. } => directional += color.max_element().max(0.0),
                Light::Point { position, color, attenuation } => {
                    point.push((position, color.max_element().max(0.0), attenuation))
                }
            }
        }
        Some(Adaptive { tolerance: tolerance / 255.0, directional, point })
    }

    /// Shortcuts 1 and 2 for a Gouraud triangle with vertex colours
    /// `colors` and 1/w values `q` (`perspective` when the frame asks for
    /// perspective-correct interpolation).
    pub fn gouraud(&self, colors: [Vec3; 3], q: [f32; 3], perspective: bool) -> GouraudChoice {
        if !colors.iter().all(|c| c.is_finite()) {
            return GouraudChoice::Full; // `min`/`max` would skip a NaN
        }
        let lo = colors[0].min(colors[1]).min(colors[2]);
        let hi = colors[0].max(colors[1]).max(colors[2]);
        let half_range = ((hi - lo) * 0.5).max_element();
        if half_range <= self.tolerance {
            return GouraudChoice::Flat((lo + hi) * 0.5);
        }
        if perspective {
            let (q_lo, q_hi) = (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]));
            // Written so that a NaN q takes no shortcut.
            if q_lo > 0.0 && (q_hi / q_lo - 1.0) * half_range <= self.tolerance {
                return GouraudChoice::Linear;
            }
            return GouraudChoice::Full;
        }
        GouraudChoice::Linear
    }

    /// Shortcut 3: true when no specular term can reach the tolerance
    /// anywhere on the triangle with eye-space vertices `eye`, for a
    /// material whose largest ks channel is `ks`.
    pub fn specular_negligible(&self, ks: f32, eye: [Vec3; 3]) -> bool {
        if ks <= 0.0 {
            return true;
        }
        let longest =
            (eye[0] - eye[1]).length().max((eye[1] - eye[2]).length()).max((eye[2] - eye[0]).length());
        let mut bound = self.directional;
        for &(position, intensity, attenuation) in &self.point {
            let nearest = eye.iter().map(|p| (*p - position).length()).fold(f32::INFINITY, f32::min);
            let d = (nearest - longest).max(0.0);
            let monotone = attenuation.a1 >= 0.0 && attenuation.a2 >= 0.0;
            bound += intensity * if monotone { attenuation.factor(d) } else { 1.0 };
        }
        ks * bound <= self.tolerance
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adaptive(tolerance: f32, lights: Vec<Light>) -> Adaptive {
        Adaptive::new(tolerance, &LightingModel { ambient: Vec3::ZERO, lights }).unwrap()
    }

    #[test]
    fn gouraud_goes_flat_only_within_half_the_tolerance() {
        let a = adaptive(1.0, Vec::new());
        let c = Vec3::splat(0.5);
        let step = Vec3::new(0.0, 2.0 / 255.0, 0.0);
        assert_eq!(a.gouraud([c, c + step, c], [1.0; 3], true), GouraudChoice::Flat(c + step * 0.5));
        let more = Vec3::new(0.0, 2.1 / 255.0, 0.0);
        assert_ne!(a.gouraud([c, c + more, c], [1.0; 3], true), GouraudChoice::Flat(c + more * 0.5));
        let nan = Vec3::splat(f32::NAN);
        assert_eq!(a.gouraud([c, nan, c], [1.0, 2.0, 1.0], true), GouraudChoice::Full);
    }

    #[test]
    fn gouraud_goes_linear_when_w_varies_little() {
        let a = adaptive(1.0, Vec::new());
        let (c0, c1) = (Vec3::ZERO, Vec3::splat(0.4));
        // (ρ − 1)·0.2 ≤ 1/255 ⇔ ρ ≤ 1.0196.
        assert_eq!(a.gouraud([c0, c1, c0], [1.0, 1.019, 1.0], true), GouraudChoice::Linear);
        assert_eq!(a.gouraud([c0, c1, c0], [1.0, 1.021, 1.0], true), GouraudChoice::Full);
        assert_eq!(a.gouraud([c0, c1, c0], [1.0, 3.0, 1.0], false), GouraudChoice::Linear);
    }

    #[test]
    fn specular_counts_every_light_at_its_nearest_possible_distance() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let point = |position| Light::Point {
            position,
            color: Vec3::ONE,
            attenuation: Attenuation { a0: 1.0, a1: 0.0, a2: 1.0 },
        };
        let far = point(Vec3::new(0.0, 0.0, 100.0));
        // f ≤ 1/(1 + 99²) ≈ 1.02e-4 < 1/255 with ks = 1.
        assert!(adaptive(1.0, vec![far]).specular_negligible(1.0, tri));
        // Next to the light, f = 1.
        let near = point(Vec3::new(0.5, 0.5, 0.1));
        assert!(!adaptive(1.0, vec![near]).specular_negligible(1.0, tri));
        let sun = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::splat(0.5) };
        assert!(!adaptive(1.0, vec![far, sun]).specular_negligible(0.1, tri));
        assert!(adaptive(1.0, vec![far, sun]).specular_negligible(0.005, tri));
    }
}

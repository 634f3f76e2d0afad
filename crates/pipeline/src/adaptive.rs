//! The adaptive mode ("model only what the scene needs", SPEC §6): given a
//! tolerance τ in 8-bit units (`RenderSettings::adaptive_tolerance`), each
//! triangle takes the cheapest evaluation whose colour provably stays within
//! τ/255 of what the full evaluation of the same shading mode gives. The
//! 8-bit output then moves by at most ⌊τ⌋ + 1 steps (a shift below one step
//! can still cross one rounding boundary).
//!
//! The shortcuts and the bounds they rest on (all values are colours per
//! channel before the final clamp to [0, 1], which is 1-Lipschitz and so
//! only shrinks differences; Gouraud vertex colours are in [0, 1] with
//! `GouraudClamp::PerVertex` and unclamped sums with `PerSample`, and
//! bounds 1 and 2 hold for any values):
//!
//! 1. **Gouraud → flat.** Interpolated colours are convex combinations of
//!    the three vertex colours (perspective-correct or not), so each channel
//!    lies in [min, max] of its vertex values; the midpoint is within
//!    (max − min)/2 of every one. Taken when (max − min)/2 ≤ τ/255 in every
//!    channel: the triangle is drawn as flat, with no attribute planes, in
//!    the midpoint clamped to [0, 1] (what the per-sample clamp would have
//!    done to it, so the bound holds after both clamps).
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
//!    Shortcuts 3 and 4 rest on the basic model's terms: a Cook–Torrance
//!    surface (SPEC §5.2) keeps its full per-sample evaluation.
//! 4. **Phong → lit once** (untextured or textured, no vertex colours).
//!    Once specular is dropped, the colour is ke + ka·Ia + Σ f·Il·kd·g with
//!    g = max(0, N·L) ∈ [0, 1]; lighting the triangle once at the centroid c
//!    (with the normalized mean of the vertex normals) moves it by at most
//!    max(kd)·Σ max(Il)·(Δf + f_max·(ΔN + ΔL)), because |f·g − f'·g'| ≤
//!    |f − f'| + f_max·|g − g'|, max(0, ·) is 1-Lipschitz and |N·L − N'·L'|
//!    ≤ |N − N'| + |L − L'| for unit vectors. The interpolated normal stays
//!    in the spherical triangle of the vertex normals, whose diameter is the
//!    largest chord between two of them (ΔN; taken only when that chord is
//!    at most 1, well inside a hemisphere); for a point light at distances
//!    dᵢ from the vertices, every point lies within [min dᵢ − ℓ, min dᵢ + ℓ],
//!    so ΔL ≤ 2ℓ/(min dᵢ − ℓ) (from |u/|u| − v/|v|| ≤ 2|u − v|/|u|) and
//!    Δf ≤ f(min dᵢ − ℓ) − f(min dᵢ + ℓ); directional lights have ΔL = Δf =
//!    0. Taken when this plus shortcut 3's bound is ≤ τ/255: the triangle is
//!    drawn flat (textured: its texel still modulates the one lit value;
//!    texels are ≤ 1, so the bound holds). A range window keeps f
//!    non-increasing, so both bounds hold with it. A spot light's cone
//!    factor is at most 1, so shortcut 3 counts it as a point light; its
//!    change across the triangle is not bounded here, so a frame with a
//!    spot light does not take shortcut 4.
//!
//! Otherwise Phong keeps its per-sample normal and position, and textured
//! triangles keep their texture coordinates' divide: a bound on how a
//! shifted texture coordinate moves the texel (nearest filtering jumps a
//! whole texel) would need the texture's Lipschitz constant, and that
//! shortcut is not taken.
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
    /// Point and spot lights in eye space: position, largest channel,
    /// attenuation.
    point: Vec<(Vec3, f32, Attenuation)>,
    /// The frame has a spot light (no shortcut 4).
    spot: bool,
}

/// What a Phong triangle can be drawn as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhongChoice {
    /// Lit once, without specular (shortcut 4).
    LitOnce,
    /// Per sample, without specular (shortcut 3).
    NoSpecular,
    /// The full evaluation.
    Full,
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
        let mut spot = false;
        for light in &eye_lighting.lights {
            match *light {
                Light::Directional { color, .. } => directional += color.max_element().max(0.0),
                Light::Point { position, color, attenuation } => {
                    point.push((position, color.max_element().max(0.0), attenuation))
                }
                Light::Spot { position, color, attenuation, .. } => {
                    spot = true;
                    point.push((position, color.max_element().max(0.0), attenuation))
                }
            }
        }
        Some(Adaptive { tolerance: tolerance / 255.0, directional, point, spot })
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

    /// Shortcuts 3 and 4 for a Phong triangle: `kd` and `ks` are the
    /// material's largest channels, `eye` the vertices' eye-space positions,
    /// `normal` their normals (`None` when the triangle must keep per-sample
    /// lighting anyway, e.g. for vertex colours).
    pub fn phong(&self, kd: f32, ks: f32, normal: Option<[Vec3; 3]>, eye: [Vec3; 3]) -> PhongChoice {
        let specular = self.specular_bound(ks, eye);
        if specular.is_nan() || specular > self.tolerance {
            return PhongChoice::Full;
        }
        let budget = self.tolerance - specular;
        match normal {
            Some(normal) if self.diffuse_within(kd, normal, eye, budget) => PhongChoice::LitOnce,
            _ => PhongChoice::NoSpecular,
        }
    }

    /// Shortcut 4's bound: true when the diffuse term provably varies by at
    /// most `budget` over the triangle.
    fn diffuse_within(&self, kd: f32, normal: [Vec3; 3], eye: [Vec3; 3], budget: f32) -> bool {
        let n = normal.map(Vec3::normalize_or_zero);
        if self.spot || n.contains(&Vec3::ZERO) {
            return false;
        }
        let spread = (n[0] - n[1]).length().max((n[1] - n[2]).length()).max((n[2] - n[0]).length());
        if spread > 1.0 {
            return false; // (NaN fails the final comparison)
        }
        let longest = longest_edge(eye);
        let mut variation = self.directional * spread;
        for &(position, intensity, attenuation) in &self.point {
            let nearest = nearest_distance(eye, position);
            let (near, far) = (nearest - longest, nearest + longest);
            if near.is_nan() || near <= 0.0 || !monotone(&attenuation) {
                return false;
            }
            let (f_near, f_far) = (attenuation.factor(near), attenuation.factor(far));
            variation += intensity * ((f_near - f_far) + f_near * (spread + 2.0 * longest / near));
        }
        kd.max(0.0) * variation <= budget
    }

    /// Shortcut 3's bound: the largest specular term on the triangle.
    fn specular_bound(&self, ks: f32, eye: [Vec3; 3]) -> f32 {
        if ks <= 0.0 {
            return 0.0;
        }
        let directional = ks * self.directional;
        if directional > self.tolerance {
            // Directional lights alone exceed the tolerance: skip the
            // per-triangle geometry (the common case with a sun and ks > 0).
            return directional;
        }
        let longest = longest_edge(eye);
        let mut bound = self.directional;
        for &(position, intensity, attenuation) in &self.point {
            let d = (nearest_distance(eye, position) - longest).max(0.0);
            bound += intensity * if monotone(&attenuation) { attenuation.factor(d) } else { 1.0 };
        }
        ks * bound
    }
}

/// The triangle's longest edge: every point of it lies within this distance
/// of each vertex.
fn longest_edge(p: [Vec3; 3]) -> f32 {
    (p[0] - p[1]).length().max((p[1] - p[2]).length()).max((p[2] - p[0]).length())
}

/// The distance from `light` to the nearest vertex.
fn nearest_distance(p: [Vec3; 3], light: Vec3) -> f32 {
    p.iter().map(|v| (*v - light).length()).fold(f32::INFINITY, f32::min)
}

/// True when f(d) does not increase with d (a1, a2 ≥ 0).
fn monotone(a: &Attenuation) -> bool {
    a.a1 >= 0.0 && a.a2 >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adaptive(tolerance: f32, lights: Vec<Light>) -> Adaptive {
        Adaptive::new(tolerance, &LightingModel { ambient: Vec3::ZERO, lights, environment: None }).unwrap()
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
            attenuation: Attenuation::new(1.0, 0.0, 1.0),
        };
        let far = point(Vec3::new(0.0, 0.0, 100.0));
        // f ≤ 1/(1 + 99²) ≈ 1.02e-4 < 1/255 with ks = 1.
        assert_eq!(adaptive(1.0, vec![far]).phong(0.0, 1.0, None, tri), PhongChoice::NoSpecular);
        // Next to the light, f = 1.
        let near = point(Vec3::new(0.5, 0.5, 0.1));
        assert_eq!(adaptive(1.0, vec![near]).phong(0.0, 1.0, None, tri), PhongChoice::Full);
        let sun = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::splat(0.5) };
        assert_eq!(adaptive(1.0, vec![far, sun]).phong(0.0, 0.1, None, tri), PhongChoice::Full);
        assert_eq!(adaptive(1.0, vec![far, sun]).phong(0.0, 0.005, None, tri), PhongChoice::NoSpecular);
    }

    #[test]
    fn lit_once_needs_no_specular_close_normals_and_far_point_lights() {
        let tri = [Vec3::new(0.0, 0.0, -5.0), Vec3::new(1.0, 0.0, -5.0), Vec3::new(0.0, 1.0, -5.0)];
        let same = [Vec3::Z; 3];
        let sun = Light::Directional { direction: Vec3::NEG_Z, color: Vec3::ONE };
        // Equal normals under a directional light: the diffuse term is constant.
        assert_eq!(adaptive(0.0, vec![sun]).phong(0.8, 0.0, Some(same), tri), PhongChoice::LitOnce);
        // ... unless specular may show.
        assert_eq!(adaptive(1.0, vec![sun]).phong(0.8, 0.5, Some(same), tri), PhongChoice::Full);
        // Normals 0.1 apart (chord): variation ≤ 0.8·0.1 = 20 steps.
        let spread = [Vec3::Z, Vec3::new(0.1, 0.0, 1.0).normalize(), Vec3::Z];
        assert_eq!(adaptive(8.0, vec![sun]).phong(0.8, 0.0, Some(spread), tri), PhongChoice::NoSpecular);
        assert_eq!(adaptive(25.0, vec![sun]).phong(0.8, 0.0, Some(spread), tri), PhongChoice::LitOnce);
        // A point light next to the triangle changes L across it.
        let bulb = Light::Point {
            position: Vec3::new(0.5, 0.5, -4.0),
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        assert_eq!(adaptive(8.0, vec![bulb]).phong(0.8, 0.0, Some(same), tri), PhongChoice::NoSpecular);
        // Zero or NaN normals take no shortcut.
        assert_eq!(
            adaptive(255.0, vec![sun]).phong(0.8, 0.0, Some([Vec3::ZERO, Vec3::Z, Vec3::Z]), tri),
            PhongChoice::NoSpecular
        );
        assert_eq!(
            adaptive(255.0, vec![sun]).phong(0.8, 0.0, Some([Vec3::NAN, Vec3::Z, Vec3::Z]), tri),
            PhongChoice::NoSpecular
        );
    }
}

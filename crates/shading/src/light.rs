//! Light sources and distance attenuation (SPEC §5).

use glam::Vec3;

/// Distance attenuation f(d) = min(1, 1/(a0 + a1·d + a2·d²)), times the
/// range window w(d) = clamp(1 − (d/range)⁴, 0, 1) of KHR_lights_punctual
/// when the light has a finite `range` (SPEC §5.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation {
    /// Constant term.
    pub a0: f32,
    /// Linear term.
    pub a1: f32,
    /// Quadratic term.
    pub a2: f32,
    /// The distance at which the light ends, smoothly; `f32::INFINITY`
    /// for a light that reaches everywhere. A range that is not a finite
    /// number > 0 (0, negative, NaN) means none, as the glTF Sample
    /// Viewer reads one ≤ 0.
    pub range: f32,
}

impl Attenuation {
    /// No attenuation: f(d) = 1 everywhere.
    pub const NONE: Attenuation = Attenuation::new(1.0, 0.0, 0.0);

    /// The polynomial attenuation with no range.
    pub const fn new(a0: f32, a1: f32, a2: f32) -> Attenuation {
        Attenuation { a0, a1, a2, range: f32::INFINITY }
    }

    /// The same attenuation ending at `range` (`f32::INFINITY`: never).
    pub const fn with_range(self, range: f32) -> Attenuation {
        Attenuation { range, ..self }
    }

    /// f(d) for a distance `d ≥ 0`: the polynomial's, times the range
    /// window. A denominator ≤ 0 (never produced by non-negative
    /// coefficients) yields 1, the clamp's value.
    #[inline]
    pub fn factor(&self, d: f32) -> f32 {
        self.polynomial(d) * self.window(d)
    }

    /// min(1, 1/(a0 + a1·d + a2·d²)).
    #[inline]
    pub fn polynomial(&self, d: f32) -> f32 {
        let denom = self.a0 + d * (self.a1 + d * self.a2);
        if denom > 1.0 {
            1.0 / denom
        } else {
            1.0
        }
    }

    /// True when the light has a range: a finite number > 0.
    #[inline]
    pub fn has_range(&self) -> bool {
        self.range > 0.0 && self.range.is_finite()
    }

    /// The range window clamp(1 − (d/range)⁴, 0, 1); 1 without a range.
    #[inline]
    pub fn window(&self, d: f32) -> f32 {
        if !self.has_range() {
            return 1.0;
        }
        let x = d / self.range;
        let x2 = x * x;
        (1.0 - x2 * x2).clamp(0.0, 1.0)
    }

    /// True when the polynomial is 1 for every distance.
    #[inline]
    pub fn is_polynomial_none(&self) -> bool {
        self.a0 <= 1.0 && self.a1 == 0.0 && self.a2 == 0.0
    }

    /// True when f(d) = 1 for every distance, so `d` need not be computed.
    #[inline]
    pub fn is_none(&self) -> bool {
        self.is_polynomial_none() && !self.has_range()
    }
}

/// A spot light's cone (KHR_lights_punctual): full intensity within the
/// inner half-angle, none past the outer one, and between them the
/// extension's recommended falloff c = clamp(cos θ·s − cos θ_o·s, 0, 1)²
/// with s = 1/max(0.001, cos θ_i − cos θ_o), θ the angle from the spot's
/// axis (SPEC §5.1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// The inner half-angle θ_i, in radians, 0 ≤ θ_i < θ_o.
    pub inner: f32,
    /// The outer half-angle θ_o, in radians, θ_o ≤ π/2.
    pub outer: f32,
}

impl Cone {
    /// glTF's default cone: θ_i = 0, θ_o = π/4.
    pub const GLTF_DEFAULT: Cone = Cone { inner: 0.0, outer: std::f32::consts::FRAC_PI_4 };

    /// The cone's (scale, offset): c = clamp(cos θ·scale + offset, 0, 1)².
    #[inline]
    pub fn scale_offset(&self) -> (f32, f32) {
        let (cos_inner, cos_outer) = (self.inner.cos(), self.outer.cos());
        let scale = 1.0 / (cos_inner - cos_outer).max(0.001);
        (scale, -cos_outer * scale)
    }

    /// The falloff at cos θ, θ the angle between the spot's axis and the
    /// direction from the light to the surface.
    #[inline]
    pub fn factor(&self, cos_theta: f32) -> f32 {
        let (scale, offset) = self.scale_offset();
        let c = (cos_theta * scale + offset).clamp(0.0, 1.0);
        c * c
    }

    /// Why these angles do not make a cone, if they do not.
    pub fn check(&self) -> Result<(), String> {
        let (i, o) = (self.inner, self.outer);
        if !(i.is_finite() && o.is_finite()) {
            return Err(format!("cone angles must be finite, got inner {i}, outer {o}"));
        }
        if !(0.0 <= i && i < o && o <= std::f32::consts::FRAC_PI_2) {
            return Err(format!(
                "cone angles must satisfy 0 ≤ inner < outer ≤ π/2 (radians), got inner {i}, outer {o}"
            ));
        }
        Ok(())
    }
}

impl Default for Attenuation {
    fn default() -> Self {
        Attenuation::NONE
    }
}

/// A light source. Colours are RGB intensities Il (SPEC §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A point light at a position, attenuated with distance.
    Point {
        /// Position of the light.
        position: Vec3,
        /// RGB intensity.
        color: Vec3,
        /// Distance attenuation.
        attenuation: Attenuation,
    },
    /// A point light that shines into a cone (KHR_lights_punctual's spot
    /// light): a point light whose colour is scaled by the cone's falloff
    /// around `direction`.
    Spot {
        /// Position of the light.
        position: Vec3,
        /// The cone's axis, the way the light points. Need not be
        /// normalized.
        direction: Vec3,
        /// RGB intensity.
        color: Vec3,
        /// Distance attenuation.
        attenuation: Attenuation,
        /// The cone.
        cone: Cone,
    },
    /// A light at infinity: constant direction, no attenuation.
    Directional {
        /// The direction the light travels (from the light towards the
        /// scene); L = −direction. Need not be normalized.
        direction: Vec3,
        /// RGB intensity.
        color: Vec3,
    },
}

impl Light {
    /// The light's colour Il.
    #[inline]
    pub fn color(&self) -> Vec3 {
        match *self {
            Light::Point { color, .. } | Light::Spot { color, .. } | Light::Directional { color, .. } => {
                color
            }
        }
    }

    /// The same light expressed in another frame: positions are transformed
    /// as points, directions as vectors (`to` must be rigid or uniformly
    /// scaled for directions to stay meaningful; view matrices are).
    pub fn transformed(&self, to: &glam::Mat4) -> Light {
        match *self {
            Light::Point { position, color, attenuation } => {
                Light::Point { position: to.transform_point3(position), color, attenuation }
            }
            Light::Spot { position, direction, color, attenuation, cone } => Light::Spot {
                position: to.transform_point3(position),
                direction: to.transform_vector3(direction),
                color,
                attenuation,
                cone,
            },
            Light::Directional { direction, color } => {
                Light::Directional { direction: to.transform_vector3(direction), color }
            }
        }
    }

    /// The unit vector from `point` towards the light and the intensity
    /// that reaches it, attenuated (SPEC §5); `None` for a point light at `point`.
    #[inline]
    pub fn incident(&self, point: Vec3) -> Option<(Vec3, Vec3)> {
        match *self {
            Light::Point { position, color, attenuation } => {
                let d = position - point;
                let dist = d.length();
                (dist != 0.0).then(|| (d / dist, color * attenuation.factor(dist)))
            }
            Light::Spot { position, direction, color, attenuation, cone } => {
                let d = position - point;
                let dist = d.length();
                let cos_axis = direction.normalize_or_zero().dot(-d / dist);
                (dist != 0.0).then(|| (d / dist, color * (attenuation.factor(dist) * cone.factor(cos_axis))))
            }
            Light::Directional { direction, color } => Some((-direction.normalize_or_zero(), color)),
        }
    }

    /// The light's position, for the lights that have one (point, spot).
    #[inline]
    pub fn position(&self) -> Option<Vec3> {
        match *self {
            Light::Point { position, .. } | Light::Spot { position, .. } => Some(position),
            Light::Directional { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_range_window_follows_the_extension() {
        let a = Attenuation::new(1.0, 0.0, 1.0).with_range(2.0);
        assert_eq!(a.factor(0.0), 1.0);
        // 1/(1 + 1) · (1 − (1/2)⁴)
        assert_eq!(a.factor(1.0), 0.5 * (1.0 - 1.0 / 16.0));
        assert_eq!(a.factor(2.0), 0.0);
        assert_eq!(a.factor(7.0), 0.0);
        assert!(!a.is_none() && !a.is_polynomial_none());
        assert!(Attenuation::NONE.with_range(1.0).is_polynomial_none());
        assert!(!Attenuation::NONE.with_range(1.0).is_none());
        assert_eq!(Attenuation::NONE.factor(1e30), 1.0);
        // A range that is not a number > 0 is none.
        for bad in [0.0, -2.0, f32::NAN, f32::NEG_INFINITY] {
            let a = Attenuation::new(1.0, 0.0, 1.0).with_range(bad);
            assert!(!a.has_range() && !a.is_polynomial_none());
            assert_eq!(a.factor(3.0), 0.1, "range {bad}");
            assert!(Attenuation::NONE.with_range(bad).is_none());
        }
    }

    #[test]
    fn the_cone_ramps_squared_between_its_cosines() {
        let cone = Cone { inner: 0.3, outer: 0.6 };
        assert_eq!(cone.factor(1.0), 1.0);
        assert_eq!(cone.factor(0.3f32.cos()), 1.0);
        assert!(cone.factor(0.6f32.cos()).abs() < 1e-6);
        assert_eq!(cone.factor(0.0), 0.0);
        // Halfway between the cosines: (1/2)².
        let mid = 0.5 * (0.3f32.cos() + 0.6f32.cos());
        assert!((cone.factor(mid) - 0.25).abs() < 1e-4, "{}", cone.factor(mid));
        // A cone with (almost) no falloff is a step at its outer angle.
        let hard = Cone { inner: 0.5, outer: 0.5 + 1e-6 };
        assert_eq!(hard.factor(0.49f32.cos()), 1.0);
        assert_eq!(hard.factor(0.51f32.cos()), 0.0);
    }

    #[test]
    fn bad_cones_say_why() {
        assert!(Cone::GLTF_DEFAULT.check().is_ok());
        for (inner, outer) in [(0.5, 0.5), (0.6, 0.5), (-0.1, 0.5), (0.0, 1.6), (f32::NAN, 0.5)] {
            let why = Cone { inner, outer }.check().unwrap_err();
            assert!(why.contains("cone angles must"), "{why}");
        }
    }
}

//! Light sources and distance attenuation (SPEC §5).

use glam::Vec3;

/// Distance attenuation f(d) = min(1, 1/(a0 + a1·d + a2·d²)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation {
    /// Constant term.
    pub a0: f32,
    /// Linear term.
    pub a1: f32,
    /// Quadratic term.
    pub a2: f32,
}

impl Attenuation {
    /// No attenuation: f(d) = 1 everywhere.
    pub const NONE: Attenuation = Attenuation { a0: 1.0, a1: 0.0, a2: 0.0 };

    /// f(d) for a distance `d ≥ 0`. A denominator ≤ 0 (never produced by
    /// non-negative coefficients) yields 1, the clamp's value.
    #[inline]
    pub fn factor(&self, d: f32) -> f32 {
        let denom = self.a0 + d * (self.a1 + d * self.a2);
        if denom > 1.0 {
            1.0 / denom
        } else {
            1.0
        }
    }

    /// True when f(d) = 1 for every distance, so `d` need not be computed.
    #[inline]
    pub fn is_none(&self) -> bool {
        self.a0 <= 1.0 && self.a1 == 0.0 && self.a2 == 0.0
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
            Light::Point { color, .. } | Light::Directional { color, .. } => color,
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
            Light::Directional { direction, color } => {
                Light::Directional { direction: to.transform_vector3(direction), color }
            }
        }
    }
}

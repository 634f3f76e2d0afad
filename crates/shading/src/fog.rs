//! Fog (SPEC §8): a factor f from the fog coordinate, then
//! C = f·C_surface + (1 − f)·C_fog, per sample, after lighting and before
//! transparency blending.

use glam::Vec3;

/// How the fog factor falls off with distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FogMode {
    /// f = (end − z)/(end − start).
    Linear {
        /// Distance where fog starts (f = 1).
        start: f32,
        /// Distance where fog is complete (f = 0).
        end: f32,
    },
    /// f = e^(−ρ·z).
    Exponential {
        /// Density ρ.
        density: f32,
    },
    /// f = e^(−(ρ·z)²).
    SquaredExponential {
        /// Density ρ.
        density: f32,
    },
}

/// What distance the fog coordinate measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FogCoordinate {
    /// Distance to the eye plane, −z_eye (SPEC §8 default).
    #[default]
    EyePlane,
    /// Distance to the eye, |p_eye|.
    Radial,
}

/// Fog settings for a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// Fall-off.
    pub mode: FogMode,
    /// Fog colour C_fog.
    pub color: Vec3,
    /// Which distance is the fog coordinate.
    pub coordinate: FogCoordinate,
}

impl Fog {
    /// The fog factor f for fog coordinate `z`, clamped to [0, 1] (a NaN
    /// coordinate gives 0: full fog). A linear fog with end = start is a
    /// step: 1 before `start`, 0 from it on.
    #[inline]
    #[expect(clippy::manual_clamp, reason = "max/min map NaN to 0; clamp would keep it")]
    pub fn factor(&self, z: f32) -> f32 {
        let f = match self.mode {
            FogMode::Linear { start, end } => {
                if end == start {
                    if z < start {
                        1.0
                    } else {
                        0.0
                    }
                } else {
                    (end - z) / (end - start)
                }
            }
            FogMode::Exponential { density } => (-density * z).exp(),
            FogMode::SquaredExponential { density } => {
                let d = density * z;
                (-(d * d)).exp()
            }
        };
        // max/min map NaN to the other operand: a NaN f becomes 0.
        f.max(0.0).min(1.0)
    }

    /// C = f·C_surface + (1 − f)·C_fog for fog coordinate `z`.
    #[inline]
    pub fn apply(&self, surface: Vec3, z: f32) -> Vec3 {
        let f = self.factor(z);
        surface * f + self.color * (1.0 - f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fog(mode: FogMode) -> Fog {
        Fog { mode, color: Vec3::new(0.5, 0.6, 0.7), coordinate: FogCoordinate::EyePlane }
    }

    #[test]
    fn linear_factor_at_chosen_depths_with_clamps() {
        let f = fog(FogMode::Linear { start: 10.0, end: 30.0 });
        assert_eq!(f.factor(5.0), 1.0); // before start: clamped
        assert_eq!(f.factor(10.0), 1.0);
        assert_eq!(f.factor(15.0), 0.75); // (30 − 15)/20
        assert_eq!(f.factor(20.0), 0.5);
        assert_eq!(f.factor(30.0), 0.0);
        assert_eq!(f.factor(100.0), 0.0); // past end: clamped
        assert_eq!(f.factor(f32::NAN), 0.0);
        let step = fog(FogMode::Linear { start: 4.0, end: 4.0 });
        assert_eq!((step.factor(3.9), step.factor(4.0)), (1.0, 0.0));
    }

    #[test]
    fn exponential_factors_at_chosen_depths() {
        let e = fog(FogMode::Exponential { density: 0.5 });
        assert_eq!(e.factor(0.0), 1.0);
        assert!((e.factor(2.0) - (-1.0f32).exp()).abs() < 1e-7); // e^(−0.5·2)
        assert!((e.factor(4.0) - (-2.0f32).exp()).abs() < 1e-7);
        let e2 = fog(FogMode::SquaredExponential { density: 0.5 });
        assert!((e2.factor(2.0) - (-1.0f32).exp()).abs() < 1e-7); // e^(−(0.5·2)²)
        assert!((e2.factor(4.0) - (-4.0f32).exp()).abs() < 1e-7);
        // Negative coordinates (behind the eye plane) clamp to 1.
        assert_eq!(e.factor(-3.0), 1.0);
    }

    #[test]
    fn apply_blends_towards_the_fog_colour() {
        let f = fog(FogMode::Linear { start: 0.0, end: 4.0 });
        let c = f.apply(Vec3::new(1.0, 0.0, 0.2), 1.0); // f = 0.75
        assert!((c - Vec3::new(0.875, 0.15, 0.325)).abs().max_element() < 1e-6, "{c}");
    }
}

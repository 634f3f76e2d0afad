//! Fog (SPEC §8) in f64: the factor from the eye-space position of the
//! surface point, C = f·C_surface + (1 − f)·C_fog.
//!
//! The coordinate is −z_eye (eye-plane) or |p_eye| (radial) of the exact
//! surface point at the sample — its perspective-correct position, whatever
//! the attribute interpolation mode, as the fast renderer recovers it from
//! the depth buffer. f is clamped to [0, 1]; NaN gives 0 (full fog); a
//! linear fog with end = start is a step, 1 before `start` and 0 from it on
//! (the conventions of `zline_shading::Fog`).

use glam::DVec3;
use zline_shading::{Fog, FogCoordinate, FogMode};

/// The fog factor at eye-space point `eye`.
pub(crate) fn fog_factor(fog: &Fog, eye: DVec3) -> f64 {
    let z = match fog.coordinate {
        FogCoordinate::EyePlane => -eye.z,
        FogCoordinate::Radial => eye.length(),
    };
    let f = match fog.mode {
        FogMode::Linear { start, end } if end == start => {
            if z < f64::from(start) {
                1.0
            } else {
                0.0
            }
        }
        FogMode::Linear { start, end } => (f64::from(end) - z) / (f64::from(end) - f64::from(start)),
        FogMode::Exponential { density } => (-f64::from(density) * z).exp(),
        FogMode::SquaredExponential { density } => (-(f64::from(density) * z).powi(2)).exp(),
    };
    if f.is_nan() {
        0.0
    } else {
        f.clamp(0.0, 1.0)
    }
}

/// C = f·C_surface + (1 − f)·C_fog.
pub(crate) fn apply_fog(fog: &Fog, surface: DVec3, eye: DVec3) -> DVec3 {
    let f = fog_factor(fog, eye);
    surface * f + fog.color.as_dvec3() * (1.0 - f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn factors_follow_the_formulas() {
        let fog = |mode| Fog { mode, color: Vec3::ONE, coordinate: FogCoordinate::EyePlane };
        let p = DVec3::new(3.0, 4.0, -15.0);
        assert_eq!(fog_factor(&fog(FogMode::Linear { start: 10.0, end: 30.0 }), p), 0.75);
        let e = fog_factor(&fog(FogMode::Exponential { density: 0.125 }), p);
        assert!((e - (-1.875f64).exp()).abs() < 1e-15);
        let e2 = fog_factor(&fog(FogMode::SquaredExponential { density: 0.125 }), p);
        assert!((e2 - (-3.515625f64).exp()).abs() < 1e-15);
        let radial =
            Fog { coordinate: FogCoordinate::Radial, ..fog(FogMode::Linear { start: 0.0, end: 50.0 }) };
        let d = (9.0f64 + 16.0 + 225.0).sqrt();
        assert!((fog_factor(&radial, p) - (50.0 - d) / 50.0).abs() < 1e-15);
        assert_eq!(fog_factor(&fog(FogMode::Linear { start: 4.0, end: 4.0 }), p), 0.0);
    }
}

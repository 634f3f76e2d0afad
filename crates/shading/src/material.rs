//! Surface materials: the coefficients of the lighting model (SPEC §5, §9).

use glam::Vec3;

/// Coefficients of the lighting model for one surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Emission coefficient ke (RGB, in [0, 1]): light the surface gives
    /// off by itself, added to the lit colour before the clamp,
    /// I = ke + ka·Ia + … (glTF `emissiveFactor`, MTL `Ke`). A texture does
    /// not modulate it.
    pub ke: Vec3,
    /// Ambient reflection coefficient ka (RGB, in [0, 1]).
    pub ka: Vec3,
    /// Diffuse reflection coefficient kd (RGB, in [0, 1]).
    pub kd: Vec3,
    /// Specular reflection coefficient ks (RGB, in [0, 1]).
    pub ks: Vec3,
    /// Shininess exponent ns (≥ 0).
    pub ns: f32,
    /// Opacity d in [0, 1]; transparency kt = 1 − d (SPEC §9).
    pub opacity: f32,
}

impl Material {
    /// A matte grey material, the default for models without an MTL file.
    pub const DEFAULT: Material = Material {
        ke: Vec3::ZERO,
        ka: Vec3::splat(0.8),
        kd: Vec3::splat(0.8),
        ks: Vec3::splat(0.2),
        ns: 32.0,
        opacity: 1.0,
    };

    /// A material with ka = kd = `color`, the given specular and shininess,
    /// no emission.
    pub fn plastic(color: Vec3, ks: f32, ns: f32) -> Material {
        Material { ke: Vec3::ZERO, ka: color, kd: color, ks: Vec3::splat(ks), ns, opacity: 1.0 }
    }

    /// True when the specular term contributes nothing for any light.
    #[inline]
    pub fn has_specular(&self) -> bool {
        self.ks.max_element() > 0.0
    }

    /// The same material with every coefficient clamped to its valid range
    /// and non-finite values replaced by 0 (shininess by 1).
    pub fn sanitized(&self) -> Material {
        let c = |v: Vec3| {
            let v = Vec3::select(v.is_nan_mask(), Vec3::ZERO, v);
            v.clamp(Vec3::ZERO, Vec3::ONE)
        };
        let ns = if self.ns.is_finite() { self.ns.max(0.0) } else { 1.0 };
        let opacity = if self.opacity.is_nan() { 1.0 } else { self.opacity.clamp(0.0, 1.0) };
        Material { ke: c(self.ke), ka: c(self.ka), kd: c(self.kd), ks: c(self.ks), ns, opacity }
    }
}

impl Default for Material {
    fn default() -> Self {
        Material::DEFAULT
    }
}

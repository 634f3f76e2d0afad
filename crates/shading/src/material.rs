//! Surface materials: the coefficients of the lighting model (SPEC §5, §9).

use glam::Vec3;

use crate::pbr::Microfacet;

/// The reflection model that lights a surface (SPEC §5).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Model {
    /// The basic lighting model of SPEC §5.1: ke, ka, kd, ks, ns.
    #[default]
    Basic,
    /// The Cook–Torrance microfacet model of SPEC §5.2, with the base
    /// colour kd (ka, ks and ns unused): glTF's metallic–roughness
    /// material, or the course's Torrance–Sparrow/Cook–Torrance with the
    /// Beckmann distribution.
    CookTorrance(Microfacet),
}

impl Model {
    /// The lower-case name the CLI and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            Model::Basic => "basic",
            Model::CookTorrance(_) => "cook-torrance",
        }
    }
}

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
    /// The reflection model: the basic one, or Cook–Torrance with kd as
    /// its base colour.
    pub model: Model,
    /// Mirror reflection coefficient kr (RGB, in [0, 1]): the weight of the
    /// reflected ray in the Whitted model (SPEC §12; MTL `Ks` with an
    /// `illum` that turns reflection on). The rasterizer ignores it.
    pub kr: Vec3,
    /// Index of refraction η of the material's inside (> 0; 1 bends
    /// nothing): the Whitted model refracts the transmitted ray (weight kt =
    /// 1 − opacity) by it (MTL `Ni`, glTF `KHR_materials_ior`). The
    /// rasterizer ignores it.
    pub ior: f32,
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
        model: Model::Basic,
        kr: Vec3::ZERO,
        ior: 1.0,
    };

    /// A material with ka = kd = `color`, the given specular and shininess,
    /// no emission.
    pub fn plastic(color: Vec3, ks: f32, ns: f32) -> Material {
        Material {
            ke: Vec3::ZERO,
            ka: color,
            kd: color,
            ks: Vec3::splat(ks),
            ns,
            opacity: 1.0,
            model: Model::Basic,
            kr: Vec3::ZERO,
            ior: 1.0,
        }
    }

    /// True when the specular term contributes nothing for any light
    /// (the basic model with ks = 0; a Cook–Torrance surface always has
    /// one).
    #[inline]
    pub fn has_specular(&self) -> bool {
        match self.model {
            Model::Basic => self.ks.max_element() > 0.0,
            Model::CookTorrance(_) => true,
        }
    }

    /// The same material lit by `model` instead (the CLI's side-by-side
    /// switch): to Cook–Torrance, a basic material becomes a dielectric
    /// (metallic 0) of base colour kd and the roughness whose GGX lobe is
    /// closest to its Blinn–Phong exponent (α² = 2/(ns + 2)); to basic, a
    /// Cook–Torrance material keeps kd and takes ka = kd, ks =
    /// mix(0.04, kd, metallic)·(1 − roughness) and ns = 2/α² − 2, within
    /// [1, 1024].
    pub fn with_model(&self, model: ModelChoice) -> Material {
        match (model, self.model) {
            (ModelChoice::Basic, Model::CookTorrance(m)) => {
                let (_, f0) = m.colors(self.kd);
                let alpha2 = m.alpha2();
                Material {
                    ka: self.kd,
                    ks: f0 * (1.0 - m.roughness),
                    ns: (2.0 / alpha2 - 2.0).clamp(1.0, 1024.0),
                    model: Model::Basic,
                    ..*self
                }
            }
            (ModelChoice::CookTorrance(distribution), Model::Basic) => {
                let alpha2 = (2.0 / (self.ns.max(0.0) + 2.0)).min(1.0);
                let roughness = alpha2.sqrt().sqrt();
                Material {
                    model: Model::CookTorrance(Microfacet { metallic: 0.0, roughness, distribution }),
                    ..*self
                }
            }
            (ModelChoice::CookTorrance(distribution), Model::CookTorrance(m)) => {
                Material { model: Model::CookTorrance(Microfacet { distribution, ..m }), ..*self }
            }
            (ModelChoice::Basic, Model::Basic) => *self,
        }
    }

    /// The same material with every coefficient clamped to its valid range
    /// and non-finite values replaced by 0 (shininess by 1, an index of
    /// refraction that is not a finite number > 0 by 1).
    pub fn sanitized(&self) -> Material {
        let c = |v: Vec3| {
            let v = Vec3::select(v.is_nan_mask(), Vec3::ZERO, v);
            v.clamp(Vec3::ZERO, Vec3::ONE)
        };
        let ns = if self.ns.is_finite() { self.ns.max(0.0) } else { 1.0 };
        let opacity = if self.opacity.is_nan() { 1.0 } else { self.opacity.clamp(0.0, 1.0) };
        let model = match self.model {
            Model::Basic => Model::Basic,
            Model::CookTorrance(m) => Model::CookTorrance(m.sanitized()),
        };
        // An index of refraction must be a finite number > 0 (0, negative
        // or NaN would turn Snell's law into nonsense): else 1.
        let ior = if self.ior.is_finite() && self.ior > 0.0 { self.ior } else { 1.0 };
        Material {
            ke: c(self.ke),
            ka: c(self.ka),
            kd: c(self.kd),
            ks: c(self.ks),
            ns,
            opacity,
            model,
            kr: c(self.kr),
            ior,
        }
    }
}

/// A model to force on every material ([`Material::with_model`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ModelChoice {
    /// The basic model.
    Basic,
    /// Cook–Torrance with this distribution.
    CookTorrance(crate::pbr::Distribution),
}

impl Default for Material {
    fn default() -> Self {
        Material::DEFAULT
    }
}

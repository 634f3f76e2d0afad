//! The lighting model prepared for many evaluations in one frame.
//!
//! [`LightingModel::shade_parts`] is the plain statement of SPEC §5. A frame
//! evaluates it millions of times with the same lights and materials, so
//! [`PreparedLights`] does once what does not change per sample: directional
//! lights get their unit L, point lights whose attenuation is 1 everywhere
//! skip the distance polynomial (and plain ones the range window and the
//! spot cone), and [`PreparedMaterial`] turns an integer
//! shininess into repeated squaring instead of `powf` (which measured about
//! a fifth of a Phong frame). The results agree with `shade_parts` to f32
//! rounding; a property test checks it.

use glam::{Mat4, Vec3};

use crate::environment::{Environment, PreparedEnvironment};
use crate::light::{Attenuation, Cone, Light};
use crate::material::{Material, Model};
use crate::model::{LightingModel, LitParts};
use crate::pbr::{Microfacet, MicrofacetSums};

/// A directional light with its unit vector towards the light.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Directional {
    to_light: Vec3,
    color: Vec3,
    /// The light's index in the scene's list (its shadow bit).
    index: u32,
}

/// A point or spot light; `attenuation` is `None` when its polynomial is 1
/// everywhere, `shape` when it has neither a range nor a cone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Point {
    pub(crate) position: Vec3,
    pub(crate) color: Vec3,
    pub(crate) attenuation: Option<Attenuation>,
    pub(crate) shape: Option<Shape>,
    /// The light's index in the scene's list (its shadow bit).
    pub(crate) index: u32,
}

impl Point {
    /// The light at `position` of `color` and `attenuation`, a spot with
    /// its unit axis and cone when `spot` is given.
    fn new(
        (position, color, attenuation): (Vec3, Vec3, Attenuation),
        spot: Option<(Vec3, Cone)>,
        index: u32,
    ) -> Point {
        let shape = Shape::new(attenuation, spot);
        let attenuation = (!attenuation.is_polynomial_none()).then_some(attenuation);
        Point { position, color, attenuation, shape, index }
    }

    /// The light's intensity at distance `dist` along the unit
    /// `to_light`: its colour times the attenuation polynomial, then
    /// times its shape's factor. The order the lanes keep
    /// ([`crate::simd`]'s light fold).
    #[inline(always)]
    fn intensity(&self, to_light: Vec3, dist: f32) -> Vec3 {
        let c = self.color * self.attenuation.map_or(1.0, |a| a.polynomial(dist));
        match &self.shape {
            None => c,
            Some(shape) => c * shape.factor(to_light, dist),
        }
    }
}

/// What limits a point light's reach besides its attenuation polynomial:
/// the range window and a spot light's cone (SPEC §5.1), as one formula
/// whose neutral values give exactly 1. The factor is w·c², where the
/// window w is clamp(1 − x⁴, 0, 1) for x = d/range (x = 0 without a
/// range) and the cone's c is clamp(offset − (L·S)·scale, 0, 1) (S = 0
/// and offset = 1 without a cone). The kernels evaluate it in line with
/// the same operations ([`crate::simd`]'s light fold): an out-of-line
/// call inside the light loop cost the Phong kernels 5 % of their wall
/// time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Shape {
    /// 1/range; 0 without a range.
    pub(crate) inv_range: f32,
    /// The unit axis the spot points along; zero without a cone.
    pub(crate) axis: Vec3,
    /// The cone's scale and offset ([`Cone::scale_offset`]); (0, 1)
    /// without a cone.
    pub(crate) scale: f32,
    pub(crate) offset: f32,
}

impl Shape {
    /// The shape of a light with `attenuation` and, for a spot light, its
    /// unit axis and cone; `None` when both are plain.
    fn new(attenuation: Attenuation, spot: Option<(Vec3, Cone)>) -> Option<Shape> {
        let ranged = attenuation.has_range();
        if !ranged && spot.is_none() {
            return None;
        }
        let inv_range = if ranged { 1.0 / attenuation.range } else { 0.0 };
        let (axis, (scale, offset)) = match spot {
            Some((axis, cone)) => (axis, cone.scale_offset()),
            None => (Vec3::ZERO, (0.0, 1.0)),
        };
        Some(Shape { inv_range, axis, scale, offset })
    }

    /// The range window at `dist` times the cone's factor for the unit
    /// `to_light` (from the surface to the light).
    #[inline]
    pub(crate) fn factor(&self, to_light: Vec3, dist: f32) -> f32 {
        let x = dist * self.inv_range;
        let x2 = x * x;
        let window = crate::pbr::clamp01(1.0 - x2 * x2);
        let c = crate::pbr::clamp01(self.offset - to_light.dot(self.axis) * self.scale);
        window * (c * c)
    }
}

/// Lights in the frame where shading happens, ready for per-sample use.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PreparedLights {
    ambient: Vec3,
    /// The environment map with the ambient folded in, when there is one.
    environment: Option<PreparedEnvironment>,
    /// Keep lit colours above 1 (a tone mapping follows): see
    /// [`PreparedLights::ceiling`].
    keep_above_one: bool,
    directional: Vec<Directional>,
    point: Vec<Point>,
}

/// The specular exponent, in the cheapest exact-enough form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shininess {
    /// A whole exponent in 0..=1024: repeated squaring.
    Whole(u32),
    /// Any other exponent: `powf`.
    Real(f32),
}

impl Shininess {
    /// The form for exponent `ns`.
    pub fn new(ns: f32) -> Shininess {
        if ns.fract() == 0.0 && (0.0..=1024.0).contains(&ns) {
            Shininess::Whole(ns as u32)
        } else {
            Shininess::Real(ns)
        }
    }

    /// x^ns for x in [0, 1].
    #[inline]
    pub fn pow(self, x: f32) -> f32 {
        match self {
            Shininess::Whole(n) => pow_by_squaring(x, 1.0, n),
            Shininess::Real(ns) => x.powf(ns),
        }
    }
}

/// x^n by repeated squaring (`one` is the multiplicative identity), for f32
/// and for SIMD lanes alike: the same multiplications in the same order.
/// The product starts at the lowest set bit's power of x instead of at
/// `one`: 1·y is y, bit for bit, so that first multiplication only added
/// its latency to the specular term's dependent chain (1 % of the Phong
/// sphere's frame). The last base is not squared, so nothing past x^n is
/// computed.
#[inline(always)]
pub(crate) fn pow_by_squaring<T: Copy + std::ops::MulAssign>(x: T, one: T, mut n: u32) -> T {
    if n == 0 {
        return one;
    }
    let mut base = x;
    while n & 1 == 0 {
        base *= base;
        n >>= 1;
    }
    let mut acc = base;
    n >>= 1;
    while n != 0 {
        base *= base;
        if n & 1 == 1 {
            acc *= base;
        }
        n >>= 1;
    }
    acc
}

/// The texels of a Cook–Torrance material's maps at one sample (the
/// scalar twin of `MapTexels`): each `None` where the material has no such
/// map.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Surface {
    /// glTF's metallic–roughness texture: (B, G), multiplying the metallic
    /// and roughness factors.
    pub metallic_roughness: Option<(f32, f32)>,
    /// The occlusion 1 + strength·(R − 1), multiplying the ambient term.
    pub occlusion: Option<f32>,
    /// The emissive texture's RGB, multiplying ke.
    pub emission: Option<Vec3>,
}

impl Surface {
    /// No maps.
    pub const NONE: Surface = Surface { metallic_roughness: None, occlusion: None, emission: None };
}

/// A material with its specular exponent prepared.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedMaterial {
    /// The material.
    pub material: Material,
    /// Its shininess.
    pub shininess: Shininess,
    /// False when ks = 0: the specular term is skipped.
    pub specular: bool,
    /// N·H at or below which (N·H)^ns < [`SPECULAR_CUTOFF`]: the term is
    /// skipped there. Besides saving the power, this keeps the arithmetic
    /// out of subnormal floats, which cost ~100 cycles per operation on x86.
    pub specular_threshold: f32,
    /// For a surface that receives shadows: the first bit of its lights in
    /// a sample's shadow mask. Light k (its index in the scene's list) is
    /// hidden at a sample whose mask has bit `first + k` set
    /// ([`PreparedLights::shade_x8_with`]'s mask).
    pub shadow_bits: Option<u32>,
    /// For a Cook–Torrance material: its parameters and α².
    pub microfacet: Option<(Microfacet, f32)>,
}

/// The smallest (N·H)^ns the lighting model evaluates; below it the term is
/// 0. With light intensities and ks ≤ 1 that changes a colour by less than
/// 2^-24, far below the 8-bit output step of 2^-8.
pub const SPECULAR_CUTOFF: f32 = 1.0 / (1u32 << 24) as f32;

impl PreparedMaterial {
    /// Prepares `material` (assumed sanitized).
    pub fn new(material: Material) -> PreparedMaterial {
        let ns = material.ns;
        let specular_threshold = if ns > 0.0 { SPECULAR_CUTOFF.powf(1.0 / ns) } else { 0.0 };
        PreparedMaterial {
            material,
            shininess: Shininess::new(ns),
            specular: material.has_specular(),
            specular_threshold,
            shadow_bits: None,
            microfacet: match material.model {
                Model::Basic => None,
                Model::CookTorrance(m) => Some((m, m.alpha2())),
            },
        }
    }
}

/// Running sums of the diffuse and specular terms over the lights.
#[derive(Default)]
struct Sums {
    diffuse: Vec3,
    specular: Vec3,
}

impl Sums {
    #[inline(always)]
    fn add(&mut self, m: &PreparedMaterial, normal: Vec3, view: Vec3, to_light: Vec3, intensity: Vec3) {
        let n_dot_l = normal.dot(to_light);
        if n_dot_l <= 0.0 {
            return;
        }
        self.diffuse += intensity * n_dot_l;
        if m.specular {
            let n_dot_h = normal.dot((to_light + view).normalize_or_zero());
            if n_dot_h > m.specular_threshold {
                self.specular += intensity * m.shininess.pow(n_dot_h);
            }
        }
    }
}

impl PreparedLights {
    /// The lights of `model` expressed through `to` (see
    /// [`Light::transformed`]), prepared.
    pub fn new(model: &LightingModel, to: &Mat4) -> PreparedLights {
        let mut out = PreparedLights::default();
        out.prepare((model.ambient, model.environment.as_ref()), &model.lights, to);
        out
    }

    /// Prepares the ambient light, the environment map if any and `lights`
    /// expressed through `to` in place, reusing this value's storage: a
    /// renderer that prepares its lights every frame allocates only when
    /// the scene gains lights.
    pub fn prepare(
        &mut self,
        (ambient, environment): (Vec3, Option<&Environment>),
        lights: &[Light],
        to: &Mat4,
    ) {
        self.ambient = ambient;
        self.environment = environment.map(|e| e.transformed(to).prepare(ambient));
        self.directional.clear();
        self.point.clear();
        for (index, light) in lights.iter().enumerate() {
            let index = index as u32;
            match light.transformed(to) {
                Light::Directional { direction, color } => {
                    let to_light = -direction.normalize_or_zero();
                    if to_light != Vec3::ZERO {
                        self.directional.push(Directional { to_light, color, index });
                    }
                }
                Light::Point { position, color, attenuation } => {
                    self.point.push(Point::new((position, color, attenuation), None, index));
                }
                Light::Spot { position, direction, color, attenuation, cone } => {
                    let spot = Some((direction.normalize_or_zero(), cone));
                    self.point.push(Point::new((position, color, attenuation), spot, index));
                }
            }
        }
    }

    /// SPEC §5 at `point` with unit `normal`, seen from `eye`: the same
    /// quantity as [`LightingModel::shade_parts`].
    #[inline]
    pub fn shade_parts(&self, m: &PreparedMaterial, point: Vec3, normal: Vec3, eye: Vec3) -> LitParts {
        if let Some(microfacet) = m.microfacet {
            return self.microfacet_parts(
                m,
                (microfacet, Surface::NONE),
                (point, normal, eye),
                m.material.kd,
            );
        }
        let view = (eye - point).normalize_or_zero();
        let mut sum = Sums::default();
        for d in &self.directional {
            sum.add(m, normal, view, d.to_light, d.color);
        }
        for p in &self.point {
            let v = p.position - point;
            let dist = v.length();
            if dist == 0.0 {
                continue;
            }
            let to_light = v / dist;
            sum.add(m, normal, view, to_light, p.intensity(to_light, dist));
        }
        let (diffuse, specular) = (sum.diffuse, sum.specular);
        let mat = &m.material;
        let ambient = self.environment.as_ref().map_or(self.ambient, |e| e.diffuse(normal));
        LitParts {
            ambient_diffuse: mat.ka * ambient + mat.kd * diffuse,
            specular: mat.ke + mat.ks * specular,
        }
    }

    /// The unclamped colour at `point` where `modulate` multiplies the
    /// material's colour (a texel, a vertex colour): the basic model's
    /// `modulate(ambient+diffuse) + specular` (SPEC §7), or Cook–Torrance
    /// with the base colour `modulate(kd)` and the texels of its maps
    /// (`maps`). The scalar twin of the kernels' lighting seam,
    /// [`Self::shade_x8_with`].
    #[inline]
    pub fn shade_modulated(
        &self,
        m: &PreparedMaterial,
        (point, normal, eye): (Vec3, Vec3, Vec3),
        modulate: impl Fn(Vec3) -> Vec3,
        maps: Surface,
    ) -> Vec3 {
        match m.microfacet {
            None => {
                let parts = self.shade_parts(m, point, normal, eye);
                modulate(parts.ambient_diffuse) + parts.specular
            }
            Some(microfacet) => {
                let microfacet = match maps.metallic_roughness {
                    None => microfacet,
                    Some((b, g)) => {
                        let (m, _) = microfacet;
                        let mapped = Microfacet { metallic: m.metallic * b, roughness: m.roughness * g, ..m };
                        (mapped, mapped.alpha2())
                    }
                };
                let parts = self.microfacet_parts(
                    m,
                    (microfacet, maps),
                    (point, normal, eye),
                    modulate(m.material.kd),
                );
                parts.ambient_diffuse + parts.specular
            }
        }
    }

    /// SPEC §5.2 at `point` for a surface of base colour `base`:
    /// ambient+diffuse (the diffuse lobe and the environment's diffuse
    /// share) and emission+specular.
    #[inline]
    fn microfacet_parts(
        &self,
        m: &PreparedMaterial,
        ((microfacet, alpha2), maps): ((Microfacet, f32), Surface),
        (point, normal, eye): (Vec3, Vec3, Vec3),
        base: Vec3,
    ) -> LitParts {
        let view = (eye - point).normalize_or_zero();
        let nv = crate::pbr::clamp01(normal.dot(view));
        let (_, f0) = microfacet.colors(base);
        let mut sums = MicrofacetSums::default();
        for d in &self.directional {
            sums.add((&microfacet, alpha2, f0), normal, view, nv, d.to_light, d.color);
        }
        for p in &self.point {
            let v = p.position - point;
            let dist = v.length();
            if dist == 0.0 {
                continue;
            }
            let to_light = v / dist;
            sums.add((&microfacet, alpha2, f0), normal, view, nv, to_light, p.intensity(to_light, dist));
        }
        let mut light = match &self.environment {
            None => (self.ambient, self.ambient),
            Some(e) => {
                (e.diffuse(normal), e.specular(crate::pbr::reflect(view, normal), microfacet.roughness))
            }
        };
        if let Some(o) = maps.occlusion {
            light = (light.0 * o, light.1 * o);
        }
        let ke = maps.emission.map_or(m.material.ke, |e| m.material.ke * e);
        let (ambient_diffuse, specular) = sums.parts(&microfacet, base, ke, light, nv);
        LitParts { ambient_diffuse, specular }
    }

    /// Ambient light Ia.
    pub(crate) fn ambient(&self) -> Vec3 {
        self.ambient
    }

    /// The environment map, prepared with the ambient folded in.
    pub(crate) fn environment(&self) -> Option<&PreparedEnvironment> {
        self.environment.as_ref()
    }

    /// True when the ambient light is the same in every direction (no
    /// environment map): what the adaptive mode's bounds assume.
    pub fn uniform_ambient(&self) -> bool {
        self.environment.is_none()
    }

    /// (unit vector towards the light, colour, index in the scene's list)
    /// of each directional light.
    pub(crate) fn directional_lights(&self) -> impl Iterator<Item = (Vec3, Vec3, u32)> + '_ {
        self.directional.iter().map(|d| (d.to_light, d.color, d.index))
    }

    /// The point and spot lights.
    pub(crate) fn point_lights(&self) -> &[Point] {
        &self.point
    }

    /// [`Self::shade_parts`], summed and clamped to [0, 1].
    #[inline]
    pub fn shade(&self, m: &PreparedMaterial, point: Vec3, normal: Vec3, eye: Vec3) -> Vec3 {
        self.shade_parts(m, point, normal, eye).color_below(self.ceiling())
    }

    /// The largest value a lit colour keeps per channel: 1 (SPEC §5's
    /// clamp), or f32::MAX when a tone mapping follows and must see the
    /// colour unclamped (SPEC §10).
    #[inline]
    pub fn ceiling(&self) -> f32 {
        if self.keep_above_one {
            f32::MAX
        } else {
            1.0
        }
    }

    /// Keeps lit colours above 1 when `tone_mapping` is not the identity.
    pub fn set_tone_mapping(&mut self, tone_mapping: &crate::tonemap::ToneMapping) {
        self.keep_above_one = !tone_mapping.is_identity();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn unit() -> impl Strategy<Value = Vec3> {
        vec3().prop_filter("non-zero", |v| v.length() > 0.1).prop_map(|v| v.normalize())
    }

    #[test]
    fn whole_powers_match_powf() {
        for n in [0u32, 1, 2, 7, 32, 100, 1024] {
            for x in [0.0f32, 0.3, 0.9, 0.999, 1.0] {
                let (got, want) = (Shininess::Whole(n).pow(x), x.powf(n as f32));
                assert!((got - want).abs() <= 1e-5 * want.max(1e-30), "{x}^{n}: {got} vs {want}");
            }
        }
        assert_eq!(Shininess::new(12.0), Shininess::Whole(12));
        assert_eq!(Shininess::new(12.5), Shininess::Real(12.5));
    }

    /// The multiplications of the textbook loop, the product starting at 1.
    fn pow_from_one(x: f32, mut n: u32) -> f32 {
        let (mut base, mut acc) = (x, 1.0f32);
        while n != 0 {
            if n & 1 == 1 {
                acc *= base;
            }
            n >>= 1;
            if n != 0 {
                base *= base;
            }
        }
        acc
    }

    proptest! {
        // Cheap: up to 64 multiplications a case.
        #![proptest_config(ProptestConfig::with_cases(2048))]
        #[test]
        fn powers_equal_the_product_from_one_bit_for_bit(
            x in prop_oneof![-2.0f32..2.0, Just(f32::MIN_POSITIVE / 4.0), Just(-0.0f32), Just(f32::NAN), Just(f32::INFINITY)],
            n in prop_oneof![0u32..300, any::<u32>()],
        ) {
            let (got, want) = (pow_by_squaring(x, 1.0, n), pow_from_one(x, n));
            prop_assert!(got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()), "{x}^{n}: {got} vs {want}");
        }
    }

    proptest! {
        // 256 cases: each is a handful of vector operations.
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn prepared_agrees_with_the_plain_model(
            p in vec3(), n in unit(), eye in vec3(), light_pos in vec3(), dir in unit(),
            ns in prop_oneof![Just(1.0f32), Just(16.0), Just(64.0), 0.5f32..100.0],
            a1 in 0.0f32..1.0, a2 in 0.0f32..1.0, range in prop_oneof![Just(f32::INFINITY), 0.5f32..20.0],
            spot_pos in vec3(), axis in unit(), inner in 0.0f32..1.0, width in 0.01f32..0.5,
        ) {
            let attenuation = Attenuation::new(1.0, a1, a2).with_range(range);
            let cone = Cone { inner, outer: inner + width };
            let model = LightingModel {
                ambient: Vec3::new(0.1, 0.2, 0.3),
                lights: vec![
                    Light::Point { position: light_pos, color: Vec3::new(1.0, 0.5, 0.25), attenuation },
                    Light::Directional { direction: dir * 3.0, color: Vec3::new(0.3, 0.6, 0.9) },
                    Light::Spot { position: spot_pos, direction: axis * 2.0, color: Vec3::new(0.5, 0.7, 0.2), attenuation, cone },
                ],
                environment: None,
            };
            let m = Material { ke: Vec3::new(0.05, 0.0, 0.1), ka: Vec3::splat(0.2), kd: Vec3::new(0.9, 0.5, 0.1), ks: Vec3::splat(0.7), ns, opacity: 1.0, model: crate::material::Model::Basic, ..Material::DEFAULT };
            let plain = model.shade_parts(&m, p, n, eye);
            let prepared = PreparedLights::new(&model, &Mat4::IDENTITY).shade_parts(&PreparedMaterial::new(m), p, n, eye);
            let err = (plain.ambient_diffuse - prepared.ambient_diffuse).abs().max_element()
                .max((plain.specular - prepared.specular).abs().max_element());
            prop_assert!(err < 2e-5 + 2.0 * SPECULAR_CUTOFF, "{plain:?} vs {prepared:?}");
        }
    }
}

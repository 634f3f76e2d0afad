//! The `[[lights]]` entries of a scene file: point, spot and directional lights,
//! and area lights (`rect`, `disc`) expanded into their k × k samples — k
//! given, or chosen once the scene is built (`samples = "auto"`,
//! [`zline_scene::choose_area_samples`]).

use std::path::Path;

use glam::Vec3;
use serde::Deserialize;
use zline_scene::{choose_area_samples, AreaLight, AreaShape, Scene, ShadowMode, MAX_AREA_SAMPLES_PER_SIDE};
use zline_shading::{Attenuation, Cone, Light};

use super::checks::{Checker, Result, S};

/// An area light's default samples per side (4 × 4 point lights).
const DEFAULT_AREA_SAMPLES: u32 = 4;

/// The default tolerance of `samples = "auto"`: 1 step of 8 bits, RMSE.
pub(super) const DEFAULT_AUTO_TOLERANCE: f32 = 1.0;

/// The largest tolerance `samples = "auto"` accepts (8-bit steps).
const MAX_AUTO_TOLERANCE: f32 = 255.0;

/// `samples = k` or `samples = "auto"`.
#[derive(Clone, Deserialize)]
#[serde(untagged)]
pub(super) enum SamplesDef {
    Count(u32),
    Word(String),
}

/// One `[[lights]]` entry, built.
pub(super) enum LightEntry {
    /// A light, or an area light's samples.
    Lights(Vec<Light>),
    /// An area light whose samples are chosen once the scene is built.
    Auto { light: AreaLight, tolerance: f32, key: String },
}

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightKind {
    Point,
    Spot,
    Directional,
    Rect,
    Disc,
}

impl LightKind {
    /// The name the file uses.
    fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Spot => "spot",
            LightKind::Directional => "directional",
            LightKind::Rect => "rect",
            LightKind::Disc => "disc",
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightDef {
    #[serde(rename = "type")]
    kind: LightKind,
    position: Option<S<[f32; 3]>>,
    direction: Option<S<[f32; 3]>>,
    color: Option<S<[f32; 3]>>,
    attenuation: Option<S<[f32; 3]>>,
    range: Option<S<f32>>,
    inner_angle: Option<S<f32>>,
    outer_angle: Option<S<f32>>,
    u: Option<S<[f32; 3]>>,
    v: Option<S<[f32; 3]>>,
    normal: Option<S<[f32; 3]>>,
    radius: Option<S<f32>>,
    samples: Option<S<SamplesDef>>,
    tolerance: Option<S<f32>>,
}

/// One `[[lights]]` entry: one light, or an area light's samples.
pub(super) fn light(check: &Checker<'_>, def: &S<LightDef>, key: &str) -> Result<LightEntry> {
    let l = def.get_ref();
    let color = match &l.color {
        Some(c) => check.vec3_in(c, &format!("{key}.color"), 0.0, f32::INFINITY)?,
        None => Vec3::ONE,
    };
    let area_only = |name: &str, v: bool| match v {
        true => {
            Err(check.error(def.span(), &format!("{key}.{name}"), "applies to rect and disc lights only"))
        }
        false => Ok(()),
    };
    if !matches!(l.kind, LightKind::Rect | LightKind::Disc) {
        area_only("samples", l.samples.is_some())?;
        area_only("tolerance", l.tolerance.is_some())?;
    }
    if !matches!(l.kind, LightKind::Rect) {
        area_only("u", l.u.is_some())?;
        area_only("v", l.v.is_some())?;
    }
    if !matches!(l.kind, LightKind::Disc) {
        area_only("normal", l.normal.is_some())?;
        area_only("radius", l.radius.is_some())?;
    }
    if !matches!(l.kind, LightKind::Spot) {
        check.not_allowed(&l.inner_angle, key, "inner_angle", "lights other than spot lights")?;
        check.not_allowed(&l.outer_angle, key, "outer_angle", "lights other than spot lights")?;
    }
    let attenuation = match &l.attenuation {
        Some(a) => {
            let [a0, a1, a2] = check.vec3_in(a, &format!("{key}.attenuation"), 0.0, f32::INFINITY)?.into();
            Attenuation::new(a0, a1, a2)
        }
        None => Attenuation::NONE,
    }
    .with_range(check.positive(&l.range, &format!("{key}.range"), f32::INFINITY)?);
    let position = || match &l.position {
        Some(p) => check.vec3(p, &format!("{key}.position")),
        None => Err(check.error(def.span(), key, format!("a {} light needs 'position'", l.kind.name()))),
    };
    let vector = |v: &Option<S<[f32; 3]>>, name: &str| match v {
        Some(v) if *v.get_ref() == [0.0; 3] => {
            Err(check.error(v.span(), &format!("{key}.{name}"), "must not be [0, 0, 0]"))
        }
        Some(v) => check.vec3(v, &format!("{key}.{name}")),
        None => Err(check.error(def.span(), key, format!("a {} light needs '{name}'", l.kind.name()))),
    };
    // Some(k), or None for "auto".
    let samples = || match &l.samples {
        Some(n) => match n.get_ref() {
            SamplesDef::Count(k) if (1..=MAX_AREA_SAMPLES_PER_SIDE).contains(k) => Ok(Some(*k)),
            SamplesDef::Word(w) if w == "auto" => Ok(None),
            other => Err(check.error(
                n.span(),
                &format!("{key}.samples"),
                format!(
                    "must be \"auto\" or in 1..={MAX_AREA_SAMPLES_PER_SIDE} (samples per side), got {}",
                    match other {
                        SamplesDef::Count(k) => k.to_string(),
                        SamplesDef::Word(w) => format!("{w:?}"),
                    }
                ),
            )),
        },
        None => Ok(Some(DEFAULT_AREA_SAMPLES)),
    };
    match l.kind {
        LightKind::Rect | LightKind::Disc => {
            check.not_allowed(&l.direction, key, "direction", "area lights")?;
            let center = position()?;
            let shape = if let LightKind::Rect = l.kind {
                AreaShape::Rect { center, u: vector(&l.u, "u")?, v: vector(&l.v, "v")? }
            } else {
                let radius = check.positive(&l.radius, &format!("{key}.radius"), 0.0)?;
                if radius <= 0.0 {
                    return Err(check.error(def.span(), key, "a disc light needs 'radius' > 0"));
                }
                AreaShape::Disc { center, normal: vector(&l.normal, "normal")?, radius }
            };
            let light = AreaLight { shape, color, attenuation };
            match samples()? {
                Some(k) => {
                    if let Some(t) = &l.tolerance {
                        let message = "applies with samples = \"auto\" only";
                        return Err(check.error(t.span(), &format!("{key}.tolerance"), message));
                    }
                    Ok(LightEntry::Lights(light.sample(k)))
                }
                None => {
                    let tolerance = match &l.tolerance {
                        Some(t) if !(0.0..=MAX_AUTO_TOLERANCE).contains(t.get_ref()) => {
                            return Err(check.error(
                                t.span(),
                                &format!("{key}.tolerance"),
                                format!(
                                    "must be in 0..={MAX_AUTO_TOLERANCE} (8-bit steps), got {}",
                                    t.get_ref()
                                ),
                            ))
                        }
                        Some(t) => *t.get_ref(),
                        None => DEFAULT_AUTO_TOLERANCE,
                    };
                    Ok(LightEntry::Auto { light, tolerance, key: key.to_string() })
                }
            }
        }
        LightKind::Point => {
            check.not_allowed(&l.direction, key, "direction", "point lights")?;
            let position = position()?;
            Ok(LightEntry::Lights(vec![Light::Point { position, color, attenuation }]))
        }
        LightKind::Spot => {
            let position = position()?;
            let direction = vector(&l.direction, "direction")?;
            let degrees = |v: &Option<S<f32>>, name: &str, default: f32| {
                check.optional(v, &format!("{key}.{name}"), default, 0.0, 90.0)
            };
            let inner = degrees(&l.inner_angle, "inner_angle", 0.0)?;
            let outer = degrees(&l.outer_angle, "outer_angle", 45.0)?;
            if inner >= outer {
                let at = l.inner_angle.as_ref().or(l.outer_angle.as_ref());
                let message = format!("must be less than outer_angle, got {inner} ≥ {outer} degrees");
                return Err(check.value_error(at, def, &format!("{key}.inner_angle"), message));
            }
            let cone = Cone { inner: inner.to_radians(), outer: outer.to_radians() };
            Ok(LightEntry::Lights(vec![Light::Spot { position, direction, color, attenuation, cone }]))
        }
        LightKind::Directional => {
            check.not_allowed(&l.position, key, "position", "directional lights")?;
            check.not_allowed(&l.attenuation, key, "attenuation", "directional lights")?;
            check.not_allowed(&l.range, key, "range", "directional lights")?;
            let Some(d) = &l.direction else {
                return Err(check.error(def.span(), key, "a directional light needs 'direction'"));
            };
            let direction = check.vec3(d, &format!("{key}.direction"))?;
            if direction == Vec3::ZERO {
                return Err(check.error(d.span(), &format!("{key}.direction"), "must not be [0, 0, 0]"));
            }
            Ok(LightEntry::Lights(vec![Light::Directional { direction, color }]))
        }
    }
}

/// The scene's lights from its entries, in file order: each `"auto"` area
/// light sampled by [`zline_scene::choose_area_samples`] on the built
/// scene. With planar shadows the shadow mask has 32 bits for every
/// (plane, light) pair, so an automatic choice stops at the largest k that
/// keeps every light shadowed. A choice that stops short of its tolerance
/// prints a `warning:` line naming `path` and the light.
pub(super) fn resolve(mut scene: Scene, entries: Vec<LightEntry>, path: &Path) -> Scene {
    let fixed: usize = entries
        .iter()
        .map(|e| match e {
            LightEntry::Lights(l) => l.len(),
            LightEntry::Auto { .. } => 0,
        })
        .sum();
    let autos = entries.iter().filter(|e| matches!(e, LightEntry::Auto { .. })).count();
    let planes = scene.shadows.planes.len();
    // Lights already placed, and automatic ones still to place (one each
    // at least).
    let (mut placed, mut pending) = (fixed, autos);
    let mut lights = Vec::new();
    for entry in entries {
        match entry {
            LightEntry::Lights(l) => lights.extend(l),
            LightEntry::Auto { light, tolerance, key } => {
                pending -= 1;
                let cap = match scene.shadows.mode {
                    ShadowMode::Planar if planes > 0 => {
                        let free = (32 / planes).saturating_sub(placed + pending);
                        (1..=MAX_AREA_SAMPLES_PER_SIDE)
                            .take_while(|k| (k * k) as usize <= free)
                            .last()
                            .unwrap_or(1)
                    }
                    _ => MAX_AREA_SAMPLES_PER_SIDE,
                };
                let choice = choose_area_samples(&scene, &light, tolerance, cap);
                if choice.capped {
                    eprintln!(
                        "warning: {}: {key}.samples: \"auto\" stopped at {k} × {k}, {:.2} steps from 16 × 16 \
                         (tolerance {tolerance}): planar shadows have 32 (plane, light) pairs",
                        path.display(),
                        choice.rmse,
                        k = choice.per_side,
                    );
                }
                let samples = light.sample(choice.per_side);
                placed += samples.len();
                lights.extend(samples);
            }
        }
    }
    scene.lights = lights;
    scene
}

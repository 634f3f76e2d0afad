//! The `[[lights]]` entries of a scene file: point and directional lights,
//! and area lights (`rect`, `disc`) expanded into their k × k samples.

use glam::Vec3;
use serde::Deserialize;
use zline_scene::{AreaLight, AreaShape, MAX_AREA_SAMPLES_PER_SIDE};
use zline_shading::{Attenuation, Light};

use super::checks::{Checker, Result, S};

/// An area light's default samples per side (4 × 4 point lights).
const DEFAULT_AREA_SAMPLES: u32 = 4;

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightKind {
    Point,
    Directional,
    Rect,
    Disc,
}

impl LightKind {
    /// The name the file uses.
    fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
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
    u: Option<S<[f32; 3]>>,
    v: Option<S<[f32; 3]>>,
    normal: Option<S<[f32; 3]>>,
    radius: Option<S<f32>>,
    samples: Option<S<u32>>,
}

/// One `[[lights]]` entry: one light, or an area light's samples.
pub(super) fn light(check: &Checker<'_>, def: &S<LightDef>, key: &str) -> Result<Vec<Light>> {
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
    }
    if !matches!(l.kind, LightKind::Rect) {
        area_only("u", l.u.is_some())?;
        area_only("v", l.v.is_some())?;
    }
    if !matches!(l.kind, LightKind::Disc) {
        area_only("normal", l.normal.is_some())?;
        area_only("radius", l.radius.is_some())?;
    }
    let attenuation = match &l.attenuation {
        Some(a) => {
            let [a0, a1, a2] = check.vec3_in(a, &format!("{key}.attenuation"), 0.0, f32::INFINITY)?.into();
            Attenuation { a0, a1, a2 }
        }
        None => Attenuation::NONE,
    };
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
    let samples = || match &l.samples {
        Some(n) if !(1..=MAX_AREA_SAMPLES_PER_SIDE).contains(n.get_ref()) => Err(check.error(
            n.span(),
            &format!("{key}.samples"),
            format!("must be in 1..={MAX_AREA_SAMPLES_PER_SIDE} (samples per side), got {}", n.get_ref()),
        )),
        Some(n) => Ok(*n.get_ref()),
        None => Ok(DEFAULT_AREA_SAMPLES),
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
            Ok(AreaLight { shape, color, attenuation }.sample(samples()?))
        }
        LightKind::Point => {
            check.not_allowed(&l.direction, key, "direction", "point lights")?;
            let position = position()?;
            Ok(vec![Light::Point { position, color, attenuation }])
        }
        LightKind::Directional => {
            check.not_allowed(&l.position, key, "position", "directional lights")?;
            check.not_allowed(&l.attenuation, key, "attenuation", "directional lights")?;
            let Some(d) = &l.direction else {
                return Err(check.error(def.span(), key, "a directional light needs 'direction'"));
            };
            let direction = check.vec3(d, &format!("{key}.direction"))?;
            if direction == Vec3::ZERO {
                return Err(check.error(d.span(), &format!("{key}.direction"), "must not be [0, 0, 0]"));
            }
            Ok(vec![Light::Directional { direction, color }])
        }
    }
}

//! An object's `[objects.material]` table: overrides of the coefficients
//! of every mesh of its model (`color`, `ka`, `kd`, `ks`, `ke`, `ns`,
//! `opacity`, and the ray tracer's `kr` and `ior`: SPEC §12) and of its
//! reflection model (SPEC §5.2): `model` ("basic" or
//! "cook-torrance"), `metallic` and `roughness` in [0, 1], `distribution`
//! ("ggx" or "beckmann").
//!
//! `model = "basic"` lights the meshes with the basic model, keeping their
//! ka, ks and ns (which the glTF and MTL loaders set to the basic model's
//! likeness of a Cook–Torrance material); `metallic`, `roughness` and
//! `distribution` are errors beside it. `model = "cook-torrance"`, or any
//! of those three keys without `model`, lights them with Cook–Torrance: a
//! mesh that has it already keeps its parameters but the keys given, a
//! basic one starts from metallic 0, roughness 0.5 and GGX. Cook–Torrance
//! uses kd as its base colour; ka, ks and ns are kept for the basic model
//! and do not change its light.

use serde::Deserialize;
use zline_shading::{Distribution, Material, Microfacet, Model};

use super::checks::{Checker, Result, S};

/// The `[objects.material]` table as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialDef {
    color: Option<S<[f32; 3]>>,
    ka: Option<S<[f32; 3]>>,
    kd: Option<S<[f32; 3]>>,
    ks: Option<S<[f32; 3]>>,
    ke: Option<S<[f32; 3]>>,
    ns: Option<S<f32>>,
    opacity: Option<S<f32>>,
    kr: Option<S<[f32; 3]>>,
    ior: Option<S<f32>>,
    /// A string checked by hand, so that a bad one names its key.
    model: Option<S<String>>,
    metallic: Option<S<f32>>,
    roughness: Option<S<f32>>,
    /// As `model`.
    distribution: Option<S<String>>,
}

/// The Cook–Torrance parameters a basic material takes when a scene file
/// switches it: a dielectric (metallic 0) of middling roughness 0.5, GGX.
const SWITCHED_TO_COOK_TORRANCE: Microfacet =
    Microfacet { metallic: 0.0, roughness: 0.5, distribution: Distribution::Ggx };

/// The names of `model`'s values ([`Model::name`]'s).
const MODELS: [&str; 2] = ["basic", "cook-torrance"];

/// `base` (a mesh's material) with the table's overrides; `key` names the
/// object (`objects[2]`).
pub(super) fn material(check: &Checker, def: &MaterialDef, base: Material, key: &str) -> Result<Material> {
    let key = format!("{key}.material");
    let mut m = base;
    if let Some(c) = &def.color {
        m.kd = check.vec3_in(c, &format!("{key}.color"), 0.0, 1.0)?;
        m.ka = m.kd;
    }
    for (value, name, field) in [
        (&def.ka, "ka", &mut m.ka),
        (&def.kd, "kd", &mut m.kd),
        (&def.ks, "ks", &mut m.ks),
        (&def.ke, "ke", &mut m.ke),
        (&def.kr, "kr", &mut m.kr),
    ] {
        if let Some(v) = value {
            *field = check.vec3_in(v, &format!("{key}.{name}"), 0.0, 1.0)?;
        }
    }
    m.ns = check.optional(&def.ns, &format!("{key}.ns"), m.ns, 0.0, f32::MAX)?;
    m.opacity = check.optional(&def.opacity, &format!("{key}.opacity"), m.opacity, 0.0, 1.0)?;
    // Between a hundredth and a hundred: outside, Snell's law bends every
    // ray to the normal or back (no known material is near either end).
    m.ior = check.optional(&def.ior, &format!("{key}.ior"), m.ior, 0.01, 100.0)?;
    m.model = model(check, def, base.model, &key)?;
    Ok(m)
}

/// The model the table gives a material whose model is `base`; `key` names
/// the table (`objects[2].material`).
fn model(check: &Checker, def: &MaterialDef, base: Model, key: &str) -> Result<Model> {
    let cook_torrance = match &def.model {
        None => def.metallic.is_some() || def.roughness.is_some() || def.distribution.is_some(),
        Some(name) => match name.get_ref().as_str() {
            "basic" => false,
            "cook-torrance" => true,
            other => {
                return Err(check.error(
                    name.span(),
                    &format!("{key}.model"),
                    format!("unknown model {other:?}, expected {}", one_of(&MODELS)),
                ))
            }
        },
    };
    if !cook_torrance {
        let what = "the basic model (model = \"basic\")";
        check.not_allowed(&def.metallic, key, "metallic", what)?;
        check.not_allowed(&def.roughness, key, "roughness", what)?;
        check.not_allowed(&def.distribution, key, "distribution", what)?;
        return Ok(match def.model {
            Some(_) => Model::Basic,
            None => base,
        });
    }
    let start = match base {
        Model::CookTorrance(m) => m,
        Model::Basic => SWITCHED_TO_COOK_TORRANCE,
    };
    let metallic = check.optional(&def.metallic, &format!("{key}.metallic"), start.metallic, 0.0, 1.0)?;
    let roughness = check.optional(&def.roughness, &format!("{key}.roughness"), start.roughness, 0.0, 1.0)?;
    let distribution = match &def.distribution {
        None => start.distribution,
        Some(name) => {
            let all = [Distribution::Ggx, Distribution::Beckmann];
            let found = all.into_iter().find(|d| d.name() == name.get_ref().as_str());
            found.ok_or_else(|| {
                check.error(
                    name.span(),
                    &format!("{key}.distribution"),
                    format!(
                        "unknown distribution {:?}, expected {}",
                        name.get_ref(),
                        one_of(&all.map(Distribution::name))
                    ),
                )
            })?
        }
    };
    Ok(Model::CookTorrance(Microfacet { metallic, roughness, distribution }))
}

/// `"a" or "b"`, `"a", "b" or "c"`.
fn one_of(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("{n:?}")).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

//! The `[raytrace]` table of a scene file → [`TraceOptions`]: the ray
//! tracer's depth limit, weight cutoff, shadow rays, acceleration
//! structure and anti-aliasing (SPEC §12), each checked and located on
//! error. `[render] renderer` says whether the ray tracer draws.

use serde::Deserialize;
use zline_scene::trace_options::{
    AccelKind, Adaptive, ShadowRays, TraceOptions, MAX_ADAPTIVE_DEPTH, MAX_DEPTH, MAX_SAMPLES,
};

use super::checks::{Checker, Result, S};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RayTraceDef {
    depth: Option<S<u32>>,
    min_weight: Option<S<f32>>,
    shadow_rays: Option<ShadowRaysDef>,
    accel: Option<AccelDef>,
    rays_per_axis: Option<S<u32>>,
    adaptive: Option<S<bool>>,
    adaptive_depth: Option<S<u32>>,
    adaptive_threshold: Option<S<f32>>,
}

/// The names are [`ShadowRays`]'.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ShadowRaysDef {
    Filtered,
    Opaque,
}

/// The names are [`AccelKind::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum AccelDef {
    Bvh,
    Kd,
    Grid,
    None,
}

/// `[render] renderer`.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum RendererDef {
    Raster,
    Raytrace,
    Radiosity,
}

/// The ray tracer's options of the `[raytrace]` table, the defaults
/// without one.
pub(super) fn options(check: &Checker, def: Option<RayTraceDef>) -> Result<TraceOptions> {
    let mut o = TraceOptions::DEFAULT;
    let Some(def) = def else { return Ok(o) };
    let whole = |v: &S<u32>, key: &str, lo: u32, hi: u32| {
        let n = *v.get_ref();
        if (lo..=hi).contains(&n) {
            Ok(n)
        } else {
            Err(check.error(v.span(), key, format!("must be in {lo}..={hi}, got {n}")))
        }
    };
    if let Some(d) = &def.depth {
        o.max_depth = whole(d, "raytrace.depth", 1, MAX_DEPTH)?;
    }
    o.min_weight = check.optional(&def.min_weight, "raytrace.min_weight", o.min_weight, 0.0, 1.0)?;
    if let Some(s) = def.shadow_rays {
        o.shadows = match s {
            ShadowRaysDef::Filtered => ShadowRays::Filtered,
            ShadowRaysDef::Opaque => ShadowRays::Opaque,
        };
    }
    if let Some(a) = def.accel {
        o.accel = match a {
            AccelDef::Bvh => AccelKind::Bvh,
            AccelDef::Kd => AccelKind::Kd,
            AccelDef::Grid => AccelKind::Grid,
            AccelDef::None => AccelKind::None,
        };
    }
    if let Some(n) = &def.rays_per_axis {
        o.samples = whole(n, "raytrace.rays_per_axis", 1, MAX_SAMPLES)?;
    }
    let on = def.adaptive.as_ref().map(|a| *a.get_ref());
    if on == Some(true)
        || (on.is_none() && (def.adaptive_depth.is_some() || def.adaptive_threshold.is_some()))
    {
        let d = Adaptive::default();
        let depth = match &def.adaptive_depth {
            Some(v) => whole(v, "raytrace.adaptive_depth", 0, MAX_ADAPTIVE_DEPTH)?,
            None => d.depth,
        };
        let threshold =
            check.optional(&def.adaptive_threshold, "raytrace.adaptive_threshold", d.threshold, 0.0, 1.0)?;
        if let Some(n) = def.rays_per_axis.as_ref().filter(|n| *n.get_ref() > 1) {
            return Err(check.error(
                n.span(),
                "raytrace.rays_per_axis",
                "and adaptive supersampling are two ways to anti-alias: give one",
            ));
        }
        o.adaptive = Some(Adaptive { depth, threshold });
    }
    Ok(o)
}

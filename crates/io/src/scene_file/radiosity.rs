//! The `[radiosity]` table of a scene file → [`RadiosityOptions`]: the
//! patch size, the hemicube's resolution, the solver, its tolerance,
//! near patches' analytic form factors, the subdivision levels and whether the scene's lights
//! shoot (SPEC §13), each checked and located on error. `[render]
//! renderer = "radiosity"` says whether radiosity draws.

use serde::Deserialize;
use zline_scene::radiosity_options::{
    Method, RadiosityOptions, MAX_RESOLUTION, MAX_SUBDIVISION as MAX_LEVELS,
};

use super::checks::{Checker, Result, S};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RadiosityDef {
    patch_size: Option<S<f32>>,
    hemicube: Option<S<u32>>,
    solver: Option<SolverDef>,
    tolerance: Option<S<f32>>,
    lights: Option<bool>,
    analytic_near: Option<bool>,
    subdivide: Option<S<u32>>,
}

/// The names are [`Method::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum SolverDef {
    Jacobi,
    GaussSeidel,
    Progressive,
}

/// The options of the `[radiosity]` table, the defaults without one.
pub(super) fn options(check: &Checker, def: Option<RadiosityDef>) -> Result<RadiosityOptions> {
    let mut o = RadiosityOptions::DEFAULT;
    let Some(def) = def else { return Ok(o) };
    if def.patch_size.is_some() {
        o.patch_size = Some(check.positive(&def.patch_size, "radiosity.patch_size", 1.0)?);
    }
    if let Some(n) = &def.hemicube {
        let max = MAX_RESOLUTION as u32;
        let res = *n.get_ref();
        if !(2..=max).contains(&res) {
            return Err(check.error(
                n.span(),
                "radiosity.hemicube",
                format!("must be in 2..={max}, got {res}"),
            ));
        }
        o.resolution = res as usize;
    }
    if let Some(s) = def.solver {
        o.method = match s {
            SolverDef::Jacobi => Method::Jacobi,
            SolverDef::GaussSeidel => Method::GaussSeidel,
            SolverDef::Progressive => Method::Progressive,
        };
    }
    let tolerance = check.optional(&def.tolerance, "radiosity.tolerance", 1e-3, 0.0, 1.0)?;
    if def.tolerance.is_some() {
        o.tolerance = f64::from(tolerance);
    }
    if let Some(lights) = def.lights {
        o.lights = lights;
    }
    if let Some(analytic) = def.analytic_near {
        o.analytic_near = analytic;
    }
    if let Some(levels) = &def.subdivide {
        let n = *levels.get_ref();
        if n > MAX_LEVELS {
            return Err(check.error(
                levels.span(),
                "radiosity.subdivide",
                format!("must be in 0..={MAX_LEVELS}, got {n}"),
            ));
        }
        o.subdivide = n;
    }
    Ok(o)
}

//! The `[render]` table of a scene file → [`RenderSettings`]: image size,
//! shading, interpolation, texture filter, supersampling, depth mode, the
//! adaptive mode's tolerance and the two conventions of SPEC §11 (Gouraud
//! clamp, lighting sides), each checked and located on error; and the
//! shadow method, which the scene (not its settings) keeps.

use serde::Deserialize;
use zline_shading::Filter;

use zline_scene::{
    DepthMode, GouraudClamp, Interpolation, LightingSides, RenderSettings, ShadowMode,
    MAX_ADAPTIVE_TOLERANCE, MAX_IMAGE_SIDE, MAX_SSAA,
};
use zline_shading::ShadingMode;

use super::checks::{Checker, Result, S};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RenderDef {
    width: Option<S<u32>>,
    height: Option<S<u32>>,
    shading: Option<ShadingDef>,
    interpolation: Option<InterpolationDef>,
    filter: Option<FilterDef>,
    ssaa: Option<S<u32>>,
    depth: Option<DepthDef>,
    adaptive: Option<S<f32>>,
    gouraud_clamp: Option<GouraudClampDef>,
    lighting: Option<LightingDef>,
    shadows: Option<ShadowsDef>,
}

/// A shading mode: `[render] shading` and an object's `shading`.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ShadingDef {
    Flat,
    Gouraud,
    Phong,
}

impl From<ShadingDef> for ShadingMode {
    fn from(s: ShadingDef) -> ShadingMode {
        match s {
            ShadingDef::Flat => ShadingMode::Flat,
            ShadingDef::Gouraud => ShadingMode::Gouraud,
            ShadingDef::Phong => ShadingMode::Phong,
        }
    }
}

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum FilterDef {
    Nearest,
    Bilinear,
    Trilinear,
}

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum InterpolationDef {
    Perspective,
    Linear,
}

/// The names are [`DepthMode::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum DepthDef {
    Normalized,
    Reversed,
}

/// The names are [`GouraudClamp::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum GouraudClampDef {
    Vertex,
    Sample,
}

/// The names are [`LightingSides::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum LightingDef {
    TwoSided,
    OneSided,
}

/// The names are [`ShadowMode::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ShadowsDef {
    None,
    Planar,
}

/// The shadow method of the `[render]` table: [`ShadowMode::None`] without
/// one or without its `shadows` key.
pub(super) fn shadow_mode(render: Option<&RenderDef>) -> ShadowMode {
    match render.and_then(|r| r.shadows) {
        Some(ShadowsDef::Planar) => ShadowMode::Planar,
        Some(ShadowsDef::None) | None => ShadowMode::None,
    }
}

/// The render settings of the `[render]` table, the defaults without one.
pub(super) fn settings(check: &Checker, render: Option<RenderDef>) -> Result<RenderSettings> {
    let mut settings = RenderSettings::default();
    let Some(render) = render else { return Ok(settings) };
    if let Some(w) = &render.width {
        settings.width = image_side(check, w, "render.width")?;
    }
    if let Some(h) = &render.height {
        settings.height = image_side(check, h, "render.height")?;
    }
    if let Some(s) = render.shading {
        settings.shading = s.into();
    }
    if let Some(i) = render.interpolation {
        settings.interpolation = match i {
            InterpolationDef::Perspective => Interpolation::PerspectiveCorrect,
            InterpolationDef::Linear => Interpolation::ScreenLinear,
        };
    }
    settings.texture_filter = render.filter.map(|f| match f {
        FilterDef::Nearest => Filter::Nearest,
        FilterDef::Bilinear => Filter::Bilinear,
        FilterDef::Trilinear => Filter::Trilinear,
    });
    if let Some(n) = &render.ssaa {
        settings.ssaa = ssaa(check, n)?;
    }
    if let Some(d) = render.depth {
        settings.depth = match d {
            DepthDef::Normalized => DepthMode::Normalized,
            DepthDef::Reversed => DepthMode::ReversedFloat,
        };
    }
    if render.adaptive.is_some() {
        let tolerance =
            check.optional(&render.adaptive, "render.adaptive", 0.0, 0.0, MAX_ADAPTIVE_TOLERANCE)?;
        settings.adaptive_tolerance = Some(tolerance);
    }
    if let Some(c) = render.gouraud_clamp {
        settings.gouraud_clamp = match c {
            GouraudClampDef::Vertex => GouraudClamp::PerVertex,
            GouraudClampDef::Sample => GouraudClamp::PerSample,
        };
    }
    if let Some(l) = render.lighting {
        settings.lighting_sides = match l {
            LightingDef::TwoSided => LightingSides::TwoSided,
            LightingDef::OneSided => LightingSides::OneSided,
        };
    }
    Ok(settings)
}

fn image_side(check: &Checker, v: &S<u32>, key: &str) -> Result<u32> {
    let side = *v.get_ref();
    if !(1..=MAX_IMAGE_SIDE).contains(&side) {
        return Err(check.error(v.span(), key, format!("must be in 1..={MAX_IMAGE_SIDE}, got {side}")));
    }
    Ok(side)
}

fn ssaa(check: &Checker, v: &S<u32>) -> Result<u32> {
    let n = *v.get_ref();
    if !(1..=MAX_SSAA).contains(&n) {
        return Err(check.error(v.span(), "render.ssaa", format!("must be in 1..={MAX_SSAA}, got {n}")));
    }
    Ok(n)
}

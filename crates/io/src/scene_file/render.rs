//! The `[render]` table of a scene file → [`RenderSettings`]: image size,
//! shading, interpolation, texture filter, supersampling, depth mode, the
//! adaptive mode's tolerance and the two conventions of SPEC §11 (Gouraud
//! clamp, lighting sides), each checked and located on error; and the
//! shadow method with its shadow-map size and filter, which the scene (not
//! its settings) keeps.

use serde::Deserialize;
use zline_shading::{Filter, ToneMap};

use zline_scene::trace_options::Renderer;
use zline_scene::{
    DepthMode, GouraudClamp, Interpolation, LightingSides, RenderSettings, ShadowMode, Shadows,
    MAX_ADAPTIVE_TOLERANCE, MAX_IMAGE_SIDE, MAX_SHADOW_MAP_SIZE, MAX_SSAA,
};
use zline_shading::ShadingMode;

use super::checks::{Checker, Result, S};
use super::raytrace::RendererDef;
use super::visibility::{VisibilityDef, VisibilityName, WireframeName};

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
    /// Any TOML value, so that a string or a float is an error naming the
    /// key like an integer out of range.
    shadow_map_size: Option<S<toml::Value>>,
    shadow_filter: Option<ShadowFilterDef>,
    visibility: Option<VisibilityName>,
    wireframe: Option<WireframeName>,
    wireframe_only: Option<bool>,
    feature_angle: Option<S<f32>>,
    transparent_background: Option<bool>,
    tonemap: Option<ToneMapDef>,
    exposure: Option<S<f32>>,
    renderer: Option<RendererDef>,
}

/// `[render] tonemap`.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum ToneMapDef {
    None,
    KhrPbrNeutral,
    Aces,
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
    Map,
}

/// How a shadow map is sampled: [`Shadows::pcf`].
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ShadowFilterDef {
    Pcf,
    Nearest,
}

/// The smallest shadow map side, in texels.
pub(super) const MIN_SHADOW_MAP_SIZE: u32 = 16;

/// The shadows of the `[render]` table, without planes (the objects bring
/// them): [`Shadows::default`] without a table or without its keys.
pub(super) fn shadows(check: &Checker, render: Option<&RenderDef>) -> Result<Shadows> {
    let mut shadows = Shadows::default();
    let Some(render) = render else { return Ok(shadows) };
    shadows.mode = match render.shadows {
        Some(ShadowsDef::Planar) => ShadowMode::Planar,
        Some(ShadowsDef::Map) => ShadowMode::Map,
        Some(ShadowsDef::None) | None => ShadowMode::None,
    };
    if let Some(v) = &render.shadow_map_size {
        shadows.map_size = shadow_map_size(check, v)?;
    }
    if let Some(f) = render.shadow_filter {
        shadows.pcf = matches!(f, ShadowFilterDef::Pcf);
    }
    Ok(shadows)
}

fn shadow_map_size(check: &Checker, v: &S<toml::Value>) -> Result<u32> {
    let range = format!("{MIN_SHADOW_MAP_SIZE}..={MAX_SHADOW_MAP_SIZE}");
    let key = "render.shadow_map_size";
    match v.get_ref() {
        toml::Value::Integer(n) => u32::try_from(*n)
            .ok()
            .filter(|n| (MIN_SHADOW_MAP_SIZE..=MAX_SHADOW_MAP_SIZE).contains(n))
            .ok_or_else(|| check.error(v.span(), key, format!("must be in {range}, got {n}"))),
        other => Err(check.error(
            v.span(),
            key,
            format!("must be a whole number of texels in {range}, got {other}"),
        )),
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
    let def = VisibilityDef {
        visibility: render.visibility,
        wireframe: render.wireframe,
        wireframe_only: render.wireframe_only,
        feature_angle: &render.feature_angle,
    };
    super::visibility::apply(check, def, &mut settings)?;
    if let Some(t) = render.transparent_background {
        settings.transparent_background = t;
    }
    if let Some(t) = render.tonemap {
        settings.tone_mapping.operator = match t {
            ToneMapDef::None => ToneMap::None,
            ToneMapDef::KhrPbrNeutral => ToneMap::KhrPbrNeutral,
            ToneMapDef::Aces => ToneMap::Aces,
        };
    }
    settings.tone_mapping.exposure =
        check.optional(&render.exposure, "render.exposure", 1.0, 0.0, f32::MAX)?;
    if let Some(r) = render.renderer {
        settings.renderer = match r {
            RendererDef::Raster => Renderer::Raster,
            RendererDef::Raytrace => Renderer::RayTrace,
            RendererDef::Radiosity => Renderer::Radiosity,
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

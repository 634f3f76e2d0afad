//! The `[render]` keys of hidden-surface and hidden-line drawing:
//! `visibility` ("zbuffer" or "painter"), `wireframe` ("none", "all",
//! "hidden-removed", "hidden-dashed"), `wireframe_only` (lines alone on the
//! background) and `feature_angle` (degrees, 0..=180: only feature edges).

use serde::Deserialize;
use zline_scene::{RenderSettings, Visibility, WireframeMode};

use super::checks::{Checker, Result, S};

/// The keys as `[render]` holds them.
pub(super) struct VisibilityDef<'a> {
    pub(super) visibility: Option<VisibilityName>,
    pub(super) wireframe: Option<WireframeName>,
    pub(super) wireframe_only: Option<bool>,
    pub(super) feature_angle: &'a Option<S<f32>>,
}

/// The names are [`Visibility::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum VisibilityName {
    Zbuffer,
    Painter,
}

/// The names are [`WireframeMode::name`]'s.
#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum WireframeName {
    None,
    All,
    HiddenRemoved,
    HiddenDashed,
}

/// The largest feature angle, in degrees.
pub(super) const MAX_FEATURE_ANGLE: f32 = 180.0;

/// Applies the keys given to `settings`.
pub(super) fn apply(check: &Checker, def: VisibilityDef<'_>, settings: &mut RenderSettings) -> Result<()> {
    if let Some(v) = def.visibility {
        settings.visibility = match v {
            VisibilityName::Zbuffer => Visibility::ZBuffer,
            VisibilityName::Painter => Visibility::Painter,
        };
    }
    if let Some(w) = def.wireframe {
        settings.wireframe.mode = match w {
            WireframeName::None => WireframeMode::None,
            WireframeName::All => WireframeMode::All,
            WireframeName::HiddenRemoved => WireframeMode::HiddenRemoved,
            WireframeName::HiddenDashed => WireframeMode::HiddenDashed,
        };
    }
    if let Some(only) = def.wireframe_only {
        settings.wireframe.only = only;
    }
    if def.feature_angle.is_some() {
        let angle = check.optional(def.feature_angle, "render.feature_angle", 0.0, 0.0, MAX_FEATURE_ANGLE)?;
        settings.wireframe.feature_angle = Some(angle);
    }
    Ok(())
}

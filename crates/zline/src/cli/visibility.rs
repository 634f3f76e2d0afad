//! The command line's hidden-surface and hidden-line options, flattened
//! into the common options: `--visibility`, `--wireframe`,
//! `--wireframe-only`, `--feature-angle`.

use clap::{Args, ValueEnum};
use zline::scene::{RenderSettings, Visibility, WireframeMode};

/// The options; each replaces the scene file's `[render]` key of the same
/// name (underscores for dashes).
#[derive(Args, Debug, Clone, Copy)]
pub(crate) struct VisibilityArgs {
    /// Hidden-surface method: the z-buffer, or the painter's algorithm
    /// (triangles sorted by their farthest depth, painted back to front,
    /// no depth buffer; wrong for cyclic overlaps and intersections).
    #[arg(long, value_enum)]
    visibility: Option<VisibilityArg>,
    /// Mesh edges drawn as 1-pixel lines: all of them solid, hidden ones
    /// removed, or hidden ones dashed (6 px on, 4 off).
    #[arg(long, value_enum)]
    wireframe: Option<WireframeArg>,
    /// With --wireframe: the lines alone on the background (the surfaces
    /// only hide lines).
    #[arg(long)]
    wireframe_only: bool,
    /// Only feature edges: borders, silhouettes and creases sharper than
    /// DEGREES (0 to 180).
    #[arg(long, value_name = "DEGREES", value_parser = parse_angle)]
    feature_angle: Option<f32>,
}

/// The names are [`Visibility::name`]'s.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum VisibilityArg {
    /// The depth buffer (the default).
    Zbuffer,
    /// The painter's algorithm.
    Painter,
}

/// The names are [`WireframeMode::name`]'s.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum WireframeArg {
    /// No lines (the default).
    None,
    /// Every edge, solid.
    All,
    /// Hidden edges not drawn.
    HiddenRemoved,
    /// Hidden edges dashed.
    HiddenDashed,
}

fn parse_angle(s: &str) -> Result<f32, String> {
    s.trim()
        .parse::<f32>()
        .ok()
        .filter(|a| (0.0..=180.0).contains(a))
        .ok_or_else(|| format!("expected an angle in degrees, 0 to 180, got '{s}'"))
}

impl VisibilityArgs {
    /// Replaces the settings the options give.
    pub(crate) fn apply(&self, settings: &mut RenderSettings) {
        if let Some(v) = self.visibility {
            settings.visibility = match v {
                VisibilityArg::Zbuffer => Visibility::ZBuffer,
                VisibilityArg::Painter => Visibility::Painter,
            };
        }
        if let Some(w) = self.wireframe {
            settings.wireframe.mode = match w {
                WireframeArg::None => WireframeMode::None,
                WireframeArg::All => WireframeMode::All,
                WireframeArg::HiddenRemoved => WireframeMode::HiddenRemoved,
                WireframeArg::HiddenDashed => WireframeMode::HiddenDashed,
            };
        }
        if self.wireframe_only {
            settings.wireframe.only = true;
        }
        if let Some(a) = self.feature_angle {
            settings.wireframe.feature_angle = Some(a);
        }
    }
}

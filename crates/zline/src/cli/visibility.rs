//! The command line's hidden-surface and hidden-line options, flattened
//! into the common options: `--visibility`, `--wireframe`,
//! `--wireframe-only`, `--feature-angle`, and two of the classroom's
//! "what breaks without it" switches, `--no-culling` and `--shuffle`.

use clap::{Args, ValueEnum};
use zline::scene::{RenderSettings, Scene, Visibility, WireframeMode};

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
    /// What breaks without it: draw back faces too (no back-face culling
    /// on any object).
    #[arg(long)]
    no_culling: bool,
    /// What the z-buffer does not depend on: draw each mesh's triangles in
    /// an order shuffled by SEED.
    #[arg(long, value_name = "SEED")]
    shuffle: Option<u64>,
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
    /// `--no-culling` and `--shuffle` on the scene's objects, each saying
    /// in a line what the learner should see.
    pub(crate) fn apply_scene(&self, scene: &mut Scene) {
        if self.no_culling {
            for object in &mut scene.objects {
                object.cull_back_faces = false;
            }
            eprintln!("note: --no-culling: back faces are drawn too; a closed model looks the same (the z-buffer hides them) while more triangles are drawn");
        }
        if let Some(seed) = self.shuffle {
            zline::order::shuffle_triangles(scene, seed);
            eprintln!("note: --shuffle: the triangles are drawn in another order; with the z-buffer the picture is the same (depth decides, not order) unless surfaces tie in depth, but the samples shaded change (the overdraw follows the order), and transparent surfaces blend in another order");
        }
    }

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

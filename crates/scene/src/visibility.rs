//! How hidden surfaces and lines are decided: the z-buffer or the painter's
//! algorithm ([`Visibility`]), and the mesh edges drawn as lines
//! ([`Wireframe`]).

/// How a frame decides which surface a sample shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Visibility {
    /// The depth buffer (SPEC §4): per sample, the nearest fragment.
    #[default]
    ZBuffer,
    /// The painter's algorithm: per tile, every triangle (opaque and
    /// transparent) sorted by its farthest NC depth, ties in draw order,
    /// and painted back to front with no depth test and no depth write.
    /// Wrong where triangles overlap in a cycle or intersect; shown for
    /// teaching.
    Painter,
}

impl Visibility {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            Visibility::ZBuffer => "zbuffer",
            Visibility::Painter => "painter",
        }
    }
}

/// Which mesh edges are drawn as lines, and how hidden ones look.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum WireframeMode {
    /// No lines.
    #[default]
    None,
    /// Every edge, drawn solid whether hidden or not.
    All,
    /// Visible edges solid, hidden ones not drawn (hidden-line removal).
    HiddenRemoved,
    /// Visible edges solid, hidden ones dashed.
    HiddenDashed,
}

impl WireframeMode {
    /// The name used by the CLI and scene files.
    pub fn name(self) -> &'static str {
        match self {
            WireframeMode::None => "none",
            WireframeMode::All => "all",
            WireframeMode::HiddenRemoved => "hidden-removed",
            WireframeMode::HiddenDashed => "hidden-dashed",
        }
    }

    /// True when hidden lines look different from visible ones (removed or
    /// dashed), so the depth of the surfaces is needed.
    pub fn hides(self) -> bool {
        matches!(self, WireframeMode::HiddenRemoved | WireframeMode::HiddenDashed)
    }
}

/// The lines a frame draws over (or instead of) its shaded image.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Wireframe {
    /// Which edges and how hidden ones look.
    pub mode: WireframeMode,
    /// Lines alone on the background: surfaces only fill the depth buffer
    /// that decides which lines are hidden.
    pub only: bool,
    /// When set, only feature edges: border edges, silhouettes (one face
    /// towards the viewer, one away) and creases whose faces meet at more
    /// than this angle, in degrees (0..=180). Unset: every edge.
    pub feature_angle: Option<f32>,
}

impl Wireframe {
    /// True when the frame draws lines.
    pub fn drawn(&self) -> bool {
        self.mode != WireframeMode::None
    }
}

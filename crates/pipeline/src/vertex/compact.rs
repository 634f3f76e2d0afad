//! Compact vertex records for the objects that setup builds in lanes
//! (`crate::setup::lanes`): per vertex, a 24-byte [`ScreenVertex`] (window
//! position, depth, 1/w, outcodes) and only the values the object's kernel
//! reads ([`ValueLayout`]), instead of a 112-byte
//! [`ClipVertex`](super::ClipVertex). For a 1M-triangle sphere whole
//! records are 56 MB a frame, written by the stage and read back by setup,
//! most of it never used.
//!
//! A triangle that needs clipping reads whole records:
//! [`CompactVertices::full`] rebuilds a vertex's record with the stage's
//! scalar twin (`transform_vertex`, which the tests hold to the lanes bit
//! for bit) and the stored values, so clipping sees the bits the whole
//! records held.

use glam::Vec3;
use zline_raster::FixedPoint;

/// What setup's lanes read of every vertex: [`super::Projected`]'s fields
/// and the outcodes, in 24 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenVertex {
    /// Window position snapped to the 1/256 grid.
    pub fixed: FixedPoint,
    /// NC depth z/w.
    pub z: f64,
    /// 1/w.
    pub inv_w: f32,
    /// `ClipVertex::view_code`.
    pub view_code: u8,
    /// `ClipVertex::clip_code`.
    pub clip_code: u8,
}

/// Which values a compact record stores, as offsets (in floats) into the
/// vertex's values; each value is three floats.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ValueLayout {
    /// Floats per vertex.
    pub(crate) stride: usize,
    /// `ClipVertex::color`: the colour the stage lit.
    pub(crate) color: Option<usize>,
    /// The colour lit with the normal turned (`VertexLights::turned`).
    pub(crate) turned: Option<usize>,
    /// `ClipVertex::normal`.
    pub(crate) normal: Option<usize>,
    /// `ClipVertex::eye`.
    pub(crate) eye: Option<usize>,
}

impl ValueLayout {
    /// The layout storing the values asked for, in this order: colour,
    /// turned colour, normal, eye position.
    pub fn new([color, turned, normal, eye]: [bool; 4]) -> ValueLayout {
        let mut stride = 0;
        let mut slot = |stored: bool| {
            let offset = stored.then_some(stride);
            stride += if stored { 3 } else { 0 };
            offset
        };
        let (color, turned, normal, eye) = (slot(color), slot(turned), slot(normal), slot(eye));
        ValueLayout { stride, color, turned, normal, eye }
    }
}

/// An object's vertices in compact records ([`transform_compact`](super::transform_compact)).
#[derive(Clone, Debug, Default)]
pub struct CompactVertices {
    /// Per vertex.
    pub screen: Vec<ScreenVertex>,
    /// Per vertex, `layout.stride` floats.
    pub values: Vec<f32>,
    /// What `values` holds.
    pub layout: ValueLayout,
    /// Whether the stage lit the vertices.
    pub lit: bool,
}

impl CompactVertices {
    /// Value `offset` of vertex `i`.
    #[inline(always)]
    pub fn value(&self, i: usize, offset: usize) -> Vec3 {
        let v = &self.values[i * self.layout.stride + offset..][..3];
        Vec3::new(v[0], v[1], v[2])
    }
}

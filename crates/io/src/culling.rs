//! The default back-face culling rule, shared by every loader and by
//! framing: culling is on for closed, opaque meshes only (SPEC §2), since
//! culling an open or see-through mesh would show holes.

use zline_scene::Mesh;

/// Culling on for closed, opaque meshes (SPEC §2).
pub(crate) fn default_culling(mesh: &Mesh, opacity: f32) -> bool {
    opacity >= 1.0 && mesh.is_closed()
}

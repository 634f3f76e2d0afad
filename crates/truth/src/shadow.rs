//! Shadows (`ShadowMode::Planar` and `ShadowMode::Map`) as light
//! visibility, decided per sample by ray casting in f64 — the exact answer
//! the fast renderer's planar projection and shadow maps approximate.
//!
//! The rule:
//! - Receivers are the objects `i` with `scene.shadows.receives(i)`: the
//!   planes' receivers in Planar mode, every object in Map mode. A
//!   receiver is lit per sample like Phong shading (interpolated eye-space
//!   position and normal, the normal renormalized; a texel or a vertex
//!   colour modulates as with Phong: ambient+diffuse, or with
//!   Cook–Torrance the base colour), whatever its shading mode: shadows
//!   need the light's visibility per sample.
//! - Casters, opaque or transparent, culled or not, are all the triangles
//!   of some objects after `world_from_object`: in Planar mode the
//!   objects that do not receive; in Map mode every object, so that a
//!   surface shadows itself and the rest of its own mesh (a concave
//!   mesh's parts shadow each other). A caster triangle with zero area or
//!   a non-finite vertex is ignored.
//! - Self-intersection: the test at a sample ignores the triangle the
//!   sample lies on — the mesh triangle (object index, triangle index) of
//!   the drawn prim, a clipped piece counting as its whole triangle — by
//!   identity, not by an offset of the ray's start. Every other triangle,
//!   of the same mesh or not, counts, including one that shares an edge or
//!   a corner with it (only its hits at t ≤ 1e-9 are dropped, as below).
//!   In Planar mode a receiver's triangle is never a caster, so the rule
//!   changes nothing there. Note that a smooth-shaded receiver is lit by
//!   its interpolated normal but shadowed by its geometry: where that
//!   normal faces a light its triangles face away from, the ray goes
//!   into the mesh and the light is hidden (the exact answer; a shadow
//!   map's bias hides the same terminator differently).
//! - At a receiver sample, at the exact (perspective-correct) surface point
//!   P, light k is hidden when a caster triangle crosses the open segment
//!   from P to the light's position (a point light), or the ray from P
//!   towards the light, along −direction (a directional light). With the
//!   segment P + t·D, D = position − P, t ∈ (1e-9, 1 − 1e-9); with the ray,
//!   D the unit vector towards the light, t > 1e-9. A hit on a triangle's
//!   edge or corner counts (so a ray through a shared edge cannot slip
//!   between two caster triangles); a segment lying in a triangle's plane
//!   does not hit it.
//! - A hidden light contributes neither diffuse nor specular to the sample,
//!   in either lighting model; ambient (Cook–Torrance: the environment
//!   term) and emission stay. Everything after lighting (clamp, texture,
//!   fog, blending) is unchanged.
//!
//! Non-receivers, and every object with `ShadowMode::None`, are shaded as
//! without shadows, bit for bit.
//!
//! The test runs in eye space (a rigid motion of world space: the light
//! positions and directions go through the same f64 view matrix as the
//! caster vertices). The casters sit in a bounding-volume hierarchy whose
//! boxes are widened a little, so that it rejects only triangles the
//! segment–triangle test would miss too: the answer is the brute-force
//! answer over all caster triangles.

pub(crate) use zline_scene::{Occluders, TriangleId};

//! Acceleration structures: which triangles a ray meets, without testing
//! them all. Every structure answers exactly as brute force does
//! ([`brute::Brute`], the oracle): the same nearest hit by [`Hit::nearer_than`]'s
//! tie rule, and the same set of hits along a segment.
//!
//! | structure | build | traversal |
//! |---|---|---|
//! | [`bvh::Bvh`] | binned surface-area heuristic (pbrt-v4's), collapsed to four children a node | four boxes a step, nearest bound first, a fixed stack |
//! | [`kdtree::KdTree`] | surface-area heuristic over box edges (pbrt-v3's) | front to back, a fixed stack |
//! | [`grid::Grid`] | cells ∝ the triangle count, capped | cell to cell by the 3D-DDA (Amanatides–Woo) |
//! | [`brute::Brute`] | none | every triangle |

use glam::Vec3;

use crate::ray::{Hit, Ray, Sheared};

pub mod brute;
pub mod bvh;
pub mod grid;
pub mod kdtree;
#[cfg(test)]
pub(crate) mod testkit;

pub use zline_scene::sah::Bounds;
pub use zline_scene::trace_options::AccelKind;

/// Work counted during traversal, per ray kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Rays traced.
    pub rays: u64,
    /// Nodes visited (for the BVH, each visit tests four boxes).
    pub nodes: u64,
    /// Ray–triangle tests.
    pub tests: u64,
}

impl std::ops::Add for Counters {
    type Output = Counters;

    /// The sum of two counts.
    fn add(self, o: Counters) -> Counters {
        Counters { rays: self.rays + o.rays, nodes: self.nodes + o.nodes, tests: self.tests + o.tests }
    }
}

/// A structure over a triangle list.
pub trait Accelerator: Send + Sync {
    /// The nearest hit of `ray` among `triangles` (the list the structure
    /// was built over), by the tie rule of [`Hit::nearer_than`].
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit>;

    /// Calls `visit` with every hit of `ray` (0 < t < t_max), in no
    /// particular order, until it returns false; returns false when it
    /// did.
    fn each_hit(
        &self,
        triangles: &[[Vec3; 3]],
        ray: &Ray,
        count: &mut Counters,
        visit: &mut dyn FnMut(Hit) -> bool,
    ) -> bool;
}

/// Every triangle tested against `ray`: the reference the structures must
/// equal (also the leaf loop of a structure).
#[inline]
pub(crate) fn nearest_in(
    triangles: &[[Vec3; 3]],
    indices: impl Iterator<Item = u32>,
    ray: &Sheared,
    best: &mut Option<Hit>,
    count: &mut Counters,
) {
    for i in indices {
        count.tests += 1;
        if let Some(hit) = ray.intersect(&triangles[i as usize], i) {
            if best.is_none_or(|b| hit.nearer_than(&b)) {
                *best = Some(hit);
            }
        }
    }
}

/// Every triangle of `indices` tested against `ray`, `visit` called with
/// each hit until it returns false; false when it did (the leaf loop of a
/// structure's `each_hit`).
#[inline]
pub(crate) fn each_in(
    triangles: &[[Vec3; 3]],
    indices: impl IntoIterator<Item = u32>,
    ray: &Sheared,
    count: &mut Counters,
    mut visit: impl FnMut(Hit) -> bool,
) -> bool {
    for i in indices {
        count.tests += 1;
        if let Some(hit) = ray.intersect(&triangles[i as usize], i) {
            if !visit(hit) {
                return false;
            }
        }
    }
    true
}

/// The triangles a ray's `each_hit` has reported, for structures that
/// hold a triangle in several leaves or cells: a few inline, the rest
/// hashed.
#[derive(Default)]
pub(crate) struct Reported {
    few: [u32; 16],
    len: usize,
    many: std::collections::HashSet<u32>,
}

impl Reported {
    /// Records `i`; false when it was recorded before.
    pub(crate) fn insert(&mut self, i: u32) -> bool {
        if self.few[..self.len].contains(&i) {
            return false;
        }
        if self.len < self.few.len() {
            self.few[self.len] = i;
            self.len += 1;
            return true;
        }
        self.many.insert(i)
    }
}

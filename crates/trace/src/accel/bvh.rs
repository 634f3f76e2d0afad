//! The SAH bounding-volume hierarchy: triangles in, a flattened tree of
//! boxes out; traversal answers exactly as [`Brute`](super::brute::Brute) does.
//!
//! **Build**: the binned SAH tree of `zline_scene::sah` (pbrt-v4's) over
//! the triangles' boxes, at most four a leaf, ≤ 63 levels; a triangle
//! with a non-finite corner is left out (the watertight test never hits
//! it). The triangle list itself is not reordered: hits name the original
//! index.
//!
//! **Traversal** reads the binary tree collapsed into nodes of four
//! children, tested four boxes at once (`wide`).
//!
//! **Exactness.** Brute force's nearest hit is the least by
//! [`Hit::nearer_than`] of the watertight test's *computed* t values, and a
//! node may be skipped only when no triangle in it can change that. The
//! usual slab test with pbrt's 1 + 2γ(3) widening is conservative against
//! the exact ray, not against the rounding of the triangle test (which can
//! accept a ray that misses by a rounding error, and whose computed t can
//! lie below the true entry into the box when the triangle is seen edge
//! on), so two triangles meeting at a box face can come out in the other
//! order. The box test here is done instead in the triangle test's own
//! sheared space, with its own operations on the box corners: the sheared
//! coordinate `v[kx] − o[kx] + s_x·(v[kz] − o[kz])` is monotone in every
//! corner coordinate (each rounded operation is), so the corners' values
//! bound those of every vertex in the box, and a triangle can be hit only
//! when the origin lies in its sheared xy bounds. A hit's computed t is a
//! weighted mean with weights of one sign of its vertices' sheared z, so it
//! is at least the box's least z times 1 − γ(7); a node is pruned when that
//! bound is strictly above the best t (a hit at equal t with a lower index
//! would win the tie). Triangles are always tested with the original ray:
//! shrinking its t_max would round differently from comparing t. The only
//! gap left is underflow (edge functions or t products below 2⁻¹²⁶, i.e.
//! triangles some 10⁻¹⁹ across), where the triangle test's own signs fail.

use glam::Vec3;

use super::{each_in, nearest_in, Accelerator, Bounds, Counters};
use crate::ray::{Hit, Ray, Sheared};

mod wide;

use wide::{Frame, Wide};
use zline_scene::sah::{SahTree, MAX_LEAF};

// A leaf reference keeps count − 1 in two bits (`wide`).
const _: () = assert!(MAX_LEAF <= 4);

/// A bounding-volume hierarchy over a triangle list (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The tree the walk reads: four children a node ([`wide`]).
    nodes: Vec<Wide>,
    /// Its levels.
    levels: usize,
    /// Triangle indices, reordered so that each leaf's are contiguous.
    indices: Vec<u32>,
    /// The binary tree's levels.
    depth: usize,
    /// The binary tree's SAH cost.
    sah_cost: f32,
}

impl Bvh {
    /// Builds the tree over `triangles` (empty when there are none, or
    /// none with finite corners).
    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        // 2^29 triangles would take 19 GB before the tree.
        assert!(triangles.len() < wide::MAX_INDICES, "2^29 triangles or more");
        let finite = (0..).zip(triangles).filter(|(_, t)| t.iter().all(|p| p.is_finite()));
        let binary = SahTree::build(finite.map(|(index, t)| (index, Bounds::of(t))));
        if binary.nodes.is_empty() {
            return Bvh::default();
        }
        let (nodes, levels) = wide::collapse(&binary.nodes);
        Bvh { nodes, levels, sah_cost: binary.sah_cost(), depth: binary.depth, indices: binary.order }
    }

    /// The number of nodes (of four children each).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The binary tree's number of levels (0 for the empty tree, 1 for a
    /// lone leaf); the wide tree has no more.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The binary tree's SAH cost ([`SahTree::sah_cost`]), for reports.
    pub fn sah_cost(&self) -> f32 {
        self.sah_cost
    }
}

impl Accelerator for Bvh {
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit> {
        count.rays += 1;
        let sheared = Sheared::new(ray)?;
        let frame = Frame::new(ray, &sheared);
        let mut best: Option<Hit> = None;
        let best_t = std::cell::Cell::new(f32::INFINITY);
        wide::traverse::<true>(
            &self.nodes,
            self.levels,
            &self.indices,
            &frame,
            count,
            || best_t.get(),
            |indices, count| {
                nearest_in(triangles, indices.iter().copied(), &sheared, &mut best, count);
                best_t.set(best.map_or(f32::INFINITY, |b| b.t));
                true
            },
        );
        best
    }

    fn each_hit(
        &self,
        triangles: &[[Vec3; 3]],
        ray: &Ray,
        count: &mut Counters,
        visit: &mut dyn FnMut(Hit) -> bool,
    ) -> bool {
        count.rays += 1;
        let Some(sheared) = Sheared::new(ray) else { return true };
        let frame = Frame::new(ray, &sheared);
        wide::traverse::<false>(
            &self.nodes,
            self.levels,
            &self.indices,
            &frame,
            count,
            || f32::INFINITY,
            |indices, count| each_in(triangles, indices.iter().copied(), &sheared, count, &mut *visit),
        )
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use zline_scene::sah::DEPTH_LIMIT;

    use super::*;
    use crate::accel::testkit::{check_each_hit_stops, check_rays, check_same, ray, scene, stacked, Rng};

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn random_scenes_answer_as_brute_force(seed: u64, n in 1usize..300) {
            let mut rng = Rng(seed);
            let tris = scene(&mut rng, n);
            let bvh = Bvh::build(&tris);
            prop_assert!(bvh.depth() <= DEPTH_LIMIT + 1 && bvh.levels <= bvh.depth());
            for _ in 0..200 {
                check_same(&bvh, &tris, &ray(&mut rng, &tris));
            }
        }
    }

    #[test]
    fn a_hundred_thousand_rays_through_a_soup_answer_as_brute_force() {
        let mut rng = Rng(0x5eed);
        let tris = scene(&mut rng, 2000);
        let (mine, brute) = check_rays(&Bvh::build(&tris), &tris, &mut rng, 100_000);
        assert!(mine.tests * 10 < brute.tests, "{mine:?} against {brute:?}");
    }

    #[test]
    fn the_walk_with_the_full_stack_answers_as_brute_force() {
        // Trees deeper than 21 levels walk with the full stack; such trees
        // are hard to build, so a shallow one is walked that way here.
        let mut rng = Rng(11);
        let tris = scene(&mut rng, 3000);
        let mut bvh = Bvh::build(&tris);
        assert!(bvh.levels <= 21);
        bvh.levels = DEPTH_LIMIT + 1;
        check_rays(&bvh, &tris, &mut rng, 20_000);
    }

    #[test]
    fn each_hit_stops_when_told() {
        let tris = stacked();
        check_each_hit_stops(&Bvh::build(&tris), &tris);
    }

    #[test]
    fn an_empty_tree_hits_nothing() {
        let bad = [[Vec3::NAN, Vec3::ZERO, Vec3::X]];
        for tris in [&[][..], &bad[..]] {
            let bvh = Bvh::build(tris);
            assert_eq!((bvh.node_count(), bvh.depth(), bvh.sah_cost()), (0, 0, 0.0));
            let ray = Ray::new(Vec3::new(0.1, 0.1, 1.0), -Vec3::Z);
            let mut count = Counters::default();
            assert_eq!(bvh.closest(tris, &ray, &mut count), None);
            assert!(bvh.each_hit(tris, &ray, &mut count, &mut |_| false));
            assert_eq!(count, Counters { rays: 2, nodes: 0, tests: 0 });
        }
    }

    #[test]
    fn coincident_and_collinear_centroids_keep_the_depth_bounded() {
        let tiny = |c: Vec3, k: f32| [c - Vec3::X * k, c + Vec3::Y * k, c + Vec3::Z * k];
        let mut tris: Vec<_> = (0..200_000).map(|i| tiny(Vec3::ONE, 1e-3 * (1 + i % 7) as f32)).collect();
        tris.extend((0..200_000).map(|i| tiny(Vec3::new(i as f32 * 1e-3, 0.0, 0.0), 1e-4)));
        let bvh = Bvh::build(&tris);
        assert!(bvh.depth() <= DEPTH_LIMIT + 1, "depth {}", bvh.depth());
        assert!(bvh.levels <= bvh.depth(), "{} levels", bvh.levels);
        let mut rng = Rng(7);
        for _ in 0..200 {
            let origin = Vec3::new(rng.float(-1.0, 201.0), rng.float(-1.0, 2.0), 5.0);
            let ray = Ray::new(origin, Vec3::new(rng.float(-1.0, 1.0), rng.float(-1.0, 1.0), -4.0));
            check_same(&bvh, &tris, &ray);
        }
        // The line alone: SAH splits all the way, far below the limit.
        let line = Bvh::build(&tris[200_000..]);
        assert!(line.depth() <= 24, "depth {}", line.depth());
    }

    #[test]
    fn separated_triangles_cost_far_less_than_a_leaf() {
        let tris: Vec<_> = (0..32 * 32)
            .map(|i| {
                let c = Vec3::new((i % 32) as f32, (i / 32) as f32, 0.0);
                [c, c + Vec3::new(0.5, 0.0, 0.1), c + Vec3::new(0.0, 0.5, 0.2)]
            })
            .collect();
        let bvh = Bvh::build(&tris);
        let cost = bvh.sah_cost();
        assert!(cost < 0.02 * tris.len() as f32, "cost {cost}");
        assert!(bvh.depth() <= 14 && bvh.node_count() < 2 * tris.len(), "{}", bvh.depth());
        assert_eq!(Bvh::build(&[tris[0]; 3]).sah_cost(), 3.0, "one leaf costs its count");
    }
}

//! The SAH bounding-volume hierarchy: triangles in, a flattened tree of
//! boxes out; traversal answers exactly as [`Brute`](super::brute::Brute) does.
//!
//! **Build** (pbrt-v4's `BVHAggregate::buildRecursive`, binned): a node's
//! triangles are split on the axis where their centroids spread most, at
//! the best of the 11 boundaries between 12 equal buckets by the surface
//! area heuristic, cost = 0.5 + (n_below·area_below + n_above·area_above) /
//! area_node against the leaf's cost n. A node becomes a leaf when that is
//! cheaper and it holds at most `MAX_LEAF` triangles; above that a split
//! is forced, by the median centroid when the centroids coincide, the area
//! is zero or not finite, or the buckets put everything on one side. Nodes
//! are stored depth first (pbrt's `LinearBVHNode`): a node's first child
//! follows it, an interior node keeps its second child's offset and the
//! split axis, a leaf a range of a reordered index list (the triangle list
//! itself is not reordered; hits name the original index). A triangle with
//! a non-finite corner is left out: the watertight test never hits it.
//!
//! **Depth bound.** The build recurses, but with bounded depth: a node at
//! depth d with n triangles is split by the median (halving n) whenever
//! d + ⌈log₂ n⌉ ≥ `DEPTH_LIMIT`, so every node keeps d + ⌈log₂ n⌉ ≤
//! `DEPTH_LIMIT` (the root has ⌈log₂ n⌉ ≤ 32; an SAH split adds 1 to d and
//! does not grow n; a median split adds 1 and takes 1 off ⌈log₂ n⌉). Leaves
//! lie at depth ≤ 62, the tree has ≤ 63 levels, and the traversal stack,
//! which holds at most one far child per interior ancestor, needs ≤ 62 of
//! its `STACK` entries.
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

use glam::{BVec4A, Vec3, Vec4};

use super::{each_in, nearest_in, Accelerator, Bounds, Counters};
use crate::ray::{gamma, Hit, Ray, Sheared};

/// The most triangles the build puts in a leaf when a split would pay.
const MAX_LEAF: usize = 4;
/// Nodes with depth + ⌈log₂ count⌉ at or above this are split by the median.
const DEPTH_LIMIT: usize = 62;
/// The traversal stack's size (≥ the interior levels, [`DEPTH_LIMIT`]).
const STACK: usize = 64;
const BUCKETS: usize = 12;
/// The lanes of the box test that take the low end of the shear's span.
const LOW_HIGH: BVec4A = BVec4A::new(true, false, true, false);

/// A bounding-volume hierarchy over a triangle list (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Triangle indices, reordered so that each leaf's are contiguous.
    indices: Vec<u32>,
    depth: usize,
}

/// A flattened node: a leaf when `count > 0` (`offset` = its first index
/// in `Bvh::indices`), else interior (`offset` = its second child; the
/// first child is the next node).
#[derive(Clone, Copy, Debug)]
struct Node {
    /// The box, axis by axis: (min x, max x, min y, max y, min z, max z),
    /// so that the box test reads two axes' four values from one place.
    bounds: [f32; 6],
    offset: u32,
    count: u16,
    axis: u8,
}

/// A triangle during the build.
#[derive(Clone, Copy, Debug)]
struct Prim {
    bounds: Bounds,
    centroid: Vec3,
    index: u32,
}

impl Bvh {
    /// Builds the tree over `triangles` (empty when there are none, or
    /// none with finite corners).
    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        assert!(u32::try_from(triangles.len()).is_ok(), "more than 2^32 triangles");
        let mut prims: Vec<Prim> = (0..)
            .zip(triangles)
            .filter(|(_, t)| t.iter().all(|p| p.is_finite()))
            .map(|(index, t)| {
                let bounds = Bounds::of(t);
                // Halves first: min + max can overflow where their mean does not.
                Prim { bounds, centroid: 0.5 * bounds.min + 0.5 * bounds.max, index }
            })
            .collect();
        let mut bvh = Bvh { nodes: Vec::with_capacity(2 * prims.len()), indices: Vec::new(), depth: 0 };
        if !prims.is_empty() {
            bvh.emit(&mut prims, 0, 0);
        }
        bvh.indices = prims.iter().map(|p| p.index).collect();
        bvh
    }

    /// Appends the subtree over `prims` (which start at `start` in the
    /// final index list), depth first. Recursion depth ≤ [`DEPTH_LIMIT`].
    fn emit(&mut self, prims: &mut [Prim], start: usize, depth: usize) {
        debug_assert!(depth + ceil_log2(prims.len()) <= DEPTH_LIMIT);
        self.depth = self.depth.max(depth + 1);
        let bounds = prims.iter().fold(Bounds::EMPTY, |b, p| b.union(p.bounds));
        let at = self.nodes.len();
        let node = |offset: usize, count: usize, axis: usize| Node {
            bounds: [bounds.min.x, bounds.max.x, bounds.min.y, bounds.max.y, bounds.min.z, bounds.max.z],
            offset: offset as u32,
            count: count as u16,
            axis: axis as u8,
        };
        self.nodes.push(node(start, prims.len(), 0));
        let Some((axis, mid)) = split(prims, bounds, depth) else { return };
        let (below, above) = prims.split_at_mut(mid);
        self.emit(below, start, depth + 1);
        let second = self.nodes.len();
        self.emit(above, start + mid, depth + 1);
        self.nodes[at] = node(second, 0, axis);
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The number of levels (0 for the empty tree, 1 for a lone leaf).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The tree's SAH cost, for reports: the expected work of a ray that
    /// meets the root, Σ over interior nodes of area/root area (one box
    /// test each) plus Σ over leaves of area/root area × count (triangle
    /// tests). A single leaf costs its count; 0 for the empty tree. Every
    /// ratio is taken as 1 when the root's area is 0 or not finite.
    pub fn sah_cost(&self) -> f32 {
        let area = |n: &Node| {
            let b = n.bounds;
            Bounds { min: Vec3::new(b[0], b[2], b[4]), max: Vec3::new(b[1], b[3], b[5]) }.area()
        };
        let root = self.nodes.first().map_or(0.0, area);
        let ratio = |n: &Node| if root > 0.0 && root.is_finite() { area(n) / root } else { 1.0 };
        self.nodes.iter().map(|n| ratio(n) * if n.count > 0 { f32::from(n.count) } else { 1.0 }).sum()
    }

    /// Visits the nodes `ray` may hit in, nearer child first, calling
    /// `leaf` with each leaf's indices; `prune(lower)` skips a node whose
    /// hits all have t ≥ `lower`. Stops when `leaf` returns false.
    #[inline]
    fn traverse(
        &self,
        ray: &Frame,
        count: &mut Counters,
        prune: impl FnMut(f32) -> bool,
        leaf: impl FnMut(&[u32], &mut Counters) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return true;
        }
        // One loop per dominant axis, so that the box test reads the
        // node's coordinates at fixed places.
        match ray.axes[2] {
            0 => self.walk::<0>(ray, count, prune, leaf),
            1 => self.walk::<1>(ray, count, prune, leaf),
            _ => self.walk::<2>(ray, count, prune, leaf),
        }
    }

    /// [`Self::traverse`] for rays whose dominant axis is `KZ`.
    #[inline(always)]
    fn walk<const KZ: usize>(
        &self,
        ray: &Frame,
        count: &mut Counters,
        mut prune: impl FnMut(f32) -> bool,
        mut leaf: impl FnMut(&[u32], &mut Counters) -> bool,
    ) -> bool {
        let mut stack = [0u32; STACK];
        let mut len = 0;
        let mut at = 0;
        loop {
            let node = &self.nodes[at];
            count.nodes += 1;
            let visit = ray.lower_bound::<KZ>(node).is_some_and(|lower| !prune(lower));
            if visit && node.count > 0 {
                let first = node.offset as usize;
                if !leaf(&self.indices[first..first + usize::from(node.count)], count) {
                    return false;
                }
            } else if visit {
                // Nearer child first: the second child when the ray runs
                // towards −axis (it holds the larger centroids).
                let (near, far) = if ray.negative[usize::from(node.axis)] {
                    (node.offset as usize, at + 1)
                } else {
                    (at + 1, node.offset as usize)
                };
                stack[len] = far as u32; // len ≤ DEPTH_LIMIT < STACK (module doc)
                len += 1;
                at = near;
                continue;
            }
            if len == 0 {
                return true;
            }
            len -= 1;
            at = stack[len] as usize;
        }
    }
}

impl Accelerator for Bvh {
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit> {
        count.rays += 1;
        let sheared = Sheared::new(ray)?;
        let frame = Frame::new(ray, &sheared);
        let mut best: Option<Hit> = None;
        let best_t = std::cell::Cell::new(f32::INFINITY);
        self.traverse(
            &frame,
            count,
            |lower| lower > best_t.get(),
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
        self.traverse(
            &frame,
            count,
            |_| false,
            |indices, count| each_in(triangles, indices.iter().copied(), &sheared, count, &mut *visit),
        )
    }
}

/// Chooses how to split `prims` (bounds `bounds`, at `depth`): `None` for a
/// leaf, else the axis and the count below, after partitioning them.
fn split(prims: &mut [Prim], bounds: Bounds, depth: usize) -> Option<(usize, usize)> {
    let n = prims.len();
    let small = n <= MAX_LEAF;
    if n == 1 || (small && bounds.area() == 0.0) {
        return None;
    }
    let centroids = prims.iter().fold(Bounds::EMPTY, |b, p| b.grow(p.centroid));
    let extent = centroids.max - centroids.min;
    let axis = extent.max_position();
    let area = bounds.area();
    let degenerate = !(extent[axis] > 0.0 && extent[axis].is_finite() && area > 0.0 && area.is_finite());
    if depth + ceil_log2(n) >= DEPTH_LIMIT || degenerate {
        return if small { None } else { Some((axis, median(prims, axis))) };
    }
    let bucket = |p: &Prim| {
        let offset = (p.centroid[axis] - centroids.min[axis]) / extent[axis];
        ((BUCKETS as f32 * offset) as usize).min(BUCKETS - 1) // NaN → 0
    };
    let mut counts = [0usize; BUCKETS];
    let mut boxes = [Bounds::EMPTY; BUCKETS];
    for p in prims.iter() {
        let b = bucket(p);
        counts[b] += 1;
        boxes[b] = boxes[b].union(p.bounds);
    }
    // costs[i]: splitting after bucket i, before the 0.5 and the division.
    let mut costs = [0.0f32; BUCKETS - 1];
    let (mut below, mut below_box) = (0, Bounds::EMPTY);
    for i in 0..BUCKETS - 1 {
        below += counts[i];
        below_box = below_box.union(boxes[i]);
        costs[i] = below as f32 * below_box.area();
    }
    let (mut above, mut above_box) = (0, Bounds::EMPTY);
    for i in (1..BUCKETS).rev() {
        above += counts[i];
        above_box = above_box.union(boxes[i]);
        costs[i - 1] += above as f32 * above_box.area();
    }
    let best = (0..BUCKETS - 1).fold(0, |b, i| if costs[i] < costs[b] { i } else { b });
    let cost = 0.5 + costs[best] / area;
    let split_pays = cost < n as f32; // false for NaN
    if small && !split_pays {
        return None;
    }
    let mid = partition(prims, |p| bucket(p) <= best);
    Some((axis, if mid == 0 || mid == n { median(prims, axis) } else { mid }))
}

/// Puts the prims for which `below` holds first; returns how many.
fn partition(prims: &mut [Prim], below: impl Fn(&Prim) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..prims.len() {
        if below(&prims[i]) {
            prims.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

/// Splits `prims` at half by centroid on `axis`; returns the half (≥ 1).
fn median(prims: &mut [Prim], axis: usize) -> usize {
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

/// ⌈log₂ n⌉ (0 for n ≤ 1).
fn ceil_log2(n: usize) -> usize {
    n.next_power_of_two().trailing_zeros() as usize
}

/// A ray's per-traversal values: the watertight test's own shear (taken
/// from its [`Sheared`]) and the bounds that make the box test exact
/// (module doc).
#[derive(Clone, Copy, Debug)]
struct Frame {
    origin: [f32; 3],
    axes: [usize; 3],
    shear: Vec3,
    negative: [bool; 3],
    /// Hits have t ≤ t_max·(1 + u)³; this is above that.
    t_limit: f32,
    /// 1 − γ(9): a box's least sheared z times this is at most any hit's t.
    shrink: f32,
    /// (o[kx], o[kx], o[ky], o[ky]): the box test's four lanes.
    origin_xy: Vec4,
    /// (s_x, s_x, s_y, s_y).
    shear_xy: Vec4,
}

impl Frame {
    /// The frame of `ray`, whose watertight test's values are `sheared`.
    fn new(ray: &Ray, sheared: &Sheared) -> Frame {
        let d = ray.dir;
        let ([kx, ky, kz], shear) = sheared.frame();
        Frame {
            origin: ray.origin.to_array(),
            axes: [kx, ky, kz],
            shear,
            negative: [d.x < 0.0, d.y < 0.0, d.z < 0.0],
            t_limit: ray.t_max * (1.0 + gamma(4)),
            shrink: 1.0 - gamma(9),
            origin_xy: Vec4::new(ray.origin[kx], ray.origin[kx], ray.origin[ky], ray.origin[ky]),
            shear_xy: Vec4::new(shear.x, shear.x, shear.y, shear.y),
        }
    }

    /// `None` when no triangle inside `node`'s box can be hit, else a lower
    /// bound on the t of its hits. Comparisons with NaN never cull.
    /// `KZ` is the ray's dominant axis, `self.axes[2]`.
    #[inline(always)]
    fn lower_bound<const KZ: usize>(&self, node: &Node) -> Option<f32> {
        let (kz, kx, ky) = (KZ, (KZ + 1) % 3, (KZ + 2) % 3);
        let (o, s) = (&self.origin, self.shear);
        let (z0, z1) = (node.bounds[2 * kz] - o[kz], node.bounds[2 * kz + 1] - o[kz]);
        // The sheared coordinate's range over the box: v − o plus the shear
        // term, the latter least at the kz face its sign picks (z0 ≤ z1 and
        // rounding is monotone, so the smaller product is that face's; the
        // box's coordinates are finite).
        // x and y in four lanes, (low x, high x, low y, high y), each lane
        // the scalar operations of the one-axis form below (a NaN, which
        // only overflowing coordinates give, never culls).
        let b = &node.bounds;
        let b = Vec4::new(b[2 * kx], b[2 * kx + 1], b[2 * ky], b[2 * ky + 1]);
        let (a, c) = (self.shear_xy * z0, self.shear_xy * z1);
        let range = (b - self.origin_xy) + Vec4::select(LOW_HIGH, a.min(c), a.max(c));
        // Culled when low x > 0, high x < 0, low y > 0 or high y < 0.
        if (range * Vec4::new(1.0, -1.0, 1.0, -1.0)).cmpgt(Vec4::ZERO).any() {
            return None;
        }
        let span = |s: f32| {
            let (a, b) = (s * z0, s * z1);
            (a.min(b), a.max(b))
        };
        let (lo, hi) = span(s.z);
        // All vertices at z ≤ 0: the test's t_scaled ≤ 0, no hit.
        if hi <= 0.0 {
            return None;
        }
        let lower = if lo >= f32::MIN_POSITIVE { lo * self.shrink } else { 0.0 };
        (lower <= self.t_limit).then_some(lower) // neither is NaN
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::accel::testkit::{check_each_hit_stops, check_rays, check_same, ray, scene, stacked, Rng};

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn random_scenes_answer_as_brute_force(seed: u64, n in 1usize..300) {
            let mut rng = Rng(seed);
            let tris = scene(&mut rng, n);
            let bvh = Bvh::build(&tris);
            prop_assert!(bvh.depth() < STACK);
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
        assert!(bvh.depth() < STACK, "depth {}", bvh.depth());
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

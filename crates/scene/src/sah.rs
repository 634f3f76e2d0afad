//! The binned surface-area-heuristic build shared by zline's bounding-volume
//! hierarchies: the ray tracer's (`zline-trace`, which collapses it to
//! four children a node), the f64 truth's, and [`Occluders`](crate::Occluders).
//! Boxes in, a binary tree of boxes out; each caller walks it with a box
//! test of its own.
//!
//! **Build** (pbrt-v4's `BVHAggregate::buildRecursive`, binned): a node's
//! boxes are split on the axis where their centroids spread most, at the
//! best of the 11 boundaries between 12 equal buckets by the surface area
//! heuristic, cost = 0.5 + (n_below·area_below + n_above·area_above) /
//! area_node against the leaf's cost n. A node becomes a leaf when that is
//! cheaper and it holds at most [`MAX_LEAF`] boxes; above that a split is
//! forced, by the median centroid when the centroids coincide, the area is
//! zero or not finite, or the buckets put everything on one side. Nodes
//! are stored depth first (pbrt's `LinearBVHNode`): a node's first child
//! follows it, an interior node keeps its second child's offset, a leaf a
//! range of [`SahTree::order`] (the boxes' own numbers, leaf by leaf).
//!
//! **Depth bound.** The build recurses, but with bounded depth: a node at
//! depth d with n boxes is split by the median (halving n) whenever
//! d + ⌈log₂ n⌉ ≥ [`DEPTH_LIMIT`], so every node keeps d + ⌈log₂ n⌉ ≤
//! `DEPTH_LIMIT` (the root has ⌈log₂ n⌉ ≤ 32; an SAH split adds 1 to d and
//! does not grow n; a median split adds 1 and takes 1 off ⌈log₂ n⌉). Leaves
//! lie at depth ≤ 62 and the tree has ≤ 63 levels: a walk that keeps one
//! child a level needs a stack of 63.
//!
//! **Precision.** Boxes are f32: a caller with f64 geometry passes
//! [`Bounds::enclosing`] (rounded outward), so every node's box holds its
//! geometry exactly.

use glam::{DVec3, Vec3};

/// The most boxes the build puts in a leaf when a split would pay.
pub const MAX_LEAF: usize = 4;
/// Nodes with depth + ⌈log₂ count⌉ at or above this are split by the median.
pub const DEPTH_LIMIT: usize = 62;
const BUCKETS: usize = 12;

/// An axis-aligned box (empty: min > max).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The low corner.
    pub min: Vec3,
    /// The high corner.
    pub max: Vec3,
}

impl Bounds {
    /// The empty box.
    pub const EMPTY: Bounds = Bounds { min: Vec3::INFINITY, max: Vec3::NEG_INFINITY };

    /// The box of a triangle.
    pub fn of(t: &[Vec3; 3]) -> Bounds {
        Bounds { min: t[0].min(t[1]).min(t[2]), max: t[0].max(t[1]).max(t[2]) }
    }

    /// The least f32 box holding the f64 points `points` (finite; rounded
    /// outward, so a coordinate beyond f32's range gives an infinite side).
    pub fn enclosing(points: &[DVec3]) -> Bounds {
        let lo = points.iter().fold(DVec3::INFINITY, |b, &p| b.min(p));
        let hi = points.iter().fold(DVec3::NEG_INFINITY, |b, &p| b.max(p));
        let down = |v: f64| {
            let f = v as f32;
            if f64::from(f) > v {
                f.next_down()
            } else {
                f
            }
        };
        let up = |v: f64| {
            let f = v as f32;
            if f64::from(f) < v {
                f.next_up()
            } else {
                f
            }
        };
        Bounds {
            min: Vec3::new(down(lo.x), down(lo.y), down(lo.z)),
            max: Vec3::new(up(hi.x), up(hi.y), up(hi.z)),
        }
    }

    /// The box holding both.
    pub fn union(self, o: Bounds) -> Bounds {
        Bounds { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    /// The box grown to hold `p`.
    pub fn grow(self, p: Vec3) -> Bounds {
        Bounds { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The surface area (0 for the empty box).
    pub fn area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// The centre.
    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }
}

/// A node of an [`SahTree`]: a leaf when `count > 0` (`offset` = its first
/// entry in [`SahTree::order`]), else interior (`offset` = its second
/// child; the first child is the next node).
#[derive(Clone, Copy, Debug)]
pub struct SahNode {
    /// The box.
    pub bounds: Bounds,
    /// The second child, or the leaf's first entry.
    pub offset: u32,
    /// The leaf's box count (1 to [`MAX_LEAF`]), 0 for an interior node.
    pub count: u16,
}

/// A binary tree over boxes (module doc).
#[derive(Clone, Debug, Default)]
pub struct SahTree {
    /// The nodes, depth first, the root at 0 (none for no boxes).
    pub nodes: Vec<SahNode>,
    /// The boxes' numbers, leaf by leaf.
    pub order: Vec<u32>,
    /// The number of levels (0 for the empty tree, 1 for a lone leaf; ≤ 63).
    pub depth: usize,
}

/// A node of an [`SahTree`] in f64, for exact tests on f64 geometry: its
/// box widened ([`SahTree::f64_nodes`]), its offset and count as in
/// [`SahNode`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F64Node {
    /// The low corner.
    pub min: DVec3,
    /// The high corner.
    pub max: DVec3,
    /// The second child, or the leaf's first entry.
    pub offset: usize,
    /// The leaf's count, 0 for an interior node.
    pub count: usize,
}

impl F64Node {
    /// Where o + t·d enters the box within [max(t_min, 0), t_max]; `None`
    /// when it misses it (slab test; a zero component of d tests o's
    /// coordinate).
    pub fn entry(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let (mut t0, mut t1) = (t_min.max(0.0), t_max);
        for axis in 0..3 {
            let (lo, hi, o, d) = (self.min[axis], self.max[axis], o[axis], d[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
            if t0 > t1 {
                return None;
            }
        }
        Some(t0)
    }
}

/// A box during the build.
#[derive(Clone, Copy, Debug)]
struct Prim {
    bounds: Bounds,
    centroid: Vec3,
    index: u32,
}

impl SahTree {
    /// The tree over `boxes`, each with its number (kept in
    /// [`SahTree::order`]); the caller leaves out what can never be hit.
    pub fn build(boxes: impl IntoIterator<Item = (u32, Bounds)>) -> SahTree {
        let mut prims: Vec<Prim> = boxes
            .into_iter()
            .map(|(index, bounds)| {
                // Halves first: min + max can overflow where their mean does not.
                Prim { bounds, centroid: 0.5 * bounds.min + 0.5 * bounds.max, index }
            })
            .collect();
        let mut tree = SahTree { nodes: Vec::with_capacity(2 * prims.len()), order: Vec::new(), depth: 0 };
        if !prims.is_empty() {
            tree.emit(&mut prims, 0, 0);
        }
        tree.order = prims.iter().map(|p| p.index).collect();
        tree
    }

    /// Appends the subtree over `prims` (which start at `start` in the
    /// final order), depth first. Recursion depth ≤ [`DEPTH_LIMIT`].
    fn emit(&mut self, prims: &mut [Prim], start: usize, depth: usize) {
        debug_assert!(depth + ceil_log2(prims.len()) <= DEPTH_LIMIT);
        self.depth = self.depth.max(depth + 1);
        let bounds = prims.iter().fold(Bounds::EMPTY, |b, p| b.union(p.bounds));
        let at = self.nodes.len();
        let node =
            |offset: usize, count: usize| SahNode { bounds, offset: offset as u32, count: count as u16 };
        self.nodes.push(node(start, prims.len()));
        let Some(mid) = split(prims, bounds, depth) else { return };
        let (below, above) = prims.split_at_mut(mid);
        self.emit(below, start, depth + 1);
        let second = self.nodes.len();
        self.emit(above, start + mid, depth + 1);
        self.nodes[at] = node(second, 0);
    }

    /// The nodes in f64, every box widened by 10⁻⁷ of the root's size (its
    /// extent or its distance from the origin, the larger): an f64 slab
    /// test's rounding then never rejects geometry an exact test hits.
    pub fn f64_nodes(&self) -> Vec<F64Node> {
        let Some(root) = self.nodes.first() else { return Vec::new() };
        let (lo, hi) = (root.bounds.min.as_dvec3(), root.bounds.max.as_dvec3());
        let scale = (hi - lo).max_element().max(lo.abs().max(hi.abs()).max_element());
        let margin = DVec3::splat(1e-7 * scale.max(f64::MIN_POSITIVE));
        let node = |n: &SahNode| F64Node {
            min: n.bounds.min.as_dvec3() - margin,
            max: n.bounds.max.as_dvec3() + margin,
            offset: n.offset as usize,
            count: usize::from(n.count),
        };
        self.nodes.iter().map(node).collect()
    }

    /// The tree's SAH cost, for reports: the expected work of a ray that
    /// meets the root, Σ over interior nodes of area/root area (one box
    /// test each) plus Σ over leaves of area/root area × count (box
    /// contents tested). A single leaf costs its count; 0 for the empty
    /// tree. Every ratio is taken as 1 when the root's area is 0 or not
    /// finite.
    pub fn sah_cost(&self) -> f32 {
        let root = self.nodes.first().map_or(0.0, |n| n.bounds.area());
        let ratio = |n: &SahNode| if root > 0.0 && root.is_finite() { n.bounds.area() / root } else { 1.0 };
        self.nodes.iter().map(|n| ratio(n) * if n.count > 0 { f32::from(n.count) } else { 1.0 }).sum()
    }
}

/// Chooses how to split `prims` (bounds `bounds`, at `depth`): `None` for a
/// leaf, else the count below, after partitioning them.
fn split(prims: &mut [Prim], bounds: Bounds, depth: usize) -> Option<usize> {
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
        return if small { None } else { Some(median(prims, axis)) };
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
    Some(if mid == 0 || mid == n { median(prims, axis) } else { mid })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks the tree's invariants: every box once, leaves of 1 to
    /// MAX_LEAF, children inside their parents, depth within the bound.
    fn check(tree: &SahTree, boxes: &[Bounds]) {
        let mut seen = tree.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..boxes.len() as u32).collect::<Vec<_>>());
        assert!(tree.depth <= DEPTH_LIMIT + 1);
        let inside = |a: &Bounds, b: &Bounds| a.min.cmpge(b.min).all() && a.max.cmple(b.max).all();
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            let n = tree.nodes[at];
            if n.count > 0 {
                assert!(usize::from(n.count) <= MAX_LEAF);
                for &i in &tree.order[n.offset as usize..n.offset as usize + usize::from(n.count)] {
                    assert!(inside(&boxes[i as usize], &n.bounds));
                }
                continue;
            }
            for child in [at + 1, n.offset as usize] {
                assert!(inside(&tree.nodes[child].bounds, &n.bounds));
                stack.push(child);
            }
        }
    }

    #[test]
    fn every_box_lands_in_one_leaf_inside_its_ancestors() {
        let mut state = 1u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        for n in [1, 2, 5, 100, 3000] {
            let boxes: Vec<Bounds> = (0..n)
                .map(|_| {
                    let c = Vec3::new(next(), next(), next()) * 10.0;
                    Bounds { min: c, max: c + Vec3::new(next(), next(), next()) * 0.3 }
                })
                .collect();
            let tree = SahTree::build((0..).zip(boxes.iter().copied()));
            check(&tree, &boxes);
        }
        // Coincident boxes: median splits only.
        let same = vec![Bounds { min: Vec3::ZERO, max: Vec3::ONE }; 1000];
        check(&SahTree::build((0..).zip(same.iter().copied())), &same);
        assert_eq!(SahTree::build(std::iter::empty()).nodes.len(), 0);
    }

    #[test]
    fn enclosing_rounds_outward() {
        let p = [DVec3::new(0.1, -0.1, 1e300), DVec3::new(1.0 / 3.0, 2.0, -1e300)];
        let b = Bounds::enclosing(&p);
        for (axis, (lo, hi)) in [(0.1, 1.0 / 3.0), (-0.1, 2.0), (-1e300, 1e300)].into_iter().enumerate() {
            assert!(f64::from(b.min[axis]) <= lo && f64::from(b.max[axis]) >= hi, "{b:?}");
        }
        assert_eq!((b.min.x, b.max.y), (0.099_999_994, 2.0));
        assert!(f64::from(b.min.x) < 0.1 && f64::from(b.min.x.next_up()) > 0.1);
        assert_eq!((b.min.z, b.max.z), (f32::NEG_INFINITY, f32::INFINITY));
    }
}

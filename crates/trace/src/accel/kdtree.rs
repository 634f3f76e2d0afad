//! The kd-tree: an axis-aligned binary space partition built by the surface
//! area heuristic (pbrt-v3's `KdTreeAccel`) and traversed front to back;
//! it answers exactly as [`Brute`](super::brute::Brute) does.
//!
//! **Build.** The root's cell is the box of the triangles with finite
//! corners (the others are left out: the watertight test never hits them).
//! A cell is split by a plane at one of its triangles' box faces strictly
//! inside it, on the cell's longest axis, or when that axis has none, on
//! the next and then the last. The candidates are swept in sorted order and
//! costed as pbrt does, 1 + 80·(1 − b)·(p_below·n_below + p_above·n_above)
//! with p a child's surface area over the cell's (its length ratio when the
//! cell has no area) and b = 0.5 when a side is empty, against the leaf's
//! 80·n. A triangle goes below when its box starts below the plane or lies
//! in it, above when its box ends above it, to both when it straddles it.
//! A node is a leaf when it holds at most one triangle, at depth
//! round(8 + 1.3·⌊log₂ N⌋) (N triangles), when no plane lies inside its
//! cell, when the best split costs over four times the leaf and it holds
//! fewer than 16 triangles, at the third split on its path that did not
//! lower the cost, or when the split would overrun its budget (below).
//! Nodes are stored depth first, the below child right after its parent;
//! the leaves' triangle indices lie in one list.
//!
//! **Bounds.** At most 2³² − 1 triangles are indexed, so the depth is at
//! most round(8 + 1.3·31) = 48: the tree has at most 49 levels, and the
//! traversal stack, one far child per interior ancestor, needs at most 48
//! of its `STACK` entries. Large overlapping triangles can be referenced by
//! many leaves; a budget caps that. The root gets 16·N + 1024 units, a leaf
//! costs 1 + its references, a node is split only when 3 + its children's
//! references fit in its units (the node and two leaves), and the units
//! left over are shared between the children in proportion to their
//! triangles. So nodes + references ≤ 16·N + 1024 for any input, however
//! the budget falls; ordinary scenes stay well below it (a scattered soup
//! of small triangles needs about 5·N), heaps of large overlapping ones
//! reach it. A node's children hold at least its references between them,
//! so the nodes of one level hold at most R, the final reference count, and
//! the build, which sorts a node's 2n box faces on at most three axes,
//! takes O(48 · R log R) time. Surface areas are taken in f64, which
//! neither overflows nor loses a flat cell.
//!
//! **Traversal and exactness.** Brute force's nearest hit is the least by
//! [`Hit::nearer_than`] of the watertight test's *computed* t values. The
//! usual argument (a hit point lies in a leaf that holds the triangle, and
//! leaves are met in order of t) holds for the exact ray, not for those
//! values: the test can accept a ray that misses by a rounding error, and
//! an edge-on triangle's computed t and a plane crossing can come out in
//! either order. It is redone with rounding. When the test reports a hit,
//! the origin lies in the triangle as computed in sheared space (the edge
//! functions keep their exact signs), so exact barycentrics β ≥ 0 of it
//! name a point Y = Σβᵢpᵢ of the world triangle. Each computed sheared
//! vertex differs from the exact shear of pᵢ by at most 2γ(4)·M, M a bound
//! on |pᵢ − o| in every coordinate, so the point X of the exact ray at
//! `t* = (Y − o)[kz]/d[kz] = Σβᵢ(pᵢ − o)[kz]/d[kz]` is within δ = 2γ(4)·M of
//! Y in every coordinate; the computed t is that sum with each term off by
//! a factor within 1 ± γ(16), so `|t − t*| ≤ τ = γ(16)·M/|d[kz]|`. Y lies in
//! the closed cell of a leaf holding the triangle (follow Y down: a
//! triangle goes to each side its box reaches past the plane, and to one
//! side when flat in it), so X lies in that cell grown by δ, at
//! t* ∈ (−τ, t_max·(1 + γ(3)) + τ). The traversal therefore works on cells
//! grown by δ: each node carries an interval [t₀, t₁] holding every
//! parameter in that range at which the exact ray is inside its grown cell
//! (plane crossings widened by `δ/|d[a]|` and by their own rounding; a ray
//! parallel to a plane enters each side its origin is within δ of), so
//! every hit is tested at the leaf holding its X. The near child goes
//! first, and `closest` skips a node when best + τ < t₀: a hit whose X lies
//! below that node has t ≥ t* − τ ≥ t₀ − τ > best (strictly, as a tie with
//! a lower index would win). The grown intervals overlap, so a skipped node
//! does not end the traversal. M is taken per ray from the scene box and
//! the origin; δ and τ are computed with twice the γ needed, which covers
//! their own rounding, and overflow makes them infinite, which only adds
//! visits. Triangles are tested with the original ray. As in the BVH, the
//! only gap is underflow (triangles some 10⁻¹⁹ across). A triangle held by
//! several leaves is tested once per leaf; `each_hit` reports it once.

use glam::Vec3;

use super::{each_in, nearest_in, Accelerator, Bounds, Counters, Reported};
use crate::ray::{gamma, Hit, Ray, Sheared};

/// pbrt's cost of a ray–triangle test, relative to a traversal step.
const ISECT_COST: f64 = 80.0;
/// pbrt's cost of a traversal step.
const TRAVERSAL_COST: f64 = 1.0;
/// The fraction of the cost taken off a split with an empty side.
const EMPTY_BONUS: f64 = 0.5;
/// A node with at most this many triangles is a leaf.
const MAX_PRIMS: usize = 1;
/// The traversal stack's size (more than the deepest tree's 48 interior levels).
const STACK: usize = 64;
/// The `axis` of a leaf.
const LEAF: u8 = 3;

/// A kd-tree over a triangle list (see the module doc).
#[derive(Clone, Debug)]
pub struct KdTree {
    nodes: Vec<Node>,
    /// The leaves' triangle indices.
    indices: Vec<u32>,
    /// The root's cell.
    bounds: Bounds,
    depth: usize,
}

/// A flattened node: a leaf when `axis` is [`LEAF`] (`value` = its first
/// index in `KdTree::indices`, `link` = how many), else interior (`value` =
/// the plane's bits, `link` = the above child; the below child is next).
#[derive(Clone, Copy, Debug)]
struct Node {
    value: u32,
    link: u32,
    axis: u8,
}

/// The state of a build.
struct Builder {
    nodes: Vec<Node>,
    indices: Vec<u32>,
    depth: usize,
    /// The depth at which nodes become leaves.
    max_depth: usize,
    /// Scratch space for [`Builder::choose`]'s sorted box faces.
    edges: Vec<u64>,
}

/// A triangle during the build: its box and index (carried along, so that
/// a node's boxes are read in order).
#[derive(Clone, Copy, Debug)]
struct Prim {
    bounds: Bounds,
    index: u32,
}

impl KdTree {
    /// Builds the tree over `triangles` (empty when there are none, or none
    /// with finite corners).
    pub fn build(triangles: &[[Vec3; 3]]) -> KdTree {
        let prims: Vec<Prim> = (0..u32::MAX)
            .zip(triangles)
            .filter(|(_, t)| t.iter().all(|p| p.is_finite()))
            .map(|(index, t)| Prim { bounds: Bounds::of(t), index })
            .collect();
        let bounds = prims.iter().fold(Bounds::EMPTY, |b, p| b.union(p.bounds));
        let n = prims.len();
        let max_depth = max_depth(n);
        let mut builder =
            Builder { nodes: Vec::new(), indices: Vec::new(), depth: 0, max_depth, edges: Vec::new() };
        if n > 0 {
            builder.grow(prims, bounds, max_depth, 0, (16 * n as u64 + 1024).min(u64::from(u32::MAX)));
        }
        KdTree { nodes: builder.nodes, indices: builder.indices, bounds, depth: builder.depth }
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The number of levels (0 for the empty tree, 1 for a lone leaf).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The number of triangle references in the leaves (a triangle held by
    /// several leaves counts once for each).
    pub fn reference_count(&self) -> usize {
        self.indices.len()
    }

    /// Visits the leaves `ray` may hit in, near child first, calling `leaf`
    /// with each leaf's indices; `prune(t0)` skips a node whose interval
    /// starts at `t0`. Stops when `leaf` returns false.
    #[inline]
    fn traverse(
        &self,
        ray: &Frame,
        count: &mut Counters,
        mut prune: impl FnMut(f32) -> bool,
        mut leaf: impl FnMut(&[u32], &mut Counters) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return true;
        }
        let Some((mut t0, mut t1)) = ray.root(&self.bounds) else {
            count.nodes += 1;
            return true;
        };
        let mut stack = [(0usize, 0.0f32, 0.0f32); STACK];
        let mut len = 0;
        let mut at = 0;
        loop {
            let node = self.nodes[at];
            count.nodes += 1;
            let next = if prune(t0) {
                None
            } else if node.axis == LEAF {
                let first = node.value as usize;
                if !leaf(&self.indices[first..first + node.link as usize], count) {
                    return false;
                }
                None
            } else {
                let axis = usize::from(node.axis);
                let split = f32::from_bits(node.value);
                let (below, above) = ray.children(axis, split, t0, t1);
                let below = below.map(|(a, b)| (at + 1, a, b));
                let above = above.map(|(a, b)| (node.link as usize, a, b));
                let d = ray.dir[axis];
                let below_first = d > 0.0 || (d == 0.0 && ray.origin[axis] <= split);
                let (near, far) = if below_first { (below, above) } else { (above, below) };
                if let (Some(_), Some(far)) = (near, far) {
                    stack[len] = far; // len < depth ≤ 48 < STACK (module doc)
                    len += 1;
                }
                near.or(far)
            };
            if let Some(next) = next {
                (at, t0, t1) = next;
            } else if len > 0 {
                len -= 1;
                (at, t0, t1) = stack[len];
            } else {
                return true;
            }
        }
    }
}

impl Accelerator for KdTree {
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit> {
        count.rays += 1;
        let sheared = Sheared::new(ray)?;
        let frame = Frame::new(ray, &self.bounds);
        let mut best: Option<Hit> = None;
        let best_t = std::cell::Cell::new(f32::INFINITY);
        self.traverse(
            &frame,
            count,
            |t0| best_t.get() + frame.tau < t0,
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
        let frame = Frame::new(ray, &self.bounds);
        let mut reported = Reported::default();
        self.traverse(
            &frame,
            count,
            |_| false,
            |indices, count| {
                each_in(triangles, indices.iter().copied(), &sheared, count, |hit| {
                    !reported.insert(hit.triangle) || visit(hit)
                })
            },
        )
    }
}

impl Builder {
    /// Appends the subtree over `prims` in `cell` (with `depth_left` splits
    /// allowed, `bad` bad refines on the path so far and `allowance` units of
    /// the budget), depth first.
    fn grow(&mut self, prims: Vec<Prim>, cell: Bounds, depth_left: usize, bad: u32, allowance: u64) {
        self.depth = self.depth.max(self.max_depth - depth_left + 1);
        let at = self.nodes.len();
        let first = self.indices.len() as u32; // at most max(N, budget) < 2³²
        self.nodes.push(Node { value: first, link: prims.len() as u32, axis: LEAF });
        let split =
            if prims.len() <= MAX_PRIMS || depth_left == 0 { None } else { self.choose(&prims, cell) };
        let Some((axis, plane, cost)) = split else { return self.leaf(&prims) };
        let n = prims.len();
        let bad = bad + u32::from(cost > ISECT_COST * n as f64);
        if (cost > 4.0 * ISECT_COST * n as f64 && n < 16) || bad == 3 {
            return self.leaf(&prims);
        }
        let (mut below, mut above) = (Vec::new(), Vec::new());
        for p in &prims {
            let (lo, hi) = (p.bounds.min[axis], p.bounds.max[axis]);
            if lo < plane || hi <= plane {
                below.push(*p);
            }
            if hi > plane {
                above.push(*p);
            }
        }
        let (n0, n1) = (below.len() as u64, above.len() as u64);
        let Some(slack) = allowance.checked_sub(3 + n0 + n1) else { return self.leaf(&prims) };
        drop(prims);
        // n0 + n1 ≥ n ≥ 2: every triangle goes to a side.
        let a0 = 1 + n0 + (u128::from(slack) * u128::from(n0) / u128::from(n0 + n1)) as u64;
        let (mut cell0, mut cell1) = (cell, cell);
        cell0.max[axis] = plane;
        cell1.min[axis] = plane;
        self.grow(below, cell0, depth_left - 1, bad, a0);
        let above_at = self.nodes.len() as u32;
        self.nodes[at] = Node { value: plane.to_bits(), link: above_at, axis: axis as u8 };
        self.grow(above, cell1, depth_left - 1, bad, allowance - 1 - a0);
    }

    /// Ends the node just pushed as a leaf holding `prims`.
    fn leaf(&mut self, prims: &[Prim]) {
        self.indices.extend(prims.iter().map(|p| p.index));
    }

    /// The cheapest plane for `prims` in `cell` by pbrt's SAH: the axis, the
    /// plane and its cost; `None` when no box face lies inside the cell.
    fn choose(&mut self, prims: &[Prim], cell: Bounds) -> Option<(usize, f32, f64)> {
        let extent = [0, 1, 2].map(|a| f64::from(cell.max[a]) - f64::from(cell.min[a]));
        let longest = (0..3).fold(0, |b, a| if extent[a] > extent[b] { a } else { b });
        let edges = &mut self.edges;
        let mut best: Option<(usize, f32, f64)> = None;
        for axis in [longest, (longest + 1) % 3, (longest + 2) % 3] {
            edges.clear();
            for p in prims {
                let (lo, hi) = (p.bounds.min[axis], p.bounds.max[axis]);
                if lo == hi {
                    edges.push(edge(lo, FLAT));
                } else {
                    edges.extend([edge(lo, START), edge(hi, END)]);
                }
            }
            edges.sort_unstable();
            let (lo, hi) = (cell.min[axis], cell.max[axis]);
            let (e0, e1) = (extent[(axis + 1) % 3], extent[(axis + 2) % 3]);
            let area = |length: f64| 2.0 * (e0 * e1 + length * (e0 + e1));
            let total = area(extent[axis]);
            let n = prims.len();
            // Boxes starting, and boxes ending, below the planes swept so far.
            let (mut started, mut ended) = (0, 0);
            let mut i = 0;
            while i < edges.len() {
                let plane = coordinate(edges[i]);
                let (mut starts, mut flats, mut ends) = (0, 0, 0);
                while i < edges.len() && coordinate(edges[i]) == plane {
                    match edges[i] & 3 {
                        START => starts += 1,
                        FLAT => flats += 1,
                        _ => ends += 1,
                    }
                    i += 1;
                }
                if lo < plane && plane < hi {
                    let (n_below, n_above) = (started + flats, n - ended - ends - flats);
                    let (below, above) = (f64::from(plane) - f64::from(lo), f64::from(hi) - f64::from(plane));
                    let (p_below, p_above) = if total > 0.0 {
                        (area(below) / total, area(above) / total)
                    } else {
                        (below / extent[axis], above / extent[axis])
                    };
                    let bonus = if n_below == 0 || n_above == 0 { EMPTY_BONUS } else { 0.0 };
                    let cost = TRAVERSAL_COST
                        + ISECT_COST * (1.0 - bonus) * (p_below * n_below as f64 + p_above * n_above as f64);
                    if best.is_none_or(|b| cost < b.2) {
                        best = Some((axis, plane, cost));
                    }
                }
                started += starts + flats;
                ended += ends + flats;
            }
            if best.is_some() {
                break;
            }
        }
        best
    }
}

/// pbrt's depth limit for `n` triangles, round(8 + 1.3·⌊log₂ n⌋).
fn max_depth(n: usize) -> usize {
    n.checked_ilog2().map_or(0, |log| (8.0 + 1.3 * f64::from(log)).round() as usize)
}

/// The kinds of a box face on the sweep axis: the low face, both faces of
/// a box flat on that axis, the high face.
const START: u64 = 0;
const FLAT: u64 = 1;
const END: u64 = 2;

/// A box face as a key that sorts as `f32::total_cmp` sorts its coordinate
/// `t` (then by `kind`).
fn edge(t: f32, kind: u64) -> u64 {
    let bits = t.to_bits();
    let ordered = if bits >> 31 == 1 { !bits } else { bits | 1 << 31 };
    u64::from(ordered) << 2 | kind
}

/// The coordinate of an [`edge`] key.
fn coordinate(edge: u64) -> f32 {
    let ordered = (edge >> 2) as u32;
    f32::from_bits(if ordered >> 31 == 1 { ordered & !(1 << 31) } else { !ordered })
}

/// A node's interval of t, `None` when the ray misses it.
type Span = Option<(f32, f32)>;

/// A ray's per-traversal values and its margins (module doc).
#[derive(Clone, Copy, Debug)]
struct Frame {
    origin: [f32; 3],
    dir: [f32; 3],
    inv: [f32; 3],
    t_max: f32,
    /// How far a hit's point may lie from the exact ray, per coordinate.
    delta: f32,
    /// How far a hit's computed t may lie from its point's t on the ray.
    tau: f32,
}

impl Frame {
    /// The values for `ray` (finite origin, finite nonzero direction) in a
    /// scene within `bounds`.
    fn new(ray: &Ray, bounds: &Bounds) -> Frame {
        let reach = (bounds.min - ray.origin).abs().max((bounds.max - ray.origin).abs()).max_element();
        Frame {
            origin: ray.origin.to_array(),
            dir: ray.dir.to_array(),
            inv: ray.dir.recip().to_array(),
            t_max: ray.t_max,
            delta: gamma(16) * reach,
            tau: gamma(32) * reach / ray.dir.abs().max_element(),
        }
    }

    /// An interval of t holding every t at which the exact ray is within
    /// `delta` of the plane at `plane` on `axis` (whose direction is not 0);
    /// never NaN.
    #[inline]
    fn crossing(&self, axis: usize, plane: f32) -> (f32, f32) {
        let t = (plane - self.origin[axis]) * self.inv[axis];
        let margin = 2.0 * (self.delta * self.inv[axis].abs() + gamma(8) * t.abs());
        let (lo, hi) = (t - margin, t + margin);
        (if lo.is_nan() { f32::NEG_INFINITY } else { lo }, if hi.is_nan() { f32::INFINITY } else { hi })
    }

    /// The root's interval: the scene box grown by `delta`, within
    /// (−τ, t_max·(1 + γ(3)) + τ); `None` when empty.
    fn root(&self, bounds: &Bounds) -> Option<(f32, f32)> {
        let mut t0 = -self.tau;
        let mut t1 = self.t_max * (1.0 + gamma(8)) + 2.0 * self.tau;
        if t1.is_nan() {
            t1 = f32::INFINITY;
        }
        for axis in 0..3 {
            let (lo, hi, o, d) = (bounds.min[axis], bounds.max[axis], self.origin[axis], self.dir[axis]);
            if d == 0.0 {
                // Rounding is monotone: o ≥ lo − δ implies o ≥ fl(lo − δ).
                if !(lo - self.delta <= o && o <= hi + self.delta) {
                    return None;
                }
                continue;
            }
            let (enter, exit) = if d > 0.0 { (lo, hi) } else { (hi, lo) };
            t0 = t0.max(self.crossing(axis, enter).0);
            t1 = t1.min(self.crossing(axis, exit).1);
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// The intervals of the children below and above `plane` on `axis` of
    /// a node with interval [t0, t1]; `None` for a child the ray misses.
    #[inline]
    fn children(&self, axis: usize, plane: f32, t0: f32, t1: f32) -> (Span, Span) {
        let (o, d) = (self.origin[axis], self.dir[axis]);
        if d == 0.0 {
            let below = o <= plane + self.delta;
            let above = o >= plane - self.delta;
            return (below.then_some((t0, t1)), above.then_some((t0, t1)));
        }
        let (lo, hi) = self.crossing(axis, plane);
        let before = (t0 <= hi.min(t1)).then(|| (t0, hi.min(t1)));
        let after = (lo.max(t0) <= t1).then(|| (lo.max(t0), t1));
        if d > 0.0 {
            (before, after)
        } else {
            (after, before)
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::accel::testkit::{check_each_hit_stops, check_rays, check_same, ray, scene, stacked, Rng};

    /// The tree's structural bounds (module doc).
    fn assert_bounded(tree: &KdTree, n: usize) {
        assert!(tree.depth() <= max_depth(n) + 1 && tree.depth() < STACK, "depth {}", tree.depth());
        assert!(tree.node_count() + tree.reference_count() <= 16 * n + 1024, "{tree:?}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn random_scenes_answer_as_brute_force(seed: u64, n in 1usize..300) {
            let mut rng = Rng(seed);
            let tris = scene(&mut rng, n);
            let tree = KdTree::build(&tris);
            assert_bounded(&tree, n);
            for _ in 0..200 {
                check_same(&tree, &tris, &ray(&mut rng, &tris));
            }
        }
    }

    #[test]
    fn a_hundred_thousand_rays_through_a_soup_answer_as_brute_force() {
        let mut rng = Rng(0x5eed);
        let tris = scene(&mut rng, 2000);
        let (mine, brute) = check_rays(&KdTree::build(&tris), &tris, &mut rng, 100_000);
        assert!(mine.tests * 10 < brute.tests, "{mine:?} against {brute:?}");
    }

    #[test]
    fn each_hit_stops_when_told() {
        let tris = stacked();
        check_each_hit_stops(&KdTree::build(&tris), &tris);
    }

    #[test]
    fn an_empty_tree_hits_nothing() {
        let bad = [[Vec3::NAN, Vec3::ZERO, Vec3::X], [Vec3::ZERO, Vec3::INFINITY, Vec3::X]];
        for tris in [&[][..], &bad[..]] {
            let tree = KdTree::build(tris);
            assert_eq!((tree.node_count(), tree.depth(), tree.reference_count()), (0, 0, 0));
            let ray = Ray::new(Vec3::new(0.1, 0.1, 1.0), -Vec3::Z);
            let mut count = Counters::default();
            assert_eq!(tree.closest(tris, &ray, &mut count), None);
            assert!(tree.each_hit(tris, &ray, &mut count, &mut |_| false));
            assert_eq!(count, Counters { rays: 2, nodes: 0, tests: 0 });
        }
    }

    /// Rays lying in the tree's split planes, along them and across them,
    /// from origins on them, through a grid whose faces coincide.
    #[test]
    fn rays_in_split_planes_answer_as_brute_force() {
        let mut tris = Vec::new();
        for i in 0..8 {
            for j in 0..8 {
                let c = Vec3::new(i as f32, j as f32, ((i * j) % 3) as f32);
                tris.push([c, c + Vec3::X, c + Vec3::Y]);
                tris.push([c + Vec3::X, c + Vec3::new(1.0, 1.0, 0.5), c + Vec3::Y]);
                tris.push([c, c + Vec3::Z, c + Vec3::X]);
            }
        }
        let tree = KdTree::build(&tris);
        assert!(tree.depth() > 5, "{}", tree.depth());
        let mut rng = Rng(11);
        for node in tree.nodes.iter().filter(|n| n.axis != LEAF).take(200) {
            let (axis, plane) = (usize::from(node.axis), f32::from_bits(node.value));
            for _ in 0..20 {
                let mut origin = rng.point(10.0) + Vec3::splat(4.0);
                origin[axis] = plane;
                let mut dir = rng.point(1.0);
                match rng.below(3) {
                    0 => dir[axis] = 0.0,
                    1 => dir = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z][rng.below(6)],
                    _ => {}
                }
                let ray = Ray::new(origin, dir);
                check_same(&tree, &tris, &ray);
                let target = tris[rng.below(tris.len())][rng.below(3)];
                check_same(&tree, &tris, &Ray::new(origin, target - origin));
            }
        }
    }

    #[test]
    fn odd_rays_answer_as_brute_force() {
        let mut rng = Rng(3);
        let tris = scene(&mut rng, 200);
        let tree = KdTree::build(&tris);
        let o = Vec3::new(0.5, 0.25, 9.0);
        for dir in [Vec3::ZERO, Vec3::NAN, Vec3::new(0.0, 0.0, -1e-40), Vec3::new(1e-30, 1e-38, -1.0)] {
            check_same(&tree, &tris, &Ray::new(o, dir));
        }
        check_same(&tree, &tris, &Ray::new(Vec3::splat(1e30), -Vec3::ONE));
        check_same(&tree, &tris, &Ray { origin: o, dir: -Vec3::Z, t_max: -1.0 });
        check_same(&tree, &tris, &Ray { origin: Vec3::INFINITY, dir: -Vec3::Z, t_max: 1.0 });
    }

    #[test]
    fn pathological_inputs_build_bounded_trees() {
        let mut rng = Rng(5);
        let mut check = |tris: &[[Vec3; 3]], reach: f32| {
            let tree = KdTree::build(tris);
            assert_bounded(&tree, tris.len());
            for _ in 0..100 {
                let origin = rng.point(reach);
                let target = tris[rng.below(tris.len())][rng.below(3)];
                check_same(&tree, tris, &Ray::new(origin, target - origin));
            }
            tree
        };
        // Long thin overlapping triangles: every split duplicates most of them.
        let sliver = |i: usize| {
            let (y, z, k) = ((i % 55) as f32 * 0.1, (i / 55) as f32 * 0.1, (i % 7) as f32 - 3.0);
            [Vec3::new(-50.0, y, z), Vec3::new(50.0, y + k, z + 0.05), Vec3::new(0.0, y + 0.05, z - k)]
        };
        let slivers: Vec<_> = (0..3000).map(sliver).collect();
        let tree = check(&slivers, 60.0);
        assert!(tree.reference_count() > slivers.len(), "{}", tree.reference_count());
        // Large triangles among small ones: the SAH would go on splitting
        // them (to some 50 references a triangle); the budget stops it.
        let soup = scene(&mut Rng(4), 2000);
        let tree = check(&soup, 12.0);
        assert!(tree.node_count() + tree.reference_count() > 12 * soup.len(), "{tree:?}");
        let huge: Vec<_> = scene(&mut Rng(1), 2000).iter().map(|t| t.map(|p| p * 1e30)).collect();
        check(&huge, 4e30);
        let flat: Vec<_> =
            scene(&mut Rng(2), 2000).iter().map(|t| t.map(|p| p * Vec3::new(1.0, 1.0, 0.0))).collect();
        check(&flat, 8.0);
        let point = vec![[Vec3::ONE; 3]; 5000];
        assert_eq!(check(&point, 4.0).node_count(), 1);
        let extreme =
            [[Vec3::splat(-f32::MAX), Vec3::ZERO, Vec3::splat(f32::MAX)], [Vec3::ZERO, Vec3::X, Vec3::Y]];
        check(&extreme, 4.0);
    }

    #[test]
    fn a_million_triangles_build_a_bounded_tree() {
        let mut rng = Rng(9);
        let tris: Vec<_> = (0..1_000_000)
            .map(|_| {
                let c = rng.point(100.0);
                [c, c + rng.point(0.3), c + rng.point(0.3)]
            })
            .collect();
        let tree = KdTree::build(&tris);
        assert_bounded(&tree, tris.len());
        for _ in 0..10 {
            let origin = rng.point(120.0);
            check_same(&tree, &tris, &Ray::new(origin, tris[rng.below(tris.len())][0] - origin));
        }
    }
}

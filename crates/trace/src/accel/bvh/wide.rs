//! The BVH's traversal form: the binary tree collapsed into nodes of four
//! children whose boxes are tested together, one child a lane.
//!
//! **Collapse** (Embree's and pbrt's wide BVHs): a binary interior node's
//! two children are opened, the interior child of the largest surface area
//! first, until four children remain or all are leaves. A wide node's
//! children lie deeper in the binary tree than it does, so the wide tree
//! has no more levels than the binary one (≤ 63, see the parent module).
//!
//! **Traversal.** A visited node tests its four boxes at once. A lone
//! child that passes is entered at once; two or more are pushed with
//! their lower bounds, for the nearest hit sorted so that the nearest is
//! on top (for any hit in lane order); the walk pops the top and skips it
//! when a hit found since has made its bound too far. Each visit pushes at most four and
//! pops one before the next, so the stack holds at most 3·(levels − 1) + 4
//! entries: ≤ 190 < [`STACK`], and ≤ [`SHALLOW`] for trees of at most 21
//! levels (about every tree: the 2M-triangle sphere's has 15), which walk
//! with a stack of that size (it is cleared a ray).
//!
//! **The box test** is the binary one's (see the parent module), lane by
//! lane: the same rounded operations on each child's corners in the
//! triangle test's sheared space, so a box is culled only when no triangle
//! in it can be hit at a t below the best one.

use glam::{BVec4A, Vec4};

use zline_scene::sah::SahNode as Node;

use crate::accel::Counters;
use crate::ray::{gamma, Ray, Sheared};

/// The traversal stack's size (module doc: ≥ 190).
const STACK: usize = 192;
/// The stack's size for trees of at most 21 levels (module doc).
const SHALLOW: usize = 64;
/// The bit of a child reference that makes it a leaf: the leaf's first
/// entry in the index list shifted up by 2, its count − 1 in the low bits.
const LEAF: u32 = 1 << 31;
/// The index list's length is below this, for leaf references.
pub(super) const MAX_INDICES: usize = 1 << 29;

/// A node of four children, their boxes axis by axis and lane by lane.
#[derive(Clone, Copy, Debug)]
pub(super) struct Wide {
    /// The four children's (min x, max x, min y, max y, min z, max z).
    bounds: [Vec4; 6],
    /// A lane's child: a wide node's index, or a leaf ([`LEAF`]).
    child: [u32; 4],
    /// The lanes in use, one bit each.
    valid: u32,
}

/// A child waiting on the stack, with the lower bound on its hits' t.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    child: u32,
    lower: f32,
}

/// Collapses the binary tree `bin` (depth first, root at 0, not empty,
/// over fewer than [`MAX_INDICES`] triangles) into wide nodes, the root
/// first; returns them and their levels.
pub(super) fn collapse(bin: &[Node]) -> (Vec<Wide>, usize) {
    let mut wide = Vec::with_capacity(bin.len() / 2 + 1);
    let levels = if bin[0].count > 0 {
        // A lone leaf: a root with one lane.
        let mut root = Wide { bounds: [Vec4::ZERO; 6], child: [0; 4], valid: 0 };
        root.set(0, &bin[0], leaf(&bin[0]));
        wide.push(root);
        1
    } else {
        open(bin, 0, &mut wide).1
    };
    (wide, levels)
}

/// The reference to the binary leaf `node`.
fn leaf(node: &Node) -> u32 {
    debug_assert!((node.offset as usize) < MAX_INDICES && (1..=4).contains(&node.count));
    LEAF | node.offset << 2 | (u32::from(node.count) - 1)
}

/// Appends the wide node over the binary interior node `at` and its
/// subtree (recursion depth ≤ the binary tree's); returns its index and
/// its subtree's levels.
fn open(bin: &[Node], at: usize, wide: &mut Vec<Wide>) -> (u32, usize) {
    let mut kids = [at + 1, bin[at].offset as usize, 0, 0];
    let mut len = 2;
    while len < 4 {
        let area = |k: usize| bin[kids[k]].bounds.area();
        let Some(k) =
            (0..len).filter(|&k| bin[kids[k]].count == 0).max_by(|&a, &b| area(a).total_cmp(&area(b)))
        else {
            break;
        };
        let c = kids[k];
        kids.copy_within(k + 1..len, k + 2);
        kids[k] = c + 1;
        kids[k + 1] = bin[c].offset as usize;
        len += 1;
    }
    let me = wide.len();
    wide.push(Wide { bounds: [Vec4::ZERO; 6], child: [0; 4], valid: 0 });
    let mut levels = 1;
    for (lane, &kid) in kids[..len].iter().enumerate() {
        let child = if bin[kid].count > 0 {
            leaf(&bin[kid])
        } else {
            let (child, below) = open(bin, kid, wide);
            levels = levels.max(below + 1);
            child
        };
        wide[me].set(lane, &bin[kid], child);
    }
    (me as u32, levels)
}

impl Wide {
    /// Puts the binary node `node` in `lane`, its child `child`.
    fn set(&mut self, lane: usize, node: &Node, child: u32) {
        for axis in 0..3 {
            self.bounds[2 * axis][lane] = node.bounds.min[axis];
            self.bounds[2 * axis + 1][lane] = node.bounds.max[axis];
        }
        self.child[lane] = child;
        self.valid |= 1 << lane;
    }
}

/// Visits the leaves `ray` may hit in, nearest bound first when `ORDERED`
/// (for the nearest hit; any order for any hit), calling `leaf` with each
/// leaf's indices; a node whose hits all have t above `best()` is skipped.
/// Stops when `leaf` returns false.
#[inline]
pub(super) fn traverse<const ORDERED: bool>(
    nodes: &[Wide],
    levels: usize,
    indices: &[u32],
    ray: &Frame,
    count: &mut Counters,
    best: impl Fn() -> f32,
    leaf: impl FnMut(&[u32], &mut Counters) -> bool,
) -> bool {
    if nodes.is_empty() {
        return true;
    }
    // One loop per dominant axis, so that the box test reads the node's
    // coordinates at fixed places.
    match (ray.kz, levels <= 21) {
        (0, true) => walk::<0, SHALLOW, ORDERED>(nodes, indices, ray, count, best, leaf),
        (1, true) => walk::<1, SHALLOW, ORDERED>(nodes, indices, ray, count, best, leaf),
        (_, true) => walk::<2, SHALLOW, ORDERED>(nodes, indices, ray, count, best, leaf),
        (0, false) => walk::<0, STACK, ORDERED>(nodes, indices, ray, count, best, leaf),
        (1, false) => walk::<1, STACK, ORDERED>(nodes, indices, ray, count, best, leaf),
        (_, false) => walk::<2, STACK, ORDERED>(nodes, indices, ray, count, best, leaf),
    }
}

/// [`traverse`] for rays whose dominant axis is `KZ`, with a stack of `S`
/// entries (module doc), children nearest first when `ORDERED`.
#[inline(always)]
fn walk<const KZ: usize, const S: usize, const ORDERED: bool>(
    nodes: &[Wide],
    indices: &[u32],
    ray: &Frame,
    count: &mut Counters,
    best: impl Fn() -> f32,
    mut leaf: impl FnMut(&[u32], &mut Counters) -> bool,
) -> bool {
    let mut stack = [Entry::default(); S];
    let mut len = 0;
    let mut at = 0;
    let mut open = |child: u32, count: &mut Counters| {
        let first = (child & !LEAF) as usize >> 2;
        let n = (child & 3) as usize + 1;
        leaf(&indices[first..first + n], count)
    };
    loop {
        let node = &nodes[at];
        count.nodes += 1;
        let (lower, keep) = ray.test::<KZ>(node, best());
        let mut lanes = keep.bitmask() & node.valid;
        if lanes != 0 && lanes & (lanes - 1) == 0 {
            // One child: straight to it, the stack untouched.
            let child = node.child[lanes.trailing_zeros() as usize];
            if child & LEAF == 0 {
                at = child as usize;
                continue;
            }
            if !open(child, count) {
                return false;
            }
        } else {
            let lower = lower.to_array();
            let base = len;
            while lanes != 0 {
                let lane = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                let entry = Entry { child: node.child[lane], lower: lower[lane] };
                // Insertion, farthest at the bottom: the nearest ends on
                // top (any order will do when any hit will).
                let mut j = len;
                while ORDERED && j > base && stack[j - 1].lower < entry.lower {
                    stack[j] = stack[j - 1];
                    j -= 1;
                }
                stack[j] = entry; // len < S (module doc)
                len += 1;
            }
        }
        loop {
            if len == 0 {
                return true;
            }
            len -= 1;
            let entry = stack[len];
            if entry.lower > best() {
                continue;
            }
            if entry.child & LEAF == 0 {
                at = entry.child as usize;
                break;
            }
            if !open(entry.child, count) {
                return false;
            }
        }
    }
}

/// A ray's per-traversal values, splatted to four lanes: the watertight
/// test's own shear (taken from its [`Sheared`]) and the bounds that make
/// the box test exact (parent module doc).
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    kz: usize,
    /// The origin's kx, ky and kz coordinates.
    origin: [Vec4; 3],
    /// The shear's x, y and z.
    shear: [Vec4; 3],
    /// For the shear's x, y and z: 1 when it is negative, else 0 (which
    /// kz face gives the least product).
    negative: [usize; 3],
    /// Hits have t ≤ t_max·(1 + u)³; this is above that.
    t_limit: Vec4,
}

impl Frame {
    /// The frame of `ray`, whose watertight test's values are `sheared`.
    pub(super) fn new(ray: &Ray, sheared: &Sheared) -> Frame {
        let ([kx, ky, kz], shear) = sheared.frame();
        let o = ray.origin;
        Frame {
            kz,
            origin: [Vec4::splat(o[kx]), Vec4::splat(o[ky]), Vec4::splat(o[kz])],
            shear: [Vec4::splat(shear.x), Vec4::splat(shear.y), Vec4::splat(shear.z)],
            negative: [shear.x, shear.y, shear.z].map(|s| usize::from(s.is_sign_negative())),
            t_limit: Vec4::splat(ray.t_max * (1.0 + gamma(4))),
        }
    }

    /// The four children's lower bounds on the t of their hits, and the
    /// lanes whose box may hold a hit at t ≤ `best`. `KZ` is the ray's
    /// dominant axis. Comparisons with NaN never cull.
    #[inline(always)]
    fn test<const KZ: usize>(&self, node: &Wide, best: f32) -> (Vec4, BVec4A) {
        let (kz, kx, ky) = (KZ, (KZ + 1) % 3, (KZ + 2) % 3);
        let b = &node.bounds;
        let [ox, oy, oz] = self.origin;
        // The sheared coordinate's range over each box: v − o plus the
        // shear term, the latter least at the kz face its sign picks (the
        // low face for s ≥ 0: rounding is monotone, so s·(z_low − o) ≤
        // s·(z_high − o); the boxes' coordinates are finite). The face is
        // picked by where it is read, off the chain of operations.
        let span = |axis: usize| {
            let low = 2 * kz + (self.negative[axis] & 1);
            let high = 2 * kz + (self.negative[axis] & 1 ^ 1);
            let s = self.shear[axis];
            (s * (b[low] - oz), s * (b[high] - oz))
        };
        let (x_lo, x_hi) = span(0);
        let (y_lo, y_hi) = span(1);
        let (z_lo, z_hi) = span(2);
        let out = ((b[2 * kx] - ox) + x_lo).cmpgt(Vec4::ZERO)
            | ((b[2 * kx + 1] - ox) + x_hi).cmplt(Vec4::ZERO)
            | ((b[2 * ky] - oy) + y_lo).cmpgt(Vec4::ZERO)
            | ((b[2 * ky + 1] - oy) + y_hi).cmplt(Vec4::ZERO)
            // All vertices at z ≤ 0: the test's t_scaled ≤ 0, no hit.
            | z_hi.cmple(Vec4::ZERO);
        // 1 − γ(9): a box's least sheared z times this is at most any hit's t.
        let shrink = Vec4::splat(1.0 - gamma(9));
        let lower = Vec4::select(z_lo.cmpge(Vec4::splat(f32::MIN_POSITIVE)), z_lo * shrink, Vec4::ZERO);
        let near = lower.cmple(self.t_limit) & !lower.cmpgt(Vec4::splat(best)); // neither is NaN
        (lower, !out & near)
    }
}

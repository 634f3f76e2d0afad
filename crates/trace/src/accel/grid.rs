//! The uniform grid: the scene's box cut into equal cells, each listing the
//! triangles whose bounding box overlaps it; a ray steps from cell to cell
//! by the 3D-DDA (Amanatides and Woo 1987, pbrt-v2's `GridAccel`) and
//! answers exactly as [`Brute`](super::brute::Brute) does.
//!
//! **Build.** The grid's box is that of the triangles with finite corners
//! (a triangle with a non-finite corner is left out: the watertight test
//! never hits it). For N of them and extents e_k the resolution aims at
//! λN cells, λ = [`CELLS_PER_TRIANGLE`] = 4, as near cubes as the box
//! allows: n_k = ⌊e_k·s⌋ with ∏ e_k·s = λN, where an axis that would get
//! under one cell (across a flat scene, or a scene in one point) gets one
//! and s is solved again over the others; λN is capped at [`MAX_CELLS`] =
//! 2²¹. A triangle goes into each cell its box overlaps, by the cell index
//! ⌊x·n_k/e_k⌋ (clamped) of its box's corners relative to the grid's; when
//! those references number over 16·N + 2²¹, every axis is halved until
//! they do not or the grid is one cell. The cells are stored compressed:
//! per-cell offsets into one list of triangle indices, counted then
//! filled. So a grid takes at most 4·(2²¹ + 1) bytes of offsets and
//! 4·max(16·N + 2²¹, N) bytes of references, whatever the input.
//!
//! **Exactness.** Brute force answers with the watertight test's computed
//! hits. That test can accept a ray that misses the triangle by a rounding
//! error, so the ray need not pass through any cell of it, and its computed
//! t is not exactly where the ray meets the triangle, so the order of the
//! cells is not quite that of the hits. Both errors are bounded in terms of
//! D, the largest distance along an axis from the ray's origin to a corner
//! of the grid (which bounds the same for every vertex). When the test
//! hits v₀v₁v₂, its edge functions have the signs of the exact ones of its
//! computed sheared vertices p′ᵢ (an error below one ulp keeps a sign), so
//! the origin is Σ wᵢp′ᵢ with wᵢ ≥ 0, Σ wᵢ = 1. Each p′ᵢ is within
//! 2γ(4)·D of the exact (affine) shear of vᵢ, so the point q = Σ wᵢvᵢ of
//! the triangle is within 2γ(4)·D, across the ray, of the ray's point at
//! q's depth, at some t_r; and the computed t, the mean of the vertices'
//! sheared depths weighted by edge functions of one sign each off by a
//! relative rounding, is within η₀ = γ(16)·D/‖d‖∞ of t_r.
//!
//! **Traversal.** With ε = γ(64)·D and η = γ(64)·D/‖d‖∞, the ray is clipped
//! to the grid's box grown by ε and to −η ≤ t ≤ t_max·(1 + γ(8)) + η: a
//! range [t₀, t₁] that holds every hit's t_r. On each axis the cells form
//! slabs; grown by ε (the outer ones to infinity, as the cell index is
//! clamped), they overlap, and at any t the ray is in a run of them. The
//! walk takes the events where the ray enters the next slab or leaves the
//! first of its run, in the order of their computed times (an entry before
//! a departure at the same time): the 3D-DDA on cells grown by ε. At t₀,
//! and at each entry, it visits the cells whose three slabs the ray is then
//! in: the slab entered times the other two runs. So it visits, once each,
//! the cells whose three grown slabs hold the ray, by the computed times,
//! at a common t in [t₀, t₁] (rounding is monotone, so the times are
//! monotone along an axis and each run only moves on). For a hit, the
//! triangle's range of cells has on every axis a cell whose slab, grown by
//! the 2γ(4)·D above and the rounding of the box and of the faces (18u·D at
//! most), holds the ray at t_r; rounding the times moves the ray by under
//! 8u·D more: well within ε, so that cell is visited.
//! [`Accelerator::closest`] stops before an entry at t when the best t is
//! below t − η: a cell not yet visited is entered at t or later, so a
//! triangle not yet tested has t_r ≥ t and a computed t above t − η₀ > best
//! t, and cannot win even a tie. [`Accelerator::each_hit`] walks the whole
//! range and reports each triangle once (a list of those reported). Each
//! entry moves the end of one run one slab on, so a ray takes at most Σ n_k
//! entries. For a ray from inside the grid, ε is some 4·10⁻⁶ of the grid's
//! size: nearly every entry visits one cell, the plain DDA's next. A ray
//! for which D, ε, η, the clipped range or the reciprocal of a nonzero
//! direction component is not finite tests every triangle. The gap left is
//! the triangle test's underflow, as for the BVH.

use std::cell::Cell;

use glam::Vec3;

use super::{each_in, nearest_in, Accelerator, Bounds, Counters, Reported};
use crate::ray::{gamma, Hit, Ray, Sheared};

/// The cells the resolution aims at per triangle (λ).
pub const CELLS_PER_TRIANGLE: u32 = 4;
/// The most cells a grid has.
pub const MAX_CELLS: usize = 1 << 21;
/// References per triangle beyond which the build halves the resolution
/// (with [`MAX_CELLS`] more allowed).
pub const REFERENCES_PER_TRIANGLE: usize = 16;

/// A uniform grid over a triangle list (see the module doc).
#[derive(Clone, Debug, Default)]
pub struct Grid {
    lattice: Lattice,
    /// Cell c's triangles are `refs[offsets[c]..offsets[c + 1]]`.
    offsets: Vec<u32>,
    refs: Vec<u32>,
}

/// The grid's geometry: its box, resolution and cell index function.
#[derive(Clone, Copy, Debug, Default)]
struct Lattice {
    min: Vec3,
    max: Vec3,
    /// The high corner relative to the low one, `max - min` rounded.
    extent: [f32; 3],
    res: [usize; 3],
    /// The last cell's index, as a float.
    last: [f32; 3],
    /// Cell widths, for the cell faces.
    width: [f32; 3],
    /// n_k / e_k, 0 on an axis of one cell: the index function's scale.
    scale: [f32; 3],
}

impl Lattice {
    fn new(bounds: Bounds, res: [u32; 3]) -> Lattice {
        let extent = (bounds.max - bounds.min).to_array();
        let mut l = Lattice { min: bounds.min, max: bounds.max, extent, ..Lattice::default() };
        for k in 0..3 {
            let (n, e) = (res[k] as f32, extent[k]);
            let scale = n / e;
            if res[k] > 1 && e > 0.0 && scale.is_finite() {
                (l.res[k], l.last[k], l.width[k], l.scale[k]) = (res[k] as usize, n - 1.0, e / n, scale);
            } else {
                (l.res[k], l.width[k]) = (1, e);
            }
        }
        l
    }

    /// The cell of axis `k` that the coordinate `x` (relative to the low
    /// corner) lies in, clamped to the grid: monotone in `x`.
    #[inline]
    fn index(&self, k: usize, x: f32) -> usize {
        // max(NaN, 0) is 0; the truncation of a number ≥ 0 is its floor.
        (x * self.scale[k]).max(0.0).min(self.last[k]) as u32 as usize
    }

    /// The cells, per axis from first to last, that a triangle's box meets.
    fn span(&self, t: &[Vec3; 3]) -> [(usize, usize); 3] {
        let b = Bounds::of(t);
        let (lo, hi) = (b.min - self.min, b.max - self.min);
        [0, 1, 2].map(|k| (self.index(k, lo[k]), self.index(k, hi[k])))
    }
}

/// The resolution for `n` triangles in a box of `extent` (module doc);
/// its product is at most `n`·λ capped at [`MAX_CELLS`].
fn resolution(extent: Vec3, n: usize) -> [u32; 3] {
    let target = (n as f64 * f64::from(CELLS_PER_TRIANGLE)).clamp(1.0, MAX_CELLS as f64);
    let e = extent.to_array().map(|e| if e > 0.0 && e.is_finite() { f64::from(e) } else { 0.0 });
    let mut free = e.map(|e| e > 0.0);
    let s = loop {
        let m = free.iter().filter(|&&f| f).count();
        if m == 0 {
            return [1; 3];
        }
        let product: f64 = (0..3).filter(|&k| free[k]).map(|k| e[k]).product();
        let s = (target / product).powf(1.0 / m as f64);
        // The free axis of least extent: fixed at one cell when that is
        // more than it would get.
        let least = (0..3).filter(|&k| free[k]).min_by(|&a, &b| e[a].total_cmp(&e[b]));
        match least {
            Some(k) if e[k] * s < 1.0 => free[k] = false,
            _ => break s,
        }
    };
    let mut res = [0, 1, 2].map(|k| if free[k] { (e[k] * s).floor().clamp(1.0, target) as u32 } else { 1 });
    while res.iter().map(|&r| r as usize).product::<usize>() > MAX_CELLS {
        let k = (0..3).max_by_key(|&k| res[k]).unwrap_or(0);
        res[k] -= 1;
    }
    res
}

impl Grid {
    /// Builds the grid over `triangles` (empty when none has finite
    /// corners; only the first 2³² − 1 are considered).
    pub fn build(triangles: &[[Vec3; 3]]) -> Grid {
        let finite: Vec<u32> = (0..u32::MAX)
            .zip(triangles)
            .filter(|(_, t)| t.iter().all(|p| p.is_finite()))
            .map(|(i, _)| i)
            .collect();
        if finite.is_empty() {
            return Grid::default();
        }
        let tri = |i: u32| &triangles[i as usize];
        let bounds = finite.iter().fold(Bounds::EMPTY, |b, &i| b.union(Bounds::of(tri(i))));
        let n = finite.len();
        let limit = (REFERENCES_PER_TRIANGLE * n + MAX_CELLS).min(u32::MAX as usize);
        let size = |s: [(usize, usize); 3]| s.iter().map(|(lo, hi)| hi - lo + 1).product::<usize>();
        let mut res = resolution(bounds.max - bounds.min, n);
        let (lattice, total) = loop {
            let lattice = Lattice::new(bounds, res);
            // Saturating: n·MAX_CELLS may not fit a 32-bit usize.
            let total = finite.iter().fold(0usize, |sum, &i| sum.saturating_add(size(lattice.span(tri(i)))));
            if total <= limit || lattice.res == [1; 3] {
                break (lattice, total);
            }
            res = lattice.res.map(|r| (r as u32 / 2).max(1));
        };
        // Counts at each cell's end, summed to ends, then filled backwards
        // so that each end moves down to its cell's start.
        let [nx, ny, _] = lattice.res;
        let each = |f: &mut dyn FnMut(usize, u32)| {
            for &i in finite.iter().rev() {
                let [(x0, x1), (y0, y1), (z0, z1)] = lattice.span(tri(i));
                for z in z0..=z1 {
                    for y in y0..=y1 {
                        (x0..=x1).for_each(|x| f(x + nx * (y + ny * z), i));
                    }
                }
            }
        };
        let mut offsets = vec![0u32; lattice.res.iter().product::<usize>() + 1];
        each(&mut |c, _| offsets[c] += 1);
        let mut sum = 0;
        for o in &mut offsets {
            sum += *o;
            *o = sum;
        }
        let mut refs = vec![0u32; total];
        each(&mut |c, i| {
            offsets[c] -= 1;
            refs[offsets[c] as usize] = i;
        });
        Grid { lattice, offsets, refs }
    }

    /// Cells per axis (0 for the empty grid).
    pub fn resolution(&self) -> [u32; 3] {
        self.lattice.res.map(|n| if self.offsets.is_empty() { 0 } else { n as u32 })
    }

    /// The number of cells (at most [`MAX_CELLS`]).
    pub fn cell_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The number of triangle references over all cells.
    pub fn reference_count(&self) -> usize {
        self.refs.len()
    }

    /// How `ray` is to be traversed (module doc).
    fn route(&self, ray: &Ray) -> Route {
        if self.refs.is_empty() {
            return Route::Miss;
        }
        let l = &self.lattice;
        let reach = (l.min - ray.origin).abs().max((l.max - ray.origin).abs()).max_element();
        let eps = gamma(64) * reach;
        let eta = gamma(64) * (reach / ray.dir.abs().max_element());
        let (origin, dir) = ((ray.origin - l.min).to_array(), ray.dir.to_array());
        let inv_dir = dir.map(|d| 1.0 / d);
        let (mut t0, mut t1) = (-eta, ray.t_max * (1.0 + gamma(8)) + eta);
        for k in 0..3 {
            let (lo, hi) = (-eps, l.extent[k] + eps);
            if dir[k] == 0.0 {
                if origin[k] < lo || origin[k] > hi {
                    return Route::Miss;
                }
                continue;
            }
            let (a, b) = ((lo - origin[k]) * inv_dir[k], (hi - origin[k]) * inv_dir[k]);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        let steep = (0..3).all(|k| dir[k] == 0.0 || inv_dir[k].is_finite());
        if !(steep && eps.is_finite() && eta.is_finite() && t0.is_finite() && t1.is_finite()) {
            Route::Every
        } else if t0 > t1 {
            Route::Miss
        } else {
            Route::Walk(Walk { origin, dir, inv_dir, eps, eta, t0, t1 })
        }
    }

    /// Visits the cells along `w` (module doc), calling `leaf` with each
    /// cell's triangles, until `leaf` returns false (then returns false)
    /// or `stop(t)` holds before a slab entered at t.
    fn walk(
        &self,
        w: &Walk,
        count: &mut Counters,
        mut stop: impl FnMut(f32) -> bool,
        mut leaf: impl FnMut(&[u32], &mut Counters) -> bool,
    ) -> bool {
        let l = &self.lattice;
        let mut axes = [0, 1, 2].map(|k| Axis::new(l, w, k));
        let [nx, ny, _] = l.res;
        let mut visit = |[xs, ys, zs]: [std::ops::Range<usize>; 3], count: &mut Counters| {
            for z in zs {
                for y in ys.clone() {
                    for x in xs.clone() {
                        let c = x + nx * (y + ny * z);
                        count.nodes += 1;
                        let (first, end) = (self.offsets[c] as usize, self.offsets[c + 1] as usize);
                        if !leaf(&self.refs[first..end], count) {
                            return false;
                        }
                    }
                }
            }
            true
        };
        if !visit(axes.each_ref().map(Axis::cells), count) {
            return false;
        }
        loop {
            let k = (1..3).fold(0, |k, i| if axes[i].enter < axes[k].enter { i } else { k });
            let t = axes[k].enter;
            if t > w.t1 || stop(t) {
                return true;
            }
            // Slabs left before t go first; one left at t stays for now.
            for a in &mut axes {
                while a.leave < t {
                    a.lo += 1;
                    a.leave = a.time(a.lo, true);
                }
            }
            let a = &mut axes[k];
            let c = a.cell(a.end);
            a.end += 1;
            a.enter = if a.end < a.n { a.time(a.end, false) } else { f32::INFINITY };
            let mut cells = axes.each_ref().map(Axis::cells);
            cells[k] = c..c + 1;
            if !visit(cells, count) {
                return false;
            }
        }
    }
}

/// What a ray needs: nothing (it cannot meet the grid), every triangle
/// (its bounds are not finite), or the walk.
enum Route {
    Miss,
    Every,
    Walk(Walk),
}

/// A ray's walk through the grid, in coordinates relative to the grid's
/// low corner.
struct Walk {
    origin: [f32; 3],
    dir: [f32; 3],
    inv_dir: [f32; 3],
    /// How far across the ray a cell is visited (ε).
    eps: f32,
    /// How far below a hit's t_r its computed t may lie (η ≥ η₀).
    eta: f32,
    /// The range of t the walk covers.
    t0: f32,
    t1: f32,
}

/// A walk along one axis: which slabs of cells (grown by ε) the ray is
/// in, numbered in the order the ray meets them, and when it enters and
/// leaves them. The first and last slabs reach out to infinity, as the
/// cell index is clamped. On an axis the ray does not move along, its
/// slabs are those within ε of its coordinate, for ever.
struct Axis {
    origin: f32,
    inv: f32,
    width: f32,
    eps: f32,
    n: usize,
    /// Slab j is cell j (the ray runs towards +axis) or cell n − 1 − j.
    up: bool,
    /// The slabs the ray is in, lo..end.
    lo: usize,
    end: usize,
    /// When it enters slab `end` and leaves slab `lo`.
    enter: f32,
    leave: f32,
}

impl Axis {
    /// Axis `k` of walk `w`, at t0.
    fn new(l: &Lattice, w: &Walk, k: usize) -> Axis {
        let (origin, n, inf) = (w.origin[k], l.res[k], f32::INFINITY);
        let (inv, width, eps, up) = (w.inv_dir[k], l.width[k], w.eps, w.dir[k] > 0.0);
        let mut a = Axis { origin, inv, width, eps, n, up, lo: 0, end: 0, enter: inf, leave: inf };
        if w.dir[k] == 0.0 {
            (a.up, a.lo, a.end) = (true, l.index(k, origin - w.eps), l.index(k, origin + w.eps) + 1);
            return a;
        }
        // From the cell at t0: end − 1 the last slab entered by t0, lo
        // the first not left before t0 (the times are monotone in j).
        let (guess, t0) = (a.cell(l.index(k, origin + w.t0 * w.dir[k])), w.t0);
        a.end = guess + 1;
        while a.end < n && a.time(a.end, false) <= t0 {
            a.end += 1;
        }
        while a.end > 1 && a.time(a.end - 1, false) > t0 {
            a.end -= 1;
        }
        a.lo = guess.min(a.end - 1);
        while a.lo > 0 && a.time(a.lo - 1, true) >= t0 {
            a.lo -= 1;
        }
        while a.time(a.lo, true) < t0 {
            a.lo += 1;
        }
        a.enter = if a.end < n { a.time(a.end, false) } else { inf };
        a.leave = a.time(a.lo, true);
        a
    }

    /// The cell of slab `j` (and the slab of cell `j`).
    #[inline]
    fn cell(&self, j: usize) -> usize {
        [self.n - 1 - j, j][usize::from(self.up)]
    }

    /// When the ray enters (`leaving` false) or leaves slab `j`: where it
    /// meets cell c's low face less ε or its high face plus ε, the outer
    /// faces of the first and last cells at infinity. c < 2²¹: exact.
    #[inline]
    fn time(&self, j: usize, leaving: bool) -> f32 {
        let c = self.cell(j);
        let x = match (self.up != leaving, c == 0, c + 1 >= self.n) {
            (true, true, _) => f32::NEG_INFINITY,
            (true, false, _) => c as u32 as f32 * self.width - self.eps,
            (false, _, true) => f32::INFINITY,
            (false, _, false) => (c + 1) as u32 as f32 * self.width + self.eps,
        };
        (x - self.origin) * self.inv
    }

    /// The cells of the slabs the ray is in.
    #[inline]
    fn cells(&self) -> std::ops::Range<usize> {
        let (lo, end) = if self.up { (self.lo, self.end) } else { (self.n - self.end, self.n - self.lo) };
        lo..end
    }
}

impl Accelerator for Grid {
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit> {
        count.rays += 1;
        let sheared = Sheared::new(ray)?;
        let mut best: Option<Hit> = None;
        match self.route(ray) {
            Route::Miss => {}
            Route::Every => {
                nearest_in(triangles, (0..u32::MAX).take(triangles.len()), &sheared, &mut best, count)
            }
            Route::Walk(w) => {
                let best_t = Cell::new(f32::INFINITY);
                self.walk(
                    &w,
                    count,
                    |b| best_t.get() < b - w.eta,
                    |cell, count| {
                        nearest_in(triangles, cell.iter().copied(), &sheared, &mut best, count);
                        best_t.set(best.map_or(f32::INFINITY, |h| h.t));
                        true
                    },
                );
            }
        }
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
        // A triangle sits in many cells: each is reported once.
        let mut reported = Reported::default();
        let mut once = |hit: Hit| !reported.insert(hit.triangle) || visit(hit);
        match self.route(ray) {
            Route::Miss => true,
            Route::Every => each_in(triangles, 0..triangles.len() as u32, &sheared, count, &mut once),
            Route::Walk(w) => self.walk(
                &w,
                count,
                |_| false,
                |cell, count| each_in(triangles, cell.iter().copied(), &sheared, count, &mut once),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::accel::brute::Brute;
    use crate::accel::testkit::{check_each_hit_stops, check_rays, check_same, ray, scene, stacked, Rng};

    /// `tris` moved to `scale`·p + `offset`.
    fn moved(tris: &[[Vec3; 3]], scale: f32, offset: Vec3) -> Vec<[Vec3; 3]> {
        tris.iter().map(|t| t.map(|p| p * scale + offset)).collect()
    }

    /// A random ray for `tris`, moved as they were, its origin set back by
    /// up to 10⁵ (the scene is some 10 across); half the time with t_max
    /// brute force's nearest t.
    fn moved_ray(rng: &mut Rng, base: &[[Vec3; 3]], tris: &[[Vec3; 3]], scale: f32, offset: Vec3) -> Ray {
        let r = ray(rng, base);
        let back = [0.0, 0.0, 10.0, 1e3, 1e5][rng.below(5)] / r.dir.length();
        let origin = (r.origin - back * r.dir) * scale + offset;
        let mut r = Ray { origin, dir: r.dir * scale, t_max: r.t_max + back };
        if rng.below(2) == 0 {
            r.t_max = Brute.closest(tris, &r, &mut Counters::default()).map_or(r.t_max, |h| h.t);
        }
        r
    }

    /// The grid's size stays within the build's caps.
    #[track_caller]
    fn bounded(grid: &Grid, n: usize) {
        assert!(grid.cell_count() <= MAX_CELLS, "{:?}", grid.resolution());
        let refs = grid.reference_count();
        assert!(refs <= (REFERENCES_PER_TRIANGLE * n + MAX_CELLS).max(n), "{refs} references");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn random_scenes_answer_as_brute_force(seed: u64, n in 1usize..300, place in 0usize..6) {
            let mut rng = Rng(seed);
            let base = scene(&mut rng, n);
            // Also small and far from the origin, large, and huge.
            let scale = [1.0, 1.0, 1.0, 1e-3, 1e5, 1e30][place];
            let (near, far) = (Vec3::new(1e3, -2e3, 5e2), Vec3::new(3e6, 0.0, -1e6));
            let offset = [Vec3::ZERO, near, far, near, far, Vec3::ZERO][place];
            let tris = moved(&base, scale, offset);
            let grid = Grid::build(&tris);
            bounded(&grid, n);
            for _ in 0..200 {
                check_same(&grid, &tris, &moved_ray(&mut rng, &base, &tris, scale, offset));
            }
        }
    }

    /// A triangle of size about `size` in a cube of half side `spread`.
    fn small(rng: &mut Rng, spread: f32, size: f32) -> [Vec3; 3] {
        let a = rng.point(spread);
        [a, a + rng.point(size), a + rng.point(size)]
    }

    #[test]
    fn a_hundred_thousand_rays_through_a_soup_answer_as_brute_force() {
        let mut rng = Rng(0x5eed);
        let soup = scene(&mut rng, 1000);
        check_rays(&Grid::build(&soup), &soup, &mut rng, 100_000);
        let tris: Vec<_> = (0..4000).map(|_| small(&mut rng, 4.0, 0.1)).collect();
        let (mine, brute) = check_rays(&Grid::build(&tris), &tris, &mut rng, 2000);
        assert!(mine.tests * 50 < brute.tests, "{mine:?} against {brute:?}");
        assert!(mine.nodes < 100 * mine.rays, "{mine:?}");
    }

    #[test]
    fn each_hit_stops_when_told() {
        let mut tris = stacked();
        tris.push([Vec3::splat(-5.0), Vec3::splat(-5.0), Vec3::splat(5.0)]);
        let grid = Grid::build(&tris);
        assert!(grid.cell_count() > 1, "the stacked triangles lie in many cells");
        check_each_hit_stops(&grid, &tris);
    }

    #[test]
    fn an_empty_grid_hits_nothing() {
        let bad = [[Vec3::NAN, Vec3::ZERO, Vec3::X], [Vec3::INFINITY, Vec3::ZERO, Vec3::Y]];
        for tris in [&[][..], &bad[..]] {
            let grid = Grid::build(tris);
            assert_eq!((grid.resolution(), grid.cell_count(), grid.reference_count()), ([0; 3], 0, 0));
            let ray = Ray::new(Vec3::new(0.1, 0.1, 1.0), -Vec3::Z);
            let mut count = Counters::default();
            assert_eq!(grid.closest(tris, &ray, &mut count), None);
            assert!(grid.each_hit(tris, &ray, &mut count, &mut |_| false));
            assert_eq!(count, Counters { rays: 2, nodes: 0, tests: 0 });
        }
    }

    /// Unit squares on the faces of an 8 × 8 × 8 grid of unit cells, and
    /// rays along those faces and their edges, from inside and outside.
    #[test]
    fn axis_parallel_rays_along_cell_faces() {
        let mut rng = Rng(11);
        let corner = |v: [usize; 3]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
        let mut tris = vec![
            [Vec3::ZERO, Vec3::new(8.0, 0.0, 0.0), Vec3::new(0.0, 8.0, 0.0)],
            [Vec3::splat(8.0), Vec3::new(0.0, 8.0, 8.0), Vec3::new(8.0, 0.0, 8.0)],
        ];
        while tris.len() < 128 {
            let (axis, mut at) = (rng.below(3), [rng.below(8), rng.below(8), rng.below(8)]);
            at[axis] = rng.below(9);
            let p = |du, dv| corner([0, 1, 2].map(|k| at[k] + [0, du, dv][(k + 3 - axis) % 3]));
            tris.extend([[p(0, 0), p(1, 0), p(1, 1)], [p(0, 0), p(1, 1), p(0, 1)]]);
        }
        let grid = Grid::build(&tris);
        assert_eq!(grid.resolution(), [8; 3]);
        let axes = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
        for _ in 0..20_000 {
            // Lattice coordinates, some halfway, some just outside the box.
            let c = |rng: &mut Rng| {
                [-1.0, 0.0, 0.5, 3.0, 4.5, 7.0, 8.0, 9.0][rng.below(8)] + 0.5 * rng.below(2) as f32
            };
            let origin = Vec3::new(c(&mut rng), c(&mut rng), c(&mut rng));
            let dir = match rng.below(3) {
                0 => axes[rng.below(6)],
                1 => axes[rng.below(6)] + axes[rng.below(6)],
                _ => Vec3::new(c(&mut rng) - 4.0, c(&mut rng) - 4.0, 0.0),
            };
            let mut ray = Ray::new(origin, dir);
            if rng.below(3) == 0 {
                ray.t_max = rng.below(10) as f32 * 0.5;
            }
            check_same(&grid, &tris, &ray);
        }
    }

    /// A terrain-like flat scene gets one cell across, a long flat strip
    /// its cells along its length.
    #[test]
    fn flat_scenes_answer_as_brute_force() {
        let mut rng = Rng(3);
        let flat: Vec<_> = (0..2000).map(|_| small(&mut rng, 4.0, 0.3).map(|p| p.with_z(2.0))).collect();
        let grid = Grid::build(&flat);
        let [nx, ny, nz] = grid.resolution();
        assert_eq!(nz, 1);
        assert!(nx * ny > 4000 && nx * ny <= 8000, "{:?}", grid.resolution());
        bounded(&grid, flat.len());
        for _ in 0..2000 {
            check_same(&grid, &flat, &ray(&mut rng, &flat));
        }
        let line: Vec<_> =
            (0..1000).map(|i| [Vec3::X * i as f32, Vec3::X * (i + 1) as f32, Vec3::Y]).collect();
        let grid = Grid::build(&line);
        assert_eq!(grid.resolution(), [2000, 2, 1]);
        for _ in 0..2000 {
            check_same(&grid, &line, &ray(&mut rng, &line));
        }
    }

    #[test]
    fn huge_and_degenerate_scenes_keep_memory_bounded() {
        let mut rng = Rng(5);
        // All in one point: a single cell holding every triangle.
        let p = Vec3::new(1.0, 2.0, 3.0);
        let point = vec![[p; 3]; 100_000];
        let grid = Grid::build(&point);
        assert_eq!((grid.resolution(), grid.reference_count()), ([1; 3], point.len()));
        check_same(&grid, &point, &Ray::new(Vec3::ZERO, p));
        // Every triangle across the whole box: the resolution drops.
        let big: Vec<_> = (0..20_000).map(|_| [(); 3].map(|_| rng.point(1e4))).collect();
        let grid = Grid::build(&big);
        bounded(&grid, big.len());
        for _ in 0..100 {
            check_same(&grid, &big, &ray(&mut rng, &big));
        }
        // Near the end of the float range (to 2.8·10³⁸): extents and
        // distances overflow, and such rays test every triangle.
        let base = scene(&mut rng, 200);
        let tris = moved(&base, 4e37, Vec3::ZERO);
        let grid = Grid::build(&tris);
        let rays: Vec<_> = (0..500).map(|_| moved_ray(&mut rng, &base, &tris, 4e37, Vec3::ZERO)).collect();
        rays.iter().for_each(|ray| check_same(&grid, &tris, ray));
        assert!(rays.iter().any(|ray| matches!(grid.route(ray), Route::Every)));
        // A million small triangles: the cell cap.
        let many: Vec<_> = (0..1_000_000).map(|_| small(&mut rng, 4.0, 0.1)).collect();
        let grid = Grid::build(&many);
        assert!(grid.cell_count() > MAX_CELLS / 2, "{:?}", grid.resolution());
        bounded(&grid, many.len());
    }
}

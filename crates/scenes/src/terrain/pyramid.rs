//! The error pyramid of the terrain's bintree and the simplification it
//! drives: per grid point the saturated error δ and the bounding radius r,
//! and the vertices a view activates (see the parent module's
//! documentation for the bounds).

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use zline_scene::{Camera, HeightField, Projection};

/// The view-independent part of the simplification: per grid point of the
/// padded (2^n + 1)² grid, the saturated error δ and the bounding radius r
/// (see the module documentation).
#[derive(Clone, Debug)]
pub struct ErrorPyramid {
    /// Samples per side of the padded grid, 2^n + 1.
    side: usize,
    columns: usize,
    rows: usize,
    cell: f32,
    /// World offset of grid point (0, 0): the grid is centred.
    origin: Vec2,
    heights: Vec<f32>,
    delta: Vec<f32>,
    radius: Vec<f32>,
}

/// A simplified grid: the vertices it keeps (as grid points) and its
/// triangles (indices into them), counter-clockwise seen from above.
#[derive(Clone, Debug, PartialEq)]
pub struct SimplifiedGrid {
    /// (column, row) of each vertex, all inside the height field.
    pub vertices: Vec<[u32; 2]>,
    /// Triangles as indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

/// How far from the surface a simplified mesh may stray, in pixels, seen
/// from one camera (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewError {
    /// The eye, in the terrain's world frame.
    pub eye: Vec3,
    /// The unit view direction (from the eye towards the target).
    pub forward: Vec3,
    /// λ: pixels per world unit at unit depth (perspective), or per world
    /// unit anywhere (orthographic).
    pub pixels_per_unit: f32,
    /// K = 1 + tan²(fovx/2) + tan²(fovy/2): d/z² ≤ K/d inside the view
    /// frustum.
    pub frustum_factor: f32,
    /// True for an orthographic camera: errors project without depth.
    pub orthographic: bool,
    /// The bound τ in pixels (0: the full grid).
    pub tolerance: f32,
}

impl ViewError {
    /// The bound for `camera` drawing a `width × height` image.
    pub fn new(camera: &Camera, width: u32, height: u32, tolerance: f32) -> ViewError {
        let aspect = width as f32 / height as f32;
        let (scale, tan_x, tan_y, orthographic) = match camera.projection {
            Projection::Perspective { fovy_degrees, .. } => {
                let tan_y = (fovy_degrees.to_radians() / 2.0).tan();
                (height as f32 / (2.0 * tan_y), tan_y * aspect, tan_y, false)
            }
            Projection::Orthographic { height: h, .. } => (height as f32 / h, 0.0, 0.0, true),
            // The widest side's slope on each axis.
            Projection::Frustum { left, right, bottom, top, near, .. } => {
                let tan = |a: f32, b: f32| a.abs().max(b.abs()) / near;
                (height as f32 * near / (top - bottom), tan(left, right), tan(bottom, top), false)
            }
        };
        ViewError {
            eye: camera.eye,
            forward: (camera.target - camera.eye).normalize_or(Vec3::NEG_Z),
            pixels_per_unit: scale,
            frustum_factor: 1.0 + tan_x * tan_x + tan_y * tan_y,
            orthographic,
            tolerance: tolerance.max(0.0),
        }
    }

    /// True when an error `delta` anywhere in the sphere of `radius`
    /// around `p` may project to more than the tolerance: when both
    /// λ·δ·(d + r)/(z − r)² and λ·K·δ/(d − r) exceed τ, with d the
    /// distance from the eye to `p` and z its depth (a bound whose
    /// denominator is not positive is infinite).
    #[inline]
    fn exceeds(&self, p: Vec3, delta: f32, radius: f32) -> bool {
        if delta <= 0.0 {
            return false;
        }
        if self.tolerance == 0.0 || !delta.is_finite() {
            return true;
        }
        if self.orthographic {
            return self.pixels_per_unit * delta > self.tolerance;
        }
        let to = p - self.eye;
        let (z, d) = (to.dot(self.forward) - radius, to.length());
        let near = d - radius;
        let lambda = self.pixels_per_unit * delta;
        (z <= 0.0 || lambda * (d + radius) > self.tolerance * z * z)
            && (near <= 0.0 || lambda * self.frustum_factor > self.tolerance * near)
    }
}

impl ErrorPyramid {
    /// The errors and radii of every grid point of `field`, bottom-up.
    pub fn new(field: &HeightField) -> ErrorPyramid {
        let (columns, rows) = (field.columns(), field.rows());
        let side = (columns.max(rows) - 1).next_power_of_two() + 1;
        let cell = field.cell_size();
        let origin = -Vec2::new((columns - 1) as f32, (rows - 1) as f32) * cell / 2.0;
        let mut heights = vec![0.0; side * side];
        heights.par_chunks_mut(side).enumerate().for_each(|(y, row)| {
            let source = &field.heights()[y.min(rows - 1) * columns..][..columns];
            row[..columns].copy_from_slice(source);
            row[columns..].fill(source[columns - 1]);
        });
        let mut pyramid = ErrorPyramid {
            side,
            columns,
            rows,
            cell,
            origin,
            heights,
            delta: vec![0.0; side * side],
            radius: vec![0.0; side * side],
        };
        pyramid.build();
        pyramid
    }

    /// Samples per side of the padded grid.
    pub fn side(&self) -> usize {
        self.side
    }

    /// The saturated vertical error δ of grid point (x, y).
    pub fn delta(&self, x: usize, y: usize) -> f32 {
        self.delta[y * self.side + x]
    }

    /// The world position of grid point (x, y) (heights clamped to the
    /// field outside it).
    #[inline]
    pub fn position(&self, x: usize, y: usize) -> Vec3 {
        let h = self.heights[y * self.side + x];
        Vec3::new(self.origin.x + x as f32 * self.cell, h, self.origin.y + y as f32 * self.cell)
    }

    fn build(&mut self) {
        let n = self.side - 1;
        let mut h = 1;
        while h < n {
            // The diamonds of half-size h: one coordinate an odd multiple
            // of h, the other an even one.
            let rows: Vec<usize> = (0..=n).step_by(h).collect();
            self.level(
                &rows,
                |y| (if (y / h).is_multiple_of(2) { h } else { 0 }, 2 * h),
                |x, y| {
                    let (a, b) =
                        if (x / h) % 2 == 1 { ((x - h, y), (x + h, y)) } else { ((x, y - h), (x, y + h)) };
                    let half = (h / 2) as isize;
                    let children = [(-1, -1), (1, -1), (-1, 1), (1, 1)]
                        .map(|(dx, dy)| offset(x, y, dx * half, dy * half, n));
                    (a, b, if h == 1 { [None; 4] } else { children })
                },
                h,
            );
            // The squares of half-size h: both coordinates odd multiples.
            let rows: Vec<usize> = (h..n).step_by(2 * h).collect();
            self.level(
                &rows,
                |_| (h, 2 * h),
                |x, y| {
                    let (i, j) = ((x - h) / (2 * h), (y - h) / (2 * h));
                    let (a, b) = if (i + j).is_multiple_of(2) {
                        ((x - h, y - h), (x + h, y + h))
                    } else {
                        ((x - h, y + h), (x + h, y - h))
                    };
                    let s = h as isize;
                    (a, b, [(-s, 0), (s, 0), (0, -s), (0, s)].map(|(dx, dy)| offset(x, y, dx, dy, n)))
                },
                h,
            );
            h *= 2;
        }
    }

    /// Settles one level: on each of `rows` (in parallel), the vertices
    /// from `first(y).0` in steps of `first(y).1`, each with its hypotenuse
    /// and children from `shape`, written in place. A level's children lie
    /// in rows it does not write, or in the vertex's own row (a square's
    /// left and right children, settled on the level before).
    fn level(
        &mut self,
        rows: &[usize],
        first: impl Fn(usize) -> (usize, usize) + Sync,
        shape: impl Fn(usize, usize) -> ((usize, usize), (usize, usize), [Option<(usize, usize)>; 4]) + Sync,
        h: usize,
    ) {
        let (side, n) = (self.side, self.side - 1);
        let geometry = Geometry {
            side,
            columns: self.columns,
            rows: self.rows,
            cell: self.cell,
            origin: self.origin,
            heights: &self.heights,
        };
        let mut written = vec![false; side];
        rows.iter().for_each(|&y| written[y] = true);
        let mut writes = Vec::with_capacity(rows.len());
        let mut reads: Vec<Option<(&[f32], &[f32])>> = vec![None; side];
        for (y, (d, r)) in self.delta.chunks_mut(side).zip(self.radius.chunks_mut(side)).enumerate() {
            if written[y] {
                writes.push((y, d, r));
            } else {
                reads[y] = Some((&*d, &*r));
            }
        }
        writes.par_iter_mut().for_each(|(y, deltas, radii)| {
            let y = *y;
            let (x0, step) = first(y);
            for x in (x0..=n).step_by(step) {
                let (a, b, children) = shape(x, y);
                let value = |(cx, cy): (usize, usize)| {
                    if cy == y {
                        (deltas[cx], radii[cx])
                    } else {
                        let (d, r) = reads[cy].expect("a level's children lie in rows it does not write");
                        (d[cx], r[cx])
                    }
                };
                let (delta, radius) = geometry.settle(x, y, h, a, b, &children, value);
                deltas[x] = delta;
                radii[x] = radius;
            }
        });
    }
}

/// The padded grid's geometry, read while its values are written.
struct Geometry<'a> {
    side: usize,
    columns: usize,
    rows: usize,
    cell: f32,
    origin: Vec2,
    heights: &'a [f32],
}

impl Geometry<'_> {
    #[inline]
    fn position(&self, x: usize, y: usize) -> Vec3 {
        let h = self.heights[y * self.side + x];
        Vec3::new(self.origin.x + x as f32 * self.cell, h, self.origin.y + y as f32 * self.cell)
    }

    /// δ and r of vertex (x, y) of half-size h, hypotenuse a–b, from its
    /// children's (δ, r) by `value`.
    #[expect(clippy::too_many_arguments, reason = "a vertex, its level, hypotenuse and children")]
    fn settle(
        &self,
        x: usize,
        y: usize,
        h: usize,
        a: (usize, usize),
        b: (usize, usize),
        children: &[Option<(usize, usize)>; 4],
        value: impl Fn((usize, usize)) -> (f32, f32),
    ) -> (f32, f32) {
        let side = self.side;
        let at = |(x, y): (usize, usize)| y * side + x;
        let p = self.position(x, y);
        let mut delta = 0.0f32;
        let mut radius = 0.0f32;
        for &c in children.iter().flatten() {
            let (d, r) = value(c);
            delta = delta.max(d);
            radius = radius.max(r + p.distance(self.position(c.0, c.1)));
        }
        if h == 1 {
            // The finest diamonds have no children: their corners.
            for (dx, dy) in [(-1, 0), (1, 0), (0, -1), (0, 1)] {
                if let Some(c) = offset(x, y, dx, dy, side - 1) {
                    radius = radius.max(p.distance(self.position(c.0, c.1)));
                }
            }
        }
        // The bounding boxes of the diamond's two triangles.
        let (x, y, s) = (x as isize, y as isize, h as isize);
        let boxes = if a.1 == b.1 {
            [[x - s, x + s, y - s, y], [x - s, x + s, y, y + s]]
        } else if a.0 == b.0 {
            [[x - s, x, y - s, y + s], [x, x + s, y - s, y + s]]
        } else {
            [[x - s, x + s, y - s, y + s]; 2]
        };
        let (w, r) = ((self.columns - 1) as isize, (self.rows - 1) as isize);
        let overlaps = |[x0, _, y0, _]: [isize; 4]| x0 < w && y0 < r;
        let straddles = |[x0, x1, y0, y1]: [isize; 4]| overlaps([x0, x1, y0, y1]) && (x1 > w || y1 > r);
        let e = if boxes.iter().any(|&b| straddles(b)) {
            f32::INFINITY
        } else if !boxes.iter().any(|&b| overlaps(b)) {
            0.0
        } else {
            let mid = (self.heights[at(a)] + self.heights[at(b)]) / 2.0;
            (self.heights[at(((x as usize), (y as usize)))] - mid).abs()
        };
        (delta + e, radius)
    }
}

impl ErrorPyramid {
    /// The simplified grid for `view` (see the module documentation).
    /// The bintree's top levels are walked here; below them the subtrees
    /// are refined in parallel and joined in order, so the result does not
    /// depend on the thread count.
    pub fn simplify(&self, view: &ViewError) -> SimplifiedGrid {
        let n = self.side - 1;
        let active = |x: usize, y: usize| {
            let i = y * self.side + x;
            view.exceeds(self.position(x, y), self.delta[i], self.radius[i])
        };
        let roots = [[(0, n), (n, n), (0, 0)], [(n, 0), (0, 0), (n, n)]];
        let mut subtrees = Vec::new();
        for root in roots {
            self.walk(root, &active, &mut |t| subtrees.push(t), 10);
        }
        let parts: Vec<Vec<[u32; 3]>> = subtrees
            .par_iter()
            .map(|&t| {
                let mut out = Vec::new();
                self.walk(t, &active, &mut |leaf| self.emit(leaf, &mut out), usize::MAX);
                out
            })
            .collect();
        self.compact(&parts)
    }

    /// Walks the bintree below triangle `[apex, left, right]`, splitting
    /// where the midpoint vertex is active, down to `depth` levels; hands
    /// each triangle reached unsplit (or at that depth) to `visit`.
    fn walk(
        &self,
        [apex, left, right]: Tri,
        active: &impl Fn(usize, usize) -> bool,
        visit: &mut impl FnMut(Tri),
        depth: usize,
    ) {
        let mid = ((left.0 + right.0) / 2, (left.1 + right.1) / 2);
        let splits = left.0.abs_diff(right.0).max(left.1.abs_diff(right.1)) > 1;
        if depth == 0 || !(splits && active(mid.0, mid.1)) {
            visit([apex, left, right]);
            return;
        }
        self.walk([mid, apex, left], active, visit, depth - 1);
        self.walk([mid, right, apex], active, visit, depth - 1);
    }

    /// Keeps a leaf triangle inside the field (padding's are dropped) as
    /// padded-grid indices.
    fn emit(&self, [apex, left, right]: Tri, out: &mut Vec<[u32; 3]>) {
        let (w, r) = ((self.columns - 1) * 3, (self.rows - 1) * 3);
        if apex.0 + left.0 + right.0 <= w && apex.1 + left.1 + right.1 <= r {
            out.push([apex, left, right].map(|(x, y)| (y * self.side + x) as u32));
        }
    }

    /// The triangles of every part, in order, over their vertices in grid
    /// order: every corner's key (padded-grid index, then the corner's
    /// place) sorted once, numbered in one pass (no array over the whole
    /// grid).
    fn compact(&self, parts: &[Vec<[u32; 3]>]) -> SimplifiedGrid {
        let mut keys: Vec<u64> = Vec::with_capacity(3 * parts.iter().map(Vec::len).sum::<usize>());
        for &i in parts.iter().flatten().flatten() {
            keys.push(u64::from(i) << 32 | keys.len() as u64);
        }
        keys.par_sort_unstable();
        let mut corners = vec![0u32; keys.len()];
        let mut vertices: Vec<[u32; 2]> = Vec::new();
        let side = self.side as u64;
        let mut last = u64::MAX;
        for key in keys {
            let i = key >> 32;
            if i != last {
                vertices.push([(i % side) as u32, (i / side) as u32]);
                last = i;
            }
            corners[(key & 0xFFFF_FFFF) as usize] = (vertices.len() - 1) as u32;
        }
        let triangles = corners.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        SimplifiedGrid { vertices, triangles }
    }
}

/// A bintree triangle: apex, then the hypotenuse's ends, as grid points.
type Tri = [(usize, usize); 3];

/// (x + dx, y + dy) when inside [0, n]².
fn offset(x: usize, y: usize, dx: isize, dy: isize, n: usize) -> Option<(usize, usize)> {
    let (x, y) = (x.checked_add_signed(dx)?, y.checked_add_signed(dy)?);
    (x <= n && y <= n).then_some((x, y))
}

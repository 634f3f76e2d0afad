//! Terrain: a [`HeightField`] made into a lit, fogged landscape scene, its
//! grid simplified to the triangles the view needs.
//!
//! **Simplification** is the right-triangle bintree (longest-edge
//! bisection) over the grid padded to (2^n + 1)² samples, with the
//! restricted-quadtree rule of Lindström and Pascucci: every grid point
//! but the four corners is the midpoint of the hypotenuse of one or two
//! bintree triangles (its *diamond*), and a triangle is split exactly when
//! its midpoint vertex is *active*. Activity is monotone (a vertex active ⇒
//! the vertices it depends on are active), so the mesh has no cracks and
//! no T-junctions. Per vertex v, bottom-up ([`ErrorPyramid::new`]):
//! - `δ(v) = e(v) + max δ(c)` over v's children c (the midpoints of its
//!   diamond's legs), with e(v) the vertical distance from the height at v
//!   to the midpoint of its hypotenuse. δ(v) bounds the vertical distance
//!   between the full grid's surface and either unsplit triangle of v's
//!   diamond (the surface deviates from a child's plane by at most δ(c),
//!   and a child's plane from the parent's by e(v), at the midpoint);
//! - `r(v) = max (r(c) + |p(v) − p(c)|)` (for the finest diamonds, which
//!   have no children, the largest distance to their corners): a sphere
//!   around p(v) holding the whole diamond.
//!
//! A vertex is active when its error may project to more than τ pixels
//! (`--terrain-error`) from the fitted camera: when both
//! `λ·δ(v)·(d + r(v)) / (z − r(v))²` and `λ·K·δ(v) / (d − r(v))` exceed τ,
//! with d = |eye − p(v)|, z the depth of p(v) along the view direction,
//! λ = H / (2·tan(fovy/2)) pixels per unit at unit depth (H the image
//! height) and K = 1 + tan²(fovx/2) + tan²(fovy/2) (a bound whose
//! denominator is not positive counts as infinite; an orthographic camera:
//! λ·δ > τ). A segment of length δ at distance d and depth z projects to
//! at most λ·δ·d/z² pixels (the largest singular value of the perspective
//! map's Jacobian is d/z²), which inside the view frustum is at most
//! λ·K·δ/d; every point of the diamond lies within r(v) of p(v). So an
//! inactive vertex's triangles stay within τ pixels of the full surface at
//! every grid sample in view (the fitted camera has the whole terrain in
//! view). Both bounds grow from child to parent (a parent's sphere holds
//! its children's and its δ is at least theirs), so activity is monotone.
//! A vertex with δ = 0 (a planar region) is never active, whatever τ;
//! τ = 0 activates every other vertex (the full grid).
//!
//! **Padding**: a grid that is not (2^n + 1)² is embedded in the next one
//! (heights clamped to the border); a vertex one of whose diamond's
//! triangles crosses the grid's border (by its bounding box) gets δ = ∞,
//! so bintree triangles are split until each lies inside or outside the
//! grid, and the outside ones are dropped; a vertex whose diamond lies
//! wholly outside has e = 0.
//!
//! **The mesh** ([`terrain_mesh`]): positions x = column·cell (east), z =
//! row·cell (south), y = height, centred on the grid; vertex normals from
//! the height field's central differences ([`HeightField::normal`]), not
//! from the simplified triangles; a height colour ramp as vertex colours,
//! or texture coordinates spanning the grid for a draped texture (s east,
//! t north: the image's top row lies on the north edge).
//!
//! **The scene** ([`terrain_scene`]): a camera fitted to the terrain
//! ([`fit_camera`]: every sample in view), a sun from the west and a sky
//! fill light, and fog when asked (linear, in the sky's colour, from the
//! depth of the bounding box's nearest corner to as far again beyond its
//! farthest corner as the box is deep: half fog at the far edge).

use std::sync::Arc;

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use zline_scene::{
    Camera, Fog, FogCoordinate, FogMode, HeightField, Light, Material, Mesh, MeshError, Object, Projection,
    RenderSettings, Scene, Shadows, TextureMap,
};

/// The vertical field of view of the fitted camera, in degrees.
pub const TERRAIN_FOVY_DEGREES: f32 = 40.0;
/// The default screen-space error bound, in pixels.
pub const DEFAULT_TERRAIN_ERROR: f32 = 1.0;
/// The sky: background and fog colour.
pub const SKY: Vec3 = Vec3::new(0.66, 0.76, 0.88);

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
        let (scale, tan_y, orthographic) = match camera.projection {
            Projection::Perspective { fovy_degrees, .. } => {
                let tan_y = (fovy_degrees.to_radians() / 2.0).tan();
                (height as f32 / (2.0 * tan_y), tan_y, false)
            }
            Projection::Orthographic { height: h, .. } => (height as f32 / h, 0.0, true),
        };
        let tan_x = tan_y * width as f32 / height as f32;
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

/// The number of triangles of the full grid: 2·(columns − 1)·(rows − 1).
pub fn full_grid_triangles(field: &HeightField) -> usize {
    2 * (field.columns() - 1) * (field.rows() - 1)
}

/// How the terrain is coloured.
#[derive(Clone, Debug, PartialEq)]
pub enum Surface {
    /// A colour ramp over the height range (vertex colours): green lowland,
    /// brown slopes, grey rock, snow on the highest tenth.
    HeightRamp,
    /// A texture draped over the whole grid.
    Texture(TextureMap),
}

/// The height ramp's colour at t ∈ [0, 1] (lowest to highest).
pub fn ramp_color(t: f32) -> Vec3 {
    const STOPS: [(f32, Vec3); 6] = [
        (0.0, Vec3::new(0.18, 0.38, 0.20)),
        (0.3, Vec3::new(0.40, 0.58, 0.28)),
        (0.55, Vec3::new(0.60, 0.52, 0.34)),
        (0.75, Vec3::new(0.50, 0.47, 0.44)),
        (0.88, Vec3::new(0.62, 0.62, 0.62)),
        (0.92, Vec3::new(0.95, 0.95, 0.97)),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let upper = STOPS.iter().position(|(s, _)| *s >= t).unwrap_or(STOPS.len() - 1);
    if upper == 0 {
        return STOPS[0].1;
    }
    let ((s0, c0), (s1, c1)) = (STOPS[upper - 1], STOPS[upper]);
    c0.lerp(c1, (t - s0) / (s1 - s0))
}

/// The mesh of a simplified grid of `field` (see the module documentation).
/// Errors when a position is not finite in f32 (a cell size or heights
/// near f32's limits).
pub fn terrain_mesh(
    field: &HeightField,
    grid: &SimplifiedGrid,
    surface: &Surface,
) -> Result<Mesh, MeshError> {
    let cell = field.cell_size();
    let (c, r) = (field.columns(), field.rows());
    let origin = -Vec2::new((c - 1) as f32, (r - 1) as f32) * cell / 2.0;
    let position = |&[x, y]: &[u32; 2]| {
        let (x, y) = (x as usize, y as usize);
        Vec3::new(origin.x + x as f32 * cell, field.at(x, y), origin.y + y as f32 * cell)
    };
    let positions: Vec<Vec3> = grid.vertices.par_iter().map(position).collect();
    let normals = grid.vertices.par_iter().map(|&[x, y]| field.normal(x as usize, y as usize)).collect();
    let white = Material { ks: Vec3::splat(0.04), ns: 12.0, ..Material::plastic(Vec3::ONE, 0.04, 12.0) };
    let mesh = Mesh::new("terrain", positions, Some(normals), grid.triangles.clone(), white)?;
    match surface {
        Surface::HeightRamp => {
            let (lo, hi) = field.range();
            let span = if hi > lo { hi - lo } else { 1.0 };
            let colors = grid
                .vertices
                .par_iter()
                .map(|&[x, y]| ramp_color((field.at(x as usize, y as usize) - lo) / span))
                .collect();
            mesh.with_colors(colors)
        }
        Surface::Texture(map) => {
            let uvs = grid
                .vertices
                .par_iter()
                .map(|&[x, y]| Vec2::new(x as f32 / (c - 1) as f32, 1.0 - y as f32 / (r - 1) as f32))
                .collect();
            Ok(mesh.with_uvs(uvs)?.with_diffuse_map(map.clone()))
        }
    }
}

/// The terrain's bounding box (min, max) in its world frame.
pub fn terrain_bounds(field: &HeightField) -> (Vec3, Vec3) {
    let (lo, hi) = field.range();
    let half = Vec2::new((field.columns() - 1) as f32, (field.rows() - 1) as f32) * field.cell_size() / 2.0;
    (Vec3::new(-half.x, lo, -half.y), Vec3::new(half.x, hi, half.y))
}

/// Points whose convex hull holds every sample of the terrain: the eight
/// corners of the box of each of about 32 × 32 blocks of the grid (the
/// block's extent, its lowest and highest sample).
fn hull_points(field: &HeightField) -> Vec<Vec3> {
    let (c, r) = (field.columns(), field.rows());
    let block = (c.max(r) - 1).div_ceil(32).max(1);
    let cell = field.cell_size();
    let origin = -Vec2::new((c - 1) as f32, (r - 1) as f32) * cell / 2.0;
    let starts = |n: usize| (0..n - 1).step_by(block).map(move |s| (s, (s + block).min(n - 1)));
    let block_rows: Vec<(usize, usize)> = starts(r).collect();
    block_rows
        .par_iter()
        .flat_map_iter(|&(y0, y1)| {
            starts(c).flat_map(move |(x0, x1)| {
                let (lo, hi) = (y0..=y1).fold((f32::INFINITY, f32::NEG_INFINITY), |acc, y| {
                    field.heights()[y * c + x0..=y * c + x1]
                        .iter()
                        .fold(acc, |(l, h), &v| (l.min(v), h.max(v)))
                });
                (0..8).map(move |i| {
                    let (x, y) = ([x0, x1][i & 1], [y0, y1][i >> 2]);
                    let h = [lo, hi][i >> 1 & 1];
                    Vec3::new(origin.x + x as f32 * cell, h, origin.y + y as f32 * cell)
                })
            })
        })
        .collect()
}

/// A perspective camera (fovy [`TERRAIN_FOVY_DEGREES`]) looking at the
/// terrain from the south-south-east, 35° above the horizon, at the least
/// distance that keeps every sample within 95 % of the view for this
/// aspect ratio, centred on the terrain's extent in the image; near and far
/// planes at 0.9 and 1.1 times the least and greatest depth of the terrain.
pub fn fit_camera(field: &HeightField, aspect: f32) -> Camera {
    let (lo, hi) = terrain_bounds(field);
    let centre = (lo + hi) / 2.0;
    let (azimuth, elevation) = (25f32.to_radians(), 35f32.to_radians());
    let back = Vec3::new(azimuth.sin() * elevation.cos(), elevation.sin(), azimuth.cos() * elevation.cos());
    let right = Vec3::Y.cross(back).normalize();
    let up = back.cross(right);
    let tan_y = (TERRAIN_FOVY_DEGREES.to_radians() / 2.0).tan() * 0.95;
    let tan_x = tan_y * aspect;
    // Camera coordinates of the hull points around the centre: right, up,
    // and towards the eye. With the eye at centre + right·sx + up·sy +
    // back·d, a point is in view when |a − sx| ≤ tan_x·(d − c) and
    // |b − sy| ≤ tan_y·(d − c).
    let points: Vec<(f32, f32, f32)> = hull_points(field)
        .iter()
        .map(|p| {
            let p = *p - centre;
            (p.dot(right), p.dot(up), p.dot(back))
        })
        .collect();
    // The interval of sx (or sy) that keeps every point in view at d.
    let window = |d: f32, side: fn(&(f32, f32, f32)) -> f32, tan: f32| {
        points.iter().fold((f32::NEG_INFINITY, f32::INFINITY), |(lo, hi), p| {
            let reach = tan * (d - p.2);
            (lo.max(side(p) - reach), hi.min(side(p) + reach))
        })
    };
    let fits = |d: f32| {
        let (x, y) = (window(d, |p| p.0, tan_x), window(d, |p| p.1, tan_y));
        x.0 <= x.1 && y.0 <= y.1 && points.iter().all(|p| d > p.2)
    };
    let mut far_enough =
        points.iter().map(|p| p.2 + p.0.abs() / tan_x + p.1.abs() / tan_y).fold(f32::MIN_POSITIVE, f32::max);
    let mut too_near = points.iter().map(|p| p.2).fold(0.0f32, f32::max);
    for _ in 0..48 {
        let mid = (far_enough + too_near) / 2.0;
        if fits(mid) {
            far_enough = mid;
        } else {
            too_near = mid;
        }
    }
    let d = far_enough;
    let (x, y) = (window(d, |p| p.0, tan_x), window(d, |p| p.1, tan_y));
    let target = centre + right * ((x.0 + x.1) / 2.0) + up * ((y.0 + y.1) / 2.0);
    let (near, far) =
        points.iter().fold((f32::INFINITY, 0.0f32), |(n, f), p| (n.min(d - p.2), f.max(d - p.2)));
    let near = (near * 0.9).max(d * 1e-4);
    Camera {
        eye: target + back * d,
        target,
        up: Vec3::Y,
        projection: Projection::Perspective { fovy_degrees: TERRAIN_FOVY_DEGREES, near, far: far * 1.1 },
    }
}

/// What [`terrain_scene`] drew.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TerrainStats {
    /// Triangles of the simplified mesh.
    pub triangles: usize,
    /// Triangles of the full grid, 2·(columns − 1)·(rows − 1).
    pub full_grid_triangles: usize,
}

/// A terrain scene of `width × height` pixels: the field simplified to
/// `error_pixels` from the fitted camera, coloured by `surface`, lit by a
/// sun and a fill light, with fog when `fog` is set (see the module
/// documentation). The pyramid is `ErrorPyramid::new(field)`, passed in
/// so that a caller can time it or reuse it. Errors as [`terrain_mesh`].
pub fn terrain_scene(
    field: &HeightField,
    pyramid: &ErrorPyramid,
    surface: &Surface,
    (width, height): (u32, u32),
    error_pixels: f32,
    fog: bool,
) -> Result<(Scene, TerrainStats), MeshError> {
    let camera = fit_camera(field, width as f32 / height as f32);
    let grid = pyramid.simplify(&ViewError::new(&camera, width, height, error_pixels));
    let mesh = terrain_mesh(field, &grid, surface)?;
    let stats =
        TerrainStats { triangles: grid.triangles.len(), full_grid_triangles: full_grid_triangles(field) };
    let (lo, hi) = terrain_bounds(field);
    let fog = fog.then(|| {
        let forward = (camera.target - camera.eye).normalize();
        let depths = (0..8).map(|i| {
            let p = Vec3::new([lo.x, hi.x][i & 1], [lo.y, hi.y][i >> 1 & 1], [lo.z, hi.z][i >> 2]);
            (p - camera.eye).dot(forward)
        });
        let (near, far) = depths.fold((f32::INFINITY, 0.0f32), |(n, f), d| (n.min(d), f.max(d)));
        let near = near.max(0.0);
        Fog {
            mode: FogMode::Linear { start: near, end: far + (far - near) },
            color: SKY,
            coordinate: FogCoordinate::EyePlane,
        }
    });
    let scene = Scene {
        camera,
        background: SKY,
        ambient: Vec3::new(0.34, 0.36, 0.40),
        lights: vec![
            // The sun from the west, a little south, across the view:
            // slopes facing it light up, the others fall into shade.
            Light::Directional { direction: Vec3::new(0.8, -0.6, -0.15), color: Vec3::new(1.0, 0.94, 0.82) },
            // Sky light from the other side.
            Light::Directional { direction: Vec3::new(-0.5, -0.6, -0.4), color: Vec3::new(0.16, 0.18, 0.22) },
        ],
        objects: vec![Object {
            mesh: Arc::new(mesh),
            world_from_object: glam::Mat4::IDENTITY,
            material: None,
            shading: None,
            cull_back_faces: false,
        }],
        settings: RenderSettings { width, height, ..RenderSettings::default() },
        fog,
        shadows: Shadows::default(),
    };
    Ok((scene, stats))
}

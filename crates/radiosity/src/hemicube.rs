//! Form factors by the hemicube (Cohen and Greenberg 1985): the scene drawn
//! from a patch's centre onto the five faces of a half cube around its
//! normal, with zline's scan converter (`zline-raster`: fixed-point edge
//! tables, the top-left rule, samples at pixel centres) and a z-buffer
//! whose "colour" is the patch index. A pixel at (u, v) of the top face
//! (z = 1, u, v ∈ [−1, 1]) holds the delta form factor
//! ΔA / (π (u² + v² + 1)²); of a side face (u ∈ [−1, 1], height v ∈
//! [0, 1]) v·ΔA / (π (u² + v² + 1)²), ΔA = (2 / res)². The deltas are
//! scaled to sum to exactly 1 over the hemicube, so a closed room's rows
//! sum to 1 (the furnace test); F_ij is the sum over the pixels patch j
//! covers.
//!
//! A patch seen from behind hides what lies beyond it and receives
//! nothing. Depth is 1/distance along the face's axis (linear in screen space),
//! nearest kept; triangles are clipped in the face's frame against a near
//! plane and the face's four sides before they are projected, so every
//! projected point lies within the face.

use glam::Vec3;
use zline_raster::{DepthPlane, EdgeTable, FixedPoint, PlaneBasis, Rect};

use crate::patch::Patch;

/// No patch seen.
const NONE: u32 = u32::MAX;
/// A patch seen from behind: it hides what lies beyond and receives
/// nothing (its back is not a surface).
const BACK: u32 = u32::MAX - 1;

/// The faces as (a, b, f) = (right, up, forward) of the hemicube frame's
/// (x, y, z) (x, y along the patch, z its normal): the top, then the
/// sides towards +x, −x, +y and −y (z up).
const FACES: [fn([f32; 3]) -> [f32; 3]; 5] = [
    |[x, y, z]| [x, y, z],
    |[x, y, z]| [y, z, x],
    |[x, y, z]| [-y, z, -x],
    |[x, y, z]| [-x, z, y],
    |[x, y, z]| [x, z, -y],
];

/// A hemicube of a given resolution: its delta form factors.
#[derive(Clone, Debug)]
pub struct Hemicube {
    res: usize,
    /// Delta form factors of every pixel: the top face's res × res, then
    /// the four sides' res × res/2 each.
    weights: Vec<f32>,
    /// Per thread: ids and depths of every pixel, laid out as `weights`.
    buffers: Vec<(Vec<u32>, Vec<f64>)>,
}

impl Hemicube {
    /// A hemicube of `res` × `res` pixels on the top face (even, ≥ 2).
    pub fn new(res: usize) -> Hemicube {
        let res = res.max(2) & !1;
        let dff = |u: f64, v: f64, side: bool| {
            let d = u * u + v * v + 1.0;
            let da = (2.0 / res as f64).powi(2);
            if side {
                v * da / (std::f64::consts::PI * d * d)
            } else {
                da / (std::f64::consts::PI * d * d)
            }
        };
        let centre = |i: usize| -1.0 + (i as f64 + 0.5) * 2.0 / res as f64;
        let mut weights: Vec<f64> =
            (0..res * res).map(|p| dff(centre(p % res), centre(p / res), false)).collect();
        // Side rows from the top (v near 1) down to the base (v near 0).
        for _ in 0..4 {
            weights.extend((0..res * res / 2).map(|p| {
                let v = 1.0 - ((p / res) as f64 + 0.5) * 2.0 / res as f64;
                dff(centre(p % res), v, true)
            }));
        }
        let sum: f64 = weights.iter().sum();
        Hemicube { res, weights: weights.iter().map(|&f| (f / sum) as f32).collect(), buffers: Vec::new() }
    }

    /// The top face's resolution.
    pub fn resolution(&self) -> usize {
        self.res
    }

    /// Adds to `row[j]` the form factor from patch `from`'s centre to
    /// every patch j it sees (`row` as long as `patches`); patch `from`
    /// itself and everything behind its plane are not seen.
    pub fn gather(&mut self, patches: &[Patch], from: usize, row: &mut [f32]) {
        self.gather_at(patches, from, patches[from].centre, 1.0, row);
    }

    /// [`Self::gather`] averaged over the patch: hemicubes at the centres
    /// of its four midpoint-subdivided quarters, each weighted ¼. Closer
    /// to the area-to-area form factor (and to reciprocity) where patches
    /// meet at an edge.
    pub fn gather_area(&mut self, patches: &[Patch], from: usize, row: &mut [f32]) {
        let [a, b, c] = patches[from].corners;
        let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
        for quarter in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            let eye = (quarter[0] + quarter[1] + quarter[2]) / 3.0;
            self.gather_at(patches, from, eye, 0.25, row);
        }
    }

    /// Adds `weight` times the form factors from the point `eye` on patch
    /// `from`. The patches are drawn in as many contiguous runs as rayon
    /// has threads, each into buffers of its own, and the runs' buffers
    /// merged pixel by pixel, the nearest kept and at equal depth the
    /// lower index: what one z-buffer drawing them in order keeps, so the
    /// row is the same for any thread count.
    fn gather_at(&mut self, patches: &[Patch], from: usize, eye: Vec3, weight: f32, row: &mut [f32]) {
        let p = &patches[from];
        let n = p.normal;
        let t = n.any_orthonormal_vector();
        let b = n.cross(t);
        // The near plane: a hair of the patch's own size, so that
        // neighbours meeting it at an edge are clipped, not divided by 0.
        let near = 1e-4 * p.area.sqrt().max(f32::MIN_POSITIVE);
        let runs = rayon::current_num_threads().clamp(1, 8).min(patches.len().div_ceil(256).max(1));
        let pixels = self.weights.len();
        self.buffers.resize_with(runs, || (vec![NONE; pixels], vec![0.0; pixels]));
        let res = self.res;
        let chunk = patches.len().div_ceil(runs);
        use rayon::prelude::*;
        self.buffers.par_iter_mut().enumerate().for_each(|(k, (ids, depth))| {
            ids.fill(NONE);
            depth.fill(0.0);
            let mut target = Target { res, ids, depth };
            let start = k * chunk;
            for (j, q) in patches.iter().enumerate().skip(start).take(chunk) {
                if j == from {
                    continue;
                }
                // In the hemicube's frame (x along t, y along b, z along n).
                let corners = q.corners.map(|c| {
                    let d = c - eye;
                    [d.dot(t), d.dot(b), d.dot(n)]
                });
                if corners.iter().all(|v| v[2] <= near) {
                    continue;
                }
                let id = if (eye - q.centre).dot(q.normal) > 0.0 { j as u32 } else { BACK };
                target.patch(corners, near, id);
            }
        });
        let (first, rest) = self.buffers.split_first_mut().expect("at least one run");
        for (ids, depth) in rest.iter() {
            for at in 0..pixels {
                let (d, id) = (depth[at], ids[at]);
                if d > first.1[at] || (d == first.1[at] && id < first.0[at]) {
                    (first.0[at], first.1[at]) = (id, d);
                }
            }
        }
        for (&id, &w) in first.0.iter().zip(&self.weights) {
            if id < BACK {
                row[id as usize] += weight * w;
            }
        }
    }
}

/// One run's buffers, all five faces.
struct Target<'a> {
    res: usize,
    ids: &'a mut [u32],
    depth: &'a mut [f64],
}

impl Target<'_> {
    /// Draws a patch with corners `v` in the hemicube's frame: into the one
    /// face whose frustum holds all three corners, unclipped, or else into
    /// every face, clipped.
    fn patch(&mut self, v: [[f32; 3]; 3], near: f32, id: u32) {
        let face = |[x, y, z]: [f32; 3]| {
            if z >= x.abs() && z >= y.abs() {
                0
            } else if x.abs() >= y.abs() {
                if x > 0.0 {
                    1
                } else {
                    2
                }
            } else if y > 0.0 {
                3
            } else {
                4
            }
        };
        let f = face(v[0]);
        let mapped = |k: usize| v.map(FACES[k]);
        let one = mapped(f);
        if v.iter().all(|c| c[2] >= 0.0 && face(*c) == f) && one.iter().all(|c| c[2] > near) {
            self.draw(f, &Polygon::of(one), id);
            return;
        }
        for k in 0..5 {
            let mut poly = Polygon::of(mapped(k));
            let side = k > 0;
            // Kept where each is ≥ 0: f − near, f ± a, f − b, and b (a
            // side) or f + b (the top).
            for plane in 0..5 {
                let value = |p: &[f32; 3]| match plane {
                    0 => p[2] - near,
                    1 => p[2] + p[0],
                    2 => p[2] - p[0],
                    3 => p[2] - p[1],
                    _ if side => p[1],
                    _ => p[2] + p[1],
                };
                poly = poly.clip(value);
                if poly.len < 3 {
                    break;
                }
            }
            if poly.len >= 3 {
                self.draw(k, &poly, id);
            }
        }
    }

    /// Draws the convex polygon `poly` (in face `face`'s (a, b, f), inside
    /// its frustum) with index `id`.
    fn draw(&mut self, face: usize, poly: &Polygon, id: u32) {
        let res = self.res;
        let (rows, offset) =
            if face == 0 { (res, 0) } else { (res / 2, res * res + (face - 1) * res * res / 2) };
        let (resf, rowsf) = (res as f32, rows as f32);
        // Window coordinates, y down: the top face's v ∈ [−1, 1] over res
        // rows, a side's v ∈ [0, 1] over res/2 rows.
        let window = |v: &[f32; 3]| {
            let (u, w) = (v[0] / v[2], v[1] / v[2]);
            let x = (u + 1.0) * 0.5 * resf;
            let y = if face == 0 { (1.0 - w) * 0.5 * resf } else { (1.0 - w) * rowsf };
            (FixedPoint::snap(x, y), 1.0 / f64::from(v[2]))
        };
        let mut projected = [(None, 0.0f64); 9];
        for (out, p) in projected.iter_mut().zip(&poly.points[..poly.len]) {
            *out = window(p);
        }
        let clip = Rect::from_size(0, 0, res as i32, rows as i32);
        let ids = &mut self.ids[offset..offset + res * rows];
        let depth = &mut self.depth[offset..offset + res * rows];
        for k in 1..poly.len - 1 {
            let tri = [projected[0], projected[k], projected[k + 1]];
            let (Some(f0), Some(f1), Some(f2)) = (tri[0].0, tri[1].0, tri[2].0) else { continue };
            let fixed = [f0, f1, f2];
            let (Some(edges), Some(basis)) = (EdgeTable::new(fixed), PlaneBasis::new(fixed)) else {
                continue;
            };
            let plane = DepthPlane::new(&basis, [tri[0].1, tri[1].1, tri[2].1]);
            edges.scan(clip, |span| {
                let y = span.y as usize;
                for x in span.x0..span.x1 {
                    let z = plane.at(f64::from(x) + 0.5, f64::from(span.y) + 0.5);
                    let at = y * res + x as usize;
                    if z > depth[at] {
                        depth[at] = z;
                        ids[at] = id;
                    }
                }
            });
        }
    }
}

/// A convex polygon of at most 9 corners (a triangle clipped by 5 planes).
#[derive(Clone, Copy)]
struct Polygon {
    points: [[f32; 3]; 9],
    len: usize,
}

impl Polygon {
    /// A triangle.
    fn of(v: [[f32; 3]; 3]) -> Polygon {
        let mut points = [[0.0; 3]; 9];
        points[..3].copy_from_slice(&v);
        Polygon { points, len: 3 }
    }

    /// Sutherland–Hodgman: the part where `inside` ≥ 0 (itself when all of
    /// it is).
    fn clip(&self, inside: impl Fn(&[f32; 3]) -> f32) -> Polygon {
        if self.points[..self.len].iter().all(|p| inside(p) >= 0.0) {
            return *self;
        }
        let mut out = Polygon { points: [[0.0; 3]; 9], len: 0 };
        for i in 0..self.len {
            let (a, b) = (self.points[i], self.points[(i + 1) % self.len]);
            let (da, db) = (inside(&a), inside(&b));
            if da >= 0.0 && out.len < 9 {
                out.points[out.len] = a;
                out.len += 1;
            }
            if (da >= 0.0) != (db >= 0.0) && out.len < 9 {
                let t = da / (da - db);
                out.points[out.len] =
                    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])];
                out.len += 1;
            }
        }
        out
    }
}

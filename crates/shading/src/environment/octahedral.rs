//! Octahedral maps: the sphere of directions folded onto a square (Engelhardt
//! and Dachsbacher 2008), with +y at the centre and −y at the four corners.
//! A direction costs one division to place, no trigonometry, and texels
//! cover nearly equal solid angles (within a factor of about 2), which is
//! what a prefiltered environment wants.

use glam::{Vec2, Vec3};

/// ±1 with the sign of `v` (+1 for ±0).
#[inline]
fn sign(v: f32) -> f32 {
    if v >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The position in [0, 1]² of direction `d` (any length, not zero).
#[inline]
pub fn octahedral_encode(d: Vec3) -> Vec2 {
    let s = d.x.abs() + d.y.abs() + d.z.abs();
    if s.is_nan() || s == 0.0 {
        return Vec2::splat(0.5);
    }
    let (mut px, mut pz) = (d.x / s, d.z / s);
    if d.y < 0.0 {
        (px, pz) = ((1.0 - pz.abs()) * sign(px), (1.0 - px.abs()) * sign(pz));
    }
    Vec2::new(px * 0.5 + 0.5, pz * 0.5 + 0.5)
}

/// The unit direction at position `uv` ∈ [0, 1]² (the inverse of
/// [`octahedral_encode`]).
#[inline]
pub fn octahedral_decode(uv: Vec2) -> Vec3 {
    let (mut px, mut pz) = (uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0);
    let y = 1.0 - px.abs() - pz.abs();
    if y < 0.0 {
        (px, pz) = ((1.0 - pz.abs()) * sign(px), (1.0 - px.abs()) * sign(pz));
    }
    Vec3::new(px, y, pz).normalize()
}

/// The solid angle of each texel of a `size × size` map, rows of
/// increasing v: each texel cut into m × m cells (m = 64/size, at least 1)
/// whose corners' directions bound spherical quadrilaterals, each summed as
/// two triangles (Van Oosterom and Strackee 1983). The cells are small
/// enough that the fold lines only bend their edges slightly.
pub fn texel_solid_angles(size: u32) -> Vec<f32> {
    let m = (64 / size.max(1)).max(1);
    let fine = (size * m) as f64;
    let corner = |i: u32, j: u32| {
        octahedral_decode(Vec2::new((f64::from(i) / fine) as f32, (f64::from(j) / fine) as f32)).as_dvec3()
    };
    let triangle = |a: glam::DVec3, b: glam::DVec3, c: glam::DVec3| {
        let numerator = a.dot(b.cross(c)).abs();
        let denominator = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
        2.0 * numerator.atan2(denominator)
    };
    let mut out = Vec::with_capacity(size as usize * size as usize);
    for j in 0..size {
        for i in 0..size {
            let mut total = 0.0;
            for b in j * m..(j + 1) * m {
                for a in i * m..(i + 1) * m {
                    let (p, q, r, t) =
                        (corner(a, b), corner(a + 1, b), corner(a + 1, b + 1), corner(a, b + 1));
                    total += triangle(p, q, r) + triangle(p, r, t);
                }
            }
            out.push(total as f32);
        }
    }
    out
}

/// A square octahedral map of RGB radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct OctahedralMap {
    size: u32,
    texels: Vec<Vec3>,
}

impl OctahedralMap {
    /// A `size × size` map whose texel (i, j) is `f` of the direction at its
    /// centre.
    pub fn from_fn(size: u32, mut f: impl FnMut(Vec3) -> Vec3) -> OctahedralMap {
        let s = size as f32;
        let mut texels = Vec::with_capacity(size as usize * size as usize);
        for j in 0..size {
            for i in 0..size {
                let uv = Vec2::new((i as f32 + 0.5) / s, (j as f32 + 0.5) / s);
                texels.push(f(octahedral_decode(uv)));
            }
        }
        OctahedralMap { size, texels }
    }

    /// [`Self::from_fn`] with the rows shared among the machine's cores
    /// (each texel computed alone, so the map is the same whatever the
    /// number of threads).
    pub(super) fn from_fn_parallel(size: u32, f: impl Fn(Vec3) -> Vec3 + Sync) -> OctahedralMap {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(size as usize).max(1);
        let rows_per = (size as usize).div_ceil(threads);
        let s = size as f32;
        let mut texels = vec![Vec3::ZERO; size as usize * size as usize];
        std::thread::scope(|scope| {
            for (chunk, out) in texels.chunks_mut(rows_per * size as usize).enumerate() {
                let f = &f;
                scope.spawn(move || {
                    for (k, t) in out.iter_mut().enumerate() {
                        let index = chunk * rows_per * size as usize + k;
                        let (i, j) = (index % size as usize, index / size as usize);
                        let uv = Vec2::new((i as f32 + 0.5) / s, (j as f32 + 0.5) / s);
                        *t = f(octahedral_decode(uv));
                    }
                });
            }
        });
        OctahedralMap { size, texels }
    }

    /// A `size × size` map of `texels` (rows of increasing v).
    pub(super) fn from_texels(size: u32, texels: Vec<Vec3>) -> OctahedralMap {
        debug_assert_eq!(texels.len(), size as usize * size as usize);
        OctahedralMap { size, texels }
    }

    /// The map with each side halved (at least 1): each texel the mean of
    /// the 2 × 2 it covers, weighted by their solid angles (octahedral
    /// texels differ by up to about 2×), so each level holds the same
    /// radiance integral.
    pub fn halved(&self) -> OctahedralMap {
        let size = (self.size / 2).max(1);
        let step = self.size / size;
        let weights = texel_solid_angles(self.size);
        let mut texels = Vec::with_capacity(size as usize * size as usize);
        for j in 0..size {
            for i in 0..size {
                let (mut sum, mut total) = (Vec3::ZERO, 0.0f32);
                for dj in 0..step {
                    for di in 0..step {
                        let (x, y) = (i * step + di, j * step + dj);
                        let w = weights[(y * self.size + x) as usize];
                        sum += self.texel(x, y) * w;
                        total += w;
                    }
                }
                texels.push(if total > 0.0 { sum / total } else { Vec3::ZERO });
            }
        }
        OctahedralMap { size, texels }
    }

    /// Side in texels.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// The texels, rows of increasing v.
    pub fn texels(&self) -> &[Vec3] {
        &self.texels
    }

    #[inline]
    fn texel(&self, i: u32, j: u32) -> Vec3 {
        self.texels[(j * self.size + i) as usize]
    }

    /// Texel (i, j) where i and j may step one past an edge: across an edge
    /// of the square the fold mirrors, so the neighbour of (−1, j) is
    /// (0, size − 1 − j), and likewise on the other three sides.
    #[inline]
    fn folded(&self, i: i64, j: i64) -> Vec3 {
        let last = i64::from(self.size) - 1;
        let (mut i, mut j) = (i, j);
        if i < 0 || i > last {
            i = i.clamp(0, last);
            j = last - j;
        }
        if j < 0 || j > last {
            j = j.clamp(0, last);
            i = last - i;
        }
        self.texel(i.clamp(0, last) as u32, j.clamp(0, last) as u32)
    }

    /// Bilinear radiance at `uv` ∈ [0, 1]² (texel centres at (i + ½)/size),
    /// the fold's mirrored neighbours past the edges.
    #[inline]
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        let s = self.size as f32;
        let (x, y) = (uv.x * s - 0.5, uv.y * s - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (i, j) = (x0 as i64, y0 as i64);
        let top = self.folded(i, j).lerp(self.folded(i + 1, j), fx);
        let bottom = self.folded(i, j + 1).lerp(self.folded(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }
}

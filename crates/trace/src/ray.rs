//! Rays, hits and the ray–triangle test every accelerator shares.
//!
//! The test is the watertight one of Woop, Benthin and Wald (2013), as
//! pbrt-v4 writes it: the triangle is moved into a space where the ray
//! starts at the origin and runs along +z, and the three 2D edge functions
//! decide coverage. A ray through an edge or a vertex shared by two
//! triangles hits at least one of them (no crack between them), and an
//! edge function that rounds to zero is recomputed in f64. The hit point's
//! rounding error is bounded ([`Hit::point_error`]) so that a secondary ray
//! starts just outside that bound ([`offset_origin`]): the offset scales
//! with the hit point's magnitude instead of being a fixed epsilon, so
//! there is no self-intersection ("acne") at any scene scale.

use glam::Vec3;

/// A ray o + t·d for 0 < t < `t_max` (`d` need not be unit length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// The origin.
    pub origin: Vec3,
    /// The direction.
    pub dir: Vec3,
    /// The far end of the ray, in units of `dir`.
    pub t_max: f32,
}

impl Ray {
    /// The ray from `origin` along `dir` with no far end.
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir, t_max: f32::INFINITY }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// The nearest hit of a ray: the parameter, the triangle and the
/// barycentric coordinates of the hit (of the triangle's vertices 0, 1, 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter.
    pub t: f32,
    /// The triangle's index in the world's triangle list.
    pub triangle: u32,
    /// Barycentric coordinates, b0 + b1 + b2 = 1.
    pub b: [f32; 3],
}

impl Hit {
    /// True when `self` is nearer than `other` by the tie rule every
    /// accelerator follows: the smaller t, and at equal t the lower
    /// triangle index (so the answer does not depend on traversal order).
    #[inline]
    pub fn nearer_than(&self, other: &Hit) -> bool {
        self.t < other.t || (self.t == other.t && self.triangle < other.triangle)
    }

    /// The hit point from the barycentrics (more accurate than o + t·d)
    /// and a bound on its rounding error per axis.
    pub fn point_error(&self, p: &[Vec3; 3]) -> (Vec3, Vec3) {
        let [b0, b1, b2] = self.b;
        let point = b0 * p[0] + b1 * p[1] + b2 * p[2];
        let error = gamma(7) * ((b0 * p[0]).abs() + (b1 * p[1]).abs() + (b2 * p[2]).abs());
        (point, error)
    }
}

/// γ(n) = n·u/(1 − n·u) with u the unit roundoff 2⁻²⁴: the relative error
/// bound of n floating-point operations (pbrt's notation).
#[inline]
pub fn gamma(n: u32) -> f32 {
    let nu = n as f32 * f32::EPSILON * 0.5;
    nu / (1.0 - nu)
}

/// Where a ray leaving a surface at `point` (rounding error `error` per
/// axis, geometric normal `n`) towards `w` starts: moved along ±n by the
/// error bound projected on n, to the side `w` goes, then rounded away
/// from the point, so the new ray cannot hit the surface it leaves.
pub fn offset_origin(point: Vec3, error: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let d = n.abs().dot(error);
    let mut offset = d * n;
    if w.dot(n) < 0.0 {
        offset = -offset;
    }
    let p = point + offset;
    let away = |v: f32, o: f32| {
        if o > 0.0 {
            next_up(v)
        } else if o < 0.0 {
            next_down(v)
        } else {
            v
        }
    };
    Vec3::new(away(p.x, offset.x), away(p.y, offset.y), away(p.z, offset.z))
}

/// The next float above `v` (infinity and NaN unchanged, −0 → the smallest
/// positive).
pub fn next_up(v: f32) -> f32 {
    if v.is_nan() || v == f32::INFINITY {
        return v;
    }
    let v = if v == -0.0 { 0.0 } else { v };
    let bits = v.to_bits();
    f32::from_bits(if v >= 0.0 { bits + 1 } else { bits - 1 })
}

/// The next float below `v`.
pub fn next_down(v: f32) -> f32 {
    -next_up(-v)
}

/// The ray's precomputed shear (the watertight test's per-ray part).
#[derive(Clone, Copy, Debug)]
pub struct Sheared {
    origin: Vec3,
    /// The axes permuted so that z is the direction's largest component.
    axes: [usize; 3],
    shear: Vec3,
    t_max: f32,
}

impl Sheared {
    /// The per-ray values for `ray`; `None` for a zero or non-finite
    /// direction (it hits nothing).
    #[inline]
    pub fn new(ray: &Ray) -> Option<Sheared> {
        let d = ray.dir;
        if !d.is_finite() || d == Vec3::ZERO || !ray.origin.is_finite() || ray.t_max.is_nan() {
            return None;
        }
        let kz = d.abs().max_position();
        let kx = (kz + 1) % 3;
        let ky = (kx + 1) % 3;
        let d = Vec3::new(d[kx], d[ky], d[kz]);
        let shear = Vec3::new(-d.x / d.z, -d.y / d.z, 1.0 / d.z);
        Some(Sheared { origin: ray.origin, axes: [kx, ky, kz], shear, t_max: ray.t_max })
    }

    /// The axes permuted so that the last is the direction's largest
    /// component, and the shear: what a structure's exact box test
    /// repeats.
    pub(crate) fn frame(&self) -> ([usize; 3], Vec3) {
        (self.axes, self.shear)
    }

    /// The watertight test of the triangle `p` (index `triangle`): the hit
    /// for 0 < t < t_max, edges and vertices included.
    #[inline]
    pub fn intersect(&self, p: &[Vec3; 3], triangle: u32) -> Option<Hit> {
        let [kx, ky, kz] = self.axes;
        let s = self.shear;
        let moved = |v: Vec3| {
            let v = v - self.origin;
            let v = Vec3::new(v[kx], v[ky], v[kz]);
            Vec3::new(v.x + s.x * v.z, v.y + s.y * v.z, v.z)
        };
        let (p0, p1, p2) = (moved(p[0]), moved(p[1]), moved(p[2]));
        // Computed in f64 from the start: pbrt's fallback for an edge
        // function of 0 (a ray through an edge or a vertex) is the rule.
        let e0 = difference_of_products(p1.x, p2.y, p1.y, p2.x);
        let e1 = difference_of_products(p2.x, p0.y, p2.y, p0.x);
        let e2 = difference_of_products(p0.x, p1.y, p0.y, p1.x);
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (z0, z1, z2) = (s.z * p0.z, s.z * p1.z, s.z * p2.z);
        let t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
        if (det < 0.0 && (t_scaled >= 0.0 || t_scaled < self.t_max * det))
            || (det > 0.0 && (t_scaled <= 0.0 || t_scaled > self.t_max * det))
        {
            return None;
        }
        let inv = 1.0 / det;
        let (b0, b1, b2) = (e0 * inv, e1 * inv, e2 * inv);
        let t = t_scaled * inv;
        // pbrt-v4's conservative bound: t must exceed the error of its own
        // computation, so a ray never hits behind its origin.
        let max_z = Vec3::new(z0, z1, z2).abs().max_element();
        let delta_z = gamma(3) * max_z;
        let max_x = Vec3::new(p0.x, p1.x, p2.x).abs().max_element();
        let max_y = Vec3::new(p0.y, p1.y, p2.y).abs().max_element();
        let delta_x = gamma(5) * (max_x + max_z);
        let delta_y = gamma(5) * (max_y + max_z);
        let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
        let max_e = Vec3::new(e0, e1, e2).abs().max_element();
        let delta_t = 3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv.abs();
        if t <= delta_t || !t.is_finite() {
            return None;
        }
        Some(Hit { t, triangle, b: [b0, b1, b2] })
    }
}

/// a·b − c·d rounded once to f64 and then to f32: the products of two f32
/// are exact in f64 (48 significant bits), so the result is within half
/// an f32 unit of the exact value plus 2⁻⁵³ relative, and
/// `difference_of_products(a, b, c, d) == −difference_of_products(c, d, a, b)`
/// exactly (rounding is symmetric), which keeps a shared edge's two edge
/// functions of opposite sign: the test stays watertight. (pbrt-v4 uses
/// Kahan's algorithm with fused multiply–adds; without FMA in the
/// baseline instruction set those are library calls.)
#[inline]
fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    (f64::from(a) * f64::from(b) - f64::from(c) * f64::from(d)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [Vec3; 3] {
        [Vec3::new(-1.0, -1.0, -2.0), Vec3::new(1.0, -1.0, -2.0), Vec3::new(0.0, 1.0, -2.0)]
    }

    #[test]
    fn a_ray_through_the_middle_hits_at_the_plane() {
        let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
        let hit = Sheared::new(&ray).unwrap().intersect(&tri(), 7).unwrap();
        assert_eq!(hit.triangle, 7);
        assert!((hit.t - 2.0).abs() < 1e-6, "{hit:?}");
        let (p, _) = hit.point_error(&tri());
        assert!((p - Vec3::new(0.0, 0.0, -2.0)).length() < 1e-6);
        assert!((hit.b.iter().sum::<f32>() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn misses_behind_beyond_and_beside() {
        let s = |o: Vec3, d: Vec3, t_max: f32| Sheared::new(&Ray { origin: o, dir: d, t_max }).unwrap();
        assert!(s(Vec3::ZERO, Vec3::Z, f32::INFINITY).intersect(&tri(), 0).is_none(), "behind");
        assert!(s(Vec3::ZERO, -Vec3::Z, 1.5).intersect(&tri(), 0).is_none(), "beyond t_max");
        assert!(
            s(Vec3::new(3.0, 0.0, 0.0), -Vec3::Z, f32::INFINITY).intersect(&tri(), 0).is_none(),
            "beside"
        );
        assert!(Sheared::new(&Ray::new(Vec3::ZERO, Vec3::ZERO)).is_none(), "zero direction");
        assert!(Sheared::new(&Ray::new(Vec3::ZERO, Vec3::NAN)).is_none(), "NaN direction");
    }

    /// Two triangles sharing an edge: rays through points on the edge hit
    /// one of them, whatever the rounding (the watertight property).
    #[test]
    fn no_ray_slips_through_a_shared_edge() {
        let a = [Vec3::new(-1.0, -1.0, -3.0), Vec3::new(1.0, 1.0, -3.5), Vec3::new(-1.0, 1.0, -3.2)];
        let b = [Vec3::new(-1.0, -1.0, -3.0), Vec3::new(1.0, -1.0, -3.1), Vec3::new(1.0, 1.0, -3.5)];
        let eye = Vec3::new(0.013, -0.021, 0.7);
        for k in 0..=2000 {
            let f = k as f32 / 2000.0;
            let on_edge = a[0].lerp(a[1], f);
            let ray = Ray::new(eye, on_edge - eye);
            let s = Sheared::new(&ray).unwrap();
            assert!(s.intersect(&a, 0).is_some() || s.intersect(&b, 1).is_some(), "slipped at {f}");
        }
    }

    #[test]
    fn offsets_grow_with_the_magnitude_of_the_point() {
        let n = Vec3::Y;
        for scale in [1.0e-3f32, 1.0, 1.0e3, 1.0e6] {
            let p = Vec3::new(scale, 0.5 * scale, -scale);
            let (_, err) = Hit { t: 1.0, triangle: 0, b: [1.0, 0.0, 0.0] }.point_error(&[p, p, p]);
            let up = offset_origin(p, err, n, Vec3::Y);
            let down = offset_origin(p, err, n, -Vec3::Y);
            assert!(up.y > p.y && down.y < p.y, "{scale}");
        }
    }

    #[test]
    fn next_float_steps() {
        assert_eq!(next_up(1.0), 1.0 + f32::EPSILON);
        assert_eq!(next_down(1.0), 1.0 - f32::EPSILON / 2.0);
        assert!(next_up(-0.0) > 0.0 && next_down(0.0) < 0.0);
        assert_eq!(next_up(f32::INFINITY), f32::INFINITY);
    }
}

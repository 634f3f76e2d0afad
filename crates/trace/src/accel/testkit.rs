//! Test generators shared by the structures' tests: scenes full of the
//! cases that break traversals (shared edges and vertices, duplicates,
//! coplanar and degenerate triangles, non-finite corners, coordinates on a
//! coarse grid so that faces coincide) and rays aimed at their vertices and
//! edges, with brute force as the oracle.

use glam::Vec3;

use super::brute::Brute;
use super::{Accelerator, Counters};
use crate::ray::{Hit, Ray};

/// splitmix64, for reproducible scenes and rays.
pub(crate) struct Rng(pub u64);

impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Uniform in [lo, hi); a quarter of the time on a coarse grid, so
    /// that coordinates (and box faces) coincide.
    pub(crate) fn float(&mut self, lo: f32, hi: f32) -> f32 {
        let u = (self.next() >> 40) as f32 / (1u64 << 24) as f32;
        let u = if self.below(4) == 0 { (u * 8.0).floor() / 8.0 } else { u };
        lo + (hi - lo) * u
    }
    pub(crate) fn point(&mut self, r: f32) -> Vec3 {
        Vec3::new(self.float(-r, r), self.float(-r, r), self.float(-r, r))
    }
}

/// `n` triangles: mostly random, some sharing an edge or a vertex with an
/// earlier one, exact duplicates, flat ones, degenerate ones and a few
/// with non-finite corners.
pub(crate) fn scene(rng: &mut Rng, n: usize) -> Vec<[Vec3; 3]> {
    let mut tris: Vec<[Vec3; 3]> = Vec::with_capacity(n);
    while tris.len() < n {
        let a = rng.point(4.0);
        let small = |rng: &mut Rng| {
            let r = if rng.below(2) == 0 { 0.5 } else { 3.0 };
            a + rng.point(r)
        };
        let earlier = (!tris.is_empty()).then(|| tris[rng.below(tris.len())]);
        let t = match (rng.below(10), earlier) {
            (0, Some(e)) => e,
            (1, Some(e)) => [e[1], e[0], small(rng)],
            (2, Some(e)) => [e[2], small(rng), small(rng)],
            (3, _) => {
                let (b, c) = (small(rng), small(rng));
                [a, Vec3::new(b.x, b.y, a.z), Vec3::new(c.x, c.y, a.z)]
            }
            (4, _) => [a, a, if rng.below(2) == 0 { a } else { small(rng) }],
            (5, _) if rng.below(4) == 0 => {
                let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.below(3)];
                let mut t = [a, small(rng), small(rng)];
                t[rng.below(3)][rng.below(3)] = bad;
                t
            }
            _ => [a, small(rng), small(rng)],
        };
        tris.push(t);
    }
    tris
}

/// A ray: from inside or outside the scene, along a random direction,
/// an axis, or at a vertex, an edge point or a centroid of a triangle;
/// t_max infinite, random, or exactly brute force's nearest t.
pub(crate) fn ray(rng: &mut Rng, tris: &[[Vec3; 3]]) -> Ray {
    let reach = if rng.below(2) == 0 { 5.0 } else { 12.0 };
    let origin = rng.point(reach);
    let t = tris[rng.below(tris.len())];
    let dir = match rng.below(5) {
        0 => [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z][rng.below(6)],
        1 => t[rng.below(3)] - origin,
        2 => t[0].lerp(t[1], rng.float(0.0, 1.0)) - origin,
        3 => (t[0] + t[1] + t[2]) / 3.0 - origin,
        _ => rng.point(1.0),
    };
    let mut ray = Ray::new(origin, dir);
    match rng.below(4) {
        0 => ray.t_max = rng.float(0.0, 3.0),
        1 => ray.t_max = Brute.closest(tris, &ray, &mut Counters::default()).map_or(1.0, |h| h.t),
        _ => {}
    }
    ray
}

pub(crate) fn key(h: Hit) -> (u32, u32, [u32; 3]) {
    (h.triangle, h.t.to_bits(), h.b.map(f32::to_bits))
}

pub(crate) fn hits(accel: &dyn Accelerator, tris: &[[Vec3; 3]], ray: &Ray) -> Vec<(u32, u32, [u32; 3])> {
    let mut all = Vec::new();
    accel.each_hit(tris, ray, &mut Counters::default(), &mut |h| {
        all.push(key(h));
        true
    });
    all.sort_unstable();
    all
}

/// `accel` answers `ray` bit for bit as brute force does: the same nearest
/// hit and the same set of hits.
#[track_caller]
pub(crate) fn check_same(accel: &dyn Accelerator, tris: &[[Vec3; 3]], ray: &Ray) {
    let mut count = Counters::default();
    let got = accel.closest(tris, ray, &mut count).map(key);
    let want = Brute.closest(tris, ray, &mut Counters::default()).map(key);
    assert_eq!(got, want, "closest, {ray:?}");
    assert_eq!(count.rays, 1);
    assert_eq!(hits(accel, tris, ray), hits(&Brute, tris, ray), "each_hit, {ray:?}");
}

/// `count` random rays through `tris`: `accel`'s nearest hit equals brute
/// force's on each, and its hits on every tenth; returns the counters of
/// `accel` and of brute force.
pub(crate) fn check_rays(
    accel: &dyn Accelerator,
    tris: &[[Vec3; 3]],
    rng: &mut Rng,
    count: usize,
) -> (Counters, Counters) {
    let (mut mine, mut brute) = (Counters::default(), Counters::default());
    for i in 0..count {
        let ray = ray(rng, tris);
        let got = accel.closest(tris, &ray, &mut mine).map(key);
        assert_eq!(got, Brute.closest(tris, &ray, &mut brute).map(key), "{ray:?}");
        if i % 10 == 0 {
            assert_eq!(hits(accel, tris, &ray), hits(&Brute, tris, &ray), "{ray:?}");
        }
    }
    (mine, brute)
}

/// Eight copies of one triangle across −z from the origin (the first
/// eight of `tris`): `each_hit` stops after the visit that returns false,
/// and reports each of them once.
pub(crate) fn check_each_hit_stops(accel: &dyn Accelerator, tris: &[[Vec3; 3]]) {
    let mut seen = 0;
    let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
    let done = accel.each_hit(tris, &ray, &mut Counters::default(), &mut |_| {
        seen += 1;
        seen < 3
    });
    assert!(!done);
    assert_eq!(seen, 3);
    assert_eq!(hits(accel, tris, &ray).len(), 8, "each once");
}

/// The eight stacked triangles [`check_each_hit_stops`] reads.
pub(crate) fn stacked() -> Vec<[Vec3; 3]> {
    vec![[Vec3::new(-1.0, -1.0, -2.0), Vec3::new(1.0, -1.0, -2.0), Vec3::new(0.0, 1.0, -2.0)]; 8]
}

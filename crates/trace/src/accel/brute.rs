//! Brute force: every triangle for every ray, the oracle the other
//! structures are tested against.

use glam::Vec3;

use super::{each_in, nearest_in, Accelerator, Counters};
use crate::ray::{Hit, Ray, Sheared};

/// No structure.
#[derive(Clone, Copy, Debug, Default)]
pub struct Brute;

impl Accelerator for Brute {
    fn closest(&self, triangles: &[[Vec3; 3]], ray: &Ray, count: &mut Counters) -> Option<Hit> {
        count.rays += 1;
        let ray = Sheared::new(ray)?;
        let mut best = None;
        nearest_in(triangles, 0..triangles.len() as u32, &ray, &mut best, count);
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
        let Some(ray) = Sheared::new(ray) else { return true };
        each_in(triangles, 0..triangles.len() as u32, &ray, count, visit)
    }
}

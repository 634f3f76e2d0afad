//! Distributed (area) lights, SPEC §5: "a set of point lights sampled over
//! its surface, each carrying its share of the intensity". An
//! [`AreaLight`] is a rectangle or a disc; [`AreaLight::sample`] turns it
//! into k × k point lights, one at the centre of each cell of a regular
//! grid over the shape (stratified, and the same every time: images stay
//! reproducible), each with 1/k² of the colour.
//!
//! With planar shadows each sample casts its own hard shadow; together
//! they give the penumbra of the light's extent.

use glam::Vec3;
use zline_shading::{Attenuation, Light};

use crate::limits::MAX_AREA_SAMPLES_PER_SIDE;

/// The surface of an area light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AreaShape {
    /// The parallelogram center ± u ± v (u and v half edges, usually
    /// perpendicular).
    Rect {
        /// Its centre.
        center: Vec3,
        /// Half of one edge.
        u: Vec3,
        /// Half of the other edge.
        v: Vec3,
    },
    /// The disc of `radius` around `center`, perpendicular to `normal`.
    Disc {
        /// Its centre.
        center: Vec3,
        /// Its normal (need not be unit).
        normal: Vec3,
        /// Its radius.
        radius: f32,
    },
}

/// A light with an area: its shape, total colour and attenuation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaLight {
    /// The surface.
    pub shape: AreaShape,
    /// The colour Il of the whole light, shared by its samples.
    pub color: Vec3,
    /// Distance attenuation of each sample.
    pub attenuation: Attenuation,
}

impl AreaLight {
    /// k × k point lights over the shape (k = `per_side`, clamped to
    /// 1..=[`MAX_AREA_SAMPLES_PER_SIDE`]), row by row, each with colour/k².
    pub fn sample(&self, per_side: u32) -> Vec<Light> {
        let k = per_side.clamp(1, MAX_AREA_SAMPLES_PER_SIDE);
        let color = self.color / (k * k) as f32;
        let cell = |i: u32| (i as f32 + 0.5) / k as f32 * 2.0 - 1.0;
        (0..k)
            .flat_map(|j| (0..k).map(move |i| (cell(i), cell(j))))
            .map(|(a, b)| Light::Point { position: self.point(a, b), color, attenuation: self.attenuation })
            .collect()
    }

    /// The point of the shape at (a, b) ∈ [−1, 1]²: the rectangle's
    /// bilinear map, or for a disc Shirley and Chiu's concentric map (it
    /// keeps the grid's cells of equal area).
    fn point(&self, a: f32, b: f32) -> Vec3 {
        match self.shape {
            AreaShape::Rect { center, u, v } => center + a * u + b * v,
            AreaShape::Disc { center, normal, radius } => {
                let (r, phi) = if a == 0.0 && b == 0.0 {
                    (0.0, 0.0)
                } else if a.abs() > b.abs() {
                    (a, std::f32::consts::FRAC_PI_4 * (b / a))
                } else {
                    (b, std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (a / b))
                };
                let n = normal.normalize_or(Vec3::Y);
                let (e1, e2) = n.any_orthonormal_pair();
                center + radius * r * (phi.cos() * e1 + phi.sin() * e2)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn positions(lights: &[Light]) -> Vec<Vec3> {
        lights
            .iter()
            .map(|l| match l {
                Light::Point { position, .. } => *position,
                _ => panic!("area samples are point lights"),
            })
            .collect()
    }

    #[test]
    fn a_rectangle_gives_the_cell_centres_sharing_the_colour() {
        let light = AreaLight {
            shape: AreaShape::Rect {
                center: Vec3::new(0.0, 3.0, 0.0),
                u: Vec3::new(1.0, 0.0, 0.0),
                v: Vec3::new(0.0, 0.0, 0.5),
            },
            color: Vec3::new(0.8, 0.4, 1.6),
            attenuation: Attenuation::NONE,
        };
        let lights = light.sample(2);
        assert_eq!(
            positions(&lights),
            vec![
                Vec3::new(-0.5, 3.0, -0.25),
                Vec3::new(0.5, 3.0, -0.25),
                Vec3::new(-0.5, 3.0, 0.25),
                Vec3::new(0.5, 3.0, 0.25)
            ]
        );
        let total: Vec3 = lights.iter().map(|l| l.color()).sum();
        assert!((total - light.color).abs().max_element() < 1e-6, "{total}");
        assert_eq!(light.sample(0).len(), 1);
        assert_eq!(
            light.sample(u32::MAX).len(),
            (MAX_AREA_SAMPLES_PER_SIDE * MAX_AREA_SAMPLES_PER_SIDE) as usize
        );
    }

    #[test]
    fn a_disc_keeps_its_samples_on_the_disc_and_spread_over_it() {
        let (center, normal) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 2.0, 0.0));
        let light = AreaLight {
            shape: AreaShape::Disc { center, normal, radius: 0.5 },
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        let points = positions(&light.sample(6));
        assert_eq!(points.len(), 36);
        for p in &points {
            let d = *p - center;
            assert!(d.y.abs() < 1e-6, "{p} is off the disc's plane");
            assert!(d.length() <= 0.5 + 1e-6, "{p} is off the disc");
        }
        // Equal-area cells: as many samples in the inner disc of radius
        // 0.5/√2 (half the area) as outside it.
        let inner = points.iter().filter(|p| (**p - center).length() < 0.5 / 2f32.sqrt()).count();
        assert!((14..=22).contains(&inner), "{inner} of 36 in the inner half");
        let mean = points.iter().copied().sum::<Vec3>() / 36.0;
        assert!((mean - center).length() < 1e-5, "{mean}");
    }
}

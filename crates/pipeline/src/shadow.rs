//! Planar projection shadows (the seed's method): the casters' triangles
//! projected onto a receiving plane from one light with the shadow matrix
//! (`zline_scene::shadow_matrix_f64`, in f64 like the clipping), cut to the
//! receiver's bounds, as a world-space mesh that the frame then transforms,
//! clips and sets up like any other (flat, never drawn: `PassKind::Shadow`
//! rasterizes it into the tiles' shadow masks).
//!
//! Only the part of a caster between the plane and the light casts a
//! shadow on it: a point on the plane's far side from the light is hidden
//! from the light by nothing the plane receives, and a point farther from
//! the plane than a point light would project through the light to the
//! wrong side (w < 0 after the matrix). Each triangle is clipped to that
//! slab in world space first — 0 < s·(g·x) and, for a point light,
//! s·(g·x) < (1 − [`SLAB_MARGIN`])·s·(g·l), with s the side of the light —
//! then projected, so the shadow of a sample P on the plane is exactly
//! "the segment from P to the light crosses a caster", the rule the truth
//! evaluates with rays.

use glam::DVec3;
use rayon::prelude::*;
use zline_scene::{light_position, shadow_matrix_f64, Light, Mesh, Object, ShadowPlane};

/// How close to the light's height above the plane a caster point may be
/// (as a fraction of it): a point at the light's own height projects to
/// infinity, one within this margin beyond 10⁶ times its distance — far
/// past the guard band, where clipping takes over.
pub(crate) const SLAB_MARGIN: f64 = 1e-6;

/// The shadow of `casters` on `plane` from `light`, as world-space
/// triangles in `out` (cleared first; positions, a normal per vertex —
/// the plane's — and triangles); `scratch` is kept by the caller so that
/// frames allocate nothing. Each caster's vertices and triangles are
/// transformed and clipped in parallel, and appended in order. Casters
/// whose vertices are not finite
/// cast nothing; a light in the plane or a directional light parallel to
/// it casts nothing.
pub(crate) fn project_casters<'a>(
    plane: &ShadowPlane,
    light: &Light,
    (receiver, casters): (&Object, impl Iterator<Item = &'a Object>),
    (out, scratch): (&mut Mesh, &mut CasterScratch),
) {
    out.positions.clear();
    out.normals.clear();
    out.triangles.clear();
    let g = plane.plane.as_dvec4();
    let l = light_position(light).as_dvec4();
    let side = g.dot(l);
    if side == 0.0 || !side.is_finite() {
        return;
    }
    let s = side.signum();
    let m = shadow_matrix_f64(g, l);
    let height = |x: DVec3| s * (g.truncate().dot(x) + g.w);
    let top = (1.0 - SLAB_MARGIN) * side.abs();
    let point_light = l.w != 0.0;
    let normal = plane.plane.truncate();
    // The receiver's world bounds, a little wider: a shadow matters only
    // there, and clipping to them keeps the projected points (up to 10⁶
    // times farther than their casters near a point light's height) at the
    // receiver's size before they are rounded to f32.
    let Some((lo, hi)) = world_bounds(receiver) else {
        return;
    };
    let pad = (hi - lo).max_element().max(1.0) * 1e-3;
    let (lo, hi) = (lo - pad, hi + pad);
    for object in casters {
        let to_world = object.world_from_object.as_dmat4();
        let positions = object.mesh.positions.par_iter();
        positions.map(|&p| to_world.transform_point3(p.as_dvec3())).collect_into_vec(&mut scratch.world);
        let world = &scratch.world;
        let shadows = object.mesh.triangles.par_iter().map(|t| {
            let (Some(&a), Some(&b), Some(&c)) =
                (world.get(t[0] as usize), world.get(t[1] as usize), world.get(t[2] as usize))
            else {
                return Polygon::EMPTY;
            };
            if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                return Polygon::EMPTY;
            }
            let mut poly = Polygon::triangle(a, b, c).clip(height);
            if point_light {
                poly = poly.clip(|x| top - height(x));
            }
            for x in poly.points_mut() {
                let p = m * x.extend(1.0);
                *x = p.truncate() / p.w;
            }
            for axis in 0..3 {
                poly = poly.clip(|x| x[axis] - lo[axis]).clip(|x| hi[axis] - x[axis]);
            }
            poly
        });
        shadows.collect_into_vec(&mut scratch.polygons);
        for poly in &mut scratch.polygons {
            let points = poly.points_mut();
            if points.len() < 3 || points.iter().any(|p| !p.is_finite()) {
                continue;
            }
            let first = out.positions.len() as u32;
            for x in points.iter() {
                out.positions.push(x.as_vec3());
                out.normals.push(normal);
            }
            for k in 1..points.len() as u32 - 1 {
                out.triangles.push([first, first + k, first + k + 1]);
            }
        }
    }
}

/// Scratch for [`project_casters`], kept from frame to frame: a caster's
/// world-space vertices and each of its triangles' clipped shadow.
#[derive(Debug, Default)]
pub(crate) struct CasterScratch {
    world: Vec<DVec3>,
    polygons: Vec<Polygon>,
}

/// The world-space bounds of an object's vertices; `None` for an object
/// without finite vertices.
fn world_bounds(object: &Object) -> Option<(DVec3, DVec3)> {
    let m = object.world_from_object.as_dmat4();
    let points =
        object.mesh.positions.iter().map(|&p| m.transform_point3(p.as_dvec3())).filter(|p| p.is_finite());
    points.fold(None, |b, p| Some(b.map_or((p, p), |(lo, hi): (DVec3, DVec3)| (lo.min(p), hi.max(p)))))
}

/// A convex polygon of at most [`Polygon::MAX`] points, on the stack: a
/// triangle cut by the two slab planes and the six faces of a box has at
/// most 3 + 8 corners.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Polygon {
    points: [DVec3; Polygon::MAX],
    len: usize,
}

impl Polygon {
    const MAX: usize = 12;
    /// No points.
    const EMPTY: Polygon = Polygon { points: [DVec3::ZERO; Polygon::MAX], len: 0 };

    pub(crate) fn triangle(a: DVec3, b: DVec3, c: DVec3) -> Polygon {
        let mut points = [DVec3::ZERO; Polygon::MAX];
        points[..3].copy_from_slice(&[a, b, c]);
        Polygon { points, len: 3 }
    }

    pub(crate) fn points_mut(&mut self) -> &mut [DVec3] {
        &mut self.points[..self.len]
    }

    /// Sutherland–Hodgman: the part where `f ≥ 0` (`f` affine, so the
    /// crossing is at the ratio of its values): a point with f = 0 stays,
    /// an edge is split only where f changes sign. A convex polygon gains
    /// at most one point per cut.
    pub(crate) fn clip(&self, f: impl Fn(DVec3) -> f64) -> Polygon {
        let mut out = Polygon::EMPTY;
        let points = &self.points[..self.len];
        for (k, &a) in points.iter().enumerate() {
            let b = points[(k + 1) % points.len()];
            let (fa, fb) = (f(a), f(b));
            let mut push = |p: DVec3| {
                if out.len < Polygon::MAX {
                    out.points[out.len] = p;
                    out.len += 1;
                }
            };
            if fa >= 0.0 {
                push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                push(a + (b - a) * (fa / (fa - fb)));
            }
        }
        out
    }
}

/// An empty mesh for [`project_casters`] to fill.
pub(crate) fn empty_mesh() -> Mesh {
    Mesh {
        name: "planar shadow".into(),
        positions: Vec::new(),
        normals: Vec::new(),
        triangles: Vec::new(),
        material: zline_scene::Material::default(),
        uvs: Vec::new(),
        colors: Vec::new(),
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        surface_maps: Default::default(),
    }
}

/// The first bit of receiving plane `p` in a sample's shadow mask, for a
/// scene with `lights` lights: plane p owns bits p·lights .. (p+1)·lights.
/// `None` past the mask's 32 bits.
pub(crate) fn first_bit(p: usize, lights: usize) -> Option<u32> {
    let first = p.checked_mul(lights)?;
    (first < 32).then_some(first as u32)
}

/// Which planes and lights get a bit: the pairs (p, k) with
/// `first_bit(p) + k < 32`, in order.
pub(crate) fn pairs(planes: usize, lights: usize) -> impl Iterator<Item = (usize, usize, u32)> {
    (0..planes).flat_map(move |p| (0..lights).map(move |k| (p, k))).filter_map(move |(p, k)| {
        let bit = first_bit(p, lights)? as usize + k;
        (bit < 32).then_some((p, k, bit as u32))
    })
}

/// A plane's normal, for tests: the unit (a, b, c) of (a, b, c, d).
#[cfg(test)]
fn unit(g: glam::Vec4) -> glam::Vec3 {
    g.truncate().normalize()
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{Mat4, Vec3, Vec4};
    use zline_scene::{Attenuation, Mesh};

    use super::*;

    fn quad(y: f32, half: f32) -> Object {
        let positions = vec![
            Vec3::new(-half, y, -half),
            Vec3::new(half, y, -half),
            Vec3::new(half, y, half),
            Vec3::new(-half, y, half),
        ];
        let mesh = Mesh {
            normals: vec![Vec3::Y; 4],
            positions,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..empty_mesh()
        };
        Object {
            mesh: Arc::new(mesh),
            world_from_object: Mat4::IDENTITY,
            material: None,
            shading: None,
            cull_back_faces: false,
        }
    }

    fn ground() -> ShadowPlane {
        ShadowPlane { receiver: 0, plane: Vec4::new(0.0, 1.0, 0.0, 0.0) }
    }

    fn bounds(m: &Mesh) -> (Vec3, Vec3) {
        let used = m.triangles.iter().flatten().map(|&i| m.positions[i as usize]);
        used.fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), p| (lo.min(p), hi.max(p)))
    }

    #[test]
    fn a_square_under_a_point_light_casts_the_scaled_square() {
        // Square of half-side 0.5 at y = 1, light at y = 4 straight above:
        // the shadow's half-side is 0.5 · 4 / (4 − 1) = 2/3.
        let light = Light::Point {
            position: Vec3::new(0.0, 4.0, 0.0),
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        let mut out = empty_mesh();
        project_casters(
            &ground(),
            &light,
            (&quad(0.0, 10.0), [quad(1.0, 0.5)].iter()),
            (&mut out, &mut CasterScratch::default()),
        );
        assert_eq!(out.triangles.len(), 2);
        let (lo, hi) = bounds(&out);
        let h = 2.0 / 3.0;
        assert!((lo - Vec3::new(-h, 0.0, -h)).abs().max_element() < 1e-6, "{lo}");
        assert!((hi - Vec3::new(h, 0.0, h)).abs().max_element() < 1e-6, "{hi}");
        assert!(out.normals.iter().all(|&n| n == unit(ground().plane)));
    }

    #[test]
    fn casters_beyond_the_light_or_below_the_plane_cast_nothing() {
        let light = Light::Point {
            position: Vec3::new(0.0, 4.0, 0.0),
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        let mut out = empty_mesh();
        project_casters(
            &ground(),
            &light,
            (&quad(0.0, 10.0), [quad(5.0, 0.5), quad(-1.0, 0.5)].iter()),
            (&mut out, &mut CasterScratch::default()),
        );
        assert!(out.triangles.is_empty(), "{:?}", out.positions);
        // A light under the plane lights its underside: the quad at y = -1
        // now casts, the one above does not.
        let under = Light::Point {
            position: Vec3::new(0.0, -4.0, 0.0),
            color: Vec3::ONE,
            attenuation: Attenuation::NONE,
        };
        project_casters(
            &ground(),
            &under,
            (&quad(0.0, 10.0), [quad(1.0, 0.5), quad(-1.0, 0.5)].iter()),
            (&mut out, &mut CasterScratch::default()),
        );
        assert_eq!(out.triangles.len(), 2);
    }

    #[test]
    fn a_caster_crossing_the_plane_is_cut_at_it() {
        // A vertical triangle from y = -1 to y = 1 under a directional light
        // going straight down: only the part above y = 0 casts, a segment
        // of zero area (it is edge-on), so its shadow triangles are flat.
        let tri = Mesh {
            positions: vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)],
            normals: vec![Vec3::Z; 3],
            triangles: vec![[0, 1, 2]],
            ..empty_mesh()
        };
        let wall = Object { mesh: Arc::new(tri), ..quad(0.0, 1.0) };
        let sun = Light::Directional { direction: Vec3::new(0.0, -1.0, -1.0), color: Vec3::ONE };
        let mut out = empty_mesh();
        project_casters(
            &ground(),
            &sun,
            (&quad(0.0, 10.0), [wall].iter()),
            (&mut out, &mut CasterScratch::default()),
        );
        // The cut is the triangle's tip above y = 0: (±0.5, 0, 0) and (0, 1, 0),
        // whose tip falls along (0, −1, −1) to (0, 0, −1).
        let (lo, hi) = bounds(&out);
        assert!((lo - Vec3::new(-0.5, 0.0, -1.0)).abs().max_element() < 1e-6, "{lo}");
        assert!((hi - Vec3::new(0.5, 0.0, 0.0)).abs().max_element() < 1e-6, "{hi}");
    }

    #[test]
    fn bits_run_out_at_32() {
        assert_eq!(pairs(2, 3).collect::<Vec<_>>().len(), 6);
        assert_eq!(pairs(5, 8).count(), 32);
        assert_eq!(pairs(5, 8).last(), Some((3, 7, 31)));
        assert_eq!(first_bit(4, 8), None);
        assert_eq!(pairs(1, 40).count(), 32);
    }
}

//! Procedural meshes: UV sphere, plane, cube and torus.
//!
//! Contract: every primitive is centred on the origin, front faces are
//! counter-clockwise seen from outside (so the geometric normal of every
//! triangle points outwards, SPEC §2), and vertex normals are the analytic
//! surface normals, not averaged face normals. Counts below their minimum
//! are raised to it; a non-finite size is taken as 1, so a primitive always
//! upholds [`Mesh`]'s invariants. The material is [`Material::DEFAULT`].

use std::f32::consts::{PI, TAU};

use glam::Vec3;
use zline_shading::Material;

use crate::model::Mesh;

/// A sphere of `rings` latitude bands (≥ 2) and `segments` longitude
/// slices (≥ 3). The poles are single vertices with triangle fans, so there
/// are `2 · segments · (rings − 1)` triangles.
pub fn uv_sphere(rings: u32, segments: u32, radius: f32) -> Mesh {
    let (rings, segments, radius) = (rings.max(2), segments.max(3), finite_or_one(radius));
    let mut directions = vec![Vec3::Y];
    for i in 1..rings {
        let theta = PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = TAU * j as f32 / segments as f32;
            directions.push(Vec3::new(theta.sin() * phi.sin(), theta.cos(), theta.sin() * phi.cos()));
        }
    }
    directions.push(Vec3::NEG_Y);
    let south = directions.len() as u32 - 1;
    let row = |i: u32, j: u32| 1 + (i - 1) * segments + j % segments;
    let mut triangles = Vec::with_capacity(2 * (segments * (rings - 1)) as usize);
    // Ring by ring, like the vertices, so consecutive triangles share
    // vertices that are close in memory.
    triangles.extend((0..segments).map(|j| [0, row(1, j), row(1, j + 1)]));
    for i in 1..rings - 1 {
        for j in 0..segments {
            let (a, b, c, d) = (row(i, j), row(i + 1, j), row(i + 1, j + 1), row(i, j + 1));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    triangles.extend((0..segments).map(|j| [south, row(rings - 1, j + 1), row(rings - 1, j)]));
    let positions = directions.iter().map(|&d| d * radius).collect();
    primitive("sphere", positions, directions, triangles)
}

/// A square of side `size` in the XZ plane, facing +Y, split into
/// `subdivisions` × `subdivisions` (≥ 1) cells of two triangles each.
pub fn plane(size: f32, subdivisions: u32) -> Mesh {
    let (n, size) = (subdivisions.max(1), finite_or_one(size));
    let coord = |i: u32| size * (i as f32 / n as f32 - 0.5);
    let mut positions = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for k in 0..=n {
        for i in 0..=n {
            positions.push(Vec3::new(coord(i), 0.0, coord(k)));
        }
    }
    let index = |i: u32, k: u32| k * (n + 1) + i;
    let mut triangles = Vec::with_capacity((2 * n * n) as usize);
    for k in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (index(i, k), index(i, k + 1), index(i + 1, k + 1), index(i + 1, k));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    let normals = vec![Vec3::Y; positions.len()];
    primitive("plane", positions, normals, triangles)
}

/// An axis-aligned cube of edge `size`: 6 flat faces of 4 vertices each
/// (24 vertices, 12 triangles), each vertex carrying its face's normal.
pub fn cube(size: f32) -> Mesh {
    let h = finite_or_one(size) / 2.0;
    // (normal, u, v) with u × v = normal, so u then v turns counter-clockwise.
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::Y, Vec3::X),
    ];
    let (mut positions, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for (n, u, v) in faces {
        let base = positions.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            positions.push((n + u * su + v * sv) * h);
            normals.push(n);
        }
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }
    primitive("cube", positions, normals, triangles)
}

/// A torus around the Y axis: a tube of radius `minor_radius` whose centre
/// follows a circle of radius `major_radius` in the XZ plane, with `rings`
/// (≥ 3) steps around the Y axis and `segments` (≥ 3) around the tube.
pub fn torus(major_radius: f32, minor_radius: f32, rings: u32, segments: u32) -> Mesh {
    let (rings, segments) = (rings.max(3), segments.max(3));
    let (major, minor) = (finite_or_one(major_radius), finite_or_one(minor_radius));
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    for i in 0..rings {
        let phi = TAU * i as f32 / rings as f32;
        let radial = Vec3::new(phi.sin(), 0.0, phi.cos());
        for j in 0..segments {
            let theta = TAU * j as f32 / segments as f32;
            let n = radial * theta.cos() + Vec3::Y * theta.sin();
            positions.push(radial * major + n * minor);
            normals.push(n);
        }
    }
    let index = |i: u32, j: u32| (i % rings) * segments + j % segments;
    let mut triangles = Vec::with_capacity((2 * rings * segments) as usize);
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j));
            triangles.extend([[a, d, c], [a, c, b]]);
        }
    }
    primitive("torus", positions, normals, triangles)
}

fn finite_or_one(x: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        1.0
    }
}

/// Assembles a primitive; the arrays are valid by construction.
fn primitive(name: &str, positions: Vec<Vec3>, normals: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh {
        name: name.to_owned(),
        positions,
        normals,
        triangles,
        material: Material::DEFAULT,
        uvs: Vec::new(),
        colors: Vec::new(),
        diffuse_map: None,
        tangents: Vec::new(),
        normal_map: None,
        surface_maps: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::face_normal;

    #[test]
    fn closedness_of_known_meshes() {
        assert!(uv_sphere(8, 12, 1.0).is_closed());
        assert!(cube(1.0).is_closed(), "split vertices at the corners still close the cube");
        assert!(!plane(1.0, 2).is_closed());
        let mut flipped = uv_sphere(8, 12, 1.0);
        flipped.triangles[3].swap(1, 2);
        assert!(!flipped.is_closed(), "one triangle facing the other way");
        let mut doubled = uv_sphere(8, 12, 1.0);
        doubled.triangles.push(doubled.triangles[0]);
        assert!(!doubled.is_closed(), "a triangle used twice");
    }

    /// Every triangle is non-degenerate, its geometric normal agrees with
    /// its vertex normals and points away from `inside(centroid)`.
    #[track_caller]
    fn check_outward(mesh: &Mesh, inside: impl Fn(Vec3) -> Vec3) {
        assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = mesh.triangle(t);
            let n =
                face_normal(a, b, c).unwrap_or_else(|| panic!("{}: triangle {t} is degenerate", mesh.name));
            for &i in tri {
                let dot = n.dot(mesh.normals[i as usize]);
                assert!(dot > 0.0, "{}: triangle {t} faces against vertex {i}'s normal", mesh.name);
            }
            let centroid = (a + b + c) / 3.0;
            assert!(n.dot(centroid - inside(centroid)) > 0.0, "{}: triangle {t} faces inwards", mesh.name);
        }
    }

    #[test]
    fn sphere_faces_outwards_with_the_promised_count() {
        for (rings, segments) in [(2, 3), (8, 12), (32, 64)] {
            let s = uv_sphere(rings, segments, 2.0);
            assert_eq!(s.triangle_count() as u32, 2 * segments * (rings - 1));
            check_outward(&s, |_| Vec3::ZERO);
            assert!(s.positions.iter().all(|p| (p.length() - 2.0).abs() < 1e-5));
        }
    }

    #[test]
    fn plane_faces_up() {
        let p = plane(4.0, 3);
        assert_eq!((p.vertex_count(), p.triangle_count()), (16, 18));
        check_outward(&p, |c| c - Vec3::Y);
        assert_eq!(p.bounds(), (Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0)));
    }

    #[test]
    fn cube_faces_outwards() {
        let c = cube(2.0);
        assert_eq!((c.vertex_count(), c.triangle_count()), (24, 12));
        check_outward(&c, |_| Vec3::ZERO);
        assert_eq!(c.bounds(), (Vec3::splat(-1.0), Vec3::splat(1.0)));
    }

    #[test]
    fn torus_faces_outwards_from_its_tube() {
        let t = torus(2.0, 0.5, 24, 12);
        assert_eq!(t.triangle_count(), 2 * 24 * 12);
        check_outward(&t, |c| Vec3::new(c.x, 0.0, c.z).normalize() * 2.0);
    }

    #[test]
    fn silly_parameters_still_give_valid_meshes() {
        for mesh in
            [uv_sphere(0, 0, f32::NAN), plane(f32::INFINITY, 0), cube(f32::NAN), torus(1.0, 0.2, 0, 1)]
        {
            let rebuilt = Mesh::new(
                "x",
                mesh.positions.clone(),
                Some(mesh.normals.clone()),
                mesh.triangles.clone(),
                mesh.material,
            );
            assert_eq!(rebuilt.map(|m| m.positions), Ok(mesh.positions));
        }
    }
}

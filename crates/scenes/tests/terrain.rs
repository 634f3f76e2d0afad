//! The terrain simplification: planar fields collapse, τ = 0 keeps the full
//! grid, the mesh has no cracks, and the projected vertical error at every
//! grid sample stays within the bound.

use std::collections::HashMap;

use glam::{Vec3, Vec4Swizzles};
use proptest::prelude::*;
use zline_scene::{Camera, HeightField};
use zline_scenes::terrain::{
    fit_camera, full_grid_triangles, ramp_color, terrain_mesh, ErrorPyramid, SimplifiedGrid, Surface,
    ViewError,
};

fn field(columns: usize, rows: usize, f: impl Fn(usize, usize) -> f32) -> HeightField {
    let heights = (0..rows).flat_map(|j| (0..columns).map(move |i| (i, j))).map(|(i, j)| f(i, j)).collect();
    HeightField::new(columns, rows, heights, 1.0).unwrap()
}

/// A deterministic pseudo-random height in [0, 1).
fn noise(seed: u64, i: usize, j: usize) -> f32 {
    let mut x = seed
        ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 29;
    (x >> 40) as f32 / (1u64 << 24) as f32
}

fn simplify(field: &HeightField, tolerance: f32, size: (u32, u32)) -> (SimplifiedGrid, Camera) {
    let camera = fit_camera(field, size.0 as f32 / size.1 as f32);
    let view = ViewError::new(&camera, size.0, size.1, tolerance);
    (ErrorPyramid::new(field).simplify(&view), camera)
}

#[test]
fn a_planar_field_collapses_to_two_triangles_at_any_tolerance() {
    // Dyadic slopes: every midpoint is exactly the mean of its ends.
    let plane = field(33, 33, |i, j| 0.25 * i as f32 - 0.75 * j as f32 + 5.0);
    for tolerance in [0.0, 0.25, 1.0, 100.0] {
        let (grid, _) = simplify(&plane, tolerance, (640, 480));
        assert_eq!(grid.triangles.len(), 2, "tolerance {tolerance}");
        assert_eq!(grid.vertices.len(), 4);
    }
    // Other slopes leave f32 rounding (~1e-6) in the midpoints, far below
    // any pixel; only the top vertices, whose spheres hold the eye's
    // surroundings (an infinite bound), may still split.
    let plane = field(65, 65, |i, j| 0.3 * i as f32 - 0.7 * j as f32 + 5.0);
    for tolerance in [0.01, 1.0] {
        let n = simplify(&plane, tolerance, (640, 480)).0.triangles.len();
        assert!(n <= 8, "tolerance {tolerance}: {n} triangles");
    }
}

#[test]
fn tolerance_zero_keeps_the_full_grid() {
    for (c, r) in [(17, 17), (33, 9), (11, 7), (2, 2), (3, 40)] {
        let rough = field(c, r, |i, j| noise(7, i, j));
        let (grid, _) = simplify(&rough, 0.0, (320, 240));
        assert_eq!(grid.triangles.len(), full_grid_triangles(&rough), "{c} x {r}");
        assert_eq!(grid.vertices.len(), c * r, "{c} x {r}");
    }
}

#[test]
fn a_larger_tolerance_draws_fewer_triangles() {
    let hills = field(129, 129, |i, j| {
        (i as f32 * 0.05).sin() * (j as f32 * 0.07).cos() * 8.0 + noise(1, i, j) * 0.1
    });
    let counts: Vec<usize> =
        [0.0, 0.5, 2.0, 8.0].iter().map(|&t| simplify(&hills, t, (640, 480)).0.triangles.len()).collect();
    assert!(counts.windows(2).all(|w| w[0] > w[1]), "{counts:?}");
    assert_eq!(counts[0], 2 * 128 * 128);
}

/// Every interior edge is used once in each direction (two triangles, the
/// same winding), every border edge once, every triangle faces up, and the
/// triangles cover the grid's area exactly.
fn check_no_cracks(field: &HeightField, grid: &SimplifiedGrid) -> Result<(), TestCaseError> {
    let (w, h) = ((field.columns() - 1) as u32, (field.rows() - 1) as u32);
    let mut edges: HashMap<([u32; 2], [u32; 2]), usize> = HashMap::new();
    let mut area2 = 0i64;
    for t in &grid.triangles {
        let p = t.map(|i| grid.vertices[i as usize]);
        let [a, b, c] = p.map(|[x, y]| (i64::from(x), i64::from(y)));
        // Counter-clockwise seen from above (+y) with x east, z = row south:
        // the cross product's y component is z_u·x_v − x_u·z_v.
        let cross = (b.1 - a.1) * (c.0 - a.0) - (b.0 - a.0) * (c.1 - a.1);
        prop_assert!(cross > 0, "triangle {p:?} is degenerate or faces down");
        area2 += cross;
        for k in 0..3 {
            *edges.entry((p[k], p[(k + 1) % 3])).or_default() += 1;
        }
    }
    prop_assert_eq!(area2, 2 * i64::from(w) * i64::from(h));
    for (&(a, b), &n) in &edges {
        prop_assert_eq!(n, 1, "edge {:?}-{:?} used {} times one way", a, b, n);
        let border = (a[0] == b[0] && (a[0] == 0 || a[0] == w)) || (a[1] == b[1] && (a[1] == 0 || a[1] == h));
        let twin = edges.contains_key(&(b, a));
        prop_assert!(border != twin, "edge {a:?}-{b:?}: border {border}, shared {twin}");
    }
    Ok(())
}

/// The window position of a world point.
fn project(camera: &Camera, size: (u32, u32), p: Vec3) -> glam::Vec2 {
    let aspect = size.0 as f32 / size.1 as f32;
    let clip = camera.clip_from_eye(aspect) * camera.eye_from_world() * p.extend(1.0);
    let ndc = clip.xy() / clip.w;
    glam::Vec2::new((ndc.x + 1.0) / 2.0 * size.0 as f32, (ndc.y + 1.0) / 2.0 * size.1 as f32)
}

/// At every grid sample, the simplified surface's height (the triangle
/// holding it, interpolated) is within `tolerance` pixels of the sample's
/// own height, once both are projected; and every sample is covered.
fn check_error_bound(
    field: &HeightField,
    grid: &SimplifiedGrid,
    camera: &Camera,
    size: (u32, u32),
    tolerance: f32,
) -> Result<(), TestCaseError> {
    let (c, r) = (field.columns(), field.rows());
    let origin = -glam::Vec2::new((c - 1) as f32, (r - 1) as f32) * field.cell_size() / 2.0;
    let world = |x: f64, y: f64, h: f32| {
        Vec3::new(origin.x + x as f32 * field.cell_size(), h, origin.y + y as f32 * field.cell_size())
    };
    let mut covered = vec![false; c * r];
    let mut worst = 0.0f32;
    for t in &grid.triangles {
        let p = t.map(|i| grid.vertices[i as usize].map(|v| v as usize));
        let hs = p.map(|[x, y]| f64::from(field.at(x, y)));
        let (x0, x1) = (p.iter().map(|v| v[0]).min().unwrap(), p.iter().map(|v| v[0]).max().unwrap());
        let (y0, y1) = (p.iter().map(|v| v[1]).min().unwrap(), p.iter().map(|v| v[1]).max().unwrap());
        let f = p.map(|[x, y]| (x as f64, y as f64));
        let det = (f[1].0 - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (f[1].1 - f[0].1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (px, py) = (x as f64, y as f64);
                let l1 = ((px - f[0].0) * (f[2].1 - f[0].1) - (f[2].0 - f[0].0) * (py - f[0].1)) / det;
                let l2 = ((f[1].0 - f[0].0) * (py - f[0].1) - (px - f[0].0) * (f[1].1 - f[0].1)) / det;
                let l0 = 1.0 - l1 - l2;
                if l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9 {
                    continue;
                }
                covered[y * c + x] = true;
                let mesh = (l0 * hs[0] + l1 * hs[1] + l2 * hs[2]) as f32;
                let a = project(camera, size, world(px, py, field.at(x, y)));
                let b = project(camera, size, world(px, py, mesh));
                let inside =
                    |p: glam::Vec2| p.x >= 0.0 && p.y >= 0.0 && p.x <= size.0 as f32 && p.y <= size.1 as f32;
                prop_assert!(inside(a), "sample ({x}, {y}) projects outside the image, to {a}");
                worst = worst.max(a.distance(b));
            }
        }
    }
    prop_assert!(covered.iter().all(|&c| c), "a grid sample lies in no triangle");
    prop_assert!(worst <= tolerance * 1.001 + 1e-3, "projected error {worst} px > {tolerance} px");
    Ok(())
}

#[test]
fn the_mesh_takes_grid_normals_ramp_colours_or_draped_uvs() {
    // h = 2·column: a slope rising east, 3 columns × 2 rows, 0.5 m cells.
    let slope = HeightField::new(3, 2, vec![0.0, 2.0, 4.0, 0.0, 2.0, 4.0], 0.5).unwrap();
    let (grid, _) = simplify(&slope, 1.0, (64, 48));
    let mesh = terrain_mesh(&slope, &grid, &Surface::HeightRamp).unwrap();
    for (v, &[x, y]) in grid.vertices.iter().enumerate() {
        let expect = Vec3::new(-0.5 + 0.5 * x as f32, 2.0 * x as f32, -0.25 + 0.5 * y as f32);
        assert_eq!(mesh.positions[v], expect);
        // ∂h/∂x = 2 / 0.5 = 4: the normal (−4, 1, 0), normalized.
        assert!(mesh.normals[v].abs_diff_eq(Vec3::new(-4.0, 1.0, 0.0).normalize(), 1e-6));
        assert_eq!(mesh.colors[v], ramp_color(x as f32 / 2.0));
    }
    let texture = zline_scene::TextureMap {
        texture: std::sync::Arc::new(zline_shading::Texture::solid(glam::Vec4::ONE)),
        sampler: Default::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    };
    let draped = terrain_mesh(&slope, &grid, &Surface::Texture(texture)).unwrap();
    for (v, &[x, y]) in grid.vertices.iter().enumerate() {
        // s east, t north: the image's top row on the north edge (row 0).
        assert_eq!(draped.uvs[v], glam::Vec2::new(x as f32 / 2.0, 1.0 - y as f32));
    }
    assert!(draped.colors.is_empty() && draped.diffuse_map.is_some());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_fields_simplify_without_cracks_and_within_the_bound(
        c in 2usize..40,
        r in 2usize..40,
        seed in any::<u64>(),
        relief in 0.0f32..20.0,
        steps in 0u32..4,
        tolerance in prop_oneof![Just(0.0f32), 0.1f32..4.0],
        wide in any::<bool>(),
    ) {
        // Quantized heights make flat patches (δ = 0) as well as rough ones.
        let levels = [0.0, 2.0, 5.0, 1e6][steps as usize];
        let rough = field(c, r, |i, j| {
            let v = noise(seed, i, j) * relief;
            if levels > 0.0 && levels < 1e6 { (v * levels).round() / levels } else { v }
        });
        let size = if wide { (640, 360) } else { (200, 300) };
        let (grid, camera) = simplify(&rough, tolerance, size);
        check_no_cracks(&rough, &grid)?;
        check_error_bound(&rough, &grid, &camera, size, tolerance)?;
    }
}

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

mod pyramid;

/// The vertical field of view of the fitted camera, in degrees.
pub const TERRAIN_FOVY_DEGREES: f32 = 40.0;
/// The default screen-space error bound, in pixels.
pub const DEFAULT_TERRAIN_ERROR: f32 = 1.0;
/// The sky: background and fog colour.
pub const SKY: Vec3 = Vec3::new(0.66, 0.76, 0.88);

pub use pyramid::{ErrorPyramid, SimplifiedGrid, ViewError};

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
        environment: None,
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

//! Scenes whose answers are computed here from the SPEC formulas, in f64,
//! independently of the truth's code.

use glam::{DVec2, DVec3, Vec3};
use zline_scene::{Camera, GouraudClamp, LightingSides, Projection, RenderSettings, Scene};
use zline_shading::{Attenuation, Fog, FogCoordinate, FogMode, Light, Material, ShadingMode};
use zline_truth::{render_truth, TruthImage};

use crate::support::{
    check_close, d, emissive, mesh, object, parts, scene, square, AMBIENT, ATTENUATION, F64_TOLERANCE, LIGHT,
    LIGHT_COLOR,
};

const MATERIAL: Material = Material {
    ke: Vec3::ZERO,
    ka: Vec3::new(0.3, 0.4, 0.5),
    kd: Vec3::new(0.7, 0.45, 0.3),
    ks: Vec3::new(0.5, 0.5, 0.5),
    ns: 12.0,
    opacity: 1.0,
    model: zline_shading::Model::Basic,
    ..Material::DEFAULT
};

/// SPEC §5 for the one point light, eye at the origin, clamped.
fn lighting(p: DVec3, n: DVec3) -> DVec3 {
    let (ambient_diffuse, specular) = parts(&MATERIAL, p, n);
    (ambient_diffuse + specular).clamp(DVec3::ZERO, DVec3::ONE)
}

fn lit_square(mode: ShadingMode) -> TruthImage {
    let light = Light::Point { position: LIGHT, color: LIGHT_COLOR, attenuation: ATTENUATION };
    let mut s =
        scene(64, AMBIENT, vec![light], vec![object(square(0.0, 0.0, 1.0, -2.0, MATERIAL), Some(mode))]);
    s.objects[0].cull_back_faces = true;
    render_truth(&s)
}

/// Pixel (32, 32) of a 64×64 image: its sample at window (32.5, 32.5) is
/// NC (1/64, −1/64); on the square at z = −2 (fovy 90°) that is eye point
/// (1/32, −1/32, −2), right of the diagonal, in the triangle (−1, −1),
/// (1, −1), (1, 1). Flat: lit at that triangle's centroid; Gouraud: its
/// vertex colours blended by the point's barycentric weights; Phong: lit at
/// the point.
#[test]
fn lit_square_centre_pixel_in_each_mode() {
    let p = DVec3::new(1.0 / 32.0, -1.0 / 32.0, -2.0);
    let corners = [DVec2::new(-1.0, -1.0), DVec2::new(1.0, -1.0), DVec2::new(1.0, 1.0)];
    let eye = |c: DVec2| c.extend(-2.0);
    // Barycentric weights of p in the lower-right triangle (in its plane,
    // where perspective-correct interpolation is exact).
    let area = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let total = area(corners[0], corners[1], corners[2]);
    let q = p.truncate();
    let w = [
        area(q, corners[1], corners[2]) / total,
        area(corners[0], q, corners[2]) / total,
        area(corners[0], corners[1], q) / total,
    ];
    let centroid = (eye(corners[0]) + eye(corners[1]) + eye(corners[2])) / 3.0;
    let gouraud: DVec3 = (0..3).map(|k| lighting(eye(corners[k]), DVec3::Z) * w[k]).sum();
    for (mode, want) in [
        (ShadingMode::Flat, lighting(centroid, DVec3::Z)),
        (ShadingMode::Gouraud, gouraud),
        (ShadingMode::Phong, lighting(p, DVec3::Z)),
    ] {
        check_close(lit_square(mode).pixel(32, 32), want, F64_TOLERANCE);
    }
    // The modes really differ here, so the test tells them apart.
    assert!((lighting(centroid, DVec3::Z) - lighting(p, DVec3::Z)).abs().max_element() > 0.01);
    assert!((gouraud - lighting(p, DVec3::Z)).abs().max_element() > 0.001);
}

/// The lit square's centre pixel (as in `lit_square_centre_pixel_in_each_mode`)
/// with an emission of 0.75 that lifts the vertex nearest the light above 1
/// in red and leaves the farthest below: Gouraud clamped per vertex blends
/// the clamped vertex colours, clamped per sample clamps the blend of the
/// unclamped ones (SPEC §11).
#[test]
fn gouraud_clamped_per_vertex_or_per_sample() {
    let m = Material { ke: Vec3::splat(0.75), ..MATERIAL };
    let unclamped = |c: DVec2| {
        let (ambient_diffuse, specular) = parts(&m, c.extend(-2.0), DVec3::Z);
        ambient_diffuse + specular
    };
    let corners = [DVec2::new(-1.0, -1.0), DVec2::new(1.0, -1.0), DVec2::new(1.0, 1.0)];
    let lit = corners.map(unclamped);
    assert!(lit[2].x > 1.05 && lit[0].x < 0.95, "{lit:?}");
    // Barycentric weights of eye point (1/32, −1/32, −2) in that triangle:
    // areas of the sub-triangles opposite each corner over the whole (4).
    let w = [31.0 / 64.0, 2.0 / 64.0, 31.0 / 64.0];
    let clamp = |c: DVec3| c.clamp(DVec3::ZERO, DVec3::ONE);
    let per_vertex: DVec3 = (0..3).map(|k| clamp(lit[k]) * w[k]).sum();
    let per_sample = clamp((0..3).map(|k| lit[k] * w[k]).sum());
    assert!((per_vertex - per_sample).abs().max_element() > 0.01, "the readings differ");
    for (reading, want) in [(GouraudClamp::PerVertex, per_vertex), (GouraudClamp::PerSample, per_sample)] {
        let light = Light::Point { position: LIGHT, color: LIGHT_COLOR, attenuation: ATTENUATION };
        let square = square(0.0, 0.0, 1.0, -2.0, m);
        let mut s = scene(64, AMBIENT, vec![light], vec![object(square, Some(ShadingMode::Gouraud))]);
        s.settings.gouraud_clamp = reading;
        check_close(render_truth(&s).pixel(32, 32), want, F64_TOLERANCE);
    }
}

/// The lit square wound the other way with normals −z, culling off: its
/// front faces away from the viewer, and the light is on the viewer's
/// side. Two-sided lighting turns the normals to +z and lights it like the
/// front; one-sided lighting leaves N·L < 0, so only ka·Ia remains, in
/// every shading mode (SPEC §11).
#[test]
fn a_back_face_lit_two_sided_or_one_sided() {
    let front = square(0.0, 0.0, 1.0, -2.0, MATERIAL);
    let back = mesh(
        front.positions.clone(),
        vec![-Vec3::Z; 4],
        front.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        MATERIAL,
    );
    let light = Light::Point { position: LIGHT, color: LIGHT_COLOR, attenuation: ATTENUATION };
    let p = DVec3::new(1.0 / 32.0, -1.0 / 32.0, -2.0);
    for mode in [ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong] {
        let mut s = scene(64, AMBIENT, vec![light], vec![object(back.clone(), Some(mode))]);
        let two_sided = render_truth(&s).pixel(32, 32);
        s.settings.lighting_sides = LightingSides::OneSided;
        let one_sided = render_truth(&s).pixel(32, 32);
        check_close(two_sided, lit_square(mode).pixel(32, 32), F64_TOLERANCE);
        check_close(one_sided, d(MATERIAL.ka) * d(AMBIENT), F64_TOLERANCE);
        if mode == ShadingMode::Phong {
            check_close(two_sided, lighting(p, DVec3::Z), F64_TOLERANCE);
        }
        assert!((two_sided - one_sided).abs().max_element() > 0.05, "{mode:?}: the readings differ");
    }
}

/// An orthographic camera whose window coordinates are (x, 16 − y) for
/// world (x, y) on a 16×16 image.
fn pixel_camera() -> Camera {
    Camera {
        eye: Vec3::new(8.0, 8.0, 10.0),
        target: Vec3::new(8.0, 8.0, 0.0),
        up: Vec3::Y,
        projection: Projection::Orthographic { height: 16.0, near: 1.0, far: 20.0 },
    }
}

/// A transparent 2×2 grid of quads (8 triangles, diagonals both ways) with
/// every vertex on a sample centre: shared vertical, horizontal and
/// diagonal edges all pass through samples. Each sample inside must be
/// blended exactly once: 0.5·colour over black; twice would give 0.75, never
/// 0. Left and top edges are in, right and bottom edges out, so pixels
/// 2..13 along both axes are covered.
#[test]
fn shared_edges_cover_every_sample_exactly_once() {
    let (xs, ys) = ([2.5f32, 7.5, 13.5], [2.5f32, 8.5, 13.5]);
    let mut positions = Vec::new();
    for &y in &ys {
        for &x in &xs {
            positions.push(Vec3::new(x, 16.0 - y, 0.0));
        }
    }
    let at = |i: u32, j: u32| j * 3 + i;
    let mut triangles = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            // Window y points down, so (a, e, c) is counter-clockwise on screen.
            if (i + j) % 2 == 0 {
                triangles.extend([[a, e, c], [a, c, b]]);
            } else {
                triangles.extend([[a, e, b], [b, e, c]]);
            }
        }
    }
    let color = Vec3::new(0.8, 0.6, 0.4);
    let m = mesh(positions, vec![Vec3::Z; 9], triangles, emissive(color, 0.5));
    let mut s = scene(16, Vec3::ONE, vec![], vec![object(m, None)]);
    s.camera = pixel_camera();
    let truth = render_truth(&s);
    for y in 0..16 {
        for x in 0..16 {
            let inside = (2..13).contains(&x) && (2..13).contains(&y);
            let want = if inside { d(color) * 0.5 } else { DVec3::ZERO };
            check_close(truth.pixel(x, y), want, F64_TOLERANCE);
        }
    }
    // The fast renderer agrees bit for bit (0.4, 0.3, 0.2 are far from
    // rounding boundaries: 102, 76.5 → 77, 51).
    let fast = zline_pipeline::render(&s, &zline_pipeline::RenderOptions::default()).0;
    assert_eq!(fast.to_rgb(), truth.quantized_rgb8());
}

/// A triangle with a vertex behind the eye: every drawn pixel is one whose
/// ray hits the triangle in front of the near plane, and every such pixel
/// is drawn, judged by an independent ray cast (pixels whose ray passes
/// within 10⁻⁶ of an edge are skipped).
#[test]
fn near_plane_crossing_triangle_has_no_stray_pixels() {
    let corners = [Vec3::new(-1.5, -1.0, -2.0), Vec3::new(1.5, -1.0, -2.0), Vec3::new(0.3, 1.5, 1.0)];
    // Behind the eye, and exactly on the eye plane (w = 0).
    for (behind, size) in [(corners[2], 40), (Vec3::new(0.3, 1.2, 0.0), 41)] {
        let c = [corners[0], corners[1], behind];
        let m = mesh(c.to_vec(), vec![Vec3::Z; 3], vec![[0, 1, 2]], emissive(Vec3::ONE, 1.0));
        let s = scene(size, Vec3::ONE, vec![], vec![object(m, None)]);
        let truth = render_truth(&s);
        let (mut drawn, mut checked) = (0, 0);
        for y in 0..size {
            for x in 0..size {
                // The ray through the pixel centre: direction (x_nc, y_nc, −1).
                let nc = DVec2::new(
                    (f64::from(x) + 0.5) / f64::from(size) * 2.0 - 1.0,
                    1.0 - (f64::from(y) + 0.5) / f64::from(size) * 2.0,
                );
                let Some(hit) = ray_hit(nc.extend(-1.0), c.map(|p| p.as_dvec3())) else { continue };
                checked += 1;
                let expect = hit.0 && hit.1 <= -0.5;
                let got = truth.pixel(x, y) != DVec3::ZERO;
                assert_eq!(got, expect, "pixel ({x}, {y}) of the {size}² image");
                drawn += usize::from(got);
            }
        }
        assert!(
            drawn > 50 && checked > size as usize * size as usize * 9 / 10,
            "{drawn} drawn, {checked} checked"
        );
    }
}

/// Intersects the ray t·dir (t > 0) with triangle `c`: (inside, z of the
/// hit); `None` when the hit is within 10⁻⁶ (barycentric) of an edge, when
/// the ray is parallel, or when the hit is on the near plane (z = −0.5).
fn ray_hit(dir: DVec3, c: [DVec3; 3]) -> Option<(bool, f64)> {
    let (e1, e2) = (c[1] - c[0], c[2] - c[0]);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = -c[0];
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    let bary = [1.0 - u - v, u, v];
    if bary.iter().any(|b| b.abs() < 1e-6) || (t * dir.z + 0.5).abs() < 1e-9 {
        return None;
    }
    Some((t > 0.0 && bary.iter().all(|&b| b > 0.0), t * dir.z))
}

/// Exponential fog on a square at z = −4: the centre colour is
/// f·C + (1 − f)·C_fog with f = e^(−ρ·4) (eye-plane coordinate); the
/// background stays unfogged. Radial fog uses the distance to the eye.
#[test]
fn fog_factor_at_a_pixel() {
    let color = Vec3::new(0.9, 0.2, 0.1);
    let fog_color = Vec3::new(0.5, 0.6, 0.7);
    let mut s =
        scene(64, Vec3::ONE, vec![], vec![object(square(0.0, 0.0, 1.0, -4.0, emissive(color, 1.0)), None)]);
    s.background = Vec3::new(0.1, 0.1, 0.1);
    for coordinate in [FogCoordinate::EyePlane, FogCoordinate::Radial] {
        s.fog = Some(Fog { mode: FogMode::Exponential { density: 0.25 }, color: fog_color, coordinate });
        let truth = render_truth(&s);
        // Pixel (37, 28): sample at NC (0.171875, 0.109375), on the square at
        // eye point (4·0.171875, 4·0.109375, −4).
        let p = DVec3::new(4.0 * 0.171875, 4.0 * 0.109375, -4.0);
        let z = if coordinate == FogCoordinate::EyePlane { 4.0 } else { p.length() };
        let f = (-0.25 * z).exp();
        check_close(truth.pixel(37, 28), d(color) * f + d(fog_color) * (1.0 - f), F64_TOLERANCE);
        check_close(truth.pixel(2, 2), d(s.background), 0.0);
    }
}

/// A transparent square (opacity 0.25) in front of part of an opaque one:
/// C = 0.25·C_t + 0.75·C_behind, with C_behind the opaque colour or the
/// background.
#[test]
fn transparent_square_over_an_opaque_one() {
    let (front, back, bg) = (Vec3::new(0.2, 0.9, 0.4), Vec3::new(0.8, 0.1, 0.3), Vec3::new(0.0, 0.0, 0.5));
    let objects = vec![
        object(square(0.5, 0.0, 1.0, -3.0, emissive(front, 0.25)), None),
        object(square(-0.5, 0.0, 1.0, -4.0, emissive(back, 1.0)), None),
    ];
    let mut s = scene(64, Vec3::ONE, vec![], objects);
    s.background = bg;
    let truth = render_truth(&s);
    let keep = f64::from(0.25f32);
    // Pixel 34 (NC x ≈ 0.078): both squares (front spans NC [−1/6, 1/2],
    // back [−3/8, 1/8]). Pixel 44 (NC ≈ 0.39): front only. Pixel 22 (NC ≈
    // −0.30): back only. Row 32 is inside both vertically.
    check_close(truth.pixel(34, 32), d(front) * keep + d(back) * (1.0 - keep), F64_TOLERANCE);
    check_close(truth.pixel(44, 32), d(front) * keep + d(bg) * (1.0 - keep), F64_TOLERANCE);
    check_close(truth.pixel(22, 32), d(back), F64_TOLERANCE);
    check_close(truth.pixel(2, 32), d(bg), 0.0);
}

/// Supersampling: with ssaa = 2 a vertical edge at window x = 10.5 splits
/// pixel 10's samples (10.25 out, 10.75 in): its colour is the mean, half
/// the square's colour and half the background.
#[test]
fn supersampling_averages_the_samples() {
    let color = Vec3::new(1.0, 0.5, 0.25);
    let x0 = 10.5;
    let positions = vec![
        Vec3::new(x0, 2.0, 0.0),
        Vec3::new(14.0, 2.0, 0.0),
        Vec3::new(14.0, 14.0, 0.0),
        Vec3::new(x0, 14.0, 0.0),
    ];
    let m = mesh(positions, vec![Vec3::Z; 4], vec![[0, 1, 2], [0, 2, 3]], emissive(color, 1.0));
    let mut s = Scene { camera: pixel_camera(), ..scene(16, Vec3::ONE, vec![], vec![object(m, None)]) };
    s.settings = RenderSettings { ssaa: 2, ..s.settings };
    let truth = render_truth(&s);
    check_close(truth.pixel(10, 8), d(color) * 0.5, F64_TOLERANCE);
    check_close(truth.pixel(11, 8), d(color), F64_TOLERANCE);
    check_close(truth.pixel(9, 8), DVec3::ZERO, 0.0);
    // Rows: y from 2 to 14 in window space; row 1 is out, rows 2..14 are in.
    check_close(truth.pixel(12, 1), DVec3::ZERO, 0.0);
    check_close(truth.pixel(12, 13), d(color), F64_TOLERANCE);
}

/// Gouraud with a white 1×1 texture is Gouraud without one: texel ⊙
/// (ambient+diffuse) + specular, clamped, against the clamped vertex
/// colours — equal wherever no vertex colour exceeds 1 — also on a
/// triangle crossing the near plane, whose new vertices carry interpolated
/// lit parts (SPEC §2), not relit ones.
#[test]
fn white_texture_leaves_gouraud_unchanged_even_when_clipped() {
    use std::sync::Arc;
    use zline_scene::TextureMap;
    use zline_shading::{Sampler, Texture};
    let white = TextureMap {
        texture: Arc::new(Texture::solid(glam::Vec4::ONE)),
        sampler: Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    };
    let positions = vec![Vec3::new(-2.0, -1.0, -3.0), Vec3::new(2.0, -1.0, -3.0), Vec3::new(0.0, -1.0, 2.0)];
    let normals = vec![Vec3::new(-0.8, 0.6, 0.0), Vec3::new(0.8, 0.6, 0.0), Vec3::new(0.0, 0.6, 0.8)];
    let material = Material {
        ka: Vec3::ZERO,
        kd: Vec3::splat(0.4),
        ks: Vec3::splat(0.3),
        ns: 8.0,
        opacity: 1.0,
        ke: Vec3::ZERO,
        model: zline_shading::Model::Basic,
        ..Material::DEFAULT
    };
    let plain = mesh(positions, normals, vec![[0, 1, 2]], material);
    let mut textured = (*plain).clone();
    textured.uvs = vec![glam::Vec2::ZERO; 3];
    textured.diffuse_map = Some(white);
    let light = Light::Point {
        position: Vec3::new(0.0, 0.0, -1.0),
        color: Vec3::ONE,
        attenuation: Attenuation::NONE,
    };
    let render = |m| {
        let mut s = scene(48, Vec3::ZERO, vec![light], vec![object(m, Some(ShadingMode::Gouraud))]);
        s.camera.target = Vec3::new(0.0, -0.5, -1.0);
        render_truth(&s)
    };
    let (a, b) = (render(plain), render(Arc::new(textured)));
    let drawn = a.rgb.iter().filter(|c| **c != DVec3::ZERO).count();
    assert!(drawn > 500, "only {drawn} pixels drawn");
    for (p, q) in a.rgb.iter().zip(&b.rgb) {
        check_close(*q, *p, F64_TOLERANCE);
    }
}

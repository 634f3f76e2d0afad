//! Emission (`Material::ke`) and vertex colours (`Mesh::colors`), with
//! answers computed here from the model in f64, independently of the
//! truth's code:
//!
//! ```text
//! c = clamp(t ⊙ (ka·Ia + Σ f·Il·kd·max(0, N·L)) + ke + Σ f·Il·ks·max(0, N·H)^ns)
//! ```
//!
//! where t, the product of the texel and the vertex colour, modulates the
//! ambient+diffuse part only.

use std::sync::Arc;

use glam::{DVec2, DVec3, Vec3, Vec4};
use zline_scene::{Interpolation, Mesh, Scene, TextureMap};
use zline_shading::{Light, Material, Sampler, ShadingMode, Texture};
use zline_truth::render_truth;

use crate::support::{
    check_close, d, mesh, object, parts, scene, square, AMBIENT, ATTENUATION, F64_TOLERANCE, LIGHT,
    LIGHT_COLOR,
};

const MATERIAL: Material = Material {
    ke: Vec3::new(0.05, 0.1, 0.2),
    ka: Vec3::new(0.3, 0.4, 0.5),
    kd: Vec3::new(0.7, 0.45, 0.3),
    ks: Vec3::new(0.5, 0.5, 0.5),
    ns: 12.0,
    opacity: 1.0,
    model: zline_shading::Model::Basic,
    ..Material::DEFAULT
};

/// The lit colour with the ambient+diffuse part multiplied by `tint`.
fn lit(m: &Material, p: DVec3, n: DVec3, tint: DVec3) -> DVec3 {
    let (ambient_diffuse, specular) = parts(m, p, n);
    (tint * ambient_diffuse + specular).clamp(DVec3::ZERO, DVec3::ONE)
}

fn light() -> Light {
    Light::Point { position: LIGHT, color: LIGHT_COLOR, attenuation: ATTENUATION }
}

/// A 64×64 scene of one mesh drawn in `mode`.
fn one_mesh(m: Arc<Mesh>, mode: ShadingMode) -> Scene {
    scene(64, AMBIENT, vec![light()], vec![object(m, Some(mode))])
}

/// A 1×1 texture of one colour on every vertex of `m`.
fn solid_texture(m: &mut Mesh, color: Vec4) {
    m.uvs = vec![glam::Vec2::splat(0.5); m.positions.len()];
    m.diffuse_map = Some(TextureMap {
        texture: Arc::new(Texture::solid(color)),
        sampler: Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    });
}

/// The lit square's pixel (32, 32): its sample is the eye point
/// (1/32, −1/32, −2), in the triangle of the square's vertices 0, 1, 2 at
/// (−1, −1), (1, −1), (1, 1) (z = −2). Returns the point, that triangle's
/// corners and the point's barycentric weights (exact in the plane z = −2
/// for both interpolations).
fn centre_sample() -> (DVec3, [DVec3; 3], [f64; 3]) {
    let p = DVec3::new(1.0 / 32.0, -1.0 / 32.0, -2.0);
    let corners = [DVec2::new(-1.0, -1.0), DVec2::new(1.0, -1.0), DVec2::new(1.0, 1.0)];
    let area = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let total = area(corners[0], corners[1], corners[2]);
    let q = p.truncate();
    let w = [
        area(q, corners[1], corners[2]) / total,
        area(corners[0], q, corners[2]) / total,
        area(corners[0], corners[1], q) / total,
    ];
    (p, corners.map(|c| c.extend(-2.0)), w)
}

/// An emission-only material (ka = kd = ks = 0) shows ke in every mode,
/// lit or not, and neither a texel nor a vertex colour changes it.
#[test]
fn emission_only_material_shows_ke_in_every_mode() {
    let ke = Vec3::new(0.2, 0.55, 0.9);
    let material = Material {
        ke,
        ka: Vec3::ZERO,
        kd: Vec3::ZERO,
        ks: Vec3::ZERO,
        ns: 1.0,
        opacity: 1.0,
        model: zline_shading::Model::Basic,
        ..Material::DEFAULT
    };
    let plain = (*square(0.0, 0.0, 1.0, -2.0, material)).clone();
    let mut textured = plain.clone();
    solid_texture(&mut textured, Vec4::new(0.5, 0.25, 0.0, 1.0));
    let coloured = plain.clone().with_colors(vec![Vec3::new(0.3, 0.0, 0.6); 4]).expect("four colours");
    for m in [plain, textured, coloured] {
        let m = Arc::new(m);
        for mode in ShadingMode::ALL {
            let truth = render_truth(&one_mesh(Arc::clone(&m), mode));
            for (x, y) in [(32, 32), (25, 40), (40, 25)] {
                check_close(truth.pixel(x, y), d(ke), F64_TOLERANCE);
            }
            check_close(truth.pixel(2, 2), DVec3::ZERO, 0.0);
        }
    }
}

/// Emission adds to the lit colour in each mode (textured Gouraud too:
/// the texel modulates the interpolated ambient+diffuse part only).
#[test]
fn emission_adds_to_the_lit_colour_in_each_mode() {
    let (p, corners, w) = centre_sample();
    let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
    let plain = Arc::new((*square(0.0, 0.0, 1.0, -2.0, MATERIAL)).clone());
    let gouraud: DVec3 = (0..3).map(|k| lit(&MATERIAL, corners[k], DVec3::Z, DVec3::ONE) * w[k]).sum();
    for (mode, want) in [
        (ShadingMode::Flat, lit(&MATERIAL, centroid, DVec3::Z, DVec3::ONE)),
        (ShadingMode::Gouraud, gouraud),
        (ShadingMode::Phong, lit(&MATERIAL, p, DVec3::Z, DVec3::ONE)),
    ] {
        check_close(render_truth(&one_mesh(Arc::clone(&plain), mode)).pixel(32, 32), want, F64_TOLERANCE);
    }
    let texel = Vec4::new(0.9, 0.5, 0.25, 1.0);
    let mut textured = (*plain).clone();
    solid_texture(&mut textured, texel);
    let (ad, sp) = (0..3)
        .map(|k| parts(&MATERIAL, corners[k], DVec3::Z))
        .zip(w)
        .fold((DVec3::ZERO, DVec3::ZERO), |(a, s), ((ad, sp), w)| (a + ad * w, s + sp * w));
    let want = (d(texel.truncate()) * ad + sp).clamp(DVec3::ZERO, DVec3::ONE);
    let truth = render_truth(&one_mesh(Arc::new(textured), ShadingMode::Gouraud));
    check_close(truth.pixel(32, 32), want, F64_TOLERANCE);
    // Emission is visible here: without it the colour would differ.
    assert!((want - (d(texel.truncate()) * ad + sp - d(MATERIAL.ke))).abs().min_element() > 0.04);
}

/// One vertex colour c on every vertex: flat is c ⊙ (ambient+diffuse) at
/// the centroid plus ke + specular; Gouraud lights each vertex so and
/// interpolates the clamped colours.
#[test]
fn uniform_vertex_colour_in_flat_and_gouraud() {
    let c = Vec3::new(0.9, 0.3, 0.6);
    let (_, corners, w) = centre_sample();
    let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
    let m = (*square(0.0, 0.0, 1.0, -2.0, MATERIAL)).clone().with_colors(vec![c; 4]).expect("four colours");
    let m = Arc::new(m);
    let flat = lit(&MATERIAL, centroid, DVec3::Z, d(c));
    let gouraud: DVec3 = (0..3).map(|k| lit(&MATERIAL, corners[k], DVec3::Z, d(c)) * w[k]).sum();
    for (mode, want) in [(ShadingMode::Flat, flat), (ShadingMode::Gouraud, gouraud)] {
        check_close(render_truth(&one_mesh(Arc::clone(&m), mode)).pixel(32, 32), want, F64_TOLERANCE);
    }
    // The colour matters: untinted, the answers differ by more than a step.
    let untinted = lit(&MATERIAL, centroid, DVec3::Z, DVec3::ONE);
    assert!((flat - untinted).abs().max_element() > 0.05);
}

/// A tilted triangle with a different colour at each vertex, Phong shaded:
/// at a pixel the colour is interpolated to the sample — perspective-
/// correctly (the barycentric weights of the ray's hit in eye space) or
/// screen-linearly (the weights of the pixel centre among the projected
/// corners, which also place the eye position) — and multiplies the
/// ambient+diffuse part lit there.
#[test]
fn phong_interpolates_vertex_colours_per_sample() {
    let corners = [Vec3::new(-1.5, -1.0, -2.0), Vec3::new(1.5, -1.2, -4.0), Vec3::new(0.2, 1.5, -3.0)];
    let colors = [Vec3::new(1.0, 0.2, 0.1), Vec3::new(0.1, 0.9, 0.3), Vec3::new(0.2, 0.3, 1.0)];
    let e = corners.map(|p| p.as_dvec3());
    let face = (e[1] - e[0]).cross(e[2] - e[0]);
    assert!(face.dot(-e[0]) > 0.0, "the front faces the eye");
    // The vertex normal as the mesh stores it (f32), renormalized as the
    // renderers do.
    let stored = face.normalize().as_vec3();
    let normal = stored.as_dvec3().normalize();
    let m = mesh(corners.to_vec(), vec![stored; 3], vec![[0, 1, 2]], MATERIAL);
    let m = Arc::new((*m).clone().with_colors(colors.to_vec()).expect("three colours"));
    let (x, y) = (34u32, 30u32);
    // The sample at the pixel centre, as a ray (x_nc, y_nc, −1) (fovy 90°).
    let nc = DVec2::new((f64::from(x) + 0.5) / 32.0 - 1.0, 1.0 - (f64::from(y) + 0.5) / 32.0);
    let dir = nc.extend(-1.0);
    let hit = dir * (face.dot(e[0]) / face.dot(dir));
    let perspective = barycentric(hit, e);
    let window = e.map(|p| DVec2::new(p.x / -p.z, p.y / -p.z));
    let linear = barycentric(nc.extend(0.0), window.map(|p| p.extend(0.0)));
    assert!(perspective.iter().chain(&linear).all(|&b| b > 0.1), "{perspective:?} {linear:?}");
    let mut wants = Vec::new();
    for (interpolation, weights) in
        [(Interpolation::PerspectiveCorrect, perspective), (Interpolation::ScreenLinear, linear)]
    {
        let blend = |v: [DVec3; 3]| -> DVec3 { (0..3).map(|k| v[k] * weights[k]).sum() };
        let want = lit(&MATERIAL, blend(e), normal, blend(colors.map(d)));
        let mut s = one_mesh(Arc::clone(&m), ShadingMode::Phong);
        s.settings.interpolation = interpolation;
        check_close(render_truth(&s).pixel(x, y), want, F64_TOLERANCE);
        wants.push(want);
    }
    // The two interpolations, and the colours, make a visible difference.
    assert!((wants[0] - wants[1]).abs().max_element() > 0.01);
    assert!((wants[0] - lit(&MATERIAL, hit, normal, DVec3::ONE)).abs().max_element() > 0.05);
}

/// Barycentric weights of `p` in the triangle `c` (p in its plane).
fn barycentric(p: DVec3, c: [DVec3; 3]) -> [f64; 3] {
    let n = (c[1] - c[0]).cross(c[2] - c[0]);
    let part = |a: DVec3, b: DVec3| (b - a).cross(p - a).dot(n) / n.length_squared();
    [part(c[1], c[2]), part(c[2], c[0]), part(c[0], c[1])]
}

//! The vertex stage's lanes against their scalar twins.

use super::*;
use proptest::prelude::*;

fn vec3() -> impl Strategy<Value = Vec3> {
    let c = prop_oneof![
        8 => -50.0f32..50.0,
        1 => Just(0.0f32),
        1 => -1e30f32..1e30,
        1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(-0.0f32), Just(1e-30f32)],
    ];
    (c.clone(), c.clone(), c).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn bits(v: &ClipVertex) -> Vec<u32> {
    let floats = [v.clip.to_array().as_slice(), &v.eye.to_array(), &v.normal.to_array()].concat();
    let p = v.projected;
    // A NaN's sign and payload are not specified by Rust or LLVM (which
    // may swap an addition's operands): every NaN compares as one.
    let mut out: Vec<u32> = floats.iter().map(|f| if f.is_nan() { u32::MAX } else { f.to_bits() }).collect();
    out.extend([
        p.fixed.x as u32,
        p.fixed.y as u32,
        p.inv_w.to_bits(),
        u32::from(v.view_code),
        u32::from(v.clip_code),
    ]);
    out.extend([p.z.to_bits() as u32, (p.z.to_bits() >> 32) as u32]);
    out
}

/// [`snap_x8`] at a level, as a job.
struct Snap([[f64; 4]; 8], Viewport);

impl zline_simd::Vectorized for Snap {
    type Output = ([i32; 8], [i32; 8], [bool; 8]);
    fn run<S: Level>(self) -> Self::Output {
        snap_x8::<S>(&self.0, self.1)
    }
}

/// The lanes' snap equals `Projected::from_quotients`' where rounding is decided
/// by a half (±0.5 and ±1.5 fixed-point units, each side of zero),
/// at the largest accepted coordinate and past it, and for NaN and
/// infinities, at the CPU's level and at the baseline.
#[test]
fn the_lanes_snap_as_fixed_point_does() {
    let s = 1.0 / 256.0;
    let max = f64::from(zline_raster::MAX_WINDOW_COORD);
    let values = [
        0.0,
        0.5 * s,
        -0.5 * s,
        1.5 * s,
        -1.5 * s,
        2.5 * s,
        -2.5 * s,
        0.49 * s,
        -0.51 * s,
        1234.5 * s,
        -1234.5 * s,
        100.25,
        -77.75,
        max,
        -max,
        max + 1.0,
        -max - 1.0,
        max * 0.75 + 0.5 * s,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1.0e300,
    ];
    // With a 2 × 2 viewport the window map is x + 1 and 1 − y, so the
    // quotients v − 1 and 1 − v land on window coordinate v.
    let viewport = Viewport { width: 2, height: 2 };
    for (i, &vx) in values.iter().enumerate() {
        let mut q = [[0.0; 4]; 8];
        for (k, lane) in q.iter_mut().enumerate() {
            let vy = values[(i + 3 * k + 1) % values.len()];
            let vx = if k == 0 { vx } else { values[(i + k) % values.len()] };
            *lane = [vx - 1.0, 1.0 - vy, 0.5, 1.0];
        }
        let expected: Vec<Option<FixedPoint>> =
            q.iter().map(|&q| Projected::from_quotients(q, viewport).map(|p| p.fixed)).collect();
        for (fx, fy, ok) in
            [zline_simd::vectorize(Snap(q, viewport)), snap_x8::<zline_simd::lanes::Baseline>(&q, viewport)]
        {
            let got: Vec<Option<FixedPoint>> =
                (0..8).map(|k| ok[k].then_some(FixedPoint { x: fx[k], y: fy[k] })).collect();
            assert_eq!(got, expected, "quotients {q:?}");
        }
    }
}

proptest! {
    /// Every lane of the vectorized transform, at the level the CPU
    /// runs and at the baseline, equals the scalar twin bit for bit:
    /// inside, outside, behind the eye, degenerate and non-finite.
    #[test]
    fn the_lanes_equal_the_scalar_twin(
        vertices in proptest::collection::vec((vec3(), vec3()), 1..30),
        eye in vec3(),
        perspective in any::<bool>(),
    ) {
        let camera = zline_scene::Camera {
            eye: eye.clamp(Vec3::splat(-5.0), Vec3::splat(5.0)).map(|c| if c.is_nan() { 0.0 } else { c }),
            target: Vec3::new(0.1, 0.2, -1.0),
            up: Vec3::Y,
            projection: if perspective {
                zline_scene::Projection::Perspective { fovy_degrees: 60.0, near: 0.5, far: 80.0 }
            } else {
                zline_scene::Projection::Orthographic { height: 40.0, near: 0.5, far: 80.0 }
            },
        };
        let model = Mat4::from_scale_rotation_translation(
            Vec3::new(1.5, -0.75, 2.0),
            glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7),
            Vec3::new(0.25, -3.0, 1.0),
        );
        let t = ObjectTransforms::new(camera.clip_from_eye(4.0 / 3.0), camera.eye_from_world(), model);
        let screen = Screen { viewport: Viewport { width: 320, height: 240 }, volume: ClipVolume::new(320, 240) };
        let (positions, normals): (Vec<Vec3>, Vec<Vec3>) = vertices.into_iter().unzip();
        let twin: Vec<Vec<u32>> =
            positions.iter().zip(&normals).map(|(&p, &n)| bits(&transform_vertex(p, n, &t, &screen))).collect();
        for baseline in [false, true] {
            let mut out = vec![ClipVertex::default(); positions.len()];
            let (positions, normals, screen) = (&positions, &normals, &screen);
            let job = TransformVertices { out: Records::Full(&mut out), positions, normals, t: &t, screen, lighting: None };
            if baseline {
                zline_simd::vectorize_at::<zline_simd::lanes::Baseline, _>(job);
            } else {
                zline_simd::vectorize(job);
            }
            let lanes: Vec<Vec<u32>> = out.iter().map(bits).collect();
            prop_assert_eq!(&lanes, &twin, "baseline: {}", baseline);
        }
        // Lit from the lanes: each colour is the scalar lighting model
        // at the vertex's own eye position and normal, clamped per
        // vertex or the unclamped sum.
        let model = zline_shading::LightingModel {
            ambient: Vec3::splat(0.1),
            lights: vec![
                zline_shading::Light::Point {
                    position: Vec3::new(4.0, 4.0, 5.0),
                    color: Vec3::ONE,
                    attenuation: zline_shading::Attenuation::new(1.0, 0.01, 0.005),
                },
                zline_shading::Light::Directional { direction: Vec3::new(1.0, -0.5, -1.0), color: Vec3::new(0.25, 0.3, 0.6) },
            ],
            environment: None,
        };
        let lights = PreparedLights::new(&model, &Mat4::IDENTITY);
        let material = PreparedMaterial::new(zline_shading::Material { ks: Vec3::splat(0.6), ns: 40.0, ..Default::default() });
        for clamp in [GouraudClamp::PerVertex, GouraudClamp::PerSample] {
            let mut out = vec![ClipVertex::default(); positions.len()];
            let lighting = Some(VertexLights { lights: &lights, material: &material, clamp, turned: true });
            let (positions, normals, screen) = (&positions, &normals, &screen);
            zline_simd::vectorize(TransformVertices { out: Records::Full(&mut out), positions, normals, t: &t, screen, lighting });
            // A vertex at a non-finite position is outside every view
            // volume plane and never drawn; the scalar model returns
            // black there, the lanes a colour.
            // The turned colour (two-sided lighting) is the same model
            // with the normal negated.
            for v in out.iter().filter(|v| v.eye.is_finite()) {
                let lit = |normal: Vec3| match clamp {
                    GouraudClamp::PerVertex => lights.shade(&material, v.eye, normal, Vec3::ZERO),
                    GouraudClamp::PerSample => {
                        let parts = lights.shade_parts(&material, v.eye, normal, Vec3::ZERO);
                        parts.ambient_diffuse + parts.specular
                    }
                };
                let canon = |c: Vec3| c.to_array().map(|f| if f.is_nan() { u32::MAX } else { f.to_bits() });
                prop_assert_eq!(canon(v.color), canon(lit(v.normal)), "{:?} at {:?}, {:?}", clamp, v.eye, v.normal);
                let turned = v.tangent.truncate();
                prop_assert_eq!(canon(turned), canon(lit(-v.normal)), "turned {:?} at {:?}", clamp, v.eye);
            }
        }
    }
}

/// Compact records hold what whole records hold: the window position,
/// depth, 1/w and outcodes of each vertex, and the values the layout
/// names, bit for bit, for every layout (none stored included) and a mesh
/// spanning several rayon chunks.
#[test]
fn compact_records_hold_the_whole_records_values() {
    let n = VERTEX_CHUNK * 2 + 37;
    let positions: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new((i % 97) as f32 * 0.3 - 14.0, (i % 13) as f32 - 6.0, -((i % 41) as f32) - 1.0))
        .collect();
    let normals: Vec<Vec3> = positions.iter().map(|p| p.normalize_or_zero()).collect();
    let mut mesh =
        Mesh::new("grid", positions, Some(normals), vec![], zline_scene::Material::default()).unwrap();
    mesh.uvs = mesh.positions.iter().map(|p| p.truncate()).collect();
    let camera = zline_scene::Camera {
        eye: Vec3::new(0.0, 0.0, 5.0),
        target: Vec3::new(0.0, 0.0, -1.0),
        up: Vec3::Y,
        projection: zline_scene::Projection::Perspective { fovy_degrees: 60.0, near: 0.5, far: 80.0 },
    };
    let t = ObjectTransforms::new(camera.clip_from_eye(4.0 / 3.0), camera.eye_from_world(), Mat4::IDENTITY);
    let screen = Screen { viewport: Viewport { width: 320, height: 240 }, volume: ClipVolume::new(320, 240) };
    let mut whole = Vec::new();
    transform_mesh(&mesh, &t, None, &screen, &mut whole);
    // A big pool cuts the mesh into smaller chunks: the same records.
    for threads in [3, 16] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut cut = Vec::new();
        pool.install(|| transform_mesh(&mesh, &t, None, &screen, &mut cut));
        assert_eq!(format!("{cut:?}"), format!("{whole:?}"), "{threads} threads");
        let layout = ValueLayout::new([true; 4]);
        let (mut one, mut many) = (CompactVertices::default(), CompactVertices::default());
        transform_compact(&mesh, &t, None, &screen, layout, &mut one);
        pool.install(|| transform_compact(&mesh, &t, None, &screen, layout, &mut many));
        assert_eq!(format!("{:?}", many.screen), format!("{:?}", one.screen), "{threads} threads");
        assert_eq!(
            many.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            one.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
    }
    let source = Source { mesh: &mesh, t: &t, screen: &screen };
    for stored in 0..16u32 {
        let layout = ValueLayout::new([0, 1, 2, 3].map(|b| stored & (1 << b) != 0));
        let mut compact = CompactVertices::default();
        transform_compact(&mesh, &t, None, &screen, layout, &mut compact);
        assert_eq!(compact.screen.len(), n);
        for (i, w) in whole.iter().enumerate() {
            let s = compact.screen[i];
            let p = w.projected;
            assert_eq!(
                (s.fixed, s.z.to_bits(), s.inv_w.to_bits(), s.view_code, s.clip_code),
                (p.fixed, p.z.to_bits(), p.inv_w.to_bits(), w.view_code, w.clip_code),
                "vertex {i}, layout {layout:?}"
            );
            let fields = [(layout.color, w.color), (layout.normal, w.normal), (layout.eye, w.eye)];
            for (offset, want) in fields {
                if let Some(o) = offset {
                    assert_eq!(
                        compact.value(i, o).to_array().map(f32::to_bits),
                        want.to_array().map(f32::to_bits)
                    );
                }
            }
            assert_eq!(format!("{:?}", compact.full(i, &source)), format!("{w:?}"), "vertex {i}");
        }
    }
}

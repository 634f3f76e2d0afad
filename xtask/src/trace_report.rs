//! `cargo xtask trace-report`: the ray tracer's acceleration structures
//! side by side (build time, size, rays per second, nodes and triangles
//! per ray, hits equal to the BVH's on every ray and to brute force on a
//! million random rays), its anti-aliasing against a 16 × 16 reference
//! (`trace_aa`), and its error against the f64 truth (`trace_truth`).

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::Result;
use glam::Vec3;
use zline::scene::{uv_sphere, Mesh, Scene};
use zline::trace::accel::brute::Brute;
use zline::trace::accel::bvh::Bvh;
use zline::trace::accel::grid::Grid;
use zline::trace::accel::kdtree::KdTree;
use zline::trace::accel::{Accelerator, Counters};
use zline::trace::ray::{Hit, Ray};
use zline::trace::world::{Camera, World};

/// One scene of the table: its triangles, and the camera rays and the
/// shadow rays (towards a light) of a frame.
pub(crate) struct Case {
    pub(crate) name: String,
    pub(crate) triangles: Vec<[Vec3; 3]>,
    pub(crate) camera: Vec<Ray>,
    light: Vec3,
}

/// Which parts to run.
pub(crate) struct Args<'a> {
    pub(crate) assets: &'a Path,
    pub(crate) width: u32,
    pub(crate) accel: bool,
    pub(crate) antialias: bool,
    pub(crate) truth: bool,
}

pub(crate) fn run(args: &Args) -> Result<()> {
    if args.accel {
        accelerators(args)?;
    }
    if args.antialias {
        crate::trace_aa::run()?;
    }
    if args.truth {
        crate::trace_truth::run(args.width.min(320))?;
    }
    Ok(())
}

fn accelerators(args: &Args) -> Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let cornell = root.join("assets/cornell/cornell_box.toml");
    let mut cases = vec![
        frame("Cornell box", &zline::io::load_scene(&cornell)?, args.width),
        frame("Whitted scene", &zline::scenes::whitted_scene(), args.width),
        frame("demo", &zline::scenes::demo_scene(), args.width),
        frame("room", &zline::scenes::room_scene(), args.width),
    ];
    let teapot = args.assets.join("obj/teapot/teapot.obj");
    let small: Vec<Mesh> = if teapot.exists() {
        zline::io::load_obj(&teapot)?
    } else {
        eprintln!("{} not found: a 6k-triangle sphere stands in for the teapot", teapot.display());
        vec![uv_sphere(40, 80, 1.5)]
    };
    cases.push(stadium(&small, args.width));
    cases.push(sphere_case("sphere 200k", 200_000, args.width));
    cases.push(sphere_case("sphere 2M", 2_000_000, args.width));

    println!("## Acceleration structures\n");
    println!(
        "One thread; camera rays of a {}-pixel-wide frame and one shadow ray per hit (any hit, towards a point light). Hits equal the BVH's on every ray of every row.\n",
        args.width
    );
    println!("| scene | triangles | structure | build | size | camera Mrays/s | nodes/ray | triangles/ray | shadow Mrays/s |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|");
    for case in &cases {
        let built: Vec<(&str, Duration, String, Box<dyn Accelerator>)> = vec![
            timed_build("bvh", || {
                let b = Bvh::build(&case.triangles);
                (format!("{} nodes", b.node_count()), Box::new(b) as Box<dyn Accelerator>)
            }),
            timed_build("kd", || {
                let k = KdTree::build(&case.triangles);
                (format!("{} nodes", k.node_count()), Box::new(k) as Box<dyn Accelerator>)
            }),
            timed_build("grid", || {
                let g = Grid::build(&case.triangles);
                let [x, y, z] = g.resolution();
                (format!("{x}×{y}×{z} cells"), Box::new(g) as Box<dyn Accelerator>)
            }),
        ];
        let reference = hits(built[0].3.as_ref(), case);
        for (name, build, size, accel) in &built {
            let (camera, shadow, count, got) = measure(accel.as_ref(), case);
            anyhow::ensure!(got == reference, "{}: {name}'s hits differ from the BVH's", case.name);
            let n = count.rays.max(1) as f64;
            println!(
                "| {} | {} | {name} | {:.1} ms | {size} | {:.2} | {:.1} | {:.1} | {:.2} |",
                case.name,
                case.triangles.len(),
                build.as_secs_f64() * 1e3,
                camera,
                count.nodes as f64 / n,
                count.tests as f64 / n,
                shadow
            );
        }
    }
    println!();
    random_rays_against_brute_force()
}

fn timed_build(
    name: &'static str,
    build: impl FnOnce() -> (String, Box<dyn Accelerator>),
) -> (&'static str, Duration, String, Box<dyn Accelerator>) {
    let start = Instant::now();
    let (size, accel) = build();
    (name, start.elapsed(), size, accel)
}

/// The camera rays of `scene` at `width` pixels across (its aspect kept).
pub(crate) fn frame(name: &str, scene: &Scene, width: u32) -> Case {
    let mut scene = scene.clone();
    let aspect = scene.settings.height as f32 / scene.settings.width as f32;
    scene.settings.width = width;
    scene.settings.height = ((width as f32 * aspect).round() as u32).max(1);
    let world = World::new(&scene);
    let camera = Camera::new(&scene);
    let (w, h) = camera.size();
    let rays = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5))
        .collect();
    let light = scene.lights.iter().find_map(|l| match l {
        zline::shading::Light::Point { position, .. } => Some(*position),
        _ => None,
    });
    let light = light.unwrap_or(scene.camera.eye + Vec3::Y * 10.0);
    Case { name: name.into(), triangles: world.triangles, camera: rays, light }
}

/// A small dense model in the middle of a huge sparse stadium: a floor of
/// two triangles and a ring of 64 tall stands, 400 units across. A uniform
/// grid puts the model in a handful of cells.
fn stadium(model: &[Mesh], width: u32) -> Case {
    let mut triangles: Vec<[Vec3; 3]> = Vec::new();
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for m in model {
        for &p in &m.positions {
            (lo, hi) = (lo.min(p), hi.max(p));
        }
    }
    // The model scaled to 2 units across, standing on the floor.
    let s = 2.0 / (hi - lo).max_element().max(1e-6);
    let place = |p: Vec3| (p - Vec3::new(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z))) * s;
    for m in model {
        for t in &m.triangles {
            triangles.push(t.map(|i| place(m.positions[i as usize])));
        }
    }
    let r = 200.0;
    triangles.push([Vec3::new(-r, 0.0, -r), Vec3::new(r, 0.0, r), Vec3::new(r, 0.0, -r)]);
    triangles.push([Vec3::new(-r, 0.0, -r), Vec3::new(-r, 0.0, r), Vec3::new(r, 0.0, r)]);
    for i in 0..64 {
        let a = |k: f32| {
            Vec3::new((k * std::f32::consts::TAU / 64.0).cos(), 0.0, (k * std::f32::consts::TAU / 64.0).sin())
        };
        let (p, q) = (a(i as f32) * r, a(i as f32 + 1.0) * r);
        let up = Vec3::Y * 60.0 + (p + q) * -0.2;
        triangles.push([p, q, q + up]);
        triangles.push([p, q + up, p + up]);
    }
    let mut scene = zline::scenes::whitted_scene();
    scene.objects.clear();
    scene.camera.eye = Vec3::new(0.0, 1.6, 4.0);
    scene.camera.target = Vec3::new(0.0, 0.7, 0.0);
    let mut case = frame("teapot in a stadium", &scene, width);
    case.triangles = triangles;
    case.light = Vec3::new(30.0, 80.0, 40.0);
    case
}

/// A UV sphere of about `n` triangles, filling the view.
pub(crate) fn sphere_case(name: &str, n: u32, width: u32) -> Case {
    let rings = ((n as f32 / 4.0).sqrt() as u32).max(2); // 4·rings² triangles
    let mesh = uv_sphere(rings, 2 * rings, 1.0);
    let mut scene = zline::scenes::whitted_scene();
    scene.objects.clear();
    scene.camera.eye = Vec3::new(0.0, 0.0, 3.2);
    scene.camera.target = Vec3::ZERO;
    let mut case = frame(name, &scene, width);
    case.triangles = mesh.triangles.iter().map(|t| t.map(|i| mesh.positions[i as usize])).collect();
    case.light = Vec3::new(4.0, 6.0, 5.0);
    case
}

/// A hit by its triangle and the bits of its t.
type HitKey = Option<(u32, u32)>;

/// The camera hits of `case` by `accel`, compared by their bits.
fn hits(accel: &dyn Accelerator, case: &Case) -> Vec<HitKey> {
    let mut count = Counters::default();
    case.camera.iter().map(|r| key(accel.closest(&case.triangles, r, &mut count))).collect()
}

fn key(hit: Option<Hit>) -> HitKey {
    hit.map(|h| (h.triangle, h.t.to_bits()))
}

/// Camera and shadow Mrays/s (best of three), the camera rays' counters
/// and their hits.
fn measure(accel: &dyn Accelerator, case: &Case) -> (f64, f64, Counters, Vec<HitKey>) {
    let mut best = (f64::MAX, f64::MAX);
    let mut count = Counters::default();
    let mut got = Vec::new();
    let mut shadows = Vec::new();
    for _ in 0..3 {
        count = Counters::default();
        let start = Instant::now();
        let hits: Vec<Option<Hit>> =
            case.camera.iter().map(|r| accel.closest(&case.triangles, r, &mut count)).collect();
        best.0 = best.0.min(start.elapsed().as_secs_f64());
        shadows = case
            .camera
            .iter()
            .zip(&hits)
            .filter_map(|(r, h)| {
                let h = h.as_ref()?;
                let p = r.at(h.t);
                let to = case.light - p;
                // Started a little off the surface towards the light.
                Some(Ray { origin: p + to * 1e-4, dir: to, t_max: 1.0 - 2e-4 })
            })
            .collect::<Vec<_>>();
        let start = Instant::now();
        let mut shadow_count = Counters::default();
        let mut blocked = 0u64;
        for ray in &shadows {
            if !accel.each_hit(&case.triangles, ray, &mut shadow_count, &mut |_| false) {
                blocked += 1;
            }
        }
        std::hint::black_box(blocked);
        best.1 = best.1.min(start.elapsed().as_secs_f64());
        got = hits.into_iter().map(key).collect();
    }
    let camera = case.camera.len() as f64 / best.0.max(1e-9) / 1e6;
    let shadow = shadows.len() as f64 / best.1.max(1e-9) / 1e6;
    (camera, shadow, count, got)
}

/// splitmix64.
fn next(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn uniform(state: &mut u64, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * ((next(state) >> 40) as f32 / (1u64 << 24) as f32)
}

/// A million random rays through a 2k-triangle sphere and a 2k-triangle
/// soup: every structure's nearest hit equals brute force's, bit for bit.
fn random_rays_against_brute_force() -> Result<()> {
    let sphere = uv_sphere(32, 32, 1.0);
    let sphere: Vec<[Vec3; 3]> =
        sphere.triangles.iter().map(|t| t.map(|i| sphere.positions[i as usize])).collect();
    let mut state = 7;
    let p = |s: &mut u64| Vec3::new(uniform(s, -1.5, 1.5), uniform(s, -1.5, 1.5), uniform(s, -1.5, 1.5));
    let soup: Vec<[Vec3; 3]> = (0..2000)
        .map(|_| {
            let a = p(&mut state);
            [a, a + p(&mut state) * 0.2, a + p(&mut state) * 0.2]
        })
        .collect();
    println!("## A million random rays against brute force\n");
    println!("| triangles | rays | structure | equal hits | triangles/ray | brute force's triangles/ray |");
    println!("|---|---:|---|---:|---:|---:|");
    for (name, tris) in [("2k sphere", &sphere), ("2k soup", &soup)] {
        let rays: Vec<Ray> = (0..1_000_000)
            .map(|i| {
                let o = p(&mut state) * 2.0;
                let t = tris[i % tris.len()];
                let aim = if i % 2 == 0 { (t[0] + t[1] + t[2]) / 3.0 } else { p(&mut state) };
                Ray::new(o, aim - o)
            })
            .collect();
        let mut brute = Counters::default();
        let want: Vec<_> = rays.iter().map(|r| key(Brute.closest(tris, r, &mut brute))).collect();
        let structures: [(&str, Box<dyn Accelerator>); 3] = [
            ("bvh", Box::new(Bvh::build(tris))),
            ("kd", Box::new(KdTree::build(tris))),
            ("grid", Box::new(Grid::build(tris))),
        ];
        for (s, accel) in &structures {
            let mut count = Counters::default();
            let equal = rays
                .iter()
                .zip(&want)
                .filter(|(r, w)| key(accel.closest(tris, r, &mut count)) == **w)
                .count();
            println!(
                "| {name} | {} | {s} | {equal} | {:.1} | {:.0} |",
                rays.len(),
                count.tests as f64 / rays.len() as f64,
                brute.tests as f64 / rays.len() as f64
            );
            anyhow::ensure!(
                equal == rays.len(),
                "{name}: {s} differs from brute force on {} rays",
                rays.len() - equal
            );
        }
    }
    println!();
    Ok(())
}

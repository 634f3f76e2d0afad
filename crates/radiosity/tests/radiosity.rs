//! Radiosity against closed forms: form factors between unit squares,
//! reciprocity, the furnace, and bad input.

use glam::Vec3;
use zline_radiosity::hemicube::Hemicube;
use zline_radiosity::solve;
use zline_radiosity::Patch;
use zline_radiosity::{Method, Options};

/// The unit square at `origin` spanned by `u` and `v` (front side u × v),
/// cut into n × n cells of two triangles each.
fn square(origin: Vec3, u: Vec3, v: Vec3, n: usize, rho: f32, e: f32) -> Vec<Patch> {
    let mut out = Vec::new();
    let at = |i: usize, j: usize| origin + u * (i as f32 / n as f32) + v * (j as f32 / n as f32);
    for i in 0..n {
        for j in 0..n {
            for corners in
                [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
            {
                out.push(Patch::new(corners, Vec3::splat(rho), Vec3::splat(e)).expect("half a cell"));
            }
        }
    }
    out
}

/// The area-averaged form factor from the first `from` patches to the
/// rest: Σ_k A_k F_k,rest / Σ_k A_k, a hemicube at each source patch.
fn form_factor(patches: &[Patch], from: usize, res: usize) -> f64 {
    let mut cube = Hemicube::new(res);
    let mut row = vec![0.0f32; patches.len()];
    let mut sum = 0.0f64;
    let mut area = 0.0f64;
    for k in 0..from {
        row.fill(0.0);
        cube.gather(patches, k, &mut row);
        let f: f64 = row[from..].iter().map(|&f| f64::from(f)).sum();
        sum += f64::from(patches[k].area) * f;
        area += f64::from(patches[k].area);
    }
    sum / area
}

/// Two parallel unit squares one apart, facing each other.
fn parallel(n: usize) -> (Vec<Patch>, usize) {
    let mut p = square(Vec3::ZERO, Vec3::X, Vec3::Y, n, 0.5, 0.0);
    let from = p.len();
    p.extend(square(Vec3::new(0.0, 1.0, 1.0), Vec3::X, -Vec3::Y, 1, 0.5, 0.0));
    (p, from)
}

/// Two unit squares sharing an edge at a right angle, facing each other.
fn perpendicular(n: usize) -> (Vec<Patch>, usize) {
    let mut p = square(Vec3::ZERO, Vec3::X, Vec3::Y, n, 0.5, 0.0);
    let from = p.len();
    p.extend(square(Vec3::ZERO, Vec3::Z, Vec3::X, 1, 0.5, 0.0));
    (p, from)
}

#[test]
fn form_factors_of_unit_squares_meet_the_closed_forms() {
    // F between parallel unit squares at distance 1, and between
    // perpendicular ones sharing an edge (Howell's catalogue, C-11, C-14).
    for (name, (patches, from), exact) in
        [("parallel", parallel(12), 0.199_825), ("perpendicular", perpendicular(24), 0.200_044)]
    {
        for (res, tolerance) in [(100, 0.002), (400, 0.0005)] {
            let f = form_factor(&patches, from, res);
            assert!((f - exact).abs() <= tolerance, "{name} at {res}²: F = {f:.6}, exact {exact}");
        }
    }
}

#[test]
fn reciprocity_holds_within_a_percent() {
    // A small square over the corner of a large one, at an angle.
    let mut small = square(Vec3::new(0.2, 0.3, 0.6), Vec3::X * 0.4, Vec3::new(0.0, -0.3, 0.1), 8, 0.5, 0.0);
    let n_small = small.len();
    let mut large = square(Vec3::new(-0.5, -0.5, 0.0), Vec3::X * 2.0, Vec3::Y * 2.0, 8, 0.5, 0.0);
    let a_small: f64 = small.iter().map(|p| f64::from(p.area)).sum();
    let a_large: f64 = large.iter().map(|p| f64::from(p.area)).sum();
    let mut both = small.clone();
    both.append(&mut large.clone());
    let f_sl = form_factor(&both, n_small, 200);
    let n_large = large.len();
    large.append(&mut small);
    let f_ls = form_factor(&large, n_large, 200);
    let (ab, ba) = (a_small * f_sl, a_large * f_ls);
    assert!(f_sl > 0.05, "{f_sl}");
    assert!((ab - ba).abs() <= 0.01 * ab, "A_s F_sl = {ab:.5}, A_l F_ls = {ba:.5}");
}

/// A closed unit cube seen from inside, every patch E = 1 and ρ = 0.5.
fn furnace(n: usize) -> Vec<Patch> {
    let (o, x, y, z) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    let mut p = Vec::new();
    for (origin, u, v) in [(o, x, y), (z, y, x), (o, z, x), (y, x, z), (o, y, z), (x, z, y)] {
        p.extend(square(origin, u, v, n, 0.5, 1.0));
    }
    p
}

#[test]
fn the_furnace_gives_e_over_one_minus_rho_on_every_patch() {
    let patches = furnace(4);
    // Every normal points into the cube.
    for p in &patches {
        assert!((Vec3::splat(0.5) - p.centre).dot(p.normal) > 0.0, "{p:?}");
    }
    let rows = solve::matrix(&patches, 100, false);
    for (i, row) in rows.iter().enumerate() {
        let sum: f32 = row.iter().sum();
        assert!((sum - 1.0).abs() < 1e-3, "row {i} sums to {sum}");
    }
    let mut cube = Hemicube::new(100);
    let exact = Options { tolerance: 1e-6, ..Options::default() };
    let runs = [
        ("jacobi", solve::sweep(&patches, &rows, false, 1e-6, 200)),
        ("gauss-seidel", solve::sweep(&patches, &rows, true, 1e-6, 200)),
        ("progressive", solve::progressive(&patches, &mut cube, &exact, false)),
        (
            "progressive, shooting from the area",
            solve::progressive(&patches, &mut cube, &Options { area_shooting: true, ..exact }, false),
        ),
    ];
    for (name, (b, convergence)) in runs {
        // The sweeps solve B = E + ρ F B with rows of F summing to 1: B = 2
        // within 0.5 %. Shooting uses F_ji = F_ij A_i / A_j, which the
        // hemicube's point samples meet only approximately between
        // triangles meeting at the cube's edges (column sums of F measured
        // from 0.91 to 1.05, at 100² and at 400² alike): 5.0 % at worst
        // (1.9 % shooting from four points), while the area-weighted mean
        // stays exact (power is conserved). Tolerances: those, rounded up.
        let tolerance = match name {
            "progressive" => 0.11,
            "progressive, shooting from the area" => 0.04,
            _ => 0.01,
        };
        for (i, bi) in b.iter().enumerate() {
            assert!((bi.x - 2.0).abs() <= tolerance, "{name}: patch {i} has B = {bi}");
        }
        let area: f32 = patches.iter().map(|p| p.area).sum();
        let mean = patches.iter().zip(&b).map(|(p, bi)| bi.x * p.area).sum::<f32>() / area;
        assert!((mean - 2.0).abs() <= 2e-4, "{name}: mean B = {mean}");
        assert!(*convergence.residuals.last().unwrap() <= 1e-6, "{name}: {:?}", convergence.residuals.last());
    }
    let _ = Method::Jacobi;
}

#[test]
fn near_patches_take_the_analytic_form_factor_where_the_hemicube_sees_them() {
    use zline_radiosity::analytic::{point_to_triangle, refine_near, NEAR_REACH};
    // Two perpendicular unit squares sharing an edge, 4 × 4 cells each.
    let (patches, from) = perpendicular(4);
    let mut cube = Hemicube::new(100);
    let mut hemicube = vec![0.0f32; patches.len()];
    cube.gather(&patches, 0, &mut hemicube);
    let mut row = hemicube.clone();
    let replaced = refine_near(&patches, 0, &mut row);
    assert!(replaced > 0);
    let p = &patches[0];
    let reach = NEAR_REACH * (2.0f32).sqrt() / 4.0;
    let mut near = 0;
    for (j, q) in patches.iter().enumerate() {
        if hemicube[j] > 0.0 && (q.centre - p.centre).length() < reach {
            near += 1;
            assert_eq!(row[j], point_to_triangle(p.centre, p.normal, &q.corners) as f32, "patch {j}");
            assert!((row[j] - hemicube[j]).abs() < 0.5 * hemicube[j], "{} against {}", row[j], hemicube[j]);
        } else {
            assert_eq!(row[j], hemicube[j], "patch {j}: far or unseen, the hemicube's");
        }
    }
    assert_eq!(near, replaced);
    assert!(from < patches.len());
}

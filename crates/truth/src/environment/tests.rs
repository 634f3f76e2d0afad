//! Unit tests of the truth's environment: the SH projection against closed
//! forms, the lobe average against a 1-D integral and against itself with
//! smaller cells, rotation and the eye frame.

use std::sync::Arc;

use glam::{DMat4, DVec3};
use zline_shading::{Environment, EnvironmentLight, Panorama};

use super::*;

/// A panorama of `w × h` texels, each `f` of its centre direction.
fn panorama(w: u32, h: u32, f: impl Fn(DVec3) -> DVec3) -> Panorama {
    let mut texels = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let d = direction((f64::from(i) + 0.5) / f64::from(w), (f64::from(j) + 0.5) / f64::from(h));
            texels.push(f(d).as_vec3());
        }
    }
    Panorama::new(w, h, texels).unwrap().0
}

/// The truth's environment of `panorama` at intensity 1, rotated
/// `degrees`, seen from a view matrix `view`.
fn truth_of(panorama: Panorama, degrees: f32, view: &DMat4) -> EnvironmentF64 {
    let mut e = Environment::new(Arc::new(EnvironmentLight::new(panorama)));
    e.rotation_degrees = degrees;
    EnvironmentF64::new(&e, view)
}

/// Some unit directions, the poles and the horizon among them.
fn directions() -> Vec<DVec3> {
    let mut v = vec![DVec3::Y, DVec3::NEG_Y, DVec3::X, DVec3::NEG_Z, DVec3::new(0.3, -0.5, 0.8).normalize()];
    for k in 0..12 {
        let t = f64::from(k) * 0.7;
        v.push(DVec3::new(t.cos() * (0.1 * t).cos(), (0.3 * t).sin(), t.sin()).normalize());
    }
    v
}

/// GGX's (N·l)-weighted mean of cos θ_l around R, ∫(N·l)² du₁ / ∫(N·l) du₁
/// in GGX's variable (midpoint rule, 10⁶ nodes): what a lobe average of
/// a linear radiance a + b·(d·e) is, a + b·(R·e)·mean.
fn mean_cosine(alpha2: f64) -> f64 {
    let n = 1_000_000;
    let (mut m1, mut m2) = (0.0, 0.0);
    for k in 0..n {
        let u = (f64::from(k) + 0.5) / f64::from(n);
        let cos2 = (1.0 - u) / (1.0 + (alpha2 - 1.0) * u);
        let nl = 2.0 * cos2 - 1.0;
        if nl > 0.0 {
            m1 += nl;
            m2 += nl * nl;
        }
    }
    m2 / m1
}

#[test]
fn uniform_panorama_gives_its_radiance() {
    let c = DVec3::new(0.25, 0.5, 1.0);
    let env = truth_of(panorama(64, 32, |_| c), 0.0, &DMat4::IDENTITY);
    let mut worst = 0.0f64;
    for d in directions() {
        // E/π: the centre rule leaves a residue in band 2 (Σ(3z² − 1)dω ≠ 0).
        worst = worst.max(((env.irradiance(d) - c) / c).abs().max_element());
        for r in [0.0f64, 0.05, 0.3, 1.0] {
            let l = env.lobe_average(d, (r * r * r * r).max(1e-7), (KAPPA, MAX_SPLIT));
            assert!(((l - c) / c).abs().max_element() < 1e-12, "{d} r {r}: {l}");
        }
        assert!(((env.bilinear_along(d) - c) / c).abs().max_element() < 1e-12);
    }
    eprintln!("uniform panorama: E/π relative error {worst:.2e}");
    // Measured 4.0e-4 (64 × 32): the quadrature of Y20 over rows.
    assert!(worst < 1e-3, "{worst}");
}

#[test]
fn irradiance_of_a_linear_radiance_is_the_closed_form() {
    // Radiance of bands 0–2, which nine coefficients hold exactly:
    // L = a + b·(d·e) gives E(N)/π = a + (2/3)·b·(N·e) (Â₁/π = 2/3), and
    // L = (d·e)² = 1/3 + ((d·e)² − 1/3) (bands 0 and 2) gives
    // E/π = 1/3 + (1/4)·((N·e)² − 1/3) (Â₂/π = 1/4).
    let e = DVec3::new(0.48, 0.6, 0.64);
    let env = truth_of(
        panorama(256, 128, |d| DVec3::new(1.0 + 0.5 * d.dot(e), d.dot(e).powi(2), 1.0)),
        0.0,
        &DMat4::IDENTITY,
    );
    let mut worst = 0.0f64;
    for n in directions() {
        let ne = n.dot(e);
        let want = DVec3::new(1.0 + 0.5 * (2.0 / 3.0) * ne, 1.0 / 3.0 + 0.25 * (ne * ne - 1.0 / 3.0), 1.0);
        worst = worst.max((env.irradiance(n) - want).abs().max_element());
    }
    eprintln!("linear and quadratic radiance: E/π off by {worst:.2e}");
    // Measured 5.5e-5 (256 × 128 texels, centre rule).
    assert!(worst < 2e-4, "{worst}");
}

#[test]
fn lobe_average_of_a_linear_radiance_is_the_closed_form() {
    // L(d) = a + b·(d·e) read bilinearly: the lobe average is
    // a + b·(R·e)·⟨cos θ_l⟩, to the bilinear reading's error.
    let e = DVec3::new(-0.36, 0.8, 0.48);
    let env = truth_of(panorama(128, 64, |d| DVec3::splat(1.0 + 0.5 * d.dot(e))), 0.0, &DMat4::IDENTITY);
    let mut report = String::new();
    let mut worst = 0.0f64;
    for r in [0.0f64, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0] {
        let alpha2 = (r.powi(4)).max(1e-7);
        let mean = mean_cosine(alpha2);
        let mut at_r = 0.0f64;
        // Not at the poles, where the bilinear reading (v clamps) of the
        // first row is not the linear function.
        for d in directions().into_iter().filter(|d| d.y.abs() < 0.99) {
            let want = 1.0 + 0.5 * d.dot(e) * mean;
            let got = env.lobe_average(d, alpha2, (KAPPA, MAX_SPLIT)).x;
            at_r = at_r.max((got - want).abs());
        }
        report += &format!(" r {r}: {at_r:.1e};");
        worst = worst.max(at_r);
    }
    eprintln!("lobe average of a linear radiance, worst error per roughness:{report}");
    // Measured at most 1.6e-4, at every roughness: the bilinear reading
    // of a linear function at 128 × 64 texels (r = 0 is that reading).
    assert!(worst < 3e-4, "{worst}");
}

#[test]
fn lobe_average_converges_on_the_sky() {
    // The procedural sky (its sun 200 times brighter than the sky): cells
    // four times smaller (and a cap four times narrower) change the
    // average by little, at every roughness, with R on and near the sun.
    let env = truth_of(Panorama::sky(64, 32), 0.0, &DMat4::IDENTITY);
    let sun = zline_shading::SKY_SUN.as_dvec3();
    let mut rs = directions();
    rs.extend([
        sun,
        (sun + DVec3::new(0.05, 0.0, 0.0)).normalize(),
        (sun + DVec3::new(0.0, -0.3, 0.1)).normalize(),
    ]);
    let mut report = String::new();
    let mut worst = 0.0f64;
    for r in [0.0f64, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0] {
        let alpha2 = (r.powi(4)).max(1e-7);
        let mut at_r = 0.0f64;
        for d in &rs {
            let coarse = env.lobe_average(*d, alpha2, (KAPPA, MAX_SPLIT));
            let fine = env.lobe_average(*d, alpha2, (KAPPA / 4.0, MAX_SPLIT * 4));
            at_r = at_r.max(((coarse - fine).abs() / fine.max(DVec3::splat(0.05))).max_element());
        }
        report += &format!(" r {r}: {at_r:.1e};");
        worst = worst.max(at_r);
    }
    eprintln!("lobe average on the sky, relative change with 4× smaller cells:{report}");
    // Measured at most 7.0e-5 (r = 0.5; 6.2e-5 at r = 0.05, in the cap).
    assert!(worst < 3e-4, "{worst}");
}

#[test]
fn a_sharp_lobe_reads_the_mirror_direction() {
    let env = truth_of(Panorama::sky(64, 32), 0.0, &DMat4::IDENTITY);
    for d in directions() {
        let mirror = env.bilinear_along(d);
        let sharp = env.lobe_average(d, 1e-7, (KAPPA, MAX_SPLIT));
        assert!(((sharp - mirror).abs() / mirror).max_element() < 1e-3, "{d}: {sharp} vs {mirror}");
    }
}

#[test]
fn rotation_and_eye_frame() {
    // Every texel distinct; the panorama turned 90° about +y: world −z
    // reads the panorama at R_y(−90°)·(−z) = +x, column u = 3/4.
    let p = panorama(8, 4, |d| DVec3::new(d.x + 2.0, d.y + 2.0, d.z + 2.0));
    let env = truth_of(p.clone(), 90.0, &DMat4::IDENTITY);
    let plain = truth_of(p, 0.0, &DMat4::IDENTITY);
    let close = |a: DVec3, b: DVec3| (a - b).abs().max_element() < 1e-12;
    assert!(close(env.radiance(DVec3::NEG_Z), plain.bilinear_along(DVec3::X)));
    assert!(close(env.bilinear_along(DVec3::X), lobe::bilinear(&env.texels, (8, 4), 0.75, 0.5)));
    // A camera looking along world +x: eye −z is world +x.
    let view = DMat4::look_at_rh(DVec3::ZERO, DVec3::X, DVec3::Y);
    let turned = truth_of(panorama(8, 4, |d| d + DVec3::splat(2.0)), 0.0, &view);
    assert!(close(turned.radiance(DVec3::NEG_Z), plain.bilinear_along(DVec3::X)));
    assert!(close(turned.diffuse(DVec3::NEG_Z), plain.irradiance(DVec3::X)));
    let (a, b) = (turned.specular(DVec3::Y, 0.1), plain.lobe_average(DVec3::Y, 0.1, (KAPPA, MAX_SPLIT)));
    assert!((a - b).abs().max_element() < 1e-9, "{a} vs {b}");
}

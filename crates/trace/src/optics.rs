//! Reflection and refraction directions (SPEC §12).
//!
//! The course's (and Whitted's 1980) form of the transmitted direction,
//! with V the unit vector from the surface towards where the ray came from
//! and N the unit normal on V's side (V·N > 0):
//!
//! - V′ = V / (V·N), so that V′·N = 1 and N − V′ is the tangential part
//!   of the incident direction −V′;
//! - k_n = n_t / n_i, the index of the medium entered over the index of
//!   the medium left;
//! - the radicand k_n²·|V′|² − |N − V′|²: total internal reflection where
//!   it is ≤ 0, else k_f = radicand^(−1/2) and
//! - T = k_f·(N − V′) − N, not of unit length.
//!
//! It is vector Snell's law in other clothes: the tests compare its
//! direction with t = η·d + (η·cos θ_i − cos θ_t)·N (η = n_i/n_t) in f64.
//! The mirror direction is R = 2(N·V)N − V.

use glam::{DVec3, Vec3};

/// The mirror direction of `v` (unit, towards the viewer) about `n`
/// (unit): R = 2(N·V)N − V, unit length.
#[inline]
pub fn reflect(v: Vec3, n: Vec3) -> Vec3 {
    2.0 * n.dot(v) * n - v
}

/// The course's transmitted direction for `v` (unit, towards where the
/// ray came from), `n` (unit, on v's side) and `k_n` = n_t/n_i: `None` for
/// total internal reflection (the radicand ≤ 0), else T = k_f(N − V′) − N,
/// normalized. Computed in f64 ([`refract_f64`]): a refraction is rare
/// beside the rays' other work, and the critical angle is then decided as
/// the truth decides it.
#[inline]
pub fn refract(v: Vec3, n: Vec3, k_n: f32) -> Option<Vec3> {
    refract_f64(v.as_dvec3(), n.as_dvec3(), f64::from(k_n)).map(|t| t.normalize().as_vec3())
}

/// The course's formula in f64 (see the module doc), not normalized.
pub fn refract_f64(v: DVec3, n: DVec3, k_n: f64) -> Option<DVec3> {
    let cos = v.dot(n);
    if cos <= 0.0 || !cos.is_finite() {
        return None;
    }
    let v1 = v / cos;
    let tangent = n - v1;
    let radicand = k_n * k_n * v1.length_squared() - tangent.length_squared();
    if radicand <= 0.0 || radicand.is_nan() {
        return None;
    }
    Some(tangent / radicand.sqrt() - n)
}

/// Vector Snell's law: the unit transmitted direction for the unit
/// incident direction `d` (towards the surface), the unit normal `n`
/// against it (d·n < 0) and η = n_i/n_t; `None` for total internal
/// reflection (sin²θ_t > 1).
pub fn snell_f64(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(eta * d + (eta * cos_i - cos_t) * n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn unit() -> impl Strategy<Value = DVec3> {
        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
            .prop_map(|(x, y, z)| DVec3::new(x, y, z))
            .prop_filter("not too short", |v| v.length() > 1e-3)
            .prop_map(DVec3::normalize)
    }

    /// `v` turned to `n`'s side.
    fn towards(v: DVec3, n: DVec3) -> DVec3 {
        if v.dot(n) < 0.0 {
            -v
        } else {
            v
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// The course's formula is Snell's law: the same unit direction
        /// within 1e-12, and total internal reflection in the same cases.
        #[test]
        fn the_course_formula_is_snells_law(v in unit(), n in unit(), k_n in 0.2f64..3.0) {
            let v = towards(v, n);
            prop_assume!(v.dot(n) > 1e-6);
            let course = refract_f64(v, n, k_n);
            let snell = snell_f64(-v, n, 1.0 / k_n);
            match (course, snell) {
                (Some(t), Some(s)) => {
                    let t = t.normalize();
                    prop_assert!((t - s).length() < 1e-12, "{t} vs {s}");
                    prop_assert!((s.length() - 1.0).abs() < 1e-12);
                    // Snell: n_i·sin θ_i = n_t·sin θ_t.
                    let (sin_i, sin_t) = (v.cross(n).length(), t.cross(n).length());
                    prop_assert!((sin_i - k_n * sin_t).abs() < 1e-12);
                }
                (None, None) => {}
                // At the critical angle itself, rounding may put one on
                // either side: then the radicand is within rounding of 0.
                (a, b) => {
                    let cos = v.dot(n);
                    let v1 = v / cos;
                    let radicand = k_n * k_n * v1.length_squared() - (n - v1).length_squared();
                    prop_assert!(radicand.abs() < 1e-12 * v1.length_squared(), "{a:?} {b:?} radicand {radicand}");
                }
            }
        }

        /// Total internal reflection exactly where the radicand is ≤ 0.
        #[test]
        fn internal_reflection_where_the_radicand_is_not_positive(v in unit(), n in unit(), k_n in 0.2f64..1.0) {
            let v = towards(v, n);
            prop_assume!(v.dot(n) > 1e-6);
            let v1 = v / v.dot(n);
            let radicand = k_n * k_n * v1.length_squared() - (n - v1).length_squared();
            prop_assert_eq!(refract_f64(v, n, k_n).is_none(), radicand <= 0.0);
        }

        /// The f32 renderer's formula follows the f64 one.
        #[test]
        fn f32_follows_f64(v in unit(), n in unit(), k_n in 0.5f64..2.5) {
            let v = towards(v, n);
            prop_assume!(v.dot(n) > 0.05);
            let (vf, nf) = (v.as_vec3(), n.as_vec3());
            let want = refract_f64(v, n, k_n).map(DVec3::normalize);
            let got = refract(vf, nf, k_n as f32);
            if let (Some(w), Some(g)) = (want, got) {
                prop_assert!((w - g.as_dvec3()).length() < 1e-4, "{w} vs {g}");
            }
        }
    }

    /// Hand-computed: into glass (n = 1.5) at 45°: sin θ_t = sin 45°/1.5.
    #[test]
    fn glass_at_45_degrees() {
        let v = DVec3::new(-1.0, 1.0, 0.0).normalize(); // from the viewer at upper left
        let t = refract_f64(v, DVec3::Y, 1.5).unwrap().normalize();
        let sin_t = (0.5f64).sqrt() / 1.5;
        assert!((t.x - sin_t).abs() < 1e-15 && (t.y + (1.0 - sin_t * sin_t).sqrt()).abs() < 1e-15, "{t}");
        // Leaving glass at 45°: sin θ_t = 1.5·0.707 > 1, total reflection.
        assert!(refract_f64(v, DVec3::Y, 1.0 / 1.5).is_none());
        // Straight through at normal incidence, any index.
        assert_eq!(refract_f64(DVec3::Y, DVec3::Y, 1.33).unwrap().normalize(), -DVec3::Y);
    }

    #[test]
    fn mirror_direction() {
        let v = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!((reflect(v, Vec3::Y) - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-7);
        assert_eq!(refract(-Vec3::Y, Vec3::Y, 1.5), None, "no incident side");
    }
}

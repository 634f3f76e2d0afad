//! The irradiance of an environment in nine spherical-harmonic coefficients
//! per channel (Ramamoorthi and Hanrahan 2001, "An Efficient Representation
//! for Irradiance Environment Maps"): the radiance projected on the real SH
//! basis up to band 2, each band multiplied by the clamped cosine's
//! coefficient Â_l/π = 1, 2/3, 1/4, so that Σ c_i·Y_i(N) is E(N)/π. Bands
//! 0–2 hold about 99 % of the cosine lobe's energy; what they miss is
//! measured in the tests against a direct integral.

use glam::{DVec3, Vec3};

use super::panorama::Panorama;

/// Coefficients per channel (bands 0, 1, 2).
pub const SH_COEFFICIENTS: usize = 9;

/// Â_l/π for the coefficient's band.
const BAND_SCALE: [f64; SH_COEFFICIENTS] =
    [1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25];

/// The basis' normalizations: 1/(2√π), √(3/4π), ½√(15/π), ¼√(5/π),
/// ¼√(15/π).
const SH_NORMS: [f64; 5] = [
    0.282_094_791_773_878_1,
    0.488_602_511_902_919_9,
    1.092_548_430_592_079_2,
    0.315_391_565_252_520_05,
    0.546_274_215_296_039_6,
];

/// The real SH basis Y_0..Y_8 at unit `n`, in the usual order
/// (Y00; Y1−1, Y10, Y11; Y2−2 … Y22) with z as the polar axis.
#[inline]
pub fn sh_basis(n: Vec3) -> [f32; SH_COEFFICIENTS] {
    basis(n.x, n.y, n.z, SH_NORMS.map(|c| c as f32))
}

/// The basis in f64, for the projection.
fn sh_basis_f64(n: DVec3) -> [f64; SH_COEFFICIENTS] {
    basis(n.x, n.y, n.z, SH_NORMS)
}

/// The basis at (x, y, z) with the normalizations `k`, written once for
/// f32 and f64.
#[inline]
fn basis<T>(x: T, y: T, z: T, k: [T; 5]) -> [T; SH_COEFFICIENTS]
where
    T: Copy + From<f32> + std::ops::Mul<Output = T> + std::ops::Sub<Output = T>,
{
    let (one, three) = (T::from(1.0), T::from(3.0));
    [
        k[0],
        k[1] * y,
        k[1] * z,
        k[1] * x,
        k[2] * x * y,
        k[2] * y * z,
        k[3] * (three * z * z - one),
        k[2] * x * z,
        k[4] * (x * x - y * y),
    ]
}

/// The coefficients c_i with E(N)/π = Σ c_i·Y_i(N), in the panorama's
/// frame: each texel's radiance times its solid angle projected on the
/// basis, summed in f64 in row order.
pub(super) fn irradiance_sh(panorama: &Panorama) -> [Vec3; SH_COEFFICIENTS] {
    let (w, h) = (panorama.width(), panorama.height());
    let mut sum = [DVec3::ZERO; SH_COEFFICIENTS];
    for j in 0..h {
        let d_omega = panorama.texel_solid_angle(j);
        let v = (f64::from(j) + 0.5) / f64::from(h);
        for i in 0..w {
            let u = (f64::from(i) + 0.5) / f64::from(w);
            let (phi, theta) = (std::f64::consts::TAU * (u - 0.5), std::f64::consts::PI * v);
            let n = DVec3::new(theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos());
            let radiance = panorama.texels()[(j * w + i) as usize].as_dvec3() * d_omega;
            for (s, y) in sum.iter_mut().zip(sh_basis_f64(n)) {
                *s += radiance * y;
            }
        }
    }
    std::array::from_fn(|k| (sum[k] * BAND_SCALE[k]).as_vec3())
}

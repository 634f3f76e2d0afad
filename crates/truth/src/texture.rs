//! Texture filtering (SPEC §7) in f64, reading stored texels through
//! `Texture::texel` — none of the fast sampling code.
//!
//! Conventions of the scene model's textures: s = 0 at the left, t = 0 at
//! the bottom, rows of a level counted from the bottom; texel k of an axis
//! of `size` texels has its centre at (k + ½)/size.
//! - Nearest (level 0): texel ⌊s·w⌋, ⌊t·h⌋ (a coordinate on a texel
//!   boundary takes the texel above it).
//! - Bilinear on a level: u = s·w − ½, the texels ⌊u⌋ and ⌊u⌋ + 1 blended by
//!   u − ⌊u⌋, first along s on the two rows, then along t.
//! - Trilinear: the level of detail λ = log2 of the larger screen-axis
//!   footprint in level-0 texels, max(|(∂s/∂x·w, ∂t/∂x·h)|,
//!   |(∂s/∂y·w, ∂t/∂y·h)|), from exact derivatives in sample space;
//!   λ ≤ 0 (or NaN) reads bilinear level 0, λ ≥ the last level reads
//!   bilinear on it, and otherwise bilinear on levels ⌊λ⌋ and ⌊λ⌋ + 1 is
//!   blended by λ − ⌊λ⌋.
//! - Wrapping applies to integer texel indices after the filter chose them:
//!   repeat is the index modulo the size, clamp-to-edge clamps it.
//! - A non-finite coordinate reads texel 0 of that axis (weight 0 on its
//!   neighbour), as the fast renderer does.

use glam::{DVec2, DVec4};
use zline_shading::{Filter, Sampler, Texture, Wrap};

/// Derivatives of (s, t) along the sample-space x and y axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct UvDerivatives {
    /// ∂(s, t)/∂x.
    pub(crate) dx: DVec2,
    /// ∂(s, t)/∂y.
    pub(crate) dy: DVec2,
}

/// The filtered texture value at `uv` with the given derivatives.
pub(crate) fn sample(texture: &Texture, sampler: &Sampler, uv: DVec2, d: &UvDerivatives) -> DVec4 {
    match sampler.filter {
        Filter::Nearest => nearest(texture, sampler, uv),
        Filter::Bilinear => bilinear(texture, 0, sampler, uv),
        Filter::Trilinear => {
            let lod = level_of_detail(texture, d);
            let last = texture.levels() - 1;
            if lod >= last as f64 {
                bilinear(texture, last, sampler, uv)
            } else if lod > 0.0 {
                let level = lod.floor();
                let finer = level as usize;
                let a = bilinear(texture, finer, sampler, uv);
                a + (bilinear(texture, finer + 1, sampler, uv) - a) * (lod - level)
            } else {
                bilinear(texture, 0, sampler, uv)
            }
        }
    }
}

/// λ = log2 of the larger footprint in level-0 texels (−∞ for no
/// footprint, NaN for NaN derivatives).
pub(crate) fn level_of_detail(texture: &Texture, d: &UvDerivatives) -> f64 {
    let size = DVec2::new(f64::from(texture.width()), f64::from(texture.height()));
    let along_x = (d.dx * size).length();
    let along_y = (d.dy * size).length();
    along_x.max(along_y).log2()
}

fn nearest(texture: &Texture, sampler: &Sampler, uv: DVec2) -> DVec4 {
    let (w, h) = texture.level_size(0);
    let index = |c: f64, size: u32, wrap: Wrap| {
        let u = c * f64::from(size);
        wrap_index(if u.is_finite() { u.floor() as i64 } else { 0 }, size, wrap)
    };
    let (x, y) = (index(uv.x, w, sampler.wrap_s), index(uv.y, h, sampler.wrap_t));
    texture.texel(0, x, y).as_dvec4()
}

fn bilinear(texture: &Texture, level: usize, sampler: &Sampler, uv: DVec2) -> DVec4 {
    let (w, h) = texture.level_size(level);
    let taps = |c: f64, size: u32, wrap: Wrap| {
        let u = c * f64::from(size) - 0.5;
        let (i, f) = if u.is_finite() { (u.floor() as i64, u - u.floor()) } else { (0, 0.0) };
        (wrap_index(i, size, wrap), wrap_index(i.saturating_add(1), size, wrap), f)
    };
    let (x0, x1, fs) = taps(uv.x, w, sampler.wrap_s);
    let (y0, y1, ft) = taps(uv.y, h, sampler.wrap_t);
    let texel = |x, y| texture.texel(level, x, y).as_dvec4();
    let below = texel(x0, y0) + (texel(x1, y0) - texel(x0, y0)) * fs;
    let above = texel(x0, y1) + (texel(x1, y1) - texel(x0, y1)) * fs;
    below + (above - below) * ft
}

fn wrap_index(i: i64, size: u32, wrap: Wrap) -> u32 {
    let n = i64::from(size);
    match wrap {
        Wrap::Repeat => i.rem_euclid(n) as u32,
        Wrap::ClampToEdge => i.clamp(0, n - 1) as u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker() -> Texture {
        // 2×2, image rows top first: top row red, green; bottom row blue, white.
        let px = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
        Texture::from_rgba8(2, 2, &px).unwrap()
    }

    #[test]
    fn nearest_and_bilinear_follow_the_conventions() {
        let t = checker();
        let s = |filter, wrap| Sampler { filter, wrap_s: wrap, wrap_t: wrap };
        let none = UvDerivatives::default();
        // Bottom-left texel (blue) at s, t ∈ [0, ½).
        assert_eq!(
            sample(&t, &s(Filter::Nearest, Wrap::Repeat), DVec2::new(0.1, 0.2), &none),
            DVec4::new(0.0, 0.0, 1.0, 1.0)
        );
        assert_eq!(sample(&t, &s(Filter::Nearest, Wrap::Repeat), DVec2::new(1.6, -0.8), &none), DVec4::ONE);
        // The middle of the texture: the mean of the four texels.
        let mid = sample(&t, &s(Filter::Bilinear, Wrap::Repeat), DVec2::splat(0.5), &none);
        assert!((mid - DVec4::new(0.5, 0.5, 0.5, 1.0)).abs().max_element() < 1e-7, "{mid}");
        // Clamp at the corner reads the corner texel; repeat blends across.
        let corner = sample(&t, &s(Filter::Bilinear, Wrap::ClampToEdge), DVec2::ZERO, &none);
        assert_eq!(corner, DVec4::new(0.0, 0.0, 1.0, 1.0));
        let wrapped = sample(&t, &s(Filter::Bilinear, Wrap::Repeat), DVec2::ZERO, &none);
        assert!((wrapped - mid).abs().max_element() < 1e-7);
    }

    #[test]
    fn trilinear_blends_levels_by_the_level_of_detail() {
        let t = checker();
        let sampler = Sampler { filter: Filter::Trilinear, ..Sampler::default() };
        let uv = DVec2::new(0.3, 0.3);
        // Footprint of 1.5 texels: λ = log2(1.5), between level 0 and level 1.
        let d = UvDerivatives { dx: DVec2::new(0.75, 0.0), dy: DVec2::new(0.0, 0.5) };
        let lod = 1.5f64.log2();
        assert!((level_of_detail(&t, &d) - lod).abs() < 1e-15);
        let a = bilinear(&t, 0, &sampler, uv);
        let b = bilinear(&t, 1, &sampler, uv);
        let got = sample(&t, &sampler, uv, &d);
        assert!((got - (a + (b - a) * lod)).abs().max_element() < 1e-12);
    }
}

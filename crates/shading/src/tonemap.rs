//! Tone mapping (SPEC §10): the colour a frame holds, multiplied by the
//! exposure, mapped into [0, 1] for display. `None` clamps, as zline always
//! has; the two operators are the Khronos glTF Sample Viewer's
//! (`source/Renderer/shaders/tonemapping.glsl`), each followed by the sRGB
//! transfer function, as the Sample Viewer's display path: Khronos PBR
//! Neutral, which keeps base colours up to 0.8 unchanged and compresses
//! only highlights, and ACES filmic in Stephen Hill's fit (with the
//! Sample Viewer's exposure boost of 1/0.6).

use glam::{Mat3, Vec3};

/// The operator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ToneMap {
    /// Clamp to [0, 1], no transfer function (SPEC §10 as before).
    #[default]
    None,
    /// Khronos PBR Neutral, then sRGB.
    KhrPbrNeutral,
    /// ACES filmic (Hill's fit), then sRGB.
    Aces,
}

impl ToneMap {
    /// Every operator, in the order the CLI lists them.
    pub const ALL: [ToneMap; 3] = [ToneMap::None, ToneMap::KhrPbrNeutral, ToneMap::Aces];

    /// The name the CLI and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            ToneMap::None => "none",
            ToneMap::KhrPbrNeutral => "khr-pbr-neutral",
            ToneMap::Aces => "aces",
        }
    }
}

/// An operator with its exposure (a factor on the colour, applied first).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToneMapping {
    /// The operator.
    pub operator: ToneMap,
    /// Multiplies the colour before the operator; 1 by default.
    pub exposure: f32,
}

impl Default for ToneMapping {
    fn default() -> Self {
        ToneMapping { operator: ToneMap::None, exposure: 1.0 }
    }
}

impl ToneMapping {
    /// True when the frame's colours pass through unchanged but for the
    /// clamp to [0, 1]: no operator, exposure 1. Shading may then clamp as
    /// it goes; otherwise it keeps values above 1 for the operator.
    pub fn is_identity(&self) -> bool {
        self.operator == ToneMap::None && self.exposure == 1.0
    }

    /// The largest value shading keeps per channel: 1 when the mapping is
    /// the identity (SPEC §5's clamp), else f32::MAX (the operator sees the
    /// unclamped colour).
    pub fn ceiling(&self) -> f32 {
        if self.is_identity() {
            1.0
        } else {
            f32::MAX
        }
    }

    /// The display colour of linear colour `c`, in [0, 1] (NaN becomes 0).
    pub fn apply(&self, c: Vec3) -> Vec3 {
        let c = (c * self.exposure).max(Vec3::ZERO);
        let mapped = match self.operator {
            ToneMap::None => return c.min(Vec3::ONE),
            ToneMap::KhrPbrNeutral => khr_pbr_neutral(c),
            ToneMap::Aces => aces_hill(c / 0.6),
        };
        srgb_encode(mapped.clamp(Vec3::ZERO, Vec3::ONE))
    }
}

/// Khronos PBR Neutral (Khronos, 2024).
fn khr_pbr_neutral(mut color: Vec3) -> Vec3 {
    const START_COMPRESSION: f32 = 0.8 - 0.04;
    const DESATURATION: f32 = 0.15;
    let x = color.min_element();
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    color -= Vec3::splat(offset);
    let peak = color.max_element();
    if peak < START_COMPRESSION {
        return color;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    color *= new_peak / peak;
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    color.lerp(Vec3::splat(new_peak), g)
}

/// ACES filmic, Stephen Hill's fit of the RRT and ODT.
fn aces_hill(color: Vec3) -> Vec3 {
    // Column-major, as the GLSL source writes them.
    let input = Mat3::from_cols_array(&[
        0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777,
    ]);
    let output = Mat3::from_cols_array(&[
        1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602,
    ]);
    let v = input * color;
    let a = v * (v + Vec3::splat(0.024_578_6)) - Vec3::splat(0.000_090_537);
    let b = v * (v * 0.983_729 + Vec3::splat(0.432_951)) + Vec3::splat(0.238_081);
    output * (a / b)
}

/// The sRGB transfer function (IEC 61966-2-1) per channel, for c in [0, 1].
fn srgb_encode(c: Vec3) -> Vec3 {
    Vec3::from_array(c.to_array().map(|v| {
        if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_clamps_and_keeps_the_rest() {
        let t = ToneMapping::default();
        assert!(t.is_identity());
        assert_eq!(t.ceiling(), 1.0);
        assert_eq!(t.apply(Vec3::new(-1.0, 0.25, 3.0)), Vec3::new(0.0, 0.25, 1.0));
        let dim = ToneMapping { exposure: 0.5, ..t };
        assert!(!dim.is_identity());
        assert_eq!(dim.apply(Vec3::new(1.0, 3.0, 0.5)), Vec3::new(0.5, 1.0, 0.25));
    }

    #[test]
    fn neutral_keeps_base_colours_and_compresses_highlights() {
        let t = ToneMapping { operator: ToneMap::KhrPbrNeutral, exposure: 1.0 };
        // Below the compression start (and with min ≥ 0.08) the operator
        // only subtracts 0.04 everywhere... then sRGB.
        let c = Vec3::new(0.5, 0.3, 0.2);
        let expect = srgb_encode(c - Vec3::splat(0.04));
        assert!((t.apply(c) - expect).abs().max_element() < 1e-6);
        // Monotone in brightness, bounded by 1, white goes to white-ish.
        let mut last = 0.0;
        for k in 0..100 {
            let v = t.apply(Vec3::splat(k as f32 * 0.2)).x;
            assert!(v >= last && v <= 1.0, "{k}: {v}");
            last = v;
        }
        assert!(t.apply(Vec3::splat(1e6)).min_element() > 0.999);
    }

    #[test]
    fn aces_matches_its_reference_points() {
        let t = ToneMapping { operator: ToneMap::Aces, exposure: 1.0 };
        assert_eq!(t.apply(Vec3::ZERO), Vec3::ZERO);
        // Mid grey 0.18 maps near 0.18·(1/0.6) through the fit: about 0.27
        // linear before sRGB (the curve's toe and shoulder leave it there).
        let grey = t.apply(Vec3::splat(0.18));
        assert!((grey.x - grey.y).abs() < 1e-3 && (0.45..0.65).contains(&grey.x), "{grey}");
        assert!(t.apply(Vec3::splat(100.0)).min_element() > 0.99);
        assert!(t.apply(Vec3::splat(f32::NAN)).is_finite());
    }

    #[test]
    fn srgb_encoding_is_continuous_at_the_joint() {
        let below = srgb_encode(Vec3::splat(0.003_130_8)).x;
        let above = srgb_encode(Vec3::splat(0.003_130_9)).x;
        assert!((above - below).abs() < 1e-5);
        assert!((srgb_encode(Vec3::ONE).x - 1.0).abs() < 1e-6);
    }
}

//! The equirectangular panorama an environment is read from (SPEC §5.3).

use glam::Vec3;

/// The largest side of a panorama, in texels (a 16k × 8k panorama is 1.5 GiB
/// of f32 RGB; past this side a file is refused before it is decoded).
pub const MAX_PANORAMA_SIDE: u32 = 16_384;

/// Radiance from every direction, linear RGB, in an equirectangular
/// (latitude–longitude) image: column u ∈ [0, 1) is the azimuth φ = 2π(u − ½)
/// measured from −z towards +x, row v ∈ [0, 1] the polar angle θ = πv from
/// +y (row 0 is straight up). The centre of the image lies along −z, the
/// way a default camera looks.
#[derive(Clone, Debug, PartialEq)]
pub struct Panorama {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
}

/// Why a panorama cannot be used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PanoramaError {
    /// A side is 0, past [`MAX_PANORAMA_SIDE`], or the texel count does not
    /// match the sides.
    Size {
        /// Width given.
        width: u32,
        /// Height given.
        height: u32,
        /// Texels given.
        texels: usize,
    },
}

impl std::fmt::Display for PanoramaError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PanoramaError::Size { width, height, texels } => write!(
                f,
                "a {width} × {height} panorama with {texels} texels (each side 1 to {MAX_PANORAMA_SIDE}, \
                 width × height texels)"
            ),
        }
    }
}

impl std::error::Error for PanoramaError {}

impl Panorama {
    /// A panorama of `width × height` texels, rows from the top. A texel
    /// that is not finite or has a negative channel becomes 0 in that
    /// channel; the second value counts them (for a warning).
    pub fn new(width: u32, height: u32, mut texels: Vec<Vec3>) -> Result<(Panorama, usize), PanoramaError> {
        let valid_side = |s: u32| (1..=MAX_PANORAMA_SIDE).contains(&s);
        if !valid_side(width) || !valid_side(height) || texels.len() != width as usize * height as usize {
            return Err(PanoramaError::Size { width, height, texels: texels.len() });
        }
        let mut replaced = 0;
        for t in &mut texels {
            let clean =
                Vec3::from_array(t.to_array().map(|c| if c.is_finite() && c > 0.0 { c } else { 0.0 }));
            // -0.0 and 0.0 are both fine; count only real repairs.
            if !t.is_finite() || t.min_element() < 0.0 {
                replaced += 1;
            }
            *t = clean;
        }
        Ok((Panorama { width, height, texels }, replaced))
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texels, rows from the top.
    pub fn texels(&self) -> &[Vec3] {
        &self.texels
    }

    /// The unit direction through image position (u, v) ∈ [0, 1]².
    pub fn direction(u: f32, v: f32) -> Vec3 {
        let phi = std::f32::consts::TAU * (u - 0.5);
        let theta = std::f32::consts::PI * v;
        let (sin_t, cos_t) = theta.sin_cos();
        Vec3::new(sin_t * phi.sin(), cos_t, -sin_t * phi.cos())
    }

    /// Image position (u, v) of unit direction `d` (the inverse of
    /// [`Self::direction`]; u wraps at the seam behind the viewer).
    pub fn position(d: Vec3) -> (f32, f32) {
        let u = 0.5 + d.x.atan2(-d.z) / std::f32::consts::TAU;
        let v = d.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
        (u, v)
    }

    /// Bilinear radiance along unit direction `d` (u wraps, v clamps).
    pub fn sample(&self, d: Vec3) -> Vec3 {
        let (u, v) = Panorama::position(d);
        let (w, h) = (self.width as i64, self.height as i64);
        let x = u * self.width as f32 - 0.5;
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (h - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |i: i64, j: i64| self.texels[(j.min(h - 1) * w + i.rem_euclid(w)) as usize];
        let (i, j) = (x0 as i64, y0 as i64);
        let top = at(i, j).lerp(at(i + 1, j), fx);
        let bottom = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }

    /// The solid angle of a texel in row `j`: (2π/W)·(cos θ_top − cos θ_bottom),
    /// exactly (the rows' solid angles sum to 4π).
    pub fn texel_solid_angle(&self, j: u32) -> f64 {
        use std::f64::consts::PI;
        let theta = |row: u32| PI * f64::from(row) / f64::from(self.height);
        (2.0 * PI / f64::from(self.width)) * (theta(j).cos() - theta(j + 1).cos())
    }
}

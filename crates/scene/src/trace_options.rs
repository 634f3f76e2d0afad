//! The ray tracer's settings (SPEC §12): which renderer draws a scene, and
//! how `zline-trace` traces it. They are plain data, here so that a scene
//! file can carry them; the ray tracer is `zline-trace`.

/// Which renderer draws the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Renderer {
    /// The z-buffer pipeline.
    #[default]
    Raster,
    /// Whitted ray tracing (`zline-trace`).
    RayTrace,
    /// Radiosity (`zline-radiosity`), drawn by the z-buffer pipeline.
    Radiosity,
}

impl Renderer {
    /// The name the command line and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            Renderer::Raster => "raster",
            Renderer::RayTrace => "raytrace",
            Renderer::Radiosity => "radiosity",
        }
    }
}

/// Shadow rays through transparent occluders.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadowRays {
    /// Each occluder passes its kt = 1 − d of the light (the product over
    /// the occluders on the segment; no refraction of the shadow ray).
    #[default]
    Filtered,
    /// Any occluder stops the light.
    Opaque,
}

/// Which structure a render uses (`--accel`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AccelKind {
    /// The SAH bounding-volume hierarchy (the default).
    #[default]
    Bvh,
    /// The SAH kd-tree (pbrt-v3's), traversed front to back.
    Kd,
    /// The uniform grid, stepped cell to cell (3D-DDA).
    Grid,
    /// Every triangle for every ray (the oracle).
    None,
}

impl AccelKind {
    /// The name the command line uses.
    pub fn name(self) -> &'static str {
        match self {
            AccelKind::Bvh => "bvh",
            AccelKind::Kd => "kd",
            AccelKind::Grid => "grid",
            AccelKind::None => "none",
        }
    }
}

/// The most subdivision levels [`Adaptive::depth`] may ask for: 4 cuts a
/// pixel down to 16 × 16 squares.
pub const MAX_ADAPTIVE_DEPTH: u32 = 4;

/// The course's adaptive supersampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// Subdivision levels at most (0: corners and centre only).
    pub depth: u32,
    /// A square is cut when its five samples spread by more than this, in
    /// any channel of the tone-mapped display value (0 to 1).
    pub threshold: f32,
}

impl Default for Adaptive {
    fn default() -> Self {
        Adaptive { depth: 3, threshold: 1.0 / 16.0 }
    }
}

/// The deepest tree `zline-trace` traces: a larger depth limit is clamped to
/// it with a warning (with kr = 1 mirrors facing each other, each level
/// costs a ray per pixel; the ray budget of `zline_trace::whitted` bounds the rest).
pub const MAX_DEPTH: u32 = 64;

/// The largest supersampling factor (n × n rays a pixel).
pub const MAX_SAMPLES: u32 = 16;

/// How `zline-trace` traces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceOptions {
    /// The tree's depth limit: 1 traces the camera rays only (the local
    /// model with shadow rays).
    pub max_depth: u32,
    /// Branches whose weight falls below this (largest channel) are cut.
    pub min_weight: f32,
    /// How shadow rays pass transparent occluders.
    pub shadows: ShadowRays,
    /// The acceleration structure.
    pub accel: AccelKind,
    /// n: n × n camera rays a pixel, on a regular grid, averaged.
    pub samples: u32,
    /// Adaptive supersampling instead of the regular grid.
    pub adaptive: Option<Adaptive>,
}

impl Default for TraceOptions {
    fn default() -> Self {
        TraceOptions::DEFAULT
    }
}

impl TraceOptions {
    /// The defaults: depth 8, weight cutoff 1/512, filtered shadow rays,
    /// the BVH, one ray a pixel.
    pub const DEFAULT: TraceOptions = TraceOptions {
        max_depth: 8,
        min_weight: 1.0 / 512.0,
        shadows: ShadowRays::Filtered,
        accel: AccelKind::Bvh,
        samples: 1,
        adaptive: None,
    };
}

impl TraceOptions {
    /// The options with every value in range, and a warning for each one
    /// that was not.
    pub fn checked(&self) -> (TraceOptions, Vec<String>) {
        let mut o = *self;
        let mut warnings = Vec::new();
        if o.max_depth == 0 || o.max_depth > MAX_DEPTH {
            let to = o.max_depth.clamp(1, MAX_DEPTH);
            warnings.push(format!("a ray-tracing depth of {} is out of range: {to} is used", o.max_depth));
            o.max_depth = to;
        }
        if !(o.min_weight >= 0.0 && o.min_weight.is_finite()) {
            warnings.push(format!("a ray weight cutoff of {} is not a number ≥ 0: 0 is used", o.min_weight));
            o.min_weight = 0.0;
        }
        if o.samples == 0 || o.samples > MAX_SAMPLES {
            let to = o.samples.clamp(1, MAX_SAMPLES);
            warnings.push(format!("{} rays a pixel per axis is out of range: {to} is used", o.samples));
            o.samples = to;
        }
        if let Some(a) = &mut o.adaptive {
            if a.depth > MAX_ADAPTIVE_DEPTH {
                warnings.push(format!(
                    "an adaptive supersampling depth of {} is out of range: {MAX_ADAPTIVE_DEPTH} is used",
                    a.depth
                ));
                a.depth = MAX_ADAPTIVE_DEPTH;
            }
            if a.threshold.is_nan() || a.threshold < 0.0 {
                let to = Adaptive::default().threshold;
                warnings.push(format!(
                    "an adaptive threshold of {} is not a number ≥ 0: {to} is used",
                    a.threshold
                ));
                a.threshold = to;
            }
            if o.samples > 1 {
                warnings.push(format!("adaptive supersampling replaces the regular {0}×{0} grid", o.samples));
                o.samples = 1;
            }
        }
        (o, warnings)
    }
}

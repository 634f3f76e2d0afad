//! Radiosity's settings (SPEC §13), plain data here so that a scene file
//! can carry them (its `[radiosity]` table); the solver is
//! `zline-radiosity`.

/// The most hemicube resolution accepted (pixels along the top face).
pub const MAX_RESOLUTION: usize = 2048;

/// The most subdivision levels a solve takes (each at most quadruples
/// the patches it cuts).
pub const MAX_SUBDIVISION: u32 = 4;

/// How the radiosity equation is solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Sweeps over the matrix, each from the previous sweep's values.
    Jacobi,
    /// Sweeps over the matrix, each reading the values already updated.
    GaussSeidel,
    /// Shooting the most unshot power first, no matrix.
    #[default]
    Progressive,
}

impl Method {
    /// The name the command line and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            Method::Jacobi => "jacobi",
            Method::GaussSeidel => "gauss-seidel",
            Method::Progressive => "progressive",
        }
    }
}

/// How to mesh and solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiosityOptions {
    /// The longest patch edge, in world units; `None`: 1/16 of the
    /// scene's largest extent.
    pub patch_size: Option<f32>,
    /// The hemicube's top-face resolution (pixels a side).
    pub resolution: usize,
    /// The solver.
    pub method: Method,
    /// Stop when the residual (the power left to move over the source
    /// power) is at most this.
    pub tolerance: f64,
    /// Stop after this many sweeps or shots.
    pub max_steps: usize,
    /// Progressive refinement shoots from four points of a patch, not its
    /// centre (four hemicubes a shot; closer to reciprocity).
    pub area_shooting: bool,
    /// Near patches' form factors from the contour integral instead of the
    /// hemicube's pixels (the hemicube still decides what is seen).
    pub analytic_near: bool,
    /// Times to cut the patches where radiosity changes fast and solve
    /// again (0: the uniform mesh only).
    pub subdivide: u32,
    /// The scene's point, spot, directional and area lights shoot first,
    /// as point sources, besides the emitting surfaces.
    pub lights: bool,
}

impl Default for RadiosityOptions {
    fn default() -> RadiosityOptions {
        RadiosityOptions::DEFAULT
    }
}

impl RadiosityOptions {
    /// The defaults: the patch size from the scene, a 100-pixel hemicube,
    /// progressive refinement to 10⁻³, the lights on.
    pub const DEFAULT: RadiosityOptions = RadiosityOptions {
        patch_size: None,
        resolution: 100,
        method: Method::Progressive,
        tolerance: 1e-3,
        max_steps: 100_000,
        area_shooting: false,
        analytic_near: false,
        subdivide: 0,
        lights: true,
    };
}

//! Radiosity for zline (SPEC §13): the course's second global illumination
//! model. Every surface is an ideal diffuse reflector cut into patches of
//! constant radiosity ([`patch`]); the form factors come from hemicubes
//! drawn with zline's scan converter and z-buffer ([`hemicube`]); the
//! scene's lights are shot once, first, as point sources ([`lights`]); the
//! equation B_i = E_i + D_i + ρ_i Σ_j F_ij B_j is solved once,
//! independently of the viewpoint, by Jacobi, Gauss–Seidel or progressive
//! refinement ([`solve()`]). The solution is drawn by the rasterizer: radiosities
//! averaged to the patches' corners and Gouraud-interpolated
//! ([`Solution::display_scene`]), so a new viewpoint costs one frame.

use std::time::{Duration, Instant};

use glam::Vec3;
use zline_scene::Scene;
use zline_trace::world::World;

pub mod analytic;
pub mod cache;
mod display;
mod error;
pub mod hemicube;
pub mod lights;
pub mod patch;
pub mod solve;
pub mod subdivide;

pub use error::RadiosityError;

pub use patch::{Patch, Patches};
pub use solve::Convergence;
pub use zline_scene::radiosity_options::{Method, RadiosityOptions as Options, MAX_RESOLUTION};

/// The most patches a solve accepts (a 4 GB form-factor matrix for the
/// sweeps; progressive refinement keeps no matrix).
pub const MAX_PATCHES: usize = 1 << 16;
/// The most patches Jacobi and Gauss–Seidel accept (their matrix of form
/// factors: 1 GiB).
pub const MAX_MATRIX_PATCHES: usize = 1 << 14;

/// A solved scene.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The patches.
    pub patches: Patches,
    /// Each patch's radiosity (with the ambient term for progressive
    /// refinement).
    pub radiosity: Vec<Vec3>,
    /// The residual after each step.
    pub convergence: Convergence,
    /// The options used (the patch size resolved).
    pub options: Options,
    /// The patches cut at each subdivision level (indices into that
    /// level's patches, see [`subdivide`]).
    pub splits: Vec<Vec<u32>>,
    /// Time to mesh and solve.
    pub took: Duration,
}

/// Meshes and solves `scene`. The hemicube resolution is clamped to
/// [`MAX_RESOLUTION`] and the step count to 10⁶, each with a warning in
/// the solution's patches.
pub fn solve(scene: &Scene, options: &Options) -> Result<Solution, RadiosityError> {
    let start = Instant::now();
    let (patches, options) = mesh(scene, options)?;
    let mut solution = solve_refined(scene, patches, &options)?;
    solution.took = start.elapsed();
    Ok(solution)
}

/// Solves meshed `patches` of `scene` with resolved `options`, then
/// `options.subdivide` times (at most [`subdivide::MAX_LEVELS`]) cuts the
/// patches where radiosity changes fast and solves again; stops early,
/// with a warning, before passing [`MAX_PATCHES`].
pub fn solve_refined(scene: &Scene, patches: Patches, options: &Options) -> Result<Solution, RadiosityError> {
    let start = Instant::now();
    let mut solution = solve_patches(patches, options)?;
    let world = (options.subdivide > 0).then(|| World::new(scene));
    for _ in 0..options.subdivide.min(subdivide::MAX_LEVELS) {
        let cut = subdivide::marks(&solution.patches, &solution.radiosity);
        if cut.is_empty() {
            break;
        }
        let mut patches = subdivide::split(&solution.patches, &cut);
        if patches.patches.len() > MAX_PATCHES {
            solution.patches.warnings.push(format!(
                "subdivision stopped after {} levels: the next would pass {MAX_PATCHES} patches",
                solution.splits.len()
            ));
            break;
        }
        if let (Some(world), true) = (&world, options.lights) {
            lights::light(&mut patches.patches, world, &scene.lights);
        }
        let (mut splits, mut convergence) =
            (std::mem::take(&mut solution.splits), std::mem::take(&mut solution.convergence));
        solution = solve_patches(patches, options)?;
        splits.push(cut);
        convergence.residuals.append(&mut solution.convergence.residuals);
        convergence.hemicubes += solution.convergence.hemicubes;
        (solution.splits, solution.convergence) = (splits, convergence);
    }
    solution.took = start.elapsed();
    Ok(solution)
}

/// The patches a solution with `splits` ended on, from the same freshly
/// meshed `patches` of `scene` (a cached solution's; see [`mesh`]): the
/// cuts replayed, the children lit. `None` when a split names a patch
/// that is not there (a file from another mesh).
pub fn replay(
    scene: &Scene,
    mut patches: Patches,
    splits: &[Vec<u32>],
    options: &Options,
) -> Option<Patches> {
    if splits.is_empty() {
        return Some(patches);
    }
    for cut in splits {
        let fits =
            cut.windows(2).all(|w| w[0] < w[1]) && cut.iter().all(|&i| (i as usize) < patches.patches.len());
        if !fits || patches.patches.len() + 3 * cut.len() > MAX_PATCHES {
            return None;
        }
        patches = subdivide::split(&patches, cut);
    }
    if options.lights {
        lights::light(&mut patches.patches, &World::new(scene), &scene.lights);
    }
    Some(patches)
}

/// The patches of `scene` and the options resolved (the patch size
/// chosen, the resolution and step count clamped with a warning).
pub fn mesh(scene: &Scene, options: &Options) -> Result<(Patches, Options), RadiosityError> {
    let world = World::new(scene);
    let mut options = *options;
    let size = options.patch_size.unwrap_or_else(|| {
        let (lo, hi) = world
            .triangles
            .iter()
            .flatten()
            .filter(|p| p.is_finite())
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        ((hi - lo).max_element() / 16.0).max(f32::MIN_POSITIVE)
    });
    options.patch_size = Some(size);
    let mut patches = Patches::new(&world, size, MAX_PATCHES)?;
    if options.lights {
        lights::light(&mut patches.patches, &world, &scene.lights);
    }
    if patches.sourced() == Vec3::ZERO {
        let lights = if options.lights { "no light reaches a surface" } else { "the scene's lights are off" };
        patches.warnings.push(format!(
            "nothing lights the scene (no material emits, its ke is 0, and {lights}): radiosity is 0 everywhere"
        ));
    }
    if options.resolution > MAX_RESOLUTION {
        patches
            .warnings
            .push(format!("hemicube resolution {} clamped to {MAX_RESOLUTION}", options.resolution));
        options.resolution = MAX_RESOLUTION;
    }
    if options.max_steps > 1_000_000 {
        patches.warnings.push(format!("{} radiosity steps clamped to 1000000", options.max_steps));
        options.max_steps = 1_000_000;
    }
    if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
        patches.warnings.push(format!("radiosity tolerance {} taken as 0.001", options.tolerance));
        options.tolerance = 1e-3;
    }
    Ok((patches, options))
}

/// Solves meshed `patches` with resolved `options` (see [`mesh`]).
pub fn solve_patches(patches: Patches, options: &Options) -> Result<Solution, RadiosityError> {
    let start = Instant::now();
    let tolerance = options.tolerance;
    let (radiosity, convergence) = match options.method {
        Method::Progressive => {
            let mut cube = hemicube::Hemicube::new(options.resolution);
            solve::progressive(&patches.patches, &mut cube, options, true)
        }
        method => {
            if patches.patches.len() > MAX_MATRIX_PATCHES {
                return Err(RadiosityError::Matrix {
                    patches: patches.patches.len(),
                    max: MAX_MATRIX_PATCHES,
                });
            }
            let rows = solve::matrix(&patches.patches, options.resolution, options.analytic_near);
            solve::sweep(&patches.patches, &rows, method == Method::GaussSeidel, tolerance, options.max_steps)
        }
    };
    Ok(Solution {
        patches,
        radiosity,
        convergence,
        options: *options,
        splits: Vec::new(),
        took: start.elapsed(),
    })
}

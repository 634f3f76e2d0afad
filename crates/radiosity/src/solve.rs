//! The discrete radiosity equation B_i = S_i + ρ_i Σ_j F_ij B_j, per
//! channel, solved three ways. The source S_i = E_i + D_i is the patch's
//! emission and the scene's lights reflected once ([`Patch::source`]).
//!
//! - **Jacobi**: every B_i from the previous sweep's B (the full matrix of
//!   form factors first, a hemicube a patch).
//! - **Gauss–Seidel**: the same sweep reading the B_j already updated.
//! - **Progressive refinement** (Cohen et al. 1988, shooting): the patch
//!   with the most unshot power ΔB_i·A_i shoots it, ΔB_j += ρ_j ΔB_i F_ij
//!   A_i / A_j (reciprocity), one hemicube a shot and no matrix; the
//!   ambient term ρ_i·R·Σ ΔB_k A_k / Σ A_k, R = 1 / (1 − ρ̄), stands for
//!   the light not yet shot when the solution is displayed.
//!
//! The residual after each step, comparable across the three: the power
//! the step left to move over the source power, Σ|ΔB_i|·A_i / Σ S_i·A_i
//! (channels summed): for a sweep the change it made, for a shot the
//! unshot power.

use glam::Vec3;
use rayon::prelude::*;

use crate::hemicube::Hemicube;
use crate::patch::Patch;
use zline_scene::radiosity_options::RadiosityOptions as Options;

/// Progressive refinement keeps every shooter's row when all of them fit
/// in this many bytes (a hemicube draws the same row each time).
const ROW_CACHE_BYTES: usize = 512 << 20;

/// How a solve went.
#[derive(Clone, Debug, Default)]
pub struct Convergence {
    /// The residual after each step (sweep or shot; module doc).
    pub residuals: Vec<f64>,
    /// Hemicubes drawn (form-factor rows).
    pub hemicubes: usize,
}

/// Σ over channels of Σ |v_i|·A_i.
fn power(patches: &[Patch], values: impl Iterator<Item = Vec3>) -> f64 {
    patches.iter().zip(values).map(|(p, v)| f64::from(v.abs().element_sum() * p.area)).sum()
}

/// Every patch's form-factor row F_i·, a hemicube each, in parallel
/// (each row the same whatever the thread count); near patches' entries
/// analytic when `analytic_near` ([`crate::analytic::refine_near`]).
pub fn matrix(patches: &[Patch], res: usize, analytic_near: bool) -> Vec<Vec<f32>> {
    (0..patches.len())
        .into_par_iter()
        .map_init(
            || Hemicube::new(res),
            |cube, i| {
                let mut row = vec![0.0; patches.len()];
                cube.gather(patches, i, &mut row);
                if analytic_near {
                    crate::analytic::refine_near(patches, i, &mut row);
                }
                row
            },
        )
        .collect()
}

/// Jacobi or Gauss–Seidel sweeps over `rows` from B = S until the
/// residual is at most `tolerance` or `max_steps` sweeps.
pub fn sweep(
    patches: &[Patch],
    rows: &[Vec<f32>],
    seidel: bool,
    tolerance: f64,
    max_steps: usize,
) -> (Vec<Vec3>, Convergence) {
    let sourced = power(patches, patches.iter().map(Patch::source)).max(f64::MIN_POSITIVE);
    let mut b: Vec<Vec3> = patches.iter().map(Patch::source).collect();
    let mut next = b.clone();
    let mut convergence = Convergence { residuals: Vec::new(), hemicubes: rows.len() };
    for _ in 0..max_steps {
        let mut moved = 0.0;
        for (i, p) in patches.iter().enumerate() {
            let source = if seidel { &next } else { &b };
            let gathered: Vec3 =
                rows[i].iter().zip(source).filter(|(f, _)| **f > 0.0).map(|(&f, &bj)| f * bj).sum();
            let value = p.source() + p.reflectance * gathered;
            moved += f64::from((value - next[i]).abs().element_sum() * p.area);
            next[i] = value;
        }
        b.copy_from_slice(&next);
        let residual = moved / sourced;
        convergence.residuals.push(residual);
        if residual <= tolerance {
            break;
        }
    }
    (b, convergence)
}

/// Progressive refinement from B = ΔB = S until the unshot power is at
/// most `options.tolerance` of the source power or `options.max_steps`
/// shots, each from the shooter's centre, or from its four quarters with
/// `options.area_shooting` ([`Hemicube::gather_area`]), near patches'
/// form factors analytic with `options.analytic_near`; returns B, with the
/// ambient term added when `ambient`.
pub fn progressive(
    patches: &[Patch],
    cube: &mut Hemicube,
    options: &Options,
    ambient: bool,
) -> (Vec<Vec3>, Convergence) {
    let (tolerance, max_steps) = (options.tolerance, options.max_steps);
    let sourced = power(patches, patches.iter().map(Patch::source)).max(f64::MIN_POSITIVE);
    let mut b: Vec<Vec3> = patches.iter().map(Patch::source).collect();
    let mut unshot = b.clone();
    // The unshot power over the source power: 1 at the start (0 when nothing
    // emits), then after each shot.
    let mut residual = power(patches, unshot.iter().copied()) / sourced;
    let mut convergence = Convergence::default();
    let mut row = vec![0.0f32; patches.len()];
    let keep = patches.len() * patches.len() * 4 <= ROW_CACHE_BYTES;
    let mut kept: Vec<Option<Vec<f32>>> = if keep { vec![None; patches.len()] } else { Vec::new() };
    for _ in 0..max_steps {
        if residual <= tolerance {
            break;
        }
        let (i, _) = patches
            .iter()
            .enumerate()
            .map(|(i, p)| (i, unshot[i].element_sum() * p.area))
            .fold((0, f32::NEG_INFINITY), |best, c| if c.1 > best.1 { c } else { best });
        // A patch shoots several times (4.4 times a patch on the Cornell
        // box): its row is kept after the first, within the budget.
        let row: &[f32] = match kept.get(i) {
            Some(Some(row)) => row,
            _ => {
                row.fill(0.0);
                if options.area_shooting {
                    cube.gather_area(patches, i, &mut row);
                    convergence.hemicubes += 4;
                } else {
                    cube.gather(patches, i, &mut row);
                    convergence.hemicubes += 1;
                }
                if options.analytic_near {
                    crate::analytic::refine_near(patches, i, &mut row);
                }
                match kept.get_mut(i) {
                    Some(slot) => slot.insert(row.clone()),
                    None => &row,
                }
            }
        };
        let shot = unshot[i];
        unshot[i] = Vec3::ZERO;
        let shooter = patches[i].area;
        for (j, q) in patches.iter().enumerate() {
            if row[j] > 0.0 {
                let gained = q.reflectance * shot * (row[j] * shooter / q.area);
                b[j] += gained;
                unshot[j] += gained;
            }
        }
        residual = power(patches, unshot.iter().copied()) / sourced;
        convergence.residuals.push(residual);
    }
    if ambient {
        let total: f32 = patches.iter().map(|p| p.area).sum();
        let mean_rho =
            patches.iter().map(|p| p.reflectance * p.area).sum::<Vec3>() / total.max(f32::MIN_POSITIVE);
        let repeat = Vec3::ONE / (Vec3::ONE - mean_rho);
        let left = patches.iter().zip(&unshot).map(|(p, u)| *u * p.area).sum::<Vec3>()
            / total.max(f32::MIN_POSITIVE);
        for (bi, p) in b.iter_mut().zip(patches) {
            *bi += p.reflectance * repeat * left;
        }
    }
    (b, convergence)
}

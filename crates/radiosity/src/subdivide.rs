//! Subdivision where radiosity changes fast (SPEC §13): after a solve,
//! every patch whose radiosity differs from a patch sharing one of its
//! corners by more than [`THRESHOLD`] of the scene's bright level is cut
//! into four by its edges' midpoints, and the finer patches are solved
//! again. Shadow edges, the corners of a room and the foot of a wall get
//! small patches; a uniformly lit wall keeps its large ones.
//!
//! A cut patch's children keep its reflectance, emission and world
//! triangle; their first reflection of the lights is computed anew. Two
//! neighbours cut along a shared edge share its midpoint; a cut patch
//! beside an uncut one leaves a T-junction, which the display's corner
//! averaging smooths over.

use std::collections::HashMap;

use glam::Vec3;

use crate::patch::{Patch, Patches};

/// A patch is cut when its radiosity differs from a neighbour's by more
/// than this share of the bright level (the area-weighted 99th
/// percentile of the patches' brightest channel), in any channel: 1/16, about 13 of the
/// display's 8-bit levels at the display scale.
pub const THRESHOLD: f32 = 1.0 / 16.0;

pub use zline_scene::radiosity_options::MAX_SUBDIVISION as MAX_LEVELS;

/// The indices of the patches to cut, in increasing order.
pub fn marks(patches: &Patches, radiosity: &[Vec3]) -> Vec<u32> {
    let bright = radiosity.iter().zip(&patches.patches).map(|(b, p)| (b.max_element(), p.area));
    let Some(level) = bright_level(bright) else { return Vec::new() };
    let limit = THRESHOLD * level;
    // The range of radiosity around each shared corner.
    let mut low = vec![Vec3::splat(f32::INFINITY); patches.vertices.len()];
    let mut high = vec![Vec3::splat(f32::NEG_INFINITY); patches.vertices.len()];
    for (p, b) in patches.patches.iter().zip(radiosity) {
        for &v in &p.vertices {
            low[v as usize] = low[v as usize].min(*b);
            high[v as usize] = high[v as usize].max(*b);
        }
    }
    (0..patches.patches.len() as u32)
        .filter(|&i| {
            let (p, b) = (&patches.patches[i as usize], radiosity[i as usize]);
            p.vertices.iter().any(|&v| {
                let spread = (high[v as usize] - b).max(b - low[v as usize]);
                spread.max_element() > limit
            })
        })
        .collect()
}

/// `patches` with those listed in `cut` (increasing indices) cut into
/// four, in place: the others keep their order, a cut patch's four
/// children take its place. The children's [`Patch::direct`] is 0.
pub fn split(patches: &Patches, cut: &[u32]) -> Patches {
    let mut out = Patches {
        patches: Vec::with_capacity(patches.patches.len() + 3 * cut.len()),
        vertices: patches.vertices.clone(),
        warnings: patches.warnings.clone(),
    };
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
    let mut cut = cut.iter().copied().peekable();
    for (i, p) in patches.patches.iter().enumerate() {
        if cut.next_if_eq(&(i as u32)).is_none() {
            out.patches.push(*p);
            continue;
        }
        let [a, b, c] = p.vertices;
        let mut mid = |u: u32, v: u32| {
            *midpoints.entry((u.min(v), u.max(v))).or_insert_with(|| {
                out.vertices.push((patches.vertices[u as usize] + patches.vertices[v as usize]) * 0.5);
                out.vertices.len() as u32 - 1
            })
        };
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        let [ta, tb, tc] = p.uvs;
        let (tab, tbc, tca) = ((ta + tb) * 0.5, (tb + tc) * 0.5, (tc + ta) * 0.5);
        let quarters = [
            ([a, ab, ca], [ta, tab, tca]),
            ([ab, b, bc], [tab, tb, tbc]),
            ([ca, bc, c], [tca, tbc, tc]),
            ([ab, bc, ca], [tab, tbc, tca]),
        ];
        for (vertices, uvs) in quarters {
            let corners = vertices.map(|v| out.vertices[v as usize]);
            if let Some(mut child) = Patch::new(corners, p.reflectance, p.emission) {
                child.triangle = p.triangle;
                child.uvs = uvs;
                child.vertices = vertices;
                out.patches.push(child);
            }
        }
    }
    out
}

/// The bright level of (value, area) pairs: the 99th percentile of the
/// finite positive values weighted by area, so that it does not move
/// when bright patches are cut finer; `None` without such a value.
pub(crate) fn bright_level(values: impl Iterator<Item = (f32, f32)>) -> Option<f32> {
    let mut lit: Vec<(f32, f32)> = values.filter(|(b, a)| b.is_finite() && *b > 0.0 && *a > 0.0).collect();
    lit.sort_by(|x, y| x.0.total_cmp(&y.0));
    let total: f64 = lit.iter().map(|(_, a)| f64::from(*a)).sum();
    let mut below = 0.0f64;
    for &(b, a) in &lit {
        below += f64::from(a);
        if below >= 0.99 * total {
            return Some(b);
        }
    }
    lit.last().map(|(b, _)| *b)
}

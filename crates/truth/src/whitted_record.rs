//! What the Whitted truth ([`crate::whitted`]) records: each pixel's
//! tree, node by node, and the mask of the pixels away from silhouettes
//! it gives.

use crate::image::TruthImage;

/// Why a ray of the tree was traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RayKind {
    /// A camera ray (the tree's root).
    Camera,
    /// The mirror ray of a surface with kr ≠ 0.
    Reflected,
    /// The refracted ray of a surface with kt > 0.
    Transmitted,
    /// The transmitted share sent along the mirror direction (total
    /// internal reflection).
    InternallyReflected,
}

/// What one light's shadow ray found at a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightPath {
    /// The light adds nothing there (behind the surface, or out of its
    /// range or cone): no shadow ray.
    Unlit,
    /// Nothing on the way.
    Clear,
    /// Through this many transparent crossings.
    Filtered(u32),
    /// Stopped (an opaque surface, or any surface with opaque shadow rays).
    Blocked,
}

/// A node of a pixel's tree, as the silhouette mask compares them.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct TreeNode {
    /// 1 for the camera ray.
    pub depth: u32,
    /// Why the ray was traced.
    pub kind: RayKind,
    /// The object hit; `None` for a miss.
    pub object: Option<u32>,
    /// The ray came from the winding's outside.
    pub front: bool,
    /// A flat object's face normal, rounded to 10⁻⁹ (flat shading jumps
    /// from facet to facet); `None` otherwise.
    pub flat_normal: Option<[i64; 3]>,
    /// The level-0 texel a nearest-filtered texture reads (unwrapped
    /// indices); `None` otherwise.
    pub texel: Option<[i64; 2]>,
    /// A mask's cut-out texel: no surface, the ray went on past it.
    pub cut_out: bool,
    /// Each light's shadow ray, in the scene's order (empty for a miss
    /// and a cut-out).
    pub lights: Vec<LightPath>,
}

impl TreeNode {
    /// The node of a ray at `depth` of `kind` that hits nothing.
    pub fn miss(depth: u32, kind: RayKind) -> TreeNode {
        TreeNode {
            depth,
            kind,
            object: None,
            front: false,
            flat_normal: None,
            texel: None,
            cut_out: false,
            lights: Vec::new(),
        }
    }
}

/// A traced image and what the truth recorded.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedTruth {
    /// Linear RGB per pixel: the mean of its samples' tree sums, not
    /// clamped (`diagnostics` is `None`).
    pub image: TruthImage,
    /// Each pixel's trees (its samples' nodes in tracing order, one sample
    /// after the other), rows top first; when asked for.
    pub trees: Option<Vec<Vec<TreeNode>>>,
    /// Camera, reflected and transmitted rays traced.
    pub rays: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
    /// Trees cut by [`crate::RAY_BUDGET`].
    pub budget_cut: u64,
    /// The deepest node that hit something (1: a camera ray's hit).
    pub deepest: u32,
}

impl TracedTruth {
    /// Pixels away from silhouettes, row by row: those whose tree equals
    /// the tree of each of their neighbours in the image (8 inside it) —
    /// the same objects hit by the same kinds of rays from the same
    /// sides, the same flat facets and nearest texels, the same light
    /// paths. A move of less than a pixel of an edge, a shadow boundary,
    /// a texel boundary or a total internal reflection boundary changes
    /// the tree of a pixel only next to a neighbour whose tree differs
    /// (unless a feature narrower than a pixel lies between the samples).
    /// `None` when the trees were not recorded or do not match the image.
    pub fn away_from_silhouettes(&self) -> Option<Vec<bool>> {
        let trees = self.trees.as_ref()?;
        let (w, h) = (i64::from(self.image.width), i64::from(self.image.height));
        if trees.len() as i64 != w * h {
            return None;
        }
        let mask = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let own = &trees[i as usize];
                (-1..=1).all(|dy| {
                    (-1..=1).all(|dx| {
                        let (nx, ny) = (x + dx, y + dy);
                        !(0..w).contains(&nx)
                            || !(0..h).contains(&ny)
                            || &trees[(ny * w + nx) as usize] == own
                    })
                })
            })
            .collect();
        Some(mask)
    }
}

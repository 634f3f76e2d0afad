//! What the keys do ([`Action`]), and keys named on the command line
//! (`zline view --keys`) as those actions.

use zline_shading::ShadingMode;

/// What a key does. The window maps keys to actions (`viewer::window`,
/// listed in `zline view --help`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Shading for objects without their own: flat, Gouraud or Phong (1, 2, 3).
    Shading(ShadingMode),
    /// Textures on or off (T).
    ToggleTextures,
    /// Fog on or off (F); a scene without fog gets one fitted to its size.
    ToggleFog,
    /// Wireframe: none → all → hidden removed → hidden dashed → none (W).
    CycleWireframe,
    /// Shadows: none → planar (when the scene has shadow planes) → map → none (M).
    CycleShadows,
    /// One more supersampling step per pixel side (+).
    MoreSamples,
    /// One fewer (−).
    FewerSamples,
    /// The home camera back (R).
    ResetCamera,
    /// The frame-time text on or off (H).
    ToggleOverlay,
    /// Save the full frame to a PNG (S).
    Screenshot,
    /// Hidden surfaces: the z-buffer or the painter's algorithm (Z).
    ToggleVisibility,
    /// Back-face culling as the scene says, or off on every object (C).
    ToggleCulling,
    /// Attribute interpolation: perspective-correct or screen-linear,
    /// the affine classic (I).
    ToggleInterpolation,
    /// Step mode on or off: the frame draws only the first triangles, in
    /// draw order (P).
    ToggleStepMode,
    /// Step mode: one triangle more (.).
    StepForward,
    /// Step mode: one triangle fewer (,).
    StepBack,
    /// The overdraw heat map instead of the image: under the top-left rule
    /// → closed triangles → open triangles → off (O).
    CycleOverdraw,
    /// The depth buffer shown as an image instead of the colours (D).
    ToggleDepthView,
    /// Step mode: the last triangle drawn one scanline further (]).
    ScanlineForward,
    /// Step mode: the last triangle drawn one scanline less ([).
    ScanlineBack,
    /// Each mesh's triangles drawn in a shuffled order, or in their own (X).
    ToggleShuffle,
    /// Close the viewer (Esc, Q).
    Quit,
}

impl Action {
    /// The action of a key named as `zline view --help` lists it (`P`,
    /// `.`, `+`, …; letters in either case), for `zline view --keys`;
    /// `None` for a key that does nothing. Screenshot and quit are not
    /// named: a script has `--save-first-frame` and `--exit-after-frames`.
    pub fn from_key_name(name: &str) -> Option<Action> {
        Some(match name.to_ascii_uppercase().as_str() {
            "1" => Action::Shading(ShadingMode::Flat),
            "2" => Action::Shading(ShadingMode::Gouraud),
            "3" => Action::Shading(ShadingMode::Phong),
            "T" => Action::ToggleTextures,
            "F" => Action::ToggleFog,
            "W" => Action::CycleWireframe,
            "M" => Action::CycleShadows,
            "+" | "=" => Action::MoreSamples,
            "-" => Action::FewerSamples,
            "R" => Action::ResetCamera,
            "H" => Action::ToggleOverlay,
            "Z" => Action::ToggleVisibility,
            "C" => Action::ToggleCulling,
            "I" => Action::ToggleInterpolation,
            "P" => Action::ToggleStepMode,
            "." => Action::StepForward,
            "," => Action::StepBack,
            "O" => Action::CycleOverdraw,
            "D" => Action::ToggleDepthView,
            "X" => Action::ToggleShuffle,
            "]" => Action::ScanlineForward,
            "[" => Action::ScanlineBack,
            _ => return None,
        })
    }
}

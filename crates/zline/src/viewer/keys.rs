//! Keys named on the command line (`zline view --keys`), as the actions
//! the window's keys give.

use zline_shading::ShadingMode;

use super::state::Action;

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
            _ => return None,
        })
    }
}

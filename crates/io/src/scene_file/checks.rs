//! Value checks and located errors for scene files: every bad value becomes
//! a [`SceneError`] naming the file, line, column, key and value.

use std::fmt::Display;
use std::ops::Range;
use std::path::Path;

use glam::Vec3;
use toml::Spanned;
use zline_scene::MAX_PRIMITIVE_DIVISIONS;

use crate::error::SceneError;

/// A value of the scene file with its byte range in the text.
pub(super) type S<T> = Spanned<T>;

/// A scene file's result.
pub(super) type Result<T, E = SceneError> = std::result::Result<T, E>;

/// The scene file being read: checks its values and locates its errors.
pub(super) struct Checker<'a> {
    /// The scene file.
    pub(super) path: &'a Path,
    /// Its text, to turn byte offsets into lines and columns.
    pub(super) text: &'a str,
}

impl Checker<'_> {
    pub(super) fn vec3(&self, v: &S<[f32; 3]>, key: &str) -> Result<Vec3> {
        self.vec3_in(v, key, f32::MIN, f32::MAX)
    }

    /// A finite 3-vector with every component in `lo..=hi`.
    pub(super) fn vec3_in(&self, v: &S<[f32; 3]>, key: &str, lo: f32, hi: f32) -> Result<Vec3> {
        let a = *v.get_ref();
        if a.iter().any(|c| !c.is_finite()) {
            return Err(self.error(v.span(), key, format!("must be finite, got {a:?}")));
        }
        if a.iter().any(|&c| c < lo || c > hi) {
            return Err(self.error(
                v.span(),
                key,
                format!("every component must be in {}, got {a:?}", range(lo, hi)),
            ));
        }
        Ok(Vec3::from(a))
    }

    /// A finite number in `lo..=hi`, or `default` when absent.
    pub(super) fn optional(
        &self,
        v: &Option<S<f32>>,
        key: &str,
        default: f32,
        lo: f32,
        hi: f32,
    ) -> Result<f32> {
        let Some(v) = v else { return Ok(default) };
        let x = *v.get_ref();
        if !x.is_finite() {
            return Err(self.error(v.span(), key, format!("must be finite, got {x}")));
        }
        if x < lo || x > hi {
            return Err(self.error(v.span(), key, format!("must be in {}, got {x}", range(lo, hi))));
        }
        Ok(x)
    }

    /// A finite number > 0, or `default` when absent.
    pub(super) fn positive(&self, v: &Option<S<f32>>, key: &str, default: f32) -> Result<f32> {
        let x = self.optional(v, key, default, 0.0, f32::MAX)?;
        match v {
            Some(v) if x <= 0.0 => Err(self.error(v.span(), key, format!("must be > 0, got {x}"))),
            _ => Ok(x),
        }
    }

    pub(super) fn count(&self, v: &Option<S<u32>>, key: &str, default: u32, min: u32) -> Result<u32> {
        let Some(v) = v else { return Ok(default) };
        let n = *v.get_ref();
        if !(min..=MAX_PRIMITIVE_DIVISIONS).contains(&n) {
            return Err(self.error(
                v.span(),
                key,
                format!("must be in {min}..={MAX_PRIMITIVE_DIVISIONS}, got {n}"),
            ));
        }
        Ok(n)
    }

    pub(super) fn not_allowed<T>(&self, v: &Option<S<T>>, key: &str, name: &str, what: &str) -> Result<()> {
        match v {
            Some(v) => {
                Err(self.error(v.span(), &format!("{key}.{name}"), format!("does not apply to {what}")))
            }
            None => Ok(()),
        }
    }

    // ---- errors ----

    pub(super) fn error(&self, span: Range<usize>, key: &str, message: impl Display) -> SceneError {
        SceneError::at_offset(self.path.to_path_buf(), self.text, span.start, format!("{key}: {message}"))
    }

    /// An error at the value when it was given, else at the enclosing table.
    pub(super) fn value_error<T, U>(
        &self,
        v: Option<&S<T>>,
        table: &S<U>,
        key: &str,
        message: impl Display,
    ) -> SceneError {
        self.error(v.map_or(table.span(), |v| v.span()), key, message)
    }

    pub(super) fn file_error(&self, message: &str) -> SceneError {
        SceneError::File { path: self.path.to_path_buf(), message: message.to_owned() }
    }
}

/// A range for messages: `[lo, hi]`, `[lo, ∞)` or any finite value.
fn range(lo: f32, hi: f32) -> String {
    match (lo == f32::MIN, hi == f32::MAX || hi == f32::INFINITY) {
        (true, true) => "any finite value".to_owned(),
        (false, true) => format!("[{lo}, ∞)"),
        _ => format!("[{lo}, {hi}]"),
    }
}

//! The value parsers of the command line's flags: each takes the flag's
//! text and returns the value or a message for clap to print.

use glam::Vec3;
use zline::scene::MAX_IMAGE_SIDE;
use zline::shading::FogMode;

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("expected WxH, e.g. 800x600, got '{s}'"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|n| (1..=MAX_IMAGE_SIDE).contains(n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("width and height must be whole numbers in 1..={MAX_IMAGE_SIDE}, got '{s}'")),
    }
}

pub(crate) fn parse_tolerance(s: &str) -> Result<f32, String> {
    s.trim()
        .parse::<f32>()
        .ok()
        .filter(|t| (0.0..=zline::scene::MAX_ADAPTIVE_TOLERANCE).contains(t))
        .ok_or_else(|| format!("expected a tolerance in 8-bit steps, 0 to 255, got '{s}'"))
}

pub(crate) fn parse_fog(s: &str) -> Result<FogMode, String> {
    let parts: Vec<&str> = s.split(':').collect();
    let num = |v: &str| {
        v.trim()
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite() && *x >= 0.0)
            .ok_or_else(|| format!("'{v}' in --fog '{s}' is not a finite, non-negative number"))
    };
    match parts.as_slice() {
        ["linear", start, end] => {
            let (start, end) = (num(start)?, num(end)?);
            if end < start {
                return Err(format!("linear fog needs end ≥ start, got '{s}'"));
            }
            Ok(FogMode::Linear { start, end })
        }
        ["exp", d] => Ok(FogMode::Exponential { density: num(d)? }),
        ["exp2", d] => Ok(FogMode::SquaredExponential { density: num(d)? }),
        _ => Err(format!("expected linear:START:END, exp:DENSITY or exp2:DENSITY, got '{s}'")),
    }
}

pub(crate) fn parse_color(s: &str) -> Result<Vec3, String> {
    let c: Vec<f32> = s.split(',').filter_map(|v| v.trim().parse().ok()).collect();
    match c.as_slice() {
        [r, g, b] if c.iter().all(|v| (0.0..=1.0).contains(v)) => Ok(Vec3::new(*r, *g, *b)),
        _ => Err(format!("expected R,G,B with each in [0, 1], got '{s}'")),
    }
}

pub(crate) fn parse_angle(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("expected an angle in degrees, got '{s}'")),
    }
}

pub(crate) fn parse_non_negative(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("expected a number ≥ 0, got '{s}'")),
    }
}

pub(crate) fn parse_positive(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a number > 0, got '{s}'")),
    }
}

pub(crate) fn parse_fov(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (1.0..=179.0).contains(&v) => Ok(v),
        _ => Err(format!("expected degrees in 1..=179, got '{s}'")),
    }
}

pub(crate) fn parse_direction(s: &str) -> Result<Vec3, String> {
    let c: Vec<f32> = s.split(',').filter_map(|v| v.trim().parse().ok()).collect();
    match c.as_slice() {
        [x, y, z] if c.iter().all(|v| v.is_finite()) && c.iter().any(|v| *v != 0.0) => {
            Ok(Vec3::new(*x, *y, *z))
        }
        _ => Err(format!("expected X,Y,Z, finite and not all zero, got '{s}'")),
    }
}

/// `--views`: named views, in order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ViewList(pub(crate) Vec<zline::views::NamedView>);

/// `--view`: one view name.
pub(crate) fn parse_view(s: &str) -> Result<zline::views::NamedView, String> {
    use zline::views::NamedView;
    NamedView::from_name(s.trim()).ok_or_else(|| {
        let names = NamedView::ALL.map(NamedView::name).join(", ");
        format!("no view named '{}' (the views: {names})", s.trim())
    })
}

/// A comma-separated list of view names, or `all`.
pub(crate) fn parse_views(s: &str) -> Result<ViewList, String> {
    use zline::views::NamedView;
    if s.trim() == "all" {
        return Ok(ViewList(NamedView::ALL.to_vec()));
    }
    let names = NamedView::ALL.map(NamedView::name).join(", ");
    let views = s
        .split(',')
        .map(|name| {
            NamedView::from_name(name.trim())
                .ok_or_else(|| format!("no view named '{}' (the views: {names}, or all)", name.trim()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if views.len() > 64 {
        return Err(format!("{} views: at most 64 in one sheet", views.len()));
    }
    Ok(ViewList(views))
}

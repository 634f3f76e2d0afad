//! Incremental attribute interpolation (SPEC §6): Gouraud colours stay
//! between the vertex colours, and a linear function of position is
//! reproduced, both within `AttributePlanes::error_bound`.

use crate::depth::Worst;
use crate::exact::Barycentric;
use crate::shapes::{all_spans, any_shape, Tri};
use proptest::array::uniform3;
use proptest::prelude::*;
use zline_raster::{for_each_sample, AttributePlanes, DepthPlane, PlaneBasis};

/// The 8-bit level of a colour value (SPEC §10): clamped to [0, 1], then
/// floor(c·255 + 0.5).
fn quantize(c: f64) -> i32 {
    (c.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as i32
}

/// Calls `f(col, row, values, bound)` for every covered sample of `t` with
/// attribute planes through `v`, `bound[i]` being `error_bound(i, …)`.
fn for_each_value<const N: usize>(
    t: Tri,
    v: [[f32; N]; 3],
    mut f: impl FnMut(i32, i32, &[f32; N], [f64; N]),
) {
    let Some(basis) = PlaneBasis::new(t) else { return };
    let planes = AttributePlanes::new(&basis, v);
    let depth = DepthPlane::new(&basis, [0.0; 3]);
    for span in all_spans(t) {
        let yc = f64::from(span.y) + 0.5;
        for_each_sample(&depth, &planes, span, |x, _, a| {
            let xc = f64::from(x) + 0.5;
            f(x, span.y, a, std::array::from_fn(|i| f64::from(planes.error_bound(i, xc, yc))));
        });
    }
}

/// Vertex colours: anywhere in [0, 1], or 8-bit levels k/255 as from a
/// texture or an 8-bit material colour.
fn colours() -> impl Strategy<Value = ([[f32; 3]; 3], bool)> {
    let any = uniform3(uniform3(0.0..=1.0f32));
    let levels = uniform3(uniform3(0..=255u8));
    prop_oneof![
        any.prop_map(|c| (c, false)),
        levels.prop_map(|c| (c.map(|c| c.map(|l| f32::from(l) / 255.0)), true)),
    ]
}

/// Gouraud: over every covered sample, each channel stays within the vertex
/// colours' [min, max], widened by `error_bound` only — f32 rounding can
/// overshoot by that much; the pipeline clamps to [0, 1] before quantizing.
/// After quantization: for 8-bit vertex levels, the level lies within the
/// vertices' levels whenever the bound is below a quarter level (which it is
/// except on slivers, where steep gradients make it large). For arbitrary
/// vertex colours no such check is possible: a vertex colour a hair below
/// (k + 0.5)/255 quantizes to k, and any overshoot, however small, to k + 1;
/// so there the level lies within the levels of [min − bound, max + bound].
/// (Found by a search: vertex (10.5, 29.5) of the triangle (10.5, 29.5),
/// (28.5, 14.5), (17.5, 34.5) has the colour 0.13137254 = (33.5/255)⁻, level
/// 33; its own sample gets 0.1313726, one ulp more, level 34 — well within
/// the bound of 7e-7.) Every value is also within the bound of the exact plane.
/// Returns the worst error against the exact plane relative to the bound.
#[track_caller]
pub(crate) fn check_gouraud(t: Tri, c: [[f32; 3]; 3], levels: bool) -> Worst {
    let exact = Barycentric::new(t);
    let mut worst = Worst::default();
    for_each_value(t, c, |x, y, got, bound| {
        for i in 0..3 {
            let vertex = [c[0][i], c[1][i], c[2][i]].map(f64::from);
            let (lo, hi) = (
                vertex.into_iter().reduce(f64::min).unwrap_or(0.0),
                vertex.into_iter().reduce(f64::max).unwrap_or(0.0),
            );
            let v = f64::from(got[i]);
            let e = bound[i];
            assert!(
                lo - e <= v && v <= hi + e,
                "channel {i} at ({x}, {y}) is {v}, outside [{lo}, {hi}] ± {e} for {t:?}, colours {c:?}"
            );
            let (q, qlo, qhi) = if levels && e < 0.25 / 255.0 {
                (quantize(v), quantize(lo), quantize(hi))
            } else {
                (quantize(v), quantize(lo - e), quantize(hi + e))
            };
            assert!(
                qlo <= q && q <= qhi,
                "channel {i} at ({x}, {y}) quantizes to {q}, outside {qlo}..={qhi} ({v} from [{lo}, {hi}] ± {e}) for {t:?}"
            );
            let want = exact.expect("covered samples have area").value(c.map(|c| c[i]), x, y);
            let error = (v - want).abs();
            assert!(
                error <= e,
                "channel {i} at ({x}, {y}) is {v}, want {want} ± {e} for {t:?}, colours {c:?}"
            );
            worst = worst.max(Worst::sample(error, e, (x, y)));
        }
    });
    worst
}

/// Two linear functions of position, v = a + b·x + c·y, with |v| ≤ 1500 over
/// the triangle: given as (a', b', c') in a form centred on the triangle,
/// v = a' + (b'·(x − mx) + c'·(y − my))·500/extent (the same functions,
/// written so that f64 evaluation is accurate far from the origin).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Linear {
    coefficients: [(f64, f64, f64); 2],
}

pub(crate) fn linear() -> impl Strategy<Value = Linear> {
    let one = || (-500.0..500.0f64, -1.0..1.0f64, -1.0..1.0f64);
    [one(), one()].prop_map(|coefficients| Linear { coefficients })
}

/// A linear attribute is reproduced at every covered sample within
/// `error_bound` plus the rounding of the vertex values to f32 (the input the
/// crate gets; inside the triangle that rounding moves the plane by at most
/// its largest value). Returns the worst error relative to that tolerance.
#[track_caller]
pub(crate) fn check_linear(t: Tri, l: Linear) -> Worst {
    let px = t.map(|p| p.to_f64());
    let (mx, my) = ((px[0].0 + px[1].0 + px[2].0) / 3.0, (px[0].1 + px[1].1 + px[2].1) / 3.0);
    let extent = px.iter().map(|p| (p.0 - mx).abs().max((p.1 - my).abs())).fold(1e-3, f64::max);
    let exact = |i: usize, x: f64, y: f64| {
        let (a, b, c) = l.coefficients[i];
        a + (b * (x - mx) + c * (y - my)) * 500.0 / extent
    };
    let vertex: [[f64; 2]; 3] = px.map(|(x, y)| [exact(0, x, y), exact(1, x, y)]);
    let input = vertex.map(|v| v.map(|v| v as f32));
    let rounding: [f64; 2] = std::array::from_fn(|i| {
        (0..3).map(|k| (f64::from(input[k][i]) - vertex[k][i]).abs()).fold(0.0, f64::max)
    });
    let mut worst = Worst::default();
    for_each_value(t, input, |x, y, got, bound| {
        for i in 0..2 {
            let (xc, yc) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let want = exact(i, xc, yc);
            let error = (f64::from(got[i]) - want).abs();
            // 1e-9: the f64 evaluation of `want`, |v| ≤ 1500.
            let tolerance = bound[i] + rounding[i] + 1e-9;
            assert!(
                error <= tolerance,
                "attribute {i} at ({x}, {y}) is {}, want {want} ± {tolerance} for {t:?}, {l:?}",
                got[i]
            );
            worst = worst.max(Worst::sample(error, tolerance, (x, y)));
        }
    });
    worst
}

proptest! {
    #![proptest_config(crate::config())]

    /// Gouraud colours on general, wide, sliver and far triangles.
    #[test]
    fn gouraud_colours_stay_between_the_vertex_colours((_, t) in any_shape(), (c, levels) in colours()) {
        check_gouraud(t, c, levels);
    }

    /// A linear function of position on general, wide, sliver and far triangles.
    #[test]
    fn linear_attributes_are_reproduced((_, t) in any_shape(), l in linear()) {
        check_linear(t, l);
    }
}

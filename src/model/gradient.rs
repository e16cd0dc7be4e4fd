//! What the terms share: the depth mapping's scale `b`, the frustum's half-extent tangent `e`,
//! and the window-depth gradient `g` of a sloped plane.
//!
//! Every `glFrustum`-family mapping stores `w(d) = α ± b/d` with the same `b = f·n/(f − n)` (`n`
//! for `f = ∞`; [`crate::precision::DepthMapping`]), so `|dw/dd| = b/d²` and the window
//! gradients of a sloped plane are the same in every convention.
//!
//! # The window gradient of a plane of slope `s`
//! A plane of eye-space slope `s = |∂z/∂x| + |∂z/∂y|` that crosses the view axis at distance `d`
//! has the window-depth gradient per pixel `gₓ = s·F·(r−l)/(W·d)`, `g_y = s·F·(t−b)/(H·d)`
//! (`F = f/(f−n)`, `W × H` the viewport). The decal's plane crosses the axis at `d_a`, not
//! necessarily at its nearest depth `d₁`: a visible point at depth `d` on the ray `(kₓ, k_y)`
//! has `d = d_a/(1 + sₓkₓ + s_y·k_y)`, so `1/d_a = 1/(d·(1 + s·k))`. The terms that run on the
//! gradient take it at `d₁` and multiply it by the tilt `1 + s·e` (`e = max(|l|, |r|, |b|,
//! |t|)/n`, the largest tangent of the frustum's half extents): the first-order size of
//! `1/(1 + s·k)`, **not a bound** where the plane grazes an off-axis ray (`1 + s·k → 0`; the
//! exact bound `1/(1 − s·e)` is infinite from `s·e = 1`, which the depths and slope alone
//! cannot exclude). There the gradient terms (`V`, `I`, `S`) are underestimated; they are small
//! beside the quantum and the transform, and `tests/gl_scenes.rs`
//! (`planes_grazing_an_off_axis_ray_hold`: 1440 decals at `1 + s·k` = 0.1 and 0.3, both
//! profiles, with and without corners) loses no pixel. With the decal's corners
//! ([`crate::recommend::Scene::footprint`]) the exact gradients replace the tilt.

use crate::error::Result;
use crate::projection::Frustum;

/// `b = f·n/(f − n)` (`n` for `f = ∞`): every `glFrustum`-family mapping stores
/// `w(d) = α ± b/d`, so `|dw/dd| = b/d²` and the window gradients match the standard ones.
pub(crate) fn scale(frustum: &Frustum) -> f64 {
    let planes = frustum.planes();
    planes.near() * planes.far_over_span()
}

/// `(eₓ, e_y) = (max(|l|, |r|)/n, max(|b|, |t|)/n)`, the largest tangents of the frustum's half
/// extents in x and y.
pub(crate) fn tangents_of(frustum: &Frustum) -> [f64; 2] {
    let (l, r, b, t, n, _) = frustum.parameters();
    [l.abs().max(r.abs()) / n, b.abs().max(t.abs()) / n]
}

/// `e = max(|l|, |r|, |b|, |t|)/n`, the largest tangent of the frustum's half extents.
pub(crate) fn half_extent_tangent(frustum: &Frustum) -> Result<f64> {
    // (|r + l|/|r − l| + 1)/(2n/|r − l|) = (|r + l| + |r − l|)/(2n) = max(|l|, |r|)/n: the
    // same value from the parameters, without building the matrix.
    let (l, r, b, t, n, _) = frustum.parameters();
    Ok(l.abs().max(r.abs()).max(b.abs()).max(t.abs()) / n)
}

/// The window-depth gradient per pixel `(gₓ, g_y)` of a plane of eye-space slope `slope` that
/// crosses the view axis at distance `d`, drawn with `frustum` into a `viewport`:
/// `s·F·(r−l)/(W·d)` and `s·F·(t−b)/(H·d)`.
pub(crate) fn window_gradient(
    frustum: &Frustum,
    viewport: [u32; 2],
    slope: f64,
    d: f64,
) -> [f64; 2] {
    let (l, r, b, t, _, _) = frustum.parameters();
    let [w, h] = viewport.map(f64::from);
    let big_f = frustum.planes().far_over_span();
    // From the parameters, not through 2/m0 = (r − l)/n: the same value without the matrix.
    let gx = slope * big_f * (r - l).abs() / (w * d);
    let gy = slope * big_f * (t - b).abs() / (h * d);
    [gx, gy]
}

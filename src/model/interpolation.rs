//! The term `I`: f32 rounding in the rasterizer's depth-plane set-up and evaluation, with the
//! extrapolation `G` it is relative to and the magnitude `M` a measured figure scales.
//!
//! The rasterizer sets the plane up and evaluates it in f32, relative to the framebuffer origin
//! (llvmpipe's `a0 = z₀ − ∂z/∂x·x₀ − ∂z/∂y·y₀`, then `a0 + ∂z/∂x·x + ∂z/∂y·y` per pixel: its
//! own source warns that `a0` can get large), so the roundings are relative to the depth
//! extrapolated across the viewport,
//!
//! `G = max(|gₓ|·X, |g_y|·Y)·(1 + s·e)`
//!
//! (`g` the window gradient per pixel of a plane crossing the axis at `d₁`, `1 + s·e` the bound
//! on its real crossing, see [`crate::model::gradient`]; `X × Y` the viewport's far corner in
//! the framebuffer, `[x + W, y + H]`, since the viewport may lie inside a larger framebuffer),
//! not only to the depth at the pixel. The tilt `s = |sₓ| + |s_y|` splits between the axes, so
//! `|gₓ|·X + |g_y|·Y` is at most the larger of the two with the whole slope. With gradients set
//! up to a relative `3u`:
//!
//! `I = u·(3·w(d₂) + 6·max(w(d₂) − w(d₁), G))`
//!
//! (`w` lifted by `near/(far − near)` under `glDepthRange(near, far)`). A steep plane near the
//! near plane showed 36 quanta (2⁻²⁴) of error on llvmpipe where the depth span alone bounds 3.
//! Zero when every corner of base and decal has the same f32 z
//! ([`crate::recommend::Scene::exact_depth`]): a constant plane has exactly zero gradients, and
//! `w₀ + 0` is exact.
//!
//! With the decal's footprint ([`crate::recommend::Scene::footprint`]), the exact run from the
//! framebuffer's origin to the decal's farthest pixel replaces the bound `G`.
//!
//! # The magnitude `M`
//! A measured profile scales its per-pixel figure by `M = |w₀| + |gₓ|·x + |g_y|·y`, the largest
//! magnitude of the plane's terms from the window origin over the decal's pixels (see
//! [`crate::model::measured`]): the footprint's own, else bounded by `w(d₂) + 2G`.

use crate::model::Pipeline;

use super::F32_UNIT_ROUNDOFF;

/// The viewport's far corner in the framebuffer, `[x + W, y + H]` pixels: how far the
/// rasterizer's plane, set up from the framebuffer's origin, can be extrapolated.
pub(crate) fn framebuffer_extent(pipeline: &Pipeline, viewport: [u32; 2]) -> [f64; 2] {
    let [x, y] = pipeline.viewport_origin.map(f64::from);
    let [w, h] = viewport.map(f64::from);
    [x + w, y + h]
}

/// The bound `G` over every plane of the slope: the larger run across the framebuffer extent
/// `extent` of the window `gradient` taken at `d₁`, times the `tilt` `1 + s·e`.
pub(crate) fn extrapolation_bound(gradient: [f64; 2], extent: [f64; 2], tilt: f64) -> f64 {
    let ([gx, gy], [width, height]) = (gradient, extent);
    (gx * width).max(gy * height) * tilt
}

/// `I = u·(3·(w_max + lift) + 6·max(w_max − w_min, G))` (module docs).
pub(crate) fn interpolation(w_min: f64, w_max: f64, extrapolated: f64, lift: f64) -> f64 {
    let span = (w_max - w_min).max(extrapolated);
    F32_UNIT_ROUNDOFF * (3.0 * (w_max + lift) + 6.0 * span)
}

/// The bound on `M` without a footprint: `|w₀| + |gₓ|·x + |g_y|·y ≤ w + 2(|gₓ|·x + |g_y|·y)`,
/// i.e. `w_max + 2G`.
pub(crate) fn magnitude_bound(w_max: f64, extrapolated: f64) -> f64 {
    w_max + 2.0 * extrapolated
}

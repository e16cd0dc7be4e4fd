//! Depth-buffer precision: window depth as a function of eye distance, and the exact size of one
//! depth step at a distance (Walker, seed 001).
//!
//! Conventions: OpenGL's standard mapping, NDC depth `[−1, 1]`, `glDepthRange(0, 1)`, an m-bit
//! unsigned normalized depth buffer whose steps are `1/(2^m − 1)` of window depth.

use crate::domain::{depth_steps, Planes};
use crate::error::Result;

/// Window depth (what the depth buffer stores, in `[0, 1]`) at eye distance `d`: Walker's
///
/// `f(d) = (f+n)/(2(f−n)) − f·n/(d(f−n)) + 1/2`,
///
/// evaluated in the equivalent form `f/(f−n) · (d−n)/d`, which has no cancellation: `d − n` is
/// exact near the near plane. `f(n) = 0`, `f(f) = 1`; with `f = +∞`, `1 − n/d`. The result is
/// clamped to `[0, 1]` (only the last ulp at `d = f` can need it).
///
/// # Errors
/// As [`Planes::new`] and [`Planes::check_distance`] (`d` in `[n, f]`).
pub fn window_depth(n: f64, f: f64, d: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_distance(d)?;
    let w = planes.far_over_span() * ((d - n) / d);
    Ok(w.clamp(0.0, 1.0))
}

/// The exact size of one depth step at eye distance `d`: the `Δd > 0` with
/// `f(d) − f(d − Δd) = 1/(2^m − 1)` — Walker's eq. (3) generalised from `d = f` to any `d`:
///
/// `Δd = q·d² / (b + q·d)`, with `q = 1/(2^m − 1)` and `b = f·n/(f − n)`.
///
/// Geometry nearer the camera than `d − Δd` is guaranteed to store a smaller value; closer
/// pairs may tie. This is also the corrected eq. 4.1.9 ([`crate::offset::min_delta_toward`]).
///
/// # Errors
/// As [`Planes::new`], [`Planes::check_distance`] and [`depth_steps`].
pub fn depth_resolution(n: f64, f: f64, bits: u32, d: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_distance(d)?;
    depth_step_toward(&planes, depth_steps(bits)?, d)
}

/// `u = q·d/b = k·d`: the depth step at `d` measured in units of `d` itself (before the
/// `1/(1+u)` correction). Each factor is a single correctly rounded operation.
pub(crate) fn steps_per_distance(planes: &Planes, steps: f64, d: f64) -> f64 {
    (d / planes.near()) * planes.span_over_far() / steps
}

/// `Δd = d·u/(1+u)`, written so that no intermediate exceeds `d`.
pub(crate) fn depth_step_toward(planes: &Planes, steps: f64, d: f64) -> Result<f64> {
    let u = steps_per_distance(planes, steps, d);
    if u.is_infinite() {
        // `d/n` overflowed (n near f64::MIN_POSITIVE): u/(1+u) is 1 to within 2^-1000, and
        // ∞/∞ would give NaN.
        return Ok(d);
    }
    Ok(d * (u / (1.0 + u)))
}

//! The term `q`: the depth quantum, the smallest difference the stored format keeps.
//!
//! Stored values keep their order once two computed values are a quantum `q` apart (the
//! conversion to the stored format is monotone), and computed values in order store in order.
//!
//! * For an m-bit unsigned normalized buffer, `q = 1/(2^m − 1)` (seed 002's correction is this
//!   factor: one window step is `2/(2^m−1)` in NDC).
//! * For `GL_DEPTH_COMPONENT32F`, the spacing of f32 at the window depth `w(d₂)` of the decal's
//!   farthest point, `2^(⌊log₂ w(d₂)⌋ − 23)` (2⁻²⁴ for `w ≥ ½`, which is why D32F under the
//!   `[−1, 1]` mapping behaves as D24). Under reversed Z the spacing is relative:
//!   `2^(e−23)` at `w ≈ n/d`.
//!
//! # Under `glDepthRange`
//! With `glDepthRange(near, far)` the stored depth is `near + (far − near)·w`: the format's
//! spacing is taken at that stored depth and counted in unit window depth, over `far − near`
//! (`unit_quantum`).

use crate::error::Result;
use crate::model::Pipeline;
use crate::precision::DepthFormat;

/// `q` for a format at window depth `w`: one step of a UNORM buffer, or the f32 spacing at `w`
/// for `GL_DEPTH_COMPONENT32F`.
pub(crate) fn quantum(format: DepthFormat, w: f64) -> Result<f64> {
    format.spacing_at(w.clamp(0.0, 1.0))
}

/// `q` in unit window depth at unit window depth `w`: the format's spacing at the stored depth
/// `near + (far − near)·w` of `glDepthRange`, over `far − near`.
pub(crate) fn unit_quantum(format: DepthFormat, pipeline: &Pipeline, w: f64) -> Result<f64> {
    Ok(pipeline.per_unit(quantum(format, pipeline.actual(w))?))
}

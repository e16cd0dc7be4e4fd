//! The term `T`: f32 rounding of the vertex transform and the viewport map, per vertex.
//!
//! With `u = 2⁻²⁴` the unit roundoff of f32, in window-depth units:
//!
//! * **`[−1, 1]` clip depth.** `clip_z = m10·z + m14` (two roundings, relative to `|m10|·d` and
//!   `|clip_z| ≤ d`), the division by `w` (reciprocal and product, two roundings relative to
//!   `|ndc|`), and `w = ½·ndc + ½` (one rounding relative to `w`):
//!   `T = u·(|m10|/2 + 1.5·|ndc|max + w(d₂))`.
//! * **`[0, 1]` and reversed `[0, 1]`.** The NDC depth is the window depth
//!   (`glDepthRange(0, 1)` maps it as `z·1 + 0`), so the transform's roundings are no longer
//!   halved: the product `m10·z` rounds relative to `|m10|·d`, i.e. `u·|m10|` after the division
//!   by `w = d`; the sum, reciprocal and product round relative to `|ndc| ≤ w_max`; the viewport
//!   map is exact but counted: `T = u·(|m10| + 4·w_max)` (under reversed Z `m10 = n/(f − n)`, 0
//!   at `f = ∞`).
//!
//! Under `glDepthRange(near, far)` the viewport map's rounding is relative to the stored depth
//! `near + (far − near)·w`, i.e. to `w + near/(far − near)` in unit window depth: that lift adds
//! to `w`. `T` applies even to bit-identical vertices, because the decal's offset element
//! differs from the base's.

use crate::projection::ClipDepth;

use super::F32_UNIT_ROUNDOFF;

/// `T` for window depths `w` (the decal's nearest and farthest, unit window depth) under
/// `clip`, with the convention's `m10` and the `glDepthRange` lift `near/(far − near)` (module
/// docs).
pub(crate) fn transform(clip: ClipDepth, m10: f64, w: [f64; 2], lift: f64) -> f64 {
    let u = F32_UNIT_ROUNDOFF;
    let [w1, w2] = w;
    let w_max = w1.max(w2);
    if clip == ClipDepth::NegOneToOne {
        // m10·z and + m14 round relative to |m10|·d and |clip_z| ≤ d (halved by the viewport
        // map), the reciprocal and product relative to |ndc|, ½·ndc + ½ relative to w.
        let ndc_max = (2.0 * w1 - 1.0).abs().max((2.0 * w2 - 1.0).abs());
        u * (m10.abs() / 2.0 + 1.5 * ndc_max + w_max + lift)
    } else {
        // NDC = window depth: the product m10·z rounds relative to |m10|·d, i.e. u·|m10| after
        // the division by w = d; the sum, reciprocal and product round relative to
        // |ndc| ≤ w_max; the viewport map z·1 + 0 is exact but counted.
        u * (m10.abs() + 4.0 * w_max + lift)
    }
}

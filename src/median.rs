//! Kooima's median-distance perspective projection (seed 003): a CPU reference of
//! `ftransform_mdp`, the shipped GLSL snippet, and its depth offset.
//!
//! The projection has no near or far plane: NDC depth is `(d − m)/(d + m)` at eye distance `d`
//! (−1 at the eye, 0 at the median `m`, → 1 at infinity), window depth `d/(d + m)`. x and y are
//! those of the application's projection matrix. Its precision is
//! [`DepthMapping::median`](crate::precision::DepthMapping::median).

use glam::{DMat4, DVec4, Mat4, Vec4};

use crate::domain::finite;
use crate::error::Result;
use crate::precision::DepthMapping;

/// The GLSL source of `zshift_ftransform_mdp(mat4 projection, vec4 eye, float median,
/// float ndc_offset)`, the file `bindings/glsl/ftransform_mdp.glsl`: Kooima's `ftransform_mdp`
/// in core-profile form, with an NDC depth offset added as `ndc_offset · clip.w`.
pub const FTRANSFORM_MDP_GLSL: &str = include_str!("../bindings/glsl/ftransform_mdp.glsl");

/// `ftransform_mdp` in f64 (seed 003): from the eye-space position `eye` and the application's
/// `projection` (column-major, right-handed, any `glFrustum`/`gluPerspective` matrix),
///
/// ```text
/// clip.xy = −(projection · eye).xy · (−eye.z + m) / eye.z
/// clip.z  = −eye.z − m  (+ ndc_offset · clip.w)
/// clip.w  = −eye.z + m
/// ```
///
/// so that after the divide `x, y` are those of `projection` and NDC depth is
/// `(d − m)/(d + m) + ndc_offset`. `eye.z = 0` gives non-finite x and y, as on the GPU.
pub fn ftransform_mdp(projection: &DMat4, eye: DVec4, median: f64, ndc_offset: f64) -> DVec4 {
    let xy = -(*projection * eye).truncate().truncate() * (-eye.z + median) / eye.z;
    let w = -eye.z + median;
    DVec4::new(xy.x, xy.y, (-eye.z - median) + ndc_offset * w, w)
}

/// [`ftransform_mdp`] in f32 with the GLSL snippet's order of operations: what a GPU with
/// correctly rounded f32 arithmetic (and no fused multiply-add) computes.
pub fn ftransform_mdp_f32(projection: &Mat4, eye: Vec4, median: f32, ndc_offset: f32) -> Vec4 {
    let xy = -(*projection * eye).truncate().truncate() * (-eye.z + median) / eye.z;
    let w = -eye.z + median;
    Vec4::new(xy.x, xy.y, (-eye.z - median) + ndc_offset * w, w)
}

/// The `ndc_offset` uniform that moves geometry at eye-space depth `Pz` toward the camera by
/// `δ` under the median projection `m`:
///
/// `c = z(d − δ) − z(d) = −2mδ / ((d + m)(d + m − δ))`, `d = −Pz`
///
/// (negative for `δ > 0`). Like Lengyel's ε (seed 000, eq. 4.1.7) it is a constant NDC offset,
/// so the eye-space shift it makes grows with distance.
///
/// # Errors
/// [`ErrorKind::NotFinite`](crate::ErrorKind::NotFinite) for NaN or ±∞;
/// [`ErrorKind::Domain`](crate::ErrorKind::Domain) unless `m > 0`, `Pz ≤ 0` and `Pz + δ ≤ 0`.
pub fn ndc_offset(median: f64, delta: f64, pz: f64) -> Result<f64> {
    finite(pz, "the eye-space depth Pz is NaN or infinite")?;
    let mapping = DepthMapping::median(median)?;
    crate::clip_offset::ndc_offset_of_shift(&mapping, delta, pz)
}

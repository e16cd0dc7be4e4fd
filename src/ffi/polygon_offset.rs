//! Polygon-offset equivalence: eye-space shift <-> glPolygonOffset / D3D / Vulkan bias.

use super::{
    api_of, checked_scalar, clip_of, format_of, ZshiftBiasApi, ZshiftClip, ZshiftFormat,
    ZshiftStatus,
};
use crate::precision::DepthMapping;

/// Writes the constant depth bias of `api` (a ZSHIFT_BIAS_*: glPolygonOffset units, Direct3D
/// DepthBias before rounding, Vulkan depthBiasConstantFactor) equivalent to moving geometry at
/// `pz` toward the camera by `delta`: (w(d - delta) - w(d)) / r, d = -pz. Negative under
/// [-1, 1] and [0, 1], positive reversed. For Direct3D round away from zero.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, pz or
/// pz + delta outside [-f, -n], unknown enum). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_bias_of_shift(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    api: ZshiftBiasApi,
    delta: f64,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        let mapping = DepthMapping::projection(n, f, clip_of(clip)?)?;
        crate::polygon_offset::bias_of_shift(&mapping, format_of(format)?, api_of(api)?, delta, pz)
    })
}

/// Writes the eye-space shift toward the camera that a constant `bias` of `api` makes at `pz`:
/// the inverse of `zshift_bias_of_shift`.
///
/// Errors: as `zshift_bias_of_shift`; ZSHIFT_ERR_UNRESOLVABLE if the biased depth is stored at
/// no distance. `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_shift_of_bias(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    api: ZshiftBiasApi,
    bias: f64,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        let mapping = DepthMapping::projection(n, f, clip_of(clip)?)?;
        crate::polygon_offset::shift_of_bias(&mapping, format_of(format)?, api_of(api)?, bias, pz)
    })
}

//! Polygon-offset equivalence: an eye-space shift `δ` at `Pz` expressed as the constant depth
//! bias of each API, and back, so an engine can compare or mix the projection-matrix offset with
//! `glPolygonOffset`, Direct3D's `DepthBias` and Vulkan's `depthBiasConstantFactor`.
//!
//! Each API adds `bias · r` to window depth (plus a slope term, which this module leaves at 0:
//! seed 004 explains why steep polygons need it), where `r` is the format's minimum resolvable
//! difference. Only the constant term is converted here.

use crate::domain::{finite, representable};
use crate::error::{Error, ErrorKind, Result};
use crate::precision::{DepthFormat, DepthMapping};

/// An API whose constant depth bias is converted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BiasApi {
    /// `glPolygonOffset(factor, units)`: `units · r`. The GL spec leaves `r` of fixed-point
    /// buffers to the implementation; this uses Mesa's `1/(2^m − 1)`.
    OpenGl,
    /// Direct3D 10–12 `DepthBias` (an integer): `r = 1/(2^m − 1)` for UNORM ("the minimum
    /// representable value > 0" of the format).
    Direct3d,
    /// Vulkan `depthBiasConstantFactor` with the default `LEAST_REPRESENTABLE_VALUE_FORMAT`
    /// representation: `r = 2^−m` for UNORM (implementations may scale it by up to 2 unless
    /// `depthBiasExact`; the bias then only grows).
    Vulkan,
}

/// The minimum resolvable difference `r` of `api` for `format` at window depth `w`: as on
/// [`BiasApi`] for UNORM formats, and `2^(e − 23)` for `Float32` in all three (`e` the exponent
/// of the primitive's largest depth; here of `w`).
///
/// # Errors
/// As [`DepthFormat::spacing_at`].
pub fn resolvable_difference(api: BiasApi, format: DepthFormat, w: f64) -> Result<f64> {
    let spacing = format.spacing_at(w)?;
    if api == BiasApi::Vulkan && format.is_unorm() {
        return Ok(2f64.powi(-(format.bits() as i32)));
    }
    Ok(spacing)
}

/// The constant bias of `api` (units of `r`, signed as the API adds it to window depth) that
/// shifts depth at `Pz` as moving the point toward the camera by `δ` would:
/// `(w(d − δ) − w(d)) / r` with `d = −Pz` and `r` taken at `w(d)`.
///
/// Negative for `δ > 0` under the standard conventions (`glPolygonOffset(0, −units)` pulls
/// toward the camera); positive under reversed Z. Not rounded: see [`d3d_depth_bias`].
///
/// # Errors
/// As [`DepthMapping::window_change_of_shift`]; [`ErrorKind::NotFinite`] for NaN `Pz`.
pub fn bias_of_shift(
    mapping: &DepthMapping,
    format: DepthFormat,
    api: BiasApi,
    delta: f64,
    pz: f64,
) -> Result<f64> {
    finite(pz, "the eye-space depth Pz is NaN or infinite")?;
    let d = -pz;
    let r = resolvable_difference(api, format, mapping.window_depth(d)?)?;
    representable(
        mapping.window_change_of_shift(delta, d)? / r,
        "the depth bias overflows f64",
    )
}

/// The eye-space shift toward the camera that a constant `bias` of `api` makes at `Pz`: the
/// inverse of [`bias_of_shift`].
///
/// # Errors
/// As [`DepthMapping::shift_of_window_change`].
pub fn shift_of_bias(
    mapping: &DepthMapping,
    format: DepthFormat,
    api: BiasApi,
    bias: f64,
    pz: f64,
) -> Result<f64> {
    finite(pz, "the eye-space depth Pz is NaN or infinite")?;
    finite(bias, "the depth bias is NaN or infinite")?;
    let d = -pz;
    let r = resolvable_difference(api, format, mapping.window_depth(d)?)?;
    mapping.shift_of_window_change(bias * r, d)
}

/// Direct3D's integer `DepthBias` for a shift `δ` at `Pz`: [`bias_of_shift`] rounded away from
/// zero, so the shift made is never smaller than `δ`.
///
/// # Errors
/// As [`bias_of_shift`]; [`ErrorKind::Overflow`] if it does not fit in `i32`.
pub fn d3d_depth_bias(
    mapping: &DepthMapping,
    format: DepthFormat,
    delta: f64,
    pz: f64,
) -> Result<i32> {
    let bias = bias_of_shift(mapping, format, BiasApi::Direct3d, delta, pz)?;
    let rounded = if bias >= 0.0 {
        bias.ceil()
    } else {
        bias.floor()
    };
    if rounded.abs() > f64::from(i32::MAX) {
        return Err(Error::new(
            ErrorKind::Overflow,
            "the Direct3D DepthBias does not fit in INT",
        ));
    }
    Ok(rounded as i32)
}

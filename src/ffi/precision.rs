//! Depth precision: window depth, the depth step, the minimum offsets (Walker, Lengyel).

use super::{checked_scalar, clip_of, format_of, ZshiftClip, ZshiftFormat, ZshiftStatus};
use crate::precision::DepthMapping;

/// Writes the smallest |epsilon| that moves depth by one step of a `bits`-bit depth buffer:
/// 2/(2^bits - 1) * (f - n)/(f + n), seed 000 eq. 4.1.8 as corrected by seed 002 (factor 2, since
/// NDC depth spans [-1, 1]). With f = +INFINITY, 2/(2^bits - 1). The seed-compatible spelling
/// (any `bits`) of `zshift_min_epsilon_clip(n, f, ZSHIFT_CLIP_NEG_ONE_TO_ONE, UNORM format, d)`.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, bits
/// outside 1..=32). `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_min_epsilon(n: f64, f: f64, bits: u32, out: *mut f64) -> ZshiftStatus {
    checked_scalar(out, || crate::offset::min_epsilon(n, f, bits))
}

/// Writes the smallest shift toward the camera (positive) that changes the stored depth of a
/// point at eye-space depth `pz`: k*pz^2 / (1 - k*pz), seed 000 eq. 4.1.9 with the corrected
/// k = (f - n)/(f*n*(2^bits - 1)) of seed 002. Equals `zshift_depth_resolution` at d = -pz: a
/// seed-compatible spelling of `zshift_depth_step(n, f, ZSHIFT_CLIP_NEG_ONE_TO_ONE, UNORM, -pz)`.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, pz
/// outside [-f, -n], bits outside 1..=32). `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_min_delta_toward(
    n: f64,
    f: f64,
    bits: u32,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || crate::offset::min_delta_toward(n, f, bits, pz))
}

/// Writes the largest (least negative) shift away from the camera that still changes the stored
/// depth of a point at `pz`: -k*pz^2 / (1 + k*pz), seed 000 eq. 4.1.10 with the corrected k.
/// Ill-conditioned as k*|pz| -> 1: the error grows with k|pz|/(1 - k|pz|), and no faster.
///
/// Errors: as `zshift_min_delta_toward`; ZSHIFT_ERR_UNRESOLVABLE if k*|pz| >= 1 (no finite shift
/// away reaches the next depth value); ZSHIFT_ERR_OVERFLOW. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_max_delta_away(
    n: f64,
    f: f64,
    bits: u32,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || crate::offset::max_delta_away(n, f, bits, pz))
}

/// Writes the window depth in [0, 1] stored for a point at eye distance `d` (positive):
/// Walker's f(d) = (f+n)/(2(f-n)) - fn/(d(f-n)) + 1/2 (seed 001), evaluated as
/// f/(f-n) * (d-n)/d without cancellation. Standard GL depth range, NDC [-1, 1]. The
/// seed-compatible spelling of `zshift_window_depth_clip(n, f, ZSHIFT_CLIP_NEG_ONE_TO_ONE, d)`.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, d
/// outside [n, f]). `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_window_depth(n: f64, f: f64, d: f64, out: *mut f64) -> ZshiftStatus {
    checked_scalar(out, || crate::precision::window_depth(n, f, d))
}

/// Writes the exact size of one depth step at eye distance `d`: the Δd > 0 with
/// f(d) - f(d - Δd) = 1/(2^bits - 1), i.e. q*d^2/(b + q*d) with q = 1/(2^bits - 1) and
/// b = fn/(f - n): Walker's eq. (3) (seed 001) generalised to any d in [n, f]. The
/// seed-compatible spelling (any `bits`) of `zshift_depth_step(n, f, ZSHIFT_CLIP_NEG_ONE_TO_ONE,
/// UNORM format, d)`.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, d
/// outside [n, f], bits outside 1..=32). `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_depth_resolution(
    n: f64,
    f: f64,
    bits: u32,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || crate::precision::depth_resolution(n, f, bits, d))
}

/// Writes the window depth in [0, 1] stored at eye distance `d` (in [n, f]) under `clip`
/// (glDepthRange(0, 1)): f(d - n)/((f - n)d) for [-1, 1] and [0, 1] (Walker, seed 001),
/// n(f - d)/((f - n)d) reversed.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, d
/// outside [n, f], unknown clip). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_window_depth_clip(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::projection(n, f, clip_of(clip)?)?.window_depth(d)
    })
}

/// Writes the exact depth step at eye distance `d` under `clip` and `format`: the shift toward
/// the camera that moves the window depth by the format's spacing r at w(d) (1/(2^m - 1), or
/// 2^(e-23) for FLOAT32): r d^2/(b + r d), b = fn/(f - n) (n if f = +INFINITY). Walker's eq. (3)
/// for every convention; also the minimum delta toward the camera.
///
/// Errors: as `zshift_window_depth_clip`; ZSHIFT_ERR_DOMAIN for an unknown format.
/// `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_depth_step(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::projection(n, f, clip_of(clip)?)?.depth_step(d, format_of(format)?)
    })
}

/// Writes the depth step at eye distance `d` (>= 0) under Kooima's median projection:
/// r (d + median)^2 / (median + r (d + median)), window depth d/(d + median).
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (median <= 0,
/// d < 0, unknown format). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_median_depth_step(
    median: f64,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::median(median)?.depth_step(d, format_of(format)?)
    })
}

/// Writes the smallest constant NDC offset (a magnitude) that changes the stored depth at `d`:
/// r / (window per NDC unit); 2/(2^m - 1) for UNORM under [-1, 1] (seed 002's quantum).
///
/// Errors: as `zshift_depth_step`. `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_min_ndc_offset(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::projection(n, f, clip_of(clip)?)?.min_ndc_offset(d, format_of(format)?)
    })
}

/// Writes the smallest |epsilon| for Lengyel's element-10 scaling m10 (1 + epsilon) (seed 000,
/// eq. 4.1.3) that changes the stored depth at `d` under `clip` and `format`: the minimum NDC
/// offset / |m10|. [-1, 1], UNORM: 2/(2^m - 1) (f - n)/(f + n) (eq. 4.1.8 as corrected by seed
/// 002); [0, 1], UNORM: 1/(2^m - 1) (f - n)/f; reversed: r (f - n)/n.
///
/// Errors: as `zshift_depth_step`; ZSHIFT_ERR_UNRESOLVABLE for reversed Z with f = +INFINITY,
/// where m10 = 0 and scaling it offsets nothing (use `zshift_min_relative_epsilon`).
/// `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_min_epsilon_clip(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::projection(n, f, clip_of(clip)?)?.min_epsilon(d, format_of(format)?)
    })
}

/// Writes the smallest relative epsilon (element 14 scaled by 1 + epsilon) that changes the
/// stored depth at `d`: r d / b. About 2^-23 at every distance for FLOAT32 under reversed Z.
///
/// Errors: as `zshift_depth_step`. `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_min_relative_epsilon(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        DepthMapping::projection(n, f, clip_of(clip)?)?.min_relative_epsilon(d, format_of(format)?)
    })
}

/// Writes the exact depth step of an orthographic projection (`zshift_ortho`) at eye distance
/// `d`: the shift that moves the stored window depth by the format's spacing r at w(d), which
/// is r*(f - n) (window depth is linear in d: (d - n)/(f - n), reversed (f - d)/(f - n)). For
/// UNORM formats the same at every distance; for FLOAT32, r = 2^(e-23) at the stored depth.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (f <= n, d outside
/// [n, f], unknown clip or format). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_ortho_depth_step(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    d: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || {
        let o = crate::orthographic::Ortho::new(-1.0, 1.0, -1.0, 1.0, n, f)?;
        o.depth_step(clip_of(clip)?, format_of(format)?, d)
    })
}

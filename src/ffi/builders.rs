//! Projection builders: glFrustum, gluPerspective, every clip convention, tweaked infinite.

use super::{checked_matrix, clip_of, ZshiftClip, ZshiftStatus};
use crate::projection::{fast, ClipDepth, DepthRow, Frustum};

/// Writes the `glFrustum` matrix (column-major, 16 floats) to `out`. The seed-compatible spelling
/// of `zshift_projection(l, r, b, t, n, f, ZSHIFT_CLIP_NEG_ONE_TO_ONE, out)` (bit-identical).
///
/// Convention: right-handed eye space, NDC depth [-1, 1], the matrix `glFrustum(l, r, b, t, n, f)`
/// builds. Each element is the f32 nearest the exact value (within 1 ulp). `f` may be
/// `+INFINITY`: then element 10 is -1 and element 14 is -2n. Seed 000, eq. 4.1.1.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `out` is NULL; ZSHIFT_ERR_NOT_FINITE for NaN or an
/// infinity other than f = +INFINITY; ZSHIFT_ERR_DOMAIN if l == r, b == t, n <= 0 or f <= n;
/// ZSHIFT_ERR_OVERFLOW if an element does not fit in a float. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_frustum(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let depth = DepthRow::Clip(ClipDepth::NegOneToOne);
    checked_matrix(out, fast(l, r, b, t, n, f, depth), move || {
        Frustum::new(l, r, b, t, n, f)?.to_cols_array()
    })
}

/// Writes the gluPerspective(fovy, aspect, n, f) matrix (column-major, 16 floats) to `out`.
///
/// Convention: right-handed, NDC depth [-1, 1]; fovy in degrees; `f` may be +INFINITY. The
/// frustum is t = n tan(fovy/2), r = t aspect, centred; each element the nearest float.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER; ZSHIFT_ERR_NOT_FINITE (NaN or infinity other than f);
/// ZSHIFT_ERR_DOMAIN unless 0 < fovy < 180, aspect > 0, 0 < n < f. `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_perspective(
    fovy: f64,
    aspect: f64,
    n: f64,
    f: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = crate::projection::perspective_fast_columns(fovy, aspect, n, f);
    checked_matrix(out, fast, move || {
        crate::projection::perspective_frustum(fovy, aspect, n, f)?.to_cols_array()
    })
}

/// Writes the glFrustum(l, r, b, t, n, f) matrix with the depth row of `clip` (a ZSHIFT_CLIP_*):
/// m10, m14 = -(f+n)/(f-n), -2fn/(f-n) for [-1, 1]; -f/(f-n), -fn/(f-n) for [0, 1];
/// n/(f-n), fn/(f-n) reversed; with f = +INFINITY: -1, -2n; -1, -n; 0, n.
///
/// Errors: as `zshift_frustum`; ZSHIFT_ERR_DOMAIN for an unknown `clip`. `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_projection(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ZshiftClip,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = clip_of(clip)
        .ok()
        .and_then(|c| fast(l, r, b, t, n, f, DepthRow::Clip(c)));
    checked_matrix(out, fast, move || {
        crate::projection::projection(&Frustum::new(l, r, b, t, n, f)?, clip_of(clip)?)
    })
}

/// The smallest tweak epsilon for `zshift_tweaked_infinite` that keeps far geometry inside the
/// clip volume in float arithmetic: 2^-22 (Lengyel, GDC 2007).
pub const ZSHIFT_MIN_INFINITE_TWEAK: f64 = 2.384185791015625e-7;

/// Writes the tweaked infinite projection (Lengyel, GDC 2007; GLM tweakedInfinitePerspective):
/// the glFrustum(l, r, b, t, n, -) x/y rows, m10 = tweak - 1, m14 = (tweak - 2) n, NDC [-1, 1].
/// With tweak >= ZSHIFT_MIN_INFINITE_TWEAK geometry at any distance stays inside the clip volume
/// in float arithmetic (the plain infinite projection puts it on the far plane, where GL_LESS
/// against a cleared 1.0 rejects it).
///
/// Errors: as `zshift_frustum` (with f = +INFINITY); ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN
/// unless 0 <= tweak < 1. `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_tweaked_infinite(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    tweak: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = fast(l, r, b, t, n, f64::INFINITY, DepthRow::Tweaked(tweak));
    checked_matrix(out, fast, move || {
        crate::projection::tweaked_infinite(&Frustum::new(l, r, b, t, n, f64::INFINITY)?, tweak)
    })
}

/// Writes the glOrtho(l, r, b, t, n, f) matrix with the depth row of `clip` (column-major, 16
/// floats): m0 = 2/(r-l), m5 = 2/(t-b), m12 = -(r+l)/(r-l), m13 = -(t+b)/(t-b), m15 = 1, and
/// m10, m14 = -2/(f-n), -(f+n)/(f-n) for [-1, 1] (glOrtho's own); -1/(f-n), -n/(f-n) for [0, 1];
/// 1/(f-n), f/(f-n) reversed. Depth is linear in eye distance; n may be 0 or negative.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER; ZSHIFT_ERR_NOT_FINITE for NaN or an infinity;
/// ZSHIFT_ERR_DOMAIN if l == r, b == t, f <= n, or `clip` is unknown; ZSHIFT_ERR_OVERFLOW.
/// `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_ortho(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ZshiftClip,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = clip_of(clip)
        .ok()
        .and_then(|c| crate::orthographic::ortho_columns(l, r, b, t, n, f, c));
    checked_matrix(out, fast, move || {
        let o = crate::orthographic::Ortho::new(l, r, b, t, n, f)?;
        crate::orthographic::ortho(&o, clip_of(clip)?)
    })
}

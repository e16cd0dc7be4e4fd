//! Offset matrices: the seed-compatible LoadOffsetMatrix, epsilon, and the offset projection of
//! every convention; Kooima's median offset.

use super::{checked_matrix, checked_scalar, clip_of, ZshiftClip, ZshiftStatus};
use crate::projection::Frustum;

/// Writes the depth-offset projection matrix: the drop-in for the seed's `LoadOffsetMatrix`,
/// with the same eight inputs, writing the matrix instead of loading it. The seed-compatible
/// spelling of `zshift_offset_projection(.., ZSHIFT_CLIP_NEG_ONE_TO_ONE, delta, pz, out)` (the same
/// offset, element 10 within one float ulp); for a matrix you already have, `zshift_offset_matrix`.
///
/// Convention: as `zshift_frustum`; `delta > 0` moves geometry toward the camera by `delta`
/// eye-space units at eye-space depth `pz` (negative, in [-f, -n]). Element 10 is scaled by
/// 1 + epsilon (seed 000, eq. 4.1.3 and 4.1.7), computed in double precision and rounded away
/// from the plain element, so the offset the GPU sees, |out[10] - plain[10]|, is never smaller
/// than |m10 * epsilon| and at most one float ulp larger. All other elements are bit-identical
/// to `zshift_frustum`'s.
///
/// Errors: as `zshift_frustum`; ZSHIFT_ERR_NOT_FINITE if `delta` or `pz` is not finite;
/// ZSHIFT_ERR_DOMAIN if pz is outside [-f, -n] or pz + delta >= 0. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_load_offset_matrix(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = crate::offset::offset_quick(l, r, b, t, n, f, delta, pz);
    checked_matrix(out, fast, move || {
        crate::offset::offset_matrix(&Frustum::new(l, r, b, t, n, f)?, delta, pz)
    })
}

/// Writes epsilon for an eye-space shift `delta` at eye-space depth `pz` (seed 000, eq. 4.1.7):
/// epsilon = -(2fn/(f+n)) * delta / (pz * (pz + delta)); with f = +INFINITY, 2fn/(f+n) -> 2n.
///
/// Convention: delta > 0 toward the camera gives epsilon < 0. Accurate to a few ulp.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, pz
/// outside [-f, -n], pz + delta >= 0), ZSHIFT_ERR_OVERFLOW. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_epsilon(
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || crate::offset::epsilon(n, f, delta, pz))
}

/// Writes `zshift_projection`'s matrix with geometry at eye depth `pz` (in [-f, -n]) moved toward
/// the camera by `delta` (negative: away). [-1, 1] and [0, 1]: a constant NDC offset
/// c = z_ndc(-pz - delta) - z_ndc(-pz) through element 10 (seed 000 eq. 4.1.3-4.1.7 generalised).
/// Reversed: element 14 scaled by 1 + delta/(-pz - delta), which moves every point to
/// d/(1 + epsilon): the offset that exists when element 10 is 0 and suits float depth.
/// The offset element is rounded away from the plain one, so the offset is never lost.
///
/// Errors: as `zshift_projection`; ZSHIFT_ERR_DOMAIN if pz is outside [-f, -n] or the shifted
/// point leaves [n, f] (or the eye). `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_projection(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ZshiftClip,
    delta: f64,
    pz: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = Frustum::new(l, r, b, t, n, f)
        .ok()
        .and_then(|frustum| offset_projection_fast(&frustum, clip, delta, pz));
    checked_matrix(out, fast, || {
        let frustum = Frustum::new(l, r, b, t, n, f)?;
        crate::clip_offset::offset_projection(&frustum, clip_of(clip)?, delta, pz)
    })
}

/// The fast path of `zshift_offset_projection` and `zshift_offset_perspective` for a valid
/// frustum (float arithmetic and comparisons only, nothing that can panic): `None` where the
/// checked, exact path must decide or explain.
#[inline(always)]
fn offset_projection_fast(
    frustum: &Frustum,
    clip: ZshiftClip,
    delta: f64,
    pz: f64,
) -> Option<glam::Mat4> {
    let clip = clip_of(clip).ok()?;
    let m = crate::clip_offset::offset_projection_fast(frustum, clip, delta, pz)?;
    Some(glam::Mat4::from_cols_array(&m))
}

/// `zshift_offset_projection` for gluPerspective parameters (fovy in degrees).
///
/// Errors: as `zshift_perspective` and `zshift_offset_projection`. `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_perspective(
    fovy: f64,
    aspect: f64,
    n: f64,
    f: f64,
    clip: ZshiftClip,
    delta: f64,
    pz: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = crate::projection::perspective_frustum(fovy, aspect, n, f)
        .ok()
        .and_then(|frustum| offset_projection_fast(&frustum, clip, delta, pz));
    checked_matrix(out, fast, || {
        let frustum = crate::projection::perspective_frustum(fovy, aspect, n, f)?;
        crate::clip_offset::offset_projection(&frustum, clip_of(clip)?, delta, pz)
    })
}

/// Writes `zshift_tweaked_infinite`'s matrix with geometry at `pz` moved toward the camera by
/// `delta` (a constant NDC offset through element 10, rounded outward).
///
/// Errors: as `zshift_tweaked_infinite`; ZSHIFT_ERR_DOMAIN if pz > -n or pz + delta > -n.
/// `out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_tweaked_infinite(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    tweak: f64,
    delta: f64,
    pz: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = Frustum::new(l, r, b, t, n, f64::INFINITY)
        .ok()
        .and_then(|frustum| {
            crate::clip_offset::offset_tweaked_infinite_fast(&frustum, tweak, delta, pz)
        })
        .map(|m| glam::Mat4::from_cols_array(&m));
    checked_matrix(out, fast, move || {
        let frustum = Frustum::new(l, r, b, t, n, f64::INFINITY)?;
        crate::clip_offset::offset_tweaked_infinite(&frustum, tweak, delta, pz)
    })
}

/// Writes the `ndc_offset` uniform of bindings/glsl/ftransform_mdp.glsl (Kooima's median
/// projection, seed 003) that moves geometry at `pz` toward the camera by `delta`:
/// -2 median delta / ((d + median)(d + median - delta)), d = -pz.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN unless median > 0,
/// pz <= 0 and pz + delta <= 0. `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_median_ndc_offset(
    median: f64,
    delta: f64,
    pz: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_scalar(out, || crate::median::ndc_offset(median, delta, pz))
}

/// Writes `zshift_ortho`'s matrix with every point moved toward the camera by `delta` eye units
/// (negative: away): element 14 moved by m10*delta (the same shift at every distance), rounded
/// outward; the other elements bit-identical to `zshift_ortho`'s.
///
/// Errors: as `zshift_ortho`; ZSHIFT_ERR_NOT_FINITE if `delta` is NaN or infinite. `out`
/// untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_ortho(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ZshiftClip,
    delta: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let fast = clip_of(clip)
        .ok()
        .and_then(|c| crate::orthographic::offset_ortho_columns(l, r, b, t, n, f, c, delta));
    checked_matrix(out, fast, move || {
        let o = crate::orthographic::Ortho::new(l, r, b, t, n, f)?;
        crate::orthographic::offset_ortho(&o, clip_of(clip)?, delta)
    })
}

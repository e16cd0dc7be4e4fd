//! Scene planning: tight near/far planes and one offset for a depth range.

use super::{
    checked_array, clip_of, format_of, kind_of, ZshiftClip, ZshiftFormat, ZshiftOffsetKind,
    ZshiftStatus,
};
use crate::precision::DepthMapping;

/// Writes the tightest planes for a scene between eye distances `nearest` and `farthest`:
/// `out[0]` = n, `out[1]` = f (possibly +INFINITY: then use the tweaked infinite projection or
/// reversed Z), keeping a window-depth margin of 2^-22 inside each plane so f32 rounding clips
/// no vertex.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN unless
/// 0 < nearest <= farthest. `out[0..2]` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_tight_planes(nearest: f64, farthest: f64, out: *mut f64) -> ZshiftStatus {
    checked_array(out, || {
        let planes = crate::plan::tight_planes(nearest, farthest)?;
        Ok([planes.near(), planes.far()])
    })
}

/// Writes the smallest single offset that moves stored depth by at least `steps` steps at every
/// distance in `[lo, hi]`: `out[0]` = the offset (`kind` ZSHIFT_OFFSET_NDC: a signed NDC offset
/// toward the camera for element 10; ZSHIFT_OFFSET_RELATIVE: epsilon for element 14),
/// `out[1]`, `out[2]` = the eye-space shifts it makes at lo and at hi. Multiply `out[0]` by k for
/// the k-th stacked decal layer; keep k * `out[2]` below the gap where decals bleed through.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN (bad planes, range
/// outside `[n, f]` or lo > hi, steps < 1, unknown enum), ZSHIFT_ERR_UNRESOLVABLE.
/// `out[0..3]` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_range_offset(
    n: f64,
    f: f64,
    clip: ZshiftClip,
    format: ZshiftFormat,
    kind: ZshiftOffsetKind,
    lo: f64,
    hi: f64,
    steps: f64,
    out: *mut f64,
) -> ZshiftStatus {
    checked_array(out, || {
        let mapping = DepthMapping::projection(n, f, clip_of(clip)?)?;
        let o =
            crate::plan::range_offset(&mapping, format_of(format)?, kind_of(kind)?, lo, hi, steps)?;
        Ok([o.offset, o.shift_near, o.shift_far])
    })
}

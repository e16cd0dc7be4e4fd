//! Scene planning, so a scene pays for the depth precision it needs and no more: tight near and
//! far planes from its eye-space bounds, the smallest single offset that works across a decal
//! depth range, and offsets for stacked decal layers that stay below a bleed-through gap.

use crate::domain::{domain, finite, Planes};
use crate::error::{Error, ErrorKind, Result};
use crate::precision::{DepthFormat, DepthMapping};

/// The window-depth margin [`tight_planes`] keeps between the scene and each clip plane:
/// `2⁻²²`, four f32 ulps of 1 — more than the f32 rounding of the matrix, the clip-space
/// product and the divide can move a vertex's depth, so no vertex of the scene is clipped.
///
/// cbindgen:ignore
pub const PLANE_MARGIN: f64 = 1.0 / 4_194_304.0;

/// The tightest planes for a scene whose geometry lies between eye distances `nearest` and
/// `farthest` (for eye-space bounds `[z_min, z_max]`, pass `−z_max` and `−z_min`), keeping
/// [`PLANE_MARGIN`] of window depth inside each plane (standard mapping, Walker's `f(d)`):
///
/// * `n = nearest·(1 − 4·margin)`, so `w(nearest) ≥ 4·margin`;
/// * `f = n·D·(1 − margin)/(n − margin·D)` with `D = farthest`, the smallest far plane with
///   `w(D) ≤ 1 − margin`, rounded up; `f = +∞` when `n ≤ margin·D` — there the scene spans
///   more than the f32 pipeline can resolve against a finite far plane, and it should use
///   [`crate::projection::tweaked_infinite`] or reversed Z.
///
/// # Errors
/// [`ErrorKind::NotFinite`] for NaN or ±∞; [`ErrorKind::Domain`] unless
/// `0 < nearest ≤ farthest`.
pub fn tight_planes(nearest: f64, farthest: f64) -> Result<Planes> {
    finite(nearest, "the nearest scene distance is NaN or infinite")?;
    finite(farthest, "the farthest scene distance is NaN or infinite")?;
    if nearest <= 0.0 || farthest < nearest {
        return Err(domain("scene bounds need 0 < nearest <= farthest"));
    }
    let n = nearest * (1.0 - 4.0 * PLANE_MARGIN);
    let slack = n - PLANE_MARGIN * farthest;
    if slack <= 0.0 {
        return Planes::new(n, f64::INFINITY);
    }
    // f·(n − ηD) ≥ nD(1 − η); two ulps of headroom cover the rounding of this expression.
    let f = (n * farthest) * ((1.0 - PLANE_MARGIN) / slack) * (1.0 + 4.0 * f64::EPSILON);
    Planes::new(n, f.max(farthest * (1.0 + 4.0 * f64::EPSILON)))
}

/// How an offset is applied: which element of the projection carries it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OffsetKind {
    /// A constant NDC depth offset through element 10 ([`crate::clip_offset::ndc_offset_matrix`]);
    /// the natural offset for UNORM buffers.
    Ndc,
    /// A relative offset, element 14 scaled by `1 + ε`
    /// ([`crate::clip_offset::relative_offset_matrix`]); the natural offset for reversed Z with
    /// float depth.
    Relative,
}

/// One offset for a whole depth range, with the eye-space shift it makes at both ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangeOffset {
    /// The offset: a signed NDC offset toward the camera (`OffsetKind::Ndc`), or the relative
    /// `ε > 0` (`OffsetKind::Relative`).
    pub offset: f64,
    /// The shift toward the camera it makes at the near end of the range.
    pub shift_near: f64,
    /// The shift toward the camera it makes at the far end of the range.
    pub shift_far: f64,
}

/// The distances in `[lo, hi]` where the requirement of `offset_needed` can peak: the ends, and
/// for float formats every distance whose window depth is a power of two (where the spacing
/// `2^(e−23)` jumps).
fn candidate_distances(
    mapping: &DepthMapping,
    format: DepthFormat,
    lo: f64,
    hi: f64,
) -> Result<Vec<f64>> {
    let mut ds = vec![lo, hi];
    if format.is_unorm() {
        return Ok(ds);
    }
    let (w_lo, w_hi) = (mapping.window_depth(lo)?, mapping.window_depth(hi)?);
    let (w_min, w_max) = (w_lo.min(w_hi), w_lo.max(w_hi));
    let mut p = 1.0f64;
    while p >= w_min && p > f64::from(f32::MIN_POSITIVE) {
        if p <= w_max {
            ds.push(mapping.distance_at_window(p)?.clamp(lo, hi));
        }
        p *= 0.5;
    }
    Ok(ds)
}

/// The offset needed at distance `d` for `steps` stored-depth steps.
fn offset_needed(
    mapping: &DepthMapping,
    format: DepthFormat,
    kind: OffsetKind,
    steps: f64,
    d: f64,
) -> Result<f64> {
    let one = match kind {
        OffsetKind::Ndc => mapping.min_ndc_offset(d, format)?,
        OffsetKind::Relative => mapping.min_relative_epsilon(d, format)?,
    };
    Ok(steps * one)
}

/// The eye-space shift toward the camera that `offset` (of `kind`) makes at distance `d`.
fn shift_made(mapping: &DepthMapping, kind: OffsetKind, offset: f64, d: f64) -> Result<f64> {
    match kind {
        OffsetKind::Ndc => mapping.shift_of_window_change(offset * mapping.window_per_ndc(), d),
        OffsetKind::Relative => Ok(d * (offset / (1.0 + offset))),
    }
}

/// The smallest single offset that moves stored depth by at least `steps` steps of `format` at
/// every distance in `[lo, hi]` (decals anywhere in that range), and the shifts it makes.
///
/// One step is the exact bound (seed 002's corrected eq. 4.1.8 for UNORM); a real rasterizer
/// needs a margin for interpolation and vertex snapping, so pass `steps ≥ 2` (see
/// `../shared/NOTES.md`: 2 for surfaces facing the camera, more on slopes).
///
/// # Errors
/// [`ErrorKind::NotFinite`] if `lo`, `hi` or `steps` is NaN or infinite;
/// [`ErrorKind::Domain`] unless `steps ≥ 1` and `lo ≤ hi` lie in the mapping's range;
/// as [`DepthMapping::min_relative_epsilon`] for `Relative` on the median projection.
pub fn range_offset(
    mapping: &DepthMapping,
    format: DepthFormat,
    kind: OffsetKind,
    lo: f64,
    hi: f64,
    steps: f64,
) -> Result<RangeOffset> {
    finite(steps, "the number of depth steps is NaN or infinite")?;
    finite(lo, "the nearest decal distance lo is NaN or infinite")?;
    finite(hi, "the farthest decal distance hi is NaN or infinite")?;
    if steps < 1.0 || lo > hi {
        return Err(domain("need steps >= 1 and lo <= hi"));
    }
    let mut needed = 0.0f64;
    for d in candidate_distances(mapping, format, lo, hi)? {
        needed = needed.max(offset_needed(mapping, format, kind, steps, d)?);
    }
    let offset = match kind {
        OffsetKind::Ndc if !mapping.is_reversed() => -needed,
        _ => needed,
    };
    let fits = |x: f64| crate::domain::representable(x, "the range offset overflows f64");
    Ok(RangeOffset {
        offset: fits(offset)?,
        shift_near: fits(shift_made(mapping, kind, offset, lo)?)?,
        shift_far: fits(shift_made(mapping, kind, offset, hi)?)?,
    })
}

/// Offsets for `layers` decals stacked on one surface (layer k drawn over layer k − 1, k = 1..),
/// anywhere in `[lo, hi]`: layer k gets `k` times [`range_offset`]'s offset, so each layer is
/// at least `steps` steps above the one below it everywhere in the range.
///
/// `gap` is the eye-space distance at which a decal would bleed through nearby geometry (the
/// thinnest gap between the decaled surface and anything in front of it): the top layer's
/// largest shift must stay below it.
///
/// # Errors
/// As [`range_offset`]; [`ErrorKind::Domain`] unless `layers ≥ 1` and `gap > 0`;
/// [`ErrorKind::Unresolvable`] if the top layer would shift by `gap` or more.
pub fn stacked_layers(
    mapping: &DepthMapping,
    format: DepthFormat,
    kind: OffsetKind,
    range: (f64, f64),
    steps: f64,
    layers: u32,
    gap: f64,
) -> Result<Vec<RangeOffset>> {
    finite(gap, "the bleed-through gap is NaN or infinite")?;
    if layers == 0 || gap <= 0.0 {
        return Err(domain("need layers >= 1 and gap > 0"));
    }
    let one = range_offset(mapping, format, kind, range.0, range.1, steps)?;
    let mut out = Vec::with_capacity(layers as usize);
    for k in 1..=layers {
        let offset = one.offset * f64::from(k);
        let layer = RangeOffset {
            offset,
            shift_near: shift_made(mapping, kind, offset, range.0)?,
            shift_far: shift_made(mapping, kind, offset, range.1)?,
        };
        if layer.shift_near.max(layer.shift_far) >= gap {
            return Err(Error::new(
                ErrorKind::Unresolvable,
                "the stacked decal layers would shift past the bleed-through gap",
            ));
        }
        out.push(layer);
    }
    Ok(out)
}

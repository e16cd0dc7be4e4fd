//! The front door: the engine's own projection matrix in, the decal's matrix out
//! (src/matrix_in.rs), and the recommendation for it.

use super::{
    checked_array, checked_matrix, checked_record, clip_of, format_named, null_pointer, ZshiftClip,
    ZshiftDepthTest, ZshiftFormat, ZshiftRecommendation, ZshiftStatus, ZSHIFT_SUBPIXEL_UNSNAPPED,
};
use crate::domain::{domain, finite};
use crate::error::Result;
use crate::matrix_in::Decal;
use crate::projection::ClipDepth;
use crate::recommend::Snapping;

/// Reads the caller's 16 floats (NULL refused, no alignment needed).
fn matrix_from_c(m: *const f32) -> Option<[f32; 16]> {
    if m.is_null() {
        return None;
    }
    // SAFETY: not NULL; the caller promises 16 readable floats; read_unaligned needs no
    // alignment and copies them before anything is computed (so `out` may overlap `m`).
    Some(unsafe { m.cast::<[f32; 16]>().read_unaligned() })
}

/// Writes the engine's projection `m` (16 floats, column-major, as glUniformMatrix4fv(..,
/// GL_FALSE, ..) takes it) with geometry at eye distance `d` moved toward the camera by `delta`
/// (eye units; negative: away), changing only the element that carries the offset. The call
/// most engines need: pass the matrix the base is drawn with, draw the decal with `out`.
///
/// `m` may come from GLM, glam, glFrustum, gluPerspective, glOrtho or the engine's own code:
/// perspective (finite, infinite, tweaked infinite, reversed; right-handed w = -z or
/// left-handed w = +z) or orthographic. `clip` says which depth convention it was built for;
/// a matrix whose depth runs the other way (a reversed-Z matrix passed with
/// ZSHIFT_CLIP_NEG_ONE_TO_ONE) is an error. Perspective under [-1, 1] and [0, 1]: element 10
/// moves by the constant NDC offset m14*delta/(d*(d - delta)) (seed 000, eq. 4.1.3-4.1.7 on the
/// engine's own elements). Perspective reversed: element 14 is scaled by 1 + delta/(d - delta)
/// (every point moved by the same fraction of its distance; works where m10 = 0). Orthographic:
/// element 14 moves by m10*delta, the same eye shift at every distance. The element is rounded
/// away from its value, so the offset the GPU sees is never less than asked and at most one
/// float ulp of the element more; the other 15 elements are bit-identical to `m`. `out` may be
/// `m` itself.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `m` or `out` is NULL; ZSHIFT_ERR_NOT_FINITE for a NaN or
/// infinite element, `delta` or `d`; ZSHIFT_ERR_DOMAIN for a matrix that is neither (an oblique
/// near plane, m[2] or m[6] != 0; a transposed matrix; m[11] not +-1), a convention mismatch, an
/// unknown `clip`, or (perspective) d <= 0 or d - delta <= 0; ZSHIFT_ERR_OVERFLOW if the element
/// leaves float. zshift_last_error() names the element or input. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_matrix(
    m: *const f32,
    clip: ZshiftClip,
    delta: f64,
    d: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    let fast = clip_of(clip)
        .ok()
        .and_then(|c| crate::matrix_in::offset_shift_fast(&m, c, delta, d));
    checked_matrix(
        out,
        fast.map(|m| glam::Mat4::from_cols_array(&m)),
        move || crate::matrix_in::offset_shift(&m, clip_of(clip)?, delta, d),
    )
}

/// Writes the engine's projection `m` with the NDC depth of every point moved toward the camera
/// by `ndc` (negative: away): element 10 of a perspective matrix (m10 + s*c, s = m[11], c the
/// signed change), element 14 of an orthographic one, rounded outward; the other elements
/// bit-identical. Under ZSHIFT_CLIP_NEG_ONE_TO_ONE an NDC offset is twice the window-depth
/// offset; under [0, 1] and reversed they are equal. For a UNORM buffer of m bits the smallest
/// offset that changes the stored depth is 2/(2^m - 1) NDC under [-1, 1] (seed 002).
///
/// Errors: as `zshift_offset_matrix` (NaN or infinite `ndc` is ZSHIFT_ERR_NOT_FINITE). `out` is
/// untouched on error.
#[no_mangle]
pub extern "C" fn zshift_offset_matrix_ndc(
    m: *const f32,
    clip: ZshiftClip,
    ndc: f64,
    out: *mut f32,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    let fast = clip_of(clip)
        .ok()
        .and_then(|c| crate::matrix_in::offset_ndc_fast(&m, c, ndc));
    checked_matrix(
        out,
        fast.map(|m| glam::Mat4::from_cols_array(&m)),
        move || crate::matrix_in::offset_ndc(&m, clip_of(clip)?, ndc),
    )
}

/// What an engine knows about a decal besides its projection matrix, for
/// `zshift_recommend_for_matrix`. Fill every field: an all-zero ZshiftDecal is refused
/// (viewport 0), and subpixel_bits = 0 is the most conservative value, not a default.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftDecal {
    /// `glViewport` width in pixels (nonzero).
    pub viewport_width: u32,
    /// `glViewport` height in pixels (nonzero).
    pub viewport_height: u32,
    /// The depth attachment's format (ZSHIFT_FORMAT_*).
    pub format: ZshiftFormat,
    /// GL_SUBPIXEL_BITS of the rasterizer (0..=32; 0 means positions snapped to whole pixels,
    /// the most conservative), or ZSHIFT_SUBPIXEL_UNSNAPPED (-1) for a rasterizer that sets
    /// depth up from unsnapped positions (Mesa llvmpipe).
    pub subpixel_bits: i32,
    /// The decal's nearest eye distance (positive, within the matrix's [n, f]).
    pub decal_near: f64,
    /// The decal's farthest eye distance (decal_far >= decal_near).
    pub decal_far: f64,
    /// Eye-space tilt of the decal's plane: |dz/dx| + |dz/dy| (0 when facing the camera).
    pub slope: f64,
    /// Nonzero when every corner of base and decal has the same float eye-space z (requires
    /// slope == 0).
    pub exact_depth: u32,
    /// 0 when every vertex of the base lies inside the view frustum (the rasterizer clips
    /// nothing); when the base may cross the near plane or the screen's edges (a floor running
    /// behind the camera), the largest |x|, |y| or |z| of its eye-space vertices, and the offset
    /// gains the clipping term (as ZshiftScene.base_reach; perspective matrices only).
    pub base_reach: f64,
    /// The rasterizer's profile from `zshift_probe`, or NULL for the worst case with
    /// `subpixel_bits`. When not NULL it supplies every rasterizer fact, its snapping included,
    /// and `subpixel_bits` is ignored (but must still lie in -1..=32).
    pub profile: *const super::probe::ZshiftProfile,
    /// The decal's eye-space corners, 3 floats each (x0, y0, z0, x1, y1, z1, ...: the
    /// positions its vertices have after the model-view transform), in any order (a triangle
    /// strip's 0, 1, 3, 2 too: the decal is taken as their convex hull), or NULL. With corners the
    /// recommendation knows the decal's exact depth plane and where it lies on the screen,
    /// which makes it far tighter on sloped planes (README, "Scenes engines draw"); perspective matrices only; the
    /// corners then define the decal, and decal_near, decal_far and slope must be 0 (they are
    /// derived). NULL (a zeroed struct): decal_near, decal_far and slope describe the decal.
    /// Projected through the matrix given (any handedness or flip). Planes that contain the
    /// view direction (ground under a level camera) are answered from the corners, and so are
    /// decals that reach behind the camera (under it) or beyond the far plane: the part drawn
    /// is what counts.
    pub decal_corners: *const f32,
    /// How many corners `decal_corners` holds (3 to 64; 0 with NULL).
    pub decal_corner_count: u32,
    /// The decal pass's depth test: ZSHIFT_DEPTH_TEST_LESS or ZSHIFT_DEPTH_TEST_LEQUAL, under
    /// reversed Z ZSHIFT_DEPTH_TEST_GREATER or ZSHIFT_DEPTH_TEST_GEQUAL; 0 (a zeroed field):
    /// the convention's strict test. An engine that draws every pass with GL_LEQUAL must say
    /// so: a tie then passes, and the bleed gap is one quantum wider than under GL_LESS.
    pub depth_func: ZshiftDepthTest,
    /// How the engine draws besides the projection: the viewport's origin, glDepthRange,
    /// world-space vertices (ZshiftPipeline; zeroed: the defaults), for perspective and
    /// orthographic matrices alike.
    pub pipeline: super::ZshiftPipeline,
}

/// Converts the caller's decal to the Rust model's (every field checked) and hands it to
/// `then` by reference, where it was built (as `super::recommend`'s `with_model` does: returned
/// through a `Result`, it would be copied once more, with a stall).
fn with_decal<R>(
    m: &[f32; 16],
    clip: ClipDepth,
    d: &ZshiftDecal,
    then: impl FnOnce(&Decal) -> Result<R>,
) -> Result<R> {
    if d.viewport_width == 0 || d.viewport_height == 0 {
        return Err(domain(
            "ZshiftDecal.viewport_width and viewport_height must be nonzero (an all-zero ZshiftDecal is refused)",
        )
        .with_integer(
            if d.viewport_width == 0 {
                "viewport_width"
            } else {
                "viewport_height"
            },
            0,
        ));
    }
    let snapping =
        match d.subpixel_bits {
            ZSHIFT_SUBPIXEL_UNSNAPPED => Snapping::Unsnapped,
            b @ 0..=32 => Snapping::SubpixelBits(b as u32),
            b => return Err(domain(
                "ZshiftDecal.subpixel_bits must lie in 0..=32 or be ZSHIFT_SUBPIXEL_UNSNAPPED (-1)",
            )
            .with_integer("subpixel_bits", i64::from(b))),
        };
    for (name, x) in [
        ("decal_near", d.decal_near),
        ("decal_far", d.decal_far),
        ("slope", d.slope),
        ("base_reach", d.base_reach),
    ] {
        finite(x, "a ZshiftDecal field is NaN or infinite").map_err(|e| e.with_value(name, x))?;
    }
    if d.base_reach < 0.0 {
        return Err(
            domain("ZshiftDecal.base_reach must be >= 0 (0: a base inside the frustum)")
                .with_value("base_reach", d.base_reach),
        );
    }
    let viewport = [d.viewport_width, d.viewport_height];
    let fields = [d.decal_near, d.decal_far, d.slope];
    let shape =
        super::recommend::decal_shape_from_c(d.decal_corners, d.decal_corner_count, fields, |c| {
            crate::matrix_in::decal_shape(m, clip, viewport, c)
        })?;
    let format = format_named(d.format.value, "format")?;
    let profile = if d.profile.is_null() {
        None
    } else {
        Some(super::probe::profile_or_worst(d.profile, snapping)?)
    };
    then(&Decal {
        viewport,
        format,
        depth_range: shape.map_or([d.decal_near, d.decal_far], |s| s.depth_range),
        slope: shape.map_or(d.slope, |s| s.slope),
        footprint: shape.map(|s| s.footprint),
        exact_depth: d.exact_depth != 0,
        snapping,
        base: if d.base_reach == 0.0 {
            crate::recommend::Base::InsideFrustum
        } else {
            crate::recommend::Base::Clipped {
                reach: d.base_reach,
            }
        },
        profile,
        depth_test: match d.depth_func.value {
            0 => None,
            func => Some(
                crate::recommend::DepthTest::from_gl(func)
                    .map_err(|e| e.with_code("depth_func", func))?,
            ),
        },
        pipeline: super::recommend::pipeline_from_c(&d.pipeline)?,
    })
}

/// The recommendation for a decal drawn with the engine's own matrix, its matrix included:
/// what both entry points below compute.
#[inline(always)]
fn recommend_for(
    m: &[f32; 16],
    clip: ZshiftClip,
    decal: &ZshiftDecal,
) -> Result<crate::recommend::ClipRecommendation> {
    let clip = clip_of(clip)?;
    with_decal(m, clip, decal, |d| crate::matrix_in::recommend(m, clip, d))
}

/// The C record of a recommendation under `clip` (valid: [`recommend_for`] has checked it).
fn record_of(r: &crate::recommend::ClipRecommendation, clip: ZshiftClip) -> ZshiftRecommendation {
    let per_ndc = if clip == super::ZSHIFT_CLIP_NEG_ONE_TO_ONE {
        0.5
    } else {
        1.0
    };
    ZshiftRecommendation::new(
        r.epsilon,
        r.window_offset / per_ndc,
        r.window_offset,
        r.delta_at_far,
        r.bleed_gap,
        r.polygon_offset,
        &r.terms,
    )
}

/// Reads the caller's decal (not NULL: the entry point has refused NULL; no alignment needed),
/// inside the entry point's checked closure, as `read_scene` does and for the same reason.
fn read_decal(decal: *const ZshiftDecal) -> ZshiftDecal {
    debug_assert!(!decal.is_null());
    // SAFETY: not NULL (checked by the entry point); the caller promises a readable ZshiftDecal.
    unsafe { super::read_record(decal, ZshiftDecal::read_fields) }
}

impl ZshiftDecal {
    /// Reads an aligned record field by field, for [`super::read_record`].
    ///
    /// # Safety
    /// `p` is not NULL, aligned, and points to a readable ZshiftDecal.
    unsafe fn read_fields(p: *const Self) -> Self {
        use std::ptr::{addr_of, read_volatile as read};
        // SAFETY: as the function's contract; every field is plain data.
        unsafe {
            Self {
                viewport_width: read(addr_of!((*p).viewport_width)),
                viewport_height: read(addr_of!((*p).viewport_height)),
                format: read(addr_of!((*p).format)),
                subpixel_bits: read(addr_of!((*p).subpixel_bits)),
                decal_near: read(addr_of!((*p).decal_near)),
                decal_far: read(addr_of!((*p).decal_far)),
                slope: read(addr_of!((*p).slope)),
                exact_depth: read(addr_of!((*p).exact_depth)),
                base_reach: read(addr_of!((*p).base_reach)),
                profile: read(addr_of!((*p).profile)),
                decal_corners: read(addr_of!((*p).decal_corners)),
                decal_corner_count: read(addr_of!((*p).decal_corner_count)),
                depth_func: read(addr_of!((*p).depth_func)),
                pipeline: super::ZshiftPipeline::read_fields(addr_of!((*p).pipeline)),
            }
        }
    }
}

/// Writes the decal's projection matrix: the engine's own projection `m` (the one its base is
/// drawn with) with the smallest offset that ends z-fighting for `decal` on a real rasterizer
/// (`zshift_recommend_clip`'s model: depth quantum, f32 rounding of transform, vertices and
/// interpolation, sub-pixel snapping of sloped planes; for an orthographic `m` the same terms
/// through its linear depth). The front door: one call, and the engine never restates its
/// frustum, which is read from `m` (any matrix `zshift_offset_matrix` accepts; a tweaked
/// infinite one with a tweak up to 2^-10 is treated as infinite). The offset is applied to
/// `m`'s own element (10, a constant NDC offset, for perspective [-1, 1] and [0, 1]; 14,
/// relative, for reversed Z; 14, constant, for orthographic), rounded outward; the other 15
/// elements are bit-identical to `m`. Verified on Mesa llvmpipe with glam-built matrices
/// (tests/gl_matrix_in.rs). `zshift_recommend_for_matrix` gives the numbers behind it.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `m`, `decal` or `out` is NULL; as `zshift_offset_matrix`
/// for `m` and `clip` (a convention mismatch included); ZSHIFT_ERR_DOMAIN for a tweak above
/// 2^-10, a zero viewport (an all-zero ZshiftDecal), an unknown format, subpixel_bits outside
/// -1..=32, decal_near/decal_far outside the matrix's [n, f] or decreasing, a negative slope,
/// exact_depth with a nonzero slope, a negative base_reach, an unknown depth_func, a `pipeline`
/// field out of range, a `profile` that fails its checks (a zero-filled ZshiftProfile);
/// ZSHIFT_ERR_NOT_FINITE; ZSHIFT_ERR_UNRESOLVABLE when the offset would push the decal past the
/// near plane (the detail says why and what to do); ZSHIFT_ERR_OVERFLOW.
/// zshift_last_error() names the field. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_decal_matrix(
    m: *const f32,
    clip: ZshiftClip,
    decal: *const ZshiftDecal,
    out: *mut f32,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    if decal.is_null() {
        return null_pointer("decal");
    }
    checked_array(out, move || {
        Ok(recommend_for(&m, clip, &read_decal(decal))?.matrix)
    })
}

/// Writes the recommendation behind `zshift_decal_matrix`: the offset in every form (epsilon,
/// NDC and window offsets, the eye shift at decal_far, the bleed-through gap, the
/// glPolygonOffset equivalent) and the error terms it was built from, as `zshift_recommend_clip`
/// writes them for the frustum read from `m`.
///
/// Errors: as `zshift_decal_matrix`. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend_for_matrix(
    m: *const f32,
    clip: ZshiftClip,
    decal: *const ZshiftDecal,
    out: *mut ZshiftRecommendation,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    if decal.is_null() {
        return null_pointer("decal");
    }
    // SAFETY: `checked` has refused NULL; the caller promises a writable ZshiftRecommendation;
    // write_unaligned needs no alignment.
    checked_record(out, move || {
        Ok(record_of(
            &recommend_for(&m, clip, &read_decal(decal))?,
            clip,
        ))
    })
}

/// The most planes one decal may be asked over: far above any decal system's pieces, low enough
/// that a garbage `count` is named rather than read.
const MOST_PLANES: u32 = 1 << 16;

/// The recommendation for one decal over several planes (`zshift::planes::recommend_planes`):
/// each C record read and checked as `zshift_decal_matrix` checks its one, an error said of its
/// plane.
fn recommend_over_planes(
    m: &[f32; 16],
    clip: ZshiftClip,
    decals: *const ZshiftDecal,
    count: u32,
) -> Result<crate::recommend::ClipRecommendation> {
    let clip = clip_of(clip)?;
    if count == 0 || count > MOST_PLANES {
        return Err(domain(
            "count must be at least 1 and at most 65536 (one ZshiftDecal per plane)",
        )
        .with_integer("count", i64::from(count)));
    }
    let mut planes = Vec::with_capacity(count as usize);
    // The caller's index of each plane kept: a piece of which nothing is drawn (wholly behind
    // the near plane, beyond the far plane or off screen, as raw triangles under a decal near
    // the camera are) is left out, and errors name the caller's planes.
    let mut index = Vec::with_capacity(count as usize);
    for i in 0..count {
        // SAFETY: the entry point refused NULL; the caller promises `count` readable records.
        let record = read_decal(unsafe { decals.add(i as usize) });
        match with_decal(m, clip, &record, |d| Ok(*d)) {
            Ok(plane) => {
                planes.push(plane);
                index.push(i);
            }
            Err(e) if crate::footprint::draws_nothing(&e) => {}
            Err(e) => return Err(e.for_item("plane", i)),
        }
    }
    if planes.is_empty() {
        return Err(domain(
            "nothing of the decal is drawn: every plane lies wholly behind the near plane, beyond the far plane or off screen",
        )
        .with_integer("count", i64::from(count)));
    }
    crate::planes::recommend_planes(m, clip, &planes).map_err(|e| {
        e.renumbered("largest_plane", |k| {
            index.get(k as usize).copied().unwrap_or(k)
        })
    })
}

/// Writes the projection matrix of one decal that lies on several planes (a mesh decal over a
/// terrain: the terrain's own triangles clipped to the decal, each piece on its triangle's
/// plane), drawn in one pass: `decals` holds `count` ZshiftDecal records, one per plane, each
/// filled as for `zshift_decal_matrix` (the same viewport, format, depth_func, profile and
/// pipeline; its own decal_corners, base_reach and pipeline.world_box; the corners of the base
/// triangle the piece was cut from, not of the piece: a sliver's corners do not pin its plane
/// down in float; cut to the frustum with zshift_clip_to_frustum where the triangle reaches
/// behind the near plane or off the screen). A plane given by corners of which nothing is drawn
/// (wholly behind the near plane, beyond the far plane or off screen) is left out. The matrix
/// carries the largest of the planes' offsets, which keeps every plane's pixels;
/// `zshift_recommend_for_planes` gives the bleed gap at that offset over every plane.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `m`, `decals` or `out` is NULL; ZSHIFT_ERR_DOMAIN for a
/// `count` of 0 or above 65536, or when nothing of any plane is drawn; any error of
/// `zshift_decal_matrix` for a plane, its detail
/// beginning "plane i: " (from 0); ZSHIFT_ERR_UNRESOLVABLE naming `largest_plane` where the
/// largest offset would move plane i past the near plane though its own fits (one plane's
/// errors dwarf the others': often a terrain triangle seen nearly edge-on): draw each piece
/// with its own matrix (`zshift_decal_matrix` for its record alone), or leave out the piece of
/// plane `largest_plane`. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_decal_matrix_planes(
    m: *const f32,
    clip: ZshiftClip,
    decals: *const ZshiftDecal,
    count: u32,
    out: *mut f32,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    if decals.is_null() {
        return null_pointer("decals");
    }
    checked_array(out, move || {
        Ok(recommend_over_planes(&m, clip, decals, count)?.matrix)
    })
}

/// Writes the recommendation behind `zshift_decal_matrix_planes`: the plane whose offset is
/// largest (its epsilon, offsets and error terms), with `bleed_gap` the largest of every
/// plane's gap at that offset (an occluder that much in front of the base at every pixel is
/// never overdrawn) and the glPolygonOffset equivalent as the largest factor and the largest
/// units of the planes'.
///
/// Errors: as `zshift_decal_matrix_planes`. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend_for_planes(
    m: *const f32,
    clip: ZshiftClip,
    decals: *const ZshiftDecal,
    count: u32,
    out: *mut ZshiftRecommendation,
) -> ZshiftStatus {
    let Some(m) = matrix_from_c(m) else {
        return null_pointer("m");
    };
    if decals.is_null() {
        return null_pointer("decals");
    }
    // SAFETY: `checked` has refused NULL; the caller promises a writable ZshiftRecommendation;
    // write_unaligned needs no alignment.
    checked_record(out, move || {
        Ok(record_of(
            &recommend_over_planes(&m, clip, decals, count)?,
            clip,
        ))
    })
}

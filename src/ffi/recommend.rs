//! The recommended offset for a real rasterizer (src/recommend.rs): the scene and record structs
//! and the zshift_recommend* entry points.

use super::{
    checked, checked_array, checked_in_place, checked_record, clip_of, format_named, null_pointer,
    write_matrix, ZshiftClip, ZshiftDepthTest, ZshiftStatus, ZSHIFT_CLIP_NEG_ONE_TO_ONE,
    ZSHIFT_ERR_DOMAIN,
};
use crate::error::Result;
use crate::projection::{ClipDepth, Frustum};

/// `subpixel_bits` value meaning the rasterizer sets its depth plane up from unsnapped float
/// vertex positions (measured on Mesa llvmpipe): the sub-pixel snapping term is zero.
pub const ZSHIFT_SUBPIXEL_UNSNAPPED: i32 = -1;

/// How the engine draws besides its projection matrix, shared by ZshiftScene and ZshiftDecal.
/// Zero-filled it is the default: the viewport at the framebuffer's origin, glDepthRange(0, 1),
/// vertices that reach the vertex shader in eye space.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftPipeline {
    /// `glViewport`'s x: the viewport's left edge in the framebuffer, pixels (0 for a viewport
    /// at the framebuffer's origin; split screens and editor panes have others). The
    /// rasterizer extrapolates each plane from the framebuffer's origin, so its rounding grows
    /// with the viewport's distance from it.
    pub viewport_x: u32,
    /// `glViewport`'s y: the viewport's bottom edge in the framebuffer, pixels.
    pub viewport_y: u32,
    /// `glDepthRange`'s near end (Direct3D: the viewport's MinDepth). With depth_range_far:
    /// 0 <= near < far <= 1; both 0 (a zeroed struct) means the default glDepthRange(0, 1).
    /// A sub-range (first-person weapons [0, 0.1], skyboxes [0.99, 1]) makes each stored step a
    /// larger part of the NDC range. An inverted range (glDepthRange(1, 0), reversed depth
    /// without glClipControl) is refused, naming glClipControl and ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE.
    pub depth_range_near: f64,
    /// `glDepthRange`'s far end (Direct3D: MaxDepth); see depth_range_near.
    pub depth_range_far: f64,
    /// 0 when base and decal vertices reach the vertex shader in eye space (relative to the
    /// camera, as camera-relative rendering sends them). Engines that keep vertices in world
    /// space and transform them with a float view (model-view, or model-view-projection)
    /// matrix on the GPU: the largest |coordinate| of the camera's position, and of every
    /// model's origin, in world space (rigid matrices; with a uniform scale k, k times that).
    /// The float transform's roundings are relative to these magnitudes, not to the distance
    /// from the camera; the offset gains that term.
    pub world_reach: f64,
    /// With world_reach > 0: nonzero when the vertex shader computes the eye position first and
    /// applies the projection to it (proj * (view * p), proj * (modelView * p), three.js's
    /// projectionMatrix * mvPosition): only the part of its float error off the decal's plane
    /// counts, a far smaller term (needs decal_corners). 0 (a zeroed struct) is the
    /// conservative choice and also covers one model-view-projection matrix (mvp * p, or GLSL's
    /// left-to-right proj * view * model * p), and one view-projection applied to world
    /// positions (bevy's clip_from_world * (world_from_local * p), Unity's UNITY_MATRIX_VP):
    /// pass the camera's view and a world_box as for a model-view multiplied in double. Its
    /// bleed gap is 6-12 times that of the same scene drawn eye first (median).
    pub eye_first: u32,
    /// The float matrix the vertex shader applies to the positions it receives to make eye
    /// coordinates (the view or model-view matrix, 16 floats, column-major), or NULL. With
    /// world_box it tells the model each eye coordinate's rounding exactly, instead of the
    /// bound from world_reach over every rotation: far tighter for a ground under a level
    /// camera, and far from the world origin (README, "The scene every engine draws"). Base and
    /// decal must both be drawn through it. A model with a matrix M of its own (a decal
    /// entity, a terrain chunk), drawn through the model-view V·M: pass the camera's view V and
    /// a world_box reaching |origin| + extent on each axis (for a model centred on its origin,
    /// a box that holds its world corners), when V·M is multiplied in double and rounded once
    /// to float (glm::dmat4); multiplied in float (glm::mat4), pass world_reach (the largest
    /// coordinate of the camera's position and of the models' origins) and view_matrix = NULL.
    /// Base and decal drawn through one model-view (a decal on a vehicle, both in its model
    /// space): pass that model-view and the box of the model-space positions, however it was
    /// multiplied (both go through the same rounded matrix, which keeps them coplanar).
    pub view_matrix: *const f32,
    /// With view_matrix: the box of the base and decal positions the shader receives (their
    /// world-space bounding box: min x, min y, min z, max x, max y, max z). Only the base's
    /// triangles under the decal reach its pixels: for a tessellated ground or terrain, the box
    /// of the cells the decal touches (far tighter than the whole ground's; a decal system
    /// knows them, it projects onto them); for one large quad, its corners. Ignored when
    /// view_matrix is NULL; all zeros with a view_matrix is refused (not given).
    pub world_box: [f64; 6],
}

impl Default for ZshiftPipeline {
    /// The zero-filled record: the default pipeline.
    fn default() -> Self {
        Self::zeroed()
    }
}

impl ZshiftPipeline {
    /// The zero-filled record (the default pipeline), usable in constants.
    pub const fn zeroed() -> Self {
        Self {
            viewport_x: 0,
            viewport_y: 0,
            depth_range_near: 0.0,
            depth_range_far: 0.0,
            world_reach: 0.0,
            eye_first: 0,
            view_matrix: std::ptr::null(),
            world_box: [0.0; 6],
        }
    }

    /// Reads the record field by field, as the records that hold it are read (each load is
    /// forwarded from the caller's store of that field; a block copy stalls on them).
    ///
    /// # Safety
    /// `p` is not NULL, aligned, and points to a readable ZshiftPipeline.
    pub(super) unsafe fn read_fields(p: *const Self) -> Self {
        use std::ptr::{addr_of, read_volatile as read};
        // SAFETY: as the function's contract; every field is plain data.
        unsafe {
            Self {
                viewport_x: read(addr_of!((*p).viewport_x)),
                viewport_y: read(addr_of!((*p).viewport_y)),
                depth_range_near: read(addr_of!((*p).depth_range_near)),
                depth_range_far: read(addr_of!((*p).depth_range_far)),
                world_reach: read(addr_of!((*p).world_reach)),
                eye_first: read(addr_of!((*p).eye_first)),
                view_matrix: read(addr_of!((*p).view_matrix)),
                // Element by element, as the caller stores them.
                world_box: std::array::from_fn(|i| {
                    read(addr_of!((*p).world_box).cast::<f64>().add(i))
                }),
            }
        }
    }
}

/// What a scene knows about one decal and the surface under it, for `zshift_recommend`.
///
/// Convention: OpenGL right-handed eye space, NDC depth [-1, 1]; the base is drawn with
/// `glFrustum(l, r, b, t, n, f)` (or `zshift_frustum`), the decal with element 10 scaled by
/// 1 + epsilon (seed 000, eq. 4.1.3), depth test GL_LESS or GL_LEQUAL.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftScene {
    /// `glFrustum` left extent on the near plane of the base's projection.
    pub l: f64,
    /// `glFrustum` right extent.
    pub r: f64,
    /// `glFrustum` bottom extent.
    pub b: f64,
    /// `glFrustum` top extent.
    pub t: f64,
    /// Near plane distance (> 0).
    pub n: f64,
    /// Far plane distance (> n; may be +INFINITY).
    pub f: f64,
    /// `glViewport` width in pixels (nonzero).
    pub viewport_width: u32,
    /// `glViewport` height in pixels (nonzero).
    pub viewport_height: u32,
    /// The depth attachment's GL internal format: GL_DEPTH_COMPONENT16 (0x81A5),
    /// GL_DEPTH_COMPONENT24 (0x81A6), GL_DEPTH_COMPONENT32 (0x81A7) or
    /// GL_DEPTH_COMPONENT32F (0x8CAC).
    pub depth_format: u32,
    /// The decal's nearest eye distance (positive, n <= decal_near <= decal_far). It also
    /// stands for where the decal's plane crosses the view axis (exact for a decal centred on
    /// it), which sets the slope term.
    pub decal_near: f64,
    /// The decal's farthest eye distance (decal_far <= f).
    pub decal_far: f64,
    /// Eye-space tilt of the decal's plane: |dz/dx| + |dz/dy| (0 when facing the camera).
    pub slope: f64,
    /// Nonzero when every corner of base and decal has the same float eye-space z (a plane
    /// facing the camera, unrotated): two rounding terms vanish. Requires slope == 0. With a
    /// probed profile whose facing_chain is known, pass decal_near == decal_far == the float -z
    /// drawn for the exact offset, and draw the base with zshift_frustum's matrix (or one within
    /// 2 float steps of it in elements 10 and 14, f >= 2n).
    pub exact_depth: u32,
    /// GL_SUBPIXEL_BITS of the rasterizer, or ZSHIFT_SUBPIXEL_UNSNAPPED (-1). Used only when
    /// `profile` is NULL (a profile carries its own, measured snapping).
    pub subpixel_bits: i32,
    /// The decal pass's depth test: ZSHIFT_DEPTH_TEST_LESS or ZSHIFT_DEPTH_TEST_LEQUAL, under
    /// reversed Z ZSHIFT_DEPTH_TEST_GREATER or ZSHIFT_DEPTH_TEST_GEQUAL. Value 0 (a zeroed
    /// struct): the convention's strict test (GL_LESS, GL_GREATER under reversed Z). The `...EQUAL` tests need one quantum less offset and
    /// report a bleed gap one quantum wider (a tie passes).
    pub depth_func: ZshiftDepthTest,
    /// 0: every vertex of the base lies inside the view frustum, so the rasterizer clips
    /// nothing (a base cut by `zshift_clip_to_frustum`, or one that fits the screen). > 0: the
    /// base may cross the near plane or the screen's edges and is clipped by the rasterizer in
    /// float; the value is the largest |x|, |y| or |z| of its eye-space vertices, and the
    /// offset gains the clipping term C (README, "Verified on a rasterizer": it is large; cut
    /// the base instead where you can).
    pub base_reach: f64,
    /// The rasterizer's profile, from `zshift_probe` (call it once per context and pass the
    /// same record to every recommendation), or NULL: the worst case
    /// (`zshift_profile_worst_case`) with this scene's `subpixel_bits`. When not NULL the
    /// profile supplies every rasterizer fact, its snapping included, and `subpixel_bits` is
    /// ignored; it is validated as `ZshiftProfile` documents (a zero-filled one is refused).
    /// A zeroed ZshiftScene has NULL here.
    pub profile: *const super::probe::ZshiftProfile,
    /// The decal's eye-space corners, 3 floats each (x0, y0, z0, x1, y1, z1, ...: the
    /// positions its vertices have after the model-view transform), or NULL. With corners the
    /// recommendation knows the decal's exact depth plane and where it lies on the screen,
    /// which makes it far tighter on sloped planes, and answers planes that contain the view
    /// direction (ground under a level camera, whose slope is infinite); the corners then
    /// define the decal, and decal_near, decal_far and slope must be 0 (they are derived).
    /// NULL (a zeroed struct): decal_near, decal_far and slope describe the decal.
    pub decal_corners: *const f32,
    /// How many corners `decal_corners` holds (3 to 64; 0 with NULL).
    pub decal_corner_count: u32,
    /// How the engine draws besides the projection: the viewport's origin, glDepthRange,
    /// world-space vertices (a zeroed ZshiftPipeline: the viewport at the framebuffer's origin,
    /// glDepthRange(0, 1), eye-space vertices).
    pub pipeline: ZshiftPipeline,
}

/// The offset `zshift_recommend` computes, in every form an engine may apply it, with the
/// error terms it was built from (window-depth units; see the README, "Verified on a
/// rasterizer").
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftRecommendation {
    /// epsilon for element 10 (negative: toward the camera); use with the matrix from
    /// `zshift_recommend_matrix`.
    pub epsilon: f64,
    /// The NDC depth offset -epsilon * m10 (= 2 * window_offset).
    pub ndc_offset: f64,
    /// The window-depth offset: quantum + 2 * (plane + snap) + clip under GL_LESS/GL_GREATER,
    /// 2 * (plane + snap) + clip under GL_LEQUAL/GL_GEQUAL; for a facing plane with exact_depth,
    /// 0 under GL_LEQUAL/GL_GEQUAL and, with a probed profile under GL_LESS, the profile's
    /// facing_quanta ([-1, 1]) or facing_quanta_zero_to_one ([0, 1]) times the quantum (D32F:
    /// 2^-24).
    pub window_offset: f64,
    /// The eye-space shift toward the camera at pz = -decal_far giving the same epsilon
    /// (eq. 4.1.7), for `zshift_load_offset_matrix(l, r, b, t, n, f, delta_at_far, -decal_far, m)`.
    pub delta_at_far: f64,
    /// Occluders whose eye depth (-z) at the same pixel is smaller than the base's by at least
    /// this are never overdrawn by the decal.
    pub bleed_gap: f64,
    /// The slope factor of the equivalent glPolygonOffset(-factor, -units): 2^(1 - subpixel bits),
    /// 0 when unsnapped.
    pub polygon_offset_factor: f64,
    /// The constant units of the equivalent glPolygonOffset(-factor, -units): the constant part
    /// of the offset over r quanta, r the profile's `resolvable` for the format (1 without a
    /// profile: the smallest r known, so the units suffice on every implementation). bleed_gap
    /// is the matrix offset's: where r is larger (2 on NVIDIA and llvmpipe's UNORM, up to 4
    /// known), these units move depth up to 4 times as far; probe the context to know r.
    pub polygon_offset_units: f64,
    /// Term q: the smallest difference the stored format keeps (window depth).
    pub quantum: f64,
    /// Term T: f32 rounding of the vertex transform and viewport mapping, per vertex.
    pub transform: f64,
    /// Term V: f32 rounding of the decal's eye-space coordinates.
    pub vertex: f64,
    /// Term I: f32 rounding of the rasterizer's depth-plane evaluation.
    pub interpolation: f64,
    /// Term S: sub-pixel snapping of a sloped plane before depth setup.
    pub snap: f64,
    /// Term E: the per-quad plane error the offset used: transform + vertex + interpolation.
    pub plane: f64,
    /// Term C: the rasterizer's float clipping of a base that reaches outside the frustum
    /// (0 when base_reach is 0), and of the decal where its corners do (a decal partly off
    /// screen, known from decal_corners).
    pub clip: f64,
}

impl ZshiftRecommendation {
    /// The C record of a recommendation: its offsets, then the error terms it was built from.
    pub(super) fn new(
        epsilon: f64,
        ndc_offset: f64,
        window_offset: f64,
        delta_at_far: f64,
        bleed_gap: f64,
        polygon_offset: [f64; 2],
        terms: &crate::recommend::ErrorTerms,
    ) -> Self {
        Self {
            epsilon,
            ndc_offset,
            window_offset,
            delta_at_far,
            bleed_gap,
            polygon_offset_factor: polygon_offset[0],
            polygon_offset_units: polygon_offset[1],
            quantum: terms.quantum,
            transform: terms.transform,
            vertex: terms.vertex,
            interpolation: terms.interpolation,
            snap: terms.snap,
            plane: terms.plane,
            clip: terms.clip + terms.decal_clip,
        }
    }
}

/// Reads a scene the caller passed by pointer (not NULL: the entry point has refused NULL; no
/// alignment needed). Called inside the entry point's checked closure, so the record is built
/// where it is used: read outside and moved in, its ~240 bytes were block-copied, stalling on
/// the field stores that had just written them.
fn read_scene(scene: *const ZshiftScene) -> ZshiftScene {
    debug_assert!(!scene.is_null());
    // SAFETY: not NULL (checked by the entry point); the caller promises a readable ZshiftScene.
    unsafe { super::read_record(scene, ZshiftScene::read_fields) }
}

/// Reads a pipeline record the caller passed by pointer (not NULL: the entry point has refused
/// NULL; no alignment needed), field by field as [`read_scene`] reads its scene.
fn read_pipeline(pipeline: *const ZshiftPipeline) -> ZshiftPipeline {
    debug_assert!(!pipeline.is_null());
    // SAFETY: not NULL (checked by the entry point); the caller promises a readable
    // ZshiftPipeline.
    unsafe { super::read_record(pipeline, ZshiftPipeline::read_fields) }
}

impl ZshiftScene {
    /// Reads an aligned record field by field, for [`super::read_record`].
    ///
    /// # Safety
    /// `p` is not NULL, aligned, and points to a readable ZshiftScene.
    unsafe fn read_fields(p: *const Self) -> Self {
        use std::ptr::{addr_of, read_volatile as read};
        // SAFETY: as the function's contract; every field is plain data.
        unsafe {
            Self {
                l: read(addr_of!((*p).l)),
                r: read(addr_of!((*p).r)),
                b: read(addr_of!((*p).b)),
                t: read(addr_of!((*p).t)),
                n: read(addr_of!((*p).n)),
                f: read(addr_of!((*p).f)),
                viewport_width: read(addr_of!((*p).viewport_width)),
                viewport_height: read(addr_of!((*p).viewport_height)),
                depth_format: read(addr_of!((*p).depth_format)),
                decal_near: read(addr_of!((*p).decal_near)),
                decal_far: read(addr_of!((*p).decal_far)),
                slope: read(addr_of!((*p).slope)),
                exact_depth: read(addr_of!((*p).exact_depth)),
                subpixel_bits: read(addr_of!((*p).subpixel_bits)),
                depth_func: read(addr_of!((*p).depth_func)),
                base_reach: read(addr_of!((*p).base_reach)),
                profile: read(addr_of!((*p).profile)),
                decal_corners: read(addr_of!((*p).decal_corners)),
                decal_corner_count: read(addr_of!((*p).decal_corner_count)),
                pipeline: ZshiftPipeline::read_fields(addr_of!((*p).pipeline)),
            }
        }
    }
}

/// The most corners a decal may have: a decal is a quad, a few more for a clipped one.
const MAX_DECAL_CORNERS: u32 = 64;

/// Reads `count` eye-space corners (3 floats each) from `corners` and computes the decal's
/// shape with `shape`; `Ok(None)` for NULL with count 0. With corners, `fields`
/// (decal_near, decal_far, slope) must be 0: the corners define the decal.
#[inline(always)]
pub(super) fn decal_shape_from_c(
    corners: *const f32,
    count: u32,
    fields: [f64; 3],
    shape: impl FnOnce(&[glam::Vec3]) -> Result<crate::footprint::DecalShape>,
) -> Result<Option<crate::footprint::DecalShape>> {
    // No corners, the usual case, decided where it is used (returned from a call, the large
    // `Result` would be copied out of memory for nothing).
    if corners.is_null() && count == 0 {
        return Ok(None);
    }
    corner_shape(corners, count, fields, shape).map(Some)
}

/// [`decal_shape_from_c`] with corners (or a NULL pointer with a nonzero count: refused).
fn corner_shape(
    corners: *const f32,
    count: u32,
    fields: [f64; 3],
    shape: impl FnOnce(&[glam::Vec3]) -> Result<crate::footprint::DecalShape>,
) -> Result<crate::footprint::DecalShape> {
    use crate::domain::domain;
    if corners.is_null() {
        return Err(
            domain("decal_corner_count must be 0 when decal_corners is NULL")
                .with_integer("decal_corner_count", i64::from(count)),
        );
    }
    if !(3..=MAX_DECAL_CORNERS).contains(&count) {
        return Err(
            domain("decal_corner_count must lie in 3..=64 when decal_corners is given")
                .with_integer("decal_corner_count", i64::from(count)),
        );
    }
    for (name, x) in ["decal_near", "decal_far", "slope"].into_iter().zip(fields) {
        if x != 0.0 {
            return Err(domain(
                "with decal_corners, decal_near, decal_far and slope must be 0: the corners define the decal",
            )
            .with_value(name, x));
        }
    }
    // SAFETY: not NULL; the caller promises `count` corners of 3 floats each, readable; f32 has
    // no invalid bit patterns, and read_unaligned needs no alignment.
    let corners: Vec<glam::Vec3> = (0..count as usize)
        .map(|i| {
            let at = |k: usize| unsafe { corners.add(3 * i + k).read_unaligned() };
            glam::Vec3::new(at(0), at(1), at(2))
        })
        .collect();
    shape(&corners)
}

/// Converts the caller's scene to the Rust model's (every field checked) and hands it to
/// `then` by reference. The model stays where it was built: returned through a `Result`, its
/// 280 bytes would be copied once more, with a block copy reading across the narrower stores
/// that just wrote it (a store-forwarding stall that cost a tenth of the call).
fn with_model<R>(
    s: &ZshiftScene,
    clip: ClipDepth,
    then: impl FnOnce(&crate::recommend::Scene) -> Result<R>,
) -> Result<R> {
    use crate::recommend::{Base, DepthTest, Scene, Snapping};
    let format = format_named(s.depth_format, "depth_format")?;
    let snapping = match s.subpixel_bits {
        ZSHIFT_SUBPIXEL_UNSNAPPED => Snapping::Unsnapped,
        b if b >= 0 => Snapping::SubpixelBits(b as u32),
        _ => {
            return Err(crate::domain::domain(
                "subpixel_bits must be >= 0 or ZSHIFT_SUBPIXEL_UNSNAPPED",
            ))
        }
    };
    let depth_test = match s.depth_func.value {
        0 if clip == ClipDepth::ReversedZeroToOne => DepthTest::Greater,
        0 => DepthTest::Less,
        func => DepthTest::from_gl(func).map_err(|e| e.with_code("depth_func", func))?,
    };
    let base = if s.base_reach == 0.0 {
        Base::InsideFrustum
    } else {
        Base::Clipped {
            reach: s.base_reach,
        }
    };
    // The worst case built in place (no `Result` to move it through).
    let profile = if s.profile.is_null() {
        crate::recommend::RasterizerProfile {
            snapping,
            ..crate::recommend::RasterizerProfile::worst_case()
        }
    } else {
        super::probe::profile_or_worst(s.profile, snapping)?
    };
    let frustum = Frustum::new(s.l, s.r, s.b, s.t, s.n, s.f)?;
    let viewport = [s.viewport_width, s.viewport_height];
    let fields = [s.decal_near, s.decal_far, s.slope];
    let shape = decal_shape_from_c(s.decal_corners, s.decal_corner_count, fields, |c| {
        crate::footprint::decal_shape(&frustum, clip, viewport, c)
    })?;
    then(&Scene {
        footprint: shape.map(|d| d.footprint),
        frustum,
        viewport,
        format,
        depth_range: shape.map_or([s.decal_near, s.decal_far], |d| d.depth_range),
        slope: shape.map_or(s.slope, |d| d.slope),
        exact_depth: s.exact_depth != 0,
        depth_test,
        base,
        profile,
        pipeline: pipeline_from_c(&s.pipeline)?,
    })
}

/// The model's [`crate::model::Pipeline`] from the C record: a depth range of `[0, 0]` (a
/// zeroed record) is `glDepthRange(0, 1)`; a NULL view matrix is none (its box ignored), a view
/// matrix with an all-zero box is refused; the model checks every field
/// ([`crate::model::Pipeline::check`]).
#[inline(always)] // built in the caller's record: returned through a `Result`, ~160 bytes are copied
pub(super) fn pipeline_from_c(p: &ZshiftPipeline) -> Result<crate::model::Pipeline> {
    let (view_matrix, world_box) = (p.view_matrix, p.world_box);
    let depth_range = [p.depth_range_near, p.depth_range_far];
    let view = if view_matrix.is_null() {
        None
    } else {
        if world_box == [0.0; 6] {
            return Err(crate::domain::domain(
                "world_box must be given with view_matrix: the box of every base and decal position the shader receives",
            ));
        }
        // SAFETY: not NULL; the caller promises 16 readable floats; no alignment needed.
        Some(std::array::from_fn(|i| unsafe {
            view_matrix.add(i).read_unaligned()
        }))
    };
    let pipeline = crate::model::Pipeline {
        world_reach: p.world_reach,
        eye_first: p.eye_first != 0,
        view,
        world_box: view.map(|_| {
            [
                [world_box[0], world_box[1], world_box[2]],
                [world_box[3], world_box[4], world_box[5]],
            ]
        }),
        viewport_origin: [p.viewport_x, p.viewport_y],
        depth_range: if depth_range == [0.0, 0.0] {
            [0.0, 1.0]
        } else {
            depth_range
        },
    };
    pipeline.check()?;
    Ok(pipeline)
}

/// Writes the smallest depth offset that ends z-fighting between a decal and its coplanar
/// base on a real rasterizer, by an error model whose every term is a worst-case bound: the
/// depth quantum, f32 rounding of the vertex transform, of the vertex coordinates and of the
/// depth interpolation, and sub-pixel snapping of sloped planes (seed 004); seed 000's eq.
/// 4.1.3/4.1.7 with seed 002's quantum. Also the bleed-through gap and the glPolygonOffset
/// equivalent. Verified on Mesa llvmpipe with D16, D24 and D32F (tests/gl_recommend.rs).
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `scene` or `out` is NULL; ZSHIFT_ERR_NOT_FINITE for NaN
/// or infinite inputs (except f = +INFINITY); ZSHIFT_ERR_DOMAIN for a bad frustum, a zero
/// viewport, an unknown depth_format, decal_near/decal_far outside [n, f] or decreasing, a
/// negative slope, exact_depth with a nonzero slope, subpixel_bits < -1 or > 32, a negative
/// base_reach, a `pipeline` field out of range (glDepthRange not 0 <= near < far <= 1, a
/// negative world_reach, a view_matrix without its world_box), or a `profile` that fails its
/// checks (a zero-filled ZshiftProfile: start from `zshift_probe` or
/// `zshift_profile_worst_case`); ZSHIFT_ERR_UNRESOLVABLE when the offset the scene needs would
/// push the decal past the near plane (the detail says why and what to do: cut the base, probe
/// the context, pass the view matrix); ZSHIFT_ERR_OVERFLOW if a result overflows. `*out` is
/// untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend(
    scene: *const ZshiftScene,
    out: *mut ZshiftRecommendation,
) -> ZshiftStatus {
    if scene.is_null() {
        return null_pointer("scene");
    }
    checked_record(out, move || {
        let s = read_scene(scene);
        let r = with_model(&s, ClipDepth::NegOneToOne, crate::recommend::recommend)?;
        Ok(ZshiftRecommendation::new(
            r.epsilon,
            r.ndc_offset,
            r.window_offset,
            r.delta_at_far,
            r.bleed_gap,
            r.polygon_offset,
            &r.terms,
        ))
    })
}

/// Writes the decal's projection matrix for the recommended offset: the `glFrustum` matrix of
/// `scene` with element 10 scaled by 1 + epsilon of `zshift_recommend`, rounded away from the
/// plain element (the offset is never lost to float rounding). Column-major, 16 floats, for
/// glLoadMatrixf or glUniformMatrix4fv(.., GL_FALSE, ..).
///
/// Errors: as `zshift_recommend`; ZSHIFT_ERR_OVERFLOW if element 10 leaves float. `out` is
/// untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend_matrix(
    scene: *const ZshiftScene,
    out: *mut f32,
) -> ZshiftStatus {
    if scene.is_null() {
        return null_pointer("scene");
    }
    checked_in_place(out, move |out| {
        let s = read_scene(scene);
        with_model(&s, ClipDepth::NegOneToOne, |model| {
            let r = crate::recommend::recommend(model)?;
            let m = match crate::offset::epsilon_columns_fast(&model.frustum, r.epsilon) {
                Some(m) => m,
                None => {
                    let m = crate::offset::epsilon_matrix(&model.frustum, r.epsilon)?;
                    glam::Mat4::from_cols_array(&m)
                }
            };
            write_matrix(out, m);
            Ok(())
        })
    })
}

/// Writes the smallest depth offset that ends z-fighting between a decal and its coplanar
/// base when both are drawn under clip convention `clip` (a ZSHIFT_CLIP_*): the model of
/// `zshift_recommend` with each term taken through that convention's depth mapping (README,
/// "Verified on a rasterizer"). Verified on Mesa llvmpipe (tests/gl_recommend_clip.rs).
///
/// - ZSHIFT_CLIP_NEG_ONE_TO_ONE: exactly `zshift_recommend`.
/// - ZSHIFT_CLIP_ZERO_TO_ONE (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), GL_LESS): a
///   constant NDC offset through element 10; `epsilon` is Lengyel's element-10 epsilon
///   (m10 * (1 + epsilon), negative), `ndc_offset` = `window_offset` its magnitude.
/// - ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE (same glClipControl, GL_GREATER, glClearDepth(0)): a
///   relative offset through element 14 (m14 * (1 + epsilon), every point moved from d to
///   d / (1 + epsilon); it works where m10 = 0, f = +INFINITY); `epsilon` is that relative
///   epsilon (positive); `ndc_offset` and `window_offset` are the offset at decal_far, the
///   smallest over the decal; `polygon_offset_factor` and `polygon_offset_units` are 0 (no
///   constant glPolygonOffset matches a relative offset).
///
/// In every case `delta_at_far` is the eye-space shift toward the camera the offset amounts to
/// at decal_far, `bleed_gap` the documented bleed-through gap, and `quantum` the format's
/// spacing at the decal's farthest point. `zshift_recommend_clip_matrix` gives the matrix.
///
/// Errors: as `zshift_recommend`; ZSHIFT_ERR_DOMAIN for an unknown `clip`; ZSHIFT_ERR_OVERFLOW
/// if a result or matrix element overflows. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend_clip(
    scene: *const ZshiftScene,
    clip: ZshiftClip,
    out: *mut ZshiftRecommendation,
) -> ZshiftStatus {
    if scene.is_null() {
        return null_pointer("scene");
    }
    checked_record(out, move || {
        let s = read_scene(scene);
        let c = clip_of(clip)?;
        let r = with_model(&s, c, |model| crate::recommend::recommend_clip(model, c))?;
        let per_ndc = if clip == ZSHIFT_CLIP_NEG_ONE_TO_ONE {
            0.5
        } else {
            1.0
        };
        Ok(ZshiftRecommendation::new(
            r.epsilon,
            r.window_offset / per_ndc,
            r.window_offset,
            r.delta_at_far,
            r.bleed_gap,
            r.polygon_offset,
            &r.terms,
        ))
    })
}

/// Writes the decal's projection matrix for `zshift_recommend_clip`'s offset under `clip` (a
/// ZSHIFT_CLIP_*): `zshift_projection`'s matrix of the scene's frustum with element 10 lowered
/// by the NDC offset (NEG_ONE_TO_ONE, ZERO_TO_ONE) or element 14 scaled by 1 + epsilon
/// (REVERSED_ZERO_TO_ONE), rounded away from the plain element so the offset is never lost to
/// float rounding. Column-major, 16 floats; draw the base with the plain matrix of the same
/// convention.
///
/// Errors: as `zshift_recommend_clip`. `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_recommend_clip_matrix(
    scene: *const ZshiftScene,
    clip: ZshiftClip,
    out: *mut f32,
) -> ZshiftStatus {
    if scene.is_null() {
        return null_pointer("scene");
    }
    checked_array(out, move || {
        let s = read_scene(scene);
        let c = clip_of(clip)?;
        with_model(&s, c, |model| {
            Ok(crate::recommend::recommend_clip(model, c)?.matrix)
        })
    })
}

/// Cuts a convex base polygon to the view frustum of `glFrustum(l, r, b, t, n, f)` in double,
/// slightly inside (near plane at n * (1 + 2^-16), sides inward by 2^-16 of the frustum's
/// width: less than a quarter pixel up to 16384 pixels; far at f * (1 - 2^-16), or where window
/// depth is 2^-20 below 1 if nearer: f*n/(n + 2^-20*(f - n)), 1 % nearer than f at f/n = 1e4,
/// 9 % at 1e5, half the range at 1e6, since f32 resolves window depth near 1 only to 2^-24;
/// under reversed Z the far plane is at window depth 0 and needs no such margin, but the cut
/// does not know the convention: there, prefer an infinite far plane), so that the
/// rasterizer clips nothing of it: draw the result as a triangle fan and pass base_reach = 0.
/// A base the rasterizer clips in float (a ground plane running behind the camera) carries the
/// large term C; cut this way it carries none. `polygon` holds `count` eye-space vertices
/// (x, y, z, in order around the polygon); `out` receives up to `capacity` vertices (count + 6
/// always suffices) and `*out_count` how many were written (0 when nothing is inside). The
/// margin is for a result drawn in eye space (or camera-relative); one stored in world space
/// far from the origin: zshift_clip_to_frustum_stored.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `polygon` (with count > 0), `out` or `out_count` is NULL;
/// ZSHIFT_ERR_NOT_FINITE for a NaN or infinite coordinate or frustum parameter (except
/// f = +INFINITY); ZSHIFT_ERR_DOMAIN for a bad frustum, count > 65536, or a result with more
/// than `capacity` vertices. `out` and `*out_count` are untouched on error.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn zshift_clip_to_frustum(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    polygon: *const f64,
    count: u32,
    out: *mut f64,
    capacity: u32,
    out_count: *mut u32,
) -> ZshiftStatus {
    let frustum = [l, r, b, t, n, f];
    cut_entry(frustum, None, (polygon, count), (out, capacity, out_count))
}

/// zshift_clip_to_frustum for a polygon the engine stores as `pipeline` says, in world space
/// through a float view matrix (its world_reach, eye_first, and view_matrix with world_box, as
/// the decal's ZshiftScene.pipeline; the viewport and depth range are not used): every plane
/// is moved inward further by the largest error that storage and the float transform can give
/// a cut vertex (6u or 14u times the world coordinates' magnitudes, u = 2^-24), so that the
/// rasterizer still clips nothing of it. That error is absolute, not relative to the vertex's
/// distance from the camera: cut by zshift_clip_to_frustum, a vertex close to the camera can
/// land outside once stored in world space far from the origin, and a rasterizer that clips
/// at the sides (Mesa's llvmpipe) then cuts a sliver off its triangle, with a pixel off the
/// plane by up to half a pixel of its depth gradient (docs/rasterizer.md, "Slivers"). The
/// price: near the camera the cut lies visibly inside the screen's edges; camera-relative
/// rendering needs none of it (use zshift_clip_to_frustum). Draw the result as a fan and pass
/// base_reach = 0.
///
/// Errors: as zshift_clip_to_frustum; ZSHIFT_ERR_NULL_POINTER also if `pipeline` is NULL
/// (eye-space vertices: zshift_clip_to_frustum); ZSHIFT_ERR_DOMAIN also for a `pipeline` field
/// out of range (a negative world_reach, a view_matrix without its world_box).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn zshift_clip_to_frustum_stored(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    pipeline: *const ZshiftPipeline,
    polygon: *const f64,
    count: u32,
    out: *mut f64,
    capacity: u32,
    out_count: *mut u32,
) -> ZshiftStatus {
    if pipeline.is_null() {
        return null_pointer("pipeline");
    }
    let stored = read_pipeline(pipeline);
    let frustum = [l, r, b, t, n, f];
    cut_entry(
        frustum,
        Some(stored),
        (polygon, count),
        (out, capacity, out_count),
    )
}

/// The checked body of both cuts: `stored` the pipeline the cut polygon is stored through
/// (`None`: eye space).
fn cut_entry(
    [l, r, b, t, n, f]: [f64; 6],
    stored: Option<ZshiftPipeline>,
    (polygon, count): (*const f64, u32),
    (out, capacity, out_count): (*mut f64, u32, *mut u32),
) -> ZshiftStatus {
    if polygon.is_null() && count > 0 {
        return null_pointer("polygon");
    }
    if out.is_null() {
        return null_pointer("out");
    }
    if count > 65_536 {
        super::last_error::set("count must be at most 65536 vertices");
        return ZSHIFT_ERR_DOMAIN;
    }
    let input = polygon_from_c(polygon, count as usize);
    checked(
        out_count,
        move || {
            let frustum = Frustum::new(l, r, b, t, n, f)?;
            let cut = match stored {
                None => crate::recommend::clip_to_frustum(&frustum, &input)?,
                Some(p) => {
                    let pipeline = pipeline_from_c(&p)?;
                    crate::recommend::clip_to_frustum_stored(&frustum, &input, &pipeline)?
                }
            };
            if cut.len() > capacity as usize {
                return Err(crate::domain::domain(
                    "the cut polygon has more vertices than capacity (count + 6 always suffices)",
                ));
            }
            Ok(cut)
        },
        |out_count, cut| store_vertices(out, out_count, &cut),
    )
}

/// Reads `count` vertices of three doubles (`count > 0` needs a non-NULL `polygon`, checked by
/// the caller; no alignment needed).
fn polygon_from_c(polygon: *const f64, count: usize) -> Vec<[f64; 3]> {
    (0..count)
        .map(|i| {
            // SAFETY: the caller promises `count` readable vertices; read_unaligned needs no
            // alignment.
            [0, 1, 2].map(|k| unsafe { polygon.add(3 * i + k).read_unaligned() })
        })
        .collect()
}

/// Writes the cut polygon and its vertex count (both pointers checked non-NULL by the caller,
/// `cut.len()` within the caller's capacity).
fn store_vertices(out: *mut f64, out_count: *mut u32, cut: &[[f64; 3]]) {
    for (i, v) in cut.iter().enumerate() {
        for (k, c) in v.iter().enumerate() {
            // SAFETY: the caller promises `capacity` writable vertices, and cut.len() <= capacity.
            unsafe { out.add(3 * i + k).write_unaligned(*c) };
        }
    }
    // SAFETY: `checked` has refused NULL.
    unsafe { out_count.write_unaligned(cut.len() as u32) };
}

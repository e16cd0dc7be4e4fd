//! Edges drawn over their own faces (src/lines/): wireframe on shaded, outlines, hidden-line
//! drawing. Two ways: the faces pushed back with polygon offset, or the edges pulled forward
//! through the projection matrix (the one offset that reaches GL_LINES).

use super::{
    checked_array, checked_record, clip_of, format_named, null_pointer, ZshiftClip,
    ZshiftDepthTest, ZshiftFormat, ZshiftStatus, ZSHIFT_SUBPIXEL_UNSNAPPED,
};
use crate::domain::{domain, finite};
use crate::error::Result;
use crate::lines::{EdgeMethod, EdgeRecommendation, Edges, FaceSlope, LineKind};
use crate::projection::ClipDepth;
use crate::recommend::{DepthTest, Snapping};

/// Faces pushed back with glPolygonOffset (D3D DepthBias/SlopeScaledDepthBias, Vulkan
/// depthBiasConstantFactor/SlopeFactor), edges drawn unoffset.
pub const ZSHIFT_EDGES_POLYGON_OFFSET: u32 = 0;
/// Edges pulled forward through the projection matrix (element 10, or 14 under reversed Z),
/// faces unoffset: the one offset that moves GL_LINES.
pub const ZSHIFT_EDGES_MATRIX: u32 = 1;

/// What an engine knows about a mesh whose edges it draws over its faces, for
/// `zshift_edge_offset` and `zshift_edge_planes`. Fill every field: an all-zero record is
/// refused (viewport 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftEdges {
    /// `glViewport` width in pixels (nonzero).
    pub viewport_width: u32,
    /// `glViewport` height in pixels (nonzero).
    pub viewport_height: u32,
    /// The depth attachment's format (ZSHIFT_FORMAT_*).
    pub format: ZshiftFormat,
    /// GL_SUBPIXEL_BITS of the worst-case profile used when `profile` is NULL (0..=32), or
    /// ZSHIFT_SUBPIXEL_UNSNAPPED (-1) for a rasterizer that sets depth up unsnapped (llvmpipe).
    pub subpixel_bits: i32,
    /// The mesh's nearest eye depth (-z), inside the matrix's [n, f].
    pub depth_near: f64,
    /// The mesh's farthest eye depth (-z), >= depth_near.
    pub depth_far: f64,
    /// glLineWidth in pixels, 1 to 64. A width between integers is taken as GL may draw it,
    /// rounded to the nearest integer (halves up) where that is wider: 2.5 as 3.
    pub line_width: f64,
    /// 0: GL_LINES; 1: the faces drawn again in glPolygonMode(GL_LINE).
    pub polygon_mode: u32,
    /// MSAA samples per pixel (1 without multisampling), 1..=64. Above 1 the line reach is
    /// sqrt(2)*(w + 1)/2 (a sample lies up to w/2 off the line in any direction), or with a
    /// probed profile its line_reach_msaa plus 1/16 plus sqrt(2)*(w - 1)/2 where smaller.
    pub samples: u32,
    /// The steepest face whose edges must be kept, as the largest angle between a face's normal
    /// and the view axis, radians in (0, pi/2); 0 to give `face_gradient` instead. It is turned
    /// into a window gradient at the mesh's nearest depth (ZshiftEdgeOffset.face_gradient, with a
    /// first-order tilt for off-axis rays): faces whose window gradient has a length
    /// sqrt(dz/dx^2 + dz/dy^2) up to it are guaranteed (single-sampled, those with max(|dz/dx|,
    /// |dz/dy|) up to it too); a face within the angle that grazes an off-axis ray can be
    /// steeper.
    pub face_angle: f64,
    /// With face_angle = 0: the largest window-depth gradient per pixel, max(|dz/dx|, |dz/dy|)
    /// (what glPolygonOffset's factor multiplies), >= 0: `zshift_steepest_face` computes the
    /// mesh's own from its triangles (its steepest face within the gradient an angle gives),
    /// which for a mesh with no face at the angle costs less.
    pub face_gradient: f64,
    /// The eye depth behind a front face from which hidden edges must not show; 0 for no
    /// promise. Where the hidden-line gap exceeds it the call fails with
    /// ZSHIFT_ERR_UNRESOLVABLE (`zshift_edge_planes` then gives planes that would work).
    pub hidden_separation: f64,
    /// The edge pass's depth test: ZSHIFT_DEPTH_TEST_LEQUAL or _LESS, under reversed Z _GEQUAL
    /// or _GREATER; 0: GL_LEQUAL (GL_GEQUAL reversed), the usual edge pass.
    pub depth_func: ZshiftDepthTest,
    /// The rasterizer's profile from `zshift_probe`, or NULL for the worst case with
    /// `subpixel_bits`.
    pub profile: *const super::probe::ZshiftProfile,
    /// How the engine draws the mesh besides its matrix, as the decal's ZshiftScene.pipeline:
    /// vertices in world space through a float view matrix (`world_reach`, or `view_matrix`
    /// with `world_box`, the box of the mesh's world positions, and `eye_first`), the
    /// viewport's origin in a larger framebuffer, glDepthRange. Zero-filled: eye-space
    /// vertices, the viewport at the framebuffer's origin, glDepthRange(0, 1).
    pub pipeline: super::recommend::ZshiftPipeline,
}

/// The offset for a mesh's edges by one method, in every form an engine applies it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftEdgeOffset {
    /// ZSHIFT_EDGES_MATRIX: the edges' projection, the engine's own with the offset applied to
    /// element 10 (14 reversed), rounded outward; ZSHIFT_EDGES_POLYGON_OFFSET: `m` unchanged.
    pub matrix: [f32; 16],
    /// glPolygonOffset(factor, units) for the faces (magnitudes: positive pushes away under
    /// [-1, 1] and [0, 1]; negate both under reversed Z); 0 for the matrix method.
    pub polygon_offset: [f64; 2],
    /// Direct3D DepthBias (integer, rounded up) and SlopeScaledDepthBias; 0 for the matrix method.
    pub d3d_bias: [f64; 2],
    /// Vulkan depthBiasConstantFactor and depthBiasSlopeFactor; 0 for the matrix method.
    pub vulkan_bias: [f64; 2],
    /// The NDC offset applied to element 10 (negative: toward the camera); 0 for the polygon
    /// offset method and where reversed Z scales element 14 instead.
    pub ndc_offset: f64,
    /// Under reversed Z, where element 14 is scaled instead of element 10 moved (whichever
    /// offsets less at the mesh's nearest depth): its relative epsilon; 0 otherwise.
    pub relative_epsilon: f64,
    /// The largest window-depth offset between edge and face the method applies.
    pub window_offset: f64,
    /// The line term g*line_reach, window depth; polygon-mode lines add the neighbouring
    /// triangle's slope term where its outline may take its own plane beyond the shared side
    /// (the worst case: 2*g*line_reach; none where the profile's outline_neighbour is f32 noise).
    /// Under MSAA with face_angle set, each part is at most g*(w + 1)/2: the angle bounds the
    /// face's whole gradient, and a sample lies within (w + 1)/2 of its line; from
    /// `zshift_edge_offset_for_mesh`, at most the mesh's gradient length times (w + 1)/2.
    pub line_term: f64,
    /// How far (pixels, times max(|dz/dx|, |dz/dy|)) from the pixel or sample a line fragment's
    /// depth is taken: (w + 1)/2 in the worst case (plus 1/8 for polygon-mode lines wider than
    /// 1), the probed reach plus 1/16 (plus (w - 1)/2 for GL_LINES) with a profile (wider
    /// polygon-mode lines: line_reach_wide plus 1/16, plus (w - 3)/2 beyond width 3);
    /// sqrt(2)*(w + 1)/2 under MSAA, or the profile's line_reach_msaa plus 1/16 plus
    /// sqrt(2)*(w - 1)/2 where smaller.
    pub line_reach: f64,
    /// g: the window-depth gradient per pixel of the steepest face that matters (its larger
    /// component given face_gradient, its length given face_angle; from
    /// `zshift_edge_offset_for_mesh`, the mesh's steepest face's larger component).
    pub face_gradient: f64,
    /// Hidden edges behind a front face by at least this eye depth never show.
    pub hidden_gap: f64,
}

fn edges_of(e: &ZshiftEdges) -> Result<Edges> {
    if e.viewport_width == 0 || e.viewport_height == 0 {
        return Err(domain(
            "ZshiftEdges.viewport_width and viewport_height must be nonzero (an all-zero ZshiftEdges is refused)",
        )
        .with_integer(
            if e.viewport_width == 0 { "viewport_width" } else { "viewport_height" },
            0,
        ));
    }
    let snapping =
        match e.subpixel_bits {
            ZSHIFT_SUBPIXEL_UNSNAPPED => Snapping::Unsnapped,
            b @ 0..=32 => Snapping::SubpixelBits(b as u32),
            b => return Err(domain(
                "ZshiftEdges.subpixel_bits must lie in 0..=32 or be ZSHIFT_SUBPIXEL_UNSNAPPED (-1)",
            )
            .with_integer("subpixel_bits", i64::from(b))),
        };
    let kind = match e.polygon_mode {
        0 => LineKind::Lines,
        1 => LineKind::PolygonMode,
        k => {
            return Err(domain(
                "ZshiftEdges.polygon_mode must be 0 (GL_LINES) or 1 (polygon-mode lines)",
            )
            .with_integer("polygon_mode", i64::from(k)))
        }
    };
    for (name, x) in [
        ("face_angle", e.face_angle),
        ("face_gradient", e.face_gradient),
    ] {
        finite(x, "a ZshiftEdges face slope is NaN or infinite")
            .map_err(|err| err.with_value(name, x))?;
    }
    let face_slope = if e.face_angle != 0.0 {
        if e.face_gradient != 0.0 {
            return Err(domain(
                "give ZshiftEdges.face_angle or face_gradient, not both (the other 0)",
            )
            .with_value("face_gradient", e.face_gradient));
        }
        FaceSlope::Angle(e.face_angle)
    } else {
        FaceSlope::WindowGradient(e.face_gradient)
    };
    let profile = if e.profile.is_null() {
        crate::recommend::RasterizerProfile {
            snapping,
            ..crate::recommend::RasterizerProfile::worst_case()
        }
    } else {
        super::probe::profile_or_worst(e.profile, snapping)?
    };
    let depth_test = match e.depth_func.value {
        0 => None,
        func => Some(DepthTest::from_gl(func).map_err(|err| err.with_code("depth_func", func))?),
    };
    Ok(Edges {
        viewport: [e.viewport_width, e.viewport_height],
        format: format_named(e.format.value, "format")?,
        depth_test: depth_test.unwrap_or(DepthTest::LessEqual),
        line_width: e.line_width,
        kind,
        samples: e.samples,
        depth_range: [e.depth_near, e.depth_far],
        face_slope,
        hidden_separation: e.hidden_separation,
        profile,
        pipeline: super::recommend::pipeline_from_c(&e.pipeline)?,
    })
}

fn method_of(method: u32) -> Result<EdgeMethod> {
    match method {
        ZSHIFT_EDGES_POLYGON_OFFSET => Ok(EdgeMethod::PolygonOffset),
        ZSHIFT_EDGES_MATRIX => Ok(EdgeMethod::Matrix),
        k => Err(domain(
            "method must be ZSHIFT_EDGES_POLYGON_OFFSET (0) or ZSHIFT_EDGES_MATRIX (1)",
        )
        .with_integer("method", i64::from(k))),
    }
}

/// The model's input under `clip`: the default edge test follows the convention.
fn input(clip: ClipDepth, e: &ZshiftEdges) -> Result<Edges> {
    let mut edges = edges_of(e)?;
    if e.depth_func.value == 0 && clip == ClipDepth::ReversedZeroToOne {
        edges.depth_test = DepthTest::GreaterEqual;
    }
    Ok(edges)
}

fn read_inputs(
    m: *const f32,
    edges: *const ZshiftEdges,
) -> std::result::Result<([f32; 16], ZshiftEdges), ZshiftStatus> {
    if m.is_null() {
        return Err(null_pointer("m"));
    }
    if edges.is_null() {
        return Err(null_pointer("edges"));
    }
    // SAFETY: not NULL; the caller promises 16 readable floats and a readable ZshiftEdges;
    // read_unaligned copies them before anything is computed and needs no alignment.
    Ok(unsafe {
        (
            m.cast::<[f32; 16]>().read_unaligned(),
            edges.read_unaligned(),
        )
    })
}

impl From<EdgeRecommendation> for ZshiftEdgeOffset {
    fn from(r: EdgeRecommendation) -> Self {
        ZshiftEdgeOffset {
            matrix: r.matrix,
            polygon_offset: r.polygon_offset,
            d3d_bias: r.d3d_bias,
            vulkan_bias: r.vulkan_bias,
            ndc_offset: r.ndc_offset,
            relative_epsilon: r.relative_epsilon,
            window_offset: r.window_offset,
            line_term: r.line_term,
            line_reach: r.line_reach,
            face_gradient: r.face_gradient,
            hidden_gap: r.hidden_gap,
        }
    }
}

/// Writes the offset that keeps every edge of `edges`' mesh in front of its own faces (faces up
/// to the face-slope limit) by `method` (ZSHIFT_EDGES_POLYGON_OFFSET or ZSHIFT_EDGES_MATRIX),
/// with the hidden-line gap it costs; `m` is the engine's perspective projection (16 floats,
/// column-major) under `clip`. The model: a line fragment's depth is taken up to (w + 1)/2 pixels
/// from the pixel along the face's steeper axis (the line term), plus the decal model's terms for
/// face and edge (docs/edges.md).
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `m`, `edges` or `out` is NULL; ZSHIFT_ERR_NOT_FINITE;
/// ZSHIFT_ERR_DOMAIN for a bad field (zshift_last_error() names it: viewport_width,
/// line_width, samples, polygon_mode, face_angle, face_gradient, hidden_separation,
/// depth_near/depth_far, depth_func, method) or an orthographic `m`; ZSHIFT_ERR_UNRESOLVABLE
/// when the hidden-line gap exceeds hidden_separation (no offset keeps every visible edge and
/// hides every hidden one) or the offset would pull the nearest edge past the near plane;
/// ZSHIFT_ERR_OVERFLOW. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_edge_offset(
    m: *const f32,
    clip: ZshiftClip,
    edges: *const ZshiftEdges,
    method: u32,
    out: *mut ZshiftEdgeOffset,
) -> ZshiftStatus {
    let (m, e) = match read_inputs(m, edges) {
        Ok(x) => x,
        Err(status) => return status,
    };
    checked_record(out, move || {
        let clip = clip_of(clip)?;
        let r = crate::lines::recommend(&m, clip, &input(clip, &e)?, method_of(method)?)?;
        Ok(ZshiftEdgeOffset::from(r))
    })
}

/// Writes near and far planes (out[0], out[1]) with which `zshift_edge_offset` answers for
/// `edges` by `method`: the tight planes of the mesh's depth range (zshift_tight_planes), with a
/// near plane a little closer where the matrix offset needs room, and `m`'s side planes. For the
/// ZSHIFT_ERR_UNRESOLVABLE of `zshift_edge_offset`.
///
/// Errors: as `zshift_edge_offset`; ZSHIFT_ERR_UNRESOLVABLE when even these planes leave the
/// gap above hidden_separation (use a deeper depth format). `out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_edge_planes(
    m: *const f32,
    clip: ZshiftClip,
    edges: *const ZshiftEdges,
    method: u32,
    out: *mut f64,
) -> ZshiftStatus {
    let (m, e) = match read_inputs(m, edges) {
        Ok(x) => x,
        Err(status) => return status,
    };
    checked_array(out, move || {
        let clip = clip_of(clip)?;
        crate::lines::working_planes(&m, clip, &input(clip, &e)?, method_of(method)?)
    })
}

/// A mesh as the engine draws it, for `zshift_steepest_face` and `zshift_edge_offset_for_mesh`:
/// its vertex positions, its triangles and the matrix that takes the positions to clip space.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftMesh {
    /// The whole projection * view * model (16 floats, column-major), as the vertex shader
    /// applies it.
    pub clip_matrix: *const f32,
    /// The first vertex's x, y, z (floats); NULL only with vertex_count 0.
    pub positions: *const f32,
    /// How many vertices `positions` holds.
    pub vertex_count: usize,
    /// Bytes from one vertex's x to the next's (an interleaved buffer), a multiple of 4 of at
    /// least 12; 0 for tightly packed (12).
    pub position_stride: usize,
    /// Three indices per triangle (GL_TRIANGLES order) into the vertices; NULL only with
    /// index_count 0.
    pub indices: *const u32,
    /// How many indices `indices` holds, a multiple of 3.
    pub index_count: usize,
}

/// The steepest face of a mesh as drawn (`zshift_steepest_face`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftSteepestFace {
    /// max(|dz/dx|, |dz/dy|) of the steepest drawn face within the limit, window depth in
    /// [0, 1] per pixel; 0 when no face counts. What ZshiftEdges.face_gradient takes (with
    /// face_angle = 0), or let `zshift_edge_offset_for_mesh` use it with `length`.
    pub gradient: f64,
    /// The largest length sqrt(dz/dx^2 + dz/dy^2) of a face that counts (of any face, not
    /// necessarily the one of `gradient`); it bounds multisampled lines, whose samples take
    /// their depth up to (w + 1)/2 pixels away in any direction.
    pub length: f64,
    /// The face of `gradient`: its first index's position in `indices` divided by 3; -1 when
    /// no face counts.
    pub triangle: i64,
    /// Triangles that count (drawn, within the limit).
    pub counted: u64,
    /// Triangles drawn but steeper than the limit (grazing: their edges are not guaranteed).
    pub beyond_limit: u64,
    /// Triangles that draw nothing: all three vertices outside one clip plane, or no area on
    /// screen.
    pub culled: u64,
}

/// Writes the steepest face of `mesh` as it is drawn: the largest window-depth gradient
/// max(|dz/dx|, |dz/dy|) among its triangles under its clip matrix and `clip`, in a viewport of
/// `viewport_width` x `viewport_height` pixels, and the largest gradient length, leaving out
/// triangles that draw nothing and those steeper than `limit` (grazing; pass the
/// ZshiftEdgeOffset.face_gradient a face_angle gives to keep every face within that angle, or
/// INFINITY for all). `zshift_edge_offset_for_mesh` does this and the offset in one call; or
/// pass `out->gradient` as ZshiftEdges.face_gradient (face_angle = 0). Exact from the float
/// inputs up to double rounding; no GL call (src/steepest_face.rs).
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `mesh`, its clip_matrix, or `out` is NULL, or its
/// positions / indices with a nonzero count; ZSHIFT_ERR_NOT_FINITE for a NaN or infinite matrix
/// element or position (zshift_last_error() names which); ZSHIFT_ERR_DOMAIN for a zero
/// viewport side, index_count not a multiple of 3, an index past vertex_count, a
/// position_stride that is neither 0 nor a multiple of 4 of at least 12, or limit NaN or
/// negative. `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_steepest_face(
    mesh: *const ZshiftMesh,
    clip: ZshiftClip,
    viewport_width: u32,
    viewport_height: u32,
    limit: f64,
    out: *mut ZshiftSteepestFace,
) -> ZshiftStatus {
    let mesh = match read_mesh(mesh) {
        Ok(x) => x,
        Err(status) => return status,
    };
    checked_record(out, move || {
        let clip = clip_of(clip)?;
        let (positions, indices) = mesh.arrays()?;
        let face = crate::steepest_face::steepest_face(
            &mesh.clip_matrix,
            clip,
            [viewport_width, viewport_height],
            &positions,
            &indices,
            limit,
        )?;
        Ok(ZshiftSteepestFace::from(face))
    })
}

/// Writes the offset for `edges`' mesh by `method`, as `zshift_edge_offset`, paying for the
/// mesh's own steepest faces rather than its face-slope limit's: `edges.face_angle` (or
/// face_gradient) is the limit beyond which faces are grazing, and the faces of `mesh` within
/// it, read exactly from its triangles in `edges`' viewport (`zshift_steepest_face` with the
/// limit's face_gradient), set the line term; every face within the limit keeps its edges, as
/// with the limit alone. A terrain of gentle hills or a box under 4x MSAA paid 7.7x and 2.65x
/// the smallest working offset for a 60-degree limit on llvmpipe (docs/edges.md).
///
/// Errors: as `zshift_edge_offset` and `zshift_steepest_face` (NULL `mesh` or its pointers, a
/// bad index or position, named). `*out` is untouched on error.
#[no_mangle]
pub extern "C" fn zshift_edge_offset_for_mesh(
    m: *const f32,
    clip: ZshiftClip,
    edges: *const ZshiftEdges,
    mesh: *const ZshiftMesh,
    method: u32,
    out: *mut ZshiftEdgeOffset,
) -> ZshiftStatus {
    let (m, e) = match read_inputs(m, edges) {
        Ok(x) => x,
        Err(status) => return status,
    };
    let mesh = match read_mesh(mesh) {
        Ok(x) => x,
        Err(status) => return status,
    };
    checked_record(out, move || {
        let clip = clip_of(clip)?;
        let (positions, indices) = mesh.arrays()?;
        let draw = crate::lines::MeshDraw {
            clip_matrix: &mesh.clip_matrix,
            positions: &positions,
            indices: &indices,
        };
        let (r, _) = crate::lines::recommend_for_mesh(
            &m,
            clip,
            &input(clip, &e)?,
            method_of(method)?,
            &draw,
        )?;
        Ok(ZshiftEdgeOffset::from(r))
    })
}

impl From<crate::steepest_face::SteepestFace> for ZshiftSteepestFace {
    fn from(face: crate::steepest_face::SteepestFace) -> Self {
        ZshiftSteepestFace {
            gradient: face.gradient,
            length: face.length,
            triangle: face.triangle.map_or(-1, |t| t as i64),
            counted: face.counted as u64,
            beyond_limit: face.beyond_limit as u64,
            culled: face.culled as u64,
        }
    }
}

/// The caller's mesh record and its matrix, or the status for a NULL pointer (the arrays are
/// read by [`mesh_arrays`] inside the computation, whose errors `checked` reports).
struct MeshInput {
    clip_matrix: [f32; 16],
    record: ZshiftMesh,
}

impl MeshInput {
    /// The positions and indices, copied.
    fn arrays(&self) -> Result<(Vec<[f32; 3]>, Vec<u32>)> {
        let r = &self.record;
        let positions = read_positions(r.positions, r.vertex_count, r.position_stride)?;
        Ok((positions, read_indices(r.indices, r.index_count)))
    }
}

fn read_mesh(mesh: *const ZshiftMesh) -> std::result::Result<MeshInput, ZshiftStatus> {
    if mesh.is_null() {
        return Err(null_pointer("mesh"));
    }
    // SAFETY: not NULL; the caller promises a readable ZshiftMesh; read_unaligned needs no
    // alignment.
    let record = unsafe { mesh.read_unaligned() };
    if record.clip_matrix.is_null() {
        return Err(null_pointer("mesh->clip_matrix"));
    }
    if record.positions.is_null() && record.vertex_count > 0 {
        return Err(null_pointer("mesh->positions"));
    }
    if record.indices.is_null() && record.index_count > 0 {
        return Err(null_pointer("mesh->indices"));
    }
    // SAFETY: not NULL; the caller promises 16 readable floats.
    let clip_matrix = unsafe { record.clip_matrix.cast::<[f32; 16]>().read_unaligned() };
    Ok(MeshInput {
        clip_matrix,
        record,
    })
}

/// The caller's `count` positions, three floats each, `stride` bytes apart (0: 12); `p` not
/// NULL when count > 0 (checked by the caller of this function).
fn read_positions(p: *const f32, count: usize, stride: usize) -> Result<Vec<[f32; 3]>> {
    let stride = if stride == 0 { 12 } else { stride };
    if stride < 12 || stride % 4 != 0 {
        return Err(domain(
            "position_stride must be 0 (tightly packed) or a multiple of 4 bytes of at least 12",
        )
        .with_integer("position_stride", stride as i64));
    }
    let step = stride / 4;
    // SAFETY: the caller promises `count` positions `stride` bytes apart, readable;
    // read_unaligned needs no alignment and any bit pattern is an f32.
    Ok((0..count)
        .map(|i| [0, 1, 2].map(|k| unsafe { p.add(step * i + k).read_unaligned() }))
        .collect())
}

/// The caller's `count` indices (`p` not NULL when count > 0, checked by the caller of this
/// function).
fn read_indices(p: *const u32, count: usize) -> Vec<u32> {
    // SAFETY: the caller promises `count` readable u32; read_unaligned needs no alignment.
    (0..count)
        .map(|i| unsafe { p.add(i).read_unaligned() })
        .collect()
}

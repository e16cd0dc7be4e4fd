//! Edges drawn over their own faces: wireframe on shaded, outlined polygons, hidden-line
//! drawing (seed 004's second and third coplanar problems).
//!
//! A mesh is drawn twice: its faces (filled; in a hidden-line drawing with the background
//! colour), then its edges, as `GL_LINES` of width `w` or as the faces again in
//! `glPolygonMode(GL_LINE)`. An edge lies in the plane of the faces it borders, so without an
//! offset its fragments tie with the faces' and lose about half of them. Two offsets are in use,
//! and this module computes both ([`EdgeMethod`]) from what the engine knows ([`Edges`]):
//!
//! * **(a) faces pushed back** with `glPolygonOffset(factor, units)` (Direct3D `DepthBias` and
//!   `SlopeScaledDepthBias`, Vulkan `depthBiasConstantFactor` and `depthBiasSlopeFactor`), edges
//!   drawn unoffset;
//! * **(b) edges pulled forward** through the projection matrix (element 10 under `[−1, 1]` and
//!   `[0, 1]`; under reversed Z element 10 too, or element 14 scaled, whichever offsets less:
//!   [`crate::matrix_in`]'s outward rounding), faces
//!   drawn unoffset. `glPolygonOffset` does not move `GL_LINES` primitives (it applies to
//!   polygons, also in `GL_LINE` polygon mode): this is the one offset that reaches them.
//!
//! # The line term
//! A line fragment's depth is the line's depth at a point near the pixel, not the face's plane at
//! the pixel centre. A `GL_LINES` segment is rasterized along its major axis: in each column (an
//! x-major line) the fragments take the line's depth at that column, and their centres lie up to
//! about `w/2` pixels across the line (the diamond-exit rule for `w = 1`, a `w`-pixel run for a
//! wide line). The face's window depth is the plane `z = z₀ + gₓ·x + g_y·y`, and the line lies in
//! it, so at a fragment
//!
//! `|z_line − z_face| ≤ |g_minor|·Δ ≤ M·Δ`,  `M = max(|gₓ|, |g_y|)`, `Δ = (w + 1)/2`,   (L)
//!
//! `g_minor` the gradient along the minor axis. `Δ = (w + 1)/2` (the worst case) keeps half a pixel of
//! the rasterizer's freedom beyond the ideal `w/2`: llvmpipe was measured at 0.50–0.52 pixel for
//! 1-pixel lines, 0.72 for polygon-mode lines (its unfilled stage re-draws the triangle's edges
//! with their own set-up) and 1.52 for width 3. A measured profile
//! ([`RasterizerProfile::line_reach`], single-sampled) replaces it by the probe's reach for the
//! line kind at width 1, plus 1/16 pixel (a sampled maximum: a sweep scene needed 0.503 where
//! the probe found 0.5006), plus `(w − 1)/2`.
//!
//! **Polygon-mode lines** ([`LineKind::PolygonMode`]): every triangle draws its own outline, so
//! along a shared edge a face `F`'s pixel may take its line fragment from the neighbour `G`'s
//! outline. A rasterizer that takes an outline's depth from its line (Mesa's draw module, the
//! line's depth constant across it) puts that fragment on the shared side's line, which lies in
//! `F`: it is off `F` by `F`'s own slope term only, as `F`'s own outline is. One that evaluates
//! `G`'s plane there puts it off `F` by `(∇G − ∇F)·v`, `v` the pixel's offset from the side: up to
//! `Δ_n·(m_F + m_G)`. The worst case assumes the second, `Δ_n = Δ = (w + 1)/2`, so the line term
//! doubles, `L = 2·g·Δ` (the neighbour up to the face-slope limit); under (a) the factor `Δ` pays
//! the face's own part and the units the neighbour's `g·Δ_n`, which the face's factor does not
//! see. The probe measures which it is ([`RasterizerProfile::outline_neighbour`]: outline
//! fragments beyond a side of constant depth, read against that depth): f32 noise (llvmpipe,
//! 6·10⁻⁶ pixel) leaves the neighbour's term out, and a 1-pixel outline then takes the probe's
//! reach like `GL_LINES`; a larger figure `n` gives the face `Δ = max(reach, n) + 1/16` and the
//! neighbour `n + 1/16`, scaled to the variant's worst-case reach. (An earlier judge counted
//! pixels drawn by a thin triangle's hidden side as its visible one's, which looked like a
//! neighbour's slope: docs/edges.md.) Wide ones (`w > 1`) add 1/8
//! (`WIDE_OUTLINE_SHIFT`): a wide-line stage that draws them as quads shifted half a pixel
//! along the line (Mesa's) makes a fragment take the line's depth up to `w/2 + 1/8` across and
//! `1/2` along from its centre, 1/8 beyond `(w + 1)/2`. A measured profile
//! ([`RasterizerProfile::line_reach_wide`]: the probe's dense geometry drawn at `glLineWidth(3)`)
//! replaces it by the 3-pixel reach plus 1/16 and `(w − 3)/2` beyond width 3, where smaller:
//! llvmpipe measures 1.5007, so `Δ` = 1.56 at width 3 (2.125 in the worst case); the quad's
//! along-the-line half pixel does not reach a fragment's depth there.
//!
//! **MSAA** ([`Edges::samples`] > 1): a multisampled line is a rectangle `w` wide whose samples
//! take the line's depth at their projection on it (or along the minor axis), and the face's
//! depth is taken at the sample. A sample lies up to `w/2` from the point whose depth it takes,
//! in a direction that is not an axis: the face's gradient along it is up to `|∇z| ≤ √2·M`, so a
//! sample is off the face by up to `(w/2)·√2·M`, more than `(w + 1)/2·M` from `w ≥ 2.5`. Under
//! MSAA `Δ = √2·(w + 1)/2` (half a pixel of freedom beyond `w/2`, along any direction) in the
//! worst case. A measured profile ([`RasterizerProfile::line_reach_msaa`]: every sample of
//! multisampled 1-pixel lines against the plane at the sample) replaces it by the probe's reach
//! for the line kind plus 1/16 and `√2·(w − 1)/2` (the rectangle's further half-width, along
//! any direction), where smaller: llvmpipe measures 1.056 for `GL_LINES`, so `Δ` = 1.12 at width
//! 1 (was 1.41) and 2.53 at width 3 (was 2.83). Polygon-mode lines take the same, with their
//! own figure (llvmpipe 1.054). A face-slope limit given as an angle ([`FaceSlope::Angle`])
//! bounds a face's whole gradient `|∇z|`, so against it the line term is `g·min(Δ, (w + 1)/2)`
//! (a sample within `(w + 1)/2` of its line's point in any direction; a measured profile's
//! [`RasterizerProfile::line_reach_msaa_whole`] plus 1/16 where smaller for 1-pixel lines,
//! llvmpipe's samples lying within 0.87 of the whole gradient, NVIDIA's within 0.5, and
//! [`RasterizerProfile::line_reach_msaa_wide_whole`] plus 1/16 for wider ones, 1.66 and 1.5 at
//! width 3), and against a mesh's own faces
//! ([`FaceSlope::Faces`]) the smaller of `M·Δ` and `length` times that; the polygon-offset factor keeps `Δ`, which multiplies each
//! face's own `M`. They had added a pixel (`+ 1`) under MSAA, set from one sample
//! a sphere lost at a vertex (`tests/gl_lines.rs`, `ZSHIFT_LINES_SEED=4`); that sample lay
//! 0.001 pixel inside its exact front face, on the side of a shallower face that borders none
//! of the edges drawn there and that the rasterizer gave it to, so its steep face's edges lost
//! to that face's smaller push under (a), with `GL_LINES` as with polygon-mode lines and with
//! either profile. The sweep no longer judges such a tie (docs/edges.md), and without the
//! `+ 1` the polygon-mode MSAA variant's full grid and seeds 1–4 and 19 keep every sample.
//! `M` is exactly the slope term of
//! `glPolygonOffset` on GL and llvmpipe (Vulkan also allows `√(gₓ² + g_y²) ≥ M`), which is why a
//! factor of `Δ` pays the line term of every face whatever its slope. A matrix offset is one
//! constant for the whole mesh, so it must pay `L = g·Δ` for the steepest face that matters:
//! [`FaceSlope`] says which that is (faces steeper than it are grazing, a few pixels wide on
//! screen; their edges are not guaranteed). Given as a limit (an angle, a gradient), it pays
//! for faces at that limit whether the mesh has them or not; [`recommend_for_mesh`] reads the
//! mesh's own steepest faces within the limit from its triangles
//! ([`crate::steepest_face`]) and pays for those.
//!
//! # The shared terms
//! Face and edge depths are computed by two primitives of one mesh: each is off its exact plane
//! by the decal model's plane error `E` and snapping `S` ([`crate::recommend`]: `T`, `V`, `I`,
//! `S`, the quantum `q`, the depth test; [`crate::model`]). They are reused, not rederived: the
//! mesh becomes a [`Scene`] whose depth range is the mesh's extent and whose slope is the eye
//! slope of a face of window gradient `g` crossing the view axis at the mesh's nearest depth
//! (`s = g·d₁/(F·min((r − l)/W, (t − b)/H))`, so every face of gradient up to `g` is within the
//! scene's bounds, as a decal's plane is in the decal model), inside the frustum. With
//! `B = 2(E + S)` (face and edge), the edge survives at every pixel of a face of gradient at most
//! `g` when
//!
//! (b) `Δw ≥ L + B + q_s`,  (a) `factor = Δ`, `units·r ≥ B + q_s + 2u·(1 + w_max)`,
//!
//! `q_s = q` under `GL_LESS`/`GL_GREATER` edges and 0 under `GL_LEQUAL`/`GL_GEQUAL` (a tie
//! passes), `2u·(1 + w_max)` the f32 roundings of the bias itself, `r` the profile's
//! [`RasterizerProfile::resolvable`] times the format's spacing at the mesh's smallest window
//! depth (D32F's `r` follows the primitive's largest depth: the smallest is the safe count).
//! Under reversed Z two offsets exist: the constant NDC offset through element 10 (as above,
//! `Δw ≥ L + B + q_s` with the quantum at the mesh's largest window depth, plus `2u·Δw` for its
//! own rounding), and the relative `ε` of element 14 (`ε·b/d` at depth `d`, carried to every
//! depth of the mesh as the decal's is). The line term is the same window error at every depth
//! (faces of gradient up to `g` anywhere), which a relative offset, falling as `1/d`, reaches
//! only at the far end (`L·d₂/d₁` at `d₁`): the constant one is used unless the relative one is
//! smaller at `d₁`.
//!
//! # The hidden-line gap
//! A hidden edge must stay behind the front face it lies behind. Its fragment competes with the
//! front face's stored depth (pushed back by up to `Δ·g·ρ + units·r_max` under (a), `r_max` at
//! the mesh's largest depth and, for a profile that did not measure `r`, 4 quanta (the largest
//! an implementation is known to use), `ρ` the
//! profile's [`RasterizerProfile::offset_slope`] — 1 for GL's `max` rule, `√2` for a root sum of
//! squares and in the worst case —, or against
//! the edge's pull `Δw` under (b)), each off its plane by `E + S`, and the hidden edge's own
//! fragment off its line by up to `L` (the sampling point's freedom along the line, for an edge
//! whose faces are within `g`); under an `…EQUAL` test a tie shows. So a hidden edge whose exact
//! window depth at the pixel is behind the front face's by
//!
//! `G_w = offset + B + L + q_t`  (`q_t = q` under `…EQUAL`, 0 strict)
//!
//! never shows. [`EdgeRecommendation::hidden_gap`] is `G_w` as an eye depth (`−z`) at the worse
//! of the mesh's nearest and farthest depths. An engine that needs hidden edges hidden from a
//! given separation on (a hidden-line drawing of a thin part) passes it as
//! [`Edges::hidden_separation`]; where the gap exceeds it no offset does both, and
//! [`recommend`] refuses ([`crate::ErrorKind::Unresolvable`]); [`working_planes`] then gives the
//! tight near and far planes of the mesh's extent ([`crate::plan::tight_planes`]) when they would
//! make the offset work.
//!
//! # What is not modelled
//! Antialiased (smooth) lines, whose coverage reaches further; lines clipped by the rasterizer
//! (an edge crossing the near plane: cut the mesh to the frustum as a decal's base is);
//! orthographic projections (refused: their depth is linear, a separate model);
//! `GL_POLYGON_OFFSET_LINE` on polygon-mode edges (pulling edges forward also pulls back-face
//! outlines over front faces).

use crate::domain::{domain, finite, representable};
use crate::error::{Error, ErrorKind, Result};
use crate::matrix_in::{recognize, Shape};
use crate::model::Pipeline;
use crate::polygon_offset::{resolvable_difference, BiasApi};
use crate::precision::{DepthFormat, DepthMapping};
use crate::projection::{ClipDepth, Frustum};
use crate::recommend::{Base, DepthTest, ErrorTerms, RasterizerProfile, Remedies, Scene};

// `u = 2⁻²⁴`, the unit roundoff of f32 (one home: crate::model).
use crate::model::F32_UNIT_ROUNDOFF as U;

mod reach;
use reach::{line_part, line_reach, msaa_across, neighbour_reach};

/// How the edges are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LineKind {
    /// `GL_LINES` (or line strips and loops) of [`Edges::line_width`].
    #[default]
    Lines,
    /// The faces drawn again under `glPolygonMode(GL_FRONT_AND_BACK, GL_LINE)`.
    PolygonMode,
}

impl LineKind {
    /// The index of this kind in the profile's per-kind line figures
    /// ([`RasterizerProfile::line_reach`] and its kin): `GL_LINES` 0, polygon-mode lines 1.
    fn index(self) -> usize {
        match self {
            LineKind::Lines => 0,
            LineKind::PolygonMode => 1,
        }
    }
}

/// The steepest face whose edges must be kept: faces steeper than it are grazing (a few pixels
/// across on screen) and their edges are not guaranteed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceSlope {
    /// The largest window-depth gradient per pixel `max(|∂w/∂x|, |∂w/∂y|)` (unit window depth,
    /// the quantity `glPolygonOffset`'s factor multiplies), `≥ 0`.
    WindowGradient(f64),
    /// The largest angle between a face's normal and the view axis, radians in `[0, π/2)`: its
    /// window gradient at the mesh's nearest depth, anywhere on screen, is the bound
    /// ([`EdgeRecommendation::face_gradient`]; the guarantee is for faces whose window gradient
    /// has a length `√((∂w/∂x)² + (∂w/∂y)²)` up to it: an angle bounds the whole gradient, not
    /// only its larger component, and under MSAA the line term uses that, module docs "MSAA";
    /// single-sampled, faces with `max(|∂w/∂x|, |∂w/∂y|)` up to it hold too). That gradient
    /// takes the first-order tilt of [`crate::model`]'s gradient term: a face within the angle
    /// that grazes an off-axis ray can be steeper, and is then not guaranteed.
    Angle(f64),
    /// The steepest faces of the mesh itself, as [`crate::steepest_face::steepest_face`] reads
    /// them from its triangles under this view ([`recommend_for_mesh`] does both): the largest
    /// `max(|∂w/∂x|, |∂w/∂y|)` and the largest gradient length of a face that matters. The
    /// guarantee is for faces within both; single-sampled the line term is that of
    /// `WindowGradient(max_component)`, under MSAA the smaller of it and `length·(w + 1)/2` (a
    /// sample within `(w + 1)/2` of its line's point in any direction, module docs "MSAA").
    Faces {
        /// The largest `max(|∂w/∂x|, |∂w/∂y|)`, `≥ 0`.
        max_component: f64,
        /// The largest `√((∂w/∂x)² + (∂w/∂y)²)`, `≥ 0`.
        length: f64,
    },
}

/// Which of the two ways of drawing edges over faces (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeMethod {
    /// (a) faces pushed back with polygon offset, edges unoffset.
    PolygonOffset,
    /// (b) edges pulled forward through the projection matrix, faces unoffset.
    Matrix,
}

/// What an engine knows about a mesh whose edges it draws over its faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edges {
    /// Viewport width and height in pixels.
    pub viewport: [u32; 2],
    /// The depth attachment's format.
    pub format: DepthFormat,
    /// The edge pass's depth test (`GL_LEQUAL` is usual: a tie keeps the edge; reversed Z:
    /// `GL_GEQUAL`/`GL_GREATER`).
    pub depth_test: DepthTest,
    /// Line width in pixels (`glLineWidth`), `1 ≤ w ≤ 64`; polygon-mode lines take it too. A
    /// width between integers is taken as GL may draw it, rounded to the nearest integer
    /// (halves up) where that is wider: 2.5 as 3, 2.4 as 2.4.
    pub line_width: f64,
    /// `GL_LINES` or polygon-mode lines.
    pub kind: LineKind,
    /// MSAA samples per pixel (1 without multisampling), `1..=64`. Above 1 the reach is
    /// `√2·(w + 1)/2` (module docs, "MSAA"): a sample lies up to `w/2` off the line in any
    /// direction (against an angle or a mesh's gradient length, `(w + 1)/2` of that length).
    pub samples: u32,
    /// The mesh's nearest and farthest eye depth (`−z`), inside the frustum.
    pub depth_range: [f64; 2],
    /// The steepest face that matters.
    pub face_slope: FaceSlope,
    /// The eye depth behind a front face from which a hidden edge must not show; 0 when the
    /// engine needs no such promise (then no scene is refused on its account).
    pub hidden_separation: f64,
    /// The rasterizer ([`RasterizerProfile::worst_case`] unless probed).
    pub profile: RasterizerProfile,
    /// World-space vertices, viewport origin, `glDepthRange` ([`Pipeline::default`]).
    pub pipeline: Pipeline,
}

impl Edges {
    /// A mesh over `depth_range` in a `viewport` with `format`: 1-pixel `GL_LINES` under
    /// `GL_LEQUAL`, no MSAA, faces up to 75° from the view axis, no hidden separation, the
    /// worst-case profile, the default pipeline.
    pub fn new(viewport: [u32; 2], format: DepthFormat, depth_range: [f64; 2]) -> Self {
        Self {
            viewport,
            format,
            depth_test: DepthTest::LessEqual,
            line_width: 1.0,
            kind: LineKind::Lines,
            samples: 1,
            depth_range,
            face_slope: FaceSlope::Angle(75f64.to_radians()),
            hidden_separation: 0.0,
            profile: RasterizerProfile::worst_case(),
            pipeline: Pipeline::default(),
        }
    }
}

/// The offset for a mesh's edges by one [`EdgeMethod`], in every form an engine applies it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeRecommendation {
    /// The method these values are for.
    pub method: EdgeMethod,
    /// (a) `glPolygonOffset(factor, units)` magnitudes for the faces (positive pushes away under
    /// `GL_LESS`/`GL_LEQUAL`; negate both under reversed Z), units counted in the profile's
    /// `r`; `[0, 0]` for (b).
    pub polygon_offset: [f64; 2],
    /// (a) Direct3D 10–12 `DepthBias` (an integer, rounded up) and `SlopeScaledDepthBias`; zero
    /// for (b).
    pub d3d_bias: [f64; 2],
    /// (a) Vulkan `depthBiasConstantFactor` and `depthBiasSlopeFactor`; zero for (b).
    pub vulkan_bias: [f64; 2],
    /// (b) the edges' projection matrix: the engine's own with the offset applied to element 10
    /// (or, under reversed Z where that offsets less, element 14 scaled), rounded outward, every
    /// other element bit-identical; (a) the engine's matrix unchanged.
    pub matrix: [f32; 16],
    /// (b) the constant NDC offset applied through element 10 (negative: toward the camera);
    /// 0 for (a) and where reversed Z uses `relative_epsilon`.
    pub ndc_offset: f64,
    /// (b) under reversed Z where element 14 is scaled instead: its relative `ε`; 0 otherwise.
    pub relative_epsilon: f64,
    /// The largest window-depth offset between edge and face the method applies over the mesh
    /// (unit window depth; (a) at the steepest face that matters).
    pub window_offset: f64,
    /// The line term `L = g·Δ` (unit window depth; polygon-mode lines `2·g·Δ`: the
    /// neighbouring triangle's outline adds its own slope term; under MSAA with a face-slope
    /// angle, each part at most `g·(w + 1)/2`: the angle bounds the whole gradient; with a
    /// mesh's own faces, at most `length·(w + 1)/2`).
    pub line_term: f64,
    /// `Δ`, pixels (times `max(|∂z/∂x|, |∂z/∂y|)`): how far from the pixel or sample a line
    /// fragment's depth is taken. `(w + 1)/2` in the worst case and for polygon-mode lines;
    /// the probed reach plus 1/16 plus `(w − 1)/2` for `GL_LINES` with a profile;
    /// `√2·(w + 1)/2` under MSAA, or the profile's multisampled reach plus 1/16 plus
    /// `√2·(w − 1)/2` where smaller.
    pub line_reach: f64,
    /// `g`: the window-depth gradient per pixel of the steepest face that matters (its larger
    /// component for [`FaceSlope::WindowGradient`], its length for [`FaceSlope::Angle`], the
    /// mesh's `max_component` for [`FaceSlope::Faces`]).
    pub face_gradient: f64,
    /// Hidden edges behind a front face by at least this eye depth (`−z`, at the same pixel)
    /// never show.
    pub hidden_gap: f64,
    /// The decal model's terms for the mesh (face and edge each), window-depth units.
    pub terms: ErrorTerms,
}

/// The offset that keeps every edge of a face within [`Edges::face_slope`] in front of it, by
/// `method`, with the hidden-line gap it costs; `m` the engine's projection (column-major f32,
/// perspective) under `clip`.
///
/// # Errors
/// [`ErrorKind::NotFinite`] / [`ErrorKind::Domain`] for a bad input (the detail names the
/// field: `line_width`, `samples`, `face_slope`, `hidden_separation`, the mesh's
/// `depth_range`, or as [`crate::matrix_in::recommend`]); [`ErrorKind::Domain`] for an
/// orthographic matrix; [`ErrorKind::Unresolvable`] when the hidden-line gap exceeds
/// `hidden_separation` (no offset keeps every visible edge and hides every hidden one: see
/// [`working_planes`]), or the offset would move the nearest edge past the near plane;
/// [`ErrorKind::Overflow`] if a result overflows.
pub fn recommend(
    m: &[f32; 16],
    clip: ClipDepth,
    edges: &Edges,
    method: EdgeMethod,
) -> Result<EdgeRecommendation> {
    let rec = unchecked_gap(m, clip, edges, method)?;
    let sep = edges.hidden_separation;
    if sep > 0.0 && rec.hidden_gap > sep {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            "no offset keeps every visible edge and hides every hidden edge at hidden_separation: the hidden-line gap exceeds it (zshift_edge_planes / working_planes gives near and far planes that would work, or use a deeper depth format)",
        )
        .with_value("hidden_separation", sep));
    }
    Ok(rec)
}

/// A mesh as the engine draws it, for [`recommend_for_mesh`]: its vertex positions, its
/// triangles (`GL_TRIANGLES` order, three indices each) and the whole matrix that takes the
/// positions to clip space (`projection · view · model`, column-major f32, as the vertex shader
/// applies it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshDraw<'a> {
    /// `projection · view · model`.
    pub clip_matrix: &'a [f32; 16],
    /// The vertex positions the shader reads.
    pub positions: &'a [[f32; 3]],
    /// Three indices per triangle into `positions`.
    pub indices: &'a [u32],
}

/// [`recommend`] for the mesh's own steepest faces: `edges.face_slope` (an angle or a window
/// gradient) is the limit beyond which faces are grazing, and the faces of `mesh` within it,
/// read exactly from its triangles under this view ([`crate::steepest_face::steepest_face`]
/// with the limit's gradient, [`EdgeRecommendation::face_gradient`] of the same ask), set the
/// line term ([`FaceSlope::Faces`]). A mesh with no face near the limit (a terrain of gentle
/// hills, a box, flat panels) pays for the faces it has; every face within the limit keeps its
/// edges, as with the limit alone. Returns the recommendation and what was read.
///
/// # Errors
/// As [`recommend`] and [`crate::steepest_face::steepest_face`] (the mesh's inputs named);
/// [`ErrorKind::Domain`] when `edges.face_slope` is already [`FaceSlope::Faces`].
pub fn recommend_for_mesh(
    m: &[f32; 16],
    clip: ClipDepth,
    edges: &Edges,
    method: EdgeMethod,
    mesh: &MeshDraw<'_>,
) -> Result<(EdgeRecommendation, crate::steepest_face::SteepestFace)> {
    if matches!(edges.face_slope, FaceSlope::Faces { .. }) {
        return Err(domain(
            "recommend_for_mesh reads the mesh's faces itself: give face_slope as the limit (an angle or a window gradient)",
        ));
    }
    let frustum = frustum_of(m, clip)?;
    check(edges, &frustum)?;
    let (_, limit) = slopes(edges, &frustum)?;
    let faces = crate::steepest_face::steepest_face(
        mesh.clip_matrix,
        clip,
        edges.viewport,
        mesh.positions,
        mesh.indices,
        limit,
    )?;
    let own = Edges {
        face_slope: FaceSlope::Faces {
            max_component: faces.gradient,
            length: faces.length,
        },
        ..*edges
    };
    Ok((recommend(m, clip, &own, method)?, faces))
}

/// Near and far planes that make [`recommend`] answer for `edges` by `method`: the tight planes
/// of the mesh's extent ([`crate::plan::tight_planes`]) with `m`'s side planes (the same
/// `l/n`, `r/n`, `b/n`, `t/n`).
///
/// # Errors
/// As [`recommend`]; [`ErrorKind::Unresolvable`] when even the tight planes leave the gap above
/// `hidden_separation` (a deeper format, or reversed Z with D32F, is then the remedy).
pub fn working_planes(
    m: &[f32; 16],
    clip: ClipDepth,
    edges: &Edges,
    method: EdgeMethod,
) -> Result<[f64; 2]> {
    let frustum = frustum_of(m, clip)?;
    check(edges, &frustum)?;
    let [d1, d2] = edges.depth_range;
    let (l, r, b, t, n, _) = frustum.parameters();
    let b_of = |f: &Frustum| f.planes().near() * f.planes().far_over_span();
    // The tightest planes first; the matrix offset pulls the nearest edge toward the eye, so a
    // near plane a little closer may be needed to leave it room.
    let mut last = None;
    for room in [1.0, 0.999, 0.99, 0.9, 0.5] {
        let planes = crate::plan::tight_planes(d1 * room, d2)?;
        let k = planes.near() / n;
        let tight = Frustum::new(l * k, r * k, b * k, t * k, planes.near(), planes.far())?;
        let mt = crate::projection::projection(&tight, clip)?;
        // A window gradient belongs to the planes: the same faces under other planes have it
        // scaled by b'/b (window depth is α ± b/d); an angle does not change.
        let mut moved = *edges;
        let k = b_of(&tight) / b_of(&frustum);
        moved.face_slope = match edges.face_slope {
            FaceSlope::WindowGradient(g) => FaceSlope::WindowGradient(g * k),
            FaceSlope::Faces {
                max_component,
                length,
            } => FaceSlope::Faces {
                max_component: max_component * k,
                length: length * k,
            },
            angle @ FaceSlope::Angle(_) => angle,
        };
        match recommend(&mt, clip, &moved, method) {
            Ok(_) => return Ok([planes.near(), planes.far()]),
            Err(e) if e.kind() == ErrorKind::Unresolvable => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    let _ = last;
    Err(Error::new(
        ErrorKind::Unresolvable,
        "even the tightest near and far planes of the mesh's depth range leave the hidden-line gap above hidden_separation: use a deeper depth format (D24, D32F with reversed Z)",
    )
    .with_value("hidden_separation", edges.hidden_separation))
}

fn frustum_of(m: &[f32; 16], clip: ClipDepth) -> Result<Frustum> {
    let r = recognize(m, clip)?;
    let Shape::Perspective { handedness, .. } = r.shape else {
        return Err(domain(
            "edges over faces need a perspective projection (an orthographic matrix's depth is linear: not modelled here)",
        ));
    };
    crate::matrix_in::frustum_of(m, &r, handedness)
}

fn check(edges: &Edges, frustum: &Frustum) -> Result<()> {
    let w = edges.line_width;
    finite(w, "line_width is NaN or infinite").map_err(|e| e.with_value("line_width", w))?;
    if !(1.0..=64.0).contains(&w) {
        return Err(domain("line_width must lie in [1, 64] pixels").with_value("line_width", w));
    }
    if !(1..=64).contains(&edges.samples) {
        return Err(
            domain("samples (MSAA samples per pixel) must lie in 1..=64")
                .with_integer("samples", i64::from(edges.samples)),
        );
    }
    non_negative(
        "hidden_separation",
        edges.hidden_separation,
        "hidden_separation is NaN or infinite",
        "hidden_separation must be >= 0 (0: no promise asked)",
    )?;
    match edges.face_slope {
        FaceSlope::WindowGradient(g) => non_negative(
            "face_slope",
            g,
            "face_slope (window gradient) is NaN or infinite",
            "face_slope (window gradient per pixel) must be >= 0",
        )?,
        FaceSlope::Faces {
            max_component,
            length,
        } => {
            for (name, g) in [("max_component", max_component), ("length", length)] {
                non_negative(
                    name,
                    g,
                    "face_slope (a mesh's face gradient) is NaN or infinite",
                    "face_slope (a mesh's face gradient per pixel) must be >= 0",
                )?;
            }
        }
        FaceSlope::Angle(a) => {
            finite(a, "face_slope (angle) is NaN or infinite")
                .map_err(|e| e.with_value("face_slope", a))?;
            if !(0.0..std::f64::consts::FRAC_PI_2).contains(&a) {
                return Err(domain(
                    "face_slope (angle from the view axis) must lie in [0, pi/2) radians",
                )
                .with_value("face_slope", a));
            }
        }
    }
    let [d1, d2] = edges.depth_range;
    let planes = frustum.planes();
    // A mesh the near or far plane cuts (the camera inside a room, a terrain running past the
    // far plane): the rasterizer clips its faces and lines in f32, which this model does not
    // bound; say what keeps the mesh inside.
    if d1 < planes.near() && d1.is_finite() {
        return Err(domain(
            "the mesh reaches in front of the near plane (depth_near < n: the camera inside or over it), where the rasterizer clips its faces and lines, which the edge model does not cover: pull the near plane in to the mesh's nearest depth, or cut the faces that cross it to the frustum (zshift_clip_to_frustum) and give the cut mesh's depth range",
        )
        .with_value("depth_near", d1)
        .with_bound("near plane n", planes.near()));
    }
    if d2 > planes.far() && d2.is_finite() {
        return Err(domain(
            "the mesh reaches beyond the far plane (depth_far > f), where the rasterizer clips its faces and lines, which the edge model does not cover: push the far plane out (an infinite one costs little), or give the depth range of the part in front and cut the faces that cross it (zshift_clip_to_frustum)",
        )
        .with_value("depth_far", d2)
        .with_bound("far plane f", planes.far()));
    }
    planes
        .check_distance(d1)
        .map_err(|e| e.with_value("depth_near", d1))?;
    planes
        .check_distance(d2)
        .map_err(|e| e.with_value("depth_far", d2))?;
    if d1 > d2 {
        return Err(domain(
            "the mesh's depth range must be [nearest, farthest]: depth_far must be >= depth_near",
        )
        .with_value("depth_far", d2));
    }
    Ok(())
}

/// `x` (the input `name`) finite and `>= 0`, else the error with `not_finite` or `negative` as
/// its detail and the value attached.
fn non_negative(
    name: &'static str,
    x: f64,
    not_finite: &'static str,
    negative: &'static str,
) -> Result<()> {
    finite(x, not_finite).map_err(|e| e.with_value(name, x))?;
    if x < 0.0 {
        return Err(domain(negative).with_value(name, x));
    }
    Ok(())
}

/// The eye slope `s` of the scene whose bounds cover every face of window gradient up to `g`,
/// and `g` itself (module docs, "The shared terms").
fn slopes(edges: &Edges, frustum: &Frustum) -> Result<(f64, f64)> {
    let (l, r, b, t, _, _) = frustum.parameters();
    let [w, h] = edges.viewport.map(f64::from);
    let (ex, ey) = ((r - l).abs() / w, (t - b).abs() / h);
    let big_f = frustum.planes().far_over_span();
    let d1 = edges.depth_range[0];
    match edges.face_slope {
        FaceSlope::WindowGradient(g)
        | FaceSlope::Faces {
            max_component: g, ..
        } => Ok((g * d1 / (big_f * ex.min(ey)), g)),
        FaceSlope::Angle(a) => {
            // |sₓ|, |s_y| ≤ tan a, |sₓ| + |s_y| ≤ √2·tan a; gradient per axis s_k·F·e_k/d_a with
            // the tilt (1 + s·e)/d₁ on 1/d_a (first-order: crate::model::gradient).
            let tan = a.tan();
            let s = std::f64::consts::SQRT_2 * tan;
            let e = crate::model::gradient::half_extent_tangent(frustum)?;
            let g = tan * big_f * ex.max(ey) / d1 * (1.0 + s * e);
            Ok((s, representable(g, "the face gradient overflows f64")?))
        }
    }
}

/// The largest `glPolygonOffset` unit known, in quanta of the format (UNORM `1/(2^m − 1)`, float
/// `2^(e−23)`): radeonsi's ×4 on D16 (`../shared/NOTES.md`; NVIDIA ×2 on every format, measured
/// on an H200 with driver 580; llvmpipe ×2 UNORM, ×1 float). The worst-case profile computes
/// units against the smallest `r` (1: enough wherever `r` is larger) and the push they make,
/// for the hidden-line gap, against this one: on the H200 the worst-case gap of a D32F mesh
/// counted ×1 and 8 hidden-edge pixels showed past it.
const LARGEST_KNOWN_RESOLVABLE: f64 = 4.0;

/// `glPolygonOffset`'s slope term over `max(|gₓ|, |g_y|)` at its largest: the measured rule
/// (1 for GL's max), else `√2` (a root sum of squares, which Vulkan allows).
fn offset_slope(p: &RasterizerProfile) -> f64 {
    crate::model::measured::measured_figure(p, p.offset_slope)
        .map_or(std::f64::consts::SQRT_2, |rule| rule.max(1.0))
}

fn unchecked_gap(
    m: &[f32; 16],
    clip: ClipDepth,
    edges: &Edges,
    method: EdgeMethod,
) -> Result<EdgeRecommendation> {
    let frustum = frustum_of(m, clip)?;
    check(edges, &frustum)?;
    let (slope, g) = slopes(edges, &frustum)?;
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    if edges.depth_test.is_reversed() != reversed {
        return Err(domain(if reversed {
            "reversed Z needs the edge pass's depth test GL_GREATER or GL_GEQUAL"
        } else {
            "this clip convention needs the edge pass's depth test GL_LESS or GL_LEQUAL"
        })
        .with_code("depth_test", edges.depth_test.gl_enum()));
    }
    let scene = Scene {
        frustum,
        viewport: edges.viewport,
        format: edges.format,
        depth_range: edges.depth_range,
        slope,
        exact_depth: false,
        depth_test: edges.depth_test,
        base: Base::InsideFrustum,
        profile: edges.profile,
        footprint: None,
        pipeline: edges.pipeline,
    };
    let terms = crate::recommend::clip_error_terms(&scene, clip)?;
    let mapping = crate::recommend::mapping_of(&scene, clip)?;
    let reach = line_reach(edges);
    // Polygon-mode edges: every triangle draws its own outline, so a face's pixel along a shared
    // edge may take its line fragment from the neighbour's outline, off the face by the
    // neighbour's slope term too where the rasterizer evaluates the neighbour's plane there
    // (module docs, "Polygon-mode lines"): that part, up to the face-slope limit, is `neighbour`.
    let own = representable(
        line_part(edges, g, reach, msaa_across(edges)),
        "the line term overflows f64",
    )?;
    let neighbour = representable(
        line_part(
            edges,
            g,
            neighbour_reach(edges),
            (reach::drawn_width(edges.line_width) + 1.0) / 2.0,
        ),
        "the line term overflows f64",
    )?;
    let line = representable(own + neighbour, "the line term overflows f64")?;
    let budget = terms.budget();
    let [d1, d2] = edges.depth_range;
    let (w1, w2) = (mapping.window_depth(d1)?, mapping.window_depth(d2)?);
    let (w_lo, w_hi) = (w1.min(w2), w1.max(w2));
    let fits = |x: f64| representable(x, "an edge offset overflows f64");
    let q_at = |d: f64| -> Result<f64> {
        crate::model::quantum::unit_quantum(scene.format, &scene.pipeline, mapping.window_depth(d)?)
    };
    // The window offset between edge and face at depth d (used by the gap), and the outputs.
    let mut out = EdgeRecommendation {
        method,
        polygon_offset: [0.0; 2],
        d3d_bias: [0.0; 2],
        vulkan_bias: [0.0; 2],
        matrix: *m,
        ndc_offset: 0.0,
        relative_epsilon: 0.0,
        window_offset: 0.0,
        line_term: line,
        line_reach: reach,
        face_gradient: g,
        hidden_gap: 0.0,
        terms,
    };
    let strict_q = |q: f64| if terms.strict { q } else { 0.0 };
    let remedies = Remedies::of(&edges.pipeline, &edges.profile);
    let offset_at: Box<dyn Fn(f64) -> Result<f64>> = match method {
        EdgeMethod::PolygonOffset => {
            // units·r ≥ B + q_s + the bias's own roundings, r counted at the smallest window
            // depth (D32F's r follows the primitive's largest depth, so it is never smaller).
            let pipeline = edges.pipeline;
            // The face's factor pays its own slope term; the units pay the neighbour's.
            let need = budget + strict_q(terms.quantum) + 2.0 * U * (1.0 + w_hi) + neighbour;
            let r_of = |api: BiasApi, w: f64| -> Result<f64> {
                Ok(pipeline.per_unit(resolvable_difference(
                    api,
                    edges.format,
                    pipeline.actual(w),
                )?))
            };
            let quanta =
                edges.profile.resolvable[crate::model::measured::profile_index(edges.format)];
            let r_gl = quanta * r_of(BiasApi::OpenGl, w_lo)?;
            let units = fits(need / r_gl)?;
            let d3d = (need / r_of(BiasApi::Direct3d, w_lo)?).ceil();
            let vk = need / r_of(BiasApi::Vulkan, w_lo)?;
            out.polygon_offset = [reach, units];
            out.d3d_bias = [fits(d3d)?, reach];
            out.vulkan_bias = [fits(vk)?, reach];
            // The push at the steepest face that matters, with r at the largest depth and, for a
            // profile that did not measure r, the largest r an implementation is known to use.
            let quanta_hi = if edges.profile.measured {
                quanta
            } else {
                quanta.max(LARGEST_KNOWN_RESOLVABLE)
            };
            let r_hi = quanta_hi * r_of(BiasApi::OpenGl, w_hi)?;
            let push = fits(reach * g * offset_slope(&edges.profile) + units * r_hi)?;
            out.window_offset = push;
            Box::new(move |_| Ok(push))
        }
        EdgeMethod::Matrix if reversed => {
            let eps = crate::recommend::reversed_epsilon_with(&scene, &mapping, &terms, line)?;
            let b = crate::model::gradient::scale(&scene.frustum);
            // The line term is a window error the same at every depth (faces of gradient up to
            // g anywhere), which the relative ε, falling as 1/d, reaches only at the mesh's far
            // end: L·d₂/d₁ at d₁. A constant NDC offset through element 10 pays it once; every
            // other term is at most its value at d₁ (the budget is a window bound at every
            // depth, the quantum largest at the largest window depth), plus the offset's own f32
            // rounding (2u of it). Whichever is smaller at d₁ is used.
            let q = if terms.strict {
                q_at(d1)?.max(q_at(d2)?).max(terms.quantum)
            } else {
                0.0
            };
            let constant = fits((line + budget + q) * (1.0 + 2.0 * U))?;
            if constant < eps * (b / d1) {
                constant_offset(&mut out, m, clip, constant, d1, &mapping, &terms, remedies)?;
                Box::new(move |_| Ok(constant))
            } else {
                relative(&mut out, m, eps, b, d1, &mapping, &terms, remedies)?;
                Box::new(move |d| Ok(eps * (b / d)))
            }
        }
        EdgeMethod::Matrix => {
            let dw = fits(line + budget + strict_q(terms.quantum))?;
            constant_offset(&mut out, m, clip, dw, d1, &mapping, &terms, remedies)?;
            Box::new(move |_| Ok(dw))
        }
    };
    // The gap, as an eye depth, at the worse of the mesh's ends.
    let toward = |dw: f64| if mapping.is_reversed() { dw } else { -dw };
    let mut gap = 0.0f64;
    for d in [d1, d2] {
        let q = q_at(d)?;
        let tie = if terms.strict { 0.0 } else { q };
        let gw = offset_at(d)? + budget + line + tie;
        let g_eye = match mapping.shift_of_window_change(toward(gw), d) {
            Ok(x) => x.min(d),
            Err(_) => d,
        };
        gap = gap.max(g_eye);
    }
    out.hidden_gap = fits(gap)?;
    Ok(out)
}

/// (b) with the constant window offset `dw` through element 10: the matrix, the NDC offset and
/// `dw` into `out`, checked to keep the mesh's nearest edge in range.
#[allow(clippy::too_many_arguments)]
fn constant_offset(
    out: &mut EdgeRecommendation,
    m: &[f32; 16],
    clip: ClipDepth,
    dw: f64,
    d1: f64,
    mapping: &DepthMapping,
    terms: &ErrorTerms,
    remedies: Remedies,
) -> Result<()> {
    crate::recommend::check_in_range(mapping, d1, dw, terms, remedies)?;
    let c = dw / mapping.window_per_ndc();
    out.ndc_offset = -c;
    // offset_ndc's c is toward the camera.
    out.matrix = crate::matrix_in::offset_ndc(m, clip, c)?;
    out.window_offset = dw;
    Ok(())
}

/// Reversed Z (b) with the relative `ε` of element 14: the matrix, `ε` and the window offset at
/// the mesh's nearest depth `d₁` into `out`, checked to stay in range.
#[allow(clippy::too_many_arguments)]
fn relative(
    out: &mut EdgeRecommendation,
    m: &[f32; 16],
    eps: f64,
    b: f64,
    d1: f64,
    mapping: &DepthMapping,
    terms: &ErrorTerms,
    remedies: Remedies,
) -> Result<()> {
    out.relative_epsilon = eps;
    out.matrix = crate::matrix_in::moved(
        m,
        14,
        crate::double_double::DoubleDouble::product(f64::from(m[14]), eps),
    )?;
    out.window_offset = representable(eps * (b / d1), "an edge offset overflows f64")?;
    crate::recommend::check_in_range(mapping, d1, out.window_offset, terms, remedies)
}

/// The window depth of eye distance `d` under `clip` for the planes of `m` (a helper for
/// reports and tests: the mapping [`recommend`] uses).
///
/// # Errors
/// As [`crate::matrix_in::recognize`] and [`DepthMapping::window_depth`].
pub fn window_depth(m: &[f32; 16], clip: ClipDepth, d: f64) -> Result<f64> {
    let frustum = frustum_of(m, clip)?;
    DepthMapping::of_planes(frustum.planes(), clip).window_depth(d)
}

#[cfg(test)]
mod tests;

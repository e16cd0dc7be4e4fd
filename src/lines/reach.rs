//! The line term's reach: how far from an edge's exact point a line's fragment (or, under MSAA,
//! its sample) takes its depth, in pixels of the face's gradient (module docs of
//! [`crate::lines`], "The line term" and "MSAA"), and how far a polygon-mode neighbour's
//! outline reaches onto a face.

use super::{Edges, FaceSlope, LineKind};
use crate::model::measured::measured_figure;
use crate::recommend::RasterizerProfile;

/// The width a rasterizer may draw a line asked `w` pixels wide: GL rounds a non-antialiased
/// line's width to the nearest integer (OpenGL 4.6 compatibility profile, 14.5.2.1, "Wide
/// Lines"), and a width halfway between may go up, so the larger of `w` and `⌊w + ½⌋`.
/// Measured: llvmpipe draws `glLineWidth(2.5)` 3 pixels wide; taken as 2.5, a default
/// `tests/gl_lines.rs` run at that width (`ZSHIFT_LINES_WIDE=2.5`) lost 4604 of 14.2 million
/// single-sampled `GL_LINES` pixels with a probed profile. Multisampled lines are taken the
/// same way, which is safe whichever width a rasterizer draws (llvmpipe draws them at the
/// exact width, a 2.5-pixel rectangle under 4× MSAA: taking 3 costs it a quarter pixel of
/// reach).
pub(super) fn drawn_width(w: f64) -> f64 {
    w.max((w + 0.5).floor())
}

/// Half of a line's width beyond the width the probe measures wide lines at
/// ([`crate::profile::WIDE_LINE_WIDTH`]), pixels; 0 for narrower lines, which reach no further
/// than 3-pixel ones.
fn beyond_wide(w: f64) -> f64 {
    (w - f64::from(crate::profile::WIDE_LINE_WIDTH)).max(0.0) / 2.0
}

/// What the model adds to the probe's measured line reach, pixels: the probe's figure is the
/// largest over its 96 lines (0.5006 for `GL_LINES` on llvmpipe), and a sweep scene drew a
/// fragment 0.503 pixel of its face's gradient off the face (`tests/gl_lines.rs`,
/// `ZSHIFT_LINES_SEED=1`); the issue's own measurement reached 0.52.
pub(super) const LINE_REACH_MARGIN: f64 = 1.0 / 16.0;

/// What a wide polygon-mode outline adds to the worst-case reach `(w + 1)/2`, pixels of `M`.
/// Mesa's draw module (llvmpipe) draws a wide line as a quad: the line's end points moved
/// `w/2 + 1/8` along the minor axis and the whole quad `1/2` pixel back along the major axis,
/// each vertex keeping its end point's depth (`draw_pipe_wide_line.c`). A fragment thus takes
/// the line's depth at a point up to `w/2 + 1/8` across and `1/2` along from its centre: off
/// the face by up to `(w/2 + 1/8)·|g_minor| + (1/2)·|g_major| ≤ ((w + 1)/2 + 1/8)·M`. Measured:
/// `ZSHIFT_LINES_SEED=19 ZSHIFT_LINES_FULL=1` lost single pixels of width-3 polygon-mode edges
/// under (a) at `(w + 1)/2` in three scenes, each kept from 1.1 times the offset; with 1/8 none
/// does (a pixel once counted lost at 1/8 was a hidden side's outline, misattributed: docs/edges.md).
pub(super) const WIDE_OUTLINE_SHIFT: f64 = 1.0 / 8.0;

/// `Δ`, in pixels of `M`: under MSAA the profile's measured multisampled reach for the line
/// kind plus [`LINE_REACH_MARGIN`] and `√2·(w − 1)/2`, at most (and unmeasured) `√2·(w + 1)/2`;
/// else the profile's measured reach for the
/// line kind plus [`LINE_REACH_MARGIN`] and `(w − 1)/2` (a measured profile; at most the worst
/// case), else `(w + 1)/2` (module docs, "The line term"); wide polygon-mode lines add
/// [`WIDE_OUTLINE_SHIFT`], or with a measured profile take its 3-pixel reach plus
/// [`LINE_REACH_MARGIN`] and `(w − 3)/2` beyond width 3, where smaller.
pub(super) fn line_reach(edges: &Edges) -> f64 {
    let w = drawn_width(edges.line_width);
    let worst = (w + 1.0) / 2.0;
    let p = &edges.profile;
    let measured = |x: f64| measured_figure(p, x);
    if edges.samples > 1 {
        // A sample up to w/2 across the line from the point whose depth it takes, half a pixel
        // of freedom beyond, in any direction: the face's gradient there is up to √2·M. A
        // measured profile's width-1 reach, its margin, and the rest of the width at √2.
        let kind = edges.kind.index();
        let root2 = std::f64::consts::SQRT_2;
        let across = root2 * worst;
        return measured(p.line_reach_msaa[kind]).map_or(across, |reach| {
            (reach + LINE_REACH_MARGIN + root2 * (w - 1.0) / 2.0).min(across)
        });
    }
    match edges.kind {
        LineKind::Lines if measured(p.line_reach[0]).is_some() => {
            (p.line_reach[0] + LINE_REACH_MARGIN + (w - 1.0) / 2.0).min(worst)
        }
        // Wide outlines take the quad shift of a wide-line stage ([`WIDE_OUTLINE_SHIFT`]), or
        // the probe's 3-pixel reach, its margin and half of any width beyond 3 (narrower ones
        // reach no further than 3-pixel ones).
        LineKind::PolygonMode if w > 1.0 => {
            let wide = worst + WIDE_OUTLINE_SHIFT;
            measured(p.line_reach_wide[1]).map_or(wide, |reach| {
                (reach + LINE_REACH_MARGIN + beyond_wide(w)).min(wide)
            })
        }
        // A 1-pixel outline takes its depth up to its own measured reach from the pixel, or,
        // where the rasterizer evaluates its triangle's plane beyond the side, up to the
        // measured distance there (module docs, "Polygon-mode lines"): the larger.
        LineKind::PolygonMode
            if measured(p.line_reach[1]).is_some() && p.outline_neighbour.is_finite() =>
        {
            (p.line_reach[1].max(p.outline_neighbour) + LINE_REACH_MARGIN).min(worst)
        }
        LineKind::Lines | LineKind::PolygonMode => worst,
    }
}

/// How far, in any direction, a multisampled line's sample may lie from the point whose depth it
/// takes, pixels (its error is at most this times the face's whole gradient `|∇z|`): `(w + 1)/2`;
/// with a measured profile, where smaller, the probe's whole-gradient reach for the line kind
/// plus [`LINE_REACH_MARGIN`]: at width 1 [`RasterizerProfile::line_reach_msaa_whole`]
/// (llvmpipe 0.865, so 0.93), wider [`RasterizerProfile::line_reach_msaa_wide_whole`] (measured
/// at width 3: llvmpipe 1.656, so 1.72 where the worst case is 2) plus `(w − 3)/2` beyond 3 (a
/// narrower wide line reaches no further than a 3-pixel one).
pub(super) fn msaa_across(edges: &Edges) -> f64 {
    let w = drawn_width(edges.line_width);
    let p = &edges.profile;
    let kind = edges.kind.index();
    let worst = (w + 1.0) / 2.0;
    let (figure, beyond) = if w == 1.0 {
        (p.line_reach_msaa_whole[kind], 0.0)
    } else {
        (p.line_reach_msaa_wide_whole[kind], beyond_wide(w))
    };
    measured_figure(p, figure).map_or(worst, |reach| worst.min(reach + LINE_REACH_MARGIN + beyond))
}

/// The part of the line term one reach makes against the face-slope limit `g` (the face's own
/// `Δ`, or a polygon-mode neighbour's `Δ_n`, in pixels of `M`), `across` the sample's distance
/// in any direction ([`msaa_across`]; the worst case's `(w + 1)/2` for a neighbour's outline,
/// which the probe does not draw): `g·reach`, except under MSAA
/// where the limit also bounds a face's whole gradient `|∇z|`, not only its larger component
/// `M` — an angle ([`FaceSlope::Angle`]), whose `g` is that length, or a mesh's own faces
/// ([`FaceSlope::Faces`], `length`): a sample lies at most `across` from the point whose depth
/// it takes, in any direction (module docs, "MSAA"), so it is off its face by at most
/// `|∇z|·across`, less than `M·Δ` wherever `Δ` exceeds it (the worst case's `√2·(w + 1)/2`
/// against `(w + 1)/2`; llvmpipe's measured 1.12 at width 1 against 0.93). The polygon-offset
/// factor keeps `Δ`: it multiplies each face's own `M`.
pub(super) fn line_part(edges: &Edges, g: f64, reach: f64, across: f64) -> f64 {
    match edges.face_slope {
        FaceSlope::Angle(_) if edges.samples > 1 => g * reach.min(across),
        FaceSlope::Faces { length, .. } if edges.samples > 1 => (g * reach).min(length * across),
        FaceSlope::Angle(_) | FaceSlope::WindowGradient(_) | FaceSlope::Faces { .. } => g * reach,
    }
}

/// A measured [`RasterizerProfile::outline_neighbour`] at most this (pixels) is f32 noise: the
/// rasterizer takes an outline's depth from its line (llvmpipe reads 6·10⁻⁶), and a neighbour's
/// outline lands on a face with the face's own depth along the shared side.
pub(super) const OUTLINE_NEIGHBOUR_NOISE: f64 = 1.0 / 64.0;

/// `Δ_n`, in pixels of the neighbouring face's `M`: how far off the shared side's line a
/// neighbour's polygon-mode outline takes a face's pixel (module docs, "Polygon-mode lines").
/// 0 for `GL_LINES`, and for outlines where the profile measured noise
/// ([`OUTLINE_NEIGHBOUR_NOISE`]); where it measured more, the figure plus
/// [`LINE_REACH_MARGIN`] scaled from the probe's outline (width 1, single-sampled: 1 pixel in
/// the worst case) to the variant's worst-case reach; else that worst-case reach.
pub(super) fn neighbour_reach(edges: &Edges) -> f64 {
    if edges.kind == LineKind::Lines {
        return 0.0;
    }
    let worst = line_reach(&Edges {
        profile: RasterizerProfile::worst_case(),
        ..*edges
    });
    let p = &edges.profile;
    let measured = p.outline_neighbour;
    if !(p.measured && measured.is_finite()) {
        worst
    } else if measured <= OUTLINE_NEIGHBOUR_NOISE {
        0.0
    } else {
        (worst * (measured + LINE_REACH_MARGIN)).min(worst)
    }
}

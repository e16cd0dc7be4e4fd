use super::reach::{LINE_REACH_MARGIN, WIDE_OUTLINE_SHIFT};
use super::*;
use crate::projection::projection;

fn matrix(n: f64, f: f64, clip: ClipDepth) -> [f32; 16] {
    let t = n * 0.5;
    projection(&Frustum::new(-t, t, -t, t, n, f).unwrap(), clip).unwrap()
}

fn edges(format: DepthFormat, d: [f64; 2], clip: ClipDepth) -> Edges {
    let mut e = Edges::new([512, 512], format, d);
    e.face_slope = FaceSlope::WindowGradient(1e-3);
    if clip == ClipDepth::ReversedZeroToOne {
        e.depth_test = DepthTest::GreaterEqual;
    }
    e
}

/// Independent reference for (b) under [−1, 1]: Δw = gΔ + 2(E + S) (LEQUAL), the gap at d₂
/// from Walker's w(d) = F(1 − n/d) solved for the eye depth.
#[test]
fn matrix_offset_is_line_term_plus_budget() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 1000.0, clip);
    let e = edges(DepthFormat::Unorm24, [10.0, 20.0], clip);
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert_eq!(r.line_reach, 1.0);
    assert!((r.line_term - 1e-3).abs() < 1e-15);
    let b = 2.0 * (r.terms.plane + r.terms.snap);
    assert!((r.window_offset - (1e-3 + b)).abs() < 1e-15, "{r:?}");
    assert!(
        r.matrix[10].abs() < m[10].abs(),
        "element 10 moved toward 0"
    );
    let gw = 2.0 * r.window_offset + r.terms.quantum;
    let (n, f) = (1.0f64, 1000.0f64);
    let big_f = f / (f - n);
    let w = |d: f64| big_f * (1.0 - n / d);
    let d_front = n / (1.0 - (w(20.0) - gw) / big_f);
    assert!(
        (r.hidden_gap - (20.0 - d_front)).abs() < 1e-6 * r.hidden_gap,
        "{r:?}"
    );
}

/// Wide polygon-mode outlines take a measured profile's 3-pixel reach plus 1/16 (and half the
/// width beyond 3) where smaller than the wide quad's `(w + 1)/2 + 1/8`; `GL_LINES` keep the
/// 1-pixel figure plus `(w − 1)/2`.
#[test]
fn a_measured_wide_reach_sets_wide_outlines() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.kind = LineKind::PolygonMode;
    e.line_width = 3.0;
    let reach = |e: &Edges| {
        recommend(&m, clip, e, EdgeMethod::Matrix)
            .unwrap()
            .line_reach
    };
    assert_eq!(reach(&e), 2.0 + WIDE_OUTLINE_SHIFT);
    e.profile.measured = true;
    e.profile.line_reach = [0.5, 0.5];
    e.profile.outline_neighbour = 0.0;
    assert_eq!(reach(&e), 2.0 + WIDE_OUTLINE_SHIFT);
    e.profile.line_reach_wide = [1.25, 1.5];
    assert_eq!(reach(&e), 1.5625);
    e.line_width = 5.0;
    assert_eq!(reach(&e), 2.5625);
    e.line_width = 2.0;
    assert_eq!(reach(&e), 1.5625);
    // Never above the quad's bound.
    e.profile.line_reach_wide = [3.0, 3.0];
    assert_eq!(reach(&e), 1.5 + WIDE_OUTLINE_SHIFT);
    // GL_LINES: the 1-pixel figure, unchanged.
    e.kind = LineKind::Lines;
    e.line_width = 3.0;
    assert_eq!(reach(&e), 0.5 + LINE_REACH_MARGIN + 1.0);
}

/// Under MSAA a measured profile's multisampled reach, plus 1/16 and the rest of the width at
/// √2, replaces `√2·(w + 1)/2` where smaller, per line kind; unmeasured, the worst case.
#[test]
fn a_measured_msaa_reach_sets_the_multisampled_line_term() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.samples = 4;
    let reach = |e: &Edges| {
        recommend(&m, clip, e, EdgeMethod::Matrix)
            .unwrap()
            .line_reach
    };
    let root2 = std::f64::consts::SQRT_2;
    // Unmeasured (the worst case, or a measured profile without the figure): √2·(w + 1)/2.
    assert_eq!(reach(&e), root2);
    e.profile.measured = true;
    e.profile.line_reach = [0.5, 0.5];
    e.profile.outline_neighbour = 0.0;
    assert_eq!(reach(&e), root2);
    // Measured: the figure plus 1/16, the single-sampled figure unused.
    e.profile.line_reach_msaa = [1.0, 0.75];
    assert_eq!(reach(&e), 1.0625);
    // Width 3: the rest of the width at √2.
    e.line_width = 3.0;
    assert!((reach(&e) - (1.0625 + root2)).abs() < 1e-15);
    // Polygon mode: its own figure.
    e.kind = LineKind::PolygonMode;
    e.line_width = 1.0;
    assert_eq!(reach(&e), 0.8125);
    // Never above the worst case.
    e.profile.line_reach_msaa = [2.0, 2.0];
    assert_eq!(reach(&e), root2);
    e.kind = LineKind::Lines;
    assert_eq!(reach(&e), root2);
}

/// Under MSAA a face-slope angle bounds a face's whole gradient, and a sample lies within
/// `(w + 1)/2` of its line's point in any direction: the line term is `g·(w + 1)/2` where
/// `Δ` is larger (the worst case's `√2·(w + 1)/2`, a measured 1.12), the factor keeps `Δ`
/// (it multiplies each face's `max(|gₓ|, |g_y|)`), and a limit given as a gradient (on that
/// larger component) keeps `g·Δ`; a polygon-mode neighbour's part is capped alike;
/// single-sampled lines keep `g·Δ` under either limit.
#[test]
fn an_angle_limit_bounds_the_multisampled_line_term_by_the_whole_gradient() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.face_slope = FaceSlope::Angle(60f64.to_radians());
    let ask = |e: &Edges, method| recommend(&m, clip, e, method).unwrap();
    let root2 = std::f64::consts::SQRT_2;
    let relative = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b;
    for (samples, width, measured) in [(4, 1.0, false), (4, 3.0, false), (4, 1.0, true)] {
        e.samples = samples;
        e.line_width = width;
        e.profile.measured = measured;
        e.profile.line_reach_msaa = if measured { [1.056; 2] } else { [f64::NAN; 2] };
        let b = ask(&e, EdgeMethod::Matrix);
        let g = b.face_gradient;
        let delta = if measured {
            1.056 + 1.0 / 16.0
        } else {
            root2 * (width + 1.0) / 2.0
        };
        assert!(relative(b.line_reach, delta), "{b:?}");
        assert!(relative(b.line_term, g * (width + 1.0) / 2.0), "{b:?}");
        assert!(relative(
            ask(&e, EdgeMethod::PolygonOffset).polygon_offset[0],
            delta
        ));
        // The same g as a gradient limit bounds only the larger component: g·Δ.
        let mut by_gradient = e;
        by_gradient.face_slope = FaceSlope::WindowGradient(g);
        assert!(relative(
            ask(&by_gradient, EdgeMethod::Matrix).line_term,
            g * delta
        ));
    }
    // Polygon-mode lines in the worst case: the neighbour's outline adds its own part, also
    // within (w + 1)/2 of the sample against the whole gradient.
    e.line_width = 1.0;
    e.kind = LineKind::PolygonMode;
    e.profile.measured = false;
    let b = ask(&e, EdgeMethod::Matrix);
    assert!(relative(b.line_term, b.face_gradient * 2.0), "{b:?}");
    e.samples = 1;
    e.kind = LineKind::Lines;
    let b = ask(&e, EdgeMethod::Matrix);
    assert!(
        relative(b.line_term, b.face_gradient * b.line_reach),
        "{b:?}"
    );
}

/// Against an angle under MSAA a measured profile's whole-gradient reach sets how far a sample
/// lies from its line's point: the width-1 figure for 1-pixel lines, the width-3 figure for
/// wider ones plus half of any width beyond 3, each plus 1/16 and at most `(w + 1)/2`;
/// unmeasured, `(w + 1)/2`.
#[test]
fn measured_whole_gradient_reaches_set_the_multisampled_line_term() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.face_slope = FaceSlope::Angle(60f64.to_radians());
    e.samples = 4;
    e.profile.measured = true;
    e.profile.line_reach_msaa = [1.056; 2];
    let relative = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    let (whole, wide) = ([0.5, 0.6], [1.6, 1.65]);
    for kind in [LineKind::Lines, LineKind::PolygonMode] {
        e.kind = kind;
        let k = kind.index();
        for width in [1.0, 2.0, 3.0, 5.0] {
            e.line_width = width;
            let worst = (width + 1.0) / 2.0;
            let across = if width == 1.0 {
                worst.min(whole[k] + 1.0 / 16.0)
            } else {
                worst.min(wide[k] + 1.0 / 16.0 + (width - 3.0).max(0.0) / 2.0)
            };
            e.profile.line_reach_msaa_whole = [f64::NAN; 2];
            e.profile.line_reach_msaa_wide_whole = [f64::NAN; 2];
            let unmeasured = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
            e.profile.line_reach_msaa_whole = whole;
            e.profile.line_reach_msaa_wide_whole = wide;
            let b = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
            let g = b.face_gradient;
            // The face's own part is g·min(Δ, across); a polygon-mode neighbour's (its worst
            // case, which the probe does not measure) is the same either way.
            let own = |across: f64| g * b.line_reach.min(across);
            assert!(
                relative(b.line_term - unmeasured.line_term, own(across) - own(worst))
                    || own(across) == own(worst) && b.line_term == unmeasured.line_term,
                "{kind:?} width {width}: {} against {} unmeasured, across {across}",
                b.line_term,
                unmeasured.line_term
            );
            if kind == LineKind::Lines {
                assert!(relative(b.line_term, own(across)), "width {width}: {b:?}");
            }
        }
    }
}

/// Polygon-mode outlines with a measured neighbour: f32 noise leaves the neighbour's term out
/// (the outline's own reach, measured, plus 1/16); a rasterizer that evaluates the
/// triangle's plane beyond its side pays that distance for the face (the factor) and for the
/// neighbour (the units, scaled to the variant's worst case).
#[test]
fn a_measured_outline_neighbour_sets_the_neighbours_term() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.kind = LineKind::PolygonMode;
    e.profile.measured = true;
    e.profile.line_reach = [0.5, 0.5];
    e.profile.offset_slope = 1.0;
    let lines = Edges {
        kind: LineKind::Lines,
        ..e
    };
    let r_gl = 1.0 / (2f64.powi(24) - 1.0);
    let units = |e: &Edges| recommend(&m, clip, e, EdgeMethod::PolygonOffset).unwrap();
    // Noise: as GL_LINES of the same reach.
    e.profile.outline_neighbour = 6e-6;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert_eq!(r.line_reach, 0.5625);
    assert_eq!(r.line_term, 0.5625 * r.face_gradient);
    assert_eq!(units(&e).polygon_offset, units(&lines).polygon_offset);
    // A plane evaluated 0.75 pixel beyond the side: reach 0.8125 for the face, as much for
    // the neighbour (width 1, single-sampled: the worst case is 1 pixel).
    e.profile.outline_neighbour = 0.75;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    let g = r.face_gradient;
    assert_eq!(r.line_reach, 0.8125);
    assert!((r.line_term - 2.0 * 0.8125 * g).abs() < 1e-15 * g, "{r:?}");
    let a = units(&e);
    assert_eq!(a.polygon_offset[0], 0.8125);
    let extra = a.polygon_offset[1] - units(&lines).polygon_offset[1];
    assert!(
        (extra * r_gl - 0.8125 * g).abs() < 1e-9 * g,
        "{extra} units"
    );
    // Width 3: the outline keeps the wide quad's reach, the neighbour scales to it.
    e.line_width = 3.0;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    let wide = 2.0 + WIDE_OUTLINE_SHIFT;
    assert_eq!(r.line_reach, wide);
    let neighbour = r.line_term / r.face_gradient - wide;
    assert!((neighbour - wide * 0.8125).abs() < 1e-12, "{neighbour}");
}

/// (a): factor Δ, units (B + 2u(1 + w))/r; D3D rounded up; width 3 reaches 2 pixels.
#[test]
fn polygon_offset_factor_is_the_line_reach() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm16, [5.0, 50.0], clip);
    e.line_width = 3.0;
    let r = recommend(&m, clip, &e, EdgeMethod::PolygonOffset).unwrap();
    assert_eq!(r.polygon_offset[0], 2.0);
    assert_eq!(r.d3d_bias[1], 2.0);
    assert_eq!(r.d3d_bias[0], r.d3d_bias[0].ceil());
    let q = 1.0 / 65535.0;
    assert!(
        r.polygon_offset[1] > 0.0 && r.polygon_offset[1] < 2.0,
        "{r:?}"
    );
    assert!(r.polygon_offset[1] * q >= 2.0 * (r.terms.plane + r.terms.snap));
    assert_eq!(r.matrix, m);
}

/// A measured profile's reach, plus a sixteenth of a pixel, replaces `(w + 1)/2` (plus
/// `(w − 1)/2` for wide lines, single-sampled only, never above the worst case), and its
/// slope rule the worst case's `√2` in (a)'s push.
#[test]
fn a_measured_profile_supplies_the_reach_and_the_slope_rule() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    let worst = recommend(&m, clip, &e, EdgeMethod::PolygonOffset).unwrap();
    e.profile.measured = true;
    e.profile.line_reach = [0.5, 0.72];
    e.profile.offset_slope = 1.0;
    let r = recommend(&m, clip, &e, EdgeMethod::PolygonOffset).unwrap();
    assert_eq!((worst.line_reach, r.line_reach), (1.0, 0.5625));
    assert_eq!(r.polygon_offset[0], 0.5625);
    let g = r.face_gradient;
    // The worst case pushes with the largest known r (4 quanta); this profile measured its
    // own (the worst case's 1, kept).
    let units_push =
        (worst.window_offset - std::f64::consts::SQRT_2 * g) / LARGEST_KNOWN_RESOLVABLE;
    assert!(
        (r.window_offset - (0.5625 * g + units_push)).abs() < 1e-12,
        "{r:?}"
    );
    e.line_width = 3.0;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert!((r.line_reach - 1.5625).abs() < 1e-15);
    // Never above the worst case: a reach measured at 0.98 stays at (w + 1)/2.
    e.profile.line_reach = [0.98, 0.72];
    e.line_width = 1.0;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert_eq!(r.line_reach, 1.0);
    // Polygon-mode lines keep the worst case where the probe did not measure a neighbour's
    // outline, and under (a) their units also cover the line term (a neighbour's outline).
    e.profile.line_reach = [0.5, 0.5];
    assert!(e.profile.outline_neighbour.is_nan());
    e.kind = LineKind::PolygonMode;
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert_eq!(r.line_reach, 1.0);
    assert_eq!(r.line_term, 2.0 * r.face_gradient);
    let lines_a = recommend(
        &m,
        clip,
        &Edges {
            kind: LineKind::Lines,
            ..e
        },
        EdgeMethod::PolygonOffset,
    )
    .unwrap();
    let poly_a = recommend(&m, clip, &e, EdgeMethod::PolygonOffset).unwrap();
    let (g, r_gl) = (poly_a.face_gradient, 1.0 / (2f64.powi(24) - 1.0));
    let extra_units = poly_a.polygon_offset[1] - lines_a.polygon_offset[1];
    assert!(
        (extra_units * r_gl - g).abs() < 1e-9 * g,
        "{extra_units} units for a line term {g}"
    );
    e.line_width = 3.0;
    e.samples = 4;
    assert_eq!(e.kind, LineKind::PolygonMode);
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    // Polygon-mode outlines as GL_LINES (no `+ 1`: docs/edges.md).
    assert_eq!(r.line_reach, 2.0 * std::f64::consts::SQRT_2);
    let lines = Edges {
        kind: LineKind::Lines,
        ..e
    };
    let r = recommend(&m, clip, &lines, EdgeMethod::Matrix).unwrap();
    assert_eq!(r.line_reach, 2.0 * std::f64::consts::SQRT_2);
    // Under MSAA a sample lies up to (w/2)·√2 off the line along the face's gradient: the
    // reach covers it at every width.
    for w in [1.0, 2.5, 3.0, 10.0, 64.0] {
        e.line_width = w;
        let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
        assert!(
            r.line_reach >= w / 2.0 * std::f64::consts::SQRT_2 + 0.5,
            "{w}"
        );
    }
}

#[test]
fn refuses_where_the_gap_exceeds_the_separation_and_finds_planes() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(0.01, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm16, [50.0, 60.0], clip);
    e.face_slope = FaceSlope::WindowGradient(1e-9);
    let free = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    e.hidden_separation = free.hidden_gap * 0.5;
    let err = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Unresolvable);
    let [n, f] = working_planes(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert!(n > 40.0 && n <= 50.0 && f >= 60.0, "{n} {f}");
}

/// Under reversed Z (b) takes the relative ε of element 14 or a constant NDC offset through
/// element 10, whichever is smaller at the mesh's nearest depth. The line term `L` is the
/// same window error at every depth: where it dominates, the constant one (about `L`) beats
/// the relative one (`L·d₂/d₁` at `d₁`); on a thin depth range with a budget that falls
/// with depth, the relative one can win.
#[test]
fn reversed_matrix_offset_takes_the_smaller_form() {
    let clip = ClipDepth::ReversedZeroToOne;
    let m = matrix(0.1, f64::INFINITY, clip);
    let e = edges(DepthFormat::Float32, [10.0, 1000.0], clip);
    let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
    assert!(r.relative_epsilon == 0.0 && r.ndc_offset < 0.0);
    assert_eq!(r.matrix[14], m[14]);
    assert!(r.matrix[10] < m[10]);
    // The constant pays L once, with the shared budget and its own rounding: L + B to
    // within 2u, far below the relative form's L·d₂/d₁ = 100·L at d₁.
    let b = r.terms.budget();
    assert!(r.window_offset >= r.line_term + b, "{r:?}");
    assert!(r.window_offset <= (r.line_term + b) * (1.0 + 1e-6), "{r:?}");
    // The matrix moves window depth by the constant: −m10 is the depth at infinity.
    let moved = -(f64::from(r.matrix[10]) - f64::from(m[10]));
    assert!(
        moved >= r.window_offset && moved < 1.0001 * r.window_offset,
        "{moved}"
    );
}

#[test]
fn bad_inputs_name_their_field() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 100.0, clip);
    let mut e = edges(DepthFormat::Unorm24, [5.0, 50.0], clip);
    e.line_width = 0.5;
    let err = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap_err();
    assert_eq!(err.input().unwrap().0, "line_width");
    e.line_width = 1.0;
    e.face_slope = FaceSlope::Angle(2.0);
    let err = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap_err();
    assert_eq!(err.input().unwrap().0, "face_slope");
    e.face_slope = FaceSlope::Angle(1.0);
    e.depth_range = [50.0, 5.0];
    assert_eq!(
        recommend(&m, clip, &e, EdgeMethod::Matrix)
            .unwrap_err()
            .kind(),
        ErrorKind::Domain
    );
    // A mesh the near or far plane cuts: the remedy is named.
    for (range, needles) in [
        (
            [0.5, 50.0],
            ["near plane", "zshift_clip_to_frustum", "depth_near"],
        ),
        (
            [5.0, 500.0],
            ["far plane", "zshift_clip_to_frustum", "depth_far"],
        ),
    ] {
        e.depth_range = range;
        let said = recommend(&m, clip, &e, EdgeMethod::Matrix)
            .unwrap_err()
            .to_string();
        for needle in needles {
            assert!(said.contains(needle), "{said}");
        }
    }
}

/// The mesh's own faces: a gentle face and one beyond the angle's gradient; the offset pays
/// the gentle one (its line term is its gradient times the reach, not the angle's), the
/// steep one is counted beyond the limit, and under MSAA the line term is at most the
/// gradient length times (w + 1)/2.
#[test]
fn a_mesh_pays_for_its_own_faces_within_the_limit() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 1000.0, clip);
    let positions: [[f32; 3]; 6] = [
        [-1.0, -1.0, -10.0],
        [1.0, -1.0, -10.5],
        [0.0, 1.0, -10.0],
        [-1.0, -1.0, -10.0],
        [-0.98, -1.0, -14.0],
        [-1.0, 1.0, -10.0],
    ];
    let indices = [0, 1, 2, 3, 4, 5];
    let mesh = MeshDraw {
        clip_matrix: &m,
        positions: &positions,
        indices: &indices,
    };
    let mut e = Edges::new([512, 512], DepthFormat::Unorm24, [9.0, 15.0]);
    e.face_slope = FaceSlope::Angle(60f64.to_radians());
    for samples in [1, 4] {
        e.samples = samples;
        let by_angle = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
        let (by_mesh, faces) = recommend_for_mesh(&m, clip, &e, EdgeMethod::Matrix, &mesh).unwrap();
        let alone = crate::steepest_face::steepest_face(
            &m,
            clip,
            [512, 512],
            &positions[..3],
            &[0, 1, 2],
            f64::INFINITY,
        )
        .unwrap();
        assert_eq!(
            (faces.counted, faces.beyond_limit, faces.triangle),
            (1, 1, Some(0))
        );
        assert_eq!(
            (faces.gradient, faces.length),
            (alone.gradient, alone.length)
        );
        assert_eq!(by_mesh.face_gradient, faces.gradient);
        assert!(by_mesh.window_offset < by_angle.window_offset);
        let reach = line_reach(&e);
        if samples == 1 {
            assert_eq!(by_mesh.line_term, faces.gradient * reach);
        } else {
            let across = faces.length * (e.line_width + 1.0) / 2.0;
            assert_eq!(by_mesh.line_term, (faces.gradient * reach).min(across));
            assert!(by_mesh.line_term < faces.gradient * reach);
        }
    }
    // The faces are read by the call: a slope given as Faces is refused.
    e.face_slope = FaceSlope::Faces {
        max_component: 1e-3,
        length: 1e-3,
    };
    let err = recommend_for_mesh(&m, clip, &e, EdgeMethod::Matrix, &mesh).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Domain);
}

/// A width between integers is taken as GL may draw it (OpenGL's aliased lines round their
/// width to the nearest integer): the worst-case line reach at `w` is `(W + 1)/2` with
/// `W = max(w, ⌊w + ½⌋)` — 2.5 as 3, 2.4 as 2.4, 3.5 as 4 — for `GL_LINES` and polygon-mode
/// lines, single-sampled and multisampled alike.
#[test]
fn a_width_between_integers_is_taken_as_drawn() {
    let clip = ClipDepth::NegOneToOne;
    let m = matrix(1.0, 1000.0, clip);
    for (w, drawn) in [(2.5, 3.0), (2.4, 2.4), (3.5, 4.0), (1.2, 1.2), (1.5, 2.0)] {
        for (kind, extra) in [
            (LineKind::Lines, 0.0),
            (LineKind::PolygonMode, WIDE_OUTLINE_SHIFT),
        ] {
            let mut e = edges(DepthFormat::Unorm24, [10.0, 20.0], clip);
            e.kind = kind;
            e.line_width = w;
            let r = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
            // Polygon-mode outlines wider than 1 pixel add the wide-line quad's shift.
            let shift = if drawn > 1.0 { extra } else { 0.0 };
            assert_eq!(r.line_reach, (drawn + 1.0) / 2.0 + shift, "{kind:?} at {w}");
            e.samples = 4;
            let msaa = recommend(&m, clip, &e, EdgeMethod::Matrix).unwrap();
            let root2 = std::f64::consts::SQRT_2;
            assert!(
                (msaa.line_reach - root2 * (drawn + 1.0) / 2.0).abs() < 1e-12,
                "{kind:?} at {w} under MSAA: {}",
                msaa.line_reach
            );
        }
    }
}

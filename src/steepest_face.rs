//! The steepest face of a mesh as it is drawn: the window-depth gradient an engine passes as
//! [`crate::lines::FaceSlope::WindowGradient`] for its own mesh, instead of the gradient a
//! face-slope angle allows ([`crate::lines::recommend_for_mesh`] reads it and passes it on,
//! with the largest gradient length, as [`crate::lines::FaceSlope::Faces`]).
//!
//! A matrix offset for edges (and the polygon-offset push that sets the hidden-line gap) pays
//! the line term `L = g·Δ` for the steepest face that matters ([`crate::lines`], "The line
//! term"). Given as an angle, `g` is the gradient of a face at that angle at the mesh's nearest
//! depth: a UV sphere has such faces, a terrain of gentle hills or a box seen from a corner has
//! none, and pays for them (measured on llvmpipe, `tests/gl_lines.rs`: the offset was 7.7× the
//! smallest working one on the terrain under 4× MSAA, 1.4× on the sphere). The engine knows its
//! triangles and its matrix; this computes each triangle's window-depth gradient exactly from
//! them and returns the largest below a limit.
//!
//! # The gradient of one triangle
//! A triangle's clip-space vertices `c₀, c₁, c₂` (the matrix times the f32 positions, in f64)
//! span a 3-dimensional subspace of clip space: every clip point of its plane is `a·c = 0`, `a`
//! the generalised cross product of `c₀, c₁ − c₀, c₂ − c₀` (the signed 3×3 minors). Dividing by
//! `w`, the NDC point `(X, Y, Z)` satisfies `a₀X + a₁Y + a₂Z + a₃ = 0`, so window depth is the
//! plane
//!
//! `∂z_w/∂x_w = −(a₀/a₂)·(2/W)·k`,  `∂z_w/∂y_w = −(a₁/a₂)·(2/H)·k`,
//!
//! `W × H` the viewport, `k` the NDC-to-window depth scale (1/2 under `[−1, 1]`, 1 under `[0, 1]`
//! and reversed Z; `glDepthRange(0, 1)`: the unit [`crate::lines`] counts gradients in). No
//! division by `w`, so a triangle that crosses the camera's plane has its gradient too; `a₂ = 0`
//! is a triangle seen edge-on (a line on screen, no pixels). The gradient reported is
//! `max(|∂z_w/∂x_w|, |∂z_w/∂y_w|)`, what `glPolygonOffset`'s factor multiplies and
//! [`crate::lines::FaceSlope::WindowGradient`] takes.
//!
//! # Which faces count
//! * A triangle whose three vertices lie outside the same clip plane (`x < −w`, `x > w`, the
//!   same in `y`, in front of the near plane, beyond the far plane) draws nothing, nor does one
//!   with no area on screen (`a₂ = 0`, or its vertices on one line): **culled**.
//! * A triangle whose gradient exceeds `limit` is grazing, a few pixels wide where the rest of
//!   the mesh is large; its edges are not guaranteed (the engine's choice, as a face-slope angle
//!   is): **beyond the limit**. An engine that sets its limit by an angle passes the
//!   [`crate::lines::EdgeRecommendation::face_gradient`] that angle gives, so every face the
//!   angle covers still counts.
//! * Every other triangle **counts**; the result is the largest gradient among them, and
//!   `FaceSlope::WindowGradient(gradient)` then keeps the edges of every one of them.
//!
//! Back faces are not culled (the engine's culling is not known here; an open mesh shows both
//! sides).

use crate::domain::domain;
use crate::error::{Error, ErrorKind, Result};
use crate::projection::ClipDepth;

/// The steepest face of a mesh under a matrix and viewport ([`steepest_face`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteepestFace {
    /// `max(|∂z_w/∂x_w|, |∂z_w/∂y_w|)` of the steepest face that counts (window depth in
    /// `[0, 1]` per pixel), 0 when none counts: pass it as
    /// [`crate::lines::FaceSlope::WindowGradient`].
    pub gradient: f64,
    /// The largest length `√((∂z_w/∂x_w)² + (∂z_w/∂y_w)²)` of a face that counts (of any face:
    /// not necessarily the one of `gradient`), 0 when none counts. Multisampled lines take their
    /// depth up to `(w + 1)/2` pixels away in any direction, which this bounds
    /// ([`crate::lines::FaceSlope::Faces`]).
    pub length: f64,
    /// That face: its first index's position in `indices`, divided by 3; `None` when none counts.
    pub triangle: Option<usize>,
    /// Triangles that count (drawn, within the limit).
    pub counted: usize,
    /// Triangles drawn but steeper than the limit (grazing; their edges not guaranteed).
    pub beyond_limit: usize,
    /// Triangles that draw nothing: outside one clip plane, or no area on screen.
    pub culled: usize,
}

/// The steepest face of the triangles `indices` (three per triangle) over `positions`, drawn
/// through `clip_matrix` (the whole `projection · view · model`, column-major f32, as the vertex
/// shader applies it) under `clip` into a viewport of `viewport` pixels: the largest window-depth
/// gradient `max(|∂z_w/∂x_w|, |∂z_w/∂y_w|)` of a drawn triangle whose gradient is at most
/// `limit` (module docs; `f64::INFINITY` counts every drawn triangle). Computed in f64 from the
/// f32 inputs, exactly up to f64 rounding (relative `~10⁻¹⁵` times the triangle's size over its
/// distance from the camera).
///
/// # Errors
/// [`ErrorKind::Domain`] for a viewport with a zero side, `indices` not a multiple of 3, an index
/// past `positions` (the detail names the index's place), or `limit` NaN or negative;
/// [`ErrorKind::NotFinite`] for a NaN or infinite matrix element or position (named by place).
pub fn steepest_face(
    clip_matrix: &[f32; 16],
    clip: ClipDepth,
    viewport: [u32; 2],
    positions: &[[f32; 3]],
    indices: &[u32],
    limit: f64,
) -> Result<SteepestFace> {
    check(clip_matrix, viewport, positions, indices, limit)?;
    let m = clip_matrix.map(f64::from);
    let k = match clip {
        ClipDepth::NegOneToOne => 0.5,
        ClipDepth::ZeroToOne | ClipDepth::ReversedZeroToOne => 1.0,
    };
    let scale = [
        2.0 * k / f64::from(viewport[0]),
        2.0 * k / f64::from(viewport[1]),
    ];
    let mut out = SteepestFace {
        gradient: 0.0,
        length: 0.0,
        triangle: None,
        counted: 0,
        beyond_limit: 0,
        culled: 0,
    };
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        let c = [0, 1, 2].map(|i| to_clip(&m, positions[tri[i] as usize]));
        let gradient = if outside_one_plane(&c, clip) {
            None
        } else {
            window_gradient(&c, scale)
        };
        match gradient {
            None => out.culled += 1,
            Some((g, _)) if g > limit => out.beyond_limit += 1,
            Some((g, length)) => {
                out.counted += 1;
                out.length = out.length.max(length);
                if out.triangle.is_none() || g > out.gradient {
                    out.gradient = g;
                    out.triangle = Some(t);
                }
            }
        }
    }
    Ok(out)
}

fn check(
    m: &[f32; 16],
    viewport: [u32; 2],
    positions: &[[f32; 3]],
    indices: &[u32],
    limit: f64,
) -> Result<()> {
    if viewport.contains(&0) {
        return Err(
            domain("the viewport's width and height must be nonzero").with_integer(
                if viewport[0] == 0 {
                    "viewport_width"
                } else {
                    "viewport_height"
                },
                0,
            ),
        );
    }
    if limit.is_nan() || limit < 0.0 {
        return Err(domain(
            "limit (the largest window gradient that counts) must be >= 0 (infinity: every face)",
        )
        .with_value("limit", limit));
    }
    if let Some(i) = m.iter().position(|x| !x.is_finite()) {
        return Err(
            Error::new(ErrorKind::NotFinite, "a matrix element is NaN or infinite")
                .for_item("clip_matrix", i as u32),
        );
    }
    if let Some(i) = positions
        .iter()
        .position(|p| p.iter().any(|x| !x.is_finite()))
    {
        return Err(
            Error::new(ErrorKind::NotFinite, "a vertex position is NaN or infinite")
                .for_item("positions", u32::try_from(i).unwrap_or(u32::MAX)),
        );
    }
    if indices.len() % 3 != 0 {
        return Err(domain(
            "indices must hold three per triangle (a multiple of 3; GL_TRIANGLES order)",
        )
        .with_integer("index_count", indices.len() as i64));
    }
    if let Some(i) = indices.iter().position(|&v| v as usize >= positions.len()) {
        return Err(domain("an index is past the last vertex position")
            .for_item("indices", u32::try_from(i).unwrap_or(u32::MAX))
            .with_integer("vertex_count", positions.len() as i64));
    }
    Ok(())
}

/// `m · (p, 1)` in f64 (each product of two f32 is exact).
fn to_clip(m: &[f64; 16], p: [f32; 3]) -> [f64; 4] {
    let [x, y, z] = p.map(f64::from);
    [0, 1, 2, 3].map(|r| m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r])
}

/// All three vertices outside the same one of the six clip planes: the triangle draws nothing.
fn outside_one_plane(c: &[[f64; 4]; 3], clip: ClipDepth) -> bool {
    // Each vertex's outcode (a bit per plane it lies outside); a plane all three share culls.
    let outcode = |v: &[f64; 4]| {
        let low_z = match clip {
            ClipDepth::NegOneToOne => v[2] < -v[3],
            ClipDepth::ZeroToOne | ClipDepth::ReversedZeroToOne => v[2] < 0.0,
        };
        [
            v[0] < -v[3],
            v[0] > v[3],
            v[1] < -v[3],
            v[1] > v[3],
            low_z,
            v[2] > v[3],
        ]
        .iter()
        .enumerate()
        .fold(0u8, |bits, (i, &out)| bits | (u8::from(out) << i))
    };
    c.iter()
        .map(outcode)
        .fold(0b11_1111, |all, bits| all & bits)
        != 0
}

/// `max(|∂z_w/∂x_w|, |∂z_w/∂y_w|)` and the length of the gradient of the plane through clip
/// points `c` (module docs), `None` for a triangle with no area on screen.
fn window_gradient(c: &[[f64; 4]; 3], scale: [f64; 2]) -> Option<(f64, f64)> {
    let d1 = [0, 1, 2, 3].map(|i| c[1][i] - c[0][i]);
    let d2 = [0, 1, 2, 3].map(|i| c[2][i] - c[0][i]);
    let rows = [c[0], d1, d2];
    // a_k = (−1)^k · det of the rows without column k; only a₀, a₁, a₂ are needed.
    let minor = |skip: usize| {
        let cols = [0, 1, 2].map(|j| if j < skip { j } else { j + 1 });
        let e = |r: usize, j: usize| rows[r][cols[j]];
        e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
            - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
            + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0))
    };
    let (a0, a1, a2) = (minor(0), minor(1), minor(2));
    if a2 == 0.0 {
        return None;
    }
    let (gx, gy) = ((a0 / a2 * scale[0]).abs(), (a1 / a2 * scale[1]).abs());
    let g = gx.max(gy);
    g.is_finite().then(|| (g, gx.hypot(gy)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::{projection, Frustum};

    fn matrix(clip: ClipDepth) -> [f32; 16] {
        projection(
            &Frustum::new(-0.5, 0.5, -0.3, 0.3, 1.0, 1000.0).unwrap(),
            clip,
        )
        .unwrap()
    }

    /// The reference: project each vertex to window coordinates (divide by w, f64), then the
    /// plane z_w(x_w, y_w) through the three, as the GL sweep's reference does.
    fn projected_gradient(m: &[f32; 16], clip: ClipDepth, vp: [u32; 2], t: [[f32; 3]; 3]) -> f64 {
        projected(m, clip, vp, t).0
    }

    /// The reference's larger component and length.
    fn projected(m: &[f32; 16], clip: ClipDepth, vp: [u32; 2], t: [[f32; 3]; 3]) -> (f64, f64) {
        let mf = m.map(f64::from);
        let win = t.map(|p| {
            let c = to_clip(&mf, p);
            let (x, y, z) = (c[0] / c[3], c[1] / c[3], c[2] / c[3]);
            let zw = if clip == ClipDepth::NegOneToOne {
                (z + 1.0) / 2.0
            } else {
                z
            };
            [
                (x + 1.0) / 2.0 * f64::from(vp[0]),
                (y + 1.0) / 2.0 * f64::from(vp[1]),
                zw,
            ]
        });
        let [a, b, c] = win;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let gx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / area;
        let gy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / area;
        (gx.abs().max(gy.abs()), gx.hypot(gy))
    }

    #[test]
    fn matches_the_projected_plane_on_random_triangles() {
        let mut u = crate::test_uniform(0x5EED_FACE);
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let m = matrix(clip);
            for _ in 0..2000 {
                let d = 2.0 + 500.0 * u();
                let size = d * (0.001 + 0.05 * u());
                let centre = [(u() - 0.5) * 0.8 * d, (u() - 0.5) * 0.5 * d, -d];
                let t =
                    [0, 1, 2].map(|_| [0, 1, 2].map(|i| (centre[i] + size * (u() - 0.5)) as f32));
                let r =
                    steepest_face(&m, clip, [1920, 1080], &t, &[0, 1, 2], f64::INFINITY).unwrap();
                let reference = projected(&m, clip, [1920, 1080], t);
                if r.counted == 1 {
                    let rel = (r.gradient - reference.0).abs() / reference.0;
                    assert!(
                        rel < 1e-7,
                        "{clip:?} {t:?}: {} vs {reference:?}",
                        r.gradient
                    );
                    let rel = (r.length - reference.1).abs() / reference.1;
                    assert!(rel < 1e-7, "{clip:?} {t:?}: {} vs {reference:?}", r.length);
                }
            }
        }
    }

    #[test]
    fn a_facing_triangle_is_flat_and_an_edge_on_one_is_culled() {
        let m = matrix(ClipDepth::NegOneToOne);
        let facing = [[-1.0, -1.0, -10.0], [1.0, -1.0, -10.0], [0.0, 1.0, -10.0]];
        let r = steepest_face(
            &m,
            ClipDepth::NegOneToOne,
            [640, 480],
            &facing,
            &[0, 1, 2],
            1.0,
        )
        .unwrap();
        assert_eq!((r.gradient, r.counted, r.triangle), (0.0, 1, Some(0)));
        // In the plane x = 0, which contains the camera: a line on screen.
        let edge_on = [[0.0, -1.0, -10.0], [0.0, 1.0, -10.0], [0.0, 0.0, -20.0]];
        let r = steepest_face(
            &m,
            ClipDepth::NegOneToOne,
            [640, 480],
            &edge_on,
            &[0, 1, 2],
            1.0,
        )
        .unwrap();
        assert_eq!((r.counted, r.culled, r.triangle), (0, 1, None));
    }

    #[test]
    fn culls_what_lies_outside_one_plane_and_counts_what_crosses() {
        let clip = ClipDepth::ZeroToOne;
        let m = matrix(clip);
        let behind = [[-1.0, 0.0, 5.0], [1.0, 0.0, 5.0], [0.0, 1.0, 6.0]];
        let beyond_far = [
            [-1.0, 0.0, -2000.0],
            [1.0, 0.0, -2000.0],
            [0.0, 1.0, -2100.0],
        ];
        // A ground under the camera, from behind it to far ahead: crosses the near plane.
        let ground = [[-50.0, -1.7, 10.0], [50.0, -1.7, 10.0], [0.0, -1.7, -500.0]];
        let positions: Vec<[f32; 3]> = [behind, beyond_far, ground].concat();
        let indices: Vec<u32> = (0..9).collect();
        let r = steepest_face(&m, clip, [800, 600], &positions, &indices, f64::INFINITY).unwrap();
        assert_eq!((r.counted, r.culled, r.triangle), (1, 2, Some(2)));
        assert!(r.gradient > 0.0 && r.gradient.is_finite());
    }

    #[test]
    fn the_limit_leaves_grazing_faces_out() {
        let clip = ClipDepth::NegOneToOne;
        let m = matrix(clip);
        let gentle = [[-1.0, -1.0, -10.0], [1.0, -1.0, -10.5], [0.0, 1.0, -10.0]];
        let steep = [[-1.0, -1.0, -10.0], [-0.9, -1.0, -30.0], [-1.0, 1.0, -10.0]];
        let positions: Vec<[f32; 3]> = [gentle, steep].concat();
        let indices: Vec<u32> = (0..6).collect();
        let vp = [512, 512];
        let (g_gentle, g_steep) = (
            projected_gradient(&m, clip, vp, gentle),
            projected_gradient(&m, clip, vp, steep),
        );
        assert!(g_steep > 10.0 * g_gentle);
        let all = steepest_face(&m, clip, vp, &positions, &indices, f64::INFINITY).unwrap();
        assert_eq!((all.triangle, all.counted), (Some(1), 2));
        let limited = steepest_face(&m, clip, vp, &positions, &indices, 2.0 * g_gentle).unwrap();
        assert_eq!(
            (limited.triangle, limited.counted, limited.beyond_limit),
            (Some(0), 1, 1)
        );
        assert!((limited.gradient - g_gentle).abs() < 1e-9 * g_gentle);
    }

    /// A face at the angle's limit, on the view axis at the mesh's nearest depth, is within the
    /// gradient that angle gives (the angle's bound takes the off-axis tilt beyond it).
    #[test]
    fn a_face_at_the_angle_is_within_the_angles_gradient() {
        use crate::lines::{recommend, EdgeMethod, Edges, FaceSlope};
        let clip = ClipDepth::NegOneToOne;
        let m = matrix(clip);
        let (d, a) = (20.0f64, 60f64.to_radians());
        // A square tilted by a about y, centred on the axis at depth d.
        let (c, s) = (a.cos(), a.sin());
        let corner = |u: f64, v: f64| [(u * c) as f32, v as f32, (-d - u * s) as f32];
        let square = [corner(-0.5, -0.5), corner(0.5, -0.5), corner(0.0, 0.5)];
        let vp = [1024, 1024];
        let face = steepest_face(&m, clip, vp, &square, &[0, 1, 2], f64::INFINITY).unwrap();
        let mut edges = Edges::new(
            vp,
            crate::precision::DepthFormat::Unorm24,
            [d - 1.0, d + 1.0],
        );
        edges.face_slope = FaceSlope::Angle(a);
        let g = recommend(&m, clip, &edges, EdgeMethod::Matrix)
            .unwrap()
            .face_gradient;
        assert!(face.gradient <= g, "{} vs {g}", face.gradient);
        // On the axis: one pixel is ((r − l)/W)·d/n of eye x, the face deepens
        // by tan a of it, and window depth moves F·n/d² per unit of depth: F·tan a·ex/d.
        let f_over_span = 1000.0 / 999.0;
        let on_axis = f_over_span * a.tan() * (1.0 / 1024.0) / d;
        assert!(
            (face.gradient / on_axis - 1.0).abs() < 0.05,
            "{} vs {on_axis}",
            face.gradient
        );
    }

    #[test]
    fn bad_inputs_are_named() {
        let m = matrix(ClipDepth::NegOneToOne);
        let t = [[0.0, 0.0, -5.0], [1.0, 0.0, -5.0], [0.0, 1.0, -5.0]];
        let run = |m: &[f32; 16], vp: [u32; 2], p: &[[f32; 3]], i: &[u32], limit: f64| {
            steepest_face(m, ClipDepth::NegOneToOne, vp, p, i, limit).unwrap_err()
        };
        let e = run(&m, [0, 10], &t, &[0, 1, 2], 1.0);
        assert_eq!(
            (e.kind(), e.input().unwrap().0),
            (ErrorKind::Domain, "viewport_width")
        );
        let e = run(&m, [10, 10], &t, &[0, 1], 1.0);
        assert_eq!(e.input().unwrap().0, "index_count");
        let e = run(&m, [10, 10], &t, &[0, 1, 3], 1.0);
        assert!(e.to_string().contains("indices"), "{e}");
        let e = run(&m, [10, 10], &t, &[0, 1, 2], f64::NAN);
        assert_eq!(e.input().unwrap().0, "limit");
        let mut nan = t;
        nan[1][2] = f32::NAN;
        let e = run(&m, [10, 10], &nan, &[0, 1, 2], 1.0);
        assert_eq!(e.kind(), ErrorKind::NotFinite);
        assert!(e.to_string().contains("positions"), "{e}");
        let mut bad = m;
        bad[5] = f32::INFINITY;
        let e = run(&bad, [10, 10], &t, &[0, 1, 2], 1.0);
        assert!(e.to_string().contains("clip_matrix"), "{e}");
    }
}

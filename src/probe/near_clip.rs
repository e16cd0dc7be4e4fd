//! Near-plane clipping (the model's `C`, [`crate::model::clip`]): whether a clipped plane keeps
//! its depth (`near_clip`) and the clipper's roundings (`clip_ulps`).

use super::*;
use crate::projection::ClipDepth;

/// How a triangle crossing the near plane keeps its depth (module docs): each ground plane is
/// drawn twice, once as given (the rasterizer clips it) and once clipped by the probe in f64 at
/// twice the near distance (nothing left for the rasterizer to clip); on the pixels both cover,
/// each is compared with the plane of the coordinates it was given (D24 quanta). Returns the
/// verdict and the two worst errors.
pub(super) unsafe fn near_clip(
    gl: &Gl,
    o: &Objects,
    snapping: Snapping,
) -> Result<(NearClip, f64, f64, f64)> {
    let view = NEAR_VIEW;
    let grounds = near_grounds();
    let given = grounds.iter().map(|g| Scene {
        matrix: view.matrix(),
        triangles: vec![View::triangle(*g)],
    });
    let preclipped = grounds.iter().map(|g| Scene {
        matrix: view.matrix(),
        triangles: clip_in_f64(*g, 2.0 * view.n)
            .into_iter()
            .map(View::triangle)
            .collect(),
    });
    // The clipper's figure, under every depth convention the context has: `[−1, 1]`, and with
    // `glClipControl` also `[0, 1]` and reversed Z (0.84, 0.86 and 0.22 on llvmpipe). The model
    // takes the largest, a sampled maximum, with a margin (crate::model::clip).
    let mut clip_ulps = clipper_figure(gl, o, ClipDepth::NegOneToOne, snapping)?;
    if let Some(clip_control) = gl.ClipControl {
        clip_control(LOWER_LEFT, ZERO_TO_ONE);
        let others = clipper_figure(gl, o, ClipDepth::ZeroToOne, snapping).and_then(|z| {
            Ok(z.max(clipper_figure(
                gl,
                o,
                ClipDepth::ReversedZeroToOne,
                snapping,
            )?))
        });
        clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
        clip_ulps = clip_ulps.max(others?);
    }
    let (mut worst_given, mut worst_preclipped) = (0.0f64, 0.0f64);
    let scenes: Vec<Scene> = given.chain(preclipped).collect();
    let stored = draw_tiles(gl, o, Format::Unorm(24), &scenes)?;
    let count = grounds.len();
    for i in 0..count {
        let given_errors = pixel_errors(&scenes[i], &stored[i], false);
        let preclipped_errors = pixel_errors(&scenes[count + i], &stored[count + i], false);
        clip_ulps = clip_ulps.max(clipper_ulps(
            ClipDepth::NegOneToOne,
            &grounds[i],
            &scenes[i],
            &stored[i],
            &preclipped_errors,
            snapping,
        ));
        let both: Vec<(f64, f64)> = given_errors
            .iter()
            .zip(&preclipped_errors)
            .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
            .collect();
        if both.len() < SIZE * SIZE / 8 {
            return Err(Error::new(
                ErrorKind::Gl,
                "a near-clipped ground plane covered less than an eighth of its tile: the \
                 rasterizer drew something else than the probe's triangles",
            ));
        }
        for (a, b) in both {
            worst_given = worst_given.max(a);
            worst_preclipped = worst_preclipped.max(b);
        }
    }
    let clip = if worst_given <= 2.0 * worst_preclipped + 2.0 {
        NearClip::PlanePreserving
    } else {
        NearClip::ClippedF32
    };
    Ok((clip, worst_given, worst_preclipped, clip_ulps))
}

/// The clipper's figure under `clip` (the caller has set `glClipControl` to match): the ground
/// planes through the two off-centre frusta and planes in random directions (slopes 0.3 to 10,
/// crossing the view axis 1 to 40 units ahead, reaching 100 times that behind and ahead)
/// through all three frusta, each drawn as given (the rasterizer clips it) and cut to the
/// frustum in f64 first (nothing left for the rasterizer to clip): the largest
/// [`clipper_ulps`]. At most `TILES²` tiles a draw.
unsafe fn clipper_figure(gl: &Gl, o: &Objects, clip: ClipDepth, snapping: Snapping) -> Result<f64> {
    let random = random_clipped_grounds();
    let views: Vec<[f64; 4]> = std::iter::once(CENTRED_NEAR_SIDES)
        .chain(SKEWED_NEAR_SIDES)
        .collect();
    let planes: Vec<([[f64; 3]; 3], [f64; 4])> = near_grounds()
        .into_iter()
        .flat_map(|g| SKEWED_NEAR_SIDES.iter().map(move |m| (g, *m)))
        .chain(
            random
                .iter()
                .enumerate()
                .map(|(i, g)| (*g, views[i % views.len()])),
        )
        .collect();
    let zero_to_one = clip != ClipDepth::NegOneToOne;
    let mut figure = 0.0f64;
    for batch in planes.chunks(TILES * TILES / 2) {
        let mut scenes = Vec::with_capacity(2 * batch.len());
        for (g, sides) in batch {
            let matrix = near_view_matrix(*sides, clip);
            scenes.push(Scene {
                matrix,
                triangles: vec![View::triangle(*g)],
            });
            scenes.push(Scene {
                matrix,
                triangles: cut_to_frustum(*g, *sides)
                    .into_iter()
                    .map(View::triangle)
                    .collect(),
            });
        }
        let stored = draw_tiles(gl, o, Format::Unorm(24), &scenes)?;
        for (i, (ground, _)) in batch.iter().enumerate() {
            let unclipped = pixel_errors(&scenes[2 * i + 1], &stored[2 * i + 1], zero_to_one);
            figure = figure.max(clipper_ulps(
                clip,
                ground,
                &scenes[2 * i],
                &stored[2 * i],
                &unclipped,
                snapping,
            ));
        }
    }
    Ok(figure)
}

/// The clipper's error on one ground drawn as given, in the model's own units
/// ([`RasterizerProfile::clip_ulps`]) under `clip`: the largest
/// `(|stored − exact| − e − q)⁺·d / (c·2⁻²⁴·L(A))` over the pixels (`c` the window depth per NDC
/// unit: ½ under `[−1, 1]`, 1 under `[0, 1]` and reversed Z), `e` the error at the same pixel of the same ground cut to the frustum in
/// f64 before drawing (`unclipped`: what the rasterizer errs without clipping), `d` the pixel's
/// eye depth, `q` one D24 quantum of conversion (and, on a rasterizer that snaps to `2⁻ᵇ`
/// pixel, `2S = 2⁻ᵇ·(|gₓ| + |g_y|)` of the plane: the clipped and the pre-cut ground's vertices
/// snap differently, and the model's `S` carries snapping, not `C`), `A` the
/// magnitudes of the ground's clip coordinates for its reach `R` (the largest eye coordinate of
/// its corners: `A = ((|m0| + |m8|)·R, (|m5| + |m9|)·R, |m10|·R + |m14|, R)`), and `L` the
/// ground plane's form on clip coordinates (`|aₓ|·A_x + |a_y|·A_y + A_z + |a₀|·A_w`, `aₓ`, `a_y`,
/// `a₀` its NDC depth plane) — the model's term `C` with `clip_ulps·u` for its `γ`.
pub(super) fn clipper_ulps(
    clip: ClipDepth,
    ground: &[[f64; 3]; 3],
    scene: &Scene,
    stored: &[f64],
    unclipped: &[Option<f64>],
    snapping: Snapping,
) -> f64 {
    let reach = ground.iter().flatten().fold(0.0f64, |a, c| a.max(c.abs()));
    let m = scene.matrix.map(f64::from);
    let a = crate::model::clip::clip_magnitudes(&m, reach);
    let zero_to_one = clip != ClipDepth::NegOneToOne;
    let Some(plane) = scene
        .exact()
        .first()
        .map(|t| Plane::with_mapping(t, zero_to_one))
    else {
        return 0.0;
    };
    let view = View {
        reversed: clip == ClipDepth::ReversedZeroToOne,
        ..NEAR_VIEW
    };
    // The NDC depth plane z_n = a₀ + aₓ·xₙ + a_y·yₙ, read off the exact plane's window depth
    // (½·z_n + ½ under [−1, 1], z_n under [0, 1]) at three tile points: NDC (0, 0), (1, 0) and
    // (0, 1) are tile pixels SIZE/2 and SIZE.
    let half = SIZE as f64 / 2.0;
    let window_per_ndc = if zero_to_one { 1.0 } else { 0.5 };
    let ndc = |x: f64, y: f64| (plane.extended(x, y) - (1.0 - window_per_ndc)) / window_per_ndc;
    let a0 = ndc(half, half);
    let (ax, ay) = (ndc(2.0 * half, half) - a0, ndc(half, 2.0 * half) - a0);
    let l = a[2] + ax.abs() * a[0] + ay.abs() * a[1] + a0.abs() * a[3];
    let q = Format::Unorm(24).quantum(0.5);
    let unit = window_per_ndc * l / 16_777_216.0;
    // Both grounds' snapping, at most the model's `S` each, from the plane's window gradient
    // per pixel.
    let origin = plane.extended(0.0, 0.0);
    let gradient = [
        plane.extended(1.0, 0.0) - origin,
        plane.extended(0.0, 1.0) - origin,
    ];
    let snaps = 2.0 * crate::model::snap::snap(snapping, gradient, 1.0);
    (0..SIZE * SIZE)
        .filter_map(|i| {
            let exact = plane.depth_inside(i % SIZE, i / SIZE)?;
            let own = unclipped[i]? * q;
            let d = view.distance_at_depth(exact);
            Some(((stored[i] - exact).abs() - own - q - snaps).max(0.0) * d / unit)
        })
        .fold(0.0, f64::max)
}

/// Per pixel of a tile, `|stored − exact|` in D24 quanta against the first of the scene's
/// triangles that covers it (by [`Plane::depth_inside`]), or `None`; `zero_to_one` for NDC
/// depth stored as is (`glClipControl(GL_ZERO_TO_ONE)`).
pub(super) fn pixel_errors(scene: &Scene, stored: &[f64], zero_to_one: bool) -> Vec<Option<f64>> {
    let planes: Vec<Plane> = scene
        .exact()
        .iter()
        .map(|t| Plane::with_mapping(t, zero_to_one))
        .collect();
    let q = Format::Unorm(24).quantum(0.5);
    (0..SIZE * SIZE)
        .map(|i| {
            let exact = planes
                .iter()
                .find_map(|p| p.depth_inside(i % SIZE, i / SIZE))?;
            Some((stored[i] - exact).abs() / q)
        })
        .collect()
}

/// Planes in random directions for [`near_clip`]'s clipper figure: slopes 0.3, 1, 3 and 10 in
/// random directions, crossing the view axis 1 to 40 units ahead, each a triangle holding the
/// disc of radius 100 times that distance around the axis point (so it runs behind the camera).
pub(super) fn random_clipped_grounds() -> Vec<[[f64; 3]; 3]> {
    let mut next = uniform_stream(0x0C11_2026_1126);
    (0..48)
        .map(|i| {
            let slope = [0.3, 1.0, 3.0, 10.0][i % 4];
            let angle = std::f64::consts::TAU * next();
            let (sx, sy) = (slope * angle.cos(), slope * angle.sin());
            let d = 10f64.powf(1.6 * next());
            let reach = 100.0 * d;
            let on = |x: f64, y: f64| [x, y, -d + sx * x + sy * y];
            [
                on(-1.8 * reach, reach),
                on(1.8 * reach, reach),
                on(0.0, -2.0 * reach),
            ]
        })
        .collect()
}

/// The near-clip view's sides `(l, r, b, t)` on its near plane (n = 0.1, f = 1000).
pub(super) const CENTRED_NEAR_SIDES: [f64; 4] = [-0.1, 0.1, -0.05625, 0.05625];

/// Off-centre sides with the near-clip view's `n` and `f`: the view axis on screen, off its
/// centre, and the view axis off the screen.
pub(super) const SKEWED_NEAR_SIDES: [[f64; 4]; 2] =
    [[-0.04, 0.13, -0.067, 0.034], [0.015, 0.16, 0.006, 0.062]];

/// `glFrustum(l, r, b, t, 0.1, 1000)` in f64 with the depth row of `clip` (`[0, 1]`:
/// `−f/(f − n)`, `−f·n/(f − n)`; reversed: `n/(f − n)`, `f·n/(f − n)`), each element rounded to
/// f32 (column-major).
pub(super) fn near_view_matrix([l, r, b, t]: [f64; 4], clip: ClipDepth) -> [f32; 16] {
    let (n, f) = (NEAR_VIEW.n, NEAR_VIEW.f);
    let (m10, m14) = depth_row(n, f, clip);
    [
        2.0 * n / (r - l),
        0.0,
        0.0,
        0.0,
        0.0,
        2.0 * n / (t - b),
        0.0,
        0.0,
        (r + l) / (r - l),
        (t + b) / (t - b),
        m10,
        -1.0,
        0.0,
        0.0,
        m14,
        0.0,
    ]
    .map(|x| x as f32)
}

/// The part of eye-space triangle `t` inside the frustum of `sides` (n = 0.1, f = 1000), cut
/// in f64 by [`crate::recommend::clip_to_frustum`], as a fan of triangles.
pub(super) fn cut_to_frustum(t: [[f64; 3]; 3], [l, r, b, tp]: [f64; 4]) -> Vec<[[f64; 3]; 3]> {
    let Ok(frustum) = crate::projection::Frustum::new(l, r, b, tp, NEAR_VIEW.n, NEAR_VIEW.f) else {
        return Vec::new();
    };
    let polygon = crate::recommend::clip_to_frustum(&frustum, &t).unwrap_or_default();
    (2..polygon.len())
        .map(|i| [polygon[0], polygon[i - 1], polygon[i]])
        .collect()
}

/// The near-clip scenes' view: `glFrustum(−0.1, 0.1, −0.05625, 0.05625, 0.1, 1000)` (16:9).
pub(super) const NEAR_VIEW: View = View {
    e: 1.0,
    n: 0.1,
    f: 1000.0,
    reversed: false,
    squash: 0.5625,
};

/// Ground planes whose triangles reach 1000 (or 10⁴) units behind and ahead of the camera, as
/// eye-space corners: sloped ones seen from 10 units, and floors 1.7 units below the eye seen
/// level and pitched down, turned about the vertical.
pub(super) fn near_grounds() -> Vec<[[f64; 3]; 3]> {
    let mut out = Vec::new();
    for slope in [-0.5, 1.0, 3.0] {
        let on = |x: f64, y: f64| [x, y, -10.0 + slope * y];
        // the corner ahead of the camera is where the plane runs away from it
        let ahead = if slope < 0.0 { 1000.0 } else { -1000.0 };
        out.push([on(-1000.0, -ahead), on(1000.0, -ahead), on(0.0, ahead)]);
    }
    // Floors 1.7 units below the eye, seen level and pitched down, turned about the vertical,
    // reaching 1000 and 10⁴ units: the ground engines draw.
    for (reach, yaw, pitch) in [
        (1000.0f64, 0.0f64, 0.0f64),
        (1000.0, 0.3, 0.05),
        (1000.0, 0.9, 0.2),
        (1000.0, 1.3, 0.6),
        (10000.0, 0.2, 0.02),
        (10000.0, 0.7, 0.35),
    ] {
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        // World (x, −1.7, z) turned by yaw about y, then pitched down about x.
        let eye = |x: f64, z: f64| {
            let (x, z) = (cy * x + sy * z, -sy * x + cy * z);
            let y = -1.7;
            [x, cp * y - sp * z, sp * y + cp * z]
        };
        // A triangle around the camera holding the disc of radius `reach` (ahead, whatever yaw).
        out.push([
            eye(-1.8 * reach, reach),
            eye(1.8 * reach, reach),
            eye(0.0, -2.0 * reach),
        ]);
    }
    out
}

/// The part of eye-space triangle `t` beyond the plane `z = −depth`, in f64 (one
/// Sutherland–Hodgman pass), as a fan of triangles.
pub(super) fn clip_in_f64(t: [[f64; 3]; 3], depth: f64) -> Vec<[[f64; 3]; 3]> {
    let inside = |p: &[f64; 3]| -p[2] >= depth;
    let mut polygon = Vec::new();
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        if inside(&a) {
            polygon.push(a);
        }
        if inside(&a) != inside(&b) {
            let s = (-depth - a[2]) / (b[2] - a[2]);
            polygon.push(std::array::from_fn(|k| a[k] + s * (b[k] - a[k])));
        }
    }
    (2..polygon.len())
        .map(|i| [polygon[0], polygon[i - 1], polygon[i]])
        .collect()
}

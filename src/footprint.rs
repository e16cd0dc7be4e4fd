//! Where a decal lies on the screen and how its depth runs across it: the exact window-space
//! geometry that lets the recommendation drop its worst-case bounds on a plane's extrapolation.
//!
//! The rasterizer sets a triangle's depth plane up relative to the framebuffer origin and
//! evaluates `w₀ + ∂w/∂x·x + ∂w/∂y·y` at each pixel (Mesa llvmpipe's `a0`), so its f32 roundings
//! scale with `M = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y`, the magnitude of those terms. Knowing only a
//! decal's depth range and slope, [`crate::recommend`] must bound the gradients over every plane
//! of that slope (the plane's axis crossing is unknown, a factor `1 + s·e`) and every pixel of
//! the viewport; on steep planes that bound is hundreds of times the real `M`. A [`Footprint`]
//! is the real thing: the window-depth plane of the decal (`w₀`, `∂w/∂x`, `∂w/∂y`, exact in f64
//! from the decal's eye-space corners) and the window rectangle it covers. [`decal_shape`]
//! computes it, with the depth range and slope, from the corners an engine already has.
//!
//! Window coordinates are GL's: pixels from the lower-left corner of the viewport. A viewport
//! elsewhere in the framebuffer is accounted for by [`Footprint::in_framebuffer`] (the model
//! does it from [`crate::model::Pipeline::viewport_origin`]).
//!
//! A plane that contains the view direction (level ground under a level camera) has an
//! infinite eye-space slope but an ordinary window plane: [`DecalShape::slope`] is then `+∞`
//! and the model runs on the footprint alone.

use glam::Vec3;

use crate::domain::{domain, finite};
use crate::error::Result;
use crate::projection::{projection_f64, ClipDepth, Frustum};

/// The window-space geometry of a decal: its depth plane and the rectangle it covers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// The plane's window depth extrapolated to window `(0, 0)`, `w₀` (under the clip
    /// convention the footprint was computed for).
    pub origin_depth: f64,
    /// The window-depth gradient per pixel, `(∂w/∂x, ∂w/∂y)`.
    pub gradient: [f64; 2],
    /// The largest window `x` and `y` (pixels) of the decal, clamped to the viewport: the
    /// corner of its bounding rectangle farthest from the origin.
    pub far_corner: [f64; 2],
    /// The largest `(|w₀| + |∂w/∂x|·x + |∂w/∂y|·y)·d` over the corners of the decal's part on
    /// screen (`d` a corner's eye depth): under reversed Z, where the offset is relative and an
    /// error counts as `error·d`, the worst pixel's `M·d` (a ratio of affine functions of the
    /// window position, largest at a corner of the convex part on screen).
    pub magnitude_depth: f64,
    /// 0 when every corner of the decal lies inside the view frustum (the rasterizer clips
    /// nothing of it); else the largest `|x|`, `|y|`, `|z|` of its eye-space corners: a decal
    /// partly off screen is clipped by the rasterizer like a base, and the model adds its
    /// clipping term ([`crate::recommend::ErrorTerms::decal_clip`]).
    pub clipped_reach: f64,
}

impl Footprint {
    /// `|∂w/∂x|·x + |∂w/∂y|·y` at the far corner: the largest run of the plane's depth from the
    /// window origin to a pixel of the decal.
    pub fn extrapolation(&self) -> f64 {
        self.gradient[0].abs() * self.far_corner[0] + self.gradient[1].abs() * self.far_corner[1]
    }

    /// `M = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y`, its largest value over the decal's pixels.
    pub fn magnitude(&self) -> f64 {
        self.origin_depth.abs() + self.extrapolation()
    }

    /// The same footprint measured from the framebuffer's origin, for a viewport whose
    /// lower-left corner is at `origin` (`glViewport(x, y, ..)`): the plane extrapolated to the
    /// framebuffer's `(0, 0)`, `w₀ − gₓ·x − g_y·y`, and the far corner moved by `origin`.
    /// `magnitude_depth` grows by at most `2(|gₓ|·x + |g_y|·y)·far`, `far` the decal's farthest
    /// eye depth (each pixel's `M` grows by at most twice the extra run).
    pub fn in_framebuffer(&self, origin: [u32; 2], far: f64) -> Footprint {
        if origin == [0, 0] {
            return *self;
        }
        let [x, y] = origin.map(f64::from);
        let [gx, gy] = self.gradient;
        let run = gx.abs() * x + gy.abs() * y;
        Footprint {
            origin_depth: self.origin_depth - gx * x - gy * y,
            gradient: self.gradient,
            far_corner: [self.far_corner[0] + x, self.far_corner[1] + y],
            magnitude_depth: self.magnitude_depth + 2.0 * run * far,
            clipped_reach: self.clipped_reach,
        }
    }
}

/// What [`decal_shape`] finds from a decal's corners: everything a
/// [`crate::recommend::Scene`] needs to know about the decal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecalShape {
    /// The nearest and farthest eye depth (`−z`) of the part drawn: the corners' where the
    /// decal lies inside the view, else those of the decal cut to the view volume (every pixel
    /// lies between them).
    pub depth_range: [f64; 2],
    /// The plane's eye-space slope `|∂z/∂x| + |∂z/∂y|`; `+∞` for a plane that contains the
    /// view direction (level ground under a level camera), which the model answers from the
    /// footprint.
    pub slope: f64,
    /// The window-space geometry.
    pub footprint: Footprint,
}

/// The largest distance of a corner from the plane through the others, relative to the decal's
/// size, that still counts as planar: far above f32 rounding of the corners (2⁻²⁴), far below
/// any decal that is really bent.
const PLANAR_TOLERANCE: f64 = 1.0 / 65_536.0;

/// How far inside the near plane, in NDC depth, a decal that reaches behind it is cut
/// ([`decal_shape_for_matrix`]): far above f64 rounding, far below a depth any pixel needs.
const NEAR_CUT_MARGIN: f64 = 1.0 / 65_536.0;

/// How far inside the far plane, relative to clip `w`, a decal that reaches beyond it is cut
/// ([`decal_shape_for_matrix`]): far above f64 rounding, so the cut corners' eye depths stay
/// within the far plane the recommendation checks them against, and far below a pixel's depth
/// step (2⁻⁴⁰ of the far plane's depth).
const FAR_CUT_MARGIN: f64 = 1.0 / 1_099_511_627_776.0;

/// The refusals of a decal of which nothing is drawn.
const WHOLLY_BEYOND: &str = "the decal lies wholly beyond the far plane: nothing of it is drawn";
const WHOLLY_BEHIND: &str = "the decal lies wholly behind the near plane: nothing of it is drawn (corners are eye-space positions, after the model-view transform: in front of the eye is -z under a right-handed projection, +z under a left-handed one)";
const WHOLLY_OFF_SCREEN: &str =
    "the decal lies wholly outside the view (off screen): nothing of it is drawn";

/// Whether `e` is [`decal_shape_for_matrix`]'s refusal of a decal of which nothing is drawn
/// (wholly behind the near plane, beyond the far plane, or off screen): a piece of a mesh
/// decal that can be left out.
pub(crate) fn draws_nothing(e: &crate::Error) -> bool {
    [WHOLLY_BEYOND, WHOLLY_BEHIND, WHOLLY_OFF_SCREEN].contains(&e.detail())
}

/// The depth range, slope and [`Footprint`] of a planar decal from its eye-space corners
/// (right-handed, looking down −z: the positions the decal's vertices have after the
/// model-view transform), seen through `frustum` under `clip` in a `viewport` of `[W, H]` pixels.
/// [`decal_shape_for_matrix`] does the same for any projection matrix.
///
/// # Errors
/// As [`decal_shape_for_matrix`].
pub fn decal_shape(
    frustum: &Frustum,
    clip: ClipDepth,
    viewport: [u32; 2],
    corners: &[Vec3],
) -> Result<DecalShape> {
    decal_shape_for_matrix(&projection_f64(frustum, clip)?, clip, viewport, corners)
}

/// The depth range, slope and [`Footprint`] of a planar decal from its eye-space `corners`, seen
/// through the projection `m` (column-major, in f64: any perspective matrix, left- or
/// right-handed, flipped or not) under `clip` in a `viewport` of `[W, H]` pixels at the
/// framebuffer's origin.
///
/// Each corner is projected in f64 to window `(x, y)` and window depth (`½·ndc + ½` under
/// `[−1, 1]`, `ndc` otherwise); a planar polygon's window depth is affine in window `(x, y)`
/// (`ndc` is affine in `1/w`, and `1/w` is affine on the screen), so the footprint's plane is
/// the plane through those points (Newell's normal, exact up to f64 rounding). The eye depth of
/// a corner is its clip `w` (`−z` right-handed, `z` left-handed); the slope is
/// `(|n_x| + |n_y|)/|n_z|` of the eye-space plane.
///
/// A decal that reaches behind the near plane (under the camera) or beyond the far plane (a
/// road marking under a short far plane) is cut to the view volume in f64 first: the depth
/// range and the footprint are those of the part the rasterizer draws, and
/// [`Footprint::clipped_reach`] the reach of every corner (the rasterizer clips the decal as
/// drawn).
///
/// # Errors
/// [`crate::ErrorKind::NotFinite`] for a NaN or infinite coordinate; [`crate::ErrorKind::Domain`]
/// for fewer than 3 corners, a zero viewport, corners that do not span a plane or are not
/// coplanar, a decal wholly outside the view, or a plane through the eye (edge-on in the
/// image).
pub fn decal_shape_for_matrix(
    m: &[f64; 16],
    clip: ClipDepth,
    viewport: [u32; 2],
    corners: &[Vec3],
) -> Result<DecalShape> {
    if corners.len() < 3 {
        return Err(domain("a decal needs at least 3 corners"));
    }
    if viewport[0] == 0 || viewport[1] == 0 {
        return Err(domain("the viewport must be at least 1×1 pixel"));
    }
    let eye: Vec<[f64; 3]> = corners
        .iter()
        .map(|c| [f64::from(c.x), f64::from(c.y), f64::from(c.z)])
        .collect();
    for p in &eye {
        for &c in p {
            finite(c, "a decal corner is not finite").map_err(|e| e.with_value("coordinate", c))?;
        }
    }
    // Any order of the corners: their hull, every corner checked against its plane.
    let hull = hull_order(&eye);
    let (normal, offset, size) = plane_of(&hull)?;
    check_flat(&eye, normal, offset, size)?;
    let eye = hull;
    // +∞ for a plane containing the view direction: its window plane is still ordinary (only a
    // plane through the eye is edge-on in the image, refused below).
    let slope = if normal[2] == 0.0 {
        f64::INFINITY
    } else {
        (normal[0].abs() + normal[1].abs()) / normal[2].abs()
    };
    let [w, h] = viewport.map(f64::from);
    let row = |r: usize, p: &[f64; 3]| m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    let mut window = Vec::with_capacity(eye.len());
    // Whether the rasterizer clips the decal: a corner outside a side, the near or the far plane.
    // NDC depth runs over [−1, 1] under OpenGL's default, [0, 1] otherwise (reversed too).
    let lowest_ndc = if clip == ClipDepth::NegOneToOne {
        -1.0
    } else {
        0.0
    };
    // A decal reaching behind the near plane (a pool under the player's feet) is cut to the
    // view frustum in f64 (its near plane 2⁻¹⁶ of NDC inside, so the cut corners stay in front
    // after rounding): its pixels are those of the visible part, whose corners lie on the same
    // plane and whose nearest eye depth is where the screen's edge meets it (a ground decal's
    // cut at the near plane is below the screen). The rasterizer clips the drawn decal, so its
    // clipping term counts (`outside`, with the reach of every corner drawn, the cut ones too).
    let near_side = |p: &[f64; 3]| {
        let inside = match clip {
            ClipDepth::NegOneToOne => row(2, p) + row(3, p),
            ClipDepth::ZeroToOne => row(2, p),
            ClipDepth::ReversedZeroToOne => row(3, p) - row(2, p),
        };
        inside - NEAR_CUT_MARGIN * row(3, p)
    };
    // Positive in front of the far plane: z_c ≤ w_c, reversed z_c ≥ 0.
    let far_side = |p: &[f64; 3]| match clip {
        ClipDepth::ReversedZeroToOne => row(2, p),
        _ => row(3, p) - row(2, p),
    };
    if eye.iter().all(|p| far_side(p) < 0.0) {
        return Err(domain(WHOLLY_BEYOND));
    }
    // A decal running on beyond the far plane (a road marking under a short far plane) is cut
    // there too: the rasterizer draws only its part in front, and its depth range is that
    // part's (a corner beyond the far plane would be refused as a distance past it).
    let crosses_near = eye.iter().any(|p| near_side(p) <= 0.0); // corners are finite
    let crosses_far = eye.iter().any(|p| far_side(p) <= 0.0);
    let far_cut = |p: &[f64; 3]| far_side(p) - FAR_CUT_MARGIN * row(3, p);
    // The part drawn: cut where a near or far plane crosses it, and nothing where it lies
    // wholly off screen at the sides. A decal only partly off screen at the sides keeps all its
    // corners for its plane (the model adds the clipping of its own edges) and takes its
    // ranges over the pixels from the cut (below).
    let cut = cut_to_view(&eye, &near_side, &far_cut, &row);
    let visible: &[[f64; 3]] = if crosses_near || crosses_far || cut.len() < 3 {
        &cut
    } else {
        &eye
    };
    if visible.len() < 3 {
        return Err(domain(if eye.iter().all(|p| near_side(p) <= 0.0) {
            WHOLLY_BEHIND
        } else {
            WHOLLY_OFF_SCREEN
        }));
    }
    let project = |p: &[f64; 3]| {
        let cw = row(3, p);
        let ndc_z = row(2, p) / cw;
        let depth = if clip == ClipDepth::NegOneToOne {
            0.5 * ndc_z + 0.5
        } else {
            ndc_z
        };
        let x = (0.5 * row(0, p) / cw + 0.5) * w;
        let y = (0.5 * row(1, p) / cw + 0.5) * h;
        [x, y, depth]
    };
    let mut outside = crosses_near || crosses_far;
    for (i, p) in visible.iter().enumerate() {
        let cw = row(3, p);
        if cw.is_nan() || cw <= 0.0 {
            return Err(
                domain("every decal corner must lie in front of the eye (clip w > 0)")
                    .with_integer("decal corner", i as i64),
            );
        }
        let ndc_z = row(2, p) / cw;
        outside |=
            row(0, p).abs() > cw || row(1, p).abs() > cw || !(lowest_ndc..=1.0).contains(&ndc_z);
        window.push(project(p));
    }
    let (plane, offset) = plane_through(&window)?;
    if plane[2] == 0.0 {
        return Err(domain(
            "the decal's plane is edge-on in the image and covers no pixel: it passes through the eye (or, under an orthographic projection, contains the view direction: level ground seen by a level orthographic camera)",
        ));
    }
    let origin_depth = finite(offset / plane[2], "the decal's window plane is not finite")?;
    let gradient = [-plane[0] / plane[2], -plane[1] / plane[2]];
    // The plane is fitted through every corner kept (a sliver cut would fit it badly); the
    // ranges over the pixels come from the part on screen. A decal only partly off screen at
    // the sides has its pixels inside the view: a corner far off screen may lie much nearer
    // the eye than any pixel (measured: a 4 ft decal 0.55 ft ahead, one off-screen corner 1.1
    // times the near distance away, was refused as moved past the near plane; its part on
    // screen begins 3.8 times as far), or much farther out along the gradient.
    let drawn = if outside && cut.len() >= 3 {
        &cut
    } else {
        visible
    };
    let mut depth_range = [f64::INFINITY, 0.0f64];
    let (mut magnitude_depth, mut far_corner) = (0.0f64, [0.0f64, 0.0f64]);
    for p in drawn {
        let (cw, [x, y, _]) = (row(3, p), project(p));
        depth_range = [depth_range[0].min(cw), depth_range[1].max(cw)];
        let magnitude = origin_depth.abs() + gradient[0].abs() * x + gradient[1].abs() * y;
        magnitude_depth = magnitude_depth.max(magnitude * cw);
        far_corner = [
            far_corner[0].max(x.clamp(0.0, w)),
            far_corner[1].max(y.clamp(0.0, h)),
        ];
    }
    let footprint = Footprint {
        origin_depth,
        gradient,
        far_corner,
        magnitude_depth,
        clipped_reach: if outside {
            eye.iter().flatten().fold(0.0f64, |a, c| a.max(c.abs()))
        } else {
            0.0
        },
    };
    Ok(DecalShape {
        depth_range,
        slope,
        footprint,
    })
}

/// A signed distance to a plane of the view volume, positive inside.
type Side<'a> = &'a dyn Fn(&[f64; 3]) -> f64;

/// `polygon` (eye space) cut to the view volume of the projection whose clip-coordinate rows
/// `row` gives: by `near_side` (positive in front of the near plane), the four sides
/// `|x_c|, |y_c| ≤ w_c` and `far_side` (positive in front of the far plane), in f64.
fn cut_to_view(
    polygon: &[[f64; 3]],
    near_side: Side,
    far_side: Side,
    row: &dyn Fn(usize, &[f64; 3]) -> f64,
) -> Vec<[f64; 3]> {
    let sides: [Side; 5] = [
        &|p| row(3, p) - row(0, p),
        &|p| row(3, p) + row(0, p),
        &|p| row(3, p) - row(1, p),
        &|p| row(3, p) + row(1, p),
        far_side,
    ];
    let mut poly = crate::model::clip::cut(polygon, near_side);
    for side in sides {
        if poly.len() < 3 {
            break;
        }
        poly = crate::model::clip::cut(&poly, side);
    }
    poly
}

/// The plane `N·p = h₀` through `points` (Newell's normal, the centroid), checked for flatness.
pub(crate) fn plane_through(points: &[[f64; 3]]) -> Result<([f64; 3], f64)> {
    let (normal, offset, size) = plane_of(points)?;
    check_flat(points, normal, offset, size)?;
    Ok((normal, offset))
}

/// Newell's normal and the centroid of the polygon `points` (in order around it), and its size
/// (the largest distance of a point from the centroid), unchecked for flatness.
fn plane_of(points: &[[f64; 3]]) -> Result<([f64; 3], f64, f64)> {
    let mut normal = [0.0f64; 3];
    let mut centre = [0.0f64; 3];
    for (i, a) in points.iter().enumerate() {
        let c = points[(i + 1) % points.len()];
        normal[0] += (a[1] - c[1]) * (a[2] + c[2]);
        normal[1] += (a[2] - c[2]) * (a[0] + c[0]);
        normal[2] += (a[0] - c[0]) * (a[1] + c[1]);
        for k in 0..3 {
            centre[k] += a[k] / points.len() as f64;
        }
    }
    let length = normal.iter().map(|v| v * v).sum::<f64>().sqrt();
    let size = points
        .iter()
        .map(|p| {
            (0..3)
                .map(|k| (p[k] - centre[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    if length.is_nan() || size.is_nan() || length <= 1e-12 * size * size {
        let count = i64::try_from(points.len()).unwrap_or(i64::MAX);
        // Points that span a plane but whose polygon encloses no area cross themselves: a
        // triangle strip's order (0, 1, 3, 2) around a quad.
        if spanning_normal(points).is_some() {
            return Err(domain(
                "the corners are not in order around the polygon (they cross themselves and \
                 enclose no area: a triangle strip's order 0, 1, 3, 2 around a quad); give them \
                 in order around its edge",
            )
            .with_integer("corners", count));
        }
        return Err(domain(
            "the decal's corners do not span a plane (they coincide or lie on one line: no area \
             on screen); for a piece of a mesh decal give the corners of the base triangle it was \
             cut from (a sliver's rounded corners do not pin its plane down), and leave out a \
             piece with no area",
        )
        .with_integer("corners", count));
    }
    let normal = normal.map(|v| v / length);
    let offset: f64 = (0..3).map(|k| normal[k] * centre[k]).sum();
    Ok((normal, offset, size))
}

/// Refuses `points` farther than 2⁻¹⁶ of `size` from the plane `normal·p = offset`.
fn check_flat(points: &[[f64; 3]], normal: [f64; 3], offset: f64, size: f64) -> Result<()> {
    let bent = points
        .iter()
        .map(|p| ((0..3).map(|k| normal[k] * p[k]).sum::<f64>() - offset).abs())
        .fold(0.0, f64::max);
    if bent > PLANAR_TOLERANCE * size {
        return Err(domain(
            "the decal's corners must be coplanar (within 2^-16 of the decal's size); a decal on \
             several planes (a mesh decal over terrain) is asked one plane at a time, together: \
             zshift_decal_matrix_planes with one ZshiftDecal per plane (Python \
             decal_matrix_planes, Rust zshift::planes::recommend_planes)",
        )
        .with_value("the largest distance of a corner from their plane", bent));
    }
    Ok(())
}

/// A unit normal of the plane `points` span, from three of them far apart (the first, the one
/// farthest from it, and the one farthest from the line through both), whatever their order;
/// `None` when they lie on one line.
fn spanning_normal(points: &[[f64; 3]]) -> Option<[f64; 3]> {
    let p0 = *points.first()?;
    let dist2 = |p: &[f64; 3]| (0..3).map(|k| (p[k] - p0[k]).powi(2)).sum::<f64>();
    let p1 = *points.iter().max_by(|a, b| dist2(a).total_cmp(&dist2(b)))?;
    let u = [0, 1, 2].map(|k| p1[k] - p0[k]);
    let cross_with = |p: &[f64; 3]| cross(u, [0, 1, 2].map(|k| p[k] - p0[k]));
    let norm2 = |c: [f64; 3]| c.iter().map(|x| x * x).sum::<f64>();
    let n = points
        .iter()
        .map(cross_with)
        .max_by(|a, b| norm2(*a).total_cmp(&norm2(*b)))?;
    let length = norm2(n).sqrt();
    // The same relative threshold as Newell's in `plane_of` (twice the area over size²).
    (length > 1e-12 * dist2(&p1) && length.is_finite()).then(|| n.map(|x| x / length))
}

/// `x × y` (the one cross product of the crate: the footprint's hull, the probe's planes).
pub(crate) fn cross(x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
    [
        x[1] * y[2] - x[2] * y[1],
        x[2] * y[0] - x[0] * y[2],
        x[0] * y[1] - x[1] * y[0],
    ]
}

/// The corners of a decal in the order of their convex hull in their own plane, whatever order
/// they came in (a triangle strip's 0, 1, 3, 2, a fan's, a mesh piece's vertices): the engine's
/// triangles over them cover only the hull, so the hull's footprint and depth range hold for
/// whatever it draws. Corners on no plane, or on one line, come back as they are (the plane
/// check refuses them).
fn hull_order(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let Some(n) = spanning_normal(points) else {
        return points.to_vec();
    };
    // A basis of the plane: e₁ along the first coordinate axis least aligned with n.
    let axis = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let mut a = [0.0f64; 3];
    a[axis] = 1.0;
    let e1 = cross(n, a);
    let e2 = cross(n, e1);
    let dot = |x: &[f64; 3], y: [f64; 3]| (0..3).map(|k| x[k] * y[k]).sum::<f64>();
    let mut flat: Vec<(f64, f64, usize)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| (dot(p, e1), dot(p, e2), i))
        .collect();
    flat.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // Andrew's monotone chain, counter-clockwise in (e₁, e₂); collinear points dropped.
    let turn = |o: (f64, f64, usize), a: (f64, f64, usize), b: (f64, f64, usize)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64, usize)> = Vec::with_capacity(2 * flat.len());
    for pass in [false, true] {
        let start = hull.len();
        let run: Vec<_> = if pass {
            flat.iter().rev().copied().collect()
        } else {
            flat.clone()
        };
        for p in run {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 3 {
        return points.to_vec();
    }
    hull.iter().map(|&(_, _, i)| points[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `glFrustum(−0.8, 1.2, −0.5, 0.7, 1, 50)`, a 200×120 viewport.
    fn frustum() -> Frustum {
        Frustum::new(-0.8, 1.2, -0.5, 0.7, 1.0, 50.0).unwrap()
    }

    /// The window depth of the plane `z = −da + sx·x + sy·y` seen through window pixel `(x, y)`,
    /// by intersecting the pixel's ray with the plane (`[−1, 1]`, `glDepthRange(0, 1)`).
    fn window_through(x: f64, y: f64, (sx, sy, da): (f64, f64, f64)) -> f64 {
        let (l, r, b, t, n, f) = (-0.8, 1.2, -0.5, 0.7, 1.0, 50.0);
        let kx = (l + x / 200.0 * (r - l)) / n;
        let ky = (b + y / 120.0 * (t - b)) / n;
        let d = da / (1.0 + sx * kx + sy * ky);
        0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * d)) + 0.5
    }

    fn on_plane(x: f32, y: f32, (sx, sy, da): (f64, f64, f64)) -> Vec3 {
        let z = -da + sx * f64::from(x) + sy * f64::from(y);
        Vec3::new(x, y, z as f32)
    }

    /// A piece wholly behind the near plane, beyond the far plane or off screen is refused as
    /// drawing nothing (`Error::draws_nothing`, what lets a mesh decal leave it out); a piece
    /// that is drawn, or refused for another reason, is not.
    #[test]
    fn pieces_that_draw_nothing_say_so() {
        let at = |points: [(f32, f32, f32); 3]| {
            let corners: Vec<Vec3> = points.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
            decal_shape(&frustum(), ClipDepth::NegOneToOne, [200, 120], &corners)
        };
        for (what, piece) in [
            (
                "behind",
                [(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (0.0, 1.0, 2.0)],
            ),
            (
                "beyond",
                [(0.0, 0.0, -60.0), (1.0, 0.0, -60.0), (0.0, 1.0, -70.0)],
            ),
            (
                "off screen",
                [(40.0, 0.0, -10.0), (41.0, 0.0, -10.0), (40.0, 1.0, -11.0)],
            ),
        ] {
            let e = at(piece).expect_err(what);
            assert!(e.draws_nothing(), "{what}: {e}");
        }
        assert!(at([(0.0, 0.0, -5.0), (1.0, 0.0, -5.0), (0.0, 1.0, -6.0)]).is_ok());
        let flat = at([(0.0, 0.0, -5.0), (1.0, 0.0, -5.0), (2.0, 0.0, -5.0)]).unwrap_err();
        assert!(!flat.draws_nothing(), "{flat}");
    }

    #[test]
    fn the_window_plane_matches_the_rays_through_the_pixels() {
        let plane = (0.3, -0.6, 8.0);
        let corners: Vec<Vec3> = [(-1.0, -1.0), (2.0, -1.0), (2.0, 1.5), (-1.0, 1.5)]
            .iter()
            .map(|&(x, y)| on_plane(x, y, plane))
            .collect();
        let shape = decal_shape(&frustum(), ClipDepth::NegOneToOne, [200, 120], &corners).unwrap();
        let fp = shape.footprint;
        // The window depth is affine in window (x, y): the footprint's plane reproduces the
        // rays' depths (to the f32 rounding of the corners' z, 2⁻²⁴ relative).
        for (x, y) in [(0.0, 0.0), (50.0, 30.0), (199.0, 7.0), (13.0, 119.0)] {
            let plane_w = fp.origin_depth + fp.gradient[0] * x + fp.gradient[1] * y;
            assert!(
                (plane_w - window_through(x, y, plane)).abs() < 1e-6,
                "({x}, {y})"
            );
        }
        let depths: Vec<f64> = corners.iter().map(|c| -f64::from(c.z)).collect();
        let (lo, hi) = (
            depths.iter().copied().fold(f64::INFINITY, f64::min),
            depths.iter().copied().fold(0.0, f64::max),
        );
        assert_eq!(shape.depth_range, [lo, hi]);
        assert!((shape.slope - 0.9).abs() < 1e-5, "{}", shape.slope);
        // The far corner: the largest projected window x and y of the corners, clamped.
        let window_x = |c: &Vec3| {
            let d = -f64::from(c.z);
            ((f64::from(c.x) / d + 0.8) / 2.0 * 200.0).clamp(0.0, 200.0)
        };
        let largest = corners.iter().map(window_x).fold(0.0, f64::max);
        assert!((fp.far_corner[0] - largest).abs() < 1e-9);
        assert_eq!(fp.magnitude(), fp.origin_depth.abs() + fp.extrapolation());
    }

    #[test]
    fn a_facing_decal_has_no_gradient() {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, -5.0));
        let shape = decal_shape(&frustum(), ClipDepth::NegOneToOne, [200, 120], &corners).unwrap();
        assert_eq!(shape.slope, 0.0);
        assert!(shape.footprint.gradient.iter().all(|g| g.abs() < 1e-15));
        assert!(
            (shape.footprint.origin_depth - window_through(0.0, 0.0, (0.0, 0.0, 5.0))).abs()
                < 1e-12
        );
    }

    /// A decal under the camera, reaching behind it: described by the part on screen (its
    /// nearest eye depth where the screen's lower edge meets the ground, not the near plane),
    /// with the clipping reach of all its corners.
    #[test]
    fn a_decal_reaching_behind_the_camera_is_its_visible_part() {
        // Ground 1.7 below the eye, the decal from 2 behind to 6 ahead; the lower edge of
        // glFrustum(−0.8, 1.2, −0.5, 0.7, 1, 50) is the ray y = −0.5·d: it meets the ground
        // at d = 3.4.
        let corners = [(-1.0, 2.0), (1.0, 2.0), (1.0, -6.0), (-1.0, -6.0)]
            .map(|(x, z)| Vec3::new(x, -1.7, z));
        let shape = decal_shape(&frustum(), ClipDepth::NegOneToOne, [200, 120], &corners).unwrap();
        let [near, far] = shape.depth_range;
        // (−1.7 in f32: 3.4 within 1e-7.)
        assert!((near - 3.4).abs() < 1e-6, "{near}");
        assert!((far - 6.0).abs() < 1e-9, "{far}");
        assert_eq!(shape.slope, f64::INFINITY);
        assert_eq!(shape.footprint.clipped_reach, 6.0);
        // The window plane is the ground's: at the lower edge (y = 0) its window depth is
        // that of d = 3.4.
        let fp = shape.footprint;
        let at_edge = fp.origin_depth + fp.gradient[0] * 100.0;
        let expected = 0.5 * ((51.0 / 49.0) - 100.0 / (49.0 * near)) + 0.5;
        assert!((at_edge - expected).abs() < 1e-9, "{at_edge} {expected}");
    }

    /// A decal partly off screen at a side, one corner far off screen and close to the eye:
    /// its depth range is that of its pixels, not of its corners. Reference: the ray through
    /// every pixel centre met with the decal's plane in f64, kept where it hits the decal.
    #[test]
    fn a_decal_partly_off_screen_is_its_visible_part() {
        // The ground 1.7 below the eye; the decal's near-left corner at x = −9 is 4.5 times
        // as far left as glFrustum(−0.8, 1.2, −0.5, 0.7, 1, 50)'s left edge at its depth 2.5,
        // and its near edge runs to (1, −6): the screen's left edge meets it at depth 4.41.
        let corners = [(-9.0, -2.5), (1.0, -6.0), (1.0, -8.0), (-1.0, -8.0)]
            .map(|(x, z)| Vec3::new(x, -1.7, z));
        let [w, h] = [200u32, 120];
        let shape = decal_shape(&frustum(), ClipDepth::NegOneToOne, [w, h], &corners).unwrap();
        // The ground's point (x, z) is on the decal where it lies on one side of every edge.
        let q: Vec<[f64; 2]> = corners
            .iter()
            .map(|c| [f64::from(c.x), f64::from(c.z)])
            .collect();
        let inside = |x: f64, z: f64| {
            let sides: Vec<f64> = (0..4)
                .map(|i| {
                    let (a, b) = (q[i], q[(i + 1) % 4]);
                    (b[0] - a[0]) * (z - a[1]) - (b[1] - a[1]) * (x - a[0])
                })
                .collect();
            sides.iter().all(|&c| c <= 0.0) || sides.iter().all(|&c| c >= 0.0)
        };
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for j in 0..h {
            for i in 0..w {
                // The pixel centre's ray (x, y, −1)·d through glFrustum(−0.8, 1.2, −0.5, 0.7, 1, …).
                let rx = -0.8 + 2.0 * (f64::from(i) + 0.5) / f64::from(w);
                let ry = -0.5 + 1.2 * (f64::from(j) + 0.5) / f64::from(h);
                if ry >= 0.0 {
                    continue;
                }
                let d = f64::from(-1.7f32) / ry;
                if inside(rx * d, -d) {
                    (lo, hi) = (lo.min(d), hi.max(d));
                }
            }
        }
        let [near, far] = shape.depth_range;
        assert!(
            near <= lo && far >= hi,
            "{near} {far} against the pixels' {lo} {hi}"
        );
        // Within a pixel's width of the pixels' own range (the corners' reach 2.5).
        assert!(
            near > 0.97 * lo && far < 1.03 * hi,
            "{near} {far} against {lo} {hi}"
        );
        // The rasterizer clips it: its clipping term counts every corner.
        assert_eq!(shape.footprint.clipped_reach, 9.0);
    }

    /// A decal running on beyond the far plane (a road marking under a short far plane): its
    /// depth range ends at the far plane, within f64 rounding, under every convention, and the
    /// rasterizer's clipping of it counts with the reach of all its corners.
    #[test]
    fn a_decal_reaching_beyond_the_far_plane_is_its_part_in_front() {
        // The ground 1.7 below the eye, the decal from 40 to 70 ahead; the far plane at 50.
        let corners = [(-1.0, -40.0), (1.0, -40.0), (1.0, -70.0), (-1.0, -70.0)]
            .map(|(x, z)| Vec3::new(x, -1.7, z));
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let shape = decal_shape(&frustum(), clip, [200, 120], &corners).unwrap();
            let [near, far] = shape.depth_range;
            assert!((near - 40.0).abs() < 1e-9, "{clip:?} {near}");
            assert!(far < 50.0 && far > 50.0 * (1.0 - 1e-9), "{clip:?} {far}");
            assert_eq!(shape.footprint.clipped_reach, 70.0, "{clip:?}");
        }
    }

    /// The corners in any order (a triangle strip's 0, 1, 3, 2; a mesh piece's vertices with
    /// one inside the others) describe the decal their hull covers: the same shape as the
    /// corners in order around it. A polygon that crosses itself is refused where the order
    /// matters (a shadow receiver's front), with the reason.
    #[test]
    fn the_corners_order_does_not_matter() {
        let at = |x: f32, z: f32| Vec3::new(x, -1.7 + 0.3 * x, z);
        let around = [
            at(-1.0, -9.0),
            at(1.0, -9.0),
            at(1.0, -11.0),
            at(-1.0, -11.0),
        ];
        let strip = [around[0], around[1], around[3], around[2]];
        let scattered = [around[2], at(0.2, -10.0), around[0], around[3], around[1]];
        let shape =
            |c: &[Vec3]| decal_shape(&frustum(), ClipDepth::NegOneToOne, [200, 120], c).unwrap();
        let expected = shape(&around);
        for other in [&strip[..], &scattered[..]] {
            let got = shape(other);
            assert_eq!(got.depth_range, expected.depth_range);
            // (Infinite here: the ground contains the view direction.)
            let same = got.slope == expected.slope
                || (got.slope - expected.slope).abs() <= 1e-12 * expected.slope;
            assert!(same, "{} {}", got.slope, expected.slope);
            let (a, b) = (got.footprint, expected.footprint);
            assert!(
                (a.origin_depth - b.origin_depth).abs() < 1e-12,
                "{a:?} {b:?}"
            );
            for k in 0..2 {
                assert!((a.gradient[k] - b.gradient[k]).abs() < 1e-12, "{a:?} {b:?}");
            }
        }
        let eye = strip.map(|c| [f64::from(c.x), f64::from(c.y), f64::from(c.z)]);
        let said = plane_through(&eye).unwrap_err().to_string();
        assert!(said.contains("not in order"), "{said}");
    }

    #[test]
    fn bad_decals_are_refused_with_the_reason() {
        let f = frustum();
        let square = |z: f32| {
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, z))
        };
        let refuse = |c: &[Vec3]| {
            decal_shape(&f, ClipDepth::NegOneToOne, [200, 120], c)
                .unwrap_err()
                .to_string()
        };
        assert!(refuse(&square(-0.5)).contains("wholly behind the near plane"));
        assert!(refuse(&square(0.5)).contains("left-handed"));
        // Reaching behind the camera, all of it far to the side: cut, nothing is left.
        let aside = [(99.0, 0.5), (101.0, 0.5), (101.0, -3.0), (99.0, -3.0)]
            .map(|(x, z)| Vec3::new(x, -1.0, z));
        assert!(refuse(&aside).contains("wholly outside the view (off screen)"));
        assert!(refuse(&square(-60.0)).contains("wholly beyond the far plane"));
        assert!(refuse(&square(-5.0)[..2]).contains("at least 3"));
        let mut bent = square(-5.0);
        bent[2].z = -5.5;
        assert!(refuse(&bent).contains("coplanar"));
        let line = [
            Vec3::new(0.0, 0.0, -2.0),
            Vec3::new(1.0, 0.0, -3.0),
            Vec3::new(2.0, 0.0, -4.0),
        ];
        // A mesh decal's piece with no area: the message says what to give instead.
        let said = refuse(&line);
        assert!(
            said.contains("span a plane") && said.contains("base triangle"),
            "{said}"
        );
        let mut nan = square(-5.0);
        nan[0].x = f32::NAN;
        assert!(refuse(&nan).contains("not finite"));
        assert!(decal_shape(&f, ClipDepth::NegOneToOne, [0, 120], &square(-5.0)).is_err());
    }
}

//! The term `C`: the base's f32 clipping, and the remedy, [`clip_to_frustum`].
//!
//! A floor running behind the camera is clipped by the rasterizer, which computes the new
//! vertices in f32 (Mesa's `draw_pipe_clip.c` interpolates every clip coordinate as
//! `c = c₀ + t·(c₁ − c₀)`; llvmpipe has no guard band, so it clips against all six planes, and
//! sets its depth plane up from the clipped vertices, `lp_state_setup.c`). The base's `reach`
//! `R` is the largest `|x|`, `|y|` or `|z|` of its eye-space vertices
//! ([`crate::recommend::Base::Clipped`]); a base inside the frustum has `C = 0`.
//!
//! # The term
//! Any point of the clip-space segment between two vertices projects onto the plane's image, so
//! the error in `t` does not matter; what moves a clipped vertex off the plane is the rounding
//! of each interpolated component. A clip-space component `c` of a base vertex is at most `A_c`
//! in magnitude: `A_x = (|m0| + |m8|)·R`, `A_y = (|m5| + |m9|)·R`, `A_z = |m10|·R + |m14|`,
//! `A_w = R`. Every rasterizer-made vertex carries component errors `|e_c| ≤ γ·A_c` with
//! `γ = (6 + 5k)·u`: `u` for the f32 eye coordinates, `2u` for the vertex transform, `5u` per
//! clip stage (`fl(c₀ + fl(t·fl(c₁ − c₀)))` errs by `u·(|c| + 2|t·(c₁ − c₀)|)`, at most
//! `5u·A_c`), `k = 6` stages at most (one per plane), and `3u` for the division and the viewport
//! map (their rounding at a vertex equals a clip-space error of `2u·|c|`, plus the window map).
//! Write the plane `z = −d_a + sₓx + s_y·y` in clip coordinates normalised to `z_c`'s
//! coefficient 1 ([`crate::model::plane_form`]): `L(c) = z_c − g_X·x_c − g_Y·y_c − Z₀·w_c` with
//! `g_X = m14·sₓ/(d_a·m0)`, `g_Y = m14·s_y/(d_a·m5)`,
//! `Z₀ = −m10 + (m14/d_a)(1 + sₓ·m8/m0 + s_y·m9/m5)` (`L` vanishes on the plane's image). A
//! vertex `c + e` then has NDC depth off the plane, at its own screen position, by exactly
//! `L(e)/(w + e_w)`, and the rasterizer's screen-space interpolation at a pixel of eye depth `d`
//! inside the triangle weighs vertex `i` by `λᵢ = μᵢ·wᵢ/d` (`μᵢ ∈ [0, 1]` the clip-space
//! barycentrics): the `1/wᵢ` amplification at the near plane cancels, and the pixel's depth
//! error is at most `maxᵢ |L(eᵢ)| / d`. With `|1/d_a| ≈ (1 + s·e)/d₁` (the tilt of
//! [`crate::model::gradient`]; exact with the decal's corners):
//!
//! `C = (window/NDC)·γ·(A_z + |g_X|·A_x + |g_Y|·A_y + |Z₀|·A_w) / (d₁ − γ·R)`
//!
//! World-space vertices carry the f32 model-view's errors into the clipper, which interpolates
//! them: `L` is linear, so an interpolated vertex is off the plane by the same convex
//! combination of its ends' `L`-values, no more than at the vertices
//! ([`crate::model::vertex`]). The vertex term `V` already pays that error at every vertex the
//! base keeps, and a pixel's depth weighs the kept and the rasterizer-made vertices with
//! weights that sum to 1, so `C` adds only what the made ones carry beyond `V`'s share
//! (`world_beyond_vertex_term`). A measured profile's `clip_ulps` `k` replaces `6 + 5k` by `4k`
//! where smaller (the probe's sampled maximum, 0.86 on llvmpipe, with the margin `CLIP_MARGIN`
//! the full `tests/gl_scenes.rs` grid asks for: it needs up to 2 where the probe finds 0.86).
//! An f32 replay of Mesa's clipper on grounds of ±1000 behind the camera (`clipper_emulation`,
//! a test) makes vertices up to 1.42 of the unit off the plane: above the probe's figure, below
//! the margin's 3.44.
//!
//! With the bound it is sound but large: on the floor (corners at ±1000, n = 0.1, decals
//! 8–13 units away) it asks 7700 f32 steps of element 10 where 27 work (`tests/gl_scenes.rs`),
//! and where it would move the decal past the near plane [`crate::recommend::recommend`]
//! refuses ([`crate::ErrorKind::Unresolvable`], "cut the base to the frustum"); elsewhere it
//! answers, and the bleed gap says what the answer costs (an occluder nearer than the gap is
//! painted over).
//!
//! # The remedy
//! [`clip_to_frustum`] cuts the base polygon in f64 to the frustum shrunk by 2⁻¹⁶ (near plane
//! slightly in front, sides slightly inside: less than a quarter pixel up to 16384 pixels; the
//! far plane where window depth is 2⁻²⁰ below 1, where f32 still resolves it); drawn
//! as a fan with [`crate::recommend::Base::InsideFrustum`], the rasterizer then clips nothing,
//! every vertex's errors are relative to its own coordinates, and the base's error is the
//! decal's `E` (on the same floor: 10 steps where 2 work).

use crate::domain::{domain, finite, representable};
use crate::error::Result;
use crate::model::measured::measured_figure;
use crate::model::{vertex, Pipeline, PlaneForm};
use crate::profile::RasterizerProfile;
use crate::projection::Frustum;

use super::F32_UNIT_ROUNDOFF;

/// Clip stages a rasterizer-made vertex can pass: one per plane of the view volume (Mesa's
/// clipper, with no guard band on llvmpipe, clips against all six in turn).
const CLIP_STAGES: f64 = 6.0;

/// The inward margin of [`clip_to_frustum`], relative: far above f32 rounding (2⁻²⁴), far below
/// half a pixel of any viewport up to 2¹⁵ pixels wide.
const FRUSTUM_MARGIN: f64 = 1.0 / 65_536.0;

/// The far plane's margin of [`clip_to_frustum`] in window depth: under `[−1, 1]` and `[0, 1]`
/// the far plane is at window depth 1, where f32 resolves only 2⁻²⁴, and a relative margin in
/// eye depth (2⁻¹⁶·f) is a window-depth margin of `2⁻¹⁶·n/f`, below f32's resolution once
/// `f/n` passes about 500: the f32 transform (about 4 roundings of NDC depth, `m10` and `m14`
/// themselves rounded to f32) then puts the cut base's far vertices past the far plane, and
/// the rasterizer clips them after all (measured: a base cut at `f/n = 10⁵` lost a decal pixel
/// to the far-plane clipper's error, `tests/gl_scenes.rs`, `ZSHIFT_SCENES_SEED=1`). 2⁻²⁰ is 16
/// f32 steps of window depth below 1 (32 of NDC depth under `[−1, 1]`).
const FAR_WINDOW_MARGIN: f64 = 1.0 / 1_048_576.0;

/// The eye depth at which [`clip_to_frustum`] cuts a finite far plane `f` (near plane `n`):
/// `f·(1 − 2⁻¹⁶)`, or nearer where that is needed for its window depth `f(d − n)/(d(f − n))`
/// (the same under `[−1, 1]` and `[0, 1]`) to stay [`FAR_WINDOW_MARGIN`] below 1:
/// `d = f·n/(n + δ·(f − n))`. Under reversed Z the far plane is at window depth 0, where f32
/// keeps its relative precision and 2⁻¹⁶ suffices, but the cut does not know the convention.
fn far_cut(n: f64, f: f64) -> f64 {
    (f * (1.0 - FRUSTUM_MARGIN)).min(f * n / (n + FAR_WINDOW_MARGIN * (f - n)))
}

/// How many times the probe's sampled maximum the model reserves for the clipper. The probe
/// finds `clip_ulps` ≈ 0.86 on llvmpipe (its largest over about 60 clipped planes under each
/// depth convention); the full `tests/gl_scenes.rs` grid (`ZSHIFT_SCENES=full`, 12125 scenes)
/// loses decal pixels with `γ` = 0.83u (27 scenes), 1.25u (4) and 1.5u (1) and none from 2u:
/// the largest of many more roundings is larger than the probe's. 4 keeps twice the largest
/// `γ` the grid needs; `tests/gl_scenes.rs` (`the_clippers_hardest_scenes_hold`) replays those
/// 27 scenes in CI. Four other draws of the grid (`ZSHIFT_SCENES_SEED=1` to `4`) lost nothing on
/// a clipped base with it.
const CLIP_MARGIN: f64 = 4.0;

/// `γ`, the bound on a rasterizer-made vertex's relative clip-space error: six clip stages of
/// f32 rounding, `(6 + 5k)·u`; with a measured profile `CLIP_MARGIN·clip_ulps·u` where smaller
/// (a sampled maximum with a margin, not a proof: see [`CLIP_MARGIN`]).
pub(crate) fn clip_gamma(profile: &RasterizerProfile) -> f64 {
    let bound = 6.0 + 5.0 * CLIP_STAGES;
    let ulps =
        measured_figure(profile, profile.clip_ulps).map_or(bound, |k| bound.min(CLIP_MARGIN * k));
    ulps * F32_UNIT_ROUNDOFF
}

/// `A_c`, the largest `|c|` of each clip coordinate of a base vertex whose eye coordinates are at
/// most `reach` in magnitude under the projection `m` (a `glFrustum`-family matrix):
/// `((|m0| + |m8|)·R, (|m5| + |m9|)·R, |m10|·R + |m14|, R)`. The probe measures the clipper in
/// these units too ([`crate::profile::RasterizerProfile::clip_ulps`]).
pub(crate) fn clip_magnitudes(m: &[f64; 16], reach: f64) -> [f64; 4] {
    [
        (m[0].abs() + m[8].abs()) * reach,
        (m[5].abs() + m[9].abs()) * reach,
        m[10].abs() * reach + m[14].abs(),
        reach,
    ]
}

/// The term `C` of a base of `reach` `R` the rasterizer clips (module docs): every
/// rasterizer-made vertex carries clip-space errors `|e_c| ≤ γ·A_c` (`A_c` the largest `|c|` a
/// base vertex can have under the projection `m`), and the depth error at a pixel at eye depth
/// `d ≥ d₁` is at most `max |L(e)|/(d − γ·R)` in NDC, `L` the plane's `form` (`exact_form`: the
/// footprint's, else bounds over every plane of the slope), times `window_per_ndc`.
///
/// # Errors
/// [`crate::ErrorKind::Domain`] where the base reaches so far that the denominator is no longer
/// bounded away from 0; [`crate::ErrorKind::Overflow`] if `C` overflows.
#[allow(clippy::too_many_arguments)]
pub(crate) fn clip_term(
    m: &[f64; 16],
    reach: f64,
    d1: f64,
    gamma: f64,
    form: &PlaneForm,
    exact_form: bool,
    pipeline: &Pipeline,
    window_per_ndc: f64,
    clipped: Clipped,
) -> Result<f64> {
    let a = clip_magnitudes(m, reach);
    // World-space vertices carry the f32 model-view's errors into the clipper, which
    // interpolates them: L is linear, so an interpolated vertex is off the plane by the same
    // convex combination of its ends' L-values, no more than at the vertices (a base vertex is
    // within √3·R of the camera). Computed eye-first, the error is an eye-space vector that only
    // counts through the form on eye coordinates; one combined matrix errs per clip coordinate.
    let (world_l, world_w) =
        vertex::world_error(form, exact_form, m, pipeline, 3f64.sqrt() * reach);
    let w_low = d1 - gamma * reach - world_w;
    let l = form.bound([0, 1, 2, 3].map(|k| gamma * a[k]))
        + world_beyond_vertex_term(form, exact_form, m, pipeline, world_l, w_low, d1);
    if w_low.is_nan() || w_low <= 0.5 * d1 {
        return Err(unbounded(clipped, world_w > gamma * reach, reach));
    }
    representable(
        window_per_ndc * l / w_low,
        "the clipping term overflows f64",
    )
}

/// What the rasterizer clips, for [`clip_term`]'s refusal: the base (its `base_reach`), or the
/// decal itself where its corners reach off screen or behind the camera (their reach).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Clipped {
    /// The base, of the caller's `base_reach`.
    Base,
    /// The decal, of its corners' reach ([`crate::footprint::Footprint::clipped_reach`]).
    Decal,
}

/// The refusal of a clipping term whose denominator is not bounded away from 0, naming the
/// larger cause (the world-space rounding of the vertices near the eye, `world`, or the
/// clipper's own rounding of a far-reaching primitive) and the remedy for what is clipped: the
/// base is cut and drawn with `base_reach = 0`; the decal is cut and its cut corners passed.
fn unbounded(clipped: Clipped, world: bool, reach: f64) -> crate::error::Error {
    let (detail, name) = match (clipped, world) {
        (Clipped::Base, true) => (
            "the world-space vertices' f32 rounding is too large near the eye to bound the clipped base: render relative to the camera, or multiply the model-view in double and pass view_matrix and world_box (C fields; Python keywords), or cut the base to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python, clip_to_frustum in Rust) and pass base_reach = 0",
            "base_reach",
        ),
        (Clipped::Base, false) => (
            "the base reaches so far that f32 clipping cannot be bounded: cut it to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python, clip_to_frustum in Rust) and pass base_reach = 0",
            "base_reach",
        ),
        (Clipped::Decal, true) => (
            "the world-space vertices' f32 rounding is too large near the eye to bound the clipping of the decal, which reaches off screen or behind the camera: render relative to the camera, or multiply the model-view in double and pass view_matrix and world_box (C fields; Python keywords), or cut the decal to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python, clip_to_frustum in Rust), draw the cut polygon and pass its corners",
            "reach of decal_corners",
        ),
        (Clipped::Decal, false) => (
            "the decal reaches so far off screen or behind the camera that f32 clipping cannot be bounded: cut it to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python, clip_to_frustum in Rust), draw the cut polygon and pass its corners",
            "reach of decal_corners",
        ),
    };
    domain(detail).with_value(name, reach)
}

/// The part of the clipped vertices' world error `world_l` (their `|L|` bound, over the
/// denominator `w_low`) that the vertex term `V` does not already pay. `V`, budgeted for the
/// base, bounds every unclipped vertex's share `F + G·wᵢ` at `F/d₁ + G` (`F` the world error's
/// fixed part, [`vertex::world_rounding`]). A pixel's depth is a combination of the clipped
/// polygon's vertices with weights summing to 1: unclipped ones (share `α`) and rasterizer-made
/// ones (share `β = 1 − α`, each at most `world_l`), so its world error is at most
/// `(α·F + β·world_l)/w_low + G ≤ V + (world_l − F·w_low/d₁)/w_low`: the clipping term adds
/// only `world_l − F·w_low/d₁`, not all of `world_l` again. With the view and box given, `F`
/// is `world_l` itself (the box's magnitudes do not grow with the reach) and the clipping term
/// keeps only the clipper's own roundings.
fn world_beyond_vertex_term(
    form: &PlaneForm,
    exact_form: bool,
    m: &[f64; 16],
    pipeline: &Pipeline,
    world_l: f64,
    w_low: f64,
    d1: f64,
) -> f64 {
    let (fixed, _) = vertex::world_error(form, exact_form, m, pipeline, 0.0);
    (world_l - fixed * (w_low / d1)).max(0.0)
}

// ---------------------------------------------------------------------------------------------
// Cutting a base to the view frustum in f64, so the rasterizer clips nothing.
// ---------------------------------------------------------------------------------------------

/// Cuts a planar polygon (eye-space vertices in order, f64) to the view frustum shrunk by a
/// relative margin of 2⁻¹⁶ (the near plane moved to `n·(1 + 2⁻¹⁶)`, the side planes inward by
/// 2⁻¹⁶ of the frustum's width) and the far plane moved to `f·(1 − 2⁻¹⁶)` or to where window
/// depth is 2⁻²⁰ below 1 if nearer (`f·n/(n + 2⁻²⁰·(f − n))`: 1 % nearer at `f/n = 10⁴`, 9 % at
/// 10⁵, half the range at 10⁶; f32 resolves window depth near 1 only to 2⁻²⁴, and under
/// `[−1, 1]` and `[0, 1]` what is cut away spans the last 16 f32 steps of depth; under reversed
/// Z the far plane is at window depth 0 and needs no such margin, but the cut does not know the
/// convention: there, prefer an infinite far plane), in f64: drawn in f32, the result needs no
/// clipping by the rasterizer, and the recommendation holds for it with
/// [`crate::recommend::Base::InsideFrustum`] (the f32 clipper's error, term `C`, is what makes a
/// base crossing the near plane lose decal pixels). The margin is far above the f32 rounding of
/// eye-space vertices and below a quarter pixel on viewports up to 16384 pixels, so no pixel
/// centre is lost at the edges. A result stored in world space far from the origin errs by its
/// world coordinates' rounding, which close to the camera can carry a vertex across the margin:
/// cut it with [`clip_to_frustum_stored`].
///
/// Returns the cut polygon (empty when nothing of the polygon is inside). Sutherland–Hodgman,
/// one plane at a time; a convex polygon stays convex (draw it as a fan). New vertices are
/// `a + t·(b − a)` per coordinate, so a coordinate every vertex shares is kept exactly: a base
/// facing the camera (every z equal) keeps its z, and with a decal of that z still qualifies for
/// [`crate::recommend::Scene::exact_depth`].
///
/// # Errors
/// [`crate::ErrorKind::NotFinite`] for a NaN or infinite coordinate;
/// [`crate::ErrorKind::Overflow`] if a cut vertex overflows f64 (coordinates near `f64::MAX`).
pub fn clip_to_frustum(frustum: &Frustum, polygon: &[[f64; 3]]) -> Result<Vec<[f64; 3]>> {
    cut_inside(frustum, polygon, StoredError::NONE)
}

/// [`clip_to_frustum`] for a polygon the engine stores as `pipeline` says (world space through
/// an f32 view matrix, [`Pipeline::world_reach`] or [`Pipeline::view`] with
/// [`Pipeline::world_box`]): every plane is moved inward further by the largest error the f32
/// storage and transform can give a cut vertex ([`crate::model::vertex`]: `γ·Aₖ` per eye
/// coordinate, `γ` = 6u eye first, 14u otherwise), so that the rasterizer still clips nothing
/// of it. That error is absolute, relative to the world coordinates and not to the vertex's
/// distance from the camera: a vertex cut 2⁻¹⁶ inside a side plane close to the camera lands
/// outside once stored in world space far from the origin, and Mesa's llvmpipe, which clips at
/// the sides, then cuts a sliver off the triangle, whose depth plane it sets up from an area
/// that cancels to a few ulps: a pixel the sliver covers can be off by half a pixel of the
/// plane's depth gradient, a thousand times the model's terms (`docs/rasterizer.md`,
/// "Slivers"). The price: near the camera the cut lies visibly inside the screen's edges (by
/// `γ·A/d` of the depth `d`: 0.3 pixel at 0.5 units with the camera 367 units from the
/// origin); camera-relative rendering (vertices sent relative to the camera) needs none of it,
/// and the plain [`clip_to_frustum`] is right for it. The eye-space default pipeline cuts as
/// [`clip_to_frustum`].
///
/// # Errors
/// As [`clip_to_frustum`], and as [`Pipeline::check`] for a field of `pipeline` out of range
/// (a negative or NaN `world_reach`, a view matrix without its box or with a NaN).
pub fn clip_to_frustum_stored(
    frustum: &Frustum,
    polygon: &[[f64; 3]],
    pipeline: &Pipeline,
) -> Result<Vec<[f64; 3]>> {
    pipeline.check()?;
    cut_inside(frustum, polygon, StoredError::of(pipeline, frustum))
}

/// The error of a stored vertex's eye coordinates, per coordinate: `fixed[k] + growing·w` at
/// eye depth `w`.
#[derive(Debug, Clone, Copy)]
struct StoredError {
    fixed: [f64; 3],
    growing: [f64; 3],
}

impl StoredError {
    const NONE: Self = Self {
        fixed: [0.0; 3],
        growing: [0.0; 3],
    };

    /// The bound of [`crate::model::vertex::eye_magnitudes`] times `γ`: with the view and box,
    /// exact whatever the vertex's distance; from `world_reach`, `√3·(4W + ρ·w)` for a vertex
    /// inside the frustum (`ρ = √(1 + eₓ² + e_y²)`). One combined matrix errs in clip space by
    /// `γ_W·Bₖ` (`B = |P|·A + |P₃|`), the same as an eye error of `γ_W·Aₖ` but for `|m14|`,
    /// which 2⁻¹⁶ of the near and far planes' depths far exceeds (`γ_W·|m14| ≤ 28u·n`).
    fn of(pipeline: &Pipeline, frustum: &Frustum) -> Self {
        if !pipeline.world_space() {
            return Self::NONE;
        }
        let gamma = F32_UNIT_ROUNDOFF
            * if pipeline.eye_first {
                vertex::EYE_FIRST_ROUNDINGS
            } else {
                vertex::WORLD_ROUNDINGS
            };
        let (l, r, b, t, n, _) = frustum.parameters();
        let rho =
            (1.0 + (l.abs().max(r.abs()) / n).powi(2) + (b.abs().max(t.abs()) / n).powi(2)).sqrt();
        let (at_eye, at_rho) = (
            vertex::eye_magnitudes(pipeline, 0.0),
            vertex::eye_magnitudes(pipeline, rho),
        );
        Self {
            fixed: at_eye.map(|a| gamma * a),
            growing: [0, 1, 2].map(|k| gamma * (at_rho[k] - at_eye[k])),
        }
    }

    /// The bound at eye depth `w`, coordinate `k`.
    fn at(&self, k: usize, w: f64) -> f64 {
        self.fixed[k] + self.growing[k] * w
    }
}

/// [`clip_to_frustum`]'s planes, each moved inward further by what `error` can move a stored
/// vertex across it: `eₖ(w)` through the plane's coefficients (`|m0|·eₓ + (|m8| + 1)·e_z` for
/// `x_c ≤ w`, `e_z` for the near and far planes), linear in `w`, so each is still a plane.
fn cut_inside(
    frustum: &Frustum,
    polygon: &[[f64; 3]],
    error: StoredError,
) -> Result<Vec<[f64; 3]>> {
    for v in polygon {
        for &c in v {
            finite(c, "a polygon vertex coordinate is NaN or infinite")?;
        }
    }
    let m = frustum.to_cols_array_f64()?;
    let planes = frustum.planes();
    let (n, f) = (planes.near(), planes.far());
    // The side planes in clip space, −w ≤ x_c ≤ w with x_c = m0·x + m8·z and w = −z (no
    // division: a subnormal n cannot overflow them), each moved inward by the margin.
    let keep = 1.0 - 2.0 * FRUSTUM_MARGIN;
    let x_c = move |p: &[f64; 3]| m[0] * p[0] + m[8] * p[2];
    let y_c = move |p: &[f64; 3]| m[5] * p[1] + m[9] * p[2];
    let e = move |k: usize, p: &[f64; 3]| error.at(k, -p[2]);
    let x_err = move |p: &[f64; 3]| m[0].abs() * e(0, p) + (m[8].abs() + 1.0) * e(2, p);
    let y_err = move |p: &[f64; 3]| m[5].abs() * e(1, p) + (m[9].abs() + 1.0) * e(2, p);
    // Each plane as a signed distance, positive inside.
    let mut sides: Vec<Side> = vec![
        Box::new(move |p| -p[2] - n * (1.0 + FRUSTUM_MARGIN) - e(2, p)),
        Box::new(move |p| x_c(p) - keep * p[2] - x_err(p)),
        Box::new(move |p| -keep * p[2] - x_c(p) - x_err(p)),
        Box::new(move |p| y_c(p) - keep * p[2] - y_err(p)),
        Box::new(move |p| -keep * p[2] - y_c(p) - y_err(p)),
    ];
    if f.is_finite() {
        let far = far_cut(n, f);
        sides.push(Box::new(move |p| far + p[2] - e(2, p)));
    }
    let mut poly = polygon.to_vec();
    for side in &sides {
        poly = cut(&poly, side.as_ref());
        if poly.is_empty() {
            break;
        }
    }
    if poly.iter().flatten().any(|c| !c.is_finite()) {
        return Err(crate::error::Error::new(
            crate::ErrorKind::Overflow,
            "the polygon's coordinates are too large to cut in f64",
        ));
    }
    Ok(poly)
}

/// A frustum plane as a signed distance, positive inside.
type Side = Box<dyn Fn(&[f64; 3]) -> f64>;

/// One Sutherland–Hodgman step: the part of `poly` where `side ≥ 0`.
pub(crate) fn cut(poly: &[[f64; 3]], side: &dyn Fn(&[f64; 3]) -> f64) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, a) in poly.iter().enumerate() {
        let b = &poly[(i + 1) % poly.len()];
        let (da, db) = (side(a), side(b));
        if da >= 0.0 {
            out.push(*a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push([0, 1, 2].map(|k| a[k] + t * (b[k] - a[k])));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Pipeline;
    use crate::projection::{projection, ClipDepth};

    /// A ground cut for world-space storage stays inside the frustum through what an engine does
    /// with it: stored in world space as f32 and transformed by an f32 view matrix in f32
    /// arithmetic (`view * p`, the shader's product), for cameras up to 10⁴ units from the
    /// origin, near the ground and looking down at it (the cut's vertices at the screen's
    /// edges lie close to the camera). The plain cut, 2⁻¹⁶ inside, lands outside in some of the
    /// same scenes: where llvmpipe clips a sliver off a triangle.
    #[test]
    fn the_stored_cut_stays_inside_through_the_f32_transform() {
        let frustum = Frustum::new(-0.0577, 0.0577, -0.0325, 0.0325, 0.1, 1000.0).unwrap();
        let m = projection(&frustum, ClipDepth::NegOneToOne)
            .unwrap()
            .map(f64::from);
        let (mut plain_outside, mut scenes) = (0, 0);
        for i in 0..400u32 {
            let t = [0.0, 100.0, 1e3, 1e4][(i % 4) as usize];
            let (yaw, pitch) = (
                0.37 * f64::from(i),
                0.2 + 0.6 * (f64::from(i) * 0.61).fract(),
            );
            let camera = [t + 0.3719, 1.7, t - 0.6143];
            // Rows of world → eye: right, up, back, for a camera pitched down by `pitch`.
            let (sy, cy, sp, cp) = (yaw.sin(), yaw.cos(), pitch.sin(), pitch.cos());
            let back = [sy * cp, sp, cy * cp];
            let right = [cy, 0.0, -sy];
            let up = crate::footprint::cross(back, right);
            let rot = [right, up, back];
            let eye_of =
                |p: [f64; 3]| rot.map(|r| (0..3).map(|k| r[k] * (p[k] - camera[k])).sum::<f64>());
            let mut view = [0.0f32; 16];
            for (k, r) in rot.iter().enumerate() {
                for j in 0..3 {
                    view[4 * j + k] = r[j] as f32;
                }
                view[12 + k] = -(0..3).map(|j| r[j] * camera[j]).sum::<f64>() as f32;
            }
            view[15] = 1.0;
            let ground = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
                .map(|[x, z]| [t + 1000.0 * x, 0.0, t + 1000.0 * z]);
            let eye: Vec<[f64; 3]> = ground.iter().map(|&p| eye_of(p)).collect();
            let pipeline = Pipeline {
                eye_first: true,
                view: Some(view),
                world_box: Some([[t - 1000.0, 0.0, t - 1000.0], [t + 1000.0, 0.0, t + 1000.0]]),
                world_reach: camera[0].abs().max(camera[2].abs()),
                ..Pipeline::default()
            };
            // The largest excess of |x_c|, |y_c| over w, or of the near plane over −z, after the
            // f32 storage and transform; positive: outside.
            let outside = |cut: &[[f64; 3]]| {
                cut.iter()
                    .map(|e| {
                        let world = [0, 1, 2].map(|j| {
                            ((0..3).map(|k| rot[k][j] * e[k]).sum::<f64>() + camera[j]) as f32
                        });
                        let shader = [0, 1, 2].map(|k| {
                            let mut acc = view[12 + k];
                            for j in 0..3 {
                                acc += view[4 * j + k] * world[j];
                            }
                            f64::from(acc)
                        });
                        let w = -shader[2];
                        let x_c = m[0] * shader[0] + m[8] * shader[2];
                        let y_c = m[5] * shader[1] + m[9] * shader[2];
                        (x_c.abs() - w).max(y_c.abs() - w).max(0.1 - w)
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            let stored = clip_to_frustum_stored(&frustum, &eye, &pipeline).unwrap();
            if stored.is_empty() {
                continue;
            }
            scenes += 1;
            assert!(
                outside(&stored) < 0.0,
                "scene {i} (T {t}): a stored cut vertex is outside"
            );
            let plain = clip_to_frustum(&frustum, &eye).unwrap();
            plain_outside += usize::from(outside(&plain) > 0.0);
        }
        assert!(scenes > 300, "{scenes} scenes see the ground");
        assert!(
            plain_outside > 0,
            "the plain cut never lands outside: the test shows nothing"
        );
    }

    /// The stored cut checks its pipeline: a NaN or negative reach, a view without its box.
    #[test]
    fn the_stored_cut_refuses_a_bad_pipeline() {
        let frustum = Frustum::new(-0.1, 0.1, -0.1, 0.1, 0.1, 100.0).unwrap();
        let ground = [[-5.0, -1.0, 5.0], [5.0, -1.0, 5.0], [5.0, -1.0, -50.0]];
        let view = [
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ];
        for bad in [
            Pipeline {
                world_reach: f64::NAN,
                ..Pipeline::default()
            },
            Pipeline {
                world_reach: -1.0,
                ..Pipeline::default()
            },
            Pipeline {
                view: Some(view),
                ..Pipeline::default()
            },
        ] {
            let e = clip_to_frustum_stored(&frustum, &ground, &bad).unwrap_err();
            assert!(
                matches!(
                    e.kind(),
                    crate::ErrorKind::Domain | crate::ErrorKind::NotFinite
                ),
                "{bad:?}: {e}"
            );
        }
        let eye = clip_to_frustum_stored(&frustum, &ground, &Pipeline::default()).unwrap();
        assert_eq!(eye, clip_to_frustum(&frustum, &ground).unwrap());
    }

    /// The far vertices of a ground cut at large f/n stay in front of the far plane through the
    /// f32 transform an engine runs (`m10·z + m14`, the division by `w`, each rounded to f32),
    /// under `[−1, 1]` and `[0, 1]`: a relative margin of 2⁻¹⁶ in eye depth alone leaves them
    /// past window depth 1 from f/n ≈ 500 on, where the rasterizer clips them after all.
    #[test]
    fn the_far_cut_stays_inside_in_f32() {
        for ratio in [1e3, 1e5, 1e7] {
            let n = 0.1;
            let frustum = Frustum::new(-0.1, 0.1, -0.06, 0.06, n, n * ratio).unwrap();
            let reach = 2.0 * n * ratio;
            let ground: Vec<[f64; 3]> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|&(x, z)| [x * reach, -1.7, z * reach])
                .collect();
            let cut = clip_to_frustum(&frustum, &ground).unwrap();
            let farthest = cut.iter().map(|p| -p[2]).fold(0.0, f64::max);
            let far = far_cut(n, n * ratio);
            assert!(
                farthest > 0.999 * far && farthest <= far * (1.0 + 1e-12),
                "the cut reaches its far plane {far}: {farthest}"
            );
            for clip in [ClipDepth::NegOneToOne, ClipDepth::ZeroToOne] {
                let m = projection(&frustum, clip).unwrap();
                for p in &cut {
                    let z = p[2] as f32;
                    let z_c = m[10] * z + m[14];
                    let ndc = z_c / -z;
                    assert!(ndc < 1.0, "{clip:?} f/n {ratio}: {p:?} at NDC depth {ndc}");
                }
            }
        }
    }
}

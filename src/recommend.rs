//! The offset a real rasterizer needs: an error model of how a decal's stored depth can differ
//! from its base's, and the smallest projection-matrix offset that beats every term of it.
//!
//! # The model
//! A decal drawn over a coplanar base with `GL_LESS` survives at a pixel when its stored depth is
//! smaller than the base's. The offset projection (seed 000, eq. 4.1.4) lowers the decal's NDC
//! depth by the constant `Δndc = −ε·m10 = |ε|·(f+n)/(f−n)`, i.e. window depth by `Δw = Δndc/2`.
//! Each quad's computed window depth at a pixel differs from the exact depth of the plane by
//! at most `T + V + I + S` (terms below); stored values keep their order once two computed
//! values are a quantum `q` apart (the conversion to the stored format is monotone). So no decal
//! pixel is lost when
//!
//! `Δw ≥ q + 2·(T + V + I + S)`                                                    (R1)
//!
//! and zshift recommends exactly the right-hand side: `ε = −2·Δw / |m10|`, rounded outward into
//! element 10 by [`crate::offset::epsilon_matrix`]. With `u = 2⁻²⁴` (the unit roundoff of f32),
//! all terms in window-depth units, `d₁ ≤ d₂` the decal's nearest and farthest eye distances,
//! `w(d)` Walker's window depth (seed 001) and `F = f/(f−n)`:
//!
//! * `q`, the **depth quantum**: `1/(2^m − 1)` for an m-bit unsigned normalized buffer (seed 002's
//!   correction is this factor: one window step is `2/(2^m−1)` in NDC); for `GL_DEPTH_COMPONENT32F`
//!   the spacing of f32 at `w(d₂)`, `2^(⌊log₂ w(d₂)⌋ − 23)` (2⁻²⁴ for `w ≥ ½`, which is why D32F
//!   under the `[−1, 1]` mapping behaves as D24).
//! * `T`, **f32 rounding of the vertex transform**, per vertex: `clip_z = m10·z + m14` (two
//!   roundings, relative to `|m10|·d` and `|clip_z| ≤ d`), the division by `w` (reciprocal and
//!   product, two roundings relative to `|ndc|`), and `w = ½·ndc + ½` (one rounding relative to
//!   `w`): `T = u·(|m10|/2 + 1.5·|ndc|max + w(d₂))`. It applies even to bit-identical vertices,
//!   because the decal's element 10 differs from the base's.
//! * `V`, **f32 rounding of the vertex coordinates**: the decal's corners are not the base's, and
//!   each eye coordinate is rounded to f32 (relative `u`); rounding z moves depth by `u·d`,
//!   rounding x or y moves a point of a plane of slope `s` by `s·u·|x|`, `|x| ≤ e·d` inside a
//!   frustum of half-extent tangent `e = max(|l|, |r|, |b|, |t|)/n`. Through `dw/dd = F·n/d²`:
//!   `V = u·F·(n/d₁)·(1 + s·e)`. Zero when every corner of base and decal has the same f32 z
//!   ([`Scene::exact_depth`]).
//! * `I`, **f32 interpolation**: the rasterizer evaluates the plane `w₀ + ∂w/∂x·Δx + ∂w/∂y·Δy`
//!   in f32 (three roundings of values at most `w(d₂)`), from gradients set up with a relative
//!   error of about `3u`, applied across at most the decal's window-depth span:
//!   `I = u·(3·w(d₂) + 3·(w(d₂) − w(d₁)))`. Zero with [`Scene::exact_depth`]: a constant plane
//!   has exactly zero gradients, and `w₀ + 0` is exact.
//! * `S`, **sub-pixel snapping**: a rasterizer that snaps window x, y to `2^-b` pixel
//!   (`GL_SUBPIXEL_BITS` = b) *before* setting up the depth plane moves each vertex by up to
//!   `2^-(b+1)` pixel per axis, so the plane's depth moves by up to
//!   `S = 2^-(b+1)·(gₓ + g_y)`, with the window-depth gradients per pixel of a plane of eye-space
//!   slope `s` seen at axis distance `d₁`: `g_y = s·F·(t−b)/(H·d₁)` (and `(r−l)/W` for x; the
//!   tilt direction is unknown, so both use `s`). Mesa's llvmpipe snaps only coverage and sets
//!   the depth plane up from the unsnapped float positions ([`Snapping::Unsnapped`], `S = 0`):
//!   measured (`examples/sweep.rs`, last line), the snapped term alone asks 963 f32 steps of
//!   element 10 at f/n = 10, slope 3, 256², where 2 suffice.
//!
//! No term is a fudge factor and there is no safety margin: each is a worst-case bound on one
//! rounding or snapping step. The bound is loose where the worst cases do not line up: on
//! llvmpipe a quad's per-pixel depth error reaches at most 27% of `q/2 + T + V + I`, and the
//! recommendation is 1.0–4.0× the smallest offset that works (bisection over f32 steps of
//! element 10) on sloped D16 planes and 3.5–15× on sloped D24/D32F planes, where the f32 terms
//! dominate (`examples/sweep.rs` prints the table; `tests/gl_recommend.rs` asserts ≤ 20×).
//!
//! [`recommend`] covers the standard `glFrustum` mapping (NDC depth `[−1, 1]`,
//! `glDepthRange(0, 1)`); [`recommend_clip`] applies the same model to the other conventions.
//!
//! # Other clip conventions
//! Every `glFrustum`-family mapping stores `w(d) = α ± b/d` with the same `b = f·n/(f − n)` (`n`
//! for `f = ∞`; [`crate::precision::DepthMapping`]), so `|dw/dd| = b/d²` and the window
//! gradients of a sloped plane are the same in every convention: `V`, `I` and `S` keep their
//! form (`V = u·(b/d₁)·(1 + s·e)`, the standard `F·n` being `b`). What changes:
//!
//! | term | `[−1, 1]` (`GL_LESS`) | `[0, 1]` (`GL_LESS`) | reversed `[0, 1]` (`GL_GREATER`, clear 0) |
//! |---|---|---|---|
//! | window depth | `½·ndc + ½` | `ndc` | `ndc`, `n(f − d)/((f − n)d)` |
//! | `q` | at `w(d₂)` | at `w(d₂)` | at `w(d₂)`: relative for D32F, `2^(e−23)` at `w ≈ n/d` |
//! | `T` | `u·(│m10│/2 + 1.5·│ndc│ + w)` | `u·(│m10│ + 4·w_max)` | `u·(│m10│ + 4·w_max)`, `m10 = n/(f−n)` (0 at `f = ∞`) |
//! | offset | `ε` on element 10 | constant `c = −Δw` on element 10 | relative `ε` on element 14 |
//! | `Δw` at `d` | `Δw` | `Δw` | `ε·b/d` |
//!
//! Under `[0, 1]` the NDC depth is the window depth (`glDepthRange(0, 1)` maps it as `z·1 + 0`),
//! so the transform's roundings are no longer halved, and `T`'s relative part is bounded by the
//! largest window depth of the decal. The offset stays a constant through element 10
//! ([`crate::clip_offset::ndc_offset_matrix`]): `Δw = q + 2(T + V + I + S)`, (R1) unchanged.
//!
//! Under reversed Z the offset is relative ([`crate::clip_offset::relative_offset_matrix`]:
//! element 14 scaled by `1 + ε` moves every point from `d` to `d/(1 + ε)`), which gives the
//! window offset `ε·b/d` at `d`: it shrinks with distance as D32F's spacing does, and exists
//! where `m10 = 0`. (R1) must hold at every `d` of the decal, so
//! `ε = max_d (q(w(d)) + 2(T + V + I + S))·d/b`: the budget part peaks at `d₂`, the quantum part
//! at `d₂` or where `w(d)` crosses a power of two (within a binade the spacing is constant and
//! `d/b` grows as `w` falls); both are evaluated, and `ε` is divided by `1 − u` for element 14's
//! own f32 rounding. The bleed gap is the eye-space shift whose window change is
//! `Δw(d) + 2(T + V + I + S)`, the larger of its values at `d₁` and `d₂`.
//!
//! Measured on llvmpipe (`tests/gl_recommend_clip.rs`: 40 configurations at 96² in CI, 184 at
//! 256² with `ZSHIFT_CLIP_SWEEP=1`; f/n 10 to 1e6 and ∞, slopes up to 3): no lost pixel at the
//! recommendation, no bleed-through at the gap, 2–18× the smallest working offset in f32 steps
//! of the offset element (up to 30× for reversed Z on slope-3 planes, where the budget taken at
//! the decal's largest window depth meets the offset's smallest value at its far end). D32F under `[0, 1]` behaves as D24 wherever
//! `w ≥ ½` (float spacing 2⁻²⁴ there), which is most of any range with f ≥ 3n.
//!
//! # Relation to glPolygonOffset
//! `glPolygonOffset(factor, units)` adds `factor·M + units·r` to window depth, `M` the polygon's
//! largest depth gradient per pixel and `r` the format's smallest resolvable difference. (R1)
//! is the same shape: `q` and `2(T + V + I)` are constants (`units = (q + 2(T+V+I))/r`) and the
//! snapping term `2S ≤ 2^-b·2M` is slope-scaled (`factor = 2^(1−b)`). The matrix offset is one
//! constant for the whole decal, so zshift evaluates the slope term at the decal's worst depth
//! instead of per polygon; [`Recommendation::polygon_offset`] gives the equivalent pair, with `r`
//! as [`crate::polygon_offset::resolvable_difference`] takes it for OpenGL (Mesa's `1/(2^m − 1)`).
//!
//! # Bleed-through
//! An occluder in front of the base must not lose to the decal. Its computed depth has the same
//! error budget, and a computed decal depth at or above the occluder's stores at or above it
//! (monotone conversion), so an occluder whose exact window depth is below the base's by at
//! least `Δw + 2(T + V + I + S) = 2Δw − q` is never overdrawn; [`Recommendation::bleed_gap`] is
//! that separation as an eye-space distance along the line of sight at `d₂`, where it is largest.

use crate::domain::{domain, finite, representable};
use crate::error::Result;
use crate::projection::Frustum;

/// The unit roundoff of f32: half an ulp of 1.
const F32_UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// What the depth attachment stores: the crate's one depth-format type.
pub use crate::precision::DepthFormat;

/// Whether the rasterizer snaps vertex positions before depth setup (see [`crate::profile`]).
pub use crate::profile::Snapping;

/// What a scene knows about one decal and the surface under it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// The `glFrustum` the base is drawn with (OpenGL conventions, NDC depth `[−1, 1]`).
    pub frustum: Frustum,
    /// Viewport width and height in pixels (`glViewport`).
    pub viewport: [u32; 2],
    /// The depth attachment's format.
    pub format: DepthFormat,
    /// The decal's nearest and farthest eye distance, `n ≤ d₁ ≤ d₂ ≤ f` (equal for a point
    /// estimate). `d₁` also stands for the distance at which the decal's plane crosses the view
    /// axis in the slope term: exact for a decal centred on the axis, conservative when the
    /// plane's axis crossing is farther than the decal's nearest point.
    pub depth_range: [f64; 2],
    /// Eye-space tilt of the plane: `|∂z/∂x| + |∂z/∂y|` (0 facing the camera, 3 ≈ 72°).
    pub slope: f64,
    /// Every corner of base and decal has the same f32 eye-space z (a camera-facing plane whose
    /// vertices reach the vertex shader unrotated): the terms `V` and `I` vanish. Requires
    /// `slope == 0`.
    pub exact_depth: bool,
    /// How the rasterizer positions vertices before depth setup.
    pub snapping: Snapping,
}

/// The worst-case error of one quad's computed window depth, term by term (window-depth units),
/// and the depth quantum. See the module docs for each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorTerms {
    /// `q`: the smallest difference the stored format keeps.
    pub quantum: f64,
    /// `T`: f32 rounding in the vertex transform and viewport mapping.
    pub transform: f64,
    /// `V`: f32 rounding of the decal's eye-space coordinates.
    pub vertex: f64,
    /// `I`: f32 rounding in the rasterizer's depth-plane evaluation.
    pub interpolation: f64,
    /// `S`: sub-pixel snapping of a sloped plane.
    pub snap: f64,
}

impl ErrorTerms {
    /// The right-hand side of (R1): `q + 2(T + V + I + S)`, in window depth.
    pub fn window_offset(&self) -> f64 {
        self.quantum + 2.0 * (self.transform + self.vertex + self.interpolation + self.snap)
    }
}

/// The recommended offset for a [`Scene`], in every form an engine may apply it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recommendation {
    /// ε for [`crate::offset::epsilon_matrix`] (negative: toward the camera), eq. 4.1.3.
    pub epsilon: f64,
    /// The NDC depth offset `−ε·m10 = 2·window_offset`.
    pub ndc_offset: f64,
    /// The window-depth offset (R1).
    pub window_offset: f64,
    /// The eye-space shift δ (toward the camera) at `Pz = −d₂` that gives the same ε through
    /// eq. 4.1.7, for `zshift_load_offset_matrix(…, delta, pz = −d₂)`.
    pub delta_at_far: f64,
    /// Occluders nearer than the base by at least this eye-space distance along the line of
    /// sight are never overdrawn by the decal.
    pub bleed_gap: f64,
    /// The equivalent `glPolygonOffset(−factor, −units)` magnitudes, with `r` = the quantum.
    pub polygon_offset: [f64; 2],
    /// The terms the offset was built from.
    pub terms: ErrorTerms,
}

/// The smallest offset that model (R1) guarantees ends z-fighting for `scene`, with its bleed gap.
///
/// Convention: OpenGL, NDC depth `[−1, 1]`, the decal drawn with element 10 scaled by `1 + ε`
/// (seed 000 eq. 4.1.3), the base with the plain matrix, depth test `GL_LESS` or `GL_LEQUAL`.
///
/// # Errors
/// [`crate::ErrorKind::NotFinite`] for NaN or infinite depths or slope;
/// [`crate::ErrorKind::Domain`] for a zero viewport, `depth_range` outside `[n, f]` or
/// decreasing, a negative slope, `exact_depth` with a nonzero slope, or bits outside 1..=32;
/// [`crate::ErrorKind::Overflow`] if a result overflows.
pub fn recommend(scene: &Scene) -> Result<Recommendation> {
    check(scene)?;
    let terms = error_terms(scene)?;
    let window_offset = terms.window_offset();
    let planes = scene.frustum.planes();
    let m10 = planes.sum_over_span();
    let epsilon = representable(-2.0 * window_offset / m10, "epsilon overflows")?;
    let d2 = scene.depth_range[1];
    let delta_at_far = delta_for_epsilon(scene, epsilon, -d2)?;
    let bleed_gap = gap_for_window_difference(scene, 2.0 * window_offset - terms.quantum, d2);
    let units = (terms.window_offset() - 2.0 * terms.snap) / terms.quantum;
    let factor = match scene.snapping {
        Snapping::SubpixelBits(b) => 2f64.powi(1 - b as i32),
        Snapping::Unsnapped => 0.0,
    };
    // Every output must fit a double (a zero quantum made `units` +∞ with ZSHIFT_OK).
    let fits = |x: f64| representable(x, "a recommended value overflows f64");
    Ok(Recommendation {
        epsilon,
        ndc_offset: fits(2.0 * window_offset)?,
        window_offset: fits(window_offset)?,
        delta_at_far: fits(delta_at_far)?,
        bleed_gap: fits(bleed_gap)?,
        polygon_offset: [fits(factor)?, fits(units)?],
        terms,
    })
}

/// The model's terms for `scene` (see the module docs), without the final sum.
///
/// # Errors
/// As [`recommend`].
pub fn error_terms(scene: &Scene) -> Result<ErrorTerms> {
    check(scene)?;
    let u = F32_UNIT_ROUNDOFF;
    let planes = scene.frustum.planes();
    let (n, big_f) = (planes.near(), planes.far_over_span());
    let [d1, d2] = scene.depth_range;
    let (w1, w2) = (window(scene, d1)?, window(scene, d2)?);
    let ndc_max = (2.0 * w1 - 1.0).abs().max((2.0 * w2 - 1.0).abs());
    let transform = u * (planes.sum_over_span() / 2.0 + 1.5 * ndc_max + w2);
    let (vertex, interpolation) = if scene.exact_depth {
        (0.0, 0.0)
    } else {
        let e = half_extent_tangent(&scene.frustum)?;
        let vertex = u * big_f * (n / d1) * (1.0 + scene.slope * e);
        (vertex, u * (3.0 * w2 + 3.0 * (w2 - w1)))
    };
    Ok(ErrorTerms {
        quantum: quantum(scene.format, w2)?,
        transform,
        vertex,
        interpolation,
        snap: snap(scene)?,
    })
}

/// The window-depth gradient per pixel `(gₓ, g_y)` of a plane of eye-space slope `s` that
/// crosses the view axis at distance `d`: `s·F·(r−l)/(W·d)` and `s·F·(t−b)/(H·d)`.
///
/// # Errors
/// As [`recommend`].
pub fn window_gradient(scene: &Scene, d: f64) -> Result<[f64; 2]> {
    let m = scene.frustum.to_cols_array_f64()?;
    let [w, h] = scene.viewport.map(f64::from);
    let big_f = scene.frustum.planes().far_over_span();
    let n = scene.frustum.planes().near();
    // 2n/(r − l) = m0, so (r − l)/n = 2/m0 (likewise m5 for t − b).
    let gx = scene.slope * big_f * (2.0 / m[0]).abs() * n / (w * d);
    let gy = scene.slope * big_f * (2.0 / m[5]).abs() * n / (h * d);
    Ok([gx, gy])
}

fn snap(scene: &Scene) -> Result<f64> {
    match scene.snapping {
        Snapping::Unsnapped => Ok(0.0),
        Snapping::SubpixelBits(b) => {
            let [gx, gy] = window_gradient(scene, scene.depth_range[0])?;
            Ok(2f64.powi(-(b as i32) - 1) * (gx + gy))
        }
    }
}

/// `q` for a format at window depth `w` (the largest the decal reaches): one step of a UNORM
/// buffer, or the f32 spacing at `w` for `GL_DEPTH_COMPONENT32F`.
fn quantum(format: DepthFormat, w: f64) -> Result<f64> {
    format.spacing_at(w.clamp(0.0, 1.0))
}

/// `e = max(|l|, |r|, |b|, |t|)/n`, from the matrix: `(r ± l)/(r − l)` and `2n/(r − l)`.
fn half_extent_tangent(frustum: &Frustum) -> Result<f64> {
    let m = frustum.to_cols_array_f64()?;
    let ex = (m[8].abs() + 1.0) / m[0].abs();
    let ey = (m[9].abs() + 1.0) / m[5].abs();
    Ok(ex.max(ey))
}

/// Walker's window depth (seed 001) at a distance `check` has put inside `[n, f]`.
fn window(scene: &Scene, d: f64) -> Result<f64> {
    let planes = scene.frustum.planes();
    crate::precision::window_depth(planes.near(), planes.far(), d)
}

/// δ with `ε(δ, Pz) = epsilon` (eq. 4.1.7 solved for δ): `δ = −ε·Pz² / (K + ε·Pz)`,
/// `K = 2fn/(f+n)`.
fn delta_for_epsilon(scene: &Scene, epsilon: f64, pz: f64) -> Result<f64> {
    let planes = scene.frustum.planes();
    let k = 2.0 * planes.near() / planes.sum_over_span() * planes.far_over_span();
    let denominator = k + epsilon * pz;
    if denominator <= 0.0 {
        return Err(domain(
            "the recommended offset exceeds what element 10 can carry at this depth",
        ));
    }
    representable(-epsilon * pz * (pz / denominator), "delta overflows")
}

/// The eye-space distance `G` in front of distance `d` whose window depth is lower by `dw`:
/// `F·n·(1/(d−G) − 1/d) = dw`, so `G = d·x/(1 + x)` with `x = dw·d/(F·n)`.
fn gap_for_window_difference(scene: &Scene, dw: f64, d: f64) -> f64 {
    let planes = scene.frustum.planes();
    let x = dw * d / (planes.far_over_span() * planes.near());
    if x.is_infinite() {
        // A near plane so small that x overflows: x/(1 + x) → 1 (∞/∞ gave NaN).
        return d;
    }
    d * (x / (1.0 + x))
}

fn check(scene: &Scene) -> Result<()> {
    let planes = scene.frustum.planes();
    let [d1, d2] = scene.depth_range;
    planes.check_distance(d1)?;
    planes.check_distance(d2)?;
    if d1 > d2 {
        return Err(domain(
            "the decal's depth range must be [nearest, farthest]",
        ));
    }
    if scene.viewport.contains(&0) {
        return Err(domain("the viewport must have a nonzero width and height"));
    }
    finite(scene.slope, "the plane slope is NaN or infinite")?;
    if scene.slope < 0.0 {
        return Err(domain("the plane slope |dz/dx| + |dz/dy| must be >= 0"));
    }
    if scene.exact_depth && scene.slope != 0.0 {
        return Err(domain(
            "exact_depth needs a plane facing the camera (slope 0)",
        ));
    }
    if let Snapping::SubpixelBits(b) = scene.snapping {
        if b > 32 {
            return Err(domain("GL_SUBPIXEL_BITS must lie in 0..=32"));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// The same model under the other clip conventions: `[0, 1]` clip depth and reversed Z.
// ---------------------------------------------------------------------------------------------

use crate::precision::DepthMapping;
use crate::projection::ClipDepth;

/// The recommended offset for a [`Scene`] drawn under a clip-depth convention, in the form that
/// convention needs, with the decal's matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipRecommendation {
    /// The convention the offset is for.
    pub clip: ClipDepth,
    /// The constant NDC depth offset `c` for [`crate::clip_offset::ndc_offset_matrix`] (element
    /// 10 becomes `m10 − c`; negative: toward the camera) under `NegOneToOne` and `ZeroToOne`;
    /// 0 under `ReversedZeroToOne`.
    pub ndc_offset: f64,
    /// The relative offset `ε` for [`crate::clip_offset::relative_offset_matrix`] (element 14
    /// scaled by `1 + ε`, every point moved from `d` to `d/(1 + ε)`) under
    /// `ReversedZeroToOne`; 0 otherwise.
    pub relative_epsilon: f64,
    /// The convention's ε in one number: Lengyel's element-10 ε (`m10·(1 + ε)` is `m10 − c`,
    /// so `ε = −c/m10`, negative) under `NegOneToOne` and `ZeroToOne`; [`Self::relative_epsilon`]
    /// (positive) under `ReversedZeroToOne`.
    pub epsilon: f64,
    /// The equivalent `glPolygonOffset(−factor, −units)` magnitudes with `r` = the quantum, as
    /// [`Recommendation::polygon_offset`], under `NegOneToOne` and `ZeroToOne`; `[0, 0]` under
    /// reversed Z, where the offset is relative and no constant `units` matches it.
    pub polygon_offset: [f64; 2],
    /// The smallest window-depth offset over the decal (at `d₂`; constant under `NegOneToOne`
    /// and `ZeroToOne`, `ε·b/d₂` under reversed Z).
    pub window_offset: f64,
    /// The eye-space shift toward the camera at `d₂` that the offset amounts to there.
    pub delta_at_far: f64,
    /// Occluders nearer than the base by at least this eye-space distance along the line of
    /// sight are never overdrawn by the decal.
    pub bleed_gap: f64,
    /// The decal's projection matrix (f32, column-major), offset rounded outward; draw the base
    /// with [`crate::projection::projection`] of the same frustum and convention.
    pub matrix: [f32; 16],
    /// The terms the offset was built from (window-depth units; `quantum` at the decal's
    /// farthest point).
    pub terms: ErrorTerms,
}

/// The smallest offset that model (R1) guarantees ends z-fighting for `scene` drawn under
/// `clip` (see "Other clip conventions" in the module docs), with its matrix and bleed gap.
///
/// Conventions: OpenGL right-handed eye space; `NegOneToOne` is `glFrustum` with `GL_LESS`
/// and gives exactly [`recommend`]'s offset; `ZeroToOne` is
/// `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)` with `GL_LESS` (Direct3D/Vulkan clip space),
/// offset through element 10; `ReversedZeroToOne` adds `glDepthFunc(GL_GREATER)` and
/// `glClearDepth(0)`, offset through element 14 (relative, works where `m10 = 0`). `f` may be
/// `+∞` in every convention.
///
/// # Errors
/// As [`recommend`]; [`crate::ErrorKind::Overflow`] if an element of the matrix leaves f32.
pub fn recommend_clip(scene: &Scene, clip: ClipDepth) -> Result<ClipRecommendation> {
    check(scene)?;
    let frustum = &scene.frustum;
    let m = crate::projection::projection_f64(frustum, clip)?;
    if clip == ClipDepth::NegOneToOne {
        let r = recommend(scene)?;
        return Ok(ClipRecommendation {
            clip,
            epsilon: r.epsilon,
            polygon_offset: r.polygon_offset,
            ndc_offset: -r.ndc_offset,
            relative_epsilon: 0.0,
            window_offset: r.window_offset,
            delta_at_far: r.delta_at_far,
            bleed_gap: r.bleed_gap,
            matrix: crate::offset::epsilon_matrix(frustum, r.epsilon)?,
            terms: r.terms,
        });
    }
    let mapping = mapping_of(scene, clip)?;
    let terms = clip_error_terms(scene, clip)?;
    let budget = 2.0 * (terms.transform + terms.vertex + terms.interpolation + terms.snap);
    let [d1, d2] = scene.depth_range;
    let fits = |x: f64| representable(x, "a recommended value overflows f64");
    let (ndc_offset, relative_epsilon, window_offset, matrix) = if clip == ClipDepth::ZeroToOne {
        // Window depth = NDC depth: the constant offset is (R1) itself.
        let dw = fits(terms.window_offset())?;
        let c = -dw / mapping.window_per_ndc();
        (c, 0.0, dw, crate::clip_offset::ndc_offset_matrix(&m, c)?)
    } else {
        let eps = reversed_epsilon(scene, &mapping, budget)?;
        let b = scale(scene);
        let matrix = crate::clip_offset::relative_offset_matrix(&m, eps)?;
        (0.0, eps, fits(eps * (b / d2))?, matrix)
    };
    // The window offset at d: constant, or ε·b/d under reversed Z.
    let offset_at = |d: f64| {
        if relative_epsilon > 0.0 {
            relative_epsilon * (scale(scene) / d)
        } else {
            window_offset
        }
    };
    let toward = |dw: f64| if mapping.is_reversed() { dw } else { -dw };
    let delta_at_far = mapping.shift_of_window_change(toward(window_offset), d2)?;
    let mut bleed_gap = 0.0f64;
    for d in [d1, d2] {
        let g = match mapping.shift_of_window_change(toward(offset_at(d) + budget), d) {
            Ok(g) => g.min(d),
            // Past the eye: no occluder in front of the base is safe from the decal.
            Err(_) => d,
        };
        bleed_gap = bleed_gap.max(g);
    }
    let (epsilon, polygon_offset) = if relative_epsilon > 0.0 {
        (relative_epsilon, [0.0, 0.0])
    } else {
        let factor = match scene.snapping {
            Snapping::SubpixelBits(b) => 2f64.powi(1 - b as i32),
            Snapping::Unsnapped => 0.0,
        };
        let units = (window_offset - 2.0 * terms.snap) / terms.quantum;
        (-ndc_offset / m[10], [factor, fits(units)?])
    };
    Ok(ClipRecommendation {
        clip,
        epsilon: fits(epsilon)?,
        polygon_offset,
        ndc_offset: fits(ndc_offset)?,
        relative_epsilon,
        window_offset,
        delta_at_far: fits(delta_at_far)?,
        bleed_gap: fits(bleed_gap)?,
        matrix,
        terms,
    })
}

/// The model's terms for `scene` under `clip` (see "Other clip conventions" in the module
/// docs); `NegOneToOne` gives exactly [`error_terms`].
///
/// # Errors
/// As [`recommend`].
pub fn clip_error_terms(scene: &Scene, clip: ClipDepth) -> Result<ErrorTerms> {
    if clip == ClipDepth::NegOneToOne {
        return error_terms(scene);
    }
    check(scene)?;
    let u = F32_UNIT_ROUNDOFF;
    let mapping = mapping_of(scene, clip)?;
    let (m10, _) = crate::projection::depth_row(&scene.frustum.planes(), clip);
    let [d1, d2] = scene.depth_range;
    let (w1, w2) = (mapping.window_depth(d1)?, mapping.window_depth(d2)?);
    let w_max = w1.max(w2);
    // NDC = window depth here: the product m10·z rounds relative to |m10|·d, i.e. u·|m10| after
    // the division by w = d; the sum, reciprocal and product round relative to |ndc| ≤ w_max;
    // the viewport map z·1 + 0 is exact but counted (one rounding relative to w_max).
    let transform = u * (m10.abs() + 4.0 * w_max);
    let (vertex, interpolation) = if scene.exact_depth {
        (0.0, 0.0)
    } else {
        let e = half_extent_tangent(&scene.frustum)?;
        let nearest = d1.min(d2);
        let vertex = u * (scale(scene) / nearest) * (1.0 + scene.slope * e);
        (vertex, u * (3.0 * w_max + 3.0 * (w1 - w2).abs()))
    };
    // The spacing at the decal's smallest window depth: its farthest point under either
    // convention (reversed Z stores n/d-like values that shrink with distance).
    let w_min = w1.min(w2);
    Ok(ErrorTerms {
        quantum: quantum(scene.format, w_min)?,
        transform,
        vertex,
        interpolation,
        snap: snap(scene)?,
    })
}

/// `b = f·n/(f − n)` (`n` for `f = ∞`): every `glFrustum`-family mapping stores
/// `w(d) = α ± b/d`, so `|dw/dd| = b/d²` and the window gradients match the standard ones.
fn scale(scene: &Scene) -> f64 {
    let planes = scene.frustum.planes();
    planes.near() * planes.far_over_span()
}

fn mapping_of(scene: &Scene, clip: ClipDepth) -> Result<DepthMapping> {
    let planes = scene.frustum.planes();
    DepthMapping::projection(planes.near(), planes.far(), clip)
}

/// The relative ε under reversed Z: the window offset it gives at `d` is `ε·b/d`, which must
/// reach `q(w(d)) + budget` at every `d` of the decal. The budget part is largest at `d₂`; the
/// quantum part `q(w)·d/b` peaks, within each binade of float depth, where `w` is smallest, so
/// at `d₂` or where `w(d)` is a power of two. Element 14 rounded to f32 (`p ≥ b·(1 − u)`)
/// carries `ε·p`, hence the final `1/(1 − u)`.
fn reversed_epsilon(scene: &Scene, mapping: &DepthMapping, budget: f64) -> Result<f64> {
    let b = scale(scene);
    let [d1, d2] = scene.depth_range;
    let need = |d: f64| -> Result<f64> {
        let q = quantum(scene.format, mapping.window_depth(d)?)?;
        Ok((q + budget) * (d / b))
    };
    let mut eps = need(d1)?.max(need(d2)?);
    let (w_lo, w_hi) = (mapping.window_depth(d2)?, mapping.window_depth(d1)?);
    if !scene.format.is_unorm() && w_lo > 0.0 {
        // exp2, not powi: powi(k) for k < −1022 is 1/2^−k, which overflows to ∞ and gives 0,
        // and a walk from 0 never ends (a subnormal window depth reaches here).
        let mut p = (w_lo.log2().floor() + 1.0).exp2();
        while p > 0.0 && p <= w_hi {
            let d = mapping.distance_at_window(p)?;
            eps = eps.max((p * 2f64.powi(-23) + budget) * (d / b));
            p *= 2.0;
        }
    }
    representable(
        eps / (1.0 - F32_UNIT_ROUNDOFF),
        "the relative epsilon overflows f64",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ErrorKind;

    fn scene(format: DepthFormat, slope: f64, snapping: Snapping) -> Scene {
        let e = 0.577_350_269_189_625_7;
        Scene {
            frustum: Frustum::new(-e, e, -e, e, 1.0, 1e3).unwrap(),
            viewport: [256, 256],
            format,
            depth_range: [80.0, 120.0],
            slope,
            exact_depth: false,
            snapping,
        }
    }

    /// ε, δ and the NDC offset agree through the seed's own equations (4.1.4 and 4.1.7, the
    /// latter through `offset::epsilon`, an independent implementation).
    #[test]
    fn the_forms_of_the_offset_agree_through_the_seed_equations() {
        let s = scene(DepthFormat::Unorm24, 1.0, Snapping::SubpixelBits(8));
        let r = recommend(&s).unwrap();
        let m10 = (1e3 + 1.0) / (1e3 - 1.0);
        assert!((-r.epsilon * m10 - r.ndc_offset).abs() <= 1e-15 * r.ndc_offset);
        assert_eq!(r.ndc_offset, 2.0 * r.window_offset);
        let eps = crate::offset::epsilon(1.0, 1e3, r.delta_at_far, -120.0).unwrap();
        assert!(
            (eps - r.epsilon).abs() <= 1e-12 * r.epsilon.abs(),
            "{eps} vs {}",
            r.epsilon
        );
    }

    /// The bleed gap is the eye distance whose window-depth difference (Walker's f(d), through
    /// `precision::window_depth`) is `2Δw − q` at the far end of the decal.
    #[test]
    fn the_bleed_gap_spans_twice_the_offset_less_a_quantum_in_window_depth() {
        let s = scene(DepthFormat::Unorm16, 3.0, Snapping::SubpixelBits(8));
        let r = recommend(&s).unwrap();
        let w = |d| crate::precision::window_depth(1.0, 1e3, d).unwrap();
        let dw = w(120.0) - w(120.0 - r.bleed_gap);
        let want = 2.0 * r.window_offset - r.terms.quantum;
        assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
    }

    /// Terms that the model says vanish do, and the ones that grow with slope do.
    #[test]
    fn terms_vanish_and_grow_where_the_model_says() {
        let facing = Scene {
            exact_depth: true,
            ..scene(DepthFormat::Float32, 0.0, Snapping::SubpixelBits(8))
        };
        let t = error_terms(&facing).unwrap();
        assert_eq!((t.vertex, t.interpolation, t.snap), (0.0, 0.0, 0.0));
        assert_eq!(
            t.quantum,
            2f64.powi(-24),
            "window depths near 1 have f32 spacing 2^-24"
        );
        let unsnapped =
            error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::Unsnapped)).unwrap();
        assert_eq!(unsnapped.snap, 0.0);
        let s1 = error_terms(&scene(DepthFormat::Float32, 1.0, Snapping::SubpixelBits(8))).unwrap();
        let s3 = error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::SubpixelBits(8))).unwrap();
        assert!((s3.snap / s1.snap - 3.0).abs() < 1e-12);
        assert!(s3.vertex > s1.vertex);
    }

    fn f32_spacing(w: f64) -> f64 {
        // The gap to the next f32 above w as f32 (w a normal number, not a power of two's edge
        // case: the spacing above and below agree inside a binade).
        let x = w as f32;
        f64::from(f32::from_bits(x.to_bits() + 1)) - f64::from(x)
    }

    /// `NegOneToOne` through `recommend_clip` is `recommend`'s offset and matrix.
    #[test]
    fn the_standard_convention_is_unchanged() {
        let s = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
        let r = recommend(&s).unwrap();
        let c = recommend_clip(&s, ClipDepth::NegOneToOne).unwrap();
        assert_eq!(c.ndc_offset, -r.ndc_offset);
        assert_eq!(c.bleed_gap, r.bleed_gap);
        assert_eq!(
            c.matrix,
            crate::offset::epsilon_matrix(&s.frustum, r.epsilon).unwrap()
        );
    }

    /// Under `[0, 1]` the f32 matrix lowers NDC (= window) depth by at least the window offset
    /// and by at most one f32 step of element 10 more; the plain projection is untouched
    /// elsewhere. Differences of nearby f32 values are exact in f64.
    #[test]
    fn zero_to_one_carries_the_window_offset_in_element_10() {
        let s = scene(DepthFormat::Unorm24, 3.0, Snapping::SubpixelBits(8));
        let c = recommend_clip(&s, ClipDepth::ZeroToOne).unwrap();
        let plain = crate::projection::projection(&s.frustum, ClipDepth::ZeroToOne).unwrap();
        let lowered = f64::from(c.matrix[10]) - f64::from(plain[10]);
        let ulp = f64::from(plain[10].abs()) * 2f64.powi(-23);
        assert!(lowered >= c.window_offset && lowered <= c.window_offset + ulp);
        assert_eq!(c.ndc_offset, -c.window_offset);
        assert_eq!(
            (c.relative_epsilon, c.terms.quantum),
            (0.0, 1.0 / 16_777_215.0)
        );
        for i in (0..16).filter(|&i| i != 10) {
            assert_eq!(c.matrix[i], plain[i]);
        }
    }

    /// Reversed Z, infinite far, D32F: element 10 is 0 and stays 0; element 14 is scaled by at
    /// least 1 + ε; and at both ends of the decal (and where `w = n/d` crosses ⅛, a binade
    /// edge inside it) the window offset `ε·n/d` beats the f32 spacing there plus the error
    /// budget, the spacing taken from the bits of the stored value.
    #[test]
    fn reversed_infinite_float_beats_the_spacing_everywhere_on_the_decal() {
        let e = 0.5;
        let s = Scene {
            frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
            depth_range: [6.0, 10.0],
            ..scene(DepthFormat::Float32, 1.0, Snapping::Unsnapped)
        };
        let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
        let plain =
            crate::projection::projection(&s.frustum, ClipDepth::ReversedZeroToOne).unwrap();
        assert_eq!((plain[10], c.matrix[10]), (0.0, 0.0));
        assert!(f64::from(c.matrix[14]) / f64::from(plain[14]) - 1.0 >= c.relative_epsilon);
        let t = c.terms;
        let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
        for d in [6.0, 8.0, 10.0] {
            let w = 1.0 / d;
            let need = if d == 8.0 {
                2f64.powi(-26)
            } else {
                f32_spacing(w)
            } + budget;
            assert!(c.relative_epsilon * w >= need, "d = {d}");
        }
        // The binade edge decides: without it the far end alone would ask less.
        let far_only = (f32_spacing(0.1) + budget) * 10.0;
        assert!(c.relative_epsilon > far_only);
    }

    /// The bleed gap under reversed Z moves the base's window depth (n/d, infinite far) by the
    /// offset plus the budget at the decal's far end: `n/(d − G) − n/d`.
    #[test]
    fn reversed_bleed_gap_spans_the_offset_and_the_budget() {
        let e = 0.5;
        let s = Scene {
            frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
            depth_range: [50.0, 60.0],
            ..scene(DepthFormat::Float32, 0.5, Snapping::Unsnapped)
        };
        let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
        let t = c.terms;
        let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
        let dw = 1.0 / (60.0 - c.bleed_gap) - 1.0 / 60.0;
        let want = c.relative_epsilon / 60.0 + budget;
        assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
    }

    #[test]
    fn bad_scenes_are_refused_with_their_kind() {
        let good = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
        let kind = |s: Scene| recommend(&s).unwrap_err().kind();
        assert_eq!(
            kind(Scene {
                slope: f64::NAN,
                ..good
            }),
            ErrorKind::NotFinite
        );
        assert_eq!(
            kind(Scene {
                slope: -1.0,
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                exact_depth: true,
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                depth_range: [120.0, 80.0],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                depth_range: [0.5, 80.0],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                viewport: [0, 256],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                snapping: Snapping::SubpixelBits(40),
                ..good
            }),
            ErrorKind::Domain
        );
    }
}

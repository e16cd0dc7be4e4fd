//! Orthographic projections (`glOrtho`): builders for every clip convention, the constant depth
//! offset through element 14, and the exact depth step, which is the same at every distance.
//!
//! Depth under `glOrtho(l, r, b, t, n, f)` is linear in the eye distance `d` (`z = −d`):
//! `z_ndc = m10·z + m14`. Window depth (`glDepthRange(0, 1)`) is `(d − n)/(f − n)` under
//! `[−1, 1]` and `[0, 1]`, `(f − d)/(f − n)` reversed. So a constant NDC offset is the same eye
//! shift everywhere, and a UNORM depth step is `q·(f − n)` at every distance (for float depth,
//! `2^(e−23)·(f − n)` with `e` the exponent of the stored depth). Unlike a perspective frustum,
//! `n` may be 0 or negative (the near plane behind the eye); `f > n`.

use crate::domain::{domain, finite};
use crate::double_double::unit_scale;
use crate::double_double::DoubleDouble;
use crate::error::Result;
use crate::offset::rounded_outward;
use crate::precision::DepthFormat;
use crate::projection::{to_f32, ClipDepth};
use crate::rounding::{decided, enclosed, nearest_of_ratio, two_sum, Ratio};

/// The six parameters of `glOrtho`, validated: finite, `l ≠ r`, `b ≠ t`, `n < f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ortho {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    near: f64,
    far: f64,
}

impl Ortho {
    /// Checks the parameters as `glOrtho` would (it raises `GL_INVALID_VALUE` for `l = r`,
    /// `b = t`, `n = f`), and more strictly (`n < f`, all finite).
    ///
    /// # Errors
    /// [`crate::ErrorKind::NotFinite`] for NaN or an infinity; [`crate::ErrorKind::Domain`] if
    /// `l = r`, `b = t` or `f ≤ n`.
    pub fn new(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Self> {
        for (name, x) in [("l", l), ("r", r), ("b", b), ("t", t), ("n", n), ("f", f)] {
            finite(x, "a glOrtho parameter is NaN or infinite")
                .map_err(|e| e.with_value(name, x))?;
        }
        if l == r {
            return Err(domain("the orthographic box has zero width: l = r").with_value("l", l));
        }
        if b == t {
            return Err(domain("the orthographic box has zero height: b = t").with_value("b", b));
        }
        if f <= n {
            return Err(
                domain("the orthographic far plane f must be greater than n").with_value("f", f),
            );
        }
        Ok(Self {
            left: l,
            right: r,
            bottom: b,
            top: t,
            near: n,
            far: f,
        })
    }

    /// The near plane distance `n` (may be 0 or negative).
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The far plane distance `f`.
    pub fn far(&self) -> f64 {
        self.far
    }

    /// `(l, r, b, t, n, f)`, as passed to [`Self::new`].
    pub fn parameters(&self) -> (f64, f64, f64, f64, f64, f64) {
        (
            self.left,
            self.right,
            self.bottom,
            self.top,
            self.near,
            self.far,
        )
    }

    /// The window depth in `[0, 1]` at eye distance `d` under `clip` (`glDepthRange(0, 1)`):
    /// `(d − n)/(f − n)`, or `(f − d)/(f − n)` reversed.
    ///
    /// # Errors
    /// [`crate::ErrorKind::NotFinite`] for NaN or ±∞; [`crate::ErrorKind::Domain`] unless
    /// `n ≤ d ≤ f`.
    pub fn window_depth(&self, clip: ClipDepth, d: f64) -> Result<f64> {
        self.check_distance(d)?;
        let span = self.far - self.near;
        Ok(if clip == ClipDepth::ReversedZeroToOne {
            (self.far - d) / span
        } else {
            (d - self.near) / span
        })
    }

    /// The exact depth step at eye distance `d`: the shift toward the camera that moves the
    /// stored window depth by the format's spacing `r` at `w(d)` (`1/(2^m − 1)` for UNORM,
    /// `2^(e−23)` for FLOAT32): `r·(f − n)`, the same at every distance for UNORM.
    ///
    /// # Errors
    /// As [`Self::window_depth`].
    pub fn depth_step(&self, clip: ClipDepth, format: DepthFormat, d: f64) -> Result<f64> {
        let w = self.window_depth(clip, d)?;
        Ok(format.spacing_at(w)? * (self.far - self.near))
    }

    fn check_distance(&self, d: f64) -> Result<()> {
        finite(d, "the eye distance d is NaN or infinite").map_err(|e| e.with_value("d", d))?;
        if d < self.near || d > self.far {
            return Err(domain("the eye distance d must lie in [n, f]").with_value("d", d));
        }
        Ok(())
    }
}

/// The depth row `(m10, m14)` of `glOrtho` under a convention:
///
/// | convention | m10 | m14 |
/// |---|---|---|
/// | `NegOneToOne` (`glOrtho`) | `−2/(f−n)` | `−(f+n)/(f−n)` |
/// | `ZeroToOne` | `−1/(f−n)` | `−n/(f−n)` |
/// | `ReversedZeroToOne` | `1/(f−n)` | `f/(f−n)` |
pub fn depth_row(ortho: &Ortho, clip: ClipDepth) -> (f64, f64) {
    let (n, f) = (ortho.near, ortho.far);
    let span = f - n;
    match clip {
        ClipDepth::NegOneToOne => (-2.0 / span, -(f + n) / span),
        ClipDepth::ZeroToOne => (-1.0 / span, -n / span),
        ClipDepth::ReversedZeroToOne => (1.0 / span, f / span),
    }
}

/// The `glOrtho` matrix with the depth row of `clip`, in f64, column-major:
/// `m0 = 2/(r−l)`, `m5 = 2/(t−b)`, `m12 = −(r+l)/(r−l)`, `m13 = −(t+b)/(t−b)`, `m15 = 1`.
pub fn ortho_f64(ortho: &Ortho, clip: ClipDepth) -> [f64; 16] {
    let (width, height) = (ortho.right - ortho.left, ortho.top - ortho.bottom);
    let mut m = [0.0; 16];
    m[0] = 2.0 / width;
    m[5] = 2.0 / height;
    m[12] = -(ortho.right + ortho.left) / width;
    m[13] = -(ortho.top + ortho.bottom) / height;
    m[15] = 1.0;
    (m[10], m[14]) = depth_row(ortho, clip);
    m
}

/// The `glOrtho` matrix of `clip` in f32, each element the nearest f32 of its exact value (ties
/// to even), decided as in [`crate::rounding`]: from the f64 estimate of [`ortho_f64`] (at
/// most three roundings) when it is far enough from an f32 rounding boundary, else exactly.
///
/// # Errors
/// [`crate::ErrorKind::Overflow`] if an element leaves f32.
pub fn ortho(ortho: &Ortho, clip: ClipDepth) -> Result<[f32; 16]> {
    match ortho_fast(ortho, clip) {
        Some(m) => Ok(m),
        None => ortho_decided(ortho, clip, true),
    }
}

/// The fast path of [`ortho`] alone: `None` where it defers (an element too close to an f32
/// rounding boundary, or an element 0, 5 or 10 that is zero or not finite). When it returns a
/// matrix, that matrix is [`ortho`]'s (and [`ortho_exact`]'s).
#[inline(always)]
pub fn ortho_fast(ortho: &Ortho, clip: ClipDepth) -> Option<[f32; 16]> {
    let (l, r, b, t, n, f) = ortho.parameters();
    Some(ortho_columns(l, r, b, t, n, f, clip)?.to_cols_array())
}

/// [`ortho`] decided by the exact path alone (every element by exact comparison with its f32
/// rounding boundaries). The same matrix, slower; tests compare the fast path with it.
///
/// # Errors
/// As [`ortho`].
pub fn ortho_exact(ortho: &Ortho, clip: ClipDepth) -> Result<[f32; 16]> {
    ortho_decided(ortho, clip, false)
}

/// [`ortho`] element by element: from its f64 estimate when `estimates` allows it and the
/// test of [`crate::rounding`] decides it, else exactly.
fn ortho_decided(ortho: &Ortho, clip: ClipDepth, estimates: bool) -> Result<[f32; 16]> {
    let y = ortho_f64(ortho, clip);
    // The estimates' error bound needs finite intermediates: a sum or difference of extents
    // near f64::MAX that overflows sends every element to the exact decision.
    let (l, r, b, t, n, f) = ortho.parameters();
    let intermediates = [r - l, r + l, t - b, t + b, f - n, f + n];
    let trusted = estimates & intermediates.iter().all(|x| x.is_finite());
    let nearest = |y: f64, num: &[f64], den: &[f64]| nearest(trusted, y, num, den);
    let (m0, m12) = nearest_row(trusted, y[0], y[12], l, r);
    let (m5, m13) = nearest_row(trusted, y[5], y[13], b, t);
    let s = unit_scale(n.abs().max(f.abs()));
    let (span, span_err) = two_sum(f * s, -(n * s));
    let den = [span, span_err];
    let (sum, sum_err) = two_sum(f * s, n * s);
    let (m10_num, m14_num): ([f64; 2], [f64; 2]) = match clip {
        ClipDepth::NegOneToOne => ([-2.0 * s, 0.0], [-sum, -sum_err]),
        ClipDepth::ZeroToOne => ([-s, 0.0], [-(n * s), 0.0]),
        ClipDepth::ReversedZeroToOne => ([s, 0.0], [f * s, 0.0]),
    };
    let m10 = nearest(y[10], &m10_num, &den);
    let m14 = nearest(y[14], &m14_num, &den);
    to_f32(&[
        f64::from(m0),
        0.0,
        0.0,
        0.0,
        0.0,
        f64::from(m5),
        0.0,
        0.0,
        0.0,
        0.0,
        f64::from(m10),
        0.0,
        f64::from(m12),
        f64::from(m13),
        f64::from(m14),
        1.0,
    ])
}

/// `2/(hi − lo)` and `−(hi + lo)/(hi − lo)` (one row of x or y), each the nearest f32 of its
/// exact value given their f64 estimates: inputs scaled by a power of two so that the exact
/// decision's products stay normal.
fn nearest_row(
    trusted: bool,
    scale_estimate: f64,
    centre_estimate: f64,
    lo: f64,
    hi: f64,
) -> (f32, f32) {
    let s = unit_scale(lo.abs().max(hi.abs()));
    let (w, w_err) = two_sum(hi * s, -(lo * s));
    let (c, c_err) = two_sum(hi * s, lo * s);
    (
        nearest(trusted, scale_estimate, &[2.0 * s, 0.0], &[w, w_err]),
        nearest(trusted, centre_estimate, &[-c, -c_err], &[w, w_err]),
    )
}

/// The nearest f32 of the exact ratio `Σ num / Σ den`, given its f64 estimate `y`: `y`'s own
/// rounding when the estimate is `trusted` (finite intermediates) and the fast test
/// (`crate::rounding`) decides it, else the exact decision.
fn nearest(trusted: bool, y: f64, num: &[f64], den: &[f64]) -> f32 {
    let fast = if trusted { enclosed(y) } else { None };
    fast.unwrap_or_else(|| {
        nearest_of_ratio(Ratio {
            num,
            den,
            scale: 1.0,
        })
    })
}

/// The fast path of [`ortho`] (and of `Ortho::new`'s checks): its matrix, or `None` where it
/// defers (an invalid input, or an element too close to an f32 rounding boundary). Arithmetic
/// and comparisons only, nothing that panics, and one branch.
///
/// The estimates go through the reciprocals of `r − l`, `t − b` and `f − n`: at most three
/// roundings (`(r + l)·(1/(r − l))`). The checks ride on the rounding test: elements 0, 5 and 10
/// must be normal (not tiny), which refuses a zero or non-finite width, height or depth span
/// (`1/0 = ∞`, `1/∞ = 0`, NaN), and `f − n > 0` is tested outright.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn ortho_columns(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ClipDepth,
) -> Option<glam::Mat4> {
    let (inv_w, inv_h, span) = (1.0 / (r - l), 1.0 / (t - b), f - n);
    let inv_s = 1.0 / span;
    let (m10, m14) = match clip {
        ClipDepth::NegOneToOne => (-2.0 * inv_s, -(f + n) * inv_s),
        ClipDepth::ZeroToOne => (-inv_s, -n * inv_s),
        ClipDepth::ReversedZeroToOne => (inv_s, f * inv_s),
    };
    let y = [
        2.0 * inv_w,
        2.0 * inv_h,
        m10,
        -(r + l) * inv_w,
        -(t + b) * inv_h,
        m14,
    ];
    let tiny_allowed = [false, false, false, true, true, true];
    let good = y
        .iter()
        .zip(tiny_allowed)
        .fold(span > 0.0, |all, (&y, tiny)| all & decided(y, tiny));
    let [m0, m5, m10, m12, m13, m14] = y.map(|y| y as f32);
    good.then(|| {
        glam::Mat4::from_cols(
            glam::Vec4::new(m0, 0.0, 0.0, 0.0),
            glam::Vec4::new(0.0, m5, 0.0, 0.0),
            glam::Vec4::new(0.0, 0.0, m10, 0.0),
            glam::Vec4::new(m12, m13, m14, 1.0),
        )
    })
}

/// The fast path of [`offset_ortho`], as [`ortho_columns`]: element 14 moved by `m10·δ` (from the
/// f32 element 10, one rounding) and rounded outward (`crate::offset::outward_of_ratio`).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn offset_ortho_columns(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    clip: ClipDepth,
    delta: f64,
) -> Option<glam::Mat4> {
    let mut m = ortho_columns(l, r, b, t, n, f, clip)?;
    let offset = f64::from(m.z_axis.z) * delta;
    let (x, decided) = crate::offset::outward_decided(m.w_axis.z, offset, 1.0);
    m.w_axis.z = x;
    (decided & (delta.abs() < f64::INFINITY)).then_some(m)
}

/// The orthographic matrix of `clip` with every point moved toward the camera by `delta` (eye
/// units; negative: away): element 14 moved by the constant NDC offset `m10·δ`, computed from
/// the f32 element 10 and rounded outward, so the eye shift the GPU sees is at least `δ`.
/// Every other element equals [`ortho`]'s.
///
/// # Errors
/// As [`ortho`]; [`crate::ErrorKind::NotFinite`] if `delta` is NaN or infinite.
pub fn offset_ortho(o: &Ortho, clip: ClipDepth, delta: f64) -> Result<[f32; 16]> {
    match offset_ortho_fast(o, clip, delta) {
        Some(m) => Ok(m),
        None => offset_ortho_decided(o, clip, delta, ortho),
    }
}

/// The fast path of [`offset_ortho`] alone, as [`ortho_fast`].
#[inline(always)]
pub fn offset_ortho_fast(o: &Ortho, clip: ClipDepth, delta: f64) -> Option<[f32; 16]> {
    let (l, r, b, t, n, f) = o.parameters();
    Some(offset_ortho_columns(l, r, b, t, n, f, clip, delta)?.to_cols_array())
}

/// [`offset_ortho`] decided by the exact path alone: [`ortho_exact`], and element 14 moved in
/// double-double arithmetic. The same matrix, slower; tests compare the fast path with it.
///
/// # Errors
/// As [`offset_ortho`].
pub fn offset_ortho_exact(o: &Ortho, clip: ClipDepth, delta: f64) -> Result<[f32; 16]> {
    offset_ortho_decided(o, clip, delta, ortho_exact)
}

/// [`offset_ortho`] from the plain matrix `plain` builds.
fn offset_ortho_decided(
    o: &Ortho,
    clip: ClipDepth,
    delta: f64,
    plain: fn(&Ortho, ClipDepth) -> Result<[f32; 16]>,
) -> Result<[f32; 16]> {
    finite(delta, "the eye-space shift delta is NaN or infinite")
        .map_err(|e| e.with_value("delta", delta))?;
    let mut m = plain(o, clip)?;
    m[14] = rounded_outward(m[14], DoubleDouble::product(f64::from(m[10]), delta))?;
    Ok(m)
}

// ---------------------------------------------------------------------------------------------
// The recommended offset for orthographic depth: `crate::recommend`'s model (R1),
// `Δw ≥ q + 2(T + V + I + S)`, with each term taken through the linear window depth
// `w(d) = w₀ ± d/(f − n)` (`|dw/dd| = 1/(f − n)` =: g at every distance).
// ---------------------------------------------------------------------------------------------

use crate::decal::Decal;
use crate::model::interpolation;
use crate::model::quantum::unit_quantum;
use crate::recommend::{ClipRecommendation, ErrorTerms, Snapping};

/// The unit roundoff of f32.
const U: f64 = 1.0 / 16_777_216.0;

/// A decal over an orthographic base.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// The `glOrtho` box the base is drawn with.
    pub ortho: Ortho,
    /// What the engine knows about the decal.
    pub decal: Decal,
}

/// The model's terms for an orthographic `scene` under `clip` (window-depth units):
///
/// * `q`: the format's spacing at the decal's largest window depth (under `glDepthRange`, at
///   its stored depth, in unit window depth: [`crate::model::quantum`]).
/// * `T`: `clip_z = m10·z + m14` (two roundings, relative to `|m10|·d₂` and `|ndc|`), `w = 1`
///   exactly, the viewport mapping (one rounding relative to the stored depth, `w` lifted by
///   `near/(far − near)` under `glDepthRange(near, far)`):
///   `T = u·(k·(|m10|·d_max + |ndc|_max) + w_max + lift)`, `k` = ½ under `[−1, 1]`, 1
///   otherwise.
/// * `V`: rounding the decal's eye z (`u·d₂`) and, on a plane of slope `s`, its x or y
///   (`s·u·X`, `X` the box's largest half-extent), through `g`: `V = u·g·(d₂ + s·X)`; 0 with
///   `exact_depth`.
/// * `I`: the perspective model's [`crate::model::interpolation`],
///   `u·(3·(w_max + lift) + 6·max(w_max − w_min, G))`, with `G = s·g·max((r − l)·X/W,
///   (t − b)·Y/H)` the plane's run from the framebuffer's origin to the viewport's far corner
///   `(X, Y)` (the viewport may lie inside a larger framebuffer: a shadow atlas's tile); 0 with
///   `exact_depth`.
/// * `S`: `2^-(b+1)·(gₓ + g_y)` with `gₓ = s·g·(r − l)/W`, `g_y = s·g·(t − b)/H` per pixel; 0
///   unsnapped.
///
/// # Errors
/// As [`check`].
pub fn error_terms(scene: &Scene, clip: ClipDepth) -> Result<ErrorTerms> {
    check(scene)?;
    if let Some(test) = scene.decal.depth_test {
        test.check_convention(clip)?;
    }
    let o = &scene.ortho;
    let [d1, d2] = scene.decal.depth_range;
    let (w1, w2) = (o.window_depth(clip, d1)?, o.window_depth(clip, d2)?);
    let (w_min, w_max) = (w1.min(w2), w1.max(w2));
    let span = o.far - o.near;
    let g = 1.0 / span;
    let (m10, _) = depth_row(o, clip);
    let k = if clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    let ndc_of = |w: f64| if k == 0.5 { 2.0 * w - 1.0 } else { w };
    let ndc_max = ndc_of(w1).abs().max(ndc_of(w2).abs());
    let d_max = d1.abs().max(d2.abs());
    let half_extent = [o.left, o.right, o.bottom, o.top]
        .into_iter()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let s = scene.decal.slope;
    let pipeline = &scene.decal.pipeline;
    // Under glDepthRange(near, far) the roundings after the projection are relative to the
    // stored depth, w + lift in unit window depth.
    let lift = pipeline.depth_range[0] / pipeline.span();
    // The window gradient per pixel of a plane of slope s, with the whole slope on either axis.
    let [width, height] = scene.decal.viewport.map(f64::from);
    let gradient = [
        s * g * (o.right - o.left).abs() / width,
        s * g * (o.top - o.bottom).abs() / height,
    ];
    let (vertex, interpolation) = if scene.decal.exact_depth {
        (0.0, 0.0)
    } else {
        let extent = interpolation::framebuffer_extent(pipeline, scene.decal.viewport);
        let extrapolated = interpolation::extrapolation_bound(gradient, extent, 1.0);
        (
            U * g * (d_max + s * half_extent),
            interpolation::interpolation(w_min, w_max, extrapolated, lift),
        )
    };
    // World-space vertices through the engine's f32 view matrix: the larger of the eye
    // rounding and the model-view term, as for perspective decals; with the decal's footprint
    // (its corners, or a shadow map's listed receiver) on its plane's exact form.
    let vertex = if pipeline.world_space() {
        let exact = scene
            .decal
            .footprint
            .map(|fp| crate::model::PlaneForm::of_footprint(&fp, scene.decal.viewport, clip));
        vertex.max(world_term(o, clip, s, exact, pipeline)?)
    } else {
        vertex
    };
    let snap = match scene.decal.rasterizer().snapping {
        Snapping::Unsnapped => 0.0,
        Snapping::SubpixelBits(b) => 2f64.powi(-(b as i32) - 1) * (gradient[0] + gradient[1]),
    };
    let transform = U * (k * (m10.abs() * d_max + ndc_max) + w_max + lift);
    let quantum = unit_quantum(scene.decal.format, pipeline, w_max)?;
    Ok(ErrorTerms {
        decal_clip: 0.0,
        quantum,
        transform,
        vertex,
        interpolation,
        snap,
        plane: transform + vertex + interpolation,
        clip: 0.0,
        // GL_LEQUAL/GL_GEQUAL: a tie passes, so no quantum in the offset and one more in the
        // gap (R1, R2).
        strict: scene.decal.depth_test.is_none_or(|t| t.is_strict()),
        correlated: false,
        facing: 0.0,
    })
}

/// The f32 model-view term `V` of world-space vertices under an orthographic projection
/// ([`crate::model::vertex`]), in unit window depth: the form of a plane of slope `s` has
/// `|aₓ| ≤ |A|·s·(r − l)/2`, `|a_y| ≤ |A|·s·(t − b)/2` (`A = m10`, the NDC depth per eye unit)
/// and `|a₀| ≤ 1 + |aₓ| + |a_y|` (the box's centre is at most one NDC unit per axis from a point
/// inside it), or `exact_form` where the plane is known; `w = 1`, and a point of the box lies
/// within `√(X² + Y² + max(|n|, |f|)²)` of the camera. Shared by orthographic decals and
/// directional lights' shadow maps.
///
/// # Errors
/// [`crate::ErrorKind::Overflow`] if the term overflows f64.
pub(crate) fn world_term(
    ortho: &Ortho,
    clip: ClipDepth,
    slope: f64,
    exact_form: Option<crate::model::PlaneForm>,
    pipeline: &crate::model::Pipeline,
) -> Result<f64> {
    let m = ortho_f64(ortho, clip);
    let (l, r, b, t, n, f) = ortho.parameters();
    let a = m[10].abs();
    let (ax, ay) = (
        a * slope * (r - l).abs() / 2.0,
        a * slope * (t - b).abs() / 2.0,
    );
    let bound = crate::model::PlaneForm {
        a0: 1.0 + ax + ay,
        ax,
        ay,
    };
    let extent = (l.abs().max(r.abs()).powi(2)
        + b.abs().max(t.abs()).powi(2)
        + n.abs().max(f.abs()).powi(2))
    .sqrt();
    let per_ndc = if clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    let (form, exact) = match exact_form {
        Some(form) => (form, true),
        None => (bound, false),
    };
    let (error, _) = crate::model::vertex::world_error(&form, exact, &m, pipeline, extent);
    crate::domain::representable(per_ndc * error, "the vertex term overflows f64")
}

/// The smallest constant offset that model (R1) guarantees ends z-fighting for a decal over an
/// orthographic base under `clip`, and the decal's matrix ([`offset_ortho`] of the eye shift
/// `Δw·(f − n)`, which moves window depth by `Δw` everywhere). `ndc_offset` is the signed NDC
/// change (negative toward the camera, positive reversed), `epsilon` and `relative_epsilon`
/// are 0 (no element-10 or relative form), `delta_at_far` the eye shift (the same at every
/// distance), `bleed_gap` the eye distance of the window separation (R2) (`2Δw − q` under a
/// strict test, `2Δw + q` under `GL_LEQUAL`/`GL_GEQUAL`, where `Δw` has no quantum and a tie
/// passes), `polygon_offset` the `glPolygonOffset(−factor, −units)` magnitudes with `r` = the
/// quantum. The decal's depth test may be strict or `…EQUAL`; it must match `clip`.
///
/// # Errors
/// As [`check`]; [`crate::ErrorKind::Domain`] for a depth test of the other direction
/// (`GL_GREATER`/`GL_GEQUAL` are for reversed Z only); [`crate::ErrorKind::Overflow`] if the
/// matrix leaves f32.
pub fn recommend(scene: &Scene, clip: ClipDepth) -> Result<ClipRecommendation> {
    let terms = error_terms(scene, clip)?;
    let window_offset = terms.window_offset();
    let o = &scene.ortho;
    let span = o.far - o.near;
    let per_ndc = if clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    let toward = if clip == ClipDepth::ReversedZeroToOne {
        1.0
    } else {
        -1.0
    };
    let delta = window_offset * span;
    check_near(o.near, o.far, scene.decal.depth_range[0], window_offset)?;
    let factor = match scene.decal.rasterizer().snapping {
        Snapping::SubpixelBits(b) => 2f64.powi(1 - b as i32),
        Snapping::Unsnapped => 0.0,
    };
    Ok(ClipRecommendation {
        clip,
        ndc_offset: toward * window_offset / per_ndc,
        relative_epsilon: 0.0,
        epsilon: 0.0,
        polygon_offset: [factor, (window_offset - 2.0 * terms.snap) / terms.quantum],
        window_offset,
        delta_at_far: delta,
        bleed_gap: terms.gap_window(window_offset) * span,
        matrix: offset_ortho(o, clip, delta)?,
        terms,
    })
}

/// Refuses an offset that moves the decal's nearest point (eye depth `d1`) past the near plane
/// `n` of a box to `f`: window depth is linear in eye depth, so a window offset moves it
/// `window_offset·(f − n)` toward the eye, and the rasterizer clips what passes `n` (under every
/// convention). Also [`crate::planes`]' check of each plane at the largest offset.
///
/// # Errors
/// [`crate::ErrorKind::Unresolvable`], with `needed` the eye distance the near plane must move
/// back (toward the eye or behind it: `n` may be negative).
pub(crate) fn check_near(n: f64, f: f64, d1: f64, window_offset: f64) -> Result<()> {
    let moved = window_offset * (f - n);
    if moved <= d1 - n {
        return Ok(());
    }
    Err(
        crate::error::Error::new(crate::ErrorKind::Unresolvable, PAST_THE_NEAR_PLANE)
            .with_value("needed", moved - (d1 - n)),
    )
}

/// [`check_near`]'s refusal.
pub(crate) const PAST_THE_NEAR_PLANE: &str = "the offset this scene needs moves the decal past the orthographic near plane: move the near plane back (toward the eye, or behind it) by at least `needed`";

/// The scene's rules: the decal's range inside `[n, f]` and increasing, a nonzero viewport, a
/// finite non-negative slope, `exact_depth` only facing the camera, at most 32 sub-pixel bits.
///
/// # Errors
/// [`crate::ErrorKind::NotFinite`] and [`crate::ErrorKind::Domain`], naming the input.
pub fn check(scene: &Scene) -> Result<()> {
    let [d1, d2] = scene.decal.depth_range;
    scene.ortho.check_distance(d1)?;
    scene.ortho.check_distance(d2)?;
    if d1 > d2 {
        return Err(domain("the decal's nearest distance exceeds its farthest")
            .with_value("decal_near", d1));
    }
    if scene.decal.viewport.contains(&0) {
        return Err(domain("the viewport must have a nonzero width and height"));
    }
    scene.decal.pipeline.check()?;
    finite(scene.decal.slope, "the plane slope is NaN or infinite")
        .map_err(|e| e.with_value("slope", scene.decal.slope))?;
    if scene.decal.slope < 0.0 {
        return Err(domain("the plane slope |dz/dx| + |dz/dy| must be >= 0")
            .with_value("slope", scene.decal.slope));
    }
    if scene.decal.exact_depth && scene.decal.slope != 0.0 {
        return Err(
            domain("exact_depth needs a plane facing the camera (slope 0)")
                .with_value("slope", scene.decal.slope),
        );
    }
    if let Snapping::SubpixelBits(b) = scene.decal.rasterizer().snapping {
        if b > 32 {
            return Err(domain("GL_SUBPIXEL_BITS must lie in 0..=32")
                .with_integer("subpixel_bits", i64::from(b)));
        }
    }
    Ok(())
}

//! Projection matrix builders (f64 inside, f32 out).
//!
//! Conventions, as OpenGL's fixed-function pipeline: right-handed eye space looking down −z,
//! clip-space depth in `[−w, w]` (NDC depth `[−1, 1]`), matrices column-major (element `i` of
//! the 16-float array is column `i / 4`, row `i % 4`, exactly what `glLoadMatrixf` and
//! `glUniformMatrix4fv(.., GL_FALSE, ..)` take).

use glam::{DMat4, Mat4};

use crate::domain::{check_tweak, domain, finite, representable, Planes};
use crate::double_double::unit_scale;
use crate::error::{Error, ErrorKind, Result};
use crate::rounding::{
    nearest_columns_then, nearest_of_ratio, two_product, two_sum, Estimates, Ratio,
};

/// The six parameters of `glFrustum`, validated.
///
/// `l`, `r`, `b`, `t` are the extents of the view window on the near plane; `n` and `f` the
/// near and far plane distances (`f` may be `+∞`, the infinite-far limit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    planes: Planes,
}

impl Frustum {
    /// Checks the parameters as `glFrustum` would, and more strictly.
    ///
    /// # Errors
    /// [`ErrorKind::NotFinite`] for NaN or an infinity (other than `f = +∞`);
    /// [`ErrorKind::Domain`] if `l = r`, `b = t`, `n ≤ 0` or `f ≤ n`
    /// (`glFrustum` raises `GL_INVALID_VALUE` for the same cases).
    #[inline]
    pub fn new(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Self> {
        // The same checks in a few comparisons, so that a valid frustum is built in place
        // where it is used (a `Result` returned from a call is copied out of memory with wider
        // loads than the stores that wrote it: a store-forwarding stall per use). Anything
        // else goes to the checks that name the input at fault.
        let finite_extents = l.is_finite() & r.is_finite() & b.is_finite() & t.is_finite();
        let planes = (n > 0.0) & (n < f64::INFINITY) & (f > n); // NaN fails
        if finite_extents & planes & (l != r) & (b != t) {
            return Ok(Self {
                left: l,
                right: r,
                bottom: b,
                top: t,
                planes: Planes::unchecked(n, f),
            });
        }
        Self::checked(l, r, b, t, n, f)
    }

    /// [`Self::new`]'s checks one by one, each failure with its own detail.
    #[cold]
    #[inline(never)]
    fn checked(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Self> {
        finite(l, "the left extent l is NaN or infinite")?;
        finite(r, "the right extent r is NaN or infinite")?;
        finite(b, "the bottom extent b is NaN or infinite")?;
        finite(t, "the top extent t is NaN or infinite")?;
        let planes = Planes::new(n, f)?;
        if l == r {
            return Err(domain("the frustum has zero width: l = r"));
        }
        if b == t {
            return Err(domain("the frustum has zero height: b = t"));
        }
        Ok(Self {
            left: l,
            right: r,
            bottom: b,
            top: t,
            planes,
        })
    }

    /// The validated near and far planes.
    pub fn planes(&self) -> Planes {
        self.planes
    }

    /// `(l, r, b, t, n, f)`, as passed to [`Self::new`].
    pub fn parameters(&self) -> (f64, f64, f64, f64, f64, f64) {
        let (n, f) = (self.planes.near(), self.planes.far());
        (self.left, self.right, self.bottom, self.top, n, f)
    }

    /// The 16 elements, column-major, each within a few f64 ulp of the exact value.
    ///
    /// ```text
    /// | 2n/(r−l)   0        (r+l)/(r−l)    0           |
    /// | 0          2n/(t−b) (t+b)/(t−b)    0           |
    /// | 0          0        −(f+n)/(f−n)   −2fn/(f−n)  |
    /// | 0          0        −1             0           |
    /// ```
    /// With `f = +∞`: element 10 is `−1` and element 14 is `−2n` (Kooima, seed 003).
    ///
    /// # Errors
    /// [`ErrorKind::Overflow`] if an element is not a finite f64 (extents near `f64::MAX`).
    pub fn to_cols_array_f64(&self) -> Result<[f64; 16]> {
        let n = self.planes.near();
        let width = self.right - self.left;
        let height = self.top - self.bottom;
        let mut m = [0.0; 16];
        m[0] = 2.0 * n / width;
        m[5] = 2.0 * n / height;
        m[8] = (self.right + self.left) / width;
        m[9] = (self.top + self.bottom) / height;
        m[10] = -self.planes.sum_over_span();
        m[11] = -1.0;
        m[14] = -2.0 * n * self.planes.far_over_span();
        // One test for all (a sum of finite elements that overflows only costs the loop).
        if !(m[0] + m[5] + m[8] + m[9] + m[10] + m[14]).is_finite() {
            for x in m {
                representable(x, "a projection matrix element overflows f64")?;
            }
        }
        Ok(m)
    }

    /// The matrix in f64, as a glam [`DMat4`].
    ///
    /// # Errors
    /// As [`Self::to_cols_array_f64`].
    pub fn to_dmat4(&self) -> Result<DMat4> {
        Ok(DMat4::from_cols_array(&self.to_cols_array_f64()?))
    }

    /// The matrix in f32, each element the nearest f32 of the exact element (ties to even),
    /// decided as in [`crate::rounding`]. `glFrustum` followed by
    /// `glGetFloatv(GL_PROJECTION_MATRIX)` rounds twice (f64, then f32) and can be one ulp off.
    ///
    /// # Errors
    /// [`ErrorKind::Overflow`] if an element does not fit in f32.
    #[inline]
    pub fn to_cols_array(&self) -> Result<[f32; 16]> {
        projection(self, ClipDepth::NegOneToOne)
    }

    /// The matrix rounded to f32, as a glam [`Mat4`].
    ///
    /// # Errors
    /// As [`Self::to_cols_array`].
    pub fn to_mat4(&self) -> Result<Mat4> {
        Ok(Mat4::from_cols_array(&self.to_cols_array()?))
    }
}

/// The `glFrustum` matrix in f32, column-major: the Rust twin of `zshift_frustum`.
///
/// Right-handed, NDC depth `[−1, 1]`; `f` may be `+∞`. See [`Frustum::to_cols_array_f64`]
/// for the elements.
///
/// # Errors
/// As [`Frustum::new`] and [`Frustum::to_cols_array`].
#[inline]
pub fn frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Result<Mat4> {
    match fast(l, r, b, t, n, f, DepthRow::Clip(ClipDepth::NegOneToOne)) {
        Some(m) => Ok(m),
        None => Ok(Mat4::from_cols_array(&exact(
            l,
            r,
            b,
            t,
            n,
            f,
            DepthRow::Clip(ClipDepth::NegOneToOne),
        )?)),
    }
}

/// Rounds each element to the nearest f32, refusing elements that overflow f32.
pub(crate) fn to_f32(m: &[f64; 16]) -> Result<[f32; 16]> {
    let mut out = [0.0f32; 16];
    for (o, &x) in out.iter_mut().zip(m) {
        *o = x as f32;
        if !o.is_finite() {
            return Err(Error::new(
                ErrorKind::Overflow,
                "a projection matrix element overflows f32",
            ));
        }
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Every projection an engine uses: gluPerspective parameters, [0,1] clip depth, reversed Z and
// the tweaked infinite projection. Each shares the x/y rows of `glFrustum`; only the depth row
// (elements 10 and 14) differs, because NDC depth is `z_ndc = −m10 + m14/d` at eye distance d.
// ---------------------------------------------------------------------------------------------

/// Which clip-space depth range a projection targets, and which way it runs.
///
/// All three keep OpenGL's right-handed eye space (looking down −z) and `w = −z_eye`; they
/// differ in the depth row only. The C ABI passes them as `ZSHIFT_CLIP_*` integers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClipDepth {
    /// OpenGL's default: NDC depth `[−1, 1]`, near → −1, far → +1 (`glFrustum`,
    /// `gluPerspective`; `glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE)`).
    NegOneToOne,
    /// NDC depth `[0, 1]`, near → 0, far → 1: `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`,
    /// as Direct3D and Vulkan define clip space. Depth test `GL_LESS`.
    ZeroToOne,
    /// NDC depth `[0, 1]` reversed, near → 1, far → 0: `glClipControl(.., GL_ZERO_TO_ONE)` with
    /// `glDepthFunc(GL_GREATER)` and `glClearDepth(0)`. With a 32-bit float depth buffer the
    /// float's relative spacing cancels the projection's 1/d, so precision is nearly uniform
    /// in relative distance.
    ReversedZeroToOne,
}

/// The depth row `(m10, m14)` of a projection with planes `n`, `f` (`f` may be `+∞`) under a
/// clip-depth convention, in f64.
///
/// | convention | m10 | m14 | `f = +∞` |
/// |---|---|---|---|
/// | `NegOneToOne` | `−(f+n)/(f−n)` | `−2fn/(f−n)` | `−1`, `−2n` |
/// | `ZeroToOne` | `−f/(f−n)` | `−fn/(f−n)` | `−1`, `−n` |
/// | `ReversedZeroToOne` | `n/(f−n)` | `fn/(f−n)` | `0`, `n` |
///
/// The first row is seed 000 eq. 4.1.1; the infinite limits are Kooima's (seed 003).
pub fn depth_row(planes: &Planes, clip: ClipDepth) -> (f64, f64) {
    let n = planes.near();
    let far_over_span = planes.far_over_span();
    let near_over_span = if planes.is_infinite() {
        0.0
    } else {
        n / (planes.far() - n)
    };
    match clip {
        ClipDepth::NegOneToOne => (-planes.sum_over_span(), -2.0 * n * far_over_span),
        ClipDepth::ZeroToOne => (-far_over_span, -n * far_over_span),
        ClipDepth::ReversedZeroToOne => (near_over_span, n * far_over_span),
    }
}

/// The `glFrustum` matrix with the depth row of `clip`, in f64, column-major.
///
/// `NegOneToOne` gives exactly [`Frustum::to_cols_array_f64`].
///
/// # Errors
/// As [`Frustum::to_cols_array_f64`].
pub fn projection_f64(frustum: &Frustum, clip: ClipDepth) -> Result<[f64; 16]> {
    let mut m = frustum.to_cols_array_f64()?;
    (m[10], m[14]) = depth_row(&frustum.planes(), clip);
    Ok(m)
}

/// The projection of `frustum` under `clip`, each element the nearest f32: what to pass to
/// `glLoadMatrixf` or `glUniformMatrix4fv` after `glClipControl` has selected `clip`.
///
/// # Errors
/// As [`projection_f64`]; [`ErrorKind::Overflow`] if an element leaves f32.
#[inline]
pub fn projection(frustum: &Frustum, clip: ClipDepth) -> Result<[f32; 16]> {
    let (l, r, b, t, n, f) = frustum.parameters();
    build(l, r, b, t, n, f, DepthRow::Clip(clip))
}

/// [`projection`] decided by the exact path alone (every element through
/// [`crate::rounding`]'s exact decision, no f64 shortcut): the same matrix, about a hundred
/// times slower. Exists so tests can compare the fast path with it.
///
/// # Errors
/// As [`projection`].
pub fn projection_exact(frustum: &Frustum, clip: ClipDepth) -> Result<[f32; 16]> {
    let (l, r, b, t, n, f) = frustum.parameters();
    exact(l, r, b, t, n, f, DepthRow::Clip(clip))
}

/// The frustum `gluPerspective(fovy, aspect, n, f)` describes: `t = n·tan(fovy/2)`, `b = −t`,
/// `r = t·aspect`, `l = −r`.
///
/// Its matrix matches `gluPerspective`'s (`m0 = cot(fovy/2)/aspect`, `m5 = cot(fovy/2)`) to a
/// few f64 ulp; `f` may be `+∞`. Use it with every builder and offset that takes a [`Frustum`].
///
/// # Errors
/// [`ErrorKind::NotFinite`] for NaN or infinite `fovy`, `aspect` or `n`;
/// [`ErrorKind::Domain`] unless `0 < fovy < 180` degrees and `aspect > 0`, and as [`Planes::new`].
pub fn perspective_frustum(fovy_degrees: f64, aspect: f64, n: f64, f: f64) -> Result<Frustum> {
    finite(fovy_degrees, "the field of view fovy is NaN or infinite")?;
    finite(aspect, "the aspect ratio is NaN or infinite")?;
    Planes::new(n, f)?;
    if !(fovy_degrees > 0.0 && fovy_degrees < 180.0) {
        return Err(domain(
            "the field of view fovy must lie in (0, 180) degrees",
        ));
    }
    if aspect <= 0.0 {
        return Err(domain("the aspect ratio must be greater than 0"));
    }
    let top = n * (fovy_degrees.to_radians() * 0.5).tan();
    let right = top * aspect;
    Frustum::new(-right, right, -top, top, n, f)
}

/// The `gluPerspective` matrix in f32, column-major (right-handed, NDC depth `[−1, 1]`).
///
/// # Errors
/// As [`perspective_frustum`] and [`Frustum::to_cols_array`].
#[inline]
pub fn perspective(fovy_degrees: f64, aspect: f64, n: f64, f: f64) -> Result<Mat4> {
    Ok(Mat4::from_cols_array(&perspective_array(
        fovy_degrees,
        aspect,
        n,
        f,
    )?))
}

/// [`perspective`] as a column-major array: each element the nearest f32 of the exact
/// `glFrustum` element of [`perspective_frustum`]'s frustum (whose `t = n·tan(fovy/2)` and
/// `r = t·aspect` are rounded in f64 first).
///
/// # Errors
/// As [`perspective`].
#[inline]
pub fn perspective_array(fovy_degrees: f64, aspect: f64, n: f64, f: f64) -> Result<[f32; 16]> {
    match perspective_fast(fovy_degrees, aspect, n, f) {
        Some(m) => Ok(m),
        None => perspective_frustum(fovy_degrees, aspect, n, f)?.to_cols_array(),
    }
}

/// The fast path of [`perspective_array`] alone: `None` where it defers to the exact path (an
/// invalid input, or an element within [`crate::rounding`]'s slack of an f32 rounding
/// boundary). When it returns a matrix, that matrix is [`perspective_array`]'s.
#[inline(always)]
pub fn perspective_fast(fovy_degrees: f64, aspect: f64, n: f64, f: f64) -> Option<[f32; 16]> {
    Some(perspective_fast_columns(fovy_degrees, aspect, n, f)?.to_cols_array())
}

/// [`perspective_fast`] as glam columns (kept in registers by the C ABI's one store).
#[inline(always)]
pub(crate) fn perspective_fast_columns(
    fovy_degrees: f64,
    aspect: f64,
    n: f64,
    f: f64,
) -> Option<Mat4> {
    let good = (fovy_degrees > 0.0) & (fovy_degrees < 180.0) & (aspect > 0.0);
    if !(good & (aspect < f64::INFINITY) & (n > 0.0) & (n < f64::INFINITY)) {
        return None;
    }
    let top = n * (fovy_degrees.to_radians() * 0.5).tan();
    let right = top * aspect;
    fast(
        -right,
        right,
        -top,
        top,
        n,
        f,
        DepthRow::Clip(ClipDepth::NegOneToOne),
    )
}

/// The fast path of [`projection`] alone: `None` where it defers to the exact path. When it
/// returns a matrix, that matrix is [`projection`]'s (and [`projection_exact`]'s).
#[inline(always)]
pub fn projection_fast(frustum: &Frustum, clip: ClipDepth) -> Option<[f32; 16]> {
    let (l, r, b, t, n, f) = frustum.parameters();
    Some(fast(l, r, b, t, n, f, DepthRow::Clip(clip))?.to_cols_array())
}

/// The fast path of [`tweaked_infinite`] alone, as [`projection_fast`].
#[inline(always)]
pub fn tweaked_infinite_fast(frustum: &Frustum, tweak: f64) -> Option<[f32; 16]> {
    let (l, r, b, t, n, _) = frustum.parameters();
    Some(fast(l, r, b, t, n, f64::INFINITY, DepthRow::Tweaked(tweak))?.to_cols_array())
}

/// The smallest tweak that keeps geometry at any distance inside the clip volume of the
/// infinite projection when the GPU evaluates it in f32: `2⁻²²`.
///
/// Why: the plain infinite projection gives `z_clip = d − 2n` and `w = d`; in f32, once
/// `2n < ulp(d)/2`, `z_clip` rounds to `w` and far geometry sits on the far clip plane, where
/// rasterizer rounding clips it. The tweak sets `m10 = ε − 1`, so `z_clip ≤ (1−ε)·d` before
/// rounding. Two correctly rounded f32 operations (the product and the sum) can each raise it by
/// a factor `1 + 2⁻²⁴`, so `ε > 2·2⁻²⁴ + 2⁻⁴⁸` keeps `z_clip < w`; `2⁻²²` doubles that to cover
/// a GPU whose multiply-add is off by one ulp instead of half. Lengyel (GDC 2007, "Projection
/// Matrix Tricks") uses the same value; `tweakedInfinitePerspective` in GLM takes it as `ep`.
///
/// cbindgen:ignore
pub const MIN_INFINITE_TWEAK: f64 = 1.0 / 4_194_304.0;

/// The tweaked infinite projection (Lengyel, GDC 2007; GLM `tweakedInfinitePerspective`):
/// the `glFrustum` x/y rows with `m10 = ε − 1` and `m14 = (ε − 2)·n`, NDC depth `[−1, 1]`.
///
/// Depth is `z_ndc = 1 − ε + (ε − 2)·n/d`: −1 at `d = n`, and `1 − ε` at infinity, so far
/// geometry stays strictly inside the clip volume when `ε ≥` [`MIN_INFINITE_TWEAK`]. The
/// frustum's `f` is ignored (the far plane is at infinity).
///
/// # Errors
/// As [`Frustum::to_cols_array_f64`]; [`ErrorKind::NotFinite`] if `tweak` is NaN or infinite;
/// [`ErrorKind::Domain`] unless `0 ≤ tweak < 1`.
pub fn tweaked_infinite_f64(frustum: &Frustum, tweak: f64) -> Result<[f64; 16]> {
    check_tweak(tweak)?;
    let mut m = frustum.to_cols_array_f64()?;
    let n = frustum.planes().near();
    m[10] = tweak - 1.0;
    m[14] = (tweak - 2.0) * n;
    Ok(m)
}

/// [`tweaked_infinite_f64`] in f32, each element the nearest f32 of the exact element
/// (element 10, `ε − 1`, is exact whenever `ε` is a multiple of `2⁻²⁴`, as
/// [`MIN_INFINITE_TWEAK`] is).
///
/// # Errors
/// As [`tweaked_infinite_f64`]; [`ErrorKind::Overflow`] if an element leaves f32.
#[inline]
pub fn tweaked_infinite(frustum: &Frustum, tweak: f64) -> Result<[f32; 16]> {
    let (l, r, b, t, n, _) = frustum.parameters();
    build(l, r, b, t, n, f64::INFINITY, DepthRow::Tweaked(tweak))
}

/// [`tweaked_infinite`] decided by the exact path alone, as [`projection_exact`].
///
/// # Errors
/// As [`tweaked_infinite`].
pub fn tweaked_infinite_exact(frustum: &Frustum, tweak: f64) -> Result<[f32; 16]> {
    let (l, r, b, t, n, _) = frustum.parameters();
    exact(l, r, b, t, n, f64::INFINITY, DepthRow::Tweaked(tweak))
}

// ---------------------------------------------------------------------------------------------
// The f32 builders: a fast path (f64 estimates, a few comparisons, one low-bit test per element)
// and an exact path (validation with details, every element decided exactly). See
// `crate::rounding` for the error bound that makes the fast path's answer the exact one.
// ---------------------------------------------------------------------------------------------

/// Which depth row a builder writes (elements 10 and 14).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum DepthRow {
    /// The projection of a clip convention (`f` may be `+∞`).
    Clip(ClipDepth),
    /// The tweaked infinite projection with this ε (`f` is ignored; pass `+∞`).
    Tweaked(f64),
}

/// The f32 matrix of `glFrustum(l, r, b, t, n, f)` with `depth`'s row, each element the
/// nearest f32 of the exact element: the fast path, falling back to [`exact`] (which also
/// explains any error).
///
/// # Errors
/// As [`Frustum::new`] and [`check_tweak`]; [`ErrorKind::Overflow`] if an element leaves f32.
#[inline(always)]
pub(crate) fn build(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    depth: DepthRow,
) -> Result<[f32; 16]> {
    match fast(l, r, b, t, n, f, depth) {
        Some(m) => Ok(m.to_cols_array()),
        None => exact(l, r, b, t, n, f, depth),
    }
}

/// The fast path: `None` if an input is invalid or an element is too close to an f32 rounding
/// boundary to decide from its f64 estimate (then [`exact`] decides). Branch-free but for the
/// one test at the end (and `f = +∞`), so a caller can write its output once.
///
/// Validation, equivalent to [`Frustum::new`]'s, is done with the rounding decision in
/// [`nearest_columns_then`]: `0 < n < ∞`, `f − n > 0` (so `f > n`; NaN fails every comparison),
/// and `r − l`, `t − b` finite and nonzero (so `l`, `r`, `b`, `t` are finite and `l ≠ r`,
/// `b ≠ t`). Every estimate is at most four roundings
/// (module docs of [`crate::rounding`]): a sum or product, a difference, its reciprocal and the
/// product with it.
#[inline(always)]
pub(crate) fn fast(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    depth: DepthRow,
) -> Option<Mat4> {
    fast_then(l, r, b, t, n, f, depth, |m10, _| (m10, true))
}

/// [`fast`] with element 10 replaced by `element_10(m10, y10)` (its f32 and its f64 estimate,
/// of at most four roundings) before the columns are assembled
/// (the offset builders round their offset element outward there, and say whether that was
/// decided; computed before the one test, so it must not panic).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn fast_then(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    depth: DepthRow,
    element_10: impl FnOnce(f32, f64) -> (f32, bool),
) -> Option<Mat4> {
    let mut good = true;
    let two_n = 2.0 * n;
    let span = f - n;
    let (depth, depth_den) = match depth {
        DepthRow::Tweaked(tweak) => {
            good = (0.0..1.0).contains(&tweak);
            ([tweak - 1.0, (tweak - 2.0) * n], 1.0)
        }
        DepthRow::Clip(clip) if f == f64::INFINITY => match clip {
            ClipDepth::NegOneToOne => ([-1.0, -two_n], 1.0),
            ClipDepth::ZeroToOne => ([-1.0, -n], 1.0),
            ClipDepth::ReversedZeroToOne => ([0.0, n], 1.0),
        },
        DepthRow::Clip(clip) => match clip {
            ClipDepth::NegOneToOne => ([-(f + n), -(two_n * f)], span),
            ClipDepth::ZeroToOne => ([-f, -(n * f)], span),
            ClipDepth::ReversedZeroToOne => ([n, n * f], span),
        },
    };
    nearest_columns_then(
        Estimates {
            scale: two_n,
            centre: [r + l, t + b],
            den: [r - l, t - b],
            depth,
            depth_den,
            planes: [n, span],
        },
        |m10, y10| {
            let (x, decided) = element_10(m10, y10);
            (x, decided & good)
        },
    )
}

/// The exact path: validates with the detailed errors of [`Frustum::new`] and [`check_tweak`],
/// then decides every element with [`nearest_of_ratio`] on inputs scaled by powers of two.
///
/// # Errors
/// As [`build`].
#[cold]
#[inline(never)]
fn exact(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64, depth: DepthRow) -> Result<[f32; 16]> {
    Frustum::new(l, r, b, t, n, f)?;
    if let DepthRow::Tweaked(tweak) = depth {
        check_tweak(tweak)?;
    }
    let (m0, m8) = exact_xy(l, r, n);
    let (m5, m9) = exact_xy(b, t, n);
    let (m10, m14) = exact_depth_row(n, f, depth);
    let m = [
        m0, 0.0, 0.0, 0.0, 0.0, m5, 0.0, 0.0, m8, m9, m10, -1.0, 0.0, 0.0, m14, 0.0,
    ];
    if m.iter().any(|x| !x.is_finite()) {
        return Err(Error::new(
            ErrorKind::Overflow,
            "a projection matrix element overflows f32",
        ));
    }
    Ok(m)
}

/// `2n/(hi − lo)` and `(hi + lo)/(hi − lo)`, exactly rounded (one row of x or y).
fn exact_xy(lo: f64, hi: f64, n: f64) -> (f32, f32) {
    let s = unit_scale(lo.abs().max(hi.abs()));
    let (lo_s, hi_s) = (lo * s, hi * s);
    let (w, w_err) = two_sum(hi_s, -lo_s);
    let (c, c_err) = two_sum(hi_s, lo_s);
    let centre = nearest_of_ratio(Ratio {
        num: &[c, c_err],
        den: &[w, w_err],
        scale: 1.0,
    });
    let s = unit_scale(lo.abs().max(hi.abs()).max(n));
    let (w, w_err) = two_sum(hi * s, -(lo * s));
    let scale = nearest_of_ratio(Ratio {
        num: &[2.0 * n * s],
        den: &[w, w_err],
        scale: 1.0,
    });
    (scale, centre)
}

/// Elements 10 and 14, exactly rounded.
fn exact_depth_row(n: f64, f: f64, depth: DepthRow) -> (f32, f32) {
    let clip = match depth {
        DepthRow::Tweaked(tweak) => {
            let (m10, m10_err) = two_sum(tweak, -1.0);
            let s = unit_scale(n);
            let (c, c_err) = two_sum(tweak, -2.0);
            let (p, p_err) = two_product(c, n * s);
            let (q, q_err) = two_product(c_err, n * s);
            let m14 = Ratio {
                num: &[p, p_err, q, q_err],
                den: &[1.0],
                scale: s,
            };
            return (
                nearest_of_ratio(Ratio {
                    num: &[m10, m10_err],
                    den: &[1.0],
                    scale: 1.0,
                }),
                nearest_of_ratio(m14),
            );
        }
        DepthRow::Clip(clip) => clip,
    };
    if f == f64::INFINITY {
        // Exact in f64, so one conversion rounds correctly.
        return match clip {
            ClipDepth::NegOneToOne => (-1.0, (-2.0 * n) as f32),
            ClipDepth::ZeroToOne => (-1.0, -n as f32),
            ClipDepth::ReversedZeroToOne => (0.0, n as f32),
        };
    }
    let s = unit_scale(f);
    let (f, n) = (f * s, n * s);
    let span = two_sum(f, -n);
    let span = [span.0, span.1];
    let (fn_, fn_err) = two_product(f, n);
    let (m10, m14) = match clip {
        ClipDepth::NegOneToOne => {
            let (sum, sum_err) = two_sum(f, n);
            ([-sum, -sum_err], [-2.0 * fn_, -2.0 * fn_err])
        }
        ClipDepth::ZeroToOne => ([-f, 0.0], [-fn_, -fn_err]),
        ClipDepth::ReversedZeroToOne => ([n, 0.0], [fn_, fn_err]),
    };
    let ratio = |num: &[f64], scale| {
        nearest_of_ratio(Ratio {
            num,
            den: &span,
            scale,
        })
    };
    (ratio(&m10, 1.0), ratio(&m14, s))
}

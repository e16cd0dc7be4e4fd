//! Lengyel's depth offset through the projection matrix (seed 000, eq. 4.1.3–4.1.11, with the
//! errata of seed 002), and its f32 rounding.
//!
//! Scaling element 10 of the `glFrustum` matrix by `1 + ε` adds `−ε·m10 = ε·(f+n)/(f−n)` to
//! every NDC depth and leaves x, y and w untouched (eq. 4.1.4). Sign convention, as in the
//! seed: `δ > 0` moves geometry toward the camera and gives `ε < 0`.

use glam::Mat4;

use crate::domain::{depth_steps, finite, representable, Planes};
use crate::double_double::{unit_scale, DoubleDouble};
use crate::error::{Error, ErrorKind, Result};
use crate::precision::{depth_step_toward, StepTerms};
use crate::projection::{ClipDepth, DepthRow, Frustum};

/// ε for an eye-space shift `δ` of a point at eye-space depth `Pz` (eq. 4.1.7):
///
/// `ε = −(2fn/(f+n)) · δ / (Pz·(Pz+δ))`
///
/// With `f = +∞` the factor `2fn/(f+n)` becomes its limit `2n`. Evaluated as one ratio in
/// double-double arithmetic (inputs first scaled by a power of two), so the result is the
/// correctly rounded f64 but for near-ties, even at the singularity `δ → −Pz`.
///
/// # Errors
/// [`ErrorKind::NotFinite`] for NaN or infinite inputs (except `f = +∞`);
/// [`ErrorKind::Domain`] for bad planes, `Pz` outside `[−f, −n]`, or `Pz + δ ≥ 0` (the shifted
/// point would be at or behind the eye); [`ErrorKind::Overflow`] if ε overflows f64.
pub fn epsilon(n: f64, f: f64, delta: f64, pz: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    shifted_depth(&planes, delta, pz)?;
    let s = unit_scale(pz);
    let (n, delta, pz) = (n * s, delta * s, pz * s);
    let mut numerator = DoubleDouble::product(-2.0 * n, delta);
    let mut denominator = DoubleDouble::from_f64(pz).mul(DoubleDouble::sum(pz, delta));
    if !planes.is_infinite() {
        let f = f * s;
        numerator = numerator.mul_f64(f);
        denominator = denominator.mul(DoubleDouble::sum(f, n));
    }
    let eps = numerator.div(denominator).to_f64();
    representable(eps, "epsilon overflows f64: Pz + delta is too close to 0")
}

/// The smallest |ε| that moves depth by one step of an m-bit buffer: the corrected eq. 4.1.8
/// (seed 002), `2/(2^m − 1) · (f − n)/(f + n)`.
///
/// The factor is 2, not the 1 printed in seed 000, because NDC depth spans `[−1, 1]`: one
/// window-depth step `1/(2^m−1)` is two NDC units of it. With `f = +∞`, `2/(2^m − 1)`.
/// This is a lower bound on a real rasterizer, not a recommendation (see `../shared/NOTES.md`).
///
/// # Errors
/// As [`Planes::new`] and [`depth_steps`].
pub fn min_epsilon(n: f64, f: f64, bits: u32) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    let steps = depth_steps(bits)?;
    if planes.is_infinite() {
        return Ok(2.0 / steps);
    }
    let s = unit_scale(f);
    let (f, n) = (f * s, n * s);
    let numerator = DoubleDouble::sum(f, -n).mul_f64(2.0);
    Ok(numerator
        .div(DoubleDouble::sum(f, n).mul_f64(steps))
        .to_f64())
}

/// The smallest shift toward the camera that changes the stored depth of a point at `Pz`
/// (eq. 4.1.9 with the corrected `k = (f − n)/(f·n·(2^m − 1))` of seed 002):
///
/// `δ = k·Pz² / (1 − k·Pz)`, positive.
///
/// It equals [`crate::precision::depth_resolution`] at `d = −Pz` (Walker's exact step).
/// Well conditioned everywhere: `1 − k·Pz > 1` since `Pz < 0`.
///
/// # Errors
/// As [`Planes::new`], [`Planes::check_eye_z`] and [`depth_steps`].
pub fn min_delta_toward(n: f64, f: f64, bits: u32, pz: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_eye_z(pz)?;
    depth_step_toward(&planes, depth_steps(bits)?, -pz)
}

/// The largest (least negative) shift away from the camera that still changes the stored depth
/// of a point at `Pz` (eq. 4.1.10 with the corrected k of seed 002):
///
/// `δ = −k·Pz² / (1 + k·Pz)`, negative.
///
/// Ill-conditioned as `k·|Pz| → 1` (condition number `k|Pz| / (1 − k|Pz|)`), so it is evaluated
/// as one ratio in double-double arithmetic: the 2⁻¹⁰⁴ relative error of the intermediate
/// terms is multiplied by the condition number, leaving the result correctly rounded unless
/// `k|Pz|` is within about 1e-15 of 1.
///
/// # Errors
/// As [`min_delta_toward`]; [`ErrorKind::Unresolvable`] if `k·|Pz| ≥ 1`: the depth step at
/// `Pz` is larger than the whole remaining depth range behind it, so no finite shift away
/// from the camera reaches the next stored value; [`ErrorKind::Overflow`] if δ overflows.
pub fn max_delta_away(n: f64, f: f64, bits: u32, pz: f64) -> Result<f64> {
    let planes = Planes::new(n, f)?;
    planes.check_eye_z(pz)?;
    let terms = StepTerms::new(&planes, depth_steps(bits)?, -pz);
    if terms.unresolvable_away() {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            "k*|Pz| >= 1: no shift away from the camera changes the stored depth",
        ));
    }
    Ok(-terms.step(false)?)
}

/// The `glFrustum` matrix with element 10 scaled by `1 + ε(δ, Pz)`: the drop-in for the seed's
/// `LoadOffsetMatrix` (eq. 4.1.3), returning the matrix instead of loading it.
///
/// Every element but 10 is bit-identical to [`crate::projection::frustum`]'s. Element 10 is
/// rounded away from the plain element: with `p = f32(m10)` and `o = m10·ε` (exactly
/// `2fnδ / ((f−n)·Pz·(Pz+δ))`), the result `x` satisfies `|o| ≤ |x − p| ≤ |o| + ulp(x)` and
/// `x − p` has the sign of `o`. The seed's f32 `m[10] *= 1 + ε` loses offsets below half an
/// ulp of `m10`; this one never does. `o` is evaluated in double-double arithmetic (≈ 2⁻¹⁰⁴
/// relative error), which decides the rounding direction.
///
/// # Errors
/// As [`Frustum::new`] and [`epsilon`]; [`ErrorKind::Overflow`] if element 10 leaves f32.
#[allow(clippy::too_many_arguments)] // the seed's LoadOffsetMatrix takes these eight
#[inline]
pub fn load_offset_matrix(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Result<Mat4> {
    match offset_quick(l, r, b, t, n, f, delta, pz) {
        Some(m) => Ok(m),
        None => Ok(Mat4::from_cols_array(&offset_slow(
            l, r, b, t, n, f, delta, pz,
        )?)),
    }
}

/// [`load_offset_matrix`] as a column-major array: the fast path (f64 estimates checked
/// against their error bound, [`crate::rounding`]), falling back to the exact path when an
/// element is too close to call or an input is invalid.
///
/// # Errors
/// As [`load_offset_matrix`].
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn load_offset_array(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Result<[f32; 16]> {
    match offset_quick(l, r, b, t, n, f, delta, pz) {
        Some(m) => Ok(m.to_cols_array()),
        None => offset_slow(l, r, b, t, n, f, delta, pz),
    }
}

/// The fast path of [`load_offset_array`]: `None` when an input is invalid or a rounding is
/// too close to call from the f64 estimates. The quick test first ([`outward_quick`], no
/// branch), then, out of line, the wide one ([`outward_decided`]) for the offsets it leaves.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn offset_fast(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Option<Mat4> {
    offset_quick(l, r, b, t, n, f, delta, pz).or_else(|| offset_wide(l, r, b, t, n, f, delta, pz))
}

/// [`offset_fast`] with the quick test alone: what the C ABI's good path runs, with no call
/// inside it (a call would make every live value a spill).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn offset_quick(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Option<Mat4> {
    offset_with(l, r, b, t, n, f, delta, pz, outward_quick)
}

/// [`offset_fast`]'s second try: the wide test, out of line.
#[allow(clippy::too_many_arguments)]
#[cold]
#[inline(never)]
fn offset_wide(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Option<Mat4> {
    offset_with(l, r, b, t, n, f, delta, pz, outward_decided)
}

/// The fast path's arithmetic, with `outward` deciding the offset element.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn offset_with(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
    outward: impl FnOnce(f32, f64, f64) -> (f32, bool),
) -> Option<Mat4> {
    // o = 2fnδ/((f − n)·Pz·(Pz + δ)) = n·δ·(1 − m10)/(Pz·(Pz + δ)), since f/(f − n) =
    // (1 − m10)/2 (and 1 with f = ∞, where m10 = −1): from the frustum's own estimate of m10.
    // Roundings: n·δ, Pz + δ, the product, its reciprocal, `over_depths`, 1 − m10's five (m10's
    // four, |m10| ≤ |1 − m10|) and the last product: 11.
    let shifted = pz + delta;
    let (n_delta, depths) = (n * delta, pz * shifted);
    let over_depths = n_delta * (1.0 / depths);
    // Pz in [−f, −n] and Pz + δ < 0 (NaN fails every comparison). n·δ and Pz·(Pz + δ) in
    // [2⁻⁵⁰⁰, 2⁵⁰⁰] keep every rounding above relative (normal results: `over_depths` lies in
    // [2⁻¹⁰⁰⁰, 2¹⁰⁰⁰], and |1 − m10| ≥ 1 keeps the offset normal or makes it infinite, which
    // `outward_decided` refuses); a NaN or infinite δ fails it.
    let good = (pz <= -n) & (pz >= -f) & (shifted < 0.0) & moderate(n_delta) & moderate(depths);
    let depth = DepthRow::Clip(ClipDepth::NegOneToOne);
    crate::projection::fast_then(l, r, b, t, n, f, depth, |m10, y10| {
        let (x, decided) = outward(m10, over_depths * (1.0 - y10), 11.0);
        (x, decided & good)
    })
}

/// Whether `|x|` lies in `[2⁻⁵⁰⁰, 2⁵⁰⁰]` (NaN does not).
#[inline(always)]
fn moderate(x: f64) -> bool {
    const LOW: f64 = 3.054936363499605e-151; // 2⁻⁵⁰⁰
    const HIGH: f64 = 3.273390607896142e150; // 2⁵⁰⁰
    (x.abs() >= LOW) & (x.abs() <= HIGH)
}

/// How far (in f64 ulps of its binade) the outward target must lie from every f32.
const OUTWARD_SLACK: u32 = 16;
/// The low 29 bits of an f64 significand: the bits an f32 drops.
const LOW_29: u32 = (1 << 29) - 1;

/// The slow side of [`load_offset_array`]: the wide test, then the exact path.
#[allow(clippy::too_many_arguments)]
#[cold]
#[inline(never)]
fn offset_slow(
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
) -> Result<[f32; 16]> {
    if let Some(m) = offset_wide(l, r, b, t, n, f, delta, pz) {
        return Ok(m.to_cols_array());
    }
    offset_matrix_exact(&Frustum::new(l, r, b, t, n, f)?, delta, pz)
}

/// [`load_offset_matrix`] for an already validated [`Frustum`], as a column-major array.
///
/// # Errors
/// As [`load_offset_matrix`].
#[inline]
pub fn offset_matrix(frustum: &Frustum, delta: f64, pz: f64) -> Result<[f32; 16]> {
    let (l, r, b, t, n, f) = frustum.parameters();
    load_offset_array(l, r, b, t, n, f, delta, pz)
}

/// The fast path of [`offset_matrix`] alone: `None` where it defers to the exact path. When it
/// returns a matrix, that matrix is [`offset_matrix`]'s (and [`offset_matrix_exact`]'s).
#[inline(always)]
pub fn offset_matrix_fast(frustum: &Frustum, delta: f64, pz: f64) -> Option<[f32; 16]> {
    let (l, r, b, t, n, f) = frustum.parameters();
    Some(offset_fast(l, r, b, t, n, f, delta, pz)?.to_cols_array())
}

/// [`offset_matrix`] decided by the exact path alone: the plain elements by
/// [`crate::projection::projection_exact`], element 10 by double-double arithmetic. The same
/// matrix, slower; tests compare the fast path with it.
///
/// # Errors
/// As [`offset_matrix`].
pub fn offset_matrix_exact(frustum: &Frustum, delta: f64, pz: f64) -> Result<[f32; 16]> {
    let planes = frustum.planes();
    shifted_depth(&planes, delta, pz)?;
    let mut m = crate::projection::projection_exact(frustum, ClipDepth::NegOneToOne)?;
    let (_, exact) = ndc_offset_of_shift(&planes, delta, pz);
    m[10] = rounded_outward(m[10], exact())?;
    Ok(m)
}

/// The `glFrustum` matrix with element 10 scaled by `1 + ε` for a given ε, rounded away from
/// the plain element as in [`offset_matrix`]: `|o| ≤ |x − p| ≤ |o| + ulp(x)` with `o = m10·ε`.
///
/// # Errors
/// As [`Frustum::to_cols_array`]; [`ErrorKind::NotFinite`] if ε is NaN or infinite;
/// [`ErrorKind::Overflow`] if element 10 leaves f32.
#[inline]
pub fn epsilon_matrix(frustum: &Frustum, epsilon: f64) -> Result<[f32; 16]> {
    match epsilon_matrix_fast(frustum, epsilon) {
        Some(m) => Ok(m),
        None => epsilon_matrix_exact(frustum, epsilon),
    }
}

/// The fast path of [`epsilon_matrix`] alone, as [`offset_matrix_fast`].
#[inline(always)]
pub fn epsilon_matrix_fast(frustum: &Frustum, epsilon: f64) -> Option<[f32; 16]> {
    Some(epsilon_columns_fast(frustum, epsilon)?.to_cols_array())
}

/// [`epsilon_matrix_fast`] as glam columns (kept in registers by the C ABI's one store).
#[inline(always)]
pub(crate) fn epsilon_columns_fast(frustum: &Frustum, epsilon: f64) -> Option<Mat4> {
    let (l, r, b, t, n, f) = frustum.parameters();
    let depth = DepthRow::Clip(ClipDepth::NegOneToOne);
    // o = m10·ε from the frustum's estimate of m10 (four roundings), and the product: 5.
    crate::projection::fast_then(l, r, b, t, n, f, depth, |m10, y10| {
        let (x, decided) = outward_decided(m10, epsilon * y10, 6.0);
        (x, decided & (epsilon.abs() < f64::INFINITY))
    })
}

/// [`epsilon_matrix`] decided by the exact path alone, as [`offset_matrix_exact`].
///
/// # Errors
/// As [`epsilon_matrix`].
pub fn epsilon_matrix_exact(frustum: &Frustum, epsilon: f64) -> Result<[f32; 16]> {
    finite(epsilon, "epsilon is NaN or infinite")?;
    let mut m = crate::projection::projection_exact(frustum, ClipDepth::NegOneToOne)?;
    let (_, exact) = ndc_offset_of_epsilon(&frustum.planes(), epsilon);
    m[10] = rounded_outward(m[10], exact())?;
    Ok(m)
}

/// Checks `δ` and returns `Pz + δ`, which must stay in front of the eye.
fn shifted_depth(planes: &Planes, delta: f64, pz: f64) -> Result<f64> {
    finite(delta, "the eye-space shift delta is NaN or infinite")?;
    planes.check_eye_z(pz)?;
    let shifted = pz + delta;
    if shifted >= 0.0 {
        return Err(crate::domain::domain(
            "the shifted depth Pz + delta must stay in front of the eye (< 0)",
        )
        .with_value("Pz + delta", shifted));
    }
    Ok(shifted)
}

/// `o = m10·ε = 2fnδ / ((f−n)·Pz·(Pz+δ))`: an f64 estimate of its numerator (two roundings)
/// and denominator (four) and, on demand, its double-double value. `f + n` cancels, and the formula is homogeneous of degree 0, so the
/// inputs are first scaled by a power of two that keeps every product in range.
fn ndc_offset_of_shift(
    planes: &Planes,
    delta: f64,
    pz: f64,
) -> (Ratio, impl FnOnce() -> DoubleDouble) {
    let s = unit_scale(pz);
    let (n, delta, pz) = (planes.near() * s, delta * s, pz * s);
    let far = (!planes.is_infinite()).then_some(planes.far() * s);
    let estimate = match far {
        None => Ratio(2.0 * n * delta, pz * (pz + delta)),
        Some(f) => Ratio(2.0 * n * delta * f, pz * (pz + delta) * (f - n)),
    };
    let exact = move || {
        let two_n_delta = DoubleDouble::product(2.0 * n, delta);
        let depth_product = DoubleDouble::from_f64(pz).mul(DoubleDouble::sum(pz, delta));
        match far {
            None => two_n_delta.div(depth_product),
            Some(f) => two_n_delta
                .mul_f64(f)
                .div(depth_product.mul(DoubleDouble::sum(f, -n))),
        }
    };
    (estimate, exact)
}

/// `o = m10·ε = −ε·(f+n)/(f−n)` (`−ε` when `f = +∞`): an f64 estimate of its numerator (two
/// roundings) and denominator (one) and, on demand, its double-double value.
fn ndc_offset_of_epsilon(planes: &Planes, epsilon: f64) -> (Ratio, impl FnOnce() -> DoubleDouble) {
    let s = unit_scale(planes.far());
    let far = (!planes.is_infinite()).then(|| (planes.far() * s, planes.near() * s));
    let estimate = match far {
        None => Ratio(-epsilon, 1.0),
        Some((f, n)) => Ratio(-epsilon * (f + n), f - n),
    };
    let exact = move || match far {
        None => DoubleDouble::from_f64(-epsilon),
        Some((f, n)) => DoubleDouble::sum(f, n)
            .mul_f64(-epsilon)
            .div(DoubleDouble::sum(f, -n)),
    };
    (estimate, exact)
}

/// An offset as f64 estimates of its numerator and denominator.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ratio(pub f64, pub f64);

impl Ratio {
    /// The quotient (one more rounding).
    pub(crate) fn value(self) -> f64 {
        self.0 / self.1
    }
}

/// The outward rounding of `plain + o` (see [`rounded_outward`]) for an offset `o = num/den`
/// known as a [`Ratio`] whose quotient takes at most `rounds` roundings (relative error below
/// `rounds·2⁻⁵³`: the f64 operations that computed it, on inputs scaled into the normal range).
/// `None` (use the double-double value) when the estimate cannot decide it, and for a zero or
/// non-finite one.
#[inline(always)]
pub(crate) fn outward_of_ratio(plain: f32, o: Ratio, rounds: f64) -> Option<f32> {
    let (x, decided) = outward_decided(plain, o.value(), rounds);
    decided.then_some(x)
}

/// [`outward_of_ratio`] for the offset's f64 estimate: the f32 and whether it is decided (if
/// not, the f32 is meaningless). Branch-free in the usual case; offsets as large as their
/// target take one more test out of line.
///
/// The f64 target `t = plain + o` (one more rounding) is rounded outward by its bits: its
/// magnitude truncated to f32, plus one f32 step when the offset points away from zero, else
/// after stepping one f64 ulp toward zero (so that a `t` equal to an f32 goes to the one
/// below). That is the outward rounding of the exact target when both lie strictly between
/// the same two f32, or `t = plain` and the exact target lies within one f32 step of it, in a
/// normal f32 binade (`2⁻¹²⁶ ≤ |t| < 2¹²⁷`, so the step stays finite). Two cases show it:
///
/// - a small offset, below `|plain|·2⁻²⁴/(1 + 2⁻¹⁴)` (with twice its error bound): at most the
///   step from `plain` to the next f32 outward, less a margin far wider than `t`'s rounding,
///   so `t` is `plain` or on the offset's side of it, short of the next f32 (the usual offset:
///   a few depth steps or less);
/// - a larger one: `t` is within `rounds·u·|o| + u·|t|` of the exact target. When `|o| < |t|`
///   that is below `rounds + 1` f64 ulps of `t`'s binade (`u·|t|` is at most one), so no f32
///   lies between them when `t`'s low 29 significand bits (those an f32 drops) are at least
///   [`OUTWARD_SLACK`] (16, so `rounds ≤ 14`) from a multiple of `2²⁹`: an integer test on the
///   bits. Otherwise (a larger offset, or a target that close to an f32), when the nearest f32
///   of `t` is farther than the error (`gap_decides`; the difference is exact). That fails for
///   an f32 within about `1e-15` relative (offsets that land on one).
///
/// The target is `plain + o`, not `m10·(1 + ε) = m10 + o`: rounding that one fraction outward
/// from `m10` would skip the rounding of `plain` itself, and loses offsets below the gap
/// `|plain − m10|` (up to half an ulp). For `n = 0.1`, `f = 1000`, `Pz = −50`,
/// `δ = −8.240355720867853e-5` (`m10 = plain + 0.11 ulp`, `o = −0.055 ulp`), `m10 + o` rounds
/// down to `plain` itself, no offset at all, where `plain + o` rounds to the f32 below it.
#[inline(always)]
pub(crate) fn outward_decided(plain: f32, estimate: f64, rounds: f64) -> (f32, bool) {
    let o = Outward::new(plain, estimate, rounds);
    let error = (rounds * estimate.abs() + o.target.abs()) * (f64::EPSILON / 2.0);
    let gap = f64::from(o.target as f32) - o.target; // exact
    (o.x, o.valid & (o.quick | (gap.abs() > error)))
}

/// [`outward_decided`] with the integer test alone (no conversions; the usual offset, below
/// its target and at least [`OUTWARD_SLACK`] ulps from an f32): the f32, and whether that
/// test decided it. A `false` may still be decided by [`outward_decided`].
#[inline(always)]
pub(crate) fn outward_quick(plain: f32, estimate: f64, rounds: f64) -> (f32, bool) {
    let o = Outward::new(plain, estimate, rounds);
    (o.x, o.valid & o.quick)
}

/// The outward rounding of `plain + estimate` by its bits, and the tests that need no
/// conversion (see [`outward_decided`]).
struct Outward {
    /// `plain + estimate` in f64.
    target: f64,
    /// The target rounded outward (meaningless unless decided).
    x: f32,
    /// A nonzero estimate and a target in the normal f32 range.
    valid: bool,
    /// Decided by the small-offset rule or the integer test.
    quick: bool,
}

impl Outward {
    #[inline(always)]
    fn new(plain: f32, estimate: f64, rounds: f64) -> Self {
        debug_assert!(rounds + 2.0 <= f64::from(OUTWARD_SLACK));
        let plain = f64::from(plain);
        let margin = (1.0 + (rounds + 2.0) * f64::EPSILON) * (1.0 + 1.0 / 16_384.0);
        let small = estimate.abs() * (margin * 16_777_216.0) < plain.abs();
        let target = plain + estimate;
        let bits = target.to_bits();
        let magnitude = bits & !(1 << 63);
        // |t| in [2⁻¹²⁶, 2¹²⁷): its high word.
        let normal = (0x3810_0000..0x47e0_0000).contains(&(magnitude >> 32));
        // No f32 (a multiple of 2²⁹ f64 ulps of t's binade) within OUTWARD_SLACK ulps of t,
        // where the error of t is below rounds + 1 ulps when |o| < |t|.
        let far = (bits as u32).wrapping_add(OUTWARD_SLACK) & LOW_29 >= 2 * OUTWARD_SLACK;
        let bounded = estimate.abs() < target.abs();
        let away = u64::from((bits ^ estimate.to_bits()) >> 63 == 0);
        // Truncated to f32 by its bits (exponent bias 1023 → 127), after the f64 step toward
        // zero.
        let truncated = (magnitude.wrapping_sub(1 - away) >> 29).wrapping_sub(896 << 23);
        let sign = (bits >> 32) as u32 & 0x8000_0000;
        Outward {
            target,
            x: f32::from_bits(truncated.wrapping_add(away) as u32 | sign),
            valid: normal & (estimate != 0.0),
            quick: small | (far & bounded),
        }
    }
}

/// [`outward_of_ratio`], falling back to the double-double `exact` offset.
#[cfg(test)]
fn rounded_outward_estimated(
    plain: f32,
    estimate: Ratio,
    exact: impl FnOnce() -> DoubleDouble,
) -> Result<f32> {
    match outward_of_ratio(plain, estimate, 8.0) {
        Some(x) => Ok(x),
        None => rounded_outward(plain, exact()),
    }
}

/// Rounds `plain + offset` to f32 away from `plain`, so the offset the GPU sees is never
/// smaller than the one asked for and at most one f32 ulp larger. Shared by every offset matrix
/// (element 10 here, elements 10 and 14 in [`crate::clip_offset`]).
pub(crate) fn rounded_outward(plain: f32, offset: DoubleDouble) -> Result<f32> {
    if !offset.is_finite() {
        return Err(Error::new(
            ErrorKind::Overflow,
            "the depth offset overflows f64",
        ));
    }
    if offset.hi == 0.0 {
        return Ok(plain);
    }
    let target = DoubleDouble::from_f64(plain as f64).add(offset);
    let x = target.to_f32_directed(offset.hi > 0.0);
    if !x.is_finite() {
        return Err(Error::new(
            ErrorKind::Overflow,
            "the offset matrix element overflows f32",
        ));
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The f64 shortcut must pick exactly the f32 that the double-double path picks.
    #[test]
    fn the_estimated_rounding_agrees_with_the_exact_one() {
        let mut next = crate::test_uniform(0x9e37_79b9_7f4a_7c15);
        let mut shortcuts = 0;
        for _ in 0..20_000 {
            let n = 10f64.powf(-6.0 + 8.0 * next());
            let f = n * 10f64.powf(0.01 + 9.0 * next());
            let planes = Planes::new(n, f).unwrap();
            let d = n * (f / n).powf(next());
            let delta = d * (2.0 * next() - 1.0) * 10f64.powf(-9.0 * next());
            let plain = -(planes.sum_over_span() as f32);
            let (estimate, exact) = ndc_offset_of_shift(&planes, delta, -d);
            let want = rounded_outward(plain, exact()).unwrap();
            let (_, exact) = ndc_offset_of_shift(&planes, delta, -d);
            assert_eq!(
                rounded_outward_estimated(plain, estimate, exact).unwrap(),
                want
            );
            shortcuts += usize::from(outward_of_ratio(plain, estimate, 8.0).is_some());
        }
        assert!(
            shortcuts > 19_000,
            "the shortcut should decide almost every case"
        );
    }

    /// Offsets that land exactly on an f32 (or are zero) take the exact path and stay exact.
    #[test]
    fn offsets_landing_on_an_f32_are_kept_exactly() {
        let one_ulp = f64::from(f32::EPSILON);
        for (plain, offset, want) in [
            (-1.5f32, one_ulp, -1.5f32 + f32::EPSILON),
            (-1.5, -one_ulp, -1.5 - f32::EPSILON),
            (-1.5, 0.0, -1.5),
        ] {
            let exact = || DoubleDouble::from_f64(offset);
            assert_eq!(
                rounded_outward_estimated(plain, Ratio(offset, 1.0), exact).unwrap(),
                want
            );
        }
    }

    /// The bit-level outward decision agrees with the double-double rounding wherever it
    /// decides, over elements of every sign and magnitude (zero, f32 subnormals, binade edges,
    /// near overflow) and offsets from far below an ulp to far above the element, and it decides
    /// the ordinary ones.
    #[test]
    fn the_outward_decision_agrees_with_double_double_everywhere() {
        let mut next = crate::test_uniform(0x5851_f42d_4c95_7f2d);
        let (mut decided, mut ordinary) = (0, 0);
        for i in 0..200_000 {
            let sign = if next() < 0.5 { -1.0f32 } else { 1.0 };
            let plain = match i % 6 {
                0 => sign * (2f32.powi((next() * 40.0) as i32 - 20)), // a power of two
                1 => sign * f32::from_bits((next() * 0x0080_0000 as f64) as u32), // subnormal
                2 => 0.0,
                3 => sign * f32::MAX * (next() as f32),
                _ => sign * (10f64.powf(next() * 16.0 - 8.0) as f32),
            };
            let ulp = f64::from(plain.abs().next_up()) - f64::from(plain.abs());
            let osign = if next() < 0.5 { -1.0 } else { 1.0 };
            let estimate = osign
                * match i % 5 {
                    // Landing near an f32 step, a few f64 ulps of the target off.
                    0 => ulp * (1.0 + (next() * 16.0).floor()) * (1.0 + (next() - 0.5) * 1e-13),
                    1 => ulp * 10f64.powf(-12.0 * next()),
                    2 => f64::from(plain).abs() * 10f64.powf(4.0 * next() - 2.0),
                    _ => ulp * 10f64.powf(6.0 * next()),
                };
            let exact = rounded_outward(plain, DoubleDouble::from_f64(estimate));
            let (x, ok) = outward_decided(plain, estimate, 0.0);
            if ok {
                assert_eq!(
                    Ok(x.to_bits()),
                    exact.map(f32::to_bits),
                    "{plain:e} {estimate:e}"
                );
            }
            if i % 5 == 3 && plain.abs() > 1e-30 && plain.abs() < 1e30 {
                ordinary += 1;
                decided += usize::from(ok);
            }
        }
        assert!(
            decided * 1000 > ordinary * 999,
            "{decided} of {ordinary} decided"
        );
    }
}

//! How every matrix element reaches f32: the nearest f32 of the exact value, decided fast from
//! an f64 estimate and exactly when the estimate is too close to call.
//!
//! Each plain matrix element is a rational function `x` of the f64 inputs (`2n/(r−l)`,
//! `−(f+n)/(f−n)`, …). The builders compute it in f64 as `y`, then need `x` rounded to the
//! nearest f32 (ties to even). Rounding `y` instead is a double rounding and is wrong whenever
//! an f32 rounding boundary (a midpoint between two adjacent f32) lies between `x` and `y`.
//!
//! ## The bound
//! The builders compute each element as `x = N/D` in f64: the numerator `N` and denominator `D`
//! from the inputs (`r + l`, `2n·f`, `f − n`, …), the reciprocal `1/D`, and the product. With
//! `u = 2⁻⁵³`, each correctly rounded operation returns `(a ∘ b)(1 + θ)`, `|θ| ≤ u`, as long as
//! its result is a normal f64, and exact operations (×2, `1/1`, negation) count for nothing.
//! Counting every rounding, no element takes more than `k = 4`:
//!
//! | elements | roundings |
//! |---|---|
//! | 0, 5: `2n·(1/(r − l))` | `r − l`, `1/·`, product: 3 |
//! | 8, 9: `(r + l)·(1/(r − l))` | 4 |
//! | 10, 14, finite `f`: `−(f + n)`, `−2n·f`, `−f`, `−n·f`, `n`, `n·f` times `1/(f − n)` | at most 4 |
//! | 10, 14, `f = ∞`: `−1`, `−2n`, `−n`, `0`, `n` (exact) | 0 |
//! | 10, 14, tweaked: `ε − 1`, `(ε − 2)·n` | at most 2 |
//!
//! (`gluPerspective`'s elements are those of the f64 frustum `t = n·tan(fovy/2)`,
//! `r = t·aspect` it describes, so they count as `glFrustum`'s; `glOrtho`'s take at most three.)
//! A reciprocal `1/D` with `D > 2¹⁰²²` is f64-subnormal, but still within `2⁻⁵¹ = 4u` (relative)
//! of `1/D`, since `D < 2¹⁰²⁴`. So `|y − x| ≤ ((1 + u)³(1 + 4u) − 1)·|x| < 7.01u·|x|`: less than
//! 8 f64 ulps of `y` (an ulp of `y`'s binade `[2ᵉ, 2ᵉ⁺¹)` is `2ᵉ⁻⁵²`, and `7.01u·|x| < 7.02·2ᵉ⁻⁵²`).
//!
//! ## The test (the same nearest f32 on both sides of the bound)
//! Rounding to nearest is monotonic: if `a ≤ x ≤ b`, the nearest f32 of `x` lies between
//! those of `a` and `b`. So the builders bracket the estimate, `a = fl(y·(1 − 2⁻⁴⁹))` and
//! `b = fl(y·(1 + 2⁻⁴⁹))` (each within `u·|y|` of `y·(1 ∓ 16u)`, so at least `15u·|y|` from
//! `y`, on either side, where the bound puts `x` within `7.02u·|y|`), convert both to f32 and
//! keep `y`'s f32 when they agree: `x` lies between `a` and `b` (or `b` and `a`, for a
//! negative `y`), so its nearest f32 is theirs, which is also `y`'s. Agreement is tested as an
//! f32 difference that is exactly zero, which also refuses an infinite pair (`∞ − ∞` is NaN)
//! and a NaN: overflow (`y` near or past `2¹²⁸`) and invalid inputs go to the exact decision.
//! (Two distinct f32 differ by at least the least subnormal, so the difference is zero only
//! for equal ones, unless a flush-to-zero mode is set, see below.) It costs two products and
//! two conversions per pair of elements, done two elements at a time with SSE2 and compared
//! four at a time (`nearest_columns_then`): no integer work, and the result is one of the
//! conversions. It fails for about one element in 16 million (`2·2⁻⁴⁹` of an f32 ulp of
//! `2⁻²⁴` relative) of evenly spread inputs, which go to the exact decision.
//!
//! f32 subnormal results (`|x| < 2⁻¹²⁶`) are decided the same way: the bound is relative and
//! `y` is a normal f64 there, and the nearest f32 is monotonic across the subnormal range and
//! its boundary at `2⁻¹⁵⁰` (rounding to zero). A tiny `y` (zero included) gives a zero of its
//! sign, and is right: for a normal `y` that is the bound; a zero or f64-subnormal `y` (with
//! both denominators finite and nonzero, as the builders check) is an exact zero (`a + b`
//! rounds to 0 only when `a = −b`) or a product whose exact value (of accurate factors) is
//! below `2⁻¹⁰²²`. An intermediate product that underflows (`2n·f` below `2⁻¹⁰²²`, so
//! `n < 2⁻⁵¹¹`) cannot pass wrongly: with an f32-sized element 14 it needs `1/(f − n) > 2⁸⁷³`,
//! which makes element 10 (`≥ 2n/(f − n)`) overflow f32. An intermediate that overflows gives
//! `±∞` or NaN, which the test refuses, and the exact decision explains the overflow. Under a
//! flush-to-zero floating-point mode (MXCSR FTZ, which the library never sets), an f32
//! subnormal element comes out as a zero of its sign, as such a caller's own f32 code would see
//! it; every normal element is unaffected.
//!
//! ## The exact decision
//! `nearest_of_ratio` takes `x` as a ratio `N/D` whose numerator and denominator are
//! each an exact sum of a few f64 (TwoSum and TwoProd give those without error). A midpoint
//! `m` between adjacent f32 has at most 25 significant bits, so each `m·Dᵢ` is exact as a
//! TwoProd pair, and the sign of `N − m·D` is the sign of an exact sum of at most 8 f64: a
//! nonoverlapping expansion (Shewchuk's Grow-Expansion), whose sign is that of its largest
//! component. Starting from the f32 nearest the estimate, it steps to the neighbour while `x`
//! lies beyond a midpoint (at a midpoint, to the even one), which also settles subnormal
//! results and overflow (`f32::MAX` is odd, so a tie there rounds to infinity, as IEEE 754
//! does). Inputs are first scaled by a power of two so that every product stays a normal
//! f64; the decision is exact unless an input is below `2⁻⁹⁰⁰` of another in the same
//! element, where the element is within `2⁻⁹⁰⁰` (relative) of its limit.
//!
//! ## Outward rounding
//! Offset elements are rounded away from the plain element instead (`crate::offset`): the
//! least f32 at or beyond `plain + o`. There the boundaries are the f32 values themselves. An
//! offset whose estimate, grown by its error bound, stays below the step to the next f32 is
//! decided as that next f32; a larger one when the f64 target lies farther from every f32 than
//! its error bound: an integer test on its bits where the offset is smaller than its target
//! (its low 29 significand bits at least 16 ulps from a multiple of `2²⁹`, where the f32 values
//! lie), else the exact f64 distance to the nearest f32; otherwise double-double decides.

use std::cmp::Ordering;

use glam::{Mat4, Vec4};

/// `1 − 2⁻⁴⁹` and `1 + 2⁻⁴⁹`: the estimate `y` times these brackets every value within twice
/// the module docs' bound of it (`16u` on either side, for a bound below `8u`).
const BELOW: f64 = 1.0 - 1.0 / 562_949_953_421_312.0;
/// See [`BELOW`].
const ABOVE: f64 = 1.0 + 1.0 / 562_949_953_421_312.0;

/// The nearest f32 of `y`, if it is that of every value within the bound of the module docs
/// (so of the exact value `y` estimates): both ends of the bracket `y·(1 ∓ 2⁻⁴⁹)` round to the
/// same finite f32, and, unless `zero_allowed`, it is not zero (the builders refuse a zero
/// element 0 or 5: it means an infinite width or height). The scalar form of the lane test in
/// [`nearest_columns_then`], with the same answers.
#[inline(always)]
pub(crate) fn enclosed_or_zero(y: f64, zero_allowed: bool) -> Option<f32> {
    let (lo, hi) = ((y * BELOW) as f32, (y * ABOVE) as f32);
    let decided = ((lo - hi) == 0.0) & (zero_allowed | (lo != 0.0));
    decided.then_some(lo)
}

/// Whether [`enclosed_or_zero`] decides `y`.
#[inline(always)]
pub(crate) fn decided(y: f64, zero_allowed: bool) -> bool {
    enclosed_or_zero(y, zero_allowed).is_some()
}

/// The nearest f32 of every value within the bound of the module docs of `y` (of the exact
/// value an estimate of at most four roundings on normal intermediates stands for), if
/// [`enclosed_or_zero`] shows it is one f32; `None` otherwise. A tiny `y` gives a zero.
#[inline(always)]
pub(crate) fn enclosed(y: f64) -> Option<f32> {
    enclosed_or_zero(y, true)
}

/// A projection's six varying elements as ratios of f64 values the builders compute:
/// `m0, m5 = scale/den`, `m8, m9 = centre/den` and `m10, m14 = depth/depth_den`, each through
/// the reciprocal of its denominator.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Estimates {
    /// `2n` (the numerator of elements 0 and 5).
    pub scale: f64,
    /// `r + l`, `t + b` (the numerators of elements 8 and 9).
    pub centre: [f64; 2],
    /// `r − l`, `t − b`.
    pub den: [f64; 2],
    /// The numerators of elements 10 and 14.
    pub depth: [f64; 2],
    /// Their denominator: `f − n`, or 1 where the row is a product (infinite, tweaked).
    pub depth_den: f64,
    /// `n` and `f − n`, checked here too: both `> 0` (NaN fails). `scale = 2n` must hold: the
    /// rest of `Frustum::new`'s checks follow from it (see [`nearest_columns_then`]).
    pub planes: [f64; 2],
}

/// The projection's columns, each element the nearest f32 of its exact value, with element 10
/// replaced by `element_10(m10, y10)` (from its f32 and its f64 estimate: an offset rounded
/// outward, and whether that was decided)
/// before the columns are assembled, so the matrix leaves in four registers. `None` unless
/// the test of the module docs decides all six elements (elements 0 and 5 not tiny),
/// `element_10` decided, and `n`, `f − n > 0`: one branch for all.
///
/// Those few tests validate the frustum as `Frustum::new` does: `n < ∞` because `2n = ∞`
/// makes element 0 infinite or NaN; `r − l` and `t − b` nonzero because a zero one makes
/// element 0 or 5 infinite (`2n > 0`); finite because an infinite one (an overflowed
/// difference of finite extents) makes it `2n·0 = 0`, refused as tiny (a true element 0 or 5
/// below `2⁻¹²⁶` only takes the exact path). On x86_64 the whole decision is a few SSE2
/// instructions and one branch (SSE2 is part of the baseline, so no detection); elsewhere the
/// same arithmetic lane by lane.
#[inline(always)]
pub(crate) fn nearest_columns_then(
    e: Estimates,
    element_10: impl FnOnce(f32, f64) -> (f32, bool),
) -> Option<Mat4> {
    #[cfg(target_arch = "x86_64")]
    {
        nearest_columns_sse2(e, element_10)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        nearest_columns_portable(e, element_10)
    }
}

/// [`nearest_columns_then`] lane by lane.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))] // x86_64 uses it in tests only
#[inline(always)]
pub(crate) fn nearest_columns_portable(
    e: Estimates,
    element_10: impl FnOnce(f32, f64) -> (f32, bool),
) -> Option<Mat4> {
    let inv = [1.0 / e.den[0], 1.0 / e.den[1]];
    let inv_z = 1.0 / e.depth_den;
    let y = [
        e.scale * inv[0],
        e.scale * inv[1],
        e.centre[0] * inv[0],
        e.centre[1] * inv[1],
        e.depth[0] * inv_z,
        e.depth[1] * inv_z,
    ];
    let mut m = [0.0f32; 6];
    let mut good = (e.planes[0] > 0.0) & (e.planes[1] > 0.0);
    for i in 0..6 {
        // Elements 0 and 5 must not be zero (`enclosed_or_zero`).
        let (lo, hi) = ((y[i] * BELOW) as f32, (y[i] * ABOVE) as f32);
        good &= ((lo - hi) == 0.0) & ((i >= 2) | (lo != 0.0));
        m[i] = lo;
    }
    let decided_10;
    (m[4], decided_10) = element_10(y[4] as f32, y[4]);
    if !(good & decided_10) {
        return None;
    }
    Some(Mat4::from_cols(
        Vec4::new(m[0], 0.0, 0.0, 0.0),
        Vec4::new(0.0, m[1], 0.0, 0.0),
        Vec4::new(m[2], m[3], m[4], -1.0),
        Vec4::new(0.0, 0.0, m[5], 0.0),
    ))
}

/// [`nearest_columns_then`] with SSE2: two elements per f64 operation, four per f32 one, and
/// the columns assembled by shuffles in registers (stored once by the caller).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(unused_unsafe)] // SSE2 intrinsics are safe to call on x86_64 from Rust 1.87 on
fn nearest_columns_sse2(
    e: Estimates,
    element_10: impl FnOnce(f32, f64) -> (f32, bool),
) -> Option<Mat4> {
    use std::arch::x86_64::*;
    // SAFETY: SSE2 is part of the x86_64 baseline; these intrinsics only compute on registers.
    unsafe {
        let den = _mm_set_pd(e.den[1], e.den[0]);
        let inv = _mm_div_pd(_mm_set1_pd(1.0), den); // [1/(r − l), 1/(t − b)]
        let inv_z = _mm_set1_pd(1.0 / e.depth_den);
        // The estimates numerator·reciprocal: [m0 m5], [m8 m9], [m10 m14].
        let y_scale = _mm_mul_pd(_mm_set1_pd(e.scale), inv);
        let y_centre = _mm_mul_pd(_mm_set_pd(e.centre[1], e.centre[0]), inv);
        let y_depth = _mm_mul_pd(_mm_set_pd(e.depth[1], e.depth[0]), inv_z);
        // Each bracket's ends in f32: [m0 m5 m8 m9] and [m10 m14 0 0], below and above.
        let (below, above) = (_mm_set1_pd(BELOW), _mm_set1_pd(ABOVE));
        let end = |y: __m128d, side: __m128d| _mm_cvtpd_ps(_mm_mul_pd(y, side));
        let lo_xy = _mm_movelh_ps(end(y_scale, below), end(y_centre, below));
        let hi_xy = _mm_movelh_ps(end(y_scale, above), end(y_centre, above));
        let (lo_z, hi_z) = (end(y_depth, below), end(y_depth, above));
        // Ends that agree (a difference of exactly zero: finite and equal), elements 0 and 5
        // not zero (a NaN in lanes 2 and 3 makes them pass), and n, f − n > 0.
        let zero = _mm_setzero_ps();
        let same_xy = _mm_cmpeq_ps(_mm_sub_ps(lo_xy, hi_xy), zero);
        let same_z = _mm_cmpeq_ps(_mm_sub_ps(lo_z, hi_z), zero);
        let nonzero = _mm_cmpneq_ps(lo_xy, _mm_set_ps(f32::NAN, f32::NAN, 0.0, 0.0));
        let planes = _mm_set_pd(e.planes[1], e.planes[0]);
        let positive = _mm_castpd_ps(_mm_cmpgt_pd(planes, _mm_setzero_pd()));
        let all = _mm_and_ps(_mm_and_ps(same_xy, same_z), _mm_and_ps(nonzero, positive));
        let (m10, decided_10) = element_10(_mm_cvtsd_f64(y_depth) as f32, _mm_cvtsd_f64(y_depth));
        if (_mm_movemask_ps(all) != 0xf) | !decided_10 {
            return None;
        }
        let lo_z = _mm_move_ss(lo_z, _mm_set_ss(m10));
        let col0 = _mm_and_ps(lo_xy, _mm_castsi128_ps(_mm_set_epi32(0, 0, 0, -1)));
        let col1 = _mm_and_ps(lo_xy, _mm_castsi128_ps(_mm_set_epi32(0, 0, -1, 0)));
        let z_and_w = _mm_unpacklo_ps(lo_z, _mm_set1_ps(-1.0)); // [m10 −1 m14 −1]
        let col2 = _mm_shuffle_ps::<0b01_00_11_10>(lo_xy, z_and_w); // [m8 m9 m10 −1]
        let col3 = _mm_shuffle_ps::<0b11_01_00_00>(_mm_setzero_ps(), lo_z); // [0 0 m14 0]
        Some(Mat4::from_cols(
            Vec4::from(col0),
            Vec4::from(col1),
            Vec4::from(col2),
            Vec4::from(col3),
        ))
    }
}

/// The error-free sum: `a + b = s + e` exactly (Knuth's TwoSum, any order of magnitudes).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// The error-free product: `a · b = p + e` exactly (with a fused multiply-add), unless `e`
/// underflows.
#[inline]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// The exact sign of `Σ terms` (finite f64): the terms are turned in place into a
/// nonoverlapping expansion of increasing magnitude (Shewchuk's Grow-Expansion, one term at a
/// time), whose sign is that of its last nonzero component.
fn sign_of_sum(terms: &mut [f64]) -> Ordering {
    for i in 1..terms.len() {
        let (grown, rest) = terms.split_at_mut(i);
        let mut q = rest[0];
        for term in grown {
            let (s, e) = two_sum(q, *term);
            *term = e;
            q = s;
        }
        rest[0] = q;
    }
    match terms.iter().rev().find(|&&x| x != 0.0) {
        Some(&x) if x > 0.0 => Ordering::Greater,
        Some(_) => Ordering::Less,
        None => Ordering::Equal,
    }
}

/// The value of an f32 for midpoints: infinities stand for `±2¹²⁸`, where IEEE 754's
/// round-to-nearest puts the overflow threshold.
fn extended(x: f32) -> f64 {
    if x.is_infinite() {
        f64::from(x.signum()) * 2f64.powi(128)
    } else {
        f64::from(x)
    }
}

/// A ratio `x = (Σ num)/(Σ den) / scale`, each sum exact, `scale` a power of two.
#[derive(Clone, Copy)]
pub(crate) struct Ratio<'a> {
    pub num: &'a [f64],
    pub den: &'a [f64],
    pub scale: f64,
}

impl Ratio<'_> {
    /// The sign of `x − m`, exactly: the sign of `N − (m·scale)·D` times the sign of `D`.
    fn compare(&self, m: f64) -> Ordering {
        let ms = m * self.scale;
        let mut terms = [0.0; 8];
        let mut len = 0;
        for &t in self.num {
            terms[len] = t;
            len += 1;
        }
        for &d in self.den {
            let (p, e) = two_product(ms, d);
            terms[len] = -p;
            terms[len + 1] = -e;
            len += 2;
        }
        let numerator_side = sign_of_sum(&mut terms[..len]);
        let mut den = [0.0; 2];
        den[..self.den.len()].copy_from_slice(self.den);
        let den_sign = sign_of_sum(&mut den[..self.den.len()]);
        if den_sign == Ordering::Less {
            numerator_side.reverse()
        } else {
            numerator_side
        }
    }

    /// A few-ulp f64 estimate of `x`.
    fn estimate(&self) -> f64 {
        let n: f64 = self.num.iter().sum();
        let d: f64 = self.den.iter().sum();
        n / d / self.scale
    }
}

/// The nearest f32 (ties to even; `±∞` past the overflow threshold) of the exact ratio `x`:
/// the exact decision of the module docs. At most 4 numerator and 2 denominator terms.
#[cold]
#[inline(never)]
pub(crate) fn nearest_of_ratio(x: Ratio<'_>) -> f32 {
    debug_assert!(x.num.len() <= 4 && x.den.len() <= 2);
    let mut c = x.estimate() as f32;
    if c.is_nan() {
        c = 0.0;
    }
    // Step to a neighbour while `x` lies beyond a midpoint (at a midpoint, toward the even f32).
    // A few steps at most from a good estimate; after that, bisect (an estimate that left the
    // normal range can be far off, and stepping one f32 at a time would take forever).
    let mut steps = 0;
    loop {
        let next = if c == f32::INFINITY {
            None
        } else {
            beyond(&x, c, c.next_up(), Ordering::Greater)
        };
        let next = next.or_else(|| {
            if c == f32::NEG_INFINITY {
                None
            } else {
                beyond(&x, c, c.next_down(), Ordering::Less)
            }
        });
        match next {
            None => return c,
            Some(n) if steps < 4 => {
                c = n;
                steps += 1;
            }
            // Bisection lands on the nearest f32 or, at a tie, beside it: one step remains.
            Some(_) => {
                c = bisected(&x);
                steps = 0;
            }
        }
    }
}

/// `neighbour` when `x` lies beyond the midpoint of `c` and `neighbour` (on the side `side`), or
/// on it with `c` odd (ties to even); `None` when `c` is at least as near.
fn beyond(x: &Ratio<'_>, c: f32, neighbour: f32, side: Ordering) -> Option<f32> {
    let m = 0.5 * (extended(c) + extended(neighbour));
    let o = x.compare(m);
    (o == side || (o == Ordering::Equal && c.to_bits() & 1 == 1)).then_some(neighbour)
}

/// An f32 within one of the nearest to `x`, by bisection over all f32 in order (32 exact
/// comparisons): the largest whose midpoint with the f32 below does not exceed `x`.
fn bisected(x: &Ratio<'_>) -> f32 {
    // f32 in order as integers: −∞ … −0 = +0 … +∞.
    let key = |v: f32| {
        let magnitude = i64::from(v.to_bits() & 0x7fff_ffff);
        if v.is_sign_negative() {
            -magnitude
        } else {
            magnitude
        }
    };
    let value = |k: i64| {
        let magnitude = k.unsigned_abs() as u32;
        f32::from_bits(if k < 0 {
            magnitude | 0x8000_0000
        } else {
            magnitude
        })
    };
    let (mut lo, mut hi) = (key(f32::NEG_INFINITY), key(f32::INFINITY));
    while lo < hi {
        let k = lo + (hi - lo + 1) / 2;
        let m = 0.5 * (extended(value(k - 1)) + extended(value(k)));
        match x.compare(m) {
            Ordering::Less => hi = k - 1,
            _ => lo = k,
        }
    }
    value(lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_test_refuses_near_midpoints_and_accepts_f32_values() {
        // Near 1 an f64 ulp is 2u, so the bracket ±16u is ±8 ulps.
        let mid = 1.0 + f64::from(f32::EPSILON) / 2.0;
        let ulps = |k: i64| f64::from_bits((mid.to_bits() as i64 + k) as u64);
        assert_eq!(enclosed(mid), None);
        assert_eq!(enclosed(ulps(4)), None);
        assert_eq!(enclosed(ulps(-4)), None);
        assert_eq!(enclosed(ulps(7)), None); // inside the bracket
        assert_eq!(enclosed(ulps(-7)), None);
        assert_eq!(enclosed(ulps(9)), Some(1.0 + f32::EPSILON));
        assert_eq!(enclosed(ulps(-9)), Some(1.0));
        assert_eq!(enclosed(ulps(40)), Some(1.0 + f32::EPSILON));
        // Just below 2 an ulp is u: the bracket reaches 16 ulps.
        let mid = 2.0 - f64::from(f32::EPSILON) / 2.0;
        let ulps = |k: i64| f64::from_bits((mid.to_bits() as i64 + k) as u64);
        assert_eq!(enclosed(ulps(-15)), None);
        assert_eq!(enclosed(ulps(-17)), Some(2.0 - f32::EPSILON));
        for (y, want) in [
            (1.0, 1.0f32),
            (-3.5, -3.5),
            (0.0, 0.0),
            (-0.0, -0.0),
            (1e-300, 0.0),
            (2f64.powi(-151), 0.0),
            (2f64.powi(-126), f32::MIN_POSITIVE),
            (1e-39, 1e-39),
            (f64::from(f32::from_bits(1)), f32::from_bits(1)),
            (-1.5 * 2f64.powi(126), -1.5 * 2f32.powi(126)),
            (2f64.powi(127), 2f32.powi(127)),
        ] {
            assert_eq!(enclosed(y).map(f32::to_bits), Some(want.to_bits()), "{y}");
        }
        // A boundary inside the bracket (2⁻¹⁵⁰ between 0 and the least subnormal, the overflow
        // threshold), infinities, NaN: the exact decision.
        let threshold = f64::from(f32::MAX) + 2f64.powi(103);
        for bad in [
            f64::NAN,
            f64::INFINITY,
            2f64.powi(128),
            2f64.powi(-150),
            threshold,
        ] {
            assert_eq!(enclosed(bad), None, "{bad}");
        }
        // A zero element 0 or 5 (an infinite width) is refused where zero is not allowed.
        assert_eq!(enclosed_or_zero(0.0, false), None);
        assert_eq!(enclosed_or_zero(1e-39, false), Some(1e-39));
    }

    /// The SSE2 and portable column builders agree, element for element and on refusals.
    #[test]
    fn the_column_builders_agree() {
        let mid = 1.0 + f64::from(f32::EPSILON) / 2.0;
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let x = f64::from_bits((state >> 12) | 0x3ff0_0000_0000_0000) - 1.5;
            x * 10f64.powi((state % 9) as i32 - 4)
        };
        let specials = [0.0, -0.0, f64::INFINITY, f64::NAN, mid, 1e-40, 1e39];
        for i in 0..20_000 {
            let mut v = [next(), next(), next(), next(), next(), next(), next()];
            if i % 7 == 0 {
                v[i % 7 + (i / 7) % 6] = specials[(i / 42) % specials.len()];
            }
            let e = Estimates {
                scale: v[0],
                centre: [v[1], v[2]],
                den: [v[3], v[4]],
                depth: [v[5], v[6]],
                depth_den: if i % 3 == 0 { 1.0 } else { v[2] - v[1] },
                planes: [v[0].abs(), v[5] - v[6]],
            };
            let portable = nearest_columns_portable(e, |m, _| (m, true)).map(|m| m.to_cols_array());
            assert_eq!(
                nearest_columns_then(e, |m, _| (m, true)).map(|m| m.to_cols_array()),
                portable,
                "{e:?}"
            );
        }
    }

    #[test]
    fn the_exact_sign_sees_what_f64_sums_lose() {
        assert_eq!(sign_of_sum(&mut [1.0, 1e-300, -1.0]), Ordering::Greater);
        assert_eq!(sign_of_sum(&mut [1e300, -1e-300, -1e300]), Ordering::Less);
        assert_eq!(sign_of_sum(&mut [0.5, 0.25, -0.75]), Ordering::Equal);
    }

    #[test]
    fn ratios_round_to_nearest_with_ties_to_even() {
        let one = [1.0];
        // (1 + 2⁻²⁴)/1 is the midpoint between 1 and 1 + 2⁻²³: ties to even (1).
        let tie = [1.0, 2f64.powi(-24)];
        let r = Ratio {
            num: &tie,
            den: &one,
            scale: 1.0,
        };
        assert_eq!(nearest_of_ratio(r), 1.0);
        // Just above the tie: up.
        let above = [1.0, 2f64.powi(-24), 2f64.powi(-80)];
        let r = Ratio {
            num: &above,
            den: &one,
            scale: 1.0,
        };
        assert_eq!(nearest_of_ratio(r), 1.0f32.next_up());
        // 1/3 with a negative denominator, halved by the scale.
        let r = Ratio {
            num: &one,
            den: &[-3.0],
            scale: 2.0,
        };
        assert_eq!(nearest_of_ratio(r), (-1.0f64 / 6.0) as f32);
        // Overflow threshold and a subnormal result.
        let threshold = [f64::from(f32::MAX), 2f64.powi(103)];
        let r = Ratio {
            num: &threshold,
            den: &one,
            scale: 1.0,
        };
        assert_eq!(nearest_of_ratio(r), f32::INFINITY);
        let tiny = [3.0 * 2f64.powi(-150)];
        let r = Ratio {
            num: &tiny,
            den: &one,
            scale: 1.0,
        };
        assert_eq!(nearest_of_ratio(r), 2.0 * 2f32.powi(-149)); // 1.5 ulp: tie to even, 2
                                                                // A useless estimate (the f64 sum cancels to 0, 2·10⁸ f32 below the value) ends at
                                                                // once, by bisection.
        let cancelling = [1.0, 1e-30, -1.0];
        let r = Ratio {
            num: &cancelling,
            den: &one,
            scale: 1.0,
        };
        assert_eq!(nearest_of_ratio(r), 1e-30f64 as f32);
    }
}

//! How every matrix element reaches f32: the nearest f32 of the exact value, decided fast from
//! an f64 estimate and exactly when the estimate is too close to call.
//!
//! Each plain matrix element is a rational function `x` of the f64 inputs (`2n/(r−l)`,
//! `−(f+n)/(f−n)`, …). The builders compute it in f64 as `y`, then need `x` rounded to the
//! nearest f32 (ties to even). Rounding `y` instead is a double rounding and is wrong whenever
//! an f32 rounding boundary (a midpoint between two adjacent f32) lies between `x` and `y`.
//!
//! ## The bound
//! Every estimate here is a chain of at most `k ≤ 8` correctly rounded f64 operations
//! (`+ − × ÷`) on the inputs, exact multiplications by 2 not counted. With `u = 2⁻⁵³`, each
//! operation returns `(a ∘ b)(1 + θ)`, `|θ| ≤ u`, as long as its result is a normal f64, so
//!
//! ```text
//! y = x · Π(1 + θᵢ)^(±1)   and   |x − y| = |y| · |1 − x/y| ≤ |y| · γₖ,   γₖ = k·u/(1 − k·u).
//! ```
//!
//! Since `ulp(y) > |y|·u` for a normal `y`, `|x − y| < k/(1 − k·u) · ulp(y) < 8.000001 ulp(y)`.
//! [`SLACK`] = 16 f64 ulps doubles that.
//!
//! ## The test (an integer test on the low bits)
//! For `2⁻¹²⁶ ≤ |y| < 2¹²⁷`, the f32 grid in `y`'s binade is the f64 grid with the 29 low
//! significand bits dropped: the f32 values are the f64 values whose low 29 bits are 0, and
//! the midpoints are those whose low 29 bits are exactly `2²⁸`. Let `L` be `y`'s low 29 bits,
//! read as an integer count of `ulp(y)`. If `|L − 2²⁸| > SLACK`, no midpoint of `y`'s binade
//! lies within `SLACK·ulp(y)` of `y`; the nearest midpoints of the neighbouring binades are at
//! least `2²⁷·ulp(y)` away (a binade edge is an f32, and the next midpoint beyond it is half an
//! f32 spacing from it). So `x` and `y` lie strictly between the same two midpoints, and
//! `y as f32` (one correct rounding of `y`) is the nearest f32 of `x`: [`settled`].
//!
//! `y = ±0` is accepted too: with every denominator checked nonzero and finite and every
//! numerator finite (the builders check both), a zero estimate is either an exact zero (`a + b`
//! rounds to 0 only when `a = −b`) or a quotient that underflowed below `2⁻¹⁰⁷⁴`, and then
//! `|x| < 2⁻¹⁵⁰` rounds to a zero of the same sign. Everything else (f32 subnormals, values
//! at or beyond `2¹²⁷`, NaN, infinities, an intermediate that left the normal f64 range, or
//! `L` within `SLACK` of `2²⁸`) goes to the exact decision. The first four cannot be decided by
//! the low-bit test; the last happens for about one element in 16 million (`2·16/2²⁹`) of
//! evenly spread inputs.
//!
//! ## The exact decision
//! [`nearest_of_ratio`] takes `x` as a ratio `N/D` whose numerator and denominator are
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
//! Offset elements are rounded away from the plain element instead ([`outward_settled`]):
//! there the boundaries are the f32 values themselves (low 29 bits 0), and the estimate's
//! error is checked in f64 against its distance to the nearest f32, falling back to
//! double-double ([`crate::offset`]).

use std::cmp::Ordering;

/// The number of f64 ulps within which an estimate is sent to the exact decision: twice the
/// proven bound of eight.
pub(crate) const SLACK: u64 = 16;

/// The significand bits an f64 has beyond an f32's.
const EXTRA_BITS: u32 = 52 - 23;
const EXTRA_MASK: u64 = (1 << EXTRA_BITS) - 1;
/// The low bits of a midpoint between adjacent f32.
const MIDPOINT: u64 = 1 << (EXTRA_BITS - 1);
/// The biased f64 exponent of `2⁻¹²⁶`, the smallest normal f32.
const MIN_EXPONENT: u64 = 1023 - 126;
/// The number of binades `[2⁻¹²⁶, 2¹²⁷)` in which the low-bit test applies.
const BINADES: u64 = 126 + 127;

/// Whether `y as f32` is the nearest f32 of every `x` within [`SLACK`] f64 ulps of `y` (or,
/// for `y = ±0`, of every `x` the module docs admit). Branch-free, so a builder can combine
/// the verdicts of all its elements with `&` and branch once.
#[inline(always)]
pub(crate) fn settled(y: f64) -> bool {
    let bits = y.to_bits();
    let exponent = (bits >> 52) & 0x7ff;
    let in_range = exponent.wrapping_sub(MIN_EXPONENT) < BINADES;
    let far = (bits & EXTRA_MASK).wrapping_sub(MIDPOINT - SLACK) > 2 * SLACK;
    (in_range & far) | (bits << 1 == 0)
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
        let mut q = terms[i];
        for j in 0..i {
            let (s, e) = two_sum(q, terms[j]);
            terms[j] = e;
            q = s;
        }
        terms[i] = q;
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
    loop {
        if c != f32::INFINITY {
            let up = c.next_up();
            let m = 0.5 * (extended(c) + extended(up));
            match x.compare(m) {
                Ordering::Greater => {
                    c = up;
                    continue;
                }
                Ordering::Equal if c.to_bits() & 1 == 1 => {
                    c = up;
                    continue;
                }
                _ => {}
            }
        }
        if c != f32::NEG_INFINITY {
            let down = c.next_down();
            let m = 0.5 * (extended(c) + extended(down));
            match x.compare(m) {
                Ordering::Less => {
                    c = down;
                    continue;
                }
                Ordering::Equal if c.to_bits() & 1 == 1 => {
                    c = down;
                    continue;
                }
                _ => {}
            }
        }
        return c;
    }
}

/// Whether outward (directed) rounding of a target known as `target ± error` is decided by
/// the f64 value alone: the nearest f32 lies farther than `error` from it (then so does every
/// other f32, since `|gap| ≤` half an f32 spacing). Returns the f32 just beyond the target in
/// the direction `up`, or `None` when undecided or not finite.
#[inline(always)]
pub(crate) fn outward_settled(target: f64, error: f64, up: bool) -> Option<f32> {
    let nearest = target as f32;
    let gap = f64::from(nearest) - target;
    if !(gap.abs() > error) || !nearest.is_finite() {
        return None;
    }
    let x = match (up, gap > 0.0) {
        (true, false) => nearest.next_up(),
        (false, true) => nearest.next_down(),
        _ => nearest,
    };
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_low_bit_test_refuses_midpoints_and_accepts_f32_values() {
        let mid = 1.0 + f64::from(f32::EPSILON) / 2.0;
        assert!(!settled(mid));
        assert!(!settled(f64::from_bits(mid.to_bits() + SLACK)));
        assert!(settled(f64::from_bits(mid.to_bits() + SLACK + 1)));
        assert!(settled(f64::from_bits(mid.to_bits() - SLACK - 1)));
        assert!(settled(1.0) && settled(-3.5) && settled(0.0) && settled(-0.0));
        for bad in [f64::NAN, f64::INFINITY, 2f64.powi(127), 1e-39, f64::MIN_POSITIVE] {
            assert!(!settled(bad), "{bad}");
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
        let r = Ratio { num: &tie, den: &one, scale: 1.0 };
        assert_eq!(nearest_of_ratio(r), 1.0);
        // Just above the tie: up.
        let above = [1.0, 2f64.powi(-24), 2f64.powi(-80)];
        let r = Ratio { num: &above, den: &one, scale: 1.0 };
        assert_eq!(nearest_of_ratio(r), 1.0f32.next_up());
        // 1/3 with a negative denominator, halved by the scale.
        let r = Ratio { num: &one, den: &[-3.0], scale: 2.0 };
        assert_eq!(nearest_of_ratio(r), (-1.0f64 / 6.0) as f32);
        // Overflow threshold and a subnormal result.
        let threshold = [f64::from(f32::MAX), 2f64.powi(103)];
        let r = Ratio { num: &threshold, den: &one, scale: 1.0 };
        assert_eq!(nearest_of_ratio(r), f32::INFINITY);
        let tiny = [3.0 * 2f64.powi(-150)];
        let r = Ratio { num: &tiny, den: &one, scale: 1.0 };
        assert_eq!(nearest_of_ratio(r), 2.0 * 2f32.powi(-149)); // 1.5 ulp: tie to even, 2
    }
}

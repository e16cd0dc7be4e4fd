//! Double-double arithmetic: a value carried as an unevaluated sum `hi + lo` of two f64, about
//! 106 bits. Used where a result is rounded to f32 in a chosen direction, so the direction is
//! decided on a value whose error (≈ 2⁻¹⁰⁴ relative) is far below any f32 spacing.

/// `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DoubleDouble {
    pub hi: f64,
    pub lo: f64,
}

impl DoubleDouble {
    pub fn from_f64(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// The exact sum `a + b` (Knuth's TwoSum).
    pub fn sum(a: f64, b: f64) -> Self {
        let s = a + b;
        let bb = s - a;
        let e = (a - (s - bb)) + (b - bb);
        Self { hi: s, lo: e }
    }

    /// The exact product `a · b` (TwoProd with a fused multiply-add).
    pub fn product(a: f64, b: f64) -> Self {
        let p = a * b;
        Self {
            hi: p,
            lo: a.mul_add(b, -p),
        }
    }

    fn renormalized(hi: f64, lo: f64) -> Self {
        let s = hi + lo;
        Self {
            hi: s,
            lo: lo - (s - hi),
        }
    }

    pub fn add(self, other: Self) -> Self {
        let s = Self::sum(self.hi, other.hi);
        Self::renormalized(s.hi, s.lo + self.lo + other.lo)
    }

    pub fn mul(self, other: Self) -> Self {
        let p = Self::product(self.hi, other.hi);
        Self::renormalized(p.hi, p.lo + self.hi * other.lo + self.lo * other.hi)
    }

    pub fn mul_f64(self, x: f64) -> Self {
        self.mul(Self::from_f64(x))
    }

    pub fn sub(self, other: Self) -> Self {
        self.add(other.neg())
    }

    /// The f64 nearest `hi + lo` (they are kept renormalized, so this is `hi`).
    pub fn to_f64(self) -> f64 {
        self.hi
    }

    pub fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    /// `self / other` by three steps of long division.
    pub fn div(self, other: Self) -> Self {
        let q1 = self.hi / other.hi;
        let r = self.sub(other.mul_f64(q1));
        let q2 = r.hi / other.hi;
        let r = r.sub(other.mul_f64(q2));
        let q3 = r.hi / other.hi;
        Self::from_f64(q1).add(Self::renormalized(q2, q3))
    }

    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    /// The sign of `self − x` for an f64 `x`, exactly (0 when equal).
    pub fn compare_f64(self, x: f64) -> std::cmp::Ordering {
        let d = Self::sum(self.hi, -x).add(Self::from_f64(self.lo));
        d.hi.partial_cmp(&0.0).unwrap_or(std::cmp::Ordering::Equal)
    }

    /// The smallest f32 not below `self` (`up`), or the largest not above it (`!up`).
    pub fn to_f32_directed(self, up: bool) -> f32 {
        use std::cmp::Ordering::{Greater, Less};
        let nearest = self.hi as f32;
        match (up, self.compare_f64(nearest as f64)) {
            (true, Greater) => nearest.next_up(),
            (false, Less) => nearest.next_down(),
            _ => nearest,
        }
    }
}

/// A power of two `s` with `|x|·s` in `[1, 2)`, so that scaling a homogeneous formula's inputs by
/// `s` is exact and keeps its products far from overflow. 1 for zero, subnormal or extreme `x`.
pub(crate) fn unit_scale(x: f64) -> f64 {
    let exponent = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    if !(-1000..=1000).contains(&exponent) {
        return 1.0;
    }
    f64::from_bits(((1023 - exponent) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sum_and_product_are_error_free() {
        let s = DoubleDouble::sum(1.0, 1e-30);
        assert_eq!((s.hi, s.lo), (1.0, 1e-30));
        let p = DoubleDouble::product(1.0 + f64::EPSILON, 1.0 + f64::EPSILON);
        assert_eq!(p.hi, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(p.lo, f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn division_recovers_a_third_to_double_double_precision() {
        let third = DoubleDouble::from_f64(1.0).div(DoubleDouble::from_f64(3.0));
        let back = third.mul(DoubleDouble::from_f64(3.0));
        assert!((back.hi - 1.0 + back.lo).abs() < 1e-31);
    }

    #[test]
    fn directed_rounding_brackets_the_value() {
        let x = DoubleDouble::sum(1.0, 1e-20);
        assert_eq!(x.to_f32_directed(true), 1.0f32.next_up());
        assert_eq!(x.to_f32_directed(false), 1.0);
        let exact = DoubleDouble::from_f64(0.5);
        assert_eq!(exact.to_f32_directed(true), 0.5);
        assert_eq!(exact.to_f32_directed(false), 0.5);
    }

    #[test]
    fn unit_scale_lands_in_one_two() {
        for x in [1e-12, 3.0, -7.5e14, 1e300] {
            let y = (x * unit_scale(x)).abs();
            assert!((1.0..2.0).contains(&y), "{x} -> {y}");
        }
    }
}

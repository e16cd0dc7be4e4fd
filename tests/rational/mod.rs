//! Exact rational arithmetic for the tests that check zshift against the defining formulas:
//! every finite f64 and f32 is a rational, so references computed here carry no rounding.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::One;

/// An exact rational.
pub type Q = BigRational;

/// The exact value of a finite f64.
pub fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// The exact value of a finite f32.
pub fn q32(x: f32) -> Q {
    q(f64::from(x))
}

/// An integer as a rational.
pub fn int(i: i64) -> Q {
    Q::from_integer(BigInt::from(i))
}

/// `2^e`, exactly.
pub fn pow2(e: i64) -> Q {
    let p = Q::from_integer(BigInt::one() << e.unsigned_abs());
    if e >= 0 {
        p
    } else {
        p.recip()
    }
}

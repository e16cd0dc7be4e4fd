//! The seed's `LoadOffsetMatrix` arithmetic (seed 000, "Source Code"), in C's types, so the
//! benchmark and the report measure exactly what a C program built from the seed computes.
//!
//! ```c
//! GLfloat epsilon = -2.0F * f * n * delta / ((f + n) * pz * (pz + delta));
//! matrix[10] *= 1.0F + epsilon;
//! ```
//! `f` and `n` are `GLdouble` and `delta`, `pz` are `GLfloat`. By C's usual arithmetic
//! conversions `-2.0F * f` is a double, so the numerator and `(f + n) * pz` are double;
//! `pz + delta` is float + float, rounded to float first; the quotient is rounded to float on
//! assignment; the tweak is all float. Rust's f32/f64 operations are IEEE-754 with no
//! contraction, as C with `FLT_EVAL_METHOD == 0`.

/// ε as the seed computes it (eq. 4.1.7 in the seed's mixed float/double arithmetic).
pub fn seed_epsilon(n: f64, f: f64, delta: f32, pz: f32) -> f32 {
    let numerator = -2.0f64 * f * n * delta as f64;
    let denominator = (f + n) * pz as f64 * (pz + delta) as f64;
    (numerator / denominator) as f32
}

/// `matrix[10] *= 1.0F + epsilon`, in float.
pub fn seed_tweak(m10: f32, epsilon: f32) -> f32 {
    m10 * (1.0f32 + epsilon)
}

//! Bugs the hardening work (fuzzing, edge-input sweeps) found, each pinned by the input that
//! found it. The references are the exact limits of the seed formulas, not the code's output.

use zshift::ffi::{zshift_depth_resolution, zshift_min_delta_toward, ZSHIFT_OK};

/// Walker's step `Δd = q·d²/(b + q·d)` with `b = fn/(f−n) ≈ n` tends to `d` as `n → 0`:
/// with n = f64::MIN_POSITIVE the ratio d/n overflowed and ∞/∞ returned NaN with ZSHIFT_OK.
#[test]
fn depth_step_with_a_near_plane_at_the_bottom_of_f64_is_the_distance_itself() {
    let (n, f, bits, d) = (f64::MIN_POSITIVE, 1000.0, 24, 50.0);
    // Exact: Δd = d·u/(1+u) with u = (d/n)·((f−n)/f)/(2^24−1) ≈ 1.3e301, so Δd = d·(1 − 1/u)
    // rounds to d.
    let mut out = f64::NAN;
    assert_eq!(zshift_depth_resolution(n, f, bits, d, &mut out), ZSHIFT_OK);
    assert_eq!(out, d);
    let mut out = f64::NAN;
    assert_eq!(zshift_min_delta_toward(n, f, bits, -d, &mut out), ZSHIFT_OK);
    assert_eq!(out, d);
}

/// The same overflow found by the fuzzer (scripts/fuzz, 15,624 executions from an empty corpus
/// with the bug restored): d/n > f64::MAX at an ordinary near plane and a far point.
#[test]
fn depth_step_at_a_distance_beyond_f64_max_times_n_is_the_distance_itself() {
    let (n, f, bits, d) = (1.2696530310154343e-15, f64::MAX, 3, 6.908781459470861e307);
    // u = (d/n)·((f−n)/f)/7 ≈ 7.8e321 (not an f64), so Δd = d·(1 − 1/u) rounds to d.
    let mut out = f64::NAN;
    assert_eq!(zshift_min_delta_toward(n, f, bits, -d, &mut out), ZSHIFT_OK);
    assert_eq!(out, d);
    let mut out = f64::NAN;
    assert_eq!(zshift_depth_resolution(n, f, bits, d, &mut out), ZSHIFT_OK);
    assert_eq!(out, d);
}

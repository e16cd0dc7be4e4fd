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

// ---- Found by the edge-input sweep of tests/abi after the projections/recommend merge ----

use num_rational::BigRational;
use num_traits::Signed;
use zshift::ffi::{
    zshift_min_epsilon, zshift_range_offset, zshift_recommend, zshift_window_depth,
    ZshiftRecommendation, ZshiftScene, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_ERR_OVERFLOW,
    ZSHIFT_FORMAT_UNORM16, ZSHIFT_OFFSET_RELATIVE,
};

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

fn within_ulps(got: f64, exact: &BigRational, ulps: f64) -> bool {
    got.is_finite() && (q(got) - exact).abs() <= exact.abs() * q(ulps * f64::EPSILON)
}

/// Seed 002's 2/(2^m − 1)·(f − n)/(f + n) at f = f64::MAX: the double-double evaluation was
/// not rescaled for |f| ≥ 2^1001, so 2(f − n) overflowed and ∞/∞ returned NaN with ZSHIFT_OK.
#[test]
fn min_epsilon_with_the_largest_far_plane_is_finite_and_exact() {
    let (n, f) = (0.1, f64::MAX);
    let mut out = f64::NAN;
    assert_eq!(zshift_min_epsilon(n, f, 24, &mut out), ZSHIFT_OK);
    let steps = q(16_777_215.0);
    let exact = q(2.0) / steps * (q(f) - q(n)) / (q(f) + q(n));
    assert!(within_ulps(out, &exact, 2.0), "{out}");
}

/// Walker's f(d) = f(d − n)/(d(f − n)) with f = f64::MAX: the inputs were scaled to put n in
/// [1, 2), which sent f to +∞ and returned NaN with ZSHIFT_OK.
#[test]
fn window_depth_with_the_largest_far_plane_is_finite_and_exact() {
    // The second input came from the sweep once the first was fixed by rescaling.
    for (n, f, d) in [
        (0.1, f64::MAX, 50.0),
        (9.316303894052092, f64::MAX, 1286634482690.3625),
    ] {
        let mut out = f64::NAN;
        assert_eq!(zshift_window_depth(n, f, d, &mut out), ZSHIFT_OK);
        let exact = q(f) * (q(d) - q(n)) / (q(d) * (q(f) - q(n)));
        assert!(within_ulps(out, &exact, 2.0), "{out}");
    }
}

/// A range offset for an absurd number of steps does not fit a double: it must say so
/// (ZSHIFT_ERR_OVERFLOW) and leave the output alone, not return +∞ with ZSHIFT_OK.
#[test]
fn range_offset_that_overflows_is_an_error() {
    let mut out = [7.0f64; 3];
    // kind RELATIVE, UNORM16, n = 1e-6, f = 1e6: one step at d = 100 is ε ≈ r·d/b ≈ 1.5e3, so
    // f64::MAX steps overflow (the shift d·ε/(1 + ε) then gave ∞/∞ = NaN).
    let (n, f, clip, format, kind) = (
        1e-6,
        1e6,
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        ZSHIFT_FORMAT_UNORM16,
        ZSHIFT_OFFSET_RELATIVE,
    );
    let status = zshift_range_offset(
        n,
        f,
        clip,
        format,
        kind,
        10.0,
        100.0,
        f64::MAX,
        out.as_mut_ptr(),
    );
    assert_eq!(status, ZSHIFT_ERR_OVERFLOW);
    assert_eq!(out, [7.0; 3]);
}

/// The bleed gap d·x/(1 + x) with x = Δw·d/(f/(f−n)·n): a subnormal near plane made x = +∞
/// and ∞/∞ returned NaN with ZSHIFT_OK. Its limit as x → ∞ is d.
#[test]
fn recommend_with_a_subnormal_near_plane_has_a_finite_bleed_gap() {
    // The input the sweep found (a wide, off-centre frustum; decal out to 1e300).
    let scene = ZshiftScene {
        pipeline: Default::default(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        l: -1e-300,
        r: -2.2250738585072014e-308,
        b: -4.486800777063599e-12,
        t: 4.486800777063599e-12,
        n: 5e-324,
        f: f64::INFINITY,
        viewport_width: 802,
        viewport_height: 2280482802,
        depth_format: 0x81A6,
        decal_near: 0.16284290802924148,
        decal_far: 1e300,
        slope: 0.0,
        exact_depth: 3,
        subpixel_bits: -1,
        depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
        base_reach: 0.0,
        profile: std::ptr::null(),
    };
    let mut out = std::mem::MaybeUninit::<ZshiftRecommendation>::uninit();
    let status = zshift_recommend(&scene, out.as_mut_ptr());
    if status == ZSHIFT_OK {
        // SAFETY: ZSHIFT_OK means the output was written.
        let r = unsafe { out.assume_init() };
        assert!(r.bleed_gap.is_finite(), "bleed gap {}", r.bleed_gap);
        assert!(r.bleed_gap <= scene.decal_far);
    }
}

mod abi;

/// Two scenes the sweep found where `zshift_recommend` returned ZSHIFT_OK with
/// polygon_offset_units = +∞ (a near-degenerate frustum, f/n − 1 ≈ 1e-15 and 2e-7): every
/// output must be finite, or the call an error that leaves the output alone (the shared
/// contract check of tests/abi).
#[test]
fn recommend_never_returns_an_infinite_polygon_offset() {
    let scenes = [
        ZshiftScene {
            pipeline: Default::default(),
            decal_corners: std::ptr::null(),
            decal_corner_count: 0,
            l: -2464271192.763489,
            r: -1.7976931348623157e308,
            b: -24752007585.897285,
            t: 3.4178453063444105e-87,
            n: 34588137.61820798,
            f: 34588137.61820802,
            viewport_width: 321,
            viewport_height: 3427,
            depth_format: 0x81A5,
            decal_near: 34588137.61820798,
            decal_far: 34588137.618208,
            slope: 0.0028721339874085983,
            exact_depth: 0,
            subpixel_bits: -1,
            depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
            base_reach: 0.0,
            profile: std::ptr::null(),
        },
        ZshiftScene {
            pipeline: Default::default(),
            decal_corners: std::ptr::null(),
            decal_corner_count: 0,
            l: -7.645722780061472,
            r: 3.0931043469988655,
            b: -0.00017595535455433751,
            t: 1e300,
            n: 0.006346310772430657,
            f: 0.006346312259126362,
            viewport_width: 4,
            viewport_height: 792,
            depth_format: 0x81A6,
            decal_near: 0.006346310772430657,
            decal_far: 0.00634631167674828,
            slope: 4.771128792552485,
            exact_depth: 0,
            subpixel_bits: -1,
            depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
            base_reach: 0.0,
            profile: std::ptr::null(),
        },
    ];
    for scene in scenes {
        let inputs = abi::Inputs {
            scene,
            ..abi::Inputs::VALID
        };
        abi::call_checked(abi::entry("zshift_recommend"), &inputs, 3);
    }
}

/// Walker's window depth at the top of f64: n = 1e300, d = f = f64::MAX. Double-double
/// products near f64::MAX overflowed inside the error-free transforms and returned NaN.
#[test]
fn window_depth_at_the_top_of_f64_is_one() {
    let mut out = f64::NAN;
    assert_eq!(
        zshift_window_depth(1e300, f64::MAX, f64::MAX, &mut out),
        ZSHIFT_OK
    );
    assert_eq!(out, 1.0); // f(f) = 1 exactly
}

/// Reversed Z with float depth and a window depth in the subnormal range at the decal's far
/// end: the recommendation walks the binades of f32 up from there. `2^k` for k below −1022 was
/// computed as `1/2^−k`, which overflows to ∞ and gave 0, and the walk never ended (found by
/// scripts/sanitize once it fed the front door). It must return, whatever it returns.
#[test]
fn reversed_float_recommendation_with_a_subnormal_window_depth_returns() {
    let scene = ZshiftScene {
        pipeline: Default::default(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        l: -1e-300,
        r: 1e-300,
        b: -1e-300,
        t: 1e-300,
        n: 1e-300,
        f: f64::INFINITY,
        viewport_width: 64,
        viewport_height: 64,
        depth_format: 0x8CAC,
        decal_near: 1e-3,
        decal_far: 1e20,
        slope: 0.0,
        exact_depth: 0,
        subpixel_bits: -1,
        depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
        base_reach: 0.0,
        profile: std::ptr::null(),
    };
    let mut out = std::mem::MaybeUninit::<ZshiftRecommendation>::uninit();
    let status = zshift::ffi::zshift_recommend_clip(
        &scene,
        zshift::ffi::ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
        out.as_mut_ptr(),
    );
    assert!(status.0 >= 0, "{status:?}");
}

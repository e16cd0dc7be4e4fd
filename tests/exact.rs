//! Every core function against exact rational arithmetic (every finite f64 is a rational), over a
//! table of stiff cases and a deterministic random sweep. References are the seed formulas
//! evaluated in `BigRational`, never the code under test.
//!
//! `cargo test --release --test exact -- --nocapture` prints the largest ulp error per function.

use std::collections::BTreeMap;
use std::sync::Mutex;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use zshift::ErrorKind;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

fn int(i: i64) -> Q {
    Q::from_integer(BigInt::from(i))
}

/// `2^m − 1`, the number of depth steps.
fn steps(bits: u32) -> Q {
    Q::from_integer((BigInt::one() << bits) - 1)
}

/// Distance of `x` from `exact` in units of the f64 spacing at `exact`.
fn ulps64(x: f64, exact: &Q) -> f64 {
    let e = exact.to_f64().unwrap();
    let spacing = if e == 0.0 {
        f64::MIN_POSITIVE
    } else {
        ulp64(e)
    };
    ((q(x) - exact).abs() / q(spacing)).to_f64().unwrap()
}

fn ulp64(x: f64) -> f64 {
    let x = x.abs();
    if x < f64::MIN_POSITIVE {
        return f64::from_bits(1);
    }
    let e = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    2f64.powi(e - 52)
}

fn ulp32(x: f32) -> f64 {
    let x = x.abs();
    if x < f32::MIN_POSITIVE {
        return f32::from_bits(1) as f64;
    }
    let e = ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    2f64.powi(e - 23)
}

/// Correct rounding, allowing the 2⁻¹⁰⁰-relative error of the double-double intermediates.
const HALF_ULP: f64 = 0.5 + 1e-12;

/// The largest error seen per function, for the closing table.
static WORST: Mutex<BTreeMap<&'static str, f64>> = Mutex::new(BTreeMap::new());

fn record(name: &'static str, err: f64) {
    let mut w = WORST.lock().unwrap();
    let e = w.entry(name).or_insert(0.0);
    *e = e.max(err);
}

// ---- exact references (seed formulas) ----

/// Finite far plane, or the `f = +∞` limit where noted.
#[derive(Clone, Copy, Debug)]
struct Case {
    n: f64,
    f: f64,
    pz: f64,
    delta: f64,
    bits: u32,
}

/// `(f + n) / (f − n)`, 1 at f = ∞.
fn ratio(c: &Case) -> Q {
    if c.f.is_infinite() {
        return Q::one();
    }
    (q(c.f) + q(c.n)) / (q(c.f) - q(c.n))
}

/// eq. 4.1.7: `−2fn/(f+n) · δ/(Pz(Pz+δ))`.
fn exact_epsilon(c: &Case) -> Q {
    let factor = if c.f.is_infinite() {
        int(2) * q(c.n)
    } else {
        int(2) * q(c.f) * q(c.n) / (q(c.f) + q(c.n))
    };
    -factor * q(c.delta) / (q(c.pz) * (q(c.pz) + q(c.delta)))
}

/// corrected k of eq. 4.1.11 (seed 002): `(f − n)/(f n (2^m − 1))`.
fn exact_k(c: &Case) -> Q {
    let span_over_far = if c.f.is_infinite() {
        Q::one()
    } else {
        (q(c.f) - q(c.n)) / q(c.f)
    };
    span_over_far / (q(c.n) * steps(c.bits))
}

/// Walker's f(d) in its printed form.
fn exact_window(n: f64, f: f64, d: f64) -> Q {
    if f.is_infinite() {
        return Q::one() - q(n) / q(d);
    }
    let (n, f, d) = (q(n), q(f), q(d));
    (&f + &n) / (int(2) * (&f - &n)) - &f * &n / (&d * (&f - &n)) + Q::new(1.into(), 2.into())
}

// ---- the checks ----

fn check_case(c: &Case) {
    let k = exact_k(c);
    let d = -c.pz;

    let eps = zshift::epsilon(c.n, c.f, c.delta, c.pz).unwrap_or_else(|e| panic!("{e} in {c:?}"));
    let err = ulps64(eps, &exact_epsilon(c));
    record("zshift_epsilon", err);
    assert!(err <= HALF_ULP, "epsilon off by {err} ulp in {c:?}");

    let min_eps = zshift::min_epsilon(c.n, c.f, c.bits).unwrap();
    let exact_min_eps = int(2) / (steps(c.bits) * ratio(c));
    let err = ulps64(min_eps, &exact_min_eps);
    record("zshift_min_epsilon", err);
    assert!(err <= HALF_ULP, "min_epsilon off by {err} ulp in {c:?}");

    // eq. 4.1.9 with the corrected k; Pz is negative.
    let toward = zshift::min_delta_toward(c.n, c.f, c.bits, c.pz).unwrap();
    let exact_toward = &k * q(c.pz) * q(c.pz) / (Q::one() - &k * q(c.pz));
    let err = ulps64(toward, &exact_toward);
    record("zshift_min_delta_toward", err);
    assert!(
        err <= HALF_ULP,
        "min_delta_toward off by {err} ulp in {c:?}"
    );

    // Walker's eq. (3) generalised: f(d) − f(d − Δd) = 1/(2^m − 1) defines Δd.
    let step = zshift::depth_resolution(c.n, c.f, c.bits, d).unwrap();
    let exact_step = {
        let dq = q(d);
        let span = if c.f.is_infinite() {
            Q::one()
        } else {
            (q(c.f) - q(c.n)) / q(c.f)
        };
        // b = fn/(f−n) = n / span;  Δd = q d² / (b + q d)
        let b = q(c.n) / span;
        let quantum = Q::one() / steps(c.bits);
        &quantum * &dq * &dq / (b + &quantum * &dq)
    };
    let err = ulps64(step, &exact_step);
    record("zshift_depth_resolution", err);
    assert!(
        err <= HALF_ULP,
        "depth_resolution off by {err} ulp in {c:?}"
    );
    // The two seeds agree once 002 is applied (NOTES): exactly equal references.
    assert_eq!(
        exact_step, exact_toward,
        "Walker's step and Lengyel's δ differ in {c:?}"
    );

    let window = zshift::window_depth(c.n, c.f, d).unwrap();
    let exact_w = exact_window(c.n, c.f, d);
    let err = ulps64(window, &exact_w);
    record("zshift_window_depth", err);
    assert!(err <= HALF_ULP, "window_depth off by {err} ulp in {c:?}");

    check_away(c, &k);
    check_offset_matrix(c);
}

/// eq. 4.1.10; unresolvable exactly when k|Pz| ≥ 1 (up to the rounding of k|Pz| itself).
fn check_away(c: &Case, k: &Q) {
    let kd = k * q(-c.pz);
    let got = zshift::max_delta_away(c.n, c.f, c.bits, c.pz);
    if kd >= Q::one() {
        let near_one = ((&kd - Q::one()).abs()).to_f64().unwrap() < 1e-28;
        if !near_one {
            assert_eq!(got.unwrap_err().kind(), ErrorKind::Unresolvable, "{c:?}");
        }
        return;
    }
    let cond = (&kd / (Q::one() - &kd)).to_f64().unwrap();
    let away = match got {
        Ok(v) => v,
        Err(e) if e.kind() == ErrorKind::Unresolvable => {
            assert!(
                cond > 1e28,
                "refused a resolvable case (cond {cond:e}): {c:?}"
            );
            return;
        }
        Err(e) => panic!("{e} in {c:?}"),
    };
    let exact = -k * q(c.pz) * q(c.pz) / (Q::one() + k * q(c.pz));
    let err = ulps64(away, &exact);
    record("zshift_max_delta_away", err);
    record("zshift_max_delta_away / (1 + cond)", err / (1.0 + cond));
    assert!(
        err <= 0.5 + 1e-13 * (1.0 + cond),
        "max_delta_away off by {err} ulp (cond {cond:e}) in {c:?}"
    );
}

/// Frustum elements within 1 f32 ulp; the offset element rounded outward by less than one ulp.
fn check_offset_matrix(c: &Case) {
    let (l, r, b, t) = (-0.75 * c.n, 0.5 * c.n, -0.4 * c.n, 0.6 * c.n);
    let exact = exact_frustum(l, r, b, t, c.n, c.f);
    let fits_f32 = exact.iter().all(|e| e.abs() < q(f32::MAX as f64));
    let plain = match zshift::frustum(l, r, b, t, c.n, c.f) {
        Ok(m) => m.to_cols_array(),
        Err(e) if !fits_f32 && e.kind() == ErrorKind::Overflow => return,
        Err(e) => panic!("{e} in {c:?}"),
    };
    for (i, (&x, e)) in plain.iter().zip(&exact).enumerate() {
        let err = ((q(x as f64) - e).abs() / q(ulp32(x))).to_f64().unwrap();
        record("zshift_frustum (f32 ulp)", err);
        assert!(
            err <= 1.0,
            "frustum element {i} off by {err} f32 ulp in {c:?}"
        );
    }
    let shifted = match zshift::load_offset_matrix(l, r, b, t, c.n, c.f, c.delta, c.pz) {
        Ok(m) => m.to_cols_array(),
        Err(e) if e.kind() == ErrorKind::Overflow => return,
        Err(e) => panic!("{e} in {c:?}"),
    };
    for i in (0..16).filter(|&i| i != 10) {
        assert_eq!(
            shifted[i].to_bits(),
            plain[i].to_bits(),
            "element {i} changed in {c:?}"
        );
    }
    // o = m10·ε, exactly.
    let offset = -ratio(c) * exact_epsilon(c);
    let seen = q(shifted[10] as f64) - q(plain[10] as f64);
    assert!(
        seen.abs() >= offset.abs(),
        "offset lost: {seen} < {offset} in {c:?}"
    );
    assert!(
        seen.is_zero() || seen.signum() == offset.signum(),
        "offset has the wrong sign in {c:?}"
    );
    let excess = ((seen.abs() - offset.abs()) / q(ulp32(shifted[10])))
        .to_f64()
        .unwrap();
    record("zshift_load_offset_matrix excess (f32 ulp)", excess);
    assert!(
        excess <= 1.0,
        "offset exceeds the request by {excess} f32 ulp in {c:?}"
    );
}

fn exact_frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> [Q; 16] {
    let (lq, rq, bq, tq, nq) = (q(l), q(r), q(b), q(t), q(n));
    let mut m: [Q; 16] = std::array::from_fn(|_| Q::zero());
    m[0] = int(2) * &nq / (&rq - &lq);
    m[5] = int(2) * &nq / (&tq - &bq);
    m[8] = (&rq + &lq) / (&rq - &lq);
    m[9] = (&tq + &bq) / (&tq - &bq);
    m[11] = int(-1);
    if f.is_infinite() {
        m[10] = int(-1);
        m[14] = int(-2) * &nq;
    } else {
        let fq = q(f);
        m[10] = -(&fq + &nq) / (&fq - &nq);
        m[14] = int(-2) * &fq * &nq / (&fq - &nq);
    }
    m
}

// ---- the cases ----

/// Stiff and extreme cases named in the core issue.
fn stiff_cases() -> Vec<(&'static str, Case)> {
    let mut cases = Vec::new();
    let planes: [(&str, f64, f64); 8] = [
        ("f/n = 1 + 1e-12", 1.0, 1.0 + 1e-12),
        ("f/n = 1e15", 1e-3, 1e12),
        ("n = 1e-12, f = 1", 1e-12, 1.0),
        ("n = 1e-12, f/n = 1e15", 1e-12, 1e3),
        ("f = +inf", 0.1, f64::INFINITY),
        ("n = 1e-12, f = +inf", 1e-12, f64::INFINITY),
        ("ordinary 0.1..1000", 0.1, 1000.0),
        ("huge 1e200..1e210", 1e200, 1e210),
    ];
    for (name, n, f) in planes {
        let far = if f.is_infinite() { n * 1e9 } else { f };
        let depths = [-n, -far, -(n.sqrt() * far.sqrt()), -(n + 0.37 * (far - n))];
        for pz in depths {
            let d = -pz;
            for bits in [1, 16, 24, 32] {
                for delta in [d * 1e-6, -d * 1e-3, d * (1.0 - 1e-12), d * 0.5, 0.0] {
                    cases.push((
                        name,
                        Case {
                            n,
                            f,
                            pz,
                            delta,
                            bits,
                        },
                    ));
                }
            }
        }
    }
    cases
}

/// Depths where k·|Pz| lies within 1e-9 of 1 on either side (the ill-conditioned eq. 4.1.10).
fn near_unresolvable_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for (n, f, bits) in [(1.0, 1e6, 16u32), (0.01, 1e6, 24), (1e-6, 1e6, 32)] {
        // k d = 1  ⇔  d = n f (2^m − 1) / (f − n)
        let d1 = n * f * ((1u64 << bits) - 1) as f64 / (f - n);
        for rel in [-1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9] {
            let d = d1 * (1.0 + rel);
            if d <= f {
                cases.push(Case {
                    n,
                    f,
                    pz: -d,
                    delta: 0.01 * d,
                    bits,
                });
            }
        }
    }
    cases
}

/// A deterministic log-uniform sweep (SplitMix64), so a failure reproduces.
fn random_cases(count: usize) -> Vec<Case> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let n = 10f64.powf(-12.0 + 15.0 * next());
            let f = n * 10f64.powf(15.0 * next()).max(1.0 + 1e-9);
            let d = n * (f / n).powf(next());
            let delta = d * (2.0 * next() - 1.0) * 10f64.powf(-8.0 * next());
            let bits = [1, 8, 16, 24, 32][(next() * 5.0) as usize % 5];
            Case {
                n,
                f,
                pz: -d.clamp(n, f),
                delta,
                bits,
            }
        })
        .collect()
}

#[test]
fn stiff_case_table_against_exact_arithmetic() {
    let cases = stiff_cases();
    for (_, c) in &cases {
        check_case(c);
    }
    for c in near_unresolvable_cases() {
        check_away(&c, &exact_k(&c));
    }
    for c in random_cases(3000) {
        check_case(&c);
    }
    println!(
        "largest error per function over {} stiff + 3000 random cases:",
        cases.len()
    );
    for (name, err) in WORST.lock().unwrap().iter() {
        println!("  {name:45} {err:.3}");
    }
}

#[test]
fn min_epsilon_is_the_corrected_bound_not_the_printed_one() {
    // 002: the printed 1/(2^m−1) is half the true NDC step; the corrected bound is twice it.
    for bits in [16, 24] {
        let got = zshift::min_epsilon(1.0, 100.0, bits).unwrap();
        let printed = (q(1.0) / steps(bits)) * (int(99) / int(101));
        assert!(ulps64(got, &(int(2) * &printed)) <= HALF_ULP);
        assert!(
            ulps64(got, &printed) > 1e10,
            "the printed bound of 000 is half the step"
        );
    }
}

#[test]
fn depth_step_separates_window_depths_by_exactly_one_quantum() {
    // f(d) − f(d − Δd) = 1/(2^m − 1) up to the f64 rounding of Δd.
    for (n, f, bits, d) in [
        (0.1, 1000.0, 24u32, 500.0),
        (1.0, 1e4, 16, 9e3),
        (0.5, 50.0, 8, 1.0),
    ] {
        let step = zshift::depth_resolution(n, f, bits, d).unwrap();
        let gap = exact_window(n, f, d) - exact_window(n, f, d - step);
        let rel = ((gap * steps(bits)) - Q::one()).abs().to_f64().unwrap();
        assert!(rel < 1e-12, "window gap off by {rel} of a quantum");
    }
}

#[test]
fn bad_inputs_say_which_rule_they_broke() {
    use ErrorKind::*;
    let cases: [(zshift::Result<f64>, ErrorKind); 12] = [
        (zshift::epsilon(f64::NAN, 10.0, 0.1, -1.0), NotFinite),
        (
            zshift::epsilon(1.0, f64::NEG_INFINITY, 0.1, -1.0),
            NotFinite,
        ),
        (zshift::epsilon(0.0, 10.0, 0.1, -1.0), Domain),
        (zshift::epsilon(1.0, 1.0, 0.1, -1.0), Domain),
        (zshift::epsilon(1.0, 10.0, 0.1, -0.5), Domain),
        (zshift::epsilon(1.0, 10.0, 0.1, -11.0), Domain),
        (zshift::epsilon(1.0, 10.0, 2.0, -2.0), Domain),
        (zshift::epsilon(1.0, 10.0, f64::INFINITY, -2.0), NotFinite),
        (zshift::min_epsilon(1.0, 10.0, 0), Domain),
        (zshift::min_epsilon(1.0, 10.0, 33), Domain),
        (zshift::window_depth(1.0, 10.0, 0.5), Domain),
        (zshift::max_delta_away(1.0, 1e6, 16, -1e6), Unresolvable),
    ];
    for (i, (got, kind)) in cases.into_iter().enumerate() {
        let e = got.expect_err(&format!("case {i} should fail"));
        assert_eq!(e.kind(), kind, "case {i}: {e}");
        assert!(!e.detail().is_empty());
    }
    assert_eq!(
        zshift::frustum(1.0, 1.0, -1.0, 1.0, 1.0, 10.0)
            .unwrap_err()
            .kind(),
        Domain
    );
    assert_eq!(
        zshift::frustum(-1.0, 1.0, 2.0, 2.0, 1.0, 10.0)
            .unwrap_err()
            .kind(),
        Domain
    );
}

#[test]
fn infinite_far_plane_gives_the_kooima_limit() {
    let m = zshift::frustum(-1.0, 1.0, -1.0, 1.0, 0.25, f64::INFINITY)
        .unwrap()
        .to_cols_array();
    assert_eq!(m[10], -1.0);
    assert_eq!(m[14], -0.5);
    assert_eq!(m[11], -1.0);
}

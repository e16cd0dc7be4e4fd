//! Property tests (proptest) of the offset and precision formulas through the C ABI, over
//! frusta, depths and shifts spread across many decades.
//!
//! The references are independent of the code under test: exact rational arithmetic
//! (num-rational over BigInt) applied to the seed formulas, with the f64 inputs taken exactly.
//! Conventions as the crate: RH eye space looking down −z, NDC depth [−1, 1], column-major
//! float[16], δ > 0 toward the camera, Pz = −d negative.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;

use zshift::ffi::{
    zshift_depth_resolution, zshift_frustum, zshift_load_offset_matrix, zshift_min_delta_toward,
    zshift_window_depth, ZSHIFT_OK,
};
use zshift::{epsilon_matrix, Frustum};

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

fn q32(x: f32) -> Q {
    q(x as f64)
}

/// One f32 ulp at |x| (the gap to the next float away from zero).
fn ulp32(x: f32) -> Q {
    let a = x.abs();
    q32(f32::from_bits(a.to_bits() + 1)) - q32(a)
}

/// |a − b| ≤ rel·|b| exactly.
fn close(a: f64, b: &Q, rel: f64) -> bool {
    (q(a) - b).abs() <= b.abs() * q(rel)
}

/// A log-uniform f64 in [10^lo, 10^hi).
fn decades(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e| 10f64.powf(e))
}

/// Valid planes: n over six decades, f/n from 1.001 to 1e7, one case in eight f = +∞.
fn planes() -> impl Strategy<Value = (f64, f64)> {
    (decades(-4.0, 2.0), decades(0.0005, 7.0), 0..8u8)
        .prop_map(|(n, ratio, inf)| (n, if inf == 0 { f64::INFINITY } else { n * ratio }))
}

/// A distance in [n, f] (f = +∞ stands for 1e7·n here).
fn distance(n: f64, f: f64, t: f64) -> f64 {
    let far = if f.is_finite() { f } else { n * 1e7 };
    (n + t * (far - n)).clamp(n, far)
}

/// A valid frustum with a point at Pz inside it.
#[derive(Debug, Clone, Copy)]
struct Scene {
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    pz: f64,
}

fn scene() -> impl Strategy<Value = Scene> {
    (
        planes(),
        0.0..=1.0f64,
        decades(-2.0, 1.0),
        decades(-2.0, 1.0),
        -1.0..1.0f64,
    )
        .prop_map(|((n, f), t, w, h, skew)| Scene {
            l: n * (skew - w),
            r: n * (skew + w),
            b: -n * h,
            t: n * h,
            n,
            f,
            pz: -distance(n, f, t),
        })
}

/// A shift at `pz`: a fraction of |Pz| from 1e-9 to 0.9, either way.
fn shift() -> impl Strategy<Value = (f64, bool)> {
    (decades(-9.0, -0.05), any::<bool>())
}

fn frustum(s: &Scene) -> [f32; 16] {
    let mut m = [0f32; 16];
    assert_eq!(
        zshift_frustum(s.l, s.r, s.b, s.t, s.n, s.f, m.as_mut_ptr()),
        ZSHIFT_OK
    );
    m
}

fn offset_matrix(s: &Scene, delta: f64) -> [f32; 16] {
    let mut m = [0f32; 16];
    let status =
        zshift_load_offset_matrix(s.l, s.r, s.b, s.t, s.n, s.f, delta, s.pz, m.as_mut_ptr());
    assert_eq!(status, ZSHIFT_OK, "{s:?} delta {delta}");
    m
}

/// The NDC offset the seed asks for, m10·ε = 2fnδ / ((f−n)·Pz·(Pz+δ)) (eq. 4.1.3 and 4.1.7),
/// exactly; 2nδ / (Pz·(Pz+δ)) when f = +∞.
fn requested_offset(s: &Scene, delta: f64) -> Q {
    let (n, pz, delta) = (q(s.n), q(s.pz), q(delta));
    let two = Q::from_integer(BigInt::from(2));
    let depth = pz.clone() * (pz + delta.clone());
    if s.f.is_infinite() {
        return two * n * delta / depth;
    }
    let f = q(s.f);
    two * f.clone() * n.clone() * delta / ((f - n) * depth)
}

/// Every element but 10 (the x, y and w rows, and the z row's 2, 6, 14).
const UNTOUCHED: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14, 15];

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Eq. 4.1.4: scaling element 10 leaves x, y and w alone, so the offset matrix's x, y and w
    /// rows (and the rest of z) are bit-identical to the plain matrix's, for δ and for ε.
    #[test]
    fn offset_matrices_keep_the_plain_rows(s in scene(), (frac, toward) in shift(),
                                           eps in decades(-12.0, -1.0)) {
        let plain = frustum(&s);
        let delta = if toward { frac * -s.pz } else { -frac * -s.pz };
        let by_delta = offset_matrix(&s, delta);
        let fr = Frustum::new(s.l, s.r, s.b, s.t, s.n, s.f).unwrap();
        for eps in [eps, -eps] {
            let by_eps = epsilon_matrix(&fr, eps).unwrap();
            for i in UNTOUCHED {
                prop_assert_eq!(by_delta[i].to_bits(), plain[i].to_bits(), "delta, element {}", i);
                prop_assert_eq!(by_eps[i].to_bits(), plain[i].to_bits(), "epsilon, element {}", i);
            }
        }
    }

    /// The offset the GPU sees, out[10] − plain[10] taken exactly, has the sign of the request
    /// and is never smaller than it, nor more than one f32 ulp larger.
    #[test]
    fn effective_offset_is_never_below_the_request(s in scene(), (frac, toward) in shift()) {
        let delta = if toward { frac * -s.pz } else { -frac * -s.pz };
        let (plain, m) = (frustum(&s)[10], offset_matrix(&s, delta)[10]);
        let got = q32(m) - q32(plain);
        let want = requested_offset(&s, delta);
        prop_assert!(!want.is_zero());
        prop_assert_eq!(got.signum(), want.signum());
        prop_assert!(got.abs() >= want.abs(), "lost offset: got {} want {}", got, want);
        prop_assert!(got.abs() <= want.abs() + ulp32(m), "more than 1 ulp extra");
    }

    /// The same bound for a given ε: |out[10] − plain[10]| ≥ |m10·ε| with the exact
    /// m10 = −(f+n)/(f−n) (−1 for f = +∞).
    #[test]
    fn epsilon_offset_is_never_below_the_request(s in scene(), eps in decades(-12.0, -1.0),
                                                 toward in any::<bool>()) {
        let eps = if toward { -eps } else { eps };
        let fr = Frustum::new(s.l, s.r, s.b, s.t, s.n, s.f).unwrap();
        let (plain, m) = (frustum(&s)[10], epsilon_matrix(&fr, eps).unwrap()[10]);
        let m10 = if s.f.is_infinite() {
            -Q::one()
        } else {
            -(q(s.f) + q(s.n)) / (q(s.f) - q(s.n))
        };
        let want = m10 * q(eps);
        let got = q32(m) - q32(plain);
        prop_assert_eq!(got.signum(), want.signum());
        prop_assert!(got.abs() >= want.abs(), "lost offset: got {} want {}", got, want);
        prop_assert!(got.abs() <= want.abs() + ulp32(m));
    }

    /// The effective offset grows with δ (toward the camera is up in NDC offset terms: a larger
    /// δ gives a larger out[10]), as the exact request does.
    #[test]
    fn effective_offset_grows_with_delta(s in scene(), (a, ta) in shift(), (b, tb) in shift()) {
        let d1 = if ta { a * -s.pz } else { -a * -s.pz };
        let d2 = if tb { b * -s.pz } else { -b * -s.pz };
        let (lo, hi) = if d1 <= d2 { (d1, d2) } else { (d2, d1) };
        prop_assert!(requested_offset(&s, lo) <= requested_offset(&s, hi));
        prop_assert!(offset_matrix(&s, lo)[10] <= offset_matrix(&s, hi)[10]);
    }

    /// Walker's window depth f(d) = f(d−n)/(d(f−n)) grows with distance, stays in [0, 1], and
    /// is within 4 ulp of the exact value.
    #[test]
    fn window_depth_grows_with_distance((n, f) in planes(), t1 in 0.0..=1.0f64,
                                        t2 in 0.0..=1.0f64) {
        let (d1, d2) = (distance(n, f, t1.min(t2)), distance(n, f, t1.max(t2)));
        let (mut w1, mut w2) = (f64::NAN, f64::NAN);
        prop_assert_eq!(zshift_window_depth(n, f, d1, &mut w1), ZSHIFT_OK);
        prop_assert_eq!(zshift_window_depth(n, f, d2, &mut w2), ZSHIFT_OK);
        prop_assert!(w1 <= w2, "f({}) = {} > f({}) = {}", d1, w1, d2, w2);
        prop_assert!((0.0..=1.0).contains(&w1) && (0.0..=1.0).contains(&w2));
        let exact = |d: f64| {
            let (n, d) = (q(n), q(d));
            if f.is_infinite() { (d.clone() - n) / d } else { q(f) * (d.clone() - n.clone()) / (d * (q(f) - n)) }
        };
        prop_assert!(close(w2, &exact(d2), 4.0 * f64::EPSILON), "f({}) = {}", d2, w2);
    }

    /// The corrected eq. 4.1.9 (seed 002) and Walker's eq. 3 (seed 001) agree: the minimum δ
    /// toward the camera at Pz is the depth step at d = −Pz, bit for bit, and both are within
    /// 8 ulp of the exact q·d²/(b + q·d), b = fn/(f−n), q = 1/(2^m − 1).
    #[test]
    fn min_delta_toward_is_the_depth_step((n, f) in planes(), t in 0.0..=1.0f64,
                                          bits in prop::sample::select(vec![8u32, 16, 24, 32])) {
        let d = distance(n, f, t);
        let (mut toward, mut step) = (f64::NAN, f64::NAN);
        prop_assert_eq!(zshift_min_delta_toward(n, f, bits, -d, &mut toward), ZSHIFT_OK);
        prop_assert_eq!(zshift_depth_resolution(n, f, bits, d, &mut step), ZSHIFT_OK);
        prop_assert_eq!(toward.to_bits(), step.to_bits());
        let qs = Q::new(BigInt::one(), (BigInt::one() << bits) - 1);
        let dd = q(d);
        let b = if f.is_infinite() { q(n) } else { q(f) * q(n) / (q(f) - q(n)) };
        let exact = qs.clone() * dd.clone() * dd.clone() / (b + qs * dd);
        prop_assert!(close(step, &exact, 8.0 * f64::EPSILON), "step {} at d {}", step, d);
    }
}

//! Every f32 matrix element the docs call "the nearest f32" is the nearest f32 of the exact
//! value, and every offset element is rounded outward from it by the least amount.
//!
//! Two kinds of evidence:
//!
//! 1. **Against exact rational arithmetic**, on inputs constructed so that an element lands
//!    within a few f64 ulps of an f32 rounding boundary (the midpoint between two f32 for plain
//!    elements, an f32 itself for offset elements), where random inputs almost never go. The
//!    reference rounds a `BigRational` to f32 by integer arithmetic on its scaled value, an
//!    implementation that shares nothing with the library's.
//! 2. **The fast path against the exact path** (`*_fast` against `*_exact`) on at least 10⁷
//!    log-uniform inputs per builder over wide ranges, stiff ones included (f/n → 1, f/n up to
//!    1e15, n down to 1e-12, f = ∞, Pz at −n and −f, δ tiny and δ near −Pz), in batches on every
//!    core, printing how often the fast path deferred to the exact one.
//!    `ZSHIFT_ROUNDING_SAMPLES=100000000 cargo test --release --test exact_rounding -- --nocapture`
//!    runs 10⁸ per builder.

use std::sync::atomic::{AtomicU64, Ordering};

use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use zshift::clip_offset::{
    ndc_offset_of_shift, offset_projection, offset_projection_exact, offset_projection_fast,
};
use zshift::offset::{
    epsilon_matrix_exact, epsilon_matrix_fast, offset_matrix_exact, offset_matrix_fast,
};
use zshift::precision::DepthMapping;
use zshift::projection::{
    perspective_array, perspective_fast, perspective_frustum, projection, projection_exact,
    projection_fast, tweaked_infinite, tweaked_infinite_exact, tweaked_infinite_fast, ClipDepth,
    MIN_INFINITE_TWEAK,
};
use zshift::{epsilon_matrix, offset_matrix, Frustum};

mod rational;
use rational::{int, pow2, q, q32, Q};

/// `floor(log2 |x|)` for a nonzero rational, from the bit lengths, corrected by comparison.
fn floor_log2(x: &Q) -> i64 {
    let x = x.abs();
    let mut e = x.numer().bits() as i64 - x.denom().bits() as i64;
    while pow2(e) > x {
        e -= 1;
    }
    while pow2(e + 1) <= x {
        e += 1;
    }
    e
}

/// The f32 nearest the rational `x`, ties to even, `±∞` from `2¹²⁸ − 2¹⁰³` on: `|x|` is scaled
/// so that 24 significant bits (fewer among subnormals) are its integer part, rounded half to
/// even as an integer, and scaled back.
fn nearest_f32(x: &Q) -> f32 {
    if x.is_zero() {
        return 0.0;
    }
    let e = (floor_log2(x) - 23).max(-149);
    let y = x.abs() / pow2(e);
    let k = y.floor();
    let frac = &y - &k;
    let half = Q::new(BigInt::one(), BigInt::from(2));
    let odd = (k.to_integer() % BigInt::from(2)) == BigInt::one();
    let k = if frac > half || (frac == half && odd) {
        k + int(1)
    } else {
        k
    };
    let magnitude = k * pow2(e);
    let value = if magnitude >= pow2(128) {
        f32::INFINITY
    } else {
        magnitude.to_f64().expect("in range") as f32
    };
    if x.is_negative() {
        -value
    } else {
        value
    }
}

#[test]
fn the_reference_rounding_is_ieee_round_to_nearest() {
    let spacing = f64::from(f32::EPSILON);
    for (x, want) in [
        (q(1.0) + q(spacing / 2.0), 1.0f32),
        (q(1.0) + q(spacing * 1.5), 1.0 + 2.0 * f32::EPSILON),
        (q(1.0) + q(spacing / 2.0) + pow2(-80), 1.0 + f32::EPSILON),
        (q(-3.0) / int(7), (-3.0f64 / 7.0) as f32),
        (pow2(-150) * int(3), 2.0 * f32::from_bits(1)),
        (pow2(128) - pow2(103), f32::INFINITY),
        (pow2(128) - pow2(103) - pow2(-10), f32::MAX),
    ] {
        assert_eq!(nearest_f32(&x), want, "{x}");
    }
}

// ---- Exact elements ----------------------------------------------------------------------

/// The exact `glFrustum` x/y elements 0, 5, 8, 9 of `(l, r, b, t, n)`.
fn exact_xy(l: f64, r: f64, b: f64, t: f64, n: f64) -> [(usize, Q); 4] {
    let (l, r, b, t, n) = (q(l), q(r), q(b), q(t), q(n));
    let width = &r - &l;
    let height = &t - &b;
    [
        (0, int(2) * &n / &width),
        (5, int(2) * &n / &height),
        (8, (&r + &l) / &width),
        (9, (&t + &b) / &height),
    ]
}

/// The exact depth row `(m10, m14)` of each convention, from its definition.
fn exact_row(n: f64, f: f64, clip: ClipDepth) -> (Q, Q) {
    let n = q(n);
    if f.is_infinite() {
        return match clip {
            ClipDepth::NegOneToOne => (int(-1), int(-2) * n),
            ClipDepth::ZeroToOne => (int(-1), -n),
            ClipDepth::ReversedZeroToOne => (Q::zero(), n),
        };
    }
    let f = q(f);
    let span = &f - &n;
    match clip {
        ClipDepth::NegOneToOne => (-(&f + &n) / &span, int(-2) * &f * &n / &span),
        ClipDepth::ZeroToOne => (-&f / &span, -&f * &n / &span),
        ClipDepth::ReversedZeroToOne => (&n / &span, &f * &n / &span),
    }
}

/// Every element of `m` is the nearest f32 of the exact matrix (elements 10 and 14 given).
fn assert_nearest(m: &[f32; 16], frustum: &Frustum, row: (Q, Q), what: &str) {
    let (l, r, b, t, n, _) = frustum.parameters();
    let mut exact: Vec<(usize, Q)> = exact_xy(l, r, b, t, n).into();
    exact.push((10, row.0));
    exact.push((14, row.1));
    exact.push((11, int(-1)));
    for (i, x) in m.iter().enumerate() {
        let want = exact
            .iter()
            .find(|(j, _)| *j == i)
            .map_or(0.0, |(_, e)| nearest_f32(e));
        assert_eq!(
            *x, want,
            "{what}: element {i} is {x:e}, the nearest f32 is {want:e} ({frustum:?})"
        );
    }
}

/// `x` is the f32 nearest `p + o` rounded away from `p`: `x − p` has the sign of `o`,
/// `|x − p| ≥ |o|`, and the f32 before `x` (toward `p`) falls short (`x = p` when `o = 0`).
fn assert_outward(x: f32, p: f32, o: &Q, what: &str) {
    if o.is_zero() {
        assert_eq!(x, p, "{what}: a zero offset must leave the element");
        return;
    }
    let seen = q32(x) - q32(p);
    assert_eq!(
        seen.is_positive(),
        o.is_positive(),
        "{what}: offset lost or reversed"
    );
    assert!(
        seen.abs() >= o.abs(),
        "{what}: offset short: {x:e} from {p:e}"
    );
    let before = if o.is_positive() {
        x.next_down()
    } else {
        x.next_up()
    };
    let short = q32(before) - q32(p);
    assert!(
        short.abs() < o.abs() || short.is_zero(),
        "{what}: not the least outward f32: {x:e} ({before:e} already holds the offset)"
    );
}

// ---- Inputs constructed near f32 rounding boundaries -----------------------------------------

/// A small deterministic generator (xorshift64*), uniform in [0, 1).
/// The state sits in a `Cell` so that draws can nest in one expression. `constructed` marks
/// an input built near a rounding boundary (counted apart in the bulk tests).
struct Rng {
    state: std::cell::Cell<u64>,
    constructed: std::cell::Cell<bool>,
}

impl Rng {
    fn new(seed: u64) -> Self {
        Self {
            state: std::cell::Cell::new(seed),
            constructed: std::cell::Cell::new(false),
        }
    }
    fn next(&self) -> f64 {
        let mut x = self.state.get();
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.state.set(x);
        (x.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn log_uniform(&self, lo: f64, hi: f64) -> f64 {
        10f64.powf(lo + (hi - lo) * self.next())
    }
    fn sign(&self) -> f64 {
        if self.next() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
    fn pick<T: Copy>(&self, xs: &[T]) -> T {
        xs[(self.next() * xs.len() as f64) as usize % xs.len()]
    }
}

/// A midpoint between two adjacent f32 of magnitude about `scale`, with the sign of `scale`.
fn midpoint_near(rng: &Rng, scale: f64) -> f64 {
    let c = (scale * (1.0 + 0.5 * rng.next())) as f32;
    0.5 * (f64::from(c) + f64::from(c.next_up()))
}

/// `x` moved by `k` f64 ulps.
fn nudge(x: f64, k: i64) -> f64 {
    f64::from_bits((x.to_bits() as i64 + k) as u64)
}

fn nudge_small(rng: &Rng, x: f64) -> f64 {
    nudge(x, (rng.next() * 129.0) as i64 - 64)
}

const CLIPS: [ClipDepth; 3] = [
    ClipDepth::NegOneToOne,
    ClipDepth::ZeroToOne,
    ClipDepth::ReversedZeroToOne,
];

/// A frustum whose element `target` (0, 5, 8, 9, 10 or 14 under `clip`) lies within a few f64
/// ulps of an f32 midpoint: the input that sets it is solved for from the midpoint.
fn frustum_near_boundary(rng: &Rng, target: usize, clip: ClipDepth) -> Frustum {
    let mut n = rng.log_uniform(-6.0, 2.0);
    let mut f = n * rng.log_uniform(0.01, 9.0);
    let mut r = n * rng.log_uniform(-1.0, 1.0);
    let mut l = -r * rng.log_uniform(-0.3, 0.3);
    let mut t = n * rng.log_uniform(-1.0, 1.0);
    let b = -t * rng.log_uniform(-0.3, 0.3);
    match target {
        // 2n/(r − l) = m
        0 => n = nudge_small(rng, midpoint_near(rng, 1.5) * (r - l) / 2.0),
        // 2n/(t − b) = m
        5 => n = nudge_small(rng, midpoint_near(rng, 1.5) * (t - b) / 2.0),
        // (r + l)/(r − l) = m: r = w(1 + m)/2, l = w(m − 1)/2
        8 => {
            let (w, m) = (r - l, midpoint_near(rng, 0.3 * rng.sign()));
            r = nudge_small(rng, w * (1.0 + m) / 2.0);
            l = w * (m - 1.0) / 2.0;
        }
        9 => {
            let (h, m) = (t - b, midpoint_near(rng, 0.3 * rng.sign()));
            t = nudge_small(rng, h * (1.0 + m) / 2.0);
        }
        10 => {
            // Solve the convention's m10(f, n) = m for f.
            f = match clip {
                ClipDepth::NegOneToOne => {
                    let m = midpoint_near(rng, -1.0 - rng.log_uniform(-6.0, 1.0));
                    n * (m - 1.0) / (m + 1.0)
                }
                ClipDepth::ZeroToOne => {
                    let m = midpoint_near(rng, -1.0 - rng.log_uniform(-6.0, 1.0));
                    m * n / (m + 1.0)
                }
                ClipDepth::ReversedZeroToOne => {
                    let m = midpoint_near(rng, rng.log_uniform(-6.0, 3.0));
                    n * (1.0 + m) / m
                }
            };
            f = nudge_small(rng, f);
        }
        _ => {
            // Solve m14(f, n) = m for n at a fixed f.
            f = n * rng.log_uniform(0.01, 9.0);
            let m = midpoint_near(rng, n);
            let a = m.abs();
            n = match clip {
                ClipDepth::NegOneToOne => a * f / (a + 2.0 * f),
                _ => a * f / (a + f),
            };
            n = nudge_small(rng, n);
        }
    }
    Frustum::new(l, r, b, t, n, f.max(n.next_up())).expect("a valid frustum")
}

#[test]
fn every_projection_element_is_the_nearest_f32_near_rounding_boundaries() {
    let rng = Rng::new(0x1234_5678_9abc_def1);
    let mut near = 0usize;
    for i in 0..6000 {
        let clip = CLIPS[i % 3];
        let target = [0, 5, 8, 9, 10, 14][(i / 3) % 6];
        let frustum = frustum_near_boundary(&rng, target, clip);
        let (_, _, _, _, n, f) = frustum.parameters();
        let m = projection(&frustum, clip).expect("in range");
        assert_nearest(&m, &frustum, exact_row(n, f, clip), &format!("{clip:?}"));
        assert_eq!(m, projection_exact(&frustum, clip).unwrap());
        if clip == ClipDepth::NegOneToOne {
            assert_eq!(m, frustum.to_cols_array().unwrap());
            assert_eq!(
                m,
                zshift::frustum(
                    frustum.parameters().0,
                    frustum.parameters().1,
                    frustum.parameters().2,
                    frustum.parameters().3,
                    n,
                    f
                )
                .unwrap()
                .to_cols_array()
            );
        }
        near += usize::from(projection_fast(&frustum, clip).is_none());
    }
    // The construction must reach the boundaries (else this test proves little).
    assert!(
        near > 300,
        "only {near} of 6000 inputs were near a boundary"
    );
    println!("{near} of 6000 constructed frustums sent an element to the exact decision");
}

/// Elements at the edges of the fast test's range (module docs of `zshift::rounding`): tiny
/// values around `2⁻¹⁵⁰` (an f32 boundary between 0 and the least subnormal, where the fast
/// path may only pass values below `2⁻¹⁵¹`), f32 subnormals and the least normals, and values
/// around `2¹²⁷` and the overflow threshold. Each matrix, fast path or not, is the nearest one.
#[test]
fn elements_at_the_edges_of_the_fast_range_are_the_nearest_f32() {
    let mut fast = 0;
    let mut checked = 0;
    let mut near = |frustum: Frustum, clip: ClipDepth| {
        let (_, _, _, _, n, f) = frustum.parameters();
        match projection(&frustum, clip) {
            Ok(m) => {
                assert!(m.iter().all(|x| x.is_finite()), "{m:?} for {frustum:?}");
                assert_nearest(&m, &frustum, exact_row(n, f, clip), "edge");
                checked += 1;
                fast += usize::from(projection_fast(&frustum, clip).is_some());
            }
            Err(e) => assert_eq!(e.kind(), zshift::ErrorKind::Overflow, "{frustum:?}"),
        }
    };
    let ulps = [-40, -16, -15, -1, 0, 1, 15, 16, 40];
    for e in [-153, -152, -151, -150, -149, -148, -127, -126, -125] {
        // Normal f32 midpoints (1 + 2⁻²⁴) and, below 2⁻¹²⁶, subnormal ones (1 + 2⁻²³ at 2⁻¹²⁷).
        let epsilon = f64::from(f32::EPSILON);
        for mantissa in [1.0, 1.5, 1.75, 1.0 + epsilon / 2.0, 1.0 + epsilon] {
            for k in ulps {
                // Reversed Z: elements 10 and 14 are about n; [−1, 1]: element 14 about −2n.
                let n = nudge(mantissa * 2f64.powi(e), k);
                // A window as narrow as n, so that elements 0 and 5 stay normal.
                let w = n * 3.0;
                for f in [1.0, 1e10, f64::INFINITY] {
                    let frustum = Frustum::new(-w, w, -w, w, n, f).expect("valid");
                    near(frustum, ClipDepth::ReversedZeroToOne);
                    near(frustum, ClipDepth::NegOneToOne);
                }
            }
        }
    }
    for e in [125, 126, 127, 128] {
        for mantissa in [1.0, 1.5, 2.0 - f64::from(f32::EPSILON) / 2.0] {
            for k in ulps {
                // Element 0 = 2n/(r − l) about 2^e.
                let width = nudge(2.0 / (mantissa * 2f64.powi(e)), k);
                let frustum = Frustum::new(0.0, width, -1.0, 1.0, 1.0, 2.0).expect("valid");
                near(frustum, ClipDepth::NegOneToOne);
            }
        }
    }
    assert!(
        checked > 1000 && fast > 100,
        "{checked} checked, {fast} fast"
    );
}

#[test]
fn the_double_rounding_example_of_the_issue_is_fixed() {
    let (l, r, b, t, n, f) = (-0.15, 0.15, -1.0, 1.0, 0.15435080230236053, 100.0);
    let m = zshift::frustum(l, r, b, t, n, f).unwrap().to_cols_array();
    let exact = q(2.0) * q(n) / (q(r) - q(l));
    assert_eq!(m[0], nearest_f32(&exact));
    assert_eq!(
        f64::from(m[0]),
        1.029_005_408_287_048_3,
        "the issue's nearest f32"
    );
    assert_ne!(
        m[0],
        (2.0 * n / (r - l)) as f32,
        "the double rounding differs here"
    );
}

#[test]
fn infinite_far_planes_are_exact_and_nearest() {
    let rng = Rng::new(77);
    for i in 0..600 {
        let clip = CLIPS[i % 3];
        let frustum = frustum_near_boundary(&rng, [0, 5, 8, 9][i % 4], clip);
        let (l, r, b, t, n, _) = frustum.parameters();
        let n = if i % 2 == 0 {
            midpoint_near(&rng, n)
        } else {
            n
        };
        let inf = Frustum::new(l, r, b, t, n, f64::INFINITY).unwrap();
        let m = projection(&inf, clip).unwrap();
        assert_nearest(&m, &inf, exact_row(n, f64::INFINITY, clip), "infinite");
    }
}

#[test]
fn tweaked_infinite_elements_are_the_nearest_f32() {
    let rng = Rng::new(99);
    for i in 0..3000 {
        let frustum = frustum_near_boundary(&rng, [0, 5, 8, 9][i % 4], ClipDepth::NegOneToOne);
        let (l, r, b, t, n, _) = frustum.parameters();
        let (tweak, n) = match i % 3 {
            // ε − 1 near a midpoint
            0 => (
                nudge_small(
                    &rng,
                    midpoint_near(&rng, -rng.log_uniform(-3.0, -0.2)) + 1.0,
                ),
                n,
            ),
            // (ε − 2)·n near a midpoint
            1 => {
                let tweak = rng.log_uniform(-9.0, -0.5);
                (
                    tweak,
                    nudge_small(&rng, midpoint_near(&rng, -2.0 * n) / (tweak - 2.0)),
                )
            }
            _ => (rng.pick(&[0.0, MIN_INFINITE_TWEAK, 1e-20, 0.5]), n),
        };
        let frustum = Frustum::new(l, r, b, t, n, f64::INFINITY).unwrap();
        let m = tweaked_infinite(&frustum, tweak).unwrap();
        let row = (q(tweak) - int(1), (q(tweak) - int(2)) * q(n));
        assert_nearest(&m, &frustum, row, "tweaked infinite");
        assert_eq!(m, tweaked_infinite_exact(&frustum, tweak).unwrap());
    }
}

#[test]
fn perspective_elements_are_the_nearest_f32_of_its_frustum() {
    let rng = Rng::new(5);
    for i in 0..3000 {
        let n = rng.log_uniform(-4.0, 1.0);
        let f = if i % 5 == 0 {
            f64::INFINITY
        } else {
            n * rng.log_uniform(0.01, 8.0)
        };
        // m5 = cot(fovy/2) near a midpoint; m0 = m5/aspect near one.
        let m5 = midpoint_near(&rng, rng.log_uniform(-0.5, 1.0));
        let fovy = 2.0 * (1.0 / m5).atan().to_degrees();
        let aspect = if i % 2 == 0 {
            m5 / midpoint_near(&rng, m5 / rng.log_uniform(-0.3, 0.5))
        } else {
            rng.log_uniform(-0.3, 0.5)
        };
        let m = perspective_array(fovy, aspect, n, f).unwrap();
        let frustum = perspective_frustum(fovy, aspect, n, f).unwrap();
        assert_nearest(
            &m,
            &frustum,
            exact_row(n, f, ClipDepth::NegOneToOne),
            "perspective",
        );
        assert_eq!(
            m,
            zshift::projection::perspective(fovy, aspect, n, f)
                .unwrap()
                .to_cols_array()
        );
    }
}

/// Exact Lengyel offset `o = m10·ε = 2fnδ / ((f − n)·Pz·(Pz + δ))` (`2nδ / (Pz·(Pz + δ))` at
/// `f = ∞`).
fn exact_shift_offset(n: f64, f: f64, delta: f64, pz: f64) -> Q {
    let (n, delta, pz) = (q(n), q(delta), q(pz));
    let depth = &pz * (&pz + &delta);
    if f.is_infinite() {
        return int(2) * n * delta / depth;
    }
    let f = q(f);
    int(2) * &f * &n * delta / ((&f - &n) * depth)
}

/// δ such that the offset o lands within a few ulps of an f32 above or below `p`: from
/// `o·Pz·(Pz + δ) = Aδ` with `A = 2fn/(f − n)` (or `2n`), `δ = o·Pz² / (A − o·Pz)`.
fn delta_for_landing(rng: &Rng, p: f32, n: f64, f: f64, pz: f64) -> f64 {
    let steps = rng.pick(&[1.0, 2.0, 3.0, 17.0, 1000.0]) * rng.sign();
    let spacing = f64::from(p.next_up()) - f64::from(p);
    let o = steps * spacing;
    let a = if f.is_infinite() {
        2.0 * n
    } else {
        2.0 * f * n / (f - n)
    };
    nudge_small(rng, o * pz * pz / (a - o * pz))
}

#[test]
fn offset_elements_round_outward_by_the_least_f32_near_boundaries() {
    let rng = Rng::new(4242);
    let mut checked = 0;
    for i in 0..6000 {
        let frustum =
            frustum_near_boundary(&rng, [0, 5, 8, 9, 10, 14][i % 6], ClipDepth::NegOneToOne);
        let (l, r, b, t, n, f) = frustum.parameters();
        let f = if i % 7 == 0 { f64::INFINITY } else { f };
        let frustum = Frustum::new(l, r, b, t, n, f).unwrap();
        let far = if f.is_infinite() { n * 1e6 } else { f };
        let pz = -rng.pick(&[n, far, n * (far / n).powf(rng.next())]);
        let plain = projection(&frustum, ClipDepth::NegOneToOne).unwrap();
        let delta = delta_for_landing(&rng, plain[10], n, f, pz);
        if pz + delta >= 0.0 || !delta.is_finite() {
            continue;
        }
        let Ok(m) = offset_matrix(&frustum, delta, pz) else {
            continue;
        };
        let (_, _, _, _, n, f) = frustum.parameters();
        let mut row = exact_row(n, f, ClipDepth::NegOneToOne);
        assert_outward(
            m[10],
            nearest_f32(&row.0),
            &exact_shift_offset(n, f, delta, pz),
            "offset_matrix",
        );
        row.0 = q32(m[10]);
        assert_nearest(
            &m,
            &frustum,
            row.clone(),
            "offset_matrix untouched elements",
        );
        assert_eq!(m, offset_matrix_exact(&frustum, delta, pz).unwrap());
        assert_eq!(
            m,
            zshift::load_offset_matrix(l, r, b, t, n, f, delta, pz)
                .unwrap()
                .to_cols_array()
        );
        // The same offset as an ε: o = m10·ε, ε = o / m10 rounded to f64.
        let eps = (exact_shift_offset(n, f, delta, pz) / exact_row(n, f, ClipDepth::NegOneToOne).0)
            .to_f64()
            .unwrap();
        let e = epsilon_matrix(&frustum, eps).unwrap();
        let o = exact_row(n, f, ClipDepth::NegOneToOne).0 * q(eps);
        assert_outward(e[10], plain[10], &o, "epsilon_matrix");
        assert_eq!(e, epsilon_matrix_exact(&frustum, eps).unwrap());
        checked += 1;
    }
    assert!(checked > 4000, "only {checked} offset cases were valid");
}

#[test]
fn offset_projections_keep_nearest_elements_and_outward_offsets() {
    let rng = Rng::new(31337);
    let mut checked = 0;
    for i in 0..3000 {
        let clip = CLIPS[i % 3];
        let frustum = frustum_near_boundary(&rng, [0, 5, 8, 9, 10, 14][(i / 3) % 6], clip);
        let (_, _, _, _, n, f) = frustum.parameters();
        let pz = -rng.pick(&[n, f, n * (f / n).powf(rng.next())]);
        let d = -pz;
        let delta = d * rng.sign() * rng.log_uniform(-12.0, -0.5);
        let Ok(m) = offset_projection(&frustum, clip, delta, pz) else {
            continue; // the shifted point left [n, f]
        };
        checked += 1;
        let mut row = exact_row(n, f, clip);
        let plain = projection(&frustum, clip).unwrap();
        if clip == ClipDepth::ReversedZeroToOne {
            // ε = δ/(d − δ) in f64 (the documented input of the relative offset), o = p14·ε.
            let eps = delta / (d - delta);
            assert_outward(
                m[14],
                plain[14],
                &(q32(plain[14]) * q(eps)),
                "relative offset",
            );
            row.1 = q32(m[14]);
        } else {
            // The constant NDC offset c (an f64 input of the rounding), element 10 lowered by c.
            let mapping = DepthMapping::projection(n, f, clip).unwrap();
            let c = ndc_offset_of_shift(&mapping, delta, pz).unwrap();
            assert_eq!(c < 0.0, delta > 0.0, "toward the camera lowers NDC depth");
            assert_outward(m[10], plain[10], &q(-c), "constant NDC offset");
            row.0 = q32(m[10]);
        }
        assert_nearest(
            &m,
            &frustum,
            row,
            &format!("offset {clip:?} untouched elements"),
        );
        assert_eq!(
            m,
            offset_projection_exact(&frustum, clip, delta, pz).unwrap()
        );
    }
    assert!(
        checked > 2000,
        "only {checked} offset projections were valid"
    );
}

// ---- The fast path against the exact path, in bulk ------------------------------------------

/// Inputs per builder: `ZSHIFT_ROUNDING_SAMPLES` (default 10⁷).
fn samples() -> u64 {
    std::env::var("ZSHIFT_ROUNDING_SAMPLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000_000)
}

/// Wide, log-uniform planes, stiff ones included: f/n → 1, f/n up to 1e15, n down to 1e-12,
/// f = ∞; asymmetric or symmetric extents.
fn wide_frustum(rng: &Rng) -> Frustum {
    let n = rng.log_uniform(-12.0, 4.0);
    let f = match (rng.next() * 4.0) as u32 {
        0 => n * (1.0 + rng.log_uniform(-12.0, 0.0)),
        1 => f64::INFINITY,
        _ => n * rng.log_uniform(0.0, 15.0),
    };
    let r = n * rng.log_uniform(-3.0, 3.0);
    let t = n * rng.log_uniform(-3.0, 3.0);
    let (l, b) = if rng.next() < 0.5 {
        (-r, -t)
    } else {
        (r * (rng.next() * 2.0 - 1.2), t * (rng.next() * 2.0 - 1.2))
    };
    let f = if f > n { f } else { n.next_up() };
    Frustum::new(l, r, b, t, n, f).expect("valid")
}

/// A [`wide_frustum`], or (one time in four) one with an element constructed within a few
/// dozen f64 ulps of an f32 rounding boundary, so that the fast path's slack is exercised from
/// both sides.
fn wide_or_near_boundary(rng: &Rng, clip: ClipDepth) -> Frustum {
    if rng.next() < 0.25 {
        rng.constructed.set(true);
        frustum_near_boundary(rng, rng.pick(&[0, 5, 8, 9, 10, 14]), clip)
    } else {
        wide_frustum(rng)
    }
}

/// An eye depth in `[−f, −n]` (up to `n·1e15` when `f = ∞`), at either plane now and then,
/// and a shift δ: tiny of either sign, ordinary, or close to `−Pz` (the point nearly at the eye).
fn wide_shift(rng: &Rng, n: f64, f: f64) -> (f64, f64) {
    let far = if f.is_infinite() { n * 1e15 } else { f };
    let pz = match (rng.next() * 8.0) as u32 {
        0 => -n,
        1 => -far,
        _ => -n * (far / n).powf(rng.next()),
    };
    let d = -pz;
    let delta = match (rng.next() * 4.0) as u32 {
        0 => d * rng.sign() * rng.log_uniform(-15.0, -6.0),
        1 => d * (1.0 - rng.log_uniform(-12.0, -1.0)),
        _ => d * rng.sign() * rng.log_uniform(-6.0, -0.5),
    };
    (delta, pz)
}

/// What one bulk comparison found.
#[derive(Clone, Copy, PartialEq)]
enum Outcome {
    /// The fast path decided, and agreed with the exact path.
    Fast,
    /// The fast path deferred to the exact path (a valid input).
    Deferred,
    /// The input is invalid (both paths refuse it).
    Refused,
}

/// Runs `check` on `samples()` inputs split over the cores, and prints how often the fast
/// path deferred to the exact one.
fn in_batches(name: &str, check: impl Fn(&Rng) -> Outcome + Sync) {
    let total = samples();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    // [random, constructed] × [valid, deferred]
    let counts: [[AtomicU64; 2]; 2] = Default::default();
    std::thread::scope(|scope| {
        for k in 0..threads {
            let (check, counts) = (&check, &counts);
            scope.spawn(move || {
                let rng = Rng::new(0x9e37_79b9_7f4a_7c15 ^ (k + 1).wrapping_mul(0x1000_0000_01b3));
                let mut local = [[0u64; 2]; 2];
                for _ in (k..total).step_by(threads as usize) {
                    rng.constructed.set(false);
                    let outcome = check(&rng);
                    let kind = usize::from(rng.constructed.get());
                    local[kind][0] += u64::from(outcome != Outcome::Refused);
                    local[kind][1] += u64::from(outcome == Outcome::Deferred);
                }
                for (c, l) in counts.iter().flatten().zip(local.iter().flatten()) {
                    c.fetch_add(*l, Ordering::Relaxed);
                }
            });
        }
    });
    let [[random, random_deferred], [built, built_deferred]] =
        counts.map(|kind| kind.map(AtomicU64::into_inner));
    let rate = |d: u64, v: u64| d as f64 / v.max(1) as f64;
    println!(
        "{name}: {} valid inputs of {total}, 0 mismatches. The fast path deferred to the exact \
         path on {random_deferred} of {random} log-uniform inputs ({:.1e}) and on \
         {built_deferred} of {built} built near a rounding boundary ({:.2})",
        random + built,
        rate(random_deferred, random),
        rate(built_deferred, built),
    );
    assert!(random + built >= total / 2, "{name}: too few valid inputs");
    // The fast path must decide nearly every input away from boundaries (the bound predicts
    // about 1e-7 per element); more means it has stopped doing its job.
    assert!(
        rate(random_deferred, random) < 1e-5,
        "{name}: the fast path deferred too often"
    );
}

/// Compares a fast result with the exact one.
fn agree<E>(
    fast: Option<[f32; 16]>,
    exact: Result<[f32; 16], E>,
    what: &dyn Fn() -> String,
) -> Outcome {
    match (fast, exact) {
        (Some(m), Ok(e)) => {
            assert_eq!(m, e, "fast and exact paths differ: {}", what());
            Outcome::Fast
        }
        (None, Ok(_)) => Outcome::Deferred,
        (None, Err(_)) => Outcome::Refused,
        (Some(_), Err(_)) => panic!(
            "the fast path accepted what the exact path refuses: {}",
            what()
        ),
    }
}

#[test]
fn fast_projection_matches_the_exact_path_in_bulk() {
    in_batches("projection (3 conventions)", |rng| {
        let clip = rng.pick(&CLIPS);
        let frustum = wide_or_near_boundary(rng, clip);
        let exact = projection_exact(&frustum, clip);
        agree(projection_fast(&frustum, clip), exact, &|| {
            format!("{frustum:?} {clip:?}")
        })
    });
}

#[test]
fn fast_tweaked_infinite_and_perspective_match_the_exact_path_in_bulk() {
    in_batches("tweaked_infinite", |rng| {
        let frustum = wide_or_near_boundary(rng, ClipDepth::NegOneToOne);
        let tweak = rng.pick(&[0.0, MIN_INFINITE_TWEAK, rng.log_uniform(-15.0, -0.1)]);
        let exact = tweaked_infinite_exact(&frustum, tweak);
        agree(tweaked_infinite_fast(&frustum, tweak), exact, &|| {
            format!("{frustum:?} {tweak}")
        })
    });
    in_batches("perspective", |rng| {
        let n = rng.log_uniform(-12.0, 4.0);
        let f = match (rng.next() * 4.0) as u32 {
            0 => f64::INFINITY,
            1 => n * (1.0 + rng.log_uniform(-12.0, 0.0)),
            _ => n * rng.log_uniform(0.0, 15.0),
        };
        let f = if f > n { f } else { n.next_up() };
        let (fovy, aspect) = (0.01 + 179.98 * rng.next(), rng.log_uniform(-2.0, 2.0));
        let frustum = perspective_frustum(fovy, aspect, n, f).unwrap();
        let exact = projection_exact(&frustum, ClipDepth::NegOneToOne);
        agree(perspective_fast(fovy, aspect, n, f), exact, &|| {
            format!("{fovy} {aspect} {n} {f}")
        })
    });
}

#[test]
fn fast_offset_matrices_match_the_exact_path_in_bulk() {
    in_batches("offset_matrix (load_offset_matrix)", |rng| {
        let frustum = wide_or_near_boundary(rng, ClipDepth::NegOneToOne);
        let (_, _, _, _, n, f) = frustum.parameters();
        let (mut delta, pz) = wide_shift(rng, n, f);
        if rng.next() < 0.25 {
            // An offset landing near an f32 (the outward rounding's boundaries).
            let plain = projection_exact(&frustum, ClipDepth::NegOneToOne).unwrap();
            delta = delta_for_landing(rng, plain[10], n, f, pz);
            rng.constructed.set(true);
        }
        let exact = offset_matrix_exact(&frustum, delta, pz);
        let what = || format!("{frustum:?} {delta} {pz}");
        agree(offset_matrix_fast(&frustum, delta, pz), exact, &what)
    });
    in_batches("epsilon_matrix", |rng| {
        let frustum = wide_frustum(rng);
        let mut eps = rng.sign() * rng.log_uniform(-15.0, -0.5);
        if rng.next() < 0.25 {
            // An offset m10·ε landing within a few dozen f64 ulps of an f32 step from plain.
            let plain = projection_exact(&frustum, ClipDepth::NegOneToOne).unwrap()[10];
            let steps = rng.pick(&[1.0, 2.0, 3.0, 17.0, 1000.0]) * rng.sign();
            let spacing = f64::from(plain.next_up()) - f64::from(plain);
            let (_, _, _, _, n, f) = frustum.parameters();
            let m10 = exact_row(n, f, ClipDepth::NegOneToOne).0.to_f64().unwrap();
            eps = nudge_small(rng, steps * spacing / m10);
            rng.constructed.set(true);
        }
        let exact = epsilon_matrix_exact(&frustum, eps);
        agree(epsilon_matrix_fast(&frustum, eps), exact, &|| {
            format!("{frustum:?} {eps}")
        })
    });
}

#[test]
fn fast_offset_projections_match_the_exact_path_in_bulk() {
    in_batches("offset_projection (3 conventions)", |rng| {
        let frustum = wide_frustum(rng);
        let (_, _, _, _, n, f) = frustum.parameters();
        let (delta, pz) = wide_shift(rng, n, f);
        let clip = rng.pick(&CLIPS);
        let exact = offset_projection_exact(&frustum, clip, delta, pz);
        let what = || format!("{frustum:?} {clip:?} {delta} {pz}");
        agree(
            offset_projection_fast(&frustum, clip, delta, pz),
            exact,
            &what,
        )
    });
}

/// The sides `(l, r, n, f)` of a `glOrtho` box with one element solved for from the f32
/// midpoint `m`, within a few dozen f64 ulps of it: `which` 0, element 0 = |m| (`r` from `l`);
/// 1, element 12 = m over the width `width()`; 2, element 10 = m (`f` from `n`); 3, element 14
/// = m over the depth span `span()` (NegOneToOne: −(f + n)/span; else −n/span or f/span).
fn ortho_sides_near(
    rng: &Rng,
    clip: ClipDepth,
    which: u32,
    m: f64,
    (mut l, mut r, mut n, mut f): (f64, f64, f64, f64),
    width: impl FnOnce() -> f64,
    span: impl FnOnce() -> f64,
) -> (f64, f64, f64, f64) {
    match which {
        0 => r = l + nudge_small(rng, 2.0 / m.abs()),
        1 => {
            // −(r + l)/(r − l) = m with r − l = w
            let w = width();
            r = nudge_small(rng, (w - m * w) / 2.0);
            l = r - w;
        }
        2 => {
            let k = match clip {
                ClipDepth::NegOneToOne => -2.0,
                ClipDepth::ZeroToOne => -1.0,
                ClipDepth::ReversedZeroToOne => 1.0,
            };
            f = n + nudge_small(rng, (k / m).abs());
        }
        _ => {
            let span = span();
            match clip {
                ClipDepth::NegOneToOne => {
                    f = nudge_small(rng, (span - m * span) / 2.0);
                    n = f - span;
                }
                ClipDepth::ZeroToOne => {
                    n = nudge_small(rng, -m * span);
                    f = n + span;
                }
                ClipDepth::ReversedZeroToOne => {
                    f = nudge_small(rng, m * span);
                    n = f - span;
                }
            }
        }
    }
    (l, r, n, f)
}

/// A `glOrtho` box over wide ranges (extents from 1e-4 to 1e4, centred or not, near planes of
/// either sign), or (one time in four) one whose element 0, 12, 10 or 14 is solved for from an
/// f32 midpoint, within a few dozen f64 ulps of it.
fn wide_or_near_boundary_box(rng: &Rng, clip: ClipDepth) -> zshift::orthographic::Ortho {
    let scale = rng.log_uniform(-4.0, 4.0);
    let (mut r, t) = (
        scale * rng.log_uniform(-1.0, 1.0),
        scale * rng.log_uniform(-1.0, 1.0),
    );
    let (mut l, b) = if rng.next() < 0.5 {
        (-r, -t)
    } else {
        (r * (rng.next() * 2.0 - 1.2), t * (rng.next() * 2.0 - 1.2))
    };
    let mut n = rng.sign() * rng.log_uniform(-6.0, 3.0);
    let mut f = n + rng.log_uniform(-9.0, 6.0);
    if rng.next() < 0.25 {
        rng.constructed.set(true);
        let m = midpoint_near(rng, rng.sign() * rng.log_uniform(-4.0, 4.0));
        let which = (rng.next() * 4.0) as u32;
        let span = f - n;
        (l, r, n, f) = ortho_sides_near(rng, clip, which, m, (l, r, n, f), || scale, || span);
    }
    if r == l {
        r = l + scale;
    }
    if f <= n || f.is_nan() {
        f = n + 1.0;
    }
    zshift::orthographic::Ortho::new(l, r, b, t, n, f).expect("a valid box")
}

#[test]
fn fast_ortho_matches_the_exact_path_in_bulk() {
    use zshift::orthographic::{offset_ortho_exact, offset_ortho_fast, ortho_exact, ortho_fast};
    in_batches("ortho (3 conventions)", |rng| {
        let clip = rng.pick(&CLIPS);
        let o = wide_or_near_boundary_box(rng, clip);
        agree(ortho_fast(&o, clip), ortho_exact(&o, clip), &|| {
            format!("{o:?} {clip:?}")
        })
    });
    in_batches("offset_ortho (3 conventions)", |rng| {
        let clip = rng.pick(&CLIPS);
        let o = wide_or_near_boundary_box(rng, clip);
        let delta = rng.sign() * rng.log_uniform(-9.0, 0.0) * (o.far() - o.near());
        let exact = offset_ortho_exact(&o, clip, delta);
        agree(offset_ortho_fast(&o, clip, delta), exact, &|| {
            format!("{o:?} {clip:?} {delta}")
        })
    });
}

/// An engine's matrix: zshift's own projection of a wide frustum under `clip` (now and then
/// left-handed: column 2 negated, as `lh` builders give it), or one time in four a `glOrtho`
/// matrix of a wide box.
fn engine_matrix(rng: &Rng, clip: ClipDepth) -> Option<[f32; 16]> {
    let mut m = if rng.next() < 0.25 {
        zshift::orthographic::ortho(&wide_or_near_boundary_box(rng, clip), clip).ok()?
    } else {
        projection(&wide_frustum(rng), clip).ok()?
    };
    if m[15] == 0.0 && rng.next() < 0.5 {
        for x in &mut m[8..12] {
            *x = -*x;
        }
    }
    rng.constructed.set(false); // a box near a boundary says nothing of the offset element
    Some(m)
}

/// The matrix-in calls (`zshift_offset_matrix`, `zshift_offset_matrix_ndc`) on engine matrices:
/// their fast paths against the double-double paths, shifts from 1e-9 of the distance to
/// nearly all of it, toward and away.
#[test]
fn fast_matrix_in_offsets_match_the_exact_path_in_bulk() {
    use zshift::matrix_in::{offset_ndc, offset_ndc_fast, offset_shift, offset_shift_fast};
    in_batches("offset_shift (engine matrices, 3 conventions)", |rng| {
        let clip = rng.pick(&CLIPS);
        let Some(m) = engine_matrix(rng, clip) else {
            return Outcome::Refused;
        };
        let d = rng.log_uniform(-6.0, 6.0);
        let delta = match (rng.next() * 4.0) as u32 {
            0 => d * (1.0 - rng.log_uniform(-12.0, -1.0)),
            _ => d * rng.sign() * rng.log_uniform(-9.0, -0.3),
        };
        let exact = offset_shift(&m, clip, delta, d);
        agree(offset_shift_fast(&m, clip, delta, d), exact, &|| {
            format!("{m:?} {clip:?} {delta} {d}")
        })
    });
    in_batches("offset_ndc (engine matrices, 3 conventions)", |rng| {
        let clip = rng.pick(&CLIPS);
        let Some(m) = engine_matrix(rng, clip) else {
            return Outcome::Refused;
        };
        let c = rng.sign() * rng.log_uniform(-12.0, -1.0);
        agree(
            offset_ndc_fast(&m, clip, c),
            offset_ndc(&m, clip, c),
            &|| format!("{m:?} {clip:?} {c}"),
        )
    });
}

// ---- The C entry points take the same fast path ---------------------------------------------

/// The C ABI's builders (their own fast path, one store) give the Rust API's matrices, bit for
/// bit, near rounding boundaries and away from them; on bad input they leave the output alone.
#[test]
fn c_entry_points_write_the_rust_matrices() {
    use zshift::ffi::{
        zshift_frustum, zshift_load_offset_matrix, zshift_perspective, zshift_projection,
        zshift_tweaked_infinite, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
        ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_ERR_DOMAIN, ZSHIFT_OK,
    };
    let c_clips = [
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        ZSHIFT_CLIP_ZERO_TO_ONE,
        ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
    ];
    let rng = Rng::new(2718);
    let bits = |m: &[f32; 16]| m.map(f32::to_bits);
    for i in 0..6000 {
        let k = i % 3;
        let frustum = wide_or_near_boundary(&rng, CLIPS[k]);
        let (l, r, b, t, n, f) = frustum.parameters();
        let mut out = [f32::NAN; 16];
        assert_eq!(
            zshift_frustum(l, r, b, t, n, f, out.as_mut_ptr()),
            ZSHIFT_OK
        );
        assert_eq!(bits(&out), bits(&frustum.to_cols_array().unwrap()));
        assert_eq!(
            zshift_projection(l, r, b, t, n, f, c_clips[k], out.as_mut_ptr()),
            ZSHIFT_OK
        );
        assert_eq!(bits(&out), bits(&projection(&frustum, CLIPS[k]).unwrap()));
        let tweak = rng.pick(&[0.0, MIN_INFINITE_TWEAK, rng.log_uniform(-9.0, -1.0)]);
        assert_eq!(
            zshift_tweaked_infinite(l, r, b, t, n, tweak, out.as_mut_ptr()),
            ZSHIFT_OK
        );
        assert_eq!(
            bits(&out),
            bits(&tweaked_infinite(&frustum, tweak).unwrap())
        );
        let (delta, pz) = wide_shift(&rng, n, f);
        let status = zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz, out.as_mut_ptr());
        match offset_matrix(&frustum, delta, pz) {
            Ok(m) => assert_eq!((status, bits(&out)), (ZSHIFT_OK, bits(&m))),
            Err(_) => assert_ne!(status, ZSHIFT_OK),
        }
        let (fovy, aspect) = (0.5 + 179.0 * rng.next(), rng.log_uniform(-1.0, 1.0));
        assert_eq!(
            zshift_perspective(fovy, aspect, n, f, out.as_mut_ptr()),
            ZSHIFT_OK
        );
        assert_eq!(
            bits(&out),
            bits(&perspective_array(fovy, aspect, n, f).unwrap())
        );
    }
    // Refused input: the status says why and the output is untouched.
    let mut out = [7.0f32; 16];
    assert_eq!(
        zshift_frustum(1.0, 1.0, -1.0, 1.0, 0.1, 10.0, out.as_mut_ptr()),
        ZSHIFT_ERR_DOMAIN
    );
    assert_eq!(out, [7.0; 16]);
    let status =
        zshift_load_offset_matrix(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0, 1.0, -0.5, out.as_mut_ptr());
    assert_eq!((status, out), (ZSHIFT_ERR_DOMAIN, [7.0; 16]));
}

/// Extreme magnitudes (1e-300 to 1e300, subnormal f32 results, overflow) take the exact path,
/// end at once, and round to the nearest f32 or refuse with an overflow.
#[test]
fn extreme_frustums_round_exactly_or_overflow() {
    let scales = [
        1e-300, 1e-200, 1e-45, 1e-40, 1e-20, 1.0, 1e20, 1e38, 1e39, 1e200, 1e300,
    ];
    let rng = Rng::new(4711);
    let mut built = 0;
    for &sn in &scales {
        for &sx in &scales {
            for clip in CLIPS {
                let n = sn * (1.0 + rng.next());
                let f = if rng.next() < 0.3 {
                    f64::INFINITY
                } else {
                    n * (1.0 + 1e3 * rng.next())
                };
                let r = sx * (1.0 + rng.next());
                let l = -r * rng.next();
                let Ok(frustum) = Frustum::new(l, r, -r, r * 0.5, n, f) else {
                    continue;
                };
                let row = exact_row(n, f, clip);
                match projection(&frustum, clip) {
                    Ok(m) => {
                        assert_nearest(&m, &frustum, row, "extreme");
                        built += 1;
                    }
                    Err(e) => {
                        assert_eq!(e.kind(), zshift::ErrorKind::Overflow, "{frustum:?}");
                        let (_, _, _, _, n, _) = frustum.parameters();
                        let mut exact: Vec<Q> = exact_xy(l, r, -r, r * 0.5, n).map(|x| x.1).into();
                        exact.extend([row.0, row.1]);
                        assert!(
                            exact.iter().any(|x| nearest_f32(x).is_infinite()),
                            "refused without an element beyond f32: {frustum:?} {clip:?}"
                        );
                    }
                }
            }
        }
    }
    assert!(built > 100, "only {built} extreme matrices were in range");
}

/// `glOrtho`'s elements as exact rationals: (index, value) for 0, 5, 10, 12, 13, 14.
fn exact_ortho(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64, clip: ClipDepth) -> Vec<(usize, Q)> {
    let (w, h, span) = (q(r) - q(l), q(t) - q(b), q(f) - q(n));
    let (m10, m14) = match clip {
        ClipDepth::NegOneToOne => (-int(2) / &span, -(q(f) + q(n)) / &span),
        ClipDepth::ZeroToOne => (-int(1) / &span, -q(n) / &span),
        ClipDepth::ReversedZeroToOne => (int(1) / &span, q(f) / &span),
    };
    vec![
        (0, int(2) / &w),
        (5, int(2) / &h),
        (10, m10),
        (12, -(q(r) + q(l)) / &w),
        (13, -(q(t) + q(b)) / &h),
        (14, m14),
    ]
}

/// Every `glOrtho` element is the nearest f32 of its exact value, on boxes built so that one
/// element (0, 12, 10 or 14) lies within a few f64 ulps of an f32 midpoint. Rounding the f64
/// element instead (what the builder did before) is wrong on some of them, so the inputs do
/// reach the boundaries.
#[test]
fn every_ortho_element_is_the_nearest_f32_near_rounding_boundaries() {
    use zshift::orthographic::{ortho, ortho_f64, Ortho};
    let rng = Rng::new(0x0f1e_2d3c_4b5a_6978);
    let mut double_rounding_wrong = 0usize;
    for i in 0..4000 {
        let clip = CLIPS[i % 3];
        let scale = 10f64.powf(rng.next() * 8.0 - 4.0);
        let m = midpoint_near(&rng, if i % 2 == 0 { scale } else { -scale });
        let (mut l, mut r, mut n, mut f) =
            (-1.0, 1.0 + rng.next(), -rng.next(), 10.0 * rng.next() + 0.5);
        let width_and_span = || 1.0 + rng.next();
        (l, r, n, f) = ortho_sides_near(
            &rng,
            clip,
            ((i / 3) % 4) as u32,
            m,
            (l, r, n, f),
            width_and_span,
            width_and_span,
        );
        let (b, t) = (-0.75, 0.5 + rng.next());
        let o = Ortho::new(l, r, b, t, n, f).expect("valid box");
        let got = ortho(&o, clip).expect("in range");
        let rounded_twice = ortho_f64(&o, clip).map(|x| x as f32);
        for (index, value) in exact_ortho(l, r, b, t, n, f, clip) {
            let want = nearest_f32(&value);
            assert_eq!(
                got[index].to_bits(),
                want.to_bits(),
                "ortho({l:e}, {r:e}, {b:e}, {t:e}, {n:e}, {f:e}, {clip:?}) element {index}: {} is not the nearest f32 {}",
                got[index],
                want
            );
            double_rounding_wrong += usize::from(rounded_twice[index].to_bits() != want.to_bits());
        }
        // The offset box: element 14 moved by m10·δ, rounded outward; the rest untouched.
        let delta = rng.sign() * 10f64.powf(-9.0 * rng.next()) * (f - n);
        let moved = zshift::orthographic::offset_ortho(&o, clip, delta).expect("in range");
        assert_outward(
            moved[14],
            got[14],
            &(q32(got[10]) * q(delta)),
            "offset_ortho",
        );
        assert_eq!(moved.map(f32::to_bits)[..14], got.map(f32::to_bits)[..14]);
    }
    assert!(
        double_rounding_wrong > 10,
        "only {double_rounding_wrong} elements were rounded wrongly by double rounding"
    );
    println!("{double_rounding_wrong} elements of 4000 boxes differ under double rounding");
}

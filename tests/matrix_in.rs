//! `zshift::matrix_in` on matrices built by glam (the Rust engine's own builders) and by the
//! engines' formulas (tweaked infinite, reversed finite, orthographic in every convention):
//! the output differs from the input only in the offset element, by at least the offset asked
//! and at most one f32 ulp of that element more. References are exact rational arithmetic on
//! the matrix's own f32 elements, never zshift's numbers.

use glam::camera::{lh::proj as lh, rh::proj as rh};
use glam::Mat4;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use zshift::matrix_in::{offset_ndc, offset_shift, recognize, Shape};
use zshift::projection::ClipDepth;
use zshift::ErrorKind;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// One f32 ulp of `x` (the gap to the next float away from zero).
fn ulp(x: f32) -> Q {
    let a = x.abs();
    q(f64::from(f32::from_bits(a.to_bits() + 1)) - f64::from(a))
}

/// A matrix an engine draws its base with, and how it was built.
struct Case {
    name: &'static str,
    m: [f32; 16],
    clip: ClipDepth,
    /// The near and far planes it was built with (far may be +∞).
    planes: (f64, f64),
    ortho: bool,
}

const FOVY: f32 = std::f32::consts::FRAC_PI_3; // 60°
const ASPECT: f32 = 16.0 / 9.0;

fn cases() -> Vec<Case> {
    let (n, f) = (0.1f32, 1000.0f32);
    let frustum = zshift::Frustum::new(-0.16, 0.16, -0.09, 0.09, 0.1, f64::INFINITY).unwrap();
    let tweaked = zshift::projection::tweaked_infinite(&frustum, 2.0f64.powi(-22)).unwrap();
    let reversed_finite = zshift::projection::projection(
        &zshift::Frustum::new(-0.16, 0.16, -0.09, 0.09, 0.1, 1000.0).unwrap(),
        ClipDepth::ReversedZeroToOne,
    )
    .unwrap();
    let c = |name, m: Mat4, clip, planes, ortho| Case {
        name,
        m: m.to_cols_array(),
        clip,
        planes,
        ortho,
    };
    let (n64, f64_) = (f64::from(n), f64::from(f));
    vec![
        c(
            "glam rh opengl::perspective ([-1, 1])",
            rh::opengl::perspective(FOVY, ASPECT, n, f),
            ClipDepth::NegOneToOne,
            (n64, f64_),
            false,
        ),
        c(
            "glam rh directx::perspective ([0, 1])",
            rh::directx::perspective(FOVY, ASPECT, n, f),
            ClipDepth::ZeroToOne,
            (n64, f64_),
            false,
        ),
        c(
            "glam lh directx::perspective ([0, 1], left-handed)",
            lh::directx::perspective(FOVY, ASPECT, n, f),
            ClipDepth::ZeroToOne,
            (n64, f64_),
            false,
        ),
        c(
            "glam rh vulkan::perspective ([0, 1], y flipped)",
            rh::vulkan::perspective(FOVY, ASPECT, n, f),
            ClipDepth::ZeroToOne,
            (n64, f64_),
            false,
        ),
        c(
            "glam rh directx::perspective_infinite ([0, 1], infinite)",
            rh::directx::perspective_infinite(FOVY, ASPECT, n),
            ClipDepth::ZeroToOne,
            (n64, f64::INFINITY),
            false,
        ),
        c(
            "glam rh directx::perspective_infinite_reverse (reversed, infinite)",
            rh::directx::perspective_infinite_reverse(FOVY, ASPECT, n),
            ClipDepth::ReversedZeroToOne,
            (n64, f64::INFINITY),
            false,
        ),
        c(
            "glam rh directx::perspective with near and far swapped (reversed, finite)",
            rh::directx::perspective(FOVY, ASPECT, f, n),
            ClipDepth::ReversedZeroToOne,
            (n64, f64_),
            false,
        ),
        c(
            "reversed finite (engine formula)",
            Mat4::from_cols_array(&reversed_finite),
            ClipDepth::ReversedZeroToOne,
            (n64, f64_),
            false,
        ),
        c(
            "tweaked infinite (Lengyel, 2^-22)",
            Mat4::from_cols_array(&tweaked),
            ClipDepth::NegOneToOne,
            (n64, f64::INFINITY),
            false,
        ),
        c(
            "glam rh opengl::orthographic (glOrtho, [-1, 1])",
            rh::opengl::orthographic(-20.0, 20.0, -10.0, 10.0, 1.0, 500.0),
            ClipDepth::NegOneToOne,
            (1.0, 500.0),
            true,
        ),
        c(
            "glam rh directx::orthographic ([0, 1], near behind the eye)",
            rh::directx::orthographic(-20.0, 20.0, -10.0, 10.0, -5.0, 500.0),
            ClipDepth::ZeroToOne,
            (-5.0, 500.0),
            true,
        ),
        c(
            "glam rh directx::orthographic with near and far swapped (reversed)",
            rh::directx::orthographic(-20.0, 20.0, -10.0, 10.0, 500.0, 1.0),
            ClipDepth::ReversedZeroToOne,
            (1.0, 500.0),
            true,
        ),
    ]
}

/// Only `element` may differ, bit for bit.
fn only_element_changed(name: &str, m: &[f32; 16], out: &[f32; 16], element: usize) {
    for i in 0..16 {
        if i != element {
            assert_eq!(
                m[i].to_bits(),
                out[i].to_bits(),
                "{name}: element {i} changed"
            );
        }
    }
    assert_ne!(
        m[element], out[element],
        "{name}: the offset element did not move"
    );
}

/// The NDC offset the GPU sees (exact, from the f32 elements) must be at least `want` in
/// magnitude and at most one f32 ulp of the element more, with the same sign.
fn at_least_and_within_an_ulp(what: &str, seen: &Q, want: &Q, element: f32) {
    assert!(
        (seen.is_negative() == want.is_negative()) && seen.abs() >= want.abs(),
        "{what}: offset {seen} is less than the {want} asked"
    );
    assert!(
        seen.abs() - want.abs() <= ulp(element),
        "{what}: offset {seen} exceeds {want} by more than one ulp of {element}"
    );
}

#[test]
fn recognises_every_engine_matrix_and_its_planes() {
    for c in cases() {
        let r = recognize(&c.m, c.clip).unwrap_or_else(|e| panic!("{}: {e}", c.name));
        assert_eq!(
            matches!(r.shape, Shape::Orthographic),
            c.ortho,
            "{}",
            c.name
        );
        // The f32 depth row pins the far plane of a perspective matrix only to about
        // 2^-23·f/n relative (m10 ± 1 cancels): that is the plane the GPU draws with.
        let (n, f) = c.planes;
        let far_tolerance = if c.ortho {
            1e-5
        } else {
            2f64.powi(-22) * f / n
        };
        let close = |got: f64, want: f64, tolerance: f64| {
            if want.is_infinite() {
                got == want
            } else {
                (got - want).abs() <= tolerance * want.abs().max(1.0)
            }
        };
        assert!(close(r.near, n, 1e-5), "{}: near {} vs {n}", c.name, r.near);
        assert!(
            close(r.far, f, far_tolerance),
            "{}: far {} vs {f}",
            c.name,
            r.far
        );
    }
}

#[test]
fn an_eye_shift_changes_one_element_by_at_least_the_offset_asked() {
    for c in cases() {
        let s = f64::from(c.m[11]);
        for (delta, d) in [(0.01, 50.0), (1e-4, 0.2), (2.5, 400.0), (-0.5, 30.0)] {
            let what = format!("{} delta {delta} at d {d}", c.name);
            let out =
                offset_shift(&c.m, c.clip, delta, d).unwrap_or_else(|e| panic!("{what}: {e}"));
            let (m10, m14) = (q(f64::from(c.m[10])), q(f64::from(c.m[14])));
            let (dq, deltaq) = (q(d), q(delta));
            if c.ortho {
                // z_ndc = m10·z + m14 with z = −d: moving δ toward the camera adds m10·δ.
                only_element_changed(&what, &c.m, &out, 14);
                let seen = q(f64::from(out[14])) - &m14;
                at_least_and_within_an_ulp(&what, &seen, &(&m10 * &deltaq), out[14]);
            } else if c.clip == ClipDepth::ReversedZeroToOne {
                // m14·(1 + ε) with ε = δ/(d − δ) moves d to d − δ exactly.
                only_element_changed(&what, &c.m, &out, 14);
                let want = &m14 * &deltaq / (&dq - &deltaq);
                let seen = q(f64::from(out[14])) - &m14;
                at_least_and_within_an_ulp(&what, &seen, &want, out[14]);
            } else {
                // z_ndc = s·m10 + m14/d: the change at d is m14·δ/(d(d − δ)), through s·Δm10.
                only_element_changed(&what, &c.m, &out, 10);
                let want = &m14 * &deltaq / (&dq * (&dq - &deltaq));
                let seen = (q(f64::from(out[10])) - &m10) * q(s);
                at_least_and_within_an_ulp(&what, &seen, &want, out[10]);
            }
        }
    }
}

#[test]
fn an_ndc_offset_moves_depth_toward_the_camera_in_every_convention() {
    for c in cases() {
        let s = if c.ortho { 1.0 } else { f64::from(c.m[11]) };
        let toward = if c.clip == ClipDepth::ReversedZeroToOne {
            1.0
        } else {
            -1.0
        };
        for ndc in [1.2e-7, 3e-5, 0.01] {
            let what = format!("{} ndc {ndc}", c.name);
            let out = offset_ndc(&c.m, c.clip, ndc).unwrap_or_else(|e| panic!("{what}: {e}"));
            let element = if c.ortho { 14 } else { 10 };
            only_element_changed(&what, &c.m, &out, element);
            let seen = (q(f64::from(out[element])) - q(f64::from(c.m[element]))) * q(s);
            at_least_and_within_an_ulp(&what, &seen, &q(toward * ndc), out[element]);
        }
    }
}

#[test]
fn a_convention_mismatch_is_an_error_naming_the_element() {
    let reversed = rh::directx::perspective_infinite_reverse(FOVY, ASPECT, 0.1).to_cols_array();
    let e = offset_shift(&reversed, ClipDepth::NegOneToOne, 0.01, 10.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Domain);
    assert!(e.to_string().contains("reversed-Z"), "{e}");
    assert!(e.to_string().contains("m[14]"), "{e}");
    let standard = rh::opengl::perspective(FOVY, ASPECT, 0.1, 100.0).to_cols_array();
    let e = offset_ndc(&standard, ClipDepth::ReversedZeroToOne, 1e-5).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Domain);
    let ortho_reversed = rh::directx::orthographic(-1.0, 1.0, -1.0, 1.0, 10.0, 0.0).to_cols_array();
    assert!(offset_ndc(&ortho_reversed, ClipDepth::ZeroToOne, 1e-5).is_err());
}

#[test]
fn what_cannot_be_offset_is_refused_with_the_element_named() {
    let m = rh::opengl::perspective(FOVY, ASPECT, 0.1, 100.0).to_cols_array();
    // Row-major (transposed): m[3] = 0 but m[11] holds the depth term and m[14] = −1.
    let t = Mat4::from_cols_array(&m).transpose().to_cols_array();
    let e = recognize(&t, ClipDepth::NegOneToOne).unwrap_err();
    assert!(e.to_string().contains("m[11]"), "{e}");
    // An oblique near plane puts x and y into the depth row.
    let mut oblique = m;
    oblique[2] = 0.25;
    let e = recognize(&oblique, ClipDepth::NegOneToOne).unwrap_err();
    assert!(
        e.to_string().contains("m[2]") && e.to_string().contains("0.25"),
        "{e}"
    );
    let mut nan = m;
    nan[5] = f32::NAN;
    assert_eq!(
        recognize(&nan, ClipDepth::NegOneToOne).unwrap_err().kind(),
        ErrorKind::NotFinite
    );
    let e = offset_shift(&m, ClipDepth::NegOneToOne, 20.0, 10.0).unwrap_err();
    assert!(e.to_string().contains("d - delta"), "{e}");
    assert!(Q::zero() < q(1.0) && BigInt::from(1) > BigInt::from(0));
}

/// The fast paths (`offset_shift_fast`, `offset_ndc_fast`, behind the C entry points) give the
/// exact path's matrix whenever they decide, decide almost every ordinary input, and defer on
/// offsets built to land within a few dozen f64 ulps of an f32 step, and on every error.
#[test]
fn the_fast_paths_match_the_exact_ones() {
    use zshift::matrix_in::{offset_ndc_fast, offset_shift_fast};
    let mut state = 0x853c_49e6_748f_ea9bu64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut decided, mut ordinary, mut built_deferred, mut built) = (0, 0, 0, 0);
    for c in cases() {
        for i in 0..20_000 {
            let d = c.planes.0 * (1.0 + 1e4 * next());
            let landing = i % 4 == 0;
            let (delta, ndc) = if landing {
                // An offset of 1, 2 or 17 f32 steps of the offset element, nudged by a few f64
                // ulps of the element (2⁻²⁶ of a step is 2⁻⁴⁹ of the element).
                let e = if c.ortho || c.clip == ClipDepth::ReversedZeroToOne {
                    14
                } else {
                    10
                };
                let p = c.m[e];
                let step = f64::from(p.abs().next_up()) - f64::from(p.abs());
                let k = [1.0, 2.0, 17.0][i % 3];
                let o = k * step * (1.0 + (next() - 0.5) * 2f64.powi(-26));
                let delta = if c.ortho {
                    o / f64::from(c.m[10]).abs()
                } else {
                    // m14·δ/(d(d − δ)) = o (or m14·δ/(d − δ) = o reversed), for δ.
                    let m14 = f64::from(c.m[14]).abs();
                    let g = if c.clip == ClipDepth::ReversedZeroToOne {
                        1.0
                    } else {
                        d
                    };
                    o * g * d / (m14 + o * g)
                };
                (delta, o)
            } else {
                let sign = if next() < 0.5 { -1.0 } else { 1.0 };
                (
                    sign * d * 10f64.powf(-7.0 * next()) * 0.5,
                    sign * 10f64.powf(-8.0 * next()),
                )
            };
            let what = || format!("{} delta {delta} d {d} ndc {ndc}", c.name);
            let exact = offset_shift(&c.m, c.clip, delta, d);
            let fast = offset_shift_fast(&c.m, c.clip, delta, d);
            if let Some(m) = fast {
                assert_eq!(Ok(m), exact.map_err(|e| e.to_string()), "{}", what());
            }
            let exact_ndc = offset_ndc(&c.m, c.clip, ndc);
            if let Some(m) = offset_ndc_fast(&c.m, c.clip, ndc) {
                assert_eq!(Ok(m), exact_ndc.map_err(|e| e.to_string()), "{}", what());
            }
            if landing {
                built += 1;
                built_deferred += usize::from(fast.is_none());
            } else if exact.is_ok() {
                ordinary += 1;
                decided += usize::from(fast.is_some());
            }
        }
    }
    println!("{decided} of {ordinary} decided, {built_deferred} of {built} built deferred");
    assert!(
        decided as f64 > 0.999 * ordinary as f64,
        "{decided} of {ordinary} decided"
    );
    assert!(
        built_deferred > built / 50,
        "{built_deferred} of {built} built inputs deferred"
    );
    for (m, clip) in [
        ([f32::NAN; 16], ClipDepth::NegOneToOne),
        (cases()[0].m, ClipDepth::ReversedZeroToOne),
    ] {
        assert_eq!(offset_shift_fast(&m, clip, 0.01, 50.0), None);
        assert_eq!(offset_ndc_fast(&m, clip, 1e-5), None);
    }
}

//! The projection builders, depth mappings, offsets, polygon-offset conversions and plans
//! against exact rational arithmetic. References are the defining formulas evaluated in
//! `BigRational` (every finite f64 and f32 is a rational), or IEEE facts checked independently
//! (`f32::next_up`), never numbers taken from the code under test.

use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use zshift::clip_offset::{
    ndc_offset_matrix, ndc_offset_of_shift, offset_projection, relative_epsilon,
    relative_offset_matrix,
};
use zshift::median::{ftransform_mdp, ndc_offset as median_ndc_offset};
use zshift::plan::{range_offset, stacked_layers, tight_planes, OffsetKind, PLANE_MARGIN};
use zshift::polygon_offset::{bias_of_shift, d3d_depth_bias, shift_of_bias, BiasApi};
use zshift::precision::{DepthFormat, DepthMapping};
use zshift::projection::{
    depth_row, perspective_frustum, projection, projection_f64, tweaked_infinite, ClipDepth,
    MIN_INFINITE_TWEAK,
};
use zshift::{ErrorKind, Frustum, Planes};

mod rational;
use rational::{int, pow2, q, q32, Q};
fn rel_err(x: f64, exact: &Q) -> f64 {
    if exact.is_zero() {
        return x.abs();
    }
    ((q(x) - exact) / exact).abs().to_f64().unwrap()
}

const CONVENTIONS: [ClipDepth; 3] = [
    ClipDepth::NegOneToOne,
    ClipDepth::ZeroToOne,
    ClipDepth::ReversedZeroToOne,
];
const FORMATS: [DepthFormat; 4] = [
    DepthFormat::Unorm16,
    DepthFormat::Unorm24,
    DepthFormat::Unorm32,
    DepthFormat::Float32,
];
const PLANES: [(f64, f64); 5] = [
    (0.1, 1000.0),
    (1.0, 3.0),
    (0.01, 1e6),
    (0.5, f64::INFINITY),
    (1.0, 1.0 + 1e-9),
];

/// Exact `(m10, m14)` of each convention from its definition: NDC depth `−m10 + m14/d` must
/// take the convention's values at `d = n` and `d = f` (or `d → ∞`).
fn exact_row(n: f64, f: f64, clip: ClipDepth) -> (Q, Q) {
    let (n, two) = (q(n), int(2));
    if f.is_infinite() {
        return match clip {
            ClipDepth::NegOneToOne => (int(-1), -two * n),
            ClipDepth::ZeroToOne => (int(-1), -n),
            ClipDepth::ReversedZeroToOne => (Q::zero(), n),
        };
    }
    let f = q(f);
    let span = &f - &n;
    match clip {
        ClipDepth::NegOneToOne => (-(&f + &n) / &span, -two * &f * &n / &span),
        ClipDepth::ZeroToOne => (-&f / &span, -&f * &n / &span),
        ClipDepth::ReversedZeroToOne => (&n / &span, &f * &n / &span),
    }
}

/// Exact NDC depth at distance `d` from exact elements.
fn ndc(row: &(Q, Q), d: &Q) -> Q {
    -&row.0 + &row.1 / d
}

/// Exact window depth: `(z + 1)/2` for `[−1, 1]`, `z` for `[0, 1]`.
fn window(clip: ClipDepth, z: Q) -> Q {
    match clip {
        ClipDepth::NegOneToOne => (z + int(1)) / int(2),
        _ => z,
    }
}

#[test]
fn depth_rows_match_their_definitions_and_map_the_planes_to_the_ends() {
    for (n, f) in PLANES {
        let planes = Planes::new(n, f).unwrap();
        for clip in CONVENTIONS {
            let (m10, m14) = depth_row(&planes, clip);
            let exact = exact_row(n, f, clip);
            assert!(
                rel_err(m10, &exact.0) < 4e-16 * 4.0,
                "{clip:?} m10 n={n} f={f}"
            );
            assert!(
                rel_err(m14, &exact.1) < 4e-16 * 4.0,
                "{clip:?} m14 n={n} f={f}"
            );
            // The ends, from the exact elements (checks the table itself).
            let near_end = window(clip, ndc(&exact, &q(n)));
            let want_near = if clip == ClipDepth::ReversedZeroToOne {
                int(1)
            } else {
                Q::zero()
            };
            assert_eq!(near_end, want_near, "{clip:?} near end");
            if f.is_finite() {
                let far_end = window(clip, ndc(&exact, &q(f)));
                let want_far = if clip == ClipDepth::ReversedZeroToOne {
                    Q::zero()
                } else {
                    int(1)
                };
                assert_eq!(far_end, want_far, "{clip:?} far end");
            }
        }
    }
}

#[test]
fn projection_keeps_the_frustum_rows_and_rounds_to_nearest() {
    let fr = Frustum::new(-0.3, 0.5, -0.2, 0.25, 0.1, 500.0).unwrap();
    let plain = fr.to_cols_array().unwrap();
    for clip in CONVENTIONS {
        let m = projection(&fr, clip).unwrap();
        let m64 = projection_f64(&fr, clip).unwrap();
        for i in [0, 5, 8, 9, 11] {
            assert_eq!(m[i].to_bits(), plain[i].to_bits(), "{clip:?} element {i}");
        }
        for i in 0..16 {
            assert_eq!(
                m[i], m64[i] as f32,
                "{clip:?} element {i} is the nearest f32"
            );
        }
    }
}

#[test]
fn perspective_matches_glu_perspective() {
    for (fovy, aspect, n, f) in [
        (60.0, 16.0 / 9.0, 0.1, 100.0),
        (90.0, 1.0, 1.0, f64::INFINITY),
        (1.0, 0.5, 2.0, 3.0),
    ] {
        let m = perspective_frustum(fovy, aspect, n, f)
            .unwrap()
            .to_cols_array_f64()
            .unwrap();
        // gluPerspective: cot(fovy/2)/aspect and cot(fovy/2), centred (elements 8, 9 zero).
        let cot = 1.0 / (fovy / 2.0).to_radians().tan();
        assert!(((m[0] - cot / aspect) / m[0]).abs() < 1e-14, "m0 {fovy}");
        assert!(((m[5] - cot) / m[5]).abs() < 1e-14, "m5 {fovy}");
        assert_eq!((m[8], m[9]), (0.0, 0.0));
    }
    for (fovy, aspect) in [(0.0, 1.0), (180.0, 1.0), (60.0, 0.0), (60.0, -1.0)] {
        assert_eq!(
            perspective_frustum(fovy, aspect, 1.0, 2.0)
                .unwrap_err()
                .kind(),
            ErrorKind::Domain
        );
    }
    assert_eq!(
        perspective_frustum(f64::NAN, 1.0, 1.0, 2.0)
            .unwrap_err()
            .kind(),
        ErrorKind::NotFinite
    );
}

/// `z_clip` and `w` of the depth row as a GPU with correctly rounded f32 computes them
/// (`m10·z_eye + m14·1`, two roundings; Rust's f32 ops are IEEE).
fn clip_zw_f32(m: &[f32; 16], d: f32) -> (f32, f32) {
    let z_eye = -d;
    ((m[10] * z_eye) + m[14], m[11] * z_eye)
}

#[test]
fn tweaked_infinite_keeps_far_geometry_inside_in_f32_and_the_plain_one_does_not() {
    let fr = Frustum::new(-1.0, 1.0, -1.0, 1.0, 0.1, f64::INFINITY).unwrap();
    let plain = projection(&fr, ClipDepth::NegOneToOne).unwrap();
    let tweaked = tweaked_infinite(&fr, MIN_INFINITE_TWEAK).unwrap();
    assert_eq!(MIN_INFINITE_TWEAK, 2f64.powi(-22));
    assert_eq!(
        f64::from(tweaked[10]),
        MIN_INFINITE_TWEAK - 1.0,
        "element 10 exact"
    );
    let mut plain_on_far_plane = 0;
    let mut d = 1.0f32;
    while d < 1e30 {
        for k in 0..64 {
            let dk = d * (1.0 + k as f32 / 64.0);
            let (z, w) = clip_zw_f32(&tweaked, dk);
            assert!(z < w, "tweaked: z_clip {z} >= w {w} at d = {dk}");
            let (z, w) = clip_zw_f32(&plain, dk);
            if z >= w {
                plain_on_far_plane += 1;
            }
        }
        d *= 2.0;
    }
    assert!(
        plain_on_far_plane > 0,
        "the plain infinite projection never reached the far plane"
    );
    // The exact NDC depth of the tweaked projection: −1 at n.
    let m = zshift::projection::tweaked_infinite_f64(&fr, MIN_INFINITE_TWEAK).unwrap();
    let z_at_n = -q(m[10]) + q(m[14]) / q(0.1);
    assert!((z_at_n + int(1)).abs() < q(1e-15));
    for bad in [-1e-9, 1.0, f64::NAN] {
        assert!(tweaked_infinite(&fr, bad).is_err());
    }
}

/// Independent f32 spacing at `w`: the gap to the next f32 above `f32(w)` (D3D/Vulkan's
/// `2^(e−23)` for normal values).
fn f32_spacing(w: f64) -> f64 {
    let s = w as f32;
    f64::from(s.next_up()) - f64::from(s)
}

#[test]
fn format_spacing_is_the_unorm_step_or_the_float_ulp() {
    for (format, bits) in [
        (DepthFormat::Unorm16, 16),
        (DepthFormat::Unorm24, 24),
        (DepthFormat::Unorm32, 32),
    ] {
        let r = format.spacing_at(0.3).unwrap();
        let exact = Q::one() / (Q::from_integer((BigInt::one() << bits) - 1));
        assert!(rel_err(r, &exact) < 2e-16, "{format:?}");
    }
    for w in [1.0, 0.75, 0.5, 0.4999, 1e-3, 3e-20, 1e-40, 0.0] {
        let r = DepthFormat::Float32.spacing_at(w).unwrap();
        let want = if w == 1.0 {
            f64::from(1.0f32 - 1.0f32.next_down()) * 2.0
        } else {
            f32_spacing(w)
        };
        assert_eq!(r, want, "Float32 at {w}");
    }
    assert!(DepthFormat::Float32.spacing_at(1.5).is_err());
    assert!(DepthFormat::Float32.spacing_at(f64::NAN).is_err());
}

/// The exact window depth of a mapping, from its definition.
fn exact_window(kind: &Mapping, d: &Q) -> Q {
    match kind {
        Mapping::Proj(n, f, clip) => window(*clip, ndc(&exact_row(*n, *f, *clip), d)),
        Mapping::Tweaked(n, t) => {
            let z = int(1) - q(*t) + (q(*t) - int(2)) * q(*n) / d;
            (z + int(1)) / int(2)
        }
        Mapping::Median(m) => {
            let m = q(*m);
            let z = (d - &m) / (d + &m);
            (z + int(1)) / int(2)
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum Mapping {
    Proj(f64, f64, ClipDepth),
    Tweaked(f64, f64),
    Median(f64),
}

fn mapping(kind: &Mapping) -> DepthMapping {
    match *kind {
        Mapping::Proj(n, f, clip) => DepthMapping::projection(n, f, clip).unwrap(),
        Mapping::Tweaked(n, t) => DepthMapping::tweaked_infinite(n, t).unwrap(),
        Mapping::Median(m) => DepthMapping::median(m).unwrap(),
    }
}

fn all_mappings() -> Vec<Mapping> {
    let mut v = Vec::new();
    for (n, f) in [(0.1, 1000.0), (1.0, 3.0), (0.5, f64::INFINITY), (0.01, 1e6)] {
        for clip in CONVENTIONS {
            v.push(Mapping::Proj(n, f, clip));
        }
    }
    v.push(Mapping::Tweaked(0.1, MIN_INFINITE_TWEAK));
    v.push(Mapping::Median(10.0));
    v.push(Mapping::Median(0.25));
    v
}

fn sample_distances(m: &DepthMapping) -> Vec<f64> {
    let n = m.near().max(1e-3);
    let f = if m.far().is_finite() {
        m.far()
    } else {
        n * 1e7
    };
    (0..=12)
        .map(|i| n * (f / n).powf(i as f64 / 12.0))
        .map(|d| d.clamp(n, f))
        .collect()
}

#[test]
fn window_depth_of_every_mapping_matches_its_definition() {
    for kind in all_mappings() {
        let m = mapping(&kind);
        for d in sample_distances(&m) {
            let w = m.window_depth(d).unwrap();
            let exact = exact_window(&kind, &q(d));
            let err = (q(w) - &exact).abs().to_f64().unwrap();
            assert!(
                err <= 4.0 * f64::EPSILON * exact.to_f64().unwrap().max(1e-300) + 1e-300,
                "{kind:?} d={d}: {w} vs {}",
                exact.to_f64().unwrap()
            );
        }
    }
}

#[test]
fn depth_step_moves_the_window_depth_by_exactly_one_spacing() {
    for kind in all_mappings() {
        let m = mapping(&kind);
        for format in FORMATS {
            for d in sample_distances(&m) {
                let step = match m.depth_step(d, format) {
                    Ok(s) => s,
                    Err(e) => panic!("{kind:?} {format:?} d={d}: {e}"),
                };
                assert!(step > 0.0);
                if d - step < m.near() {
                    continue; // the step reaches past the near plane: nothing to compare
                }
                let w = exact_window(&kind, &q(d));
                let r = if format.is_unorm() {
                    Q::one() / Q::from_integer((BigInt::one() << format.bits()) - 1)
                } else {
                    q(f32_spacing(w.to_f64().unwrap()))
                };
                let moved = (exact_window(&kind, &(q(d) - q(step))) - &w).abs();
                let err = ((moved - &r) / &r).abs().to_f64().unwrap();
                assert!(
                    err < 1e-9,
                    "{kind:?} {format:?} d={d}: moved {err} off one spacing"
                );
            }
        }
    }
}

#[test]
fn standard_unorm_steps_agree_with_walker_and_the_core() {
    for (n, f) in [(0.1, 1000.0), (1.0, 3.0)] {
        let m = DepthMapping::projection(n, f, ClipDepth::NegOneToOne).unwrap();
        for d in [n, 2.0 * n, f / 2.0, f] {
            let core = zshift::depth_resolution(n, f, 24, d).unwrap();
            let step = m.depth_step(d, DepthFormat::Unorm24).unwrap();
            assert!(((core - step) / core).abs() < 1e-14, "n={n} f={f} d={d}");
        }
        // The quantum of seed 002: 2/(2^m − 1) in NDC.
        let c = m.min_ndc_offset(f / 2.0, DepthFormat::Unorm16).unwrap();
        assert!(rel_err(c, &(int(2) / int(65535))) < 1e-15);
    }
}

#[test]
fn shift_and_window_change_are_inverse_and_exact() {
    for kind in all_mappings() {
        let m = mapping(&kind);
        for d in sample_distances(&m) {
            let delta = 1e-3 * (d - m.near());
            if delta <= 0.0 {
                continue;
            }
            let dw = m.window_change_of_shift(delta, d).unwrap();
            let exact = exact_window(&kind, &(q(d) - q(delta))) - exact_window(&kind, &q(d));
            assert!(rel_err(dw, &exact) < 1e-13, "{kind:?} d={d}");
            assert_eq!(dw > 0.0, m.is_reversed(), "{kind:?}: sign of the change");
            let back = m.shift_of_window_change(dw, d).unwrap();
            assert!(
                ((back - delta) / delta).abs() < 1e-9,
                "{kind:?} d={d}: {back} vs {delta}"
            );
        }
    }
}

#[test]
fn ndc_offset_matrix_rounds_element_10_outward() {
    let fr = Frustum::new(-1.0, 1.0, -1.0, 1.0, 0.1, 1000.0).unwrap();
    for clip in CONVENTIONS {
        let m = projection_f64(&fr, clip).unwrap();
        let p = projection(&fr, clip).unwrap();
        for c in [-1e-7, 3e-8, -2.5e-9, 1e-3] {
            let o = ndc_offset_matrix(&m, c).unwrap();
            for i in (0..16).filter(|&i| i != 10) {
                assert_eq!(o[i].to_bits(), p[i].to_bits());
            }
            // The offset the GPU sees: z_ndc = −m10 + ..., so it is p10 − o10.
            let seen = q32(p[10]) - q32(o[10]);
            assert!(seen.abs() >= q(c).abs(), "{clip:?} c={c}: offset lost");
            assert_eq!(seen.is_positive(), c > 0.0);
            let ulp = f64::from(o[10].abs().next_up() - o[10].abs())
                .max(f64::from(o[10].abs() - o[10].abs().next_down()));
            assert!(
                seen.abs() <= q(c).abs() + q(ulp),
                "{clip:?} c={c}: more than one ulp extra"
            );
        }
    }
}

#[test]
fn relative_offset_is_exactly_a_proportional_shift_in_every_convention() {
    let fr = Frustum::new(-1.0, 1.0, -1.0, 1.0, 0.1, 1000.0).unwrap();
    let inf = Frustum::new(-1.0, 1.0, -1.0, 1.0, 0.1, f64::INFINITY).unwrap();
    for (frustum, clip) in [
        (fr, ClipDepth::ReversedZeroToOne),
        (inf, ClipDepth::ReversedZeroToOne),
        (fr, ClipDepth::NegOneToOne),
        (fr, ClipDepth::ZeroToOne),
    ] {
        for (delta, pz) in [(1e-5, -1.0), (2e-3, -50.0), (0.5, -900.0)] {
            let m = offset_projection(&frustum, clip, delta, pz).unwrap();
            let plain = projection(&frustum, clip).unwrap();
            if clip != ClipDepth::ReversedZeroToOne {
                // The constant NDC offset: the GPU's NDC depth at Pz is at least that of Pz + δ.
                let mapping = DepthMapping::projection(0.1, 1000.0, clip).unwrap();
                let c = ndc_offset_of_shift(&mapping, delta, pz).unwrap();
                let row = exact_row(0.1, 1000.0, clip);
                let exact_c = ndc(&row, &(q(-pz) - q(delta))) - ndc(&row, &q(-pz));
                assert!(rel_err(c, &exact_c) < 1e-12, "{clip:?}");
                assert!(
                    (q32(plain[10]) - q32(m[10])) <= q(c),
                    "{clip:?}: offset lost"
                );
                continue;
            }
            assert_eq!(
                m[10].to_bits(),
                plain[10].to_bits(),
                "reversed: element 10 untouched"
            );
            // Element 14 scaled: depth at d equals the plain depth at d' = d·p14/o14.
            let ratio = q32(plain[14]) / q32(m[14]);
            let d = q(-pz);
            let d_seen = &d * &ratio;
            assert!(
                &d - &d_seen >= q(delta) * q(1.0 - 1e-12),
                "reversed: shift {delta} at {pz} lost"
            );
            // At most one f32 ulp of element 14 (relative 2^-23) more than asked.
            assert!(
                &d - &d_seen <= q(delta) + &d * pow2(-23),
                "reversed: more than one ulp extra"
            );
            // The same fraction at every other distance.
            for other in [0.2, 7.0, 999.0] {
                let o = q(other);
                let frac_here = (&d - &d_seen) / &d;
                let frac_there = (&o - &o * &ratio) / &o;
                assert_eq!(frac_here, frac_there);
            }
        }
    }
    // Scaling element 10 of the infinite reversed projection does nothing: it is 0.
    let m = projection(&inf, ClipDepth::ReversedZeroToOne).unwrap();
    assert_eq!(m[10], 0.0);
    assert_eq!(m[10] * (1.0 + 1e-3), 0.0);
    let eps = relative_epsilon(1e-3, -2.0).unwrap();
    assert!(rel_err(eps, &(q(1e-3) / (q(2.0) - q(1e-3)))) < 1e-15);
    let o = relative_offset_matrix(
        &projection_f64(&inf, ClipDepth::ReversedZeroToOne).unwrap(),
        eps,
    )
    .unwrap();
    assert!(q32(o[14]) / q32(m[14]) >= int(1) + q(eps));
}

#[test]
fn relative_epsilon_under_reversed_float_is_about_one_ulp_at_every_distance() {
    let m = DepthMapping::projection(0.1, f64::INFINITY, ClipDepth::ReversedZeroToOne).unwrap();
    for d in [0.1, 1.0, 37.0, 1e4, 1e8] {
        let eps = m.min_relative_epsilon(d, DepthFormat::Float32).unwrap();
        assert!(
            eps > 2f64.powi(-24) && eps <= 2f64.powi(-23),
            "d={d}: {eps}"
        );
    }
    // UNORM24 reversed: the same ε grows linearly with distance — float is what makes it flat.
    let e1 = m.min_relative_epsilon(1.0, DepthFormat::Unorm24).unwrap();
    let e2 = m.min_relative_epsilon(100.0, DepthFormat::Unorm24).unwrap();
    assert!((e2 / e1 - 100.0).abs() < 1e-9);
}

#[test]
fn median_projection_reference_and_offset() {
    let proj = zshift::projection::perspective_frustum(60.0, 1.5, 0.1, 100.0)
        .unwrap()
        .to_dmat4()
        .unwrap();
    for (median, d, x, y) in [
        (10.0, 3.0, 0.5, -0.25),
        (2.0, 0.01, 0.001, 0.002),
        (50.0, 1e4, 100.0, 3.0),
    ] {
        let eye = glam::DVec4::new(x, y, -d, 1.0);
        let c = ftransform_mdp(&proj, eye, median, 0.0);
        let std = proj * eye;
        // x, y after the divide are those of the standard projection.
        assert!(((c.x / c.w) - std.x / std.w).abs() < 1e-12 * (std.x / std.w).abs().max(1.0));
        assert!(((c.y / c.w) - std.y / std.w).abs() < 1e-12 * (std.y / std.w).abs().max(1.0));
        let z = (q(d) - q(median)) / (q(d) + q(median));
        assert!(rel_err(c.z / c.w, &z) < 1e-14 || (q(c.z / c.w) - &z).abs() < q(1e-15));
        // The offset: NDC at d with the uniform equals NDC at d − δ.
        let delta = d * 1e-3;
        let off = median_ndc_offset(median, delta, -d).unwrap();
        let exact = (q(d) - q(delta) - q(median)) / (q(d) - q(delta) + q(median)) - &z;
        assert!(rel_err(off, &exact) < 1e-12, "median {median} d {d}");
        let co = ftransform_mdp(&proj, eye, median, off);
        assert!(rel_err(co.z / co.w, &(z + exact)) < 1e-9);
    }
    assert!(zshift::median::FTRANSFORM_MDP_GLSL.contains("vec4 zshift_ftransform_mdp("));
    assert_eq!(
        DepthMapping::median(0.0).unwrap_err().kind(),
        ErrorKind::Domain
    );
}

#[test]
fn polygon_offset_units_convert_exactly_and_back() {
    let m = DepthMapping::projection(0.1, 1000.0, ClipDepth::NegOneToOne).unwrap();
    for format in FORMATS {
        for api in [BiasApi::OpenGl, BiasApi::Direct3d, BiasApi::Vulkan] {
            for (delta, pz) in [(1e-3, -1.0), (0.5, -500.0)] {
                let bias = bias_of_shift(&m, format, api, delta, pz).unwrap();
                let d = q(-pz);
                let dw = exact_window(
                    &Mapping::Proj(0.1, 1000.0, ClipDepth::NegOneToOne),
                    &(&d - q(delta)),
                ) - exact_window(&Mapping::Proj(0.1, 1000.0, ClipDepth::NegOneToOne), &d);
                let r = match (format.is_unorm(), api) {
                    (true, BiasApi::Vulkan) => pow2(-i64::from(format.bits())),
                    (true, _) => Q::one() / Q::from_integer((BigInt::one() << format.bits()) - 1),
                    (false, _) => q(f32_spacing(
                        exact_window(&Mapping::Proj(0.1, 1000.0, ClipDepth::NegOneToOne), &d)
                            .to_f64()
                            .unwrap(),
                    )),
                };
                assert!(rel_err(bias, &(dw / r)) < 1e-12, "{format:?} {api:?}");
                assert!(bias < 0.0, "toward the camera is a negative bias");
                let back = shift_of_bias(&m, format, api, bias, pz).unwrap();
                assert!(((back - delta) / delta).abs() < 1e-9);
            }
        }
        let int_bias = d3d_depth_bias(&m, format, 1e-3, -1.0).unwrap();
        let real = bias_of_shift(&m, format, BiasApi::Direct3d, 1e-3, -1.0).unwrap();
        assert!(
            f64::from(int_bias) <= real && f64::from(int_bias) > real - 1.0,
            "rounded away from zero"
        );
    }
    let rev = DepthMapping::projection(0.1, f64::INFINITY, ClipDepth::ReversedZeroToOne).unwrap();
    assert!(bias_of_shift(&rev, DepthFormat::Float32, BiasApi::Vulkan, 1e-3, -1.0).unwrap() > 0.0);
}

#[test]
fn tight_planes_keep_the_margin_and_no_more() {
    let eta = q(PLANE_MARGIN);
    for (near, far) in [(0.5, 20.0), (1.0, 1.0), (0.01, 5000.0), (2.0, 1e5)] {
        let planes = tight_planes(near, far).unwrap();
        let (n, f) = (planes.near(), planes.far());
        assert!(f.is_finite(), "{near}..{far}");
        let w = |d: f64| {
            let (qn, qf, qd) = (q(n), q(f), q(d));
            &qf * (&qd - &qn) / ((&qf - &qn) * &qd)
        };
        assert!(
            w(near) >= &eta * int(4) * q(1.0 - 1e-9),
            "near margin {near}..{far}"
        );
        assert!(w(far) <= int(1) - &eta, "far margin {near}..{far}");
        assert!(
            w(far) >= int(1) - &eta * int(2),
            "far plane not tight {near}..{far}"
        );
    }
    // Beyond what a finite far plane can hold in f32: infinite.
    assert!(tight_planes(1e-3, 1e5).unwrap().is_infinite());
    assert!(tight_planes(0.0, 1.0).is_err());
    assert!(tight_planes(2.0, 1.0).is_err());
}

#[test]
fn one_offset_for_a_range_covers_every_distance_in_it() {
    let cases = [
        (
            Mapping::Proj(0.1, 1000.0, ClipDepth::NegOneToOne),
            DepthFormat::Unorm24,
            OffsetKind::Ndc,
        ),
        (
            Mapping::Proj(0.1, 1000.0, ClipDepth::NegOneToOne),
            DepthFormat::Float32,
            OffsetKind::Ndc,
        ),
        (
            Mapping::Proj(0.1, f64::INFINITY, ClipDepth::ReversedZeroToOne),
            DepthFormat::Float32,
            OffsetKind::Relative,
        ),
        (
            Mapping::Proj(0.1, 1000.0, ClipDepth::ReversedZeroToOne),
            DepthFormat::Float32,
            OffsetKind::Relative,
        ),
        (Mapping::Median(10.0), DepthFormat::Unorm24, OffsetKind::Ndc),
    ];
    for (kind, format, okind) in cases {
        let m = mapping(&kind);
        let (lo, hi) = (0.5, 800.0);
        let plan = range_offset(&m, format, okind, lo, hi, 2.0).unwrap();
        let mut tightest = f64::INFINITY;
        for i in 0..=400 {
            let d = lo * (hi / lo).powf(i as f64 / 400.0);
            let w = exact_window(&kind, &q(d));
            let r = if format.is_unorm() {
                Q::one() / Q::from_integer((BigInt::one() << format.bits()) - 1)
            } else {
                q(f32_spacing(w.to_f64().unwrap()))
            };
            let moved = match okind {
                OffsetKind::Ndc => q(plan.offset).abs() * q(m.window_per_ndc()),
                OffsetKind::Relative => {
                    let d2 = q(d) / (int(1) + q(plan.offset));
                    (exact_window(&kind, &d2) - &w).abs()
                }
            };
            let ratio = (moved / (int(2) * r)).to_f64().unwrap();
            assert!(
                ratio >= 1.0 - 1e-9,
                "{kind:?} {format:?} d={d}: only {ratio} of 2 steps"
            );
            tightest = tightest.min(ratio);
        }
        assert!(
            tightest < 1.01,
            "{kind:?} {format:?}: offset not the smallest ({tightest})"
        );
        assert!(plan.shift_near > 0.0 && plan.shift_far > 0.0);
    }
}

#[test]
fn stacked_layers_multiply_and_stop_at_the_gap() {
    let m = DepthMapping::projection(0.1, 1000.0, ClipDepth::NegOneToOne).unwrap();
    let layers = stacked_layers(
        &m,
        DepthFormat::Unorm24,
        OffsetKind::Ndc,
        (1.0, 100.0),
        2.0,
        4,
        1.0,
    )
    .unwrap();
    assert_eq!(layers.len(), 4);
    for (k, l) in layers.iter().enumerate() {
        assert_eq!(l.offset, layers[0].offset * (k + 1) as f64);
        assert!(l.shift_far < 1.0 && l.shift_far > l.shift_near);
    }
    let top_far = layers[3].shift_far;
    let err = stacked_layers(
        &m,
        DepthFormat::Unorm24,
        OffsetKind::Ndc,
        (1.0, 100.0),
        2.0,
        4,
        top_far * 0.99,
    )
    .unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Unresolvable);
}

mod c_abi {
    use super::*;
    use zshift::ffi::*;

    #[test]
    fn entry_points_match_the_rust_functions_and_leave_output_untouched_on_error() {
        assert_eq!(ZSHIFT_MIN_INFINITE_TWEAK, MIN_INFINITE_TWEAK);
        let fr = Frustum::new(-1.0, 1.0, -0.5, 0.5, 0.1, 100.0).unwrap();
        let mut m = [7.0f32; 16];
        let clips = [
            (ZSHIFT_CLIP_NEG_ONE_TO_ONE, ClipDepth::NegOneToOne),
            (ZSHIFT_CLIP_ZERO_TO_ONE, ClipDepth::ZeroToOne),
            (
                ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
                ClipDepth::ReversedZeroToOne,
            ),
        ];
        for (c, clip) in clips {
            assert_eq!(
                zshift_projection(-1.0, 1.0, -0.5, 0.5, 0.1, 100.0, c, m.as_mut_ptr()),
                ZSHIFT_OK
            );
            assert_eq!(m, projection(&fr, clip).unwrap());
            let st = zshift_offset_projection(
                -1.0,
                1.0,
                -0.5,
                0.5,
                0.1,
                100.0,
                c,
                0.01,
                -5.0,
                m.as_mut_ptr(),
            );
            assert_eq!(st, ZSHIFT_OK);
            assert_eq!(m, offset_projection(&fr, clip, 0.01, -5.0).unwrap());
        }
        let before = m;
        assert_eq!(
            zshift_projection(
                -1.0,
                1.0,
                -0.5,
                0.5,
                0.1,
                100.0,
                ZshiftClip { value: 3 },
                m.as_mut_ptr()
            ),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(
            zshift_perspective(0.0, 1.0, 0.1, 10.0, m.as_mut_ptr()),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(
            zshift_tweaked_infinite(-1.0, 1.0, -1.0, 1.0, 0.1, 1.0, m.as_mut_ptr()),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(m, before, "output untouched on error");
        assert_eq!(
            zshift_perspective(60.0, 1.0, 0.1, 10.0, std::ptr::null_mut()),
            ZSHIFT_ERR_NULL_POINTER
        );
        assert_eq!(
            zshift_perspective(60.0, 1.5, 0.1, 10.0, m.as_mut_ptr()),
            ZSHIFT_OK
        );
        assert_eq!(
            m,
            perspective_frustum(60.0, 1.5, 0.1, 10.0)
                .unwrap()
                .to_cols_array()
                .unwrap()
        );
        let st = zshift_offset_perspective(
            60.0,
            1.5,
            0.1,
            10.0,
            ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
            0.01,
            -2.0,
            m.as_mut_ptr(),
        );
        assert_eq!(st, ZSHIFT_OK);
        let pf = perspective_frustum(60.0, 1.5, 0.1, 10.0).unwrap();
        assert_eq!(
            m,
            offset_projection(&pf, ClipDepth::ReversedZeroToOne, 0.01, -2.0).unwrap()
        );
        assert_eq!(
            zshift_tweaked_infinite(
                -1.0,
                1.0,
                -1.0,
                1.0,
                0.1,
                MIN_INFINITE_TWEAK,
                m.as_mut_ptr()
            ),
            ZSHIFT_OK
        );
        let inf = Frustum::new(-1.0, 1.0, -1.0, 1.0, 0.1, f64::INFINITY).unwrap();
        assert_eq!(m, tweaked_infinite(&inf, MIN_INFINITE_TWEAK).unwrap());

        let mut x = 42.0f64;
        let fmt = ZSHIFT_FORMAT_FLOAT32;
        assert_eq!(
            zshift_depth_step(
                0.1,
                100.0,
                ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
                fmt,
                3.0,
                &mut x
            ),
            ZSHIFT_OK
        );
        let m_rev = DepthMapping::projection(0.1, 100.0, ClipDepth::ReversedZeroToOne).unwrap();
        assert_eq!(x, m_rev.depth_step(3.0, DepthFormat::Float32).unwrap());
        assert_eq!(
            zshift_depth_step(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                ZshiftFormat { value: 9 },
                3.0,
                &mut x
            ),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(
            zshift_depth_step(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                300.0,
                &mut x
            ),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(
            x,
            m_rev.depth_step(3.0, DepthFormat::Float32).unwrap(),
            "untouched"
        );
        assert_eq!(
            zshift_median_depth_step(10.0, ZSHIFT_FORMAT_UNORM24, 5.0, &mut x),
            ZSHIFT_OK
        );
        assert_eq!(
            x,
            DepthMapping::median(10.0)
                .unwrap()
                .depth_step(5.0, DepthFormat::Unorm24)
                .unwrap()
        );
        assert_eq!(zshift_median_ndc_offset(10.0, 0.1, -5.0, &mut x), ZSHIFT_OK);
        assert_eq!(x, median_ndc_offset(10.0, 0.1, -5.0).unwrap());
        assert_eq!(
            zshift_window_depth_clip(0.1, 100.0, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, 0.1, &mut x),
            ZSHIFT_OK
        );
        assert_eq!(x, 1.0);
        assert_eq!(
            zshift_min_ndc_offset(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                ZSHIFT_FORMAT_UNORM16,
                1.0,
                &mut x
            ),
            ZSHIFT_OK
        );
        assert!(rel_err(x, &(int(2) / int(65535))) < 1e-15);
        assert_eq!(
            zshift_min_relative_epsilon(
                0.1,
                100.0,
                ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
                fmt,
                1.0,
                &mut x
            ),
            ZSHIFT_OK
        );
        assert_eq!(
            x,
            m_rev
                .min_relative_epsilon(1.0, DepthFormat::Float32)
                .unwrap()
        );
        let std = DepthMapping::projection(0.1, 100.0, ClipDepth::NegOneToOne).unwrap();
        assert_eq!(
            zshift_bias_of_shift(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                ZSHIFT_BIAS_VULKAN,
                0.01,
                -5.0,
                &mut x
            ),
            ZSHIFT_OK
        );
        assert_eq!(
            x,
            bias_of_shift(&std, DepthFormat::Unorm24, BiasApi::Vulkan, 0.01, -5.0).unwrap()
        );
        let bias = x;
        assert_eq!(
            zshift_shift_of_bias(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                ZSHIFT_BIAS_VULKAN,
                bias,
                -5.0,
                &mut x
            ),
            ZSHIFT_OK
        );
        assert!((x - 0.01).abs() < 1e-9);
        assert_eq!(
            zshift_bias_of_shift(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                ZshiftBiasApi { value: 7 },
                0.01,
                -5.0,
                &mut x
            ),
            ZSHIFT_ERR_DOMAIN
        );

        let mut two = [0.0f64; 2];
        assert_eq!(zshift_tight_planes(0.5, 20.0, two.as_mut_ptr()), ZSHIFT_OK);
        let p = tight_planes(0.5, 20.0).unwrap();
        assert_eq!(two, [p.near(), p.far()]);
        assert_eq!(
            zshift_tight_planes(0.0, 20.0, two.as_mut_ptr()),
            ZSHIFT_ERR_DOMAIN
        );
        let mut three = [0.0f64; 3];
        let st = zshift_range_offset(
            0.1,
            100.0,
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            zshift::ffi::ZSHIFT_FORMAT_UNORM24,
            ZSHIFT_OFFSET_NDC,
            1.0,
            50.0,
            2.0,
            three.as_mut_ptr(),
        );
        assert_eq!(st, ZSHIFT_OK);
        let o = range_offset(&std, DepthFormat::Unorm24, OffsetKind::Ndc, 1.0, 50.0, 2.0).unwrap();
        assert_eq!(three, [o.offset, o.shift_near, o.shift_far]);
        assert_eq!(
            zshift_range_offset(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                ZshiftOffsetKind { value: 5 },
                1.0,
                50.0,
                2.0,
                three.as_mut_ptr()
            ),
            ZSHIFT_ERR_DOMAIN
        );
        assert_eq!(
            zshift_range_offset(
                0.1,
                100.0,
                ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                zshift::ffi::ZSHIFT_FORMAT_UNORM24,
                ZSHIFT_OFFSET_NDC,
                1.0,
                50.0,
                2.0,
                std::ptr::null_mut()
            ),
            ZSHIFT_ERR_NULL_POINTER
        );
    }
}

#[test]
fn min_epsilon_per_convention_has_its_own_quantum() {
    for (n, f) in [(0.1, 1000.0), (1.0, 3.0)] {
        for bits in [16u32, 24] {
            let fmt = if bits == 16 {
                DepthFormat::Unorm16
            } else {
                DepthFormat::Unorm24
            };
            let qm = Q::one() / Q::from_integer((BigInt::one() << bits) - 1);
            let (qn, qf) = (q(n), q(f));
            let std = DepthMapping::projection(n, f, ClipDepth::NegOneToOne).unwrap();
            let e = std.min_epsilon(f / 2.0, fmt).unwrap();
            assert!(rel_err(e, &(int(2) * &qm * (&qf - &qn) / (&qf + &qn))) < 1e-14);
            assert!(((e - zshift::min_epsilon(n, f, bits).unwrap()) / e).abs() < 1e-14);
            let zo = DepthMapping::projection(n, f, ClipDepth::ZeroToOne).unwrap();
            let e = zo.min_epsilon(f / 2.0, fmt).unwrap();
            assert!(rel_err(e, &(&qm * (&qf - &qn) / &qf)) < 1e-14);
            let rev = DepthMapping::projection(n, f, ClipDepth::ReversedZeroToOne).unwrap();
            let e = rev.min_epsilon(f / 2.0, fmt).unwrap();
            assert!(rel_err(e, &(&qm * (&qf - &qn) / &qn)) < 1e-14);
        }
    }
    let rev_inf =
        DepthMapping::projection(0.1, f64::INFINITY, ClipDepth::ReversedZeroToOne).unwrap();
    let err = rev_inf.min_epsilon(3.0, DepthFormat::Float32).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Unresolvable);
    let mut x = 5.0;
    assert_eq!(
        zshift::ffi::zshift_min_epsilon_clip(
            0.1,
            f64::INFINITY,
            zshift::ffi::ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE,
            zshift::ffi::ZSHIFT_FORMAT_FLOAT32,
            3.0,
            &mut x
        ),
        zshift::ffi::ZSHIFT_ERR_UNRESOLVABLE
    );
    assert_eq!(x, 5.0);
    assert_eq!(
        zshift::ffi::zshift_min_epsilon_clip(
            0.1,
            100.0,
            zshift::ffi::ZSHIFT_CLIP_ZERO_TO_ONE,
            zshift::ffi::ZSHIFT_FORMAT_UNORM24,
            3.0,
            &mut x
        ),
        zshift::ffi::ZSHIFT_OK
    );
    assert_eq!(
        x,
        DepthMapping::projection(0.1, 100.0, ClipDepth::ZeroToOne)
            .unwrap()
            .min_epsilon(3.0, DepthFormat::Unorm24)
            .unwrap()
    );
}

#[test]
fn median_f32_reference_tracks_the_exact_depth() {
    let proj = zshift::projection::perspective(60.0, 1.0, 0.1, 100.0).unwrap();
    for (median, d) in [(10.0f32, 3.0f32), (10.0, 250.0), (0.5, 0.01)] {
        let eye = glam::Vec4::new(0.2, -0.1, -d, 1.0);
        let c = zshift::median::ftransform_mdp_f32(&proj, eye, median, 0.0);
        let exact = (q32(d) - q32(median)) / (q32(d) + q32(median));
        // Two roundings (z and w) and the divide: a few f32 ulps of the larger of d and m.
        let z = q32(c.z) / q32(c.w);
        let tol = q(4.0 * f64::from(f32::EPSILON));
        assert!((z - &exact).abs() <= tol, "median {median} d {d}");
        let x_std = (proj * eye).x / d;
        assert!((c.x / c.w - x_std).abs() <= 4.0 * f32::EPSILON * x_std.abs().max(1.0));
    }
}

//! Unit tests of the decal recommendation: references from the seeds' formulas and exact
//! arithmetic, not from the code under test.

use super::*;
use crate::ErrorKind;

fn scene(format: DepthFormat, slope: f64, snapping: Snapping) -> Scene {
    let profile = RasterizerProfile {
        snapping,
        ..RasterizerProfile::worst_case()
    };
    let e = 0.577_350_269_189_625_7;
    Scene {
        pipeline: Default::default(),
        footprint: None,
        frustum: Frustum::new(-e, e, -e, e, 1.0, 1e3).unwrap(),
        viewport: [256, 256],
        format,
        depth_range: [80.0, 120.0],
        slope,
        exact_depth: false,
        depth_test: DepthTest::Less,
        base: Base::InsideFrustum,
        profile,
    }
}

/// With an identified depth chain, a shared-z facing decal's matrix moves the offset element
/// by exactly the steps the chain needs, the largest over the elements an engine's own f32
/// code might hold (within two steps) and over its shader fusing `m10·z + m14` or not, or one
/// more: checked against the chain emulated here
/// on every nearby element, for every format and convention, at depths the probe never drew.
#[test]
fn an_identified_chain_gives_the_steps_it_needs() {
    use crate::depth_chain::{stepped, DepthChain};
    let chain = DepthChain::from_code(2).unwrap(); // Mesa llvmpipe's
    for clip in [
        ClipDepth::NegOneToOne,
        ClipDepth::ZeroToOne,
        ClipDepth::ReversedZeroToOne,
    ] {
        for format in [
            DepthFormat::Unorm16,
            DepthFormat::Unorm24,
            DepthFormat::Float32,
        ] {
            for d in [1.37f32, 11.25, 80.0, 333.3] {
                let mut s = scene(format, 0.0, Snapping::Unsnapped);
                s.exact_depth = true;
                s.depth_range = [f64::from(d); 2];
                s.depth_test = if clip == ClipDepth::ReversedZeroToOne {
                    DepthTest::Greater
                } else {
                    DepthTest::Less
                };
                s.profile.measured = true;
                s.profile.facing_chain = Some(chain);
                let plain = crate::projection::projection(&s.frustum, clip).unwrap();
                let r = recommend_clip(&s, clip).unwrap();
                let reversed = clip == ClipDepth::ReversedZeroToOne;
                let element = if reversed { 14 } else { 10 };
                let taken = r.matrix[element]
                    .to_bits()
                    .abs_diff(plain[element].to_bits());
                let bits = match format {
                    DepthFormat::Unorm16 => 16,
                    DepthFormat::Unorm24 => 24,
                    _ => 0,
                };
                // The smallest k that passes on the matrix an engine might hold, its
                // shader fusing m10·z + m14 or not.
                let mut need = 0;
                for fused_clip in [false, true] {
                    let chain = DepthChain {
                        fused_clip,
                        ..chain
                    };
                    let stored = |m10: f32, m14: f32, k: u32| {
                        let (a, b) = stepped((m10, m14), reversed, k).unwrap();
                        chain.stored(bits, chain.window_depth(clip, a, b, -d))
                    };
                    for i in 0..5u32 {
                        for j in 0..5u32 {
                            let m10 = f32::from_bits(plain[10].to_bits() + i - 2);
                            let m14 = f32::from_bits(plain[14].to_bits() + j - 2);
                            let base = stored(m10, m14, 0);
                            let k = (1..1 << 16)
                                .find(|&k| {
                                    let s = stored(m10, m14, k);
                                    if reversed {
                                        s > base
                                    } else {
                                        s < base
                                    }
                                })
                                .unwrap();
                            need = need.max(k);
                        }
                    }
                }
                assert!(
                    taken == need || taken == need + 1,
                    "{clip:?} {format:?} d {d}: {taken} steps taken, {need} needed"
                );
            }
        }
    }
}

/// ε, δ and the NDC offset agree through the seed's own equations (4.1.4 and 4.1.7, the
/// latter through `offset::epsilon`, an independent implementation).
#[test]
fn the_forms_of_the_offset_agree_through_the_seed_equations() {
    let s = scene(DepthFormat::Unorm24, 1.0, Snapping::SubpixelBits(8));
    let r = recommend(&s).unwrap();
    let m10 = (1e3 + 1.0) / (1e3 - 1.0);
    assert!((-r.epsilon * m10 - r.ndc_offset).abs() <= 1e-15 * r.ndc_offset);
    assert_eq!(r.ndc_offset, 2.0 * r.window_offset);
    let eps = crate::offset::epsilon(1.0, 1e3, r.delta_at_far, -120.0).unwrap();
    assert!(
        (eps - r.epsilon).abs() <= 1e-12 * r.epsilon.abs(),
        "{eps} vs {}",
        r.epsilon
    );
}

/// The bleed gap is the eye distance whose window-depth difference (Walker's f(d), through
/// `precision::window_depth`) is `2Δw − q` at the far end of the decal.
#[test]
fn the_bleed_gap_spans_twice_the_offset_less_a_quantum_in_window_depth() {
    let s = scene(DepthFormat::Unorm16, 3.0, Snapping::SubpixelBits(8));
    let r = recommend(&s).unwrap();
    let w = |d| crate::precision::window_depth(1.0, 1e3, d).unwrap();
    let dw = w(120.0) - w(120.0 - r.bleed_gap);
    let want = 2.0 * r.window_offset - r.terms.quantum;
    assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
}

/// Terms that the model says vanish do, and the ones that grow with slope do.
#[test]
fn terms_vanish_and_grow_where_the_model_says() {
    let facing = Scene {
        exact_depth: true,
        ..scene(DepthFormat::Float32, 0.0, Snapping::SubpixelBits(8))
    };
    let t = error_terms(&facing).unwrap();
    assert_eq!((t.vertex, t.interpolation, t.snap), (0.0, 0.0, 0.0));
    assert_eq!(
        t.quantum,
        2f64.powi(-24),
        "window depths near 1 have f32 spacing 2^-24"
    );
    let unsnapped = error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::Unsnapped)).unwrap();
    assert_eq!(unsnapped.snap, 0.0);
    let s1 = error_terms(&scene(DepthFormat::Float32, 1.0, Snapping::SubpixelBits(8))).unwrap();
    let s3 = error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::SubpixelBits(8))).unwrap();
    // S grows with the slope and with the axis-crossing tilt (1 + s·e)/d₁.
    let e = 0.577_350_269_189_625_7;
    let want = 3.0 * (1.0 + 3.0 * e) / (1.0 + e);
    assert!((s3.snap / s1.snap - want).abs() < 1e-12);
    assert!(s3.vertex > s1.vertex);
}

fn f32_spacing(w: f64) -> f64 {
    // The gap to the next f32 above w as f32 (w a normal number, not a power of two's edge
    // case: the spacing above and below agree inside a binade).
    let x = w as f32;
    f64::from(f32::from_bits(x.to_bits() + 1)) - f64::from(x)
}

/// `NegOneToOne` through `recommend_clip` is `recommend`'s offset and matrix.
#[test]
fn the_standard_convention_is_unchanged() {
    let s = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
    let r = recommend(&s).unwrap();
    let c = recommend_clip(&s, ClipDepth::NegOneToOne).unwrap();
    assert_eq!(c.ndc_offset, -r.ndc_offset);
    assert_eq!(c.bleed_gap, r.bleed_gap);
    assert_eq!(
        c.matrix,
        crate::offset::epsilon_matrix(&s.frustum, r.epsilon).unwrap()
    );
}

/// Under `[0, 1]` the f32 matrix lowers NDC (= window) depth by at least the window offset
/// and by at most one f32 step of element 10 more; the plain projection is untouched
/// elsewhere. Differences of nearby f32 values are exact in f64.
#[test]
fn zero_to_one_carries_the_window_offset_in_element_10() {
    let s = scene(DepthFormat::Unorm24, 3.0, Snapping::SubpixelBits(8));
    let c = recommend_clip(&s, ClipDepth::ZeroToOne).unwrap();
    let plain = crate::projection::projection(&s.frustum, ClipDepth::ZeroToOne).unwrap();
    let lowered = f64::from(c.matrix[10]) - f64::from(plain[10]);
    let ulp = f64::from(plain[10].abs()) * 2f64.powi(-23);
    assert!(lowered >= c.window_offset && lowered <= c.window_offset + ulp);
    assert_eq!(c.ndc_offset, -c.window_offset);
    assert_eq!(
        (c.relative_epsilon, c.terms.quantum),
        (0.0, 1.0 / 16_777_215.0)
    );
    for i in (0..16).filter(|&i| i != 10) {
        assert_eq!(c.matrix[i], plain[i]);
    }
}

/// Reversed Z, infinite far, D32F: element 10 is 0 and stays 0; element 14 is scaled by at
/// least 1 + ε; and at both ends of the decal (and where `w = n/d` crosses ⅛, a binade
/// edge inside it) the window offset `ε·n/d` beats the f32 spacing there plus the error
/// budget, the spacing taken from the bits of the stored value.
#[test]
fn reversed_infinite_float_beats_the_spacing_everywhere_on_the_decal() {
    let e = 0.5;
    let s = Scene {
        frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
        depth_range: [6.0, 10.0],
        depth_test: DepthTest::Greater,
        ..scene(DepthFormat::Float32, 1.0, Snapping::Unsnapped)
    };
    let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
    let plain = crate::projection::projection(&s.frustum, ClipDepth::ReversedZeroToOne).unwrap();
    assert_eq!((plain[10], c.matrix[10]), (0.0, 0.0));
    assert!(f64::from(c.matrix[14]) / f64::from(plain[14]) - 1.0 >= c.relative_epsilon);
    let t = c.terms;
    let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
    for d in [6.0, 8.0, 10.0] {
        let w = 1.0 / d;
        let need = if d == 8.0 {
            2f64.powi(-26)
        } else {
            f32_spacing(w)
        } + budget;
        assert!(c.relative_epsilon * w >= need, "d = {d}");
    }
    // The binade edge decides: without it the far end alone would ask less.
    let far_only = (f32_spacing(0.1) + budget) * 10.0;
    assert!(c.relative_epsilon > far_only);
}

/// The bleed gap under reversed Z moves the base's window depth (n/d, infinite far) by the
/// offset plus the budget at the decal's far end: `n/(d − G) − n/d`.
#[test]
fn reversed_bleed_gap_spans_the_offset_and_the_budget() {
    let e = 0.5;
    let s = Scene {
        frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
        depth_range: [50.0, 60.0],
        depth_test: DepthTest::Greater,
        ..scene(DepthFormat::Float32, 0.5, Snapping::Unsnapped)
    };
    let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
    let t = c.terms;
    let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
    let dw = 1.0 / (60.0 - c.bleed_gap) - 1.0 / 60.0;
    let want = c.relative_epsilon / 60.0 + budget;
    assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
}

/// Under GL_LEQUAL a tie passes: the offset is one quantum smaller and the gap's window
/// separation one quantum larger than under GL_LESS, for the same terms. The gap is an eye
/// depth (−z) at the same pixel: Walker's window depth through `precision::window_depth`.
#[test]
fn or_equal_tests_trade_a_quantum_of_offset_for_a_quantum_of_gap() {
    let less = scene(DepthFormat::Unorm16, 1.0, Snapping::Unsnapped);
    let lequal = Scene {
        depth_test: DepthTest::LessEqual,
        ..less
    };
    let (a, b) = (recommend(&less).unwrap(), recommend(&lequal).unwrap());
    let q = a.terms.quantum;
    assert!((a.window_offset - b.window_offset - q).abs() <= 1e-12 * q);
    let w = |d| crate::precision::window_depth(1.0, 1e3, d).unwrap();
    let sep = |r: &Recommendation| w(120.0) - w(120.0 - r.bleed_gap);
    let budget = 2.0 * (a.terms.plane + a.terms.snap);
    assert!((sep(&a) - (a.window_offset + budget)).abs() <= 1e-9 * sep(&a));
    assert!((sep(&b) - (b.window_offset + budget + q)).abs() <= 1e-9 * sep(&b));
}

/// A base the rasterizer clips adds the term C, which grows with its reach; one inside the
/// frustum adds nothing. A reach so large that the offset would push the decal past the
/// near plane is refused as unresolvable, never answered.
#[test]
fn the_clip_term_grows_with_the_base_and_is_refused_when_unbounded() {
    let inside = scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped);
    let clipped = |reach| Scene {
        base: Base::Clipped { reach },
        ..inside
    };
    assert_eq!(error_terms(&inside).unwrap().clip, 0.0);
    let (c1, c2) = (
        error_terms(&clipped(1e3)).unwrap().clip,
        error_terms(&clipped(1e4)).unwrap().clip,
    );
    assert!(c1 > 0.0 && c2 > 9.0 * c1, "{c1} {c2}");
    assert!(recommend(&clipped(1e3)).unwrap().window_offset > c1);
    // A costly base is answered, and the bleed gap says what it costs (an occluder in the
    // nearer part of the way to the eye is painted over) ...
    let costly = recommend(&clipped(1e7)).unwrap();
    assert!(costly.bleed_gap > 0.5 * inside.depth_range[1], "{costly:?}");
    // ... until the f32 clipper's error reaches the decal's own distance: refused, and the
    // message says what to do in C and Python.
    let e = recommend(&clipped(1e8)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Domain);
    assert!(
        e.to_string().contains("zshift_clip_to_frustum") && e.to_string().contains("base_reach"),
        "{e}"
    );
}

/// World-space vertices so far from the origin that the offset would push the decal past the
/// near plane are refused as unresolvable, and the message offers what applies to this engine:
/// computing the eye position first only where the shader applies one combined matrix, a
/// probed profile only where none was given.
#[test]
fn the_near_plane_refusal_offers_what_applies() {
    let far_away = |eye_first: bool, measured: bool| {
        let mut s = scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped);
        s.pipeline.world_reach = 1e9;
        s.pipeline.eye_first = eye_first;
        s.profile.measured = measured;
        recommend(&s).unwrap_err()
    };
    for (eye_first, measured) in [(false, false), (false, true), (true, false), (true, true)] {
        let e = far_away(eye_first, measured);
        assert_eq!(e.kind(), ErrorKind::Unresolvable, "{e}");
        let text = e.to_string();
        assert!(text.contains("past the near plane"), "{text}");
        assert_eq!(text.contains("eye_first"), !eye_first, "{text}");
        assert_eq!(text.contains("probed profile"), !measured, "{text}");
        assert!(text.ends_with("or move the near plane out"), "{text}");
    }
}

/// A ground the rasterizer clips, drawn through the view matrix from world space: with the view
/// and the box given, the world rounding grows with the camera's distance from the origin in
/// the vertex term `V`, which pays it at every vertex, and the clipping term `C` keeps only the
/// clipper's own roundings (the rasterizer-made vertices carry no world error beyond `V`'s
/// share): `C` grows by a few hundredths of what `V` gains (only through its smaller
/// denominator), where it grew as much as `V` before.
#[test]
fn the_clipping_term_does_not_count_the_world_rounding_again() {
    let at = |t: f32| {
        let mut s = scene(DepthFormat::Float32, 0.5, Snapping::Unsnapped);
        s.base = Base::Clipped { reach: 1e3 };
        let mut view = [0.0f32; 16];
        (view[0], view[5], view[10], view[15]) = (1.0, 1.0, 1.0, 1.0);
        (view[12], view[13], view[14]) = (-t, -1.7, -t);
        let t = f64::from(t);
        s.pipeline = Pipeline {
            view: Some(view),
            world_box: Some([[t - 1e3, 0.0, t - 1e3], [t + 1e3, 0.0, t + 1e3]]),
            eye_first: true,
            ..Pipeline::default()
        };
        error_terms(&s).unwrap()
    };
    let (near, far) = (at(0.0), at(1e5));
    assert!(far.vertex > 100.0 * near.vertex, "{near:?} {far:?}");
    let grown = |t: fn(&ErrorTerms) -> f64| t(&far) - t(&near);
    assert!(
        grown(|t| t.clip) < 0.03 * grown(|t| t.vertex),
        "{near:?} {far:?}"
    );
}

/// A measured `error_ulps` replaces `T + I` by `k·u·(1 + M)` (`M = w(d₂) + 2·G` without a
/// footprint): the part above `V` doubles with `k`, stays below the bound, and the summary
/// `plane_error` changes nothing.
#[test]
fn measured_error_ulps_scales_the_plane_error() {
    let worst = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
    let with = |k: f64, plane_error: f64| Scene {
        profile: RasterizerProfile {
            error_ulps: k,
            plane_error: [plane_error; 4],
            measured: true,
            ..worst.profile
        },
        ..worst
    };
    let bound = error_terms(&worst).unwrap();
    let a = error_terms(&with(1.4, f64::NAN)).unwrap();
    let b = error_terms(&with(2.8, f64::NAN)).unwrap();
    assert_eq!(
        bound.plane,
        bound.transform + bound.vertex + bound.interpolation
    );
    assert!(a.plane < bound.plane, "{a:?} vs {bound:?}");
    let above = |t: &ErrorTerms| t.plane - t.vertex;
    assert!((above(&b) - 2.0 * above(&a)).abs() <= 1e-12 * above(&b));
    assert_eq!(a, error_terms(&with(1.4, 0.5)).unwrap());
    // A huge figure never exceeds the bound.
    assert_eq!(
        error_terms(&with(1e6, f64::NAN)).unwrap().plane,
        bound.plane
    );
}

/// A facing plane with shared f32 z under GL_LEQUAL needs no offset (the chain is monotone in
/// element 10); under GL_LESS it keeps q + 2E; the gap keeps the occluder's error either way.
#[test]
fn correlated_facing_planes_need_no_offset_under_an_equal_test() {
    let less = Scene {
        exact_depth: true,
        ..scene(DepthFormat::Unorm24, 0.0, Snapping::Unsnapped)
    };
    let lequal = Scene {
        depth_test: DepthTest::LessEqual,
        ..less
    };
    let (a, b) = (recommend(&less).unwrap(), recommend(&lequal).unwrap());
    assert!(!a.terms.correlated && b.terms.correlated);
    assert_eq!((b.window_offset, b.epsilon), (0.0, 0.0));
    assert!((a.window_offset - (a.terms.quantum + 2.0 * a.terms.plane)).abs() < 1e-20);
    assert!(b.bleed_gap > 0.0);
    let reversed = Scene {
        frustum: Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, f64::INFINITY).unwrap(),
        depth_test: DepthTest::GreaterEqual,
        ..lequal
    };
    let r = recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).unwrap();
    assert_eq!(r.relative_epsilon, 0.0);
}

/// A measured facing figure replaces q + 2E for shared-z facing planes under a strict test and
/// [−1, 1] only; never from the worst case, another convention or a sloped plane.
#[test]
fn a_measured_facing_offset_replaces_the_bound_where_measured() {
    let less = Scene {
        exact_depth: true,
        ..scene(DepthFormat::Unorm24, 0.0, Snapping::Unsnapped)
    };
    let measured = Scene {
        profile: RasterizerProfile {
            facing_quanta: [f64::NAN, 3.0, f64::NAN, 3.0],
            measured: true,
            ..less.profile
        },
        ..less
    };
    let q = 1.0 / 16_777_215.0;
    let (a, b) = (recommend(&less).unwrap(), recommend(&measured).unwrap());
    assert!((b.window_offset - 3.0 * q).abs() < 1e-20 && a.window_offset > b.window_offset);
    let float = Scene {
        format: DepthFormat::Float32,
        ..measured
    };
    assert_eq!(
        recommend(&float).unwrap().window_offset,
        3.0 * F32_UNIT_ROUNDOFF
    );
    let zero_to_one = recommend_clip(&measured, ClipDepth::ZeroToOne).unwrap();
    assert_eq!(zero_to_one.terms.facing, 0.0);
    // Reversed Z, D32F: the measured relative ε, over 1 − u for element 14's rounding.
    let reversed = Scene {
        frustum: Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, f64::INFINITY).unwrap(),
        format: DepthFormat::Float32,
        depth_test: DepthTest::Greater,
        profile: RasterizerProfile {
            facing_reversed: 2.5,
            ..measured.profile
        },
        ..measured
    };
    let r = recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).unwrap();
    let want = 2.5 * F32_UNIT_ROUNDOFF / (1.0 - F32_UNIT_ROUNDOFF);
    assert_eq!(r.relative_epsilon, want);
    let unmeasured = Scene {
        profile: RasterizerProfile {
            measured: false,
            ..measured.profile
        },
        ..measured
    };
    assert_eq!(
        recommend(&unmeasured).unwrap().window_offset,
        a.window_offset
    );
}

/// A plane-preserving clipper replaces C by the base's own E + S plus 2 D24 quanta; the
/// polygon-offset units divide by the profile's r.
#[test]
fn near_clip_and_resolvable_enter_where_documented() {
    let clipped = Scene {
        base: Base::Clipped { reach: 1e3 },
        ..scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped)
    };
    let preserving = Scene {
        profile: RasterizerProfile {
            near_clip: NearClip::PlanePreserving,
            resolvable: [2.0; 4],
            ..clipped.profile
        },
        ..clipped
    };
    let (f32c, kept) = (
        error_terms(&clipped).unwrap(),
        error_terms(&preserving).unwrap(),
    );
    assert!((kept.clip - (kept.plane + kept.snap + 2.0 / 16_777_215.0)).abs() < 1e-20);
    assert!(kept.clip < f32c.clip);
    let (a, b) = (
        recommend(&clipped).unwrap(),
        recommend(&preserving).unwrap(),
    );
    let units = |r: &Recommendation, per: f64| r.window_offset / (per * r.terms.quantum);
    assert!((a.polygon_offset[1] - units(&a, 1.0)).abs() <= 1e-9 * a.polygon_offset[1]);
    assert!((b.polygon_offset[1] - units(&b, 2.0)).abs() <= 1e-9 * b.polygon_offset[1]);
    let zero_r = Scene {
        profile: RasterizerProfile {
            resolvable: [0.0; 4],
            ..clipped.profile
        },
        ..clipped
    };
    assert_eq!(recommend(&zero_r).unwrap_err().kind(), ErrorKind::Domain);
}

/// A measured `clip_ulps` `k` sets the clipper's `γ` to `4k·u` where that is below the bound
/// `36u`: C is the bound's over 36/(4k), slightly more as the bound's larger `γ` also shrinks
/// the denominator `d₁ − γR`; a figure above 9 keeps the bound; NaN (not measured) too.
#[test]
fn a_measured_clipper_figure_enters_with_its_margin() {
    let clipped = Scene {
        base: Base::Clipped { reach: 1e3 },
        ..scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped)
    };
    let with = |k: f64| Scene {
        profile: RasterizerProfile {
            measured: true,
            clip_ulps: k,
            ..clipped.profile
        },
        ..clipped
    };
    let c = |s: &Scene| error_terms(s).unwrap().clip;
    let bound = c(&clipped);
    let ratio = bound / c(&with(1.0));
    assert!((9.0..9.0 * 1.01).contains(&ratio), "{ratio}");
    assert_eq!(c(&with(9.5)), bound);
    assert_eq!(c(&with(f64::NAN)), bound);
}

/// The depth test must match the convention; `DepthTest` round-trips GL enums.
#[test]
fn depth_tests_match_their_convention() {
    let s = scene(DepthFormat::Float32, 1.0, Snapping::Unsnapped);
    let reversed = Scene {
        depth_test: DepthTest::GreaterEqual,
        ..s
    };
    assert_eq!(recommend(&reversed).unwrap_err().kind(), ErrorKind::Domain);
    assert_eq!(
        recommend_clip(&s, ClipDepth::ReversedZeroToOne)
            .unwrap_err()
            .kind(),
        ErrorKind::Domain
    );
    assert!(recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).is_ok());
    for t in [
        DepthTest::Less,
        DepthTest::LessEqual,
        DepthTest::Greater,
        DepthTest::GreaterEqual,
    ] {
        assert_eq!(DepthTest::from_gl(t.gl_enum()).unwrap(), t);
    }
    assert!(DepthTest::from_gl(0x0202).is_err()); // GL_EQUAL
}

#[test]
fn bad_scenes_are_refused_with_their_kind() {
    let good = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
    let kind = |s: Scene| recommend(&s).unwrap_err().kind();
    assert_eq!(
        kind(Scene {
            slope: f64::NAN,
            ..good
        }),
        ErrorKind::NotFinite
    );
    assert_eq!(
        kind(Scene {
            slope: -1.0,
            ..good
        }),
        ErrorKind::Domain
    );
    assert_eq!(
        kind(Scene {
            exact_depth: true,
            ..good
        }),
        ErrorKind::Domain
    );
    assert_eq!(
        kind(Scene {
            depth_range: [120.0, 80.0],
            ..good
        }),
        ErrorKind::Domain
    );
    assert_eq!(
        kind(Scene {
            depth_range: [0.5, 80.0],
            ..good
        }),
        ErrorKind::Domain
    );
    assert_eq!(
        kind(Scene {
            viewport: [0, 256],
            ..good
        }),
        ErrorKind::Domain
    );
    assert_eq!(
        kind(Scene {
            profile: RasterizerProfile {
                snapping: Snapping::SubpixelBits(40),
                ..good.profile
            },
            ..good
        }),
        ErrorKind::Domain
    );
}

/// A clipped base whose depth cannot be bounded is refused naming the larger cause: the
/// clipper's rounding of a base that reaches too far (cut it), or the world-space rounding of
/// its vertices near the eye (render relative to the camera, or tell the exact term).
#[test]
fn an_unbounded_clipped_base_names_its_cause() {
    let refused = |reach: f64, world_reach: f64| {
        let mut s = scene(DepthFormat::Float32, 0.5, Snapping::Unsnapped);
        s.base = Base::Clipped { reach };
        s.pipeline = Pipeline {
            world_reach,
            ..Pipeline::default()
        };
        let e = error_terms(&s).unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Domain, "{e}");
        e.to_string()
    };
    let far_base = refused(1e9, 0.0);
    assert!(far_base.contains("the base reaches so far"), "{far_base}");
    let far_world = refused(10.0, 1e11);
    assert!(
        far_world.contains("world-space vertices' f32 rounding"),
        "{far_world}"
    );
    assert!(
        far_world.contains("render relative to the camera"),
        "{far_world}"
    );
}

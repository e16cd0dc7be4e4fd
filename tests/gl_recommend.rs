//! zshift's recommended offset checked on a real rasterizer (headless EGL; Mesa llvmpipe in CI):
//! the coplanar-quads experiment of `zshift-harness` over a small grid of configurations.
//! References are GL readbacks, never zshift's own numbers. Fails (never skips) without GL.
//!
//! The full table: `cargo run --release --example sweep`.

mod gl_common;

use gl_common::{measure, scene_of, setup, snapping_of, Row};
use zshift_harness::{DepthFormat, Gl, Profile};

/// Viewport size of the CI grid (small: llvmpipe on two shared cores).
const SIZE: u32 = 96;

/// The stated factor: on sloped planes the recommended NDC offset is at most this many times
/// the smallest offset that works (bisection over f32 steps of element 10). The model bounds
/// worst cases that rarely line up; the interpolation term's extrapolation across the viewport
/// (llvmpipe evaluates the plane from the framebuffer origin) dominates steep planes near the
/// near plane: 33× at f/n = 10, slope 1, on this 96² grid, where one step works.
const FACTOR_SLOPED: f64 = 40.0;
/// On facing planes the smallest working offset depends on where the plane's depth falls between
/// two stored values (anything in (0, 2q] in NDC), so the recommendation is compared with the
/// worst such phase, one quantum 2q: at most this factor above it (the f32 transform term).
const FACTOR_FACING: f64 = 10.0;

fn context() -> Gl {
    Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"))
}

fn grid(format: DepthFormat) -> Vec<zshift_harness::coplanar::Setup> {
    let mut v = Vec::new();
    for ratio in [10.0, 1e4] {
        for p in [0.2, 0.9] {
            for slope in [0.0, 1.0, 3.0] {
                v.push(setup(format, ratio, p, slope, SIZE));
            }
        }
    }
    v
}

fn rows(format: DepthFormat) -> Vec<Row> {
    let mut gl = context();
    grid(format)
        .into_iter()
        .map(|s| measure(&mut gl, s).unwrap_or_else(|e| panic!("{}: {e}", s.label())))
        .collect()
}

fn check_format(format: DepthFormat) {
    let rows = rows(format);
    let mut sensitive = 0;
    for r in &rows {
        println!("{}", gl_common::format_row(r));
        let label = r.setup.label();
        assert_eq!(
            r.rec.hit, 0,
            "{label}: {} of {} decal pixels lost at the recommendation",
            r.rec.hit, r.rec.of
        );
        assert_eq!(
            r.rec_via_delta.hit, 0,
            "{label}: pixels lost through zshift_load_offset_matrix(delta_at_far, -d2)"
        );
        if r.setup.slope == 0.0 {
            assert!(
                r.none.hit > 0,
                "{label}: a facing decal with no offset must z-fight"
            );
        }
        sensitive += usize::from(r.none.hit > 0);
        let min = r
            .min_ndc
            .unwrap_or_else(|| panic!("{label}: no offset below 2^20 ulps works"));
        assert!(
            r.rec_ndc >= min,
            "{label}: the recommendation works, so it is at least the minimum"
        );
        if r.setup.slope > 0.0 {
            assert!(
                r.rec_ndc <= FACTOR_SLOPED * min,
                "{label}: recommended {:.3e} > {FACTOR_SLOPED} x minimum {min:.3e}",
                r.rec_ndc
            );
        } else {
            let q = 2.0 * r.recommendation.terms.quantum;
            assert!(
                min <= q * (1.0 + 1e-6) + 1.2e-7,
                "{label}: a facing plane needs at most one quantum (+1 ulp of element 10)"
            );
            assert!(
                r.rec_ndc <= FACTOR_FACING * q,
                "{label}: recommended {:.3e} > {FACTOR_FACING} x quantum {q:.3e}",
                r.rec_ndc
            );
        }
    }
    assert!(
        sensitive * 2 > rows.len(),
        "most configurations must z-fight with no offset ({sensitive} of {})",
        rows.len()
    );
}

#[test]
fn d16_no_lost_pixel_at_the_recommendation() {
    check_format(DepthFormat::D16);
}

#[test]
fn d24_no_lost_pixel_at_the_recommendation() {
    check_format(DepthFormat::D24);
}

#[test]
fn d32f_no_lost_pixel_at_the_recommendation() {
    check_format(DepthFormat::D32F);
}

/// The seed's bound (c = 1) loses pixels on D16, as the errata (seed 002) says; the corrected
/// bound (c = 2) loses none on facing planes.
#[test]
fn the_seed_bound_is_too_small_on_d16() {
    let rows = rows(DepthFormat::D16);
    assert!(
        rows.iter().any(|r| r.c1.hit > 0),
        "c = 1 should lose pixels somewhere on D16"
    );
    for r in rows.iter().filter(|r| r.setup.slope == 0.0) {
        assert_eq!(
            r.c2.hit,
            0,
            "{}: c = 2 loses pixels on a facing plane",
            r.setup.label()
        );
    }
}

/// No decal pixel is drawn over an occluder at least the documented gap in front of the base;
/// an occluder a tenth of that gap in front is overdrawn (so the check can fail).
#[test]
fn no_bleed_through_beyond_the_documented_gap() {
    let mut gl = context();
    let snapping = snapping_of(&gl);
    let mut bled_when_close = 0;
    for format in DepthFormat::ALL {
        for s in grid(format) {
            let label = s.label();
            let rec =
                zshift::recommend::recommend(&scene_of(&s, snapping)).expect("recommendation");
            let frustum = gl_common::frustum_of(&s);
            let plain = frustum.to_cols_array().expect("plain");
            let decal = zshift::epsilon_matrix(&frustum, rec.epsilon).expect("decal matrix");
            let mut bench = zshift_harness::coplanar::Bench::new(&mut gl, s, plain).expect("bench");
            let far = bench
                .bleed(&decal, rec.bleed_gap)
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            assert!(far.of > 0, "{label}: the occluder covers no decal pixel");
            assert_eq!(
                far.hit, 0,
                "{label}: {} of {} pixels bleed through an occluder {:.3e} in front",
                far.hit, far.of, rec.bleed_gap
            );
            let near = bench
                .bleed(&decal, rec.bleed_gap / 10.0)
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            bled_when_close += usize::from(near.hit > 0);
        }
    }
    assert!(
        bled_when_close > 0,
        "an occluder at a tenth of the gap never bled: the test cannot fail"
    );
}

/// The C scene of `s` (D24, slope 1, unsnapped, every newer field at its default).
fn c_scene_of(s: &zshift_harness::coplanar::Setup) -> zshift::ffi::ZshiftScene {
    let (l, r, b, t, n, f) = s.frustum();
    let (d1, d2) = s.decal_depth_range();
    zshift::ffi::ZshiftScene {
        pipeline: Default::default(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        l,
        r,
        b,
        t,
        n,
        f,
        viewport_width: SIZE,
        viewport_height: SIZE,
        depth_format: 0x81A6,
        decal_near: d1,
        decal_far: d2,
        slope: 1.0,
        exact_depth: 0,
        subpixel_bits: zshift::ffi::ZSHIFT_SUBPIXEL_UNSNAPPED,
        depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
        base_reach: 0.0,
        profile: std::ptr::null(),
    }
}

/// The C entry points give the Rust recommendation and its matrix bit for bit.
#[test]
fn c_entry_points_match_the_rust_recommendation() {
    use zshift::ffi::*;
    let s = setup(DepthFormat::D24, 1e4, 0.5, 1.0, SIZE);
    let scene = c_scene_of(&s);
    let rust = zshift::recommend::recommend(&scene_of(&s, zshift::recommend::Snapping::Unsnapped))
        .unwrap();
    let mut out = std::mem::MaybeUninit::<ZshiftRecommendation>::uninit();
    assert_eq!(zshift_recommend(&scene, out.as_mut_ptr()), ZSHIFT_OK);
    let out = unsafe { out.assume_init() };
    assert_eq!(
        (out.epsilon, out.bleed_gap, out.delta_at_far),
        (rust.epsilon, rust.bleed_gap, rust.delta_at_far)
    );
    let mut m = [0.0f32; 16];
    assert_eq!(zshift_recommend_matrix(&scene, m.as_mut_ptr()), ZSHIFT_OK);
    assert_eq!(
        m,
        zshift::epsilon_matrix(&gl_common::frustum_of(&s), rust.epsilon).unwrap()
    );
    // Errors leave the output untouched.
    let bad = ZshiftScene {
        depth_format: 0x1234,
        ..scene
    };
    let mut keep = [7.0f32; 16];
    assert_eq!(
        zshift_recommend_matrix(&bad, keep.as_mut_ptr()),
        ZSHIFT_ERR_DOMAIN
    );
    assert_eq!(keep, [7.0; 16]);
    assert_eq!(
        zshift_recommend_matrix(std::ptr::null(), keep.as_mut_ptr()),
        ZSHIFT_ERR_NULL_POINTER
    );
    let tilted_exact = ZshiftScene {
        exact_depth: 1,
        ..scene
    };
    assert_eq!(
        zshift_recommend_matrix(&tilted_exact, keep.as_mut_ptr()),
        ZSHIFT_ERR_DOMAIN
    );
    let nan = ZshiftScene {
        slope: f64::NAN,
        ..scene
    };
    assert_eq!(
        zshift_recommend_matrix(&nan, keep.as_mut_ptr()),
        ZSHIFT_ERR_NOT_FINITE
    );
    assert_eq!(keep, [7.0; 16]);
}

/// The recommendation's glPolygonOffset equivalent works too: the decal drawn with the plain
/// matrix and glPolygonOffset(−factor, −units) loses no pixel.
#[test]
fn the_polygon_offset_equivalent_loses_no_pixel() {
    let mut gl = context();
    let snapping = snapping_of(&gl);
    for format in DepthFormat::ALL {
        for s in grid(format) {
            let rec =
                zshift::recommend::recommend(&scene_of(&s, snapping)).expect("recommendation");
            let [factor, units] = rec.polygon_offset;
            let plain = gl_common::frustum_of(&s).to_cols_array().unwrap();
            let mut bench = zshift_harness::coplanar::Bench::new(&mut gl, s, plain).expect("bench");
            let state = zshift_harness::DrawState {
                polygon_offset: Some((-factor as f32, -units as f32)),
                ..Default::default()
            };
            let lost = bench.lost_with(&plain, &state).unwrap();
            println!(
                "{}: glPolygonOffset(-{factor}, -{units:.2}) lost {}/{}",
                s.label(),
                lost.hit,
                lost.of
            );
            assert_eq!(
                lost.hit,
                0,
                "{}: glPolygonOffset(-{factor}, -{units}) lost {} of {} pixels",
                s.label(),
                lost.hit,
                lost.of
            );
        }
    }
}

/// The C scene's newer fields reach the model with their documented defaults: depth_func 0 is
/// the convention's strict test, GL_LEQUAL gives one quantum less offset, base_reach > 0 adds
/// the clipping term, a profile (from the probe) supplies snapping and r, a zero-filled one is
/// refused, a reversed-Z test under `[−1, 1]`
/// is refused; zshift_clip_to_frustum gives the Rust cut.
#[test]
fn c_scene_fields_reach_the_model() {
    use zshift::ffi::*;
    let s = setup(DepthFormat::D24, 1e4, 0.5, 1.0, SIZE);
    let scene = c_scene_of(&s);
    let rec = |s: &ZshiftScene, clip: ZshiftClip| {
        let mut out = std::mem::MaybeUninit::<ZshiftRecommendation>::uninit();
        let status = zshift_recommend_clip(s, clip, out.as_mut_ptr());
        (
            status,
            (status == ZSHIFT_OK).then(|| unsafe { out.assume_init() }),
        )
    };
    let (_, plain) = rec(&scene, ZSHIFT_CLIP_NEG_ONE_TO_ONE);
    let plain = plain.unwrap();
    let less = ZshiftScene {
        depth_func: ZSHIFT_DEPTH_TEST_LESS,
        ..scene
    };
    assert_eq!(rec(&less, ZSHIFT_CLIP_NEG_ONE_TO_ONE).1.unwrap(), plain);
    let lequal = ZshiftScene {
        depth_func: ZSHIFT_DEPTH_TEST_LEQUAL,
        ..scene
    };
    let le = rec(&lequal, ZSHIFT_CLIP_NEG_ONE_TO_ONE).1.unwrap();
    assert!((plain.window_offset - le.window_offset - plain.quantum).abs() < 1e-9 * plain.quantum);
    let clipped = ZshiftScene {
        base_reach: 1e3,
        ..scene
    };
    let c = rec(&clipped, ZSHIFT_CLIP_NEG_ONE_TO_ONE).1.unwrap();
    assert!(c.clip > 0.0 && c.window_offset > plain.window_offset);
    // A profile supplies every rasterizer fact: its snapping wins over subpixel_bits, its r
    // divides the polygon-offset units.
    let mut record = std::mem::MaybeUninit::<ZshiftProfile>::uninit();
    assert_eq!(zshift_profile_worst_case(record.as_mut_ptr()), ZSHIFT_OK);
    let mut profile = unsafe { record.assume_init() };
    profile.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
    profile.resolvable = [2.0; 4];
    let snapped = ZshiftScene {
        subpixel_bits: 8,
        ..scene
    };
    assert!(rec(&snapped, ZSHIFT_CLIP_NEG_ONE_TO_ONE).1.unwrap().snap > 0.0);
    let profiled = ZshiftScene {
        profile: &profile,
        ..snapped
    };
    let p = rec(&profiled, ZSHIFT_CLIP_NEG_ONE_TO_ONE).1.unwrap();
    assert_eq!((p.snap, p.window_offset), (0.0, plain.window_offset));
    let units = plain.window_offset / (2.0 * plain.quantum);
    assert!((p.polygon_offset_units - units).abs() <= 1e-9 * units);
    let zeroed: ZshiftProfile = unsafe { std::mem::zeroed() };
    for (bad, status) in [
        (
            ZshiftScene {
                depth_func: ZSHIFT_DEPTH_TEST_GREATER,
                ..scene
            },
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            ZshiftScene {
                base_reach: -1.0,
                ..scene
            },
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            ZshiftScene {
                profile: &zeroed,
                ..scene
            },
            ZSHIFT_ERR_DOMAIN,
        ),
    ] {
        assert_eq!(rec(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE).0, status, "{bad:?}");
    }
    // Reversed Z: depth_func 0 means GL_GREATER; GL_LESS is a convention mismatch.
    let float = ZshiftScene {
        depth_format: 0x8CAC,
        ..scene
    };
    assert_eq!(rec(&float, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE).0, ZSHIFT_OK);
    let mismatched = ZshiftScene {
        depth_func: ZSHIFT_DEPTH_TEST_LESS,
        ..float
    };
    assert_eq!(
        rec(&mismatched, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE).0,
        ZSHIFT_ERR_DOMAIN
    );
    // zshift_clip_to_frustum: the Rust cut, vertex for vertex; too small a capacity refused.
    let quad = [
        [-1e3, -1e3, 490.0],
        [1e3, -1e3, 490.0],
        [1e3, 1e3, -510.0],
        [-1e3, 1e3, -510.0],
    ];
    let (l, r, b, t, n, f) = s.frustum();
    let frustum = zshift::Frustum::new(l, r, b, t, n, f).unwrap();
    let want = zshift::recommend::clip_to_frustum(&frustum, &quad).unwrap();
    let flat: Vec<f64> = quad.iter().flatten().copied().collect();
    let mut out = [0.0f64; 30];
    let mut count = 0u32;
    let status = zshift_clip_to_frustum(
        l,
        r,
        b,
        t,
        n,
        f,
        flat.as_ptr(),
        4,
        out.as_mut_ptr(),
        10,
        &mut count,
    );
    assert_eq!(status, ZSHIFT_OK);
    assert_eq!(count as usize, want.len());
    assert!(want.len() >= 3);
    let got: Vec<[f64; 3]> = out[..3 * want.len()]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    assert_eq!(got, want);
    let mut keep = [7.0f64; 6];
    let mut kept = 99u32;
    let status = zshift_clip_to_frustum(
        l,
        r,
        b,
        t,
        n,
        f,
        flat.as_ptr(),
        4,
        keep.as_mut_ptr(),
        2,
        &mut kept,
    );
    assert_eq!((status, kept, keep), (ZSHIFT_ERR_DOMAIN, 99, [7.0; 6]));
    // zshift_clip_to_frustum_stored: the Rust stored cut, vertex for vertex (world space 10⁴
    // from the origin, the view given: inside the plain cut); NULL pipeline and a view without
    // its box refused, the outputs untouched.
    let view: [f32; 16] = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1e4, 0.0, -1e4, 1.0,
    ];
    let stored = ZshiftPipeline {
        eye_first: 1,
        view_matrix: view.as_ptr(),
        world_box: [9e3, -1e3, 9e3, 11e3, 1e3, 11e3],
        ..ZshiftPipeline::default()
    };
    let pipeline = zshift::model::Pipeline {
        eye_first: true,
        view: Some(view),
        world_box: Some([[9e3, -1e3, 9e3], [11e3, 1e3, 11e3]]),
        ..zshift::model::Pipeline::default()
    };
    let want_stored =
        zshift::recommend::clip_to_frustum_stored(&frustum, &quad, &pipeline).unwrap();
    assert_ne!(
        want_stored, want,
        "stored 10⁴ from the origin, the cut moves inward"
    );
    let status = zshift_clip_to_frustum_stored(
        l,
        r,
        b,
        t,
        n,
        f,
        &stored,
        flat.as_ptr(),
        4,
        out.as_mut_ptr(),
        10,
        &mut count,
    );
    assert_eq!(status, ZSHIFT_OK);
    let got: Vec<[f64; 3]> = out[..3 * count as usize]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    assert_eq!(got, want_stored);
    let no_box = ZshiftPipeline {
        world_box: [0.0; 6],
        ..stored
    };
    for (p, status) in [
        (std::ptr::null(), ZSHIFT_ERR_NULL_POINTER),
        (&no_box as *const ZshiftPipeline, ZSHIFT_ERR_DOMAIN),
    ] {
        let got = zshift_clip_to_frustum_stored(
            l,
            r,
            b,
            t,
            n,
            f,
            p,
            flat.as_ptr(),
            4,
            keep.as_mut_ptr(),
            10,
            &mut kept,
        );
        assert_eq!((got, kept, keep), (status, 99, [7.0; 6]));
    }
}

/// Under 4× MSAA every sample is tested against its own interpolated depth: the decal drawn at
/// the recommendation over its base into a multisampled target of each format loses no sample
/// (each sample read back on its own), where the plain matrix loses some.
#[test]
fn every_msaa_sample_keeps_the_decal() {
    use zshift_harness::coplanar::{BASE, CLEAR, DECAL};
    use zshift_harness::edges::{Msaa, SIZE as MSAA_SIZE};
    let mut gl = context();
    let snapping = snapping_of(&gl);
    let always = zshift_harness::DrawState {
        depth_func: glow::ALWAYS,
        ..Default::default()
    };
    let less = zshift_harness::DrawState::default();
    let decal_colour = [255, 0, 0];
    let (mut scenes, mut samples, mut plain_lost) = (0, 0, 0);
    for format in DepthFormat::ALL {
        gl.set_target(MSAA_SIZE, MSAA_SIZE, format).unwrap();
        let msaa = Msaa::new(&gl, format, 4);
        for ratio in [10.0, 1e4] {
            for p in [0.2, 0.9] {
                for slope in [0.0, 1.0, 3.0] {
                    let s = setup(format, ratio, p, slope, MSAA_SIZE);
                    let rec = zshift::recommend::recommend(&scene_of(&s, snapping))
                        .unwrap_or_else(|e| panic!("{}: {e}", s.label()));
                    let frustum = gl_common::frustum_of(&s);
                    let plain = frustum.to_cols_array().unwrap();
                    let matrix = zshift::epsilon_matrix(&frustum, rec.epsilon).unwrap();
                    // The decal's samples, drawn alone.
                    msaa.bind(&gl);
                    gl.clear(CLEAR, 1.0).unwrap();
                    gl.draw_quad(&s.decal(), &matrix, DECAL, &always).unwrap();
                    let mask: Vec<bool> = msaa
                        .read_samples(&gl)
                        .iter()
                        .map(|c| c[..3] == decal_colour)
                        .collect();
                    let mut lost_at = |decal: &[f32; 16]| -> usize {
                        msaa.bind(&gl);
                        gl.clear(CLEAR, 1.0).unwrap();
                        gl.draw_quad(&s.base(), &plain, BASE, &less).unwrap();
                        gl.draw_quad(&s.decal(), decal, DECAL, &less).unwrap();
                        msaa.read_samples(&gl)
                            .iter()
                            .zip(&mask)
                            .filter(|(c, &m)| m && c[..3] != decal_colour)
                            .count()
                    };
                    let lost = lost_at(&matrix);
                    plain_lost += lost_at(&plain);
                    assert_eq!(
                        lost,
                        0,
                        "{}: {lost} of {} decal samples lost under 4x MSAA",
                        s.label(),
                        mask.iter().filter(|&&m| m).count()
                    );
                    scenes += 1;
                    samples += mask.iter().filter(|&&m| m).count();
                }
            }
        }
        msaa.delete(&gl);
    }
    println!("4x MSAA: {scenes} scenes, {samples} decal samples, 0 lost at the recommendation; {plain_lost} lost with the plain matrix");
    assert!(
        plain_lost > 0,
        "no sample lost without an offset: the check cannot fail"
    );
}

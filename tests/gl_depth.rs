//! The depth readback confirms the precision formulas (seed 001) and the f32 transform term of
//! the recommendation's error model (`src/recommend/`). Measured on llvmpipe:
//!
//! * D16: `glReadPixels(GL_DEPTH_COMPONENT)` is within half a quantum of `zshift_window_depth`,
//!   and facing planes one `zshift_depth_resolution` apart always sort; a quarter step apart
//!   they tie at some depths.
//! * D24 and D32F: the f32 vertex transform (`T`, about 2⁻²⁴ per rounding) is as large as the
//!   24-bit quantum, so the readback is within `q/2 + T` (up to ~2 quanta), and planes one
//!   24-bit step apart do not always sort; planes `q + 2T` apart in window depth always do.
//!
//! Fails (never skips) without GL.

mod gl_common;

use zshift::ffi::{zshift_depth_resolution, zshift_frustum, zshift_window_depth, ZSHIFT_OK};
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Profile, Quad};

const SIZE: u32 = 32;
const TAN_HALF: f64 = 0.5773502691896257;

fn context() -> Gl {
    Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"))
}

fn projection(n: f64, f: f64) -> [f32; 16] {
    let e = n * TAN_HALF;
    let mut m = [0.0f32; 16];
    assert_eq!(
        zshift_frustum(-e, e, -e, e, n, f, m.as_mut_ptr()),
        ZSHIFT_OK
    );
    m
}

/// A facing quad filling the viewport at eye distance `d` (as f32), and that f32 distance.
fn facing(d: f64) -> (Quad, f64) {
    let z = -d as f32;
    let x = (2.0 * d * TAN_HALF) as f32;
    (Quad::rect(-x, x, -x, x, z), -f64::from(z))
}

/// One stored step of the format at window depth `w`: 1/(2^m − 1), or the f32 spacing at `w`.
fn quantum(format: DepthFormat, w: f64) -> f64 {
    match format {
        DepthFormat::D16 => 1.0 / 65535.0,
        DepthFormat::D24 => 1.0 / 16777215.0,
        DepthFormat::D32F => 2f64.powi(w.log2().floor() as i32 - 23),
    }
}

fn window_depth(n: f64, f: f64, d: f64) -> f64 {
    let mut w = 0.0;
    assert_eq!(zshift_window_depth(n, f, d, &mut w), ZSHIFT_OK);
    w
}

#[test]
fn depth_readback_matches_window_depth_within_the_quantum_and_transform_error() {
    let mut gl = context();
    let mut worst = [0.0f64; 3];
    for format in DepthFormat::ALL {
        gl.set_target(SIZE, SIZE, format).expect("target");
        for ratio in [10.0, 1e3, 1e6] {
            let m = projection(1.0, ratio);
            for p in [0.001, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
                let (quad, d) = facing(1.0 + p * (ratio - 1.0));
                gl.clear([0.0; 4], 1.0).unwrap();
                gl.draw_quad(&quad, &m, [1.0; 4], &DrawState::default())
                    .unwrap();
                let depth = gl.read_depth().unwrap();
                let read = f64::from(depth[(SIZE * SIZE / 2 + SIZE / 2) as usize]);
                let expect = window_depth(1.0, ratio, d);
                let q = quantum(format, expect);
                let err = (read - expect).abs();
                let bound = match format {
                    DepthFormat::D16 => q,
                    _ => 0.5 * q + transform_term(ratio, d),
                };
                worst[format as usize] = worst[format as usize].max(err / q);
                println!("{format:?} f/n={ratio:e} d={d:.6e}: read {read:.9} window_depth {expect:.9} ({:.2} quanta, bound {:.2})", err / q, bound / q);
                assert!(err <= bound, "{format:?} f/n={ratio} d={d}: read {read} vs window_depth {expect}: {:.2} quanta apart", err / q);
            }
        }
    }
    println!("largest readback difference in quanta (D16, D24, D32F): {worst:.2?}");
}

/// The model's per-vertex f32 transform bound `T` at distance `d` (window depth).
fn transform_term(ratio: f64, d: f64) -> f64 {
    let e = TAN_HALF;
    let scene = zshift::recommend::Scene {
        pipeline: Default::default(),
        footprint: None,
        frustum: zshift::Frustum::new(-e, e, -e, e, 1.0, ratio).unwrap(),
        viewport: [SIZE, SIZE],
        format: zshift::recommend::DepthFormat::Float32,
        depth_range: [d, d],
        slope: 0.0,
        exact_depth: true,
        depth_test: zshift::recommend::DepthTest::Less,
        base: zshift::recommend::Base::InsideFrustum,
        profile: zshift::recommend::RasterizerProfile {
            snapping: zshift::recommend::Snapping::Unsnapped,
            ..Default::default()
        },
    };
    zshift::recommend::error_terms(&scene).unwrap().transform
}

/// Draws the far plane then the near one (and the reverse) with GL_LESS; true when the near one
/// covers every pixel both times.
fn sorts(gl: &mut Gl, m: &[f32; 16], far: f64, near: f64) -> bool {
    let (far_q, _) = facing(far);
    let (near_q, _) = facing(near);
    let (red, blue) = ([1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]);
    let mut ok = true;
    for order in [
        [(&far_q, blue), (&near_q, red)],
        [(&near_q, red), (&far_q, blue)],
    ] {
        gl.clear([0.0; 4], 1.0).unwrap();
        for (q, c) in order {
            gl.draw_quad(q, m, c, &DrawState::default()).unwrap();
        }
        let image = gl.read_color().unwrap();
        ok &= image.count(rgba8(red), None) == image.pixels.len();
    }
    ok
}

#[test]
fn d16_planes_a_depth_resolution_apart_sort_and_a_fraction_apart_do_not() {
    let mut gl = context();
    for (format, bits) in [(DepthFormat::D16, 16)] {
        gl.set_target(SIZE, SIZE, format).expect("target");
        for ratio in [10.0, 1e3, 1e5] {
            let m = projection(1.0, ratio);
            let mut fraction_failed = 0;
            let depths: Vec<f64> = (1..=12)
                .map(|i| 1.0 + (i as f64 / 13.0) * (ratio - 1.0))
                .collect();
            for &d in &depths {
                let (_, d) = facing(d);
                let mut step = 0.0;
                assert_eq!(
                    zshift_depth_resolution(1.0, ratio, bits, d, &mut step),
                    ZSHIFT_OK
                );
                let full = sorts(&mut gl, &m, d, d - step);
                println!(
                    "{format:?} f/n={ratio:e} d={d:.4e} step {step:.3e}: sorts at 1 step {full}"
                );
                assert!(full, "{format:?} f/n={ratio} d={d}: planes {step:e} apart (one depth step) do not sort");
                fraction_failed += usize::from(!sorts(&mut gl, &m, d, d - 0.25 * step));
            }
            assert!(fraction_failed > 0, "{format:?} f/n={ratio}: planes a quarter step apart always sorted: the step is not the resolution");
        }
    }
}

/// Walker's step generalised to a window-depth difference `dw` (seed 001, eq. 3 with Δf = dw):
/// `Δd = dw·d² / (b + dw·d)`, `b = f·n/(f − n)`.
fn walker_step(n: f64, f: f64, dw: f64, d: f64) -> f64 {
    let b = f * n / (f - n);
    dw * d * d / (b + dw * d)
}

/// D24: one 24-bit step is not always enough (the f32 transform error is as large), a window
/// difference of `q + 2T` always is, and a quarter step ties somewhere.
#[test]
fn d24_planes_sort_at_the_quantum_plus_transform_error() {
    let mut gl = context();
    gl.set_target(SIZE, SIZE, DepthFormat::D24).expect("target");
    let q = 1.0 / 16777215.0;
    let (mut one_step_failures, mut total) = (0, 0);
    for ratio in [10.0, 1e3, 1e5] {
        let m = projection(1.0, ratio);
        let mut fraction_failed = 0;
        for i in 1..=12 {
            let (_, d) = facing(1.0 + (i as f64 / 13.0) * (ratio - 1.0));
            let mut step = 0.0;
            assert_eq!(
                zshift_depth_resolution(1.0, ratio, 24, d, &mut step),
                ZSHIFT_OK
            );
            total += 1;
            one_step_failures += usize::from(!sorts(&mut gl, &m, d, d - step));
            let wide = walker_step(1.0, ratio, q + 2.0 * transform_term(ratio, d), d);
            assert!(
                sorts(&mut gl, &m, d, d - wide),
                "D24 f/n={ratio} d={d}: planes {wide:e} apart (q + 2T) do not sort"
            );
            fraction_failed += usize::from(!sorts(&mut gl, &m, d, d - 0.25 * step));
        }
        assert!(
            fraction_failed > 0,
            "D24 f/n={ratio}: planes a quarter step apart always sorted"
        );
    }
    println!("D24: planes one depth_resolution apart failed to sort at {one_step_failures} of {total} depths");
}

/// The recommendation's per-quad error model checked pixel by pixel on sloped planes (D32F, so
/// storage adds at most half an f32 step): every depth read back lies within
/// `q/2 + T + V + I` of the exact plane's window depth along that pixel centre's line of sight.
#[test]
fn sloped_plane_depth_stays_within_the_models_per_quad_bound() {
    use zshift_harness::coplanar::Setup;
    let mut gl = context();
    let mut worst = 0.0f64;
    for ratio in [10.0, 1e3, 1e6] {
        for p in [0.2, 0.9] {
            for slope in [0.3, 1.0, 3.0] {
                let s = Setup {
                    n: 1.0,
                    f: ratio,
                    tan_half: TAN_HALF,
                    size: 64,
                    format: DepthFormat::D32F,
                    depth_fraction: p,
                    slope,
                };
                let m = projection(1.0, ratio);
                gl.set_target(s.size, s.size, s.format).unwrap();
                gl.clear([0.0; 4], 1.0).unwrap();
                gl.draw_quad(&s.base(), &m, [1.0; 4], &DrawState::default())
                    .unwrap();
                let depth = gl.read_depth().unwrap();
                // The base spans the plane's visible depth range; bound its terms over it.
                let (mut d_near, mut d_far) = (f64::MAX, 0.0f64);
                for c in s.base().corners {
                    let d = -f64::from(c[2]);
                    d_near = d_near.min(d);
                    d_far = d_far.max(d);
                }
                let e = TAN_HALF;
                let scene = zshift::recommend::Scene {
                    pipeline: Default::default(),
                    footprint: None,
                    frustum: zshift::Frustum::new(-e, e, -e, e, 1.0, ratio).unwrap(),
                    viewport: [s.size, s.size],
                    format: zshift::recommend::DepthFormat::Float32,
                    depth_range: [d_near, d_far],
                    slope,
                    exact_depth: false,
                    depth_test: zshift::recommend::DepthTest::Less,
                    base: zshift::recommend::Base::InsideFrustum,
                    profile: zshift::recommend::RasterizerProfile {
                        snapping: gl_common::snapping_of(&gl),
                        ..Default::default()
                    },
                };
                let t = zshift::recommend::error_terms(&scene).unwrap();
                // The exact plane is through the unsnapped vertices: a snapping rasterizer's
                // plane is off it by `S` (0 on llvmpipe).
                let per_quad = 0.5 * t.quantum + t.transform + t.vertex + t.interpolation + t.snap;
                let size = s.size as usize;
                let covered = depth.iter().filter(|&&r| r < 1.0).count();
                assert!(
                    covered > 100,
                    "{}: the base covers only {covered} pixels",
                    s.label()
                );
                for (i, &read) in depth.iter().enumerate().filter(|(_, &r)| r < 1.0) {
                    let y_ndc = 2.0 * ((i / size) as f64 + 0.5) / size as f64 - 1.0;
                    let d = s.axis_depth() / (1.0 + slope * y_ndc * TAN_HALF);
                    let err = (f64::from(read) - window_depth(1.0, ratio, d)).abs();
                    worst = worst.max(err / per_quad);
                    assert!(err <= per_quad, "{} pixel {i}: depth {read} is {err:e} from the plane's, above the model's {per_quad:e}", s.label());
                }
            }
        }
    }
    println!("largest per-pixel error as a fraction of the model's per-quad bound: {worst:.2}");
}

/// The slope term's window-depth gradient per pixel (`recommend::window_gradient`) is what the
/// rasterizer draws: the read-back depth of a tilted plane changes by that much per row.
#[test]
fn window_gradient_matches_the_rendered_depth_slope() {
    use zshift_harness::coplanar::Setup;
    let mut gl = context();
    for (ratio, p, slope) in [
        (10.0, 0.2, 3.0),
        (1e3, 0.5, 1.0),
        (1e3, 0.2, 3.0),
        (1e4, 0.1, 0.3),
    ] {
        let s = Setup {
            n: 1.0,
            f: ratio,
            tan_half: TAN_HALF,
            size: 128,
            format: DepthFormat::D32F,
            depth_fraction: p,
            slope,
        };
        gl.set_target(s.size, s.size, s.format).unwrap();
        gl.clear([0.0; 4], 1.0).unwrap();
        gl.draw_quad(
            &s.base(),
            &projection(1.0, ratio),
            [1.0; 4],
            &DrawState::default(),
        )
        .unwrap();
        let depth = gl.read_depth().unwrap();
        let (c, size) = (64usize, 128usize);
        // Window depth is affine in window coordinates over a plane: average over 20 rows.
        let measured =
            f64::from(depth[(c - 10) * size + c] - depth[(c + 10) * size + c]).abs() / 20.0;
        let e = TAN_HALF;
        let scene = zshift::recommend::Scene {
            pipeline: Default::default(),
            footprint: None,
            frustum: zshift::Frustum::new(-e, e, -e, e, 1.0, ratio).unwrap(),
            viewport: [128, 128],
            format: zshift::recommend::DepthFormat::Float32,
            depth_range: [s.axis_depth(), s.axis_depth()],
            slope,
            exact_depth: false,
            depth_test: zshift::recommend::DepthTest::Less,
            base: zshift::recommend::Base::InsideFrustum,
            profile: zshift::recommend::RasterizerProfile {
                snapping: zshift::recommend::Snapping::SubpixelBits(8),
                ..Default::default()
            },
        };
        let [_, gy] = zshift::recommend::window_gradient(&scene, s.axis_depth()).unwrap();
        println!(
            "{}: rendered {measured:.6e} per row, window_gradient {gy:.6e}",
            s.label()
        );
        assert!(
            (measured - gy).abs() <= 0.01 * gy + 4e-7,
            "{}: rendered {measured:e} vs model {gy:e}",
            s.label()
        );
    }
}

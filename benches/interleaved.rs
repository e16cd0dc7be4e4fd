//! The Rust side of the CPU comparison, timed the way benches/cpp/glm_bench.cpp times the C++
//! side: batches of every variant interleaved round by round, so that a machine shared with
//! other jobs loads them alike, and the median batch reported. Criterion (benches/cpu.rs) times
//! one variant after another, which on a busy machine can move a ratio by 2×.
//!
//! `cargo bench --bench interleaved` prints one JSON object: median ns per call of each variant
//! (the same case as benches/cpu.rs). `scripts/report` puts it in docs/report.md.

use std::hint::black_box;
use std::time::Instant;

#[path = "shared/seed.rs"]
mod seed;

const CALLS: u32 = 100_000;
const ROUNDS: usize = 41;

/// Nanoseconds per call of `body` over one batch. zshift's Rust calls are unwrapped, as
/// benches/cpu.rs does and a caller would: black-boxing the whole `Result<Mat4>` times a copy
/// of the enum through memory (a store-forwarding stall) that no caller makes.
fn batch<T>(mut body: impl FnMut() -> T) -> f64 {
    let start = Instant::now();
    for _ in 0..CALLS {
        black_box(body());
    }
    start.elapsed().as_nanos() as f64 / f64::from(CALLS)
}

/// One variant: a closure that times one batch.
type Batch<'a> = Box<dyn FnMut() -> f64 + 'a>;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    // `cargo test --all-targets` runs benches with --bench absent; time only when asked.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let (l, r, b, t, n, f, pz) = (-0.0577, 0.0577, -0.0414, 0.0414, 0.1, 1000.0, -50.0);
    let delta = 4.0 * zshift::min_delta_toward(n, f, 24, pz).expect("valid case");
    let frustum = zshift::Frustum::new(l, r, b, t, n, f).expect("valid case");
    let v = |x: f64| black_box(x);
    let glam = || {
        glam::camera::rh::proj::opengl::frustum(
            v(l) as f32,
            v(r) as f32,
            v(b) as f32,
            v(t) as f32,
            v(n) as f32,
            v(f) as f32,
        )
    };
    let mut out = [0.0f32; 16];
    let mut variants: Vec<(&str, Batch)> = vec![
        ("glam_frustum", Box::new(|| batch(glam))),
        (
            "glam_frustum_seed_tweak",
            Box::new(|| {
                batch(|| {
                    let mut m = glam();
                    let eps = seed::seed_epsilon(v(n), v(f), v(delta) as f32, v(pz) as f32);
                    m.z_axis.z = seed::seed_tweak(m.z_axis.z, eps);
                    m
                })
            }),
        ),
        (
            "zshift_frustum",
            Box::new(|| {
                batch(|| zshift::frustum(v(l), v(r), v(b), v(t), v(n), v(f)).expect("valid case"))
            }),
        ),
        (
            "zshift_load_offset_matrix",
            Box::new(|| {
                batch(|| {
                    zshift::load_offset_matrix(v(l), v(r), v(b), v(t), v(n), v(f), v(delta), v(pz))
                        .expect("valid case")
                })
            }),
        ),
        (
            "zshift_frustum_c_abi",
            Box::new(move || {
                batch(|| {
                    let s = zshift::ffi::zshift_frustum(
                        v(l),
                        v(r),
                        v(b),
                        v(t),
                        v(n),
                        v(f),
                        out.as_mut_ptr(),
                    );
                    black_box(&out);
                    s
                })
            }),
        ),
        (
            "zshift_offset_matrix_c_abi",
            Box::new(move || {
                // The front door: the engine's own matrix in (glam's, as above), element 10 out.
                let engine = glam().to_cols_array();
                batch(|| {
                    let s = zshift::ffi::zshift_offset_matrix(
                        black_box(engine.as_ptr()),
                        zshift::ffi::ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                        v(delta),
                        v(-pz),
                        out.as_mut_ptr(),
                    );
                    black_box(&out);
                    s
                })
            }),
        ),
        (
            "zshift_ortho_c_abi",
            Box::new(move || {
                batch(|| {
                    let s = zshift::ffi::zshift_ortho(
                        v(-4.0),
                        v(4.0),
                        v(-2.25),
                        v(2.25),
                        v(0.5),
                        v(100.0),
                        zshift::ffi::ZSHIFT_CLIP_NEG_ONE_TO_ONE,
                        out.as_mut_ptr(),
                    );
                    black_box(&out);
                    s
                })
            }),
        ),
        (
            "zshift_recommend_epsilon_matrix",
            Box::new(|| {
                batch(|| {
                    let scene = zshift::recommend::Scene {
                        footprint: None,
                        frustum: black_box(frustum),
                        viewport: [1920, 1080],
                        format: zshift::recommend::DepthFormat::Unorm24,
                        depth_range: [v(-pz), -pz],
                        slope: v(1.0),
                        exact_depth: false,
                        depth_test: zshift::recommend::DepthTest::Less,
                        base: zshift::recommend::Base::InsideFrustum,
                        profile: zshift::recommend::RasterizerProfile {
                            snapping: zshift::recommend::Snapping::SubpixelBits(8),
                            ..Default::default()
                        },
                    };
                    let rec = zshift::recommend::recommend(&scene).expect("valid scene");
                    zshift::epsilon_matrix(&frustum, rec.epsilon).expect("valid case")
                })
            }),
        ),
    ];
    let mut times = vec![Vec::new(); variants.len()];
    for round in 0..ROUNDS + 2 {
        for (i, (_, run)) in variants.iter_mut().enumerate() {
            let ns = run();
            if round >= 2 {
                times[i].push(ns); // the first two rounds warm caches and clocks
            }
        }
    }
    // Ratios round by round (the two sides under the same load), then their median.
    let ratio =
        |a: usize, b: usize| median(times[a].iter().zip(&times[b]).map(|(x, y)| x / y).collect());
    let ratios = [
        ("ratio_frustum_to_glam", ratio(2, 0)),
        ("ratio_offset_to_glam_tweak", ratio(3, 1)),
    ];
    let fields: Vec<String> = variants
        .iter()
        .map(|(name, _)| *name)
        .zip(times.iter().map(|t| median(t.clone())))
        .chain(ratios)
        .map(|(name, value)| format!("\"{name}\": {value:.3}"))
        .collect();
    println!("{{{}}}", fields.join(", "));
}

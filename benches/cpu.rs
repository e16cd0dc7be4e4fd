//! CPU cost of building a depth-offset projection matrix, every way an engine might: zshift
//! through its Rust API and its C ABI, glam's `glFrustum` builder (plain, and with the seed's
//! f32 tweak), and the seed's own path on Mesa (compatibility profile: `glFrustum` +
//! `glGetFloatv` + the `m[10]` tweak + `glLoadMatrixf`) beside zshift + `glLoadMatrixf`.
//!
//! `cargo bench --bench cpu`; `scripts/report` runs it and turns the medians into ratios
//! (docs/report.md). GLM's `glm::frustum` is timed by the C++ harness in benches/cpp/.
//! The Mesa benches need a GL context (EGL surfaceless); without one they fail with the reason.

use std::ffi::c_void;
use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use zshift_harness::{DepthFormat, Gl, Profile};

#[path = "shared/seed.rs"]
mod seed;

/// One ordinary engine case: a 60° × 45° frustum, n = 0.1, f = 1000, a decal at 50 units,
/// shifted by 4 depth steps of a 24-bit buffer.
struct Case {
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    n: f64,
    f: f64,
    delta: f64,
    pz: f64,
}

fn case() -> Case {
    let (n, f, pz) = (0.1, 1000.0, -50.0);
    let delta = 4.0 * zshift::min_delta_toward(n, f, 24, pz).expect("valid case");
    Case {
        l: -0.0577,
        r: 0.0577,
        b: -0.0414,
        t: 0.0414,
        n,
        f,
        delta,
        pz,
    }
}

fn cpu_builders(c: &mut Criterion) {
    let k = case();
    let mut g = c.benchmark_group("offset_matrix");
    g.bench_function("zshift_rust", |b| {
        b.iter(|| {
            zshift::load_offset_matrix(
                black_box(k.l),
                black_box(k.r),
                black_box(k.b),
                black_box(k.t),
                black_box(k.n),
                black_box(k.f),
                black_box(k.delta),
                black_box(k.pz),
            )
            .unwrap()
        })
    });
    g.bench_function("zshift_c_abi", |b| {
        let mut out = [0.0f32; 16];
        b.iter(|| {
            let status = zshift::ffi::zshift_load_offset_matrix(
                black_box(k.l),
                black_box(k.r),
                black_box(k.b),
                black_box(k.t),
                black_box(k.n),
                black_box(k.f),
                black_box(k.delta),
                black_box(k.pz),
                black_box(out.as_mut_ptr()),
            );
            black_box(&out);
            status
        })
    });
    g.bench_function("zshift_recommend_epsilon_matrix", |b| {
        let frustum = zshift::Frustum::new(k.l, k.r, k.b, k.t, k.n, k.f).unwrap();
        b.iter(|| {
            let scene = zshift::recommend::Scene {
                pipeline: Default::default(),
                footprint: None,
                frustum: black_box(frustum),
                viewport: [1920, 1080],
                format: zshift::recommend::DepthFormat::Unorm24,
                depth_range: [black_box(-k.pz), -k.pz],
                slope: black_box(1.0),
                exact_depth: false,
                depth_test: zshift::recommend::DepthTest::Less,
                base: zshift::recommend::Base::InsideFrustum,
                profile: zshift::recommend::RasterizerProfile {
                    snapping: zshift::recommend::Snapping::SubpixelBits(8),
                    ..Default::default()
                },
            };
            let rec = zshift::recommend::recommend(&scene).unwrap();
            zshift::epsilon_matrix(&frustum, rec.epsilon).unwrap()
        })
    });
    g.bench_function("zshift_frustum_plain", |b| {
        b.iter(|| {
            zshift::frustum(
                black_box(k.l),
                black_box(k.r),
                black_box(k.b),
                black_box(k.t),
                black_box(k.n),
                black_box(k.f),
            )
            .unwrap()
        })
    });
    g.bench_function("zshift_frustum_c_abi", |b| {
        let mut out = [0.0f32; 16];
        b.iter(|| {
            let status = zshift::ffi::zshift_frustum(
                black_box(k.l),
                black_box(k.r),
                black_box(k.b),
                black_box(k.t),
                black_box(k.n),
                black_box(k.f),
                black_box(out.as_mut_ptr()),
            );
            black_box(&out);
            status
        })
    });
    g.bench_function("glam_frustum_plain", |b| {
        b.iter(|| glam_frustum(&k, black_box(1.0)))
    });
    g.bench_function("glam_frustum_seed_tweak", |b| {
        b.iter(|| {
            let mut m = glam_frustum(&k, black_box(1.0)).to_cols_array();
            let eps = seed::seed_epsilon(
                black_box(k.n),
                black_box(k.f),
                black_box(k.delta as f32),
                black_box(k.pz as f32),
            );
            m[10] = seed::seed_tweak(m[10], eps);
            m
        })
    });
    g.finish();
}

/// glam's `glFrustum` equivalent (glam 0.34: `camera::rh::proj::opengl::frustum`; the old
/// `Mat4::frustum_rh_gl` is deprecated). f32 in, as glam takes it. `scale` is a black-boxed 1
/// so the inputs are not constant-folded.
fn glam_frustum(k: &Case, scale: f32) -> glam::Mat4 {
    glam::camera::rh::proj::opengl::frustum(
        k.l as f32 * scale,
        k.r as f32 * scale,
        k.b as f32 * scale,
        k.t as f32 * scale,
        k.n as f32 * scale,
        k.f as f32 * scale,
    )
}

type MatrixMode = extern "system" fn(u32);
type Frustum = extern "system" fn(f64, f64, f64, f64, f64, f64);
type LoadIdentity = extern "system" fn();
type GetFloatv = extern "system" fn(u32, *mut f32);
type LoadMatrixf = extern "system" fn(*const f32);

/// The fixed-function entry points the seed calls, straight from the driver (no glGetError
/// per call; errors are checked once after each bench).
struct Legacy {
    matrix_mode: MatrixMode,
    load_identity: LoadIdentity,
    frustum: Frustum,
    get_floatv: GetFloatv,
    load_matrixf: LoadMatrixf,
}

const GL_PROJECTION: u32 = 0x1701;
const GL_PROJECTION_MATRIX: u32 = 0x0BA7;

fn entry<F: Copy>(gl: &Gl, name: &str) -> F {
    let p = gl.proc_address(name);
    assert!(!p.is_null(), "the driver does not export {name}");
    assert_eq!(
        std::mem::size_of::<F>(),
        std::mem::size_of::<*const c_void>()
    );
    // SAFETY: `name` is a GL entry point whose C signature is F; the context outlives the use.
    unsafe { std::mem::transmute_copy(&p) }
}

fn mesa_paths(c: &mut Criterion) {
    let mut gl = Gl::new(Profile::Compatibility)
        .unwrap_or_else(|e| panic!("no compatibility GL context for the Mesa benches: {e}"));
    gl.set_target(16, 16, DepthFormat::D24).expect("target");
    let fx = Legacy {
        matrix_mode: entry(&gl, "glMatrixMode"),
        load_identity: entry(&gl, "glLoadIdentity"),
        frustum: entry(&gl, "glFrustum"),
        get_floatv: entry(&gl, "glGetFloatv"),
        load_matrixf: entry(&gl, "glLoadMatrixf"),
    };
    let k = case();
    let mut g = c.benchmark_group("offset_matrix_on_mesa");
    // The seed's LoadOffsetMatrix, with the glLoadIdentity any caller must do first (glFrustum
    // multiplies the current matrix).
    g.bench_function("seed_glFrustum_glGetFloatv_tweak_glLoadMatrixf", |b| {
        b.iter(|| {
            let mut m = [0.0f32; 16];
            (fx.matrix_mode)(GL_PROJECTION);
            (fx.load_identity)();
            (fx.frustum)(k.l, k.r, k.b, k.t, k.n, k.f);
            (fx.get_floatv)(GL_PROJECTION_MATRIX, m.as_mut_ptr());
            let eps = seed::seed_epsilon(k.n, k.f, k.delta as f32, k.pz as f32);
            m[10] = seed::seed_tweak(m[10], eps);
            (fx.load_matrixf)(m.as_ptr());
        })
    });
    g.bench_function("zshift_c_abi_glLoadMatrixf", |b| {
        b.iter(|| {
            let mut m = [0.0f32; 16];
            (fx.matrix_mode)(GL_PROJECTION);
            let s = zshift::ffi::zshift_load_offset_matrix(
                black_box(k.l),
                black_box(k.r),
                black_box(k.b),
                black_box(k.t),
                black_box(k.n),
                black_box(k.f),
                black_box(k.delta),
                black_box(k.pz),
                m.as_mut_ptr(),
            );
            (fx.load_matrixf)(m.as_ptr());
            s
        })
    });
    g.finish();
    gl.check("the Mesa benches").expect("no GL error");
}

fn config() -> Criterion {
    // Short runs: the report must regenerate in minutes on 2 shared cores.
    Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = cpu_builders, mesa_paths
}
criterion_main!(benches);

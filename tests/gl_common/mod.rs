//! Shared by the rendered tests (`tests/gl_*.rs`) and `examples/sweep.rs`: the coplanar-quads
//! experiment of `zshift-harness` measured against zshift's matrices and recommendation.
#![allow(dead_code)]

use zshift::projection::Frustum;
use zshift::recommend::{self, DepthFormat as Format, Recommendation, Scene, Snapping};
use zshift_harness::coplanar::{
    smallest_working_ulps, smallest_working_ulps_below, ulps_toward_camera,
    with_ulps_toward_camera, Bench, Count, Setup,
};
use zshift_harness::{DepthFormat, Gl};

/// The frustum of a setup, validated by zshift.
pub fn frustum_of(s: &Setup) -> Frustum {
    let (l, r, b, t, n, f) = s.frustum();
    Frustum::new(l, r, b, t, n, f).expect("valid setup frustum")
}

/// zshift's depth format for a GL attachment.
pub fn format_of(f: DepthFormat) -> Format {
    Format::from_gl_internal_format(f.gl_enum()).expect("a GL depth format")
}

/// The profile `zshift::probe::probe` measures in `gl`'s own context (what an engine does once at
/// start-up).
pub fn probed(gl: &Gl) -> recommend::RasterizerProfile {
    let loader = |name: &std::ffi::CStr| gl.proc_address(name.to_str().unwrap_or(""));
    // SAFETY: the harness's context is current on this thread and EGL returns its entry points.
    unsafe { zshift::probe::probe(loader) }.unwrap_or_else(|e| panic!("probe failed: {e}"))
}

/// How this rasterizer positions vertices for depth: llvmpipe sets its depth plane up from the
/// unsnapped float positions (measured, see `src/recommend/`); any other driver is assumed to
/// snap to GL_SUBPIXEL_BITS first (the conservative choice).
pub fn snapping_of(gl: &Gl) -> Snapping {
    if gl.renderer().contains("llvmpipe") {
        Snapping::Unsnapped
    } else {
        Snapping::SubpixelBits(gl.subpixel_bits())
    }
}

/// What the scene knows about the setup's decal, as zshift's recommendation takes it.
pub fn scene_of(s: &Setup, snapping: Snapping) -> Scene {
    let (d1, d2) = s.decal_depth_range();
    Scene {
        pipeline: Default::default(),
        footprint: None,
        frustum: frustum_of(s),
        viewport: [s.size, s.size],
        format: format_of(s.format),
        depth_range: [d1, d2],
        slope: s.slope,
        // The setup's facing quads put one f32 z on every corner.
        exact_depth: s.slope == 0.0,
        depth_test: zshift::recommend::DepthTest::Less,
        base: zshift::recommend::Base::InsideFrustum,
        profile: zshift::recommend::RasterizerProfile {
            snapping,
            ..Default::default()
        },
    }
}

/// The seed's bound (c = 1, seed 000 eq. 4.1.8) or the corrected one (c = 2, seed 002):
/// ε = −c/(2^m − 1)·(f − n)/(f + n), with m = 24 for D32F (f32 spacing at window depths ≥ ½).
pub fn seed_epsilon(c: f64, s: &Setup) -> f64 {
    let m = s.format.bits().min(24);
    -c / ((1u64 << m) - 1) as f64 * (s.f - s.n) / (s.f + s.n)
}

/// One row of the table.
#[derive(Debug, Clone)]
pub struct Row {
    pub setup: Setup,
    pub none: Count,
    pub c1: Count,
    pub c2: Count,
    pub rec: Count,
    /// Lost with `zshift_load_offset_matrix(…, delta_at_far, −d₂)`, the seed-shaped entry point.
    pub rec_via_delta: Count,
    pub recommendation: Recommendation,
    /// NDC offset of the recommended matrix (element 10 difference, as the GPU sees it).
    pub rec_ndc: f64,
    /// Smallest NDC offset (whole f32 steps of element 10) from which every larger one up to
    /// the recommendation loses no pixel (scan down from the recommendation).
    pub min_ndc: Option<f64>,
    /// Smallest working NDC offset found by bisection over 1..=2^20 steps (assumes losses
    /// shrink monotonically with the offset, which they do only roughly near the threshold).
    pub bisect_ndc: Option<f64>,
    /// Bleed-through at the recommendation past an occluder a quarter of the documented gap
    /// in front of the base, and past one the full gap in front.
    pub bleed_quarter: Count,
    pub bleed_gap: Count,
}

/// Renders the setup with no offset, at c = 1, c = 2, at the recommendation, past occluders,
/// and finds the smallest working offset (scan down from the recommendation, and bisection).
pub fn measure(gl: &mut Gl, s: Setup) -> Result<Row, String> {
    let snapping = snapping_of(gl);
    let frustum = frustum_of(&s);
    let plain = frustum.to_cols_array().map_err(|e| e.to_string())?;
    let recommendation =
        recommend::recommend(&scene_of(&s, snapping)).map_err(|e| e.to_string())?;
    let rec_matrix =
        zshift::epsilon_matrix(&frustum, recommendation.epsilon).map_err(|e| e.to_string())?;
    let seed =
        |c: f64| zshift::epsilon_matrix(&frustum, seed_epsilon(c, &s)).map_err(|e| e.to_string());
    let (m1, m2) = (seed(1.0)?, seed(2.0)?);
    let mut bench = Bench::new(gl, s, plain)?;
    let none = bench.lost(&plain)?;
    let c1 = bench.lost(&m1)?;
    let c2 = bench.lost(&m2)?;
    let rec = bench.lost(&rec_matrix)?;
    let (l, r, b, t, n, f) = s.frustum();
    let (_, d2) = s.decal_depth_range();
    let via_delta = zshift::load_offset_matrix(l, r, b, t, n, f, recommendation.delta_at_far, -d2)
        .map_err(|e| e.to_string())?
        .to_cols_array();
    let rec_via_delta = bench.lost(&via_delta)?;
    let bleed_quarter = bench.bleed(&rec_matrix, 0.25 * recommendation.bleed_gap)?;
    let bleed_gap = bench.bleed(&rec_matrix, recommendation.bleed_gap)?;
    let to_ndc =
        |k: Option<u32>| k.map(|k| (with_ulps_toward_camera(&plain, k)[10] - plain[10]) as f64);
    let bisect_ndc = to_ndc(smallest_working_ulps(&mut bench, 1 << 20)?);
    let k_rec = ulps_toward_camera(&plain, &rec_matrix);
    let min_ndc = to_ndc(smallest_working_ulps_below(&mut bench, k_rec)?);
    let rec_ndc = (rec_matrix[10] - plain[10]) as f64;
    Ok(Row {
        setup: s,
        none,
        c1,
        c2,
        rec,
        rec_via_delta,
        recommendation,
        rec_ndc,
        min_ndc,
        bisect_ndc,
        bleed_quarter,
        bleed_gap,
    })
}

/// A setup on the common geometry: 60° field of view, n = 1.
pub fn setup(format: DepthFormat, ratio: f64, depth_fraction: f64, slope: f64, size: u32) -> Setup {
    Setup {
        n: 1.0,
        f: ratio,
        tan_half: (30f64).to_radians().tan(),
        size,
        format,
        depth_fraction,
        slope,
    }
}

/// The table header and a row, as `examples/sweep.rs` prints them. ε values are
/// `−Δndc/|m10|` for the NDC offset the f32 matrix actually carries; "min" is the scan-down
/// threshold (every offset from it up to the recommendation works), "bisect" the bisection's.
pub const HEADER: &str = "configuration                      |    px | lost: none    c=1    c=2    rec |    eps min |  eps bisect |    eps rec | rec/min | gap/d2  | bleed: G/4    G";

pub fn format_row(r: &Row) -> String {
    let pct = |c: &Count| format!("{:5.1}%", 100.0 * c.fraction());
    let m10 = (r.setup.f + r.setup.n) / (r.setup.f - r.setup.n);
    let eps = |x: Option<f64>| x.map_or("none".to_string(), |m| format!("{:.3e}", -m / m10));
    let ratio = r
        .min_ndc
        .map_or("-".to_string(), |m| format!("{:.1}", r.rec_ndc / m));
    format!(
        "{} | {:5} | {} {} {} {} | {:>10} | {:>11} | {:.3e} | {:>7} | {:.1e} | {} {}",
        r.setup.label(),
        r.none.of,
        pct(&r.none),
        pct(&r.c1),
        pct(&r.c2),
        pct(&r.rec),
        eps(r.min_ndc),
        eps(r.bisect_ndc),
        -r.rec_ndc / m10,
        ratio,
        r.recommendation.bleed_gap / r.setup.decal_depth_range().1,
        pct(&r.bleed_quarter),
        pct(&r.bleed_gap)
    )
}

/// `<var>=<i>/<n>`: only the cases whose index is `i` modulo `n`, so that `n` processes (each
/// with its own context) share a grid on a machine with cores to spare (`scripts/gpu-checks`);
/// `(0, 1)` without it.
pub fn shard(var: &str) -> (usize, usize) {
    let Ok(text) = std::env::var(var) else {
        return (0, 1);
    };
    let parsed = text
        .split_once('/')
        .and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)));
    match parsed {
        Some((i, n)) if i < n => (i, n),
        _ => panic!("{var}={text}: expected <i>/<n> with i < n, e.g. 0/8"),
    }
}

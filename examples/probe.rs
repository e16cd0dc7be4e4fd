//! Measures the rasterizer profile of a headless OpenGL context (EGL surfaceless, Mesa llvmpipe
//! unless another EGL driver is installed) and prints it with the figures it was decided from.
//!
//! `cargo run --release --example probe` (`-- compat` for a compatibility-profile context;
//! `ZSHIFT_PROBE_RUNS=N` probes N times in the same context and prints each run time: the first
//! includes the driver's shader compilation, as an engine's one call at start-up does).
//! The probe itself needs only the context's function loader: an engine calls
//! `zshift::probe::probe(|name| get_proc_address(name))` with its own context current.

use zshift_harness::{Gl, Profile};

fn main() {
    let profile = match std::env::args().nth(1).as_deref() {
        Some("compat") => Profile::Compatibility,
        _ => Profile::Core,
    };
    let gl = Gl::new(profile).unwrap_or_else(|e| panic!("no {profile:?} GL context: {e}"));
    let loader = |name: &std::ffi::CStr| gl.proc_address(name.to_str().unwrap_or(""));
    // SAFETY: the harness's context is current on this thread; EGL returns its entry points.
    let (p, figures) = unsafe { zshift::probe::probe_with_figures(loader) }
        .unwrap_or_else(|e| panic!("probe failed: {e}"));
    let runs: usize = std::env::var("ZSHIFT_PROBE_RUNS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(1);
    let mut times = vec![p.probe_seconds * 1e3];
    for _ in 1..runs {
        // SAFETY: as above.
        let again =
            unsafe { zshift::probe::probe(loader) }.unwrap_or_else(|e| panic!("probe failed: {e}"));
        times.push(again.probe_seconds * 1e3);
    }
    if runs > 1 {
        let mut later = times[1..].to_vec();
        later.sort_by(f64::total_cmp);
        println!(
            "run times      first {:.1} ms, later median {:.1} ms (min {:.1}, max {:.1}) over {}",
            times[0],
            later[later.len() / 2],
            later[0],
            later[later.len() - 1],
            later.len()
        );
    }
    println!("renderer       {} ({})", figures.renderer, figures.version);
    println!("run time       {:.1} ms", p.probe_seconds * 1e3);
    println!(
        "snapping       {:?} (GL_SUBPIXEL_BITS {}; residual unsnapped {:.2e}, best snapped b={} {:.2e})",
        p.snapping,
        figures.subpixel_bits,
        figures.snapping_residual.0,
        figures.snapping_residual.1,
        figures.snapping_residual.2
    );
    println!(
        "near clip      {:?} (ground planes clipped by GL: {:.1} D24 quanta off; clipped in f64 first: {:.1}); clipper error clip_ulps {:.3} (the model takes 4 times it; its bound: 36)",
        p.near_clip, figures.near_clip_error, figures.near_preclipped_error, p.clip_ulps
    );
    println!(
        "lines          reach (pixels along the steepest gradient): GL_LINES width 1 {:.4} over {} fragments, polygon-mode {:.4} over {} (off its line onto a neighbour: {:.2e} over {}); glPolygonOffset slope rule {:.4} on a diagonal plane (1 = max, 1.414 = root sum of squares), {:.4} on an axis plane",
        p.line_reach[0], figures.line_pixels[0], p.line_reach[1], figures.line_pixels[1], p.outline_neighbour, figures.outline_neighbour_pixels, p.offset_slope, figures.offset_slope_axis
    );
    println!(
        "MSAA lines     reach (pixels along the steepest gradient, from the sample): GL_LINES width 1 {:.4} over {} samples, polygon-mode {:.4} over {} (drawn at {:?} samples); over the whole gradient |∇z|: {:.4}, {:.4}; at glLineWidth(3), over the whole gradient: {:.4}, {:.4} over {:?} samples",
        p.line_reach_msaa[0], figures.msaa_line_samples[0], p.line_reach_msaa[1], figures.msaa_line_samples[1], figures.msaa_sample_counts,
        p.line_reach_msaa_whole[0], p.line_reach_msaa_whole[1],
        p.line_reach_msaa_wide_whole[0], p.line_reach_msaa_wide_whole[1], figures.msaa_wide_line_samples
    );
    println!(
        "wide lines     reach at glLineWidth(3) (pixels along the steepest gradient): GL_LINES {:.4} over {} fragments, polygon-mode {:.4} over {}",
        p.line_reach_wide[0], figures.wide_line_pixels[0], p.line_reach_wide[1], figures.wide_line_pixels[1]
    );
    println!("format  r (quanta)  plane_error (quanta)  error (u*(1+M))  pixels");
    for (i, name) in ["D16", "D24", "D32", "D32F"].iter().enumerate() {
        println!(
            "{name:<6}  {:<10.4}  {:<20.4}  {:<19.3}  {}",
            p.resolvable[i], p.plane_error[i], figures.error_ulps[i], figures.plane_pixels[i]
        );
    }
    println!(
        "D32F [0,1]: error {:.3} (u*(2+M)); error_ulps (the model's figure for [-1,1] and [0,1]) {:.3}",
        figures.error_ulps_zero_to_one, p.error_ulps
    );
    println!(
        "D32F reversed Z: plane_error {:.4} quanta over {} pixels; error_ulps_reversed {:.3} (u*(|m10| + M))",
        p.plane_error_reversed, figures.reversed_pixels, p.error_ulps_reversed
    );
    println!(
        "D32F plane error in quanta at each pixel's own depth: [-1,1] {:.2}, reversed {:.2}",
        figures.float_local_plane_error[0], figures.float_local_plane_error[1]
    );
    println!(
        "D32F r per band (w ~ 0.45, w ~ 0.055): {:?}",
        figures.float_resolvable
    );
    println!(
        "facing decal over a shared-z base, GL_LESS (quanta; D32F: 2^-24; NaN not measured): [-1,1] {:?}, [0,1] {:?}; reversed D32F relative epsilon {:.2} x 2^-24",
        p.facing_quanta, p.facing_quanta_zero_to_one, p.facing_reversed
    );
    println!(
        "facing depth chain: {:?} (code {}), checked on {} stored depths",
        p.facing_chain,
        p.facing_chain.map_or(-1, |c| c.code()),
        figures.chain_observations
    );
}

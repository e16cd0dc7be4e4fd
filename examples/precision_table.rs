//! Prints the precision table of issue 4: for each projection convention and depth format, the
//! depth step (the smallest eye-space shift toward the camera that changes the stored depth)
//! that zshift predicts, beside the step measured on a real rasterizer (headless EGL, Mesa
//! llvmpipe through `zshift-harness`), at several distances.
//!
//! Run: `cargo run --release --example precision_table`
//!
//! Measurement: 256 facing strips, one per pixel column, at distances `d + (127.5 − k)·h` (`h` = predicted
//! step / 8, vertex z rounded to f32), each stored with `GL_ALWAYS`; the measured step is the
//! distance spanned over the number of distinct stored values less one. Where the f32 spacing of
//! the vertex's own eye z exceeds the predicted step, the measurement cannot go below it.

#[path = "../tests/projections_gl/mod.rs"]
mod projections_gl;

use projections_gl::{eye_z_spacing, measure_step, Drawer, MdpProgram};
use zshift::precision::{DepthFormat, DepthMapping};
use zshift::projection::{projection, tweaked_infinite, ClipDepth, MIN_INFINITE_TWEAK};
use zshift::Frustum;
use zshift_harness::{ClipDepth as GlClip, DepthFormat as GlFormat, Gl, Profile};

fn frustum(n: f64, f: f64) -> Frustum {
    Frustum::new(-0.5 * n, 0.5 * n, -0.5 * n, 0.5 * n, n, f).expect("frustum")
}

fn main() -> Result<(), String> {
    let mut gl = Gl::new(Profile::Core)?;
    let (n, f) = (0.5, 1000.0);
    let median = 10.0;
    let prog = MdpProgram::new(&gl)?;
    let std_proj = projection(&frustum(n, f), ClipDepth::NegOneToOne).map_err(|e| e.to_string())?;
    let zo_proj = projection(&frustum(n, f), ClipDepth::ZeroToOne).map_err(|e| e.to_string())?;
    let rev_proj =
        projection(&frustum(n, f), ClipDepth::ReversedZeroToOne).map_err(|e| e.to_string())?;
    let rev_inf = frustum(n, f64::INFINITY);
    let rev_inf_proj =
        projection(&rev_inf, ClipDepth::ReversedZeroToOne).map_err(|e| e.to_string())?;
    let tweaked = tweaked_infinite(&rev_inf, MIN_INFINITE_TWEAK).map_err(|e| e.to_string())?;
    let map = |clip, far| DepthMapping::projection(n, far, clip).expect("mapping");
    let rows: Vec<(&str, GlFormat, GlClip, DepthMapping, DepthFormat, Drawer)> = vec![
        (
            "standard [-1,1], D16",
            GlFormat::D16,
            GlClip::NegativeOneToOne,
            map(ClipDepth::NegOneToOne, f),
            DepthFormat::Unorm16,
            Drawer::Matrix(std_proj),
        ),
        (
            "standard [-1,1], D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            map(ClipDepth::NegOneToOne, f),
            DepthFormat::Unorm24,
            Drawer::Matrix(std_proj),
        ),
        (
            "standard [-1,1], D32F",
            GlFormat::D32F,
            GlClip::NegativeOneToOne,
            map(ClipDepth::NegOneToOne, f),
            DepthFormat::Float32,
            Drawer::Matrix(std_proj),
        ),
        (
            "[0,1], D32F",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            map(ClipDepth::ZeroToOne, f),
            DepthFormat::Float32,
            Drawer::Matrix(zo_proj),
        ),
        (
            "reversed [0,1], D32F",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            map(ClipDepth::ReversedZeroToOne, f),
            DepthFormat::Float32,
            Drawer::Matrix(rev_proj),
        ),
        (
            "reversed infinite, D32F",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            map(ClipDepth::ReversedZeroToOne, f64::INFINITY),
            DepthFormat::Float32,
            Drawer::Matrix(rev_inf_proj),
        ),
        (
            "tweaked infinite, D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            DepthMapping::tweaked_infinite(n, MIN_INFINITE_TWEAK).expect("mapping"),
            DepthFormat::Unorm24,
            Drawer::Matrix(tweaked),
        ),
        (
            "median m=10, D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            DepthMapping::median(median).expect("mapping"),
            DepthFormat::Unorm24,
            Drawer::Median(&prog, std_proj, median as f32),
        ),
    ];
    println!(
        "Depth step: predicted (zshift) vs measured ({}, {}); n = {n}, f = {f}, median = {median}",
        gl.renderer(),
        gl.version()
    );
    println!();
    println!("| projection, format | d | predicted step | measured step | measured/predicted | f32 eye-z spacing |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (name, glf, clip, mapping, fmt, drawer) in &rows {
        gl.set_target(projections_gl::COLUMNS as u32, 2, *glf)?;
        gl.clip_control(*clip)?;
        for d in [1.0, 5.0, 20.0, 100.0, 500.0] {
            let predicted = mapping.depth_step(d, *fmt).map_err(|e| e.to_string())?;
            let m = measure_step(&mut gl, drawer, d, predicted)?;
            let measured = m.step.map_or("none".to_string(), |s| format!("{s:.3e}"));
            let ratio = m
                .step
                .map_or("-".to_string(), |s| format!("{:.2}", s / predicted));
            let note = if m.reversals > 0 {
                format!(" ({} reversals)", m.reversals)
            } else {
                String::new()
            };
            println!(
                "| {name} | {d} | {predicted:.3e} | {measured}{note} | {ratio} | {:.1e} |",
                eye_z_spacing(d)
            );
        }
    }
    Ok(())
}

//! Prints the precision table: for each projection convention and depth format, the
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

use projections_gl::{decal_loss, eye_z_spacing, measure_step, Drawer, MdpProgram};
use zshift::clip_offset::{ndc_offset_matrix, relative_offset_matrix};
use zshift::precision::{DepthFormat, DepthMapping};
use zshift::projection::projection_f64;
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
    margin_table(&mut gl)?;
    range_table(&mut gl)
}

/// One offset for decals anywhere in [1, 500] (`plan::range_offset`, 8 steps): the eye-space
/// shift it costs at both ends, per placement, and whether decals at 1, 30 and 500 (slope 3)
/// all win on the rasterizer with it.
fn range_table(gl: &mut Gl) -> Result<(), String> {
    use zshift::plan::{range_offset, OffsetKind};
    let err = |e: zshift::Error| e.to_string();
    let n = 0.5;
    let cases = [
        (
            "standard, D24, element 10",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            ClipDepth::NegOneToOne,
            1000.0,
            DepthFormat::Unorm24,
            OffsetKind::Ndc,
        ),
        (
            "reversed infinite, D32F, element 14",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
            f64::INFINITY,
            DepthFormat::Float32,
            OffsetKind::Relative,
        ),
        (
            "reversed infinite, D32F, element 10",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
            f64::INFINITY,
            DepthFormat::Float32,
            OffsetKind::Ndc,
        ),
    ];
    println!();
    println!("One offset for decals anywhere in d = [1, 500], 8 steps (plan::range_offset), slope-3 decals on the rasterizer:");
    println!();
    println!("| placement | offset | shift at d = 1 | shift at d = 500 | decal pixels lost at d = 1, 30, 500 |");
    println!("|---|---:|---:|---:|---|");
    for (name, format, glclip, clip, far, fmt, kind) in cases {
        gl.set_target(96, 96, format)?;
        gl.clip_control(glclip)?;
        let fr = frustum(n, far);
        let m64 = projection_f64(&fr, clip).map_err(err)?;
        let plain = projection(&fr, clip).map_err(err)?;
        let mapping = DepthMapping::projection(n, far, clip).map_err(err)?;
        let plan = range_offset(&mapping, fmt, kind, 1.0, 500.0, 8.0).map_err(err)?;
        let decal = match kind {
            OffsetKind::Ndc => ndc_offset_matrix(&m64, plan.offset),
            OffsetKind::Relative => relative_offset_matrix(&m64, plan.offset),
        }
        .map_err(err)?;
        let reversed = clip == ClipDepth::ReversedZeroToOne;
        let mut lost = Vec::new();
        for d in [1.0, 30.0, 500.0] {
            lost.push(decal_loss(gl, &plain, &decal, d, 3.0, reversed)?.to_string());
        }
        println!(
            "| {name} | {:.3e} | {:.3e} | {:.3e} | {} |",
            plan.offset,
            plan.shift_near,
            plan.shift_far,
            lost.join(", ")
        );
    }
    Ok(())
}

/// The smallest offset, in units of the one-step minimum at the decal's distance, at which a
/// coplanar decal loses no pixel: per offset placement, depth format and surface slope.
fn margin_table(gl: &mut Gl) -> Result<(), String> {
    let n = 0.5;
    let inf = frustum(n, f64::INFINITY);
    let fin = frustum(n, 1000.0);
    let err = |e: zshift::Error| e.to_string();
    struct Row {
        name: &'static str,
        format: GlFormat,
        glclip: GlClip,
        clip: ClipDepth,
        far: f64,
        relative: bool,
        fmt: DepthFormat,
    }
    let rows = [
        Row {
            name: "standard, D24, element 10 (constant)",
            format: GlFormat::D24,
            glclip: GlClip::NegativeOneToOne,
            clip: ClipDepth::NegOneToOne,
            far: 1000.0,
            relative: false,
            fmt: DepthFormat::Unorm24,
        },
        Row {
            name: "standard, D32F, element 10 (constant)",
            format: GlFormat::D32F,
            glclip: GlClip::NegativeOneToOne,
            clip: ClipDepth::NegOneToOne,
            far: 1000.0,
            relative: false,
            fmt: DepthFormat::Float32,
        },
        Row {
            name: "reversed infinite, D32F, element 14 (relative)",
            format: GlFormat::D32F,
            glclip: GlClip::ZeroToOne,
            clip: ClipDepth::ReversedZeroToOne,
            far: f64::INFINITY,
            relative: true,
            fmt: DepthFormat::Float32,
        },
        Row {
            name: "reversed infinite, D32F, element 10 (constant)",
            format: GlFormat::D32F,
            glclip: GlClip::ZeroToOne,
            clip: ClipDepth::ReversedZeroToOne,
            far: f64::INFINITY,
            relative: false,
            fmt: DepthFormat::Float32,
        },
    ];
    println!();
    println!("Smallest offset, in one-step minima at the decal's distance (min_ndc_offset or min_relative_epsilon),");
    println!("at which a coplanar decal (96x96 target) loses no pixel; slope = eye-space dz/dy of the surface:");
    println!();
    println!("| offset placement | slope | d = 1 | d = 30 | d = 500 |");
    println!("|---|---:|---:|---:|---:|");
    for row in &rows {
        gl.set_target(96, 96, row.format)?;
        gl.clip_control(row.glclip)?;
        let fr = if row.far.is_finite() { fin } else { inf };
        let m64 = projection_f64(&fr, row.clip).map_err(err)?;
        let plain = projection(&fr, row.clip).map_err(err)?;
        let mapping = DepthMapping::projection(n, row.far, row.clip).map_err(err)?;
        let reversed = row.clip == ClipDepth::ReversedZeroToOne;
        for slope in [0.0, 1.0, 3.0] {
            let mut cells = Vec::new();
            for d in [1.0, 30.0, 500.0] {
                let mut found = None;
                for k in (0..=12).map(|i| f64::from(1u32 << i)) {
                    let decal = if row.relative {
                        let eps = k * mapping.min_relative_epsilon(d, row.fmt).map_err(err)?;
                        relative_offset_matrix(&m64, eps)
                    } else {
                        let c = k * mapping.min_ndc_offset(d, row.fmt).map_err(err)?;
                        ndc_offset_matrix(&m64, if reversed { c } else { -c })
                    }
                    .map_err(err)?;
                    if decal_loss(gl, &plain, &decal, d, slope, reversed)? == 0 {
                        found = Some(k);
                        break;
                    }
                }
                cells.push(found.map_or("> 4096".to_string(), |k| format!("{k}")));
            }
            println!("| {} | {slope} | {} |", row.name, cells.join(" | "));
        }
    }
    Ok(())
}

//! The full coplanar-quads sweep on a real rasterizer (headless EGL): for every configuration,
//! the fraction of decal pixels lost to the base with no offset, at the seed's bound (c = 1),
//! at the corrected bound (c = 2) and at zshift's recommendation, and the smallest offset that
//! works (bisection over f32 steps of element 10) beside the recommended one; then the
//! documented bleed gap G (as a fraction of the decal's farthest distance) and the fraction of
//! shared pixels where the decal bleeds past an occluder G/4 and G in front of the base.
//!
//! `cargo run --release --example sweep [size]` (default 256 × 256). Exits with an error if the
//! recommendation loses a pixel anywhere. The scenes engines draw (bases clipped by the
//! rasterizer or cut by `clip_to_frustum`, odd viewports, off-centre frusta, `GL_LEQUAL`, every
//! convention, the worst-case and a measured profile) are in `tests/gl_scenes.rs`
//! (`ZSHIFT_SCENES=full` for the whole grid).

#[path = "../tests/gl_common/mod.rs"]
mod common;

use zshift_harness::{DepthFormat, Gl, Profile};

fn main() -> Result<(), String> {
    let size = std::env::args()
        .nth(1)
        .map_or(Ok(256), |a| a.parse())
        .map_err(|e| format!("size: {e}"))?;
    let mut gl = Gl::new(Profile::Core)?;
    println!(
        "renderer: {} / {}; GL_SUBPIXEL_BITS {}; model snapping: {:?}",
        gl.renderer(),
        gl.version(),
        gl.subpixel_bits(),
        common::snapping_of(&gl)
    );
    println!("{}", common::HEADER);
    let (mut worst_ratio, mut failures) = (0.0f64, 0);
    for format in DepthFormat::ALL {
        for ratio in [10.0, 1e3, 1e6] {
            for p in [0.2, 0.5, 0.9] {
                for slope in [0.0, 0.3, 1.0, 3.0] {
                    let row =
                        common::measure(&mut gl, common::setup(format, ratio, p, slope, size))?;
                    println!("{}", common::format_row(&row));
                    failures += usize::from(row.rec.hit > 0);
                    if let Some(m) = row.min_ndc {
                        worst_ratio = worst_ratio.max(row.rec_ndc / m);
                    }
                }
            }
        }
    }
    println!("configurations losing pixels at the recommendation: {failures}; largest rec/min: {worst_ratio:.1}");
    snap_check(&mut gl, size)?;
    if failures > 0 {
        return Err(format!(
            "the recommendation lost pixels in {failures} configurations"
        ));
    }
    Ok(())
}

/// Whether this rasterizer snaps vertices before setting up depth: the steepest near
/// configuration's smallest working offset beside the snapping term `S` that
/// `GL_SUBPIXEL_BITS` would add (in f32 steps of element 10).
fn snap_check(gl: &mut Gl, size: u32) -> Result<(), String> {
    let s = common::setup(DepthFormat::D24, 10.0, 0.2, 3.0, size);
    let snapped = zshift::recommend::Snapping::SubpixelBits(gl.subpixel_bits());
    let rec =
        zshift::recommend::recommend(&common::scene_of(&s, snapped)).map_err(|e| e.to_string())?;
    let row = common::measure(gl, s)?;
    let ulp = 2f64.powi(-23); // |m10| = 11/9 lies in [1, 2)
    println!(
        "snapping check ({}): the term S for GL_SUBPIXEL_BITS = {} alone asks {:.0} steps of element 10; the smallest working offset is {:.0}",
        s.label(),
        gl.subpixel_bits(),
        4.0 * rec.terms.snap / ulp,
        row.min_ndc.map_or(f64::NAN, |m| m / ulp)
    );
    Ok(())
}

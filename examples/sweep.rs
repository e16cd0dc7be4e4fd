//! The full coplanar-quads sweep on a real rasterizer (headless EGL): for every configuration,
//! the fraction of decal pixels lost to the base with no offset, at the seed's bound (c = 1),
//! at the corrected bound (c = 2) and at zshift's recommendation, and the smallest offset that
//! works (bisection over f32 steps of element 10) beside the recommended one.
//!
//! `cargo run --release --example sweep [size]` (default 256 × 256). Exits with an error if the
//! recommendation loses a pixel anywhere.

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
    if failures > 0 {
        return Err(format!(
            "the recommendation lost pixels in {failures} configurations"
        ));
    }
    Ok(())
}

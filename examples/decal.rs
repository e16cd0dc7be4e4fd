//! The main demonstration: a decal on a sloped floor, rendered headless three times.
//!
//! ```sh
//! cargo run --release --example decal            # writes target/decal/{none,seed,zshift}.png
//! cargo run --release --example decal -- DIR     # writes the pictures into DIR
//! cargo run --release --example decal -- --sweep # lost pixels over slopes, far planes, depths
//! ```
//!
//! A floor (blue) and a smaller decal (red) lie in the same plane, tilted away from the camera
//! like a road or a floor seen from eye height, and are drawn base first with the depth test
//! `GL_LESS`, through the fixed-function pipeline (`glMatrixMode(GL_PROJECTION)` +
//! `glLoadMatrixf`) on a 24-bit depth buffer. The decal's projection is made three ways:
//!
//! 1. **none**: the plain `glFrustum` matrix. The decal z-fights with the floor.
//! 2. **seed**: the seed's `LoadOffsetMatrix` (000, 4.1) as printed — the driver's `glFrustum`
//!    matrix read back with `glGetFloatv`, ε from eq. 4.1.7 rounded to float, element 10 scaled
//!    by `1.0F + epsilon` in float — with the δ the seed prints as the minimum (eq. 4.1.9 with
//!    4.1.11's k, before the errata of seed 002 doubled it).
//! 3. **zshift**: `zshift::load_offset_matrix` with the δ of zshift's recommendation
//!    (`zshift::recommend`, see `decal_scene::recommendation`).
//!
//! For each it prints how many of the decal's pixels the floor hid, and writes the picture as
//! PNG. Exits nonzero, with the reason, if no GL context can be made or if zshift's decal loses
//! a pixel (the claim this demonstrates; `scripts/test` runs it). Conventions as zshift's:
//! OpenGL right-handed eye space looking down −z, NDC depth [−1, 1], column-major matrices.

use std::path::{Path, PathBuf};

use zshift_harness::{Gl, Profile};

// The scene, the three projections and the renders, shared with examples/decal_window.rs.
#[path = "decal_scene/mod.rs"]
mod decal_scene;
use decal_scene::{compare, report, verdict, Scene, DEPTH, MAIN, SIZE};

/// Renders the main scene, writes the three pictures, prints the table. Fails if zshift's
/// decal loses a pixel: that is the claim this demonstration shows.
fn demonstrate(gl: &mut Gl, out_dir: &Path) -> Result<(), String> {
    let (rows, decal_pixels) = compare(gl, &MAIN)?;
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    report(gl, &rows, decal_pixels, Some(out_dir))?;
    verdict(&rows)
}

/// `--sweep`: the lost-pixel percentages over slopes, far planes and depths (no pictures).
fn sweep(gl: &mut Gl) -> Result<(), String> {
    println!(
        "{:>6} {:>8} {:>7} {:>7} {:>7} {:>7}",
        "dz/dy", "f/n", "Pz", "none%", "seed%", "zshift%"
    );
    for slope in [0.0, -0.3, -1.0, -3.0] {
        for f in [1e4, 1e5, 1e7] {
            for z0 in [-50.0, -500.0] {
                let scene = Scene {
                    half: 0.05,
                    n: 0.1,
                    f: f * 0.1,
                    z0,
                    slope,
                };
                let (rows, total) = compare(gl, &scene)?;
                let pct: Vec<String> = rows
                    .iter()
                    .map(|r| format!("{:>7.1}", 100.0 * r.5 as f64 / total as f64))
                    .collect();
                println!("{slope:>6} {f:>8.0e} {z0:>7} {}", pct.join(" "));
            }
        }
    }
    Ok(())
}

fn main() {
    let arg = std::env::args_os().nth(1);
    let mut gl = match Gl::new(Profile::Compatibility)
        .and_then(|mut gl| gl.set_target(SIZE, SIZE, DEPTH).map(|_| gl))
    {
        Ok(gl) => gl,
        Err(e) => {
            eprintln!("decal: no headless OpenGL compatibility context: {e}");
            std::process::exit(1);
        }
    };
    let result = if arg.as_deref() == Some(std::ffi::OsStr::new("--sweep")) {
        sweep(&mut gl)
    } else {
        let out_dir = arg
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("target/decal"));
        demonstrate(&mut gl, &out_dir)
    };
    if let Err(e) = result {
        eprintln!("decal: {e}");
        std::process::exit(1);
    }
}

//! The main demonstration: a decal on a sloped floor, rendered headless five ways, as one
//! labelled picture and an animation.
//!
//! ```sh
//! cargo run --release -p zshift-demo               # writes target/decal/decal.png and decal.gif
//! cargo run --release -p zshift-demo -- DIR        # writes them into DIR
//! cargo run --release -p zshift-demo -- --sweep    # lost pixels over slopes, far planes, depths
//! cargo run --release -p zshift-demo -- --edges DIR    # edges over their faces: DIR/edges.png
//! cargo run --release -p zshift-demo -- --shadows DIR  # shadow-map bias: DIR/shadows.png
//! ```
//!
//! A floor (blue) and a smaller decal (red) lie in the same plane, tilted away from the camera
//! like a road seen from eye height, with a grey plank lying 3 units above the floor across the
//! decal's right side. Floor and plank are drawn first, then the decal, with the depth test
//! `GL_LESS`, through the fixed-function pipeline (`glMatrixMode(GL_PROJECTION)` +
//! `glLoadMatrixf`) on a 24-bit depth buffer. The decal is drawn five ways (`scene::METHODS`):
//! with no offset; with the seed's `LoadOffsetMatrix` as printed (f32 ε, the seed's printed
//! minimum δ); with `glPolygonOffset(-4, 0)` (three.js's decal example) and `(0, -1)` (Ogre's
//! `depth_bias 1`); and with zshift's recommendation (`zshift::recommend`, then
//! `zshift::load_offset_matrix`).
//!
//! Each render is read back with `glReadPixels` and counted: **lost** decal pixels (outside the
//! plank, the floor shows instead: z-fighting, too little offset) and **bled** ones (the decal
//! drawn over the plank, which is nearer the camera: too much offset). `decal.png` shows the
//! five renders side by side with their counts; `decal.gif` moves the camera ±60 units along its
//! axis over 24 frames, each method recomputed per frame as an engine would: the z-fighting
//! pattern shimmers, zshift's decal stays whole. Exits nonzero, with the reason, if no GL context
//! can be made or if zshift's decal loses or bleeds a pixel in any frame (`scripts/test` runs
//! it). Conventions as zshift's: OpenGL right-handed eye space looking down −z, NDC depth
//! [−1, 1], column-major matrices.

use std::path::{Path, PathBuf};

use zshift_demo::picture::{compose, write_gif, Picture};
use zshift_demo::scene::{
    compare, percent, report, verdict, Canvas, Comparison, Scene, DEPTH, MAIN, SIZE,
};
use zshift_harness::{Gl, Profile};

/// Animation frames and how far the camera swings along its axis (eye units, each way).
const FRAMES: usize = 24;
const SWING: f64 = 60.0;

/// The title lines over a picture of `c`.
fn title(c: &Comparison, frame: Option<usize>) -> Vec<String> {
    let s = &c.scene;
    let gap = s.occluder_gap.unwrap_or(0.0);
    let mut lines = vec![
        format!(
            "RED DECAL (YELLOW OUTLINE: WHERE IT BELONGS) ON A BLUE FLOOR AT 45 DEG, {:.0} UNITS AWAY, F/N = 1E7, D24",
            -s.plane_z(0.0)
        ),
        format!("GREY PLANK {gap} UNITS ABOVE THE FLOOR. LOST: DECAL HIDDEN BY THE FLOOR (Z-FIGHTING). BLED: DECAL OVER THE PLANK"),
    ];
    // On a line of its own: appended to the one above, it ran off the picture.
    if let Some(k) = frame {
        lines.push(format!("FRAME {:>2}/{FRAMES} OF THE CAMERA'S SWING", k + 1));
    }
    lines
}

/// The footer: where the counts come from and what zshift asked for.
fn footer(gl: &impl Canvas, c: &Comparison) -> Vec<String> {
    let rec = &c.recommendation;
    vec![
        format!(
            "COUNTED WITH GLREADPIXELS: {} DECAL PIXELS TO SHOW, {} UNDER THE PLANK ({})",
            c.visible,
            c.covered,
            gl.renderer().split(" (").next().unwrap_or_default()
        ),
        format!(
            "ZSHIFT: DELTA {:.3} AT PZ = {:.0} (WINDOW OFFSET {:.2E}); BLEED GAP {:.2} < PLANK {}",
            rec.delta_at_far,
            c.rows
                .iter()
                .find(|r| r.method.name == "zshift")
                .map_or(f64::NAN, |r| r.at),
            rec.window_offset,
            rec.bleed_gap,
            c.scene.occluder_gap.unwrap_or(0.0)
        ),
    ]
}

/// Renders the main scene and the animation, writes `decal.png` and `decal.gif` into `out_dir`,
/// prints the table. Fails if zshift's decal loses or bleeds a pixel in any of them.
fn demonstrate(gl: &mut Gl, out_dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let main = compare(gl, &MAIN)?;
    report(gl, &main);

    let mut failures: Vec<String> = verdict(&main).err().into_iter().collect();
    let mut frames: Vec<Picture> = Vec::new();
    let mut worst = vec![(0usize, 0usize); main.rows.len()];
    // The frame where a constant offset loses the most (Ogre's depth_bias, three.js's polygon
    // offset): the picture's second row, where the constants fail and zshift does not.
    let mut constants_fail: Option<(usize, usize)> = None;
    for k in 0..FRAMES {
        let dz = SWING * (2.0 * std::f64::consts::PI * k as f64 / FRAMES as f64).sin();
        let c = compare(gl, &MAIN.moved(dz))?;
        for (w, r) in worst.iter_mut().zip(&c.rows) {
            *w = (w.0.max(r.lost), w.1.max(r.bled));
        }
        failures.extend(verdict(&c).err());
        let constant_lost = c
            .rows
            .iter()
            .filter(|r| r.method.name.starts_with("ogre") || r.method.name.starts_with("three"))
            .map(|r| r.lost + r.bled)
            .max()
            .unwrap_or(0);
        if constants_fail.is_none_or(|(_, most)| constant_lost > most) {
            constants_fail = Some((k, constant_lost));
        }
        frames.push(compose(&c, &title(&c, Some(k)), &footer(gl, &c)));
    }
    let png = out_dir.join("decal.png");
    let first = compose(&main, &title(&main, None), &footer(gl, &main));
    match constants_fail {
        Some((k, _)) => Picture::stacked(&first, &frames[k]).write_png(&png)?,
        None => first.write_png(&png)?,
    }
    println!("picture: {}", png.display());
    let gif = out_dir.join("decal.gif");
    write_gif(&gif, &frames, 12)?;
    let worst: Vec<String> = main
        .rows
        .iter()
        .zip(&worst)
        .map(|(r, (lost, bled))| format!("{} {lost}/{bled}", r.method.name))
        .collect();
    println!(
        "animation: {} ({FRAMES} frames, decal {:.0} to {:.0} units away); most lost/bled in a frame: {}",
        gif.display(),
        -MAIN.plane_z(0.0) - SWING,
        -MAIN.plane_z(0.0) + SWING,
        worst.join(", ")
    );
    match failures.first() {
        None => Ok(()),
        Some(first) => Err(format!(
            "{} of {} renders failed; first: {first}",
            failures.len(),
            FRAMES + 1
        )),
    }
}

/// `--sweep`: the lost-pixel percentages over slopes, far planes and depths (no plank, no
/// pictures).
fn sweep(gl: &mut Gl) -> Result<(), String> {
    let names: Vec<String> = zshift_demo::scene::METHODS
        .iter()
        .map(|m| format!("{:>9}", m.name))
        .collect();
    println!("lost decal pixels, % ({SIZE}x{SIZE}, {})", DEPTH.name());
    println!(
        "{:>6} {:>8} {:>7} {}",
        "dz/dy",
        "f/n",
        "Pz",
        names.join(" ")
    );
    let mut failures = 0;
    for slope in [0.0, -0.3, -1.0, -3.0] {
        for f in [1e4, 1e5, 1e7] {
            for z0 in [-50.0, -500.0] {
                let scene = Scene {
                    half: 0.05,
                    n: 0.1,
                    f: f * 0.1,
                    z0,
                    slope,
                    size: -z0,
                    occluder_gap: None,
                };
                let c = compare(gl, &scene)?;
                failures += usize::from(verdict(&c).is_err());
                let pct: Vec<String> = c
                    .rows
                    .iter()
                    .map(|r| format!("{:>9.1}", percent(r.lost, c.visible)))
                    .collect();
                println!("{slope:>6} {f:>8.0e} {z0:>7} {}", pct.join(" "));
            }
        }
    }
    match failures {
        0 => Ok(()),
        n => Err(format!("zshift's decal lost pixels in {n} configurations")),
    }
}

fn main() {
    let arg = std::env::args_os().nth(1);
    // The shadows demonstration makes its own (core) context.
    if arg.as_deref() == Some(std::ffi::OsStr::new("--shadows")) {
        if let Err(e) = zshift_demo::shadows::run(std::env::args_os().nth(2)) {
            eprintln!("zshift-demo: {e}");
            std::process::exit(1);
        }
        return;
    }
    let mut gl = match Gl::new(Profile::Compatibility)
        .and_then(|mut gl| gl.set_target(SIZE, SIZE, DEPTH).map(|_| gl))
    {
        Ok(gl) => gl,
        Err(e) => {
            eprintln!("zshift-demo: no headless OpenGL compatibility context: {e}");
            std::process::exit(1);
        }
    };
    let result = if arg.as_deref() == Some(std::ffi::OsStr::new("--sweep")) {
        sweep(&mut gl)
    } else if arg.as_deref() == Some(std::ffi::OsStr::new("--edges")) {
        let out_dir = std::env::args_os().nth(2).map(PathBuf::from);
        zshift_demo::edges::demonstrate(&mut gl, &out_dir.unwrap_or("target/edges".into()))
    } else {
        let out_dir = arg
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("target/decal"));
        demonstrate(&mut gl, &out_dir)
    };
    if let Err(e) = result {
        eprintln!("zshift-demo: {e}");
        std::process::exit(1);
    }
}

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
//!    (`zshift::recommend`, see [`recommendation`]).
//!
//! For each it prints how many of the decal's pixels the floor hid, and writes the picture as
//! PNG. Exits nonzero, with the reason, if no GL context can be made or if zshift's decal loses
//! a pixel (the claim this demonstrates; `scripts/test` runs it). Conventions as zshift's:
//! OpenGL right-handed eye space looking down −z, NDC depth [−1, 1], column-major matrices.

use std::path::{Path, PathBuf};

use zshift::recommend::{
    DepthFormat as RecommendFormat, Recommendation, Scene as RecommendScene, Snapping,
};
use zshift::Frustum;
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Image, Profile, Quad};

/// Framebuffer size: large enough to see the pattern, small enough for a software rasterizer.
const SIZE: u32 = 256;
const DEPTH: DepthFormat = DepthFormat::D24;
const CLEAR: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
const FLOOR: [f32; 4] = [0.2, 0.35, 0.9, 1.0];
const DECAL: [f32; 4] = [0.95, 0.15, 0.1, 1.0];

/// The camera and the plane: a symmetric frustum and the eye-space plane `z = z0 + slope·y`.
struct Scene {
    /// `glFrustum(-half, half, -half, half, n, f)`.
    half: f64,
    n: f64,
    f: f64,
    /// Eye-space depth of the plane at y = 0 (negative).
    z0: f64,
    /// Eye-space `dz/dy`, negative: the plane recedes as it rises on screen, like a floor.
    slope: f64,
}

impl Scene {
    fn plane_z(&self, y: f64) -> f64 {
        self.z0 + self.slope * y
    }

    /// A quad on the plane spanning eye-space `x ∈ [−w, w]`, `y ∈ [y0, y1]`.
    fn quad(&self, w: f64, y0: f64, y1: f64) -> Quad {
        Quad::on_plane(-w, w, y0, y1, |_, y| self.plane_z(y))
    }

    fn floor(&self) -> Quad {
        let d = -self.z0;
        self.quad(0.45 * d, -0.3 * d, 0.35 * d)
    }

    /// Different vertices from the floor's, the same plane: a coplanar decal.
    fn decal(&self) -> Quad {
        let d = -self.z0;
        self.quad(0.2 * d, -0.15 * d, 0.15 * d)
    }

    fn plain(&self) -> [f32; 16] {
        let (h, n, f) = (self.half, self.n, self.f);
        zshift::frustum(-h, h, -h, h, n, f)
            .expect("the scene's frustum is valid")
            .to_cols_array()
    }
}

/// How the rasterizer sets up depth, as the recommendation's error model takes it: Mesa's
/// llvmpipe interpolates depth from unsnapped positions (measured, `tests/gl_recommend.rs`);
/// any other driver is assumed to snap to `GL_SUBPIXEL_BITS`, the conservative case.
fn snapping_of(gl: &Gl) -> Snapping {
    if gl.renderer().contains("llvmpipe") {
        Snapping::Unsnapped
    } else {
        Snapping::SubpixelBits(gl.subpixel_bits())
    }
}

/// zshift's recommendation for the decal (`zshift::recommend`): what the engine knows of the
/// scene — frustum, viewport, depth format, the decal's nearest and farthest distance, the
/// plane's slope, the rasterizer's snapping — in, the offset that its error model guarantees
/// out; also the decal's farthest distance d₂, where the recommended δ applies.
fn recommendation(scene: &Scene, snapping: Snapping) -> Result<(Recommendation, f64), String> {
    let (h, n, f) = (scene.half, scene.n, scene.f);
    let depths = scene.decal().corners.map(|[_, _, z]| -f64::from(z));
    let nearest = depths.iter().copied().fold(f64::INFINITY, f64::min);
    let farthest = depths.iter().copied().fold(0.0, f64::max);
    let model = RecommendScene {
        frustum: Frustum::new(-h, h, -h, h, n, f).map_err(|e| e.to_string())?,
        viewport: [SIZE, SIZE],
        format: RecommendFormat::from_gl_internal_format(DEPTH.gl_enum())
            .map_err(|e| e.to_string())?,
        depth_range: [nearest, farthest],
        slope: scene.slope.abs(),
        exact_depth: false,
        snapping,
    };
    let rec =
        zshift::recommend::recommend(&model).map_err(|e| format!("zshift::recommend: {e}"))?;
    Ok((rec, farthest))
}

/// The seed's minimum δ as printed: eq. 4.1.9 with eq. 4.1.11's `k = (f−n)/(2fn(2^m−1))`.
fn seed_min_delta(scene: &Scene, pz: f64) -> f64 {
    let (n, f) = (scene.n, scene.f);
    let k = (f - n) / (2.0 * f * n * (2f64.powi(DEPTH.bits() as i32) - 1.0));
    k * pz * pz / (1.0 - k * pz)
}

/// The seed's `LoadOffsetMatrix` (000, 4.1), line for line: the driver's `glFrustum` matrix,
/// `GLfloat epsilon = -2.0F * f * n * delta / ((f + n) * pz * (pz + delta))` (double
/// arithmetic, since f and n are GLdouble, rounded to float), `matrix[10] *= 1.0F + epsilon`.
fn seed_load_offset_matrix(
    gl: &mut Gl,
    s: &Scene,
    delta: f32,
    pz: f32,
) -> Result<[f32; 16], String> {
    let (h, n, f) = (s.half, s.n, s.f);
    let mut matrix = gl.legacy_frustum(-h, h, -h, h, n, f)?;
    let (delta, pz) = (f64::from(delta), f64::from(pz));
    let epsilon = (-2.0 * f * n * delta / ((f + n) * pz * (pz + delta))) as f32;
    matrix[10] *= 1.0f32 + epsilon;
    Ok(matrix)
}

/// Draws the floor, then the decal with `decal_projection`, through `glLoadMatrixf`.
fn render(gl: &mut Gl, scene: &Scene, decal_projection: &[f32; 16]) -> Result<Image, String> {
    gl.clear(CLEAR, 1.0)?;
    gl.legacy_load_projection(&scene.plain())?;
    gl.legacy_draw_quad(&scene.floor(), FLOOR, &DrawState::default())?;
    gl.legacy_load_projection(decal_projection)?;
    gl.legacy_draw_quad(&scene.decal(), DECAL, &DrawState::default())?;
    gl.read_color()
}

/// The decal's own pixels: drawn alone on a cleared target.
fn decal_mask(gl: &mut Gl, scene: &Scene) -> Result<Vec<bool>, String> {
    gl.clear(CLEAR, 1.0)?;
    gl.legacy_load_projection(&scene.plain())?;
    gl.legacy_draw_quad(&scene.decal(), DECAL, &DrawState::default())?;
    Ok(gl.read_color()?.mask_of(rgba8(DECAL)))
}

/// Writes the image as an RGBA PNG, top row first.
fn write_png(path: &Path, image: &Image) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(
        std::io::BufWriter::new(file),
        image.width as u32,
        image.height as u32,
    );
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let rows = image.pixels.chunks_exact(image.width).rev();
    let data: Vec<u8> = rows.flatten().flatten().copied().collect();
    encoder
        .write_header()
        .and_then(|mut w| w.write_image_data(&data))
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// One scene's three renders: `(method, δ, the Pz it applies at, element 10, image, decal
/// pixels lost)`.
type Row = (&'static str, f64, f64, f32, Image, usize);

/// Renders `scene` three ways; returns the rows and the decal's pixel count.
fn compare(gl: &mut Gl, scene: &Scene) -> Result<(Vec<Row>, usize), String> {
    let pz = scene.plane_z(0.0); // the decal's centre, where the seed's δ is taken
    let (h, n, f) = (scene.half, scene.n, scene.f);
    let mask = decal_mask(gl, scene)?;
    let seed_delta = seed_min_delta(scene, pz);
    let seed_matrix = seed_load_offset_matrix(gl, scene, seed_delta as f32, pz as f32)?;
    // The recommendation's δ applies at the decal's farthest point, Pz = −d₂.
    let (rec, farthest) = recommendation(scene, snapping_of(gl))?;
    let far_pz = -farthest;
    let zshift_matrix = zshift::load_offset_matrix(-h, h, -h, h, n, f, rec.delta_at_far, far_pz)
        .map_err(|e| format!("zshift::load_offset_matrix: {e}"))?
        .to_cols_array();
    let mut rows = Vec::new();
    for (name, delta, at, matrix) in [
        ("none", 0.0, pz, scene.plain()),
        ("seed", seed_delta, pz, seed_matrix),
        ("zshift", rec.delta_at_far, far_pz, zshift_matrix),
    ] {
        let image = render(gl, scene, &matrix)?;
        let lost = image.count_not_in_mask(&mask, rgba8(DECAL));
        rows.push((name, delta, at, matrix[10], image, lost));
    }
    Ok((rows, mask.iter().filter(|&&m| m).count()))
}

/// The demonstration's scene: a floor at 45° (dz/dy = −1) under a frustum with
/// f/n = 10^7, the decal's centre 500 units away.
const MAIN: Scene = Scene {
    half: 0.05,
    n: 0.1,
    f: 1e6,
    z0: -500.0,
    slope: -1.0,
};

/// Renders the main scene, writes the three pictures, prints the table. Fails if zshift's
/// decal loses a pixel: that is the claim this demonstration shows.
fn demonstrate(gl: &mut Gl, out_dir: &Path) -> Result<(), String> {
    let (rows, decal_pixels) = compare(gl, &MAIN)?;
    let (rec, _) = recommendation(&MAIN, snapping_of(gl))?;
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    println!(
        "decal on a floor sloped dz/dy = {}, glFrustum(±{}, ±{}, n = {}, f = {}), decal centre at Pz = {}, {SIZE}x{SIZE} {}, {decal_pixels} decal pixels",
        MAIN.slope, MAIN.half, MAIN.half, MAIN.n, MAIN.f, MAIN.plane_z(0.0), DEPTH.name()
    );
    println!(
        "{:<8} {:>18} {:>14} {:>17}  picture",
        "method", "delta @ Pz", "element 10", "decal pixels lost"
    );
    for (name, delta, at, m10, image, lost) in &rows {
        let path = out_dir.join(format!("{name}.png"));
        write_png(&path, image)?;
        println!(
            "{name:<8} {:>18} {m10:>14.9} {lost:>8} ({:>5.1}%)  {}",
            format!("{delta:.4} @ {at}"),
            100.0 * *lost as f64 / decal_pixels as f64,
            path.display()
        );
    }
    let t = rec.terms;
    println!(
        "zshift's recommendation ({:?}, {}): window offset {:.3e} = quantum {:.3e} + 2 x (transform {:.3e} + vertex {:.3e} + interpolation {:.3e} + snap {:.3e}); bleed gap {:.4} eye units",
        snapping_of(gl), gl.renderer(), rec.window_offset, t.quantum, t.transform, t.vertex, t.interpolation, t.snap, rec.bleed_gap
    );
    match rows.iter().find(|r| r.0 == "zshift") {
        Some((_, _, _, _, _, 0)) => Ok(()),
        Some((_, _, _, _, _, lost)) => Err(format!("zshift's decal lost {lost} pixels")),
        None => Err("no zshift row".into()),
    }
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

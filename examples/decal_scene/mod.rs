//! The decal demonstration's scene, matrices and renders, shared by `examples/decal.rs`
//! (headless, EGL surfaceless) and `examples/decal_window.rs` (a window, glutin + winit).
//!
//! Both include this file with `#[path = "decal_scene/mod.rs"] mod decal_scene;`. Everything
//! that talks to GL goes through [`Canvas`], which the harness's headless [`Gl`] implements here
//! and the windowed example implements over its own context, so the two programs draw the same
//! quads with the same three projections and count lost pixels the same way.
//!
//! Conventions as zshift's: OpenGL right-handed eye space looking down −z, NDC depth [−1, 1],
//! column-major matrices.

use std::path::Path;

use zshift::recommend::{
    DepthFormat as RecommendFormat, Recommendation, Scene as RecommendScene, Snapping,
};
use zshift::Frustum;
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Image, Quad};

/// Framebuffer size: large enough to see the pattern, small enough for a software rasterizer.
pub const SIZE: u32 = 256;
/// The depth buffer the scene is drawn and the recommendation computed for.
pub const DEPTH: DepthFormat = DepthFormat::D24;
/// Background (black), floor (blue) and decal (red) colours.
pub const CLEAR: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
pub const FLOOR: [f32; 4] = [0.2, 0.35, 0.9, 1.0];
pub const DECAL: [f32; 4] = [0.95, 0.15, 0.1, 1.0];

/// A compatibility-profile OpenGL context drawing into a `SIZE × SIZE` RGBA8 target with a
/// [`DEPTH`] depth buffer, as the demonstration uses it: fixed-function projection
/// (`glMatrixMode(GL_PROJECTION)` + `glLoadMatrixf`), model-view identity, quads drawn with
/// the depth test `GL_LESS`, colour read back with `glReadPixels` (rows bottom-up).
///
/// Every method fails with the GL call that failed and why.
pub trait Canvas {
    /// `GL_RENDERER`.
    fn renderer(&self) -> String;
    /// `GL_SUBPIXEL_BITS`.
    fn subpixel_bits(&self) -> u32;
    /// The driver's own `glFrustum(l, r, b, t, n, f)` matrix, read back with
    /// `glGetFloatv(GL_PROJECTION_MATRIX)`.
    fn driver_frustum(
        &mut self,
        l: f64,
        r: f64,
        b: f64,
        t: f64,
        n: f64,
        f: f64,
    ) -> Result<[f32; 16], String>;
    /// `glClearColor(color)`, `glClearDepth(depth)`, `glClear` of the target.
    fn clear_target(&mut self, color: [f32; 4], depth: f64) -> Result<(), String>;
    /// `glMatrixMode(GL_PROJECTION); glLoadMatrixf(m)`.
    fn load_projection(&mut self, m: &[f32; 16]) -> Result<(), String>;
    /// Draws `quad` (eye-space corners) in flat `color` with the loaded projection, depth test
    /// `GL_LESS`, depth writes on.
    fn draw(&mut self, quad: &Quad, color: [f32; 4]) -> Result<(), String>;
    /// The target's colour, `SIZE × SIZE`.
    fn read_back(&mut self) -> Result<Image, String>;
}

/// The headless harness context (made with `Profile::Compatibility`, target set by the caller).
impl Canvas for Gl {
    fn renderer(&self) -> String {
        Gl::renderer(self)
    }
    fn subpixel_bits(&self) -> u32 {
        Gl::subpixel_bits(self)
    }
    fn driver_frustum(
        &mut self,
        l: f64,
        r: f64,
        b: f64,
        t: f64,
        n: f64,
        f: f64,
    ) -> Result<[f32; 16], String> {
        self.legacy_frustum(l, r, b, t, n, f)
    }
    fn clear_target(&mut self, color: [f32; 4], depth: f64) -> Result<(), String> {
        self.clear(color, depth)
    }
    fn load_projection(&mut self, m: &[f32; 16]) -> Result<(), String> {
        self.legacy_load_projection(m)
    }
    fn draw(&mut self, quad: &Quad, color: [f32; 4]) -> Result<(), String> {
        self.legacy_draw_quad(quad, color, &DrawState::default())
    }
    fn read_back(&mut self) -> Result<Image, String> {
        self.read_color()
    }
}

/// The camera and the plane: a symmetric frustum and the eye-space plane `z = z0 + slope·y`.
pub struct Scene {
    /// `glFrustum(-half, half, -half, half, n, f)`: the half-width of the near window, and the
    /// near and far distances.
    pub half: f64,
    pub n: f64,
    pub f: f64,
    /// Eye-space depth of the plane at y = 0 (negative).
    pub z0: f64,
    /// Eye-space `dz/dy`, negative: the plane recedes as it rises on screen, like a floor.
    pub slope: f64,
}

impl Scene {
    /// Eye-space z of the plane at eye-space height `y`.
    pub fn plane_z(&self, y: f64) -> f64 {
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

/// The demonstration's scene: a floor at 45° (dz/dy = −1) under a frustum with
/// f/n = 10^7, the decal's centre 500 units away.
pub const MAIN: Scene = Scene {
    half: 0.05,
    n: 0.1,
    f: 1e6,
    z0: -500.0,
    slope: -1.0,
};

/// How the rasterizer sets up depth, as the recommendation's error model takes it: Mesa's
/// llvmpipe interpolates depth from unsnapped positions (measured, `tests/gl_recommend.rs`);
/// any other driver is assumed to snap to `GL_SUBPIXEL_BITS`, the conservative case.
pub fn snapping_of(gl: &impl Canvas) -> Snapping {
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
pub fn recommendation(scene: &Scene, snapping: Snapping) -> Result<(Recommendation, f64), String> {
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
        depth_test: zshift::recommend::DepthTest::Less,
        base: zshift::recommend::Base::InsideFrustum,
        profile: zshift::recommend::RasterizerProfile {
            snapping: snapping,
            ..Default::default()
        },
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
    gl: &mut impl Canvas,
    s: &Scene,
    delta: f32,
    pz: f32,
) -> Result<[f32; 16], String> {
    let (h, n, f) = (s.half, s.n, s.f);
    let mut matrix = gl.driver_frustum(-h, h, -h, h, n, f)?;
    let (delta, pz) = (f64::from(delta), f64::from(pz));
    let epsilon = (-2.0 * f * n * delta / ((f + n) * pz * (pz + delta))) as f32;
    matrix[10] *= 1.0f32 + epsilon;
    Ok(matrix)
}

/// Draws the floor, then the decal with `decal_projection`, through `glLoadMatrixf`.
fn render(
    gl: &mut impl Canvas,
    scene: &Scene,
    decal_projection: &[f32; 16],
) -> Result<Image, String> {
    gl.clear_target(CLEAR, 1.0)?;
    gl.load_projection(&scene.plain())?;
    gl.draw(&scene.floor(), FLOOR)?;
    gl.load_projection(decal_projection)?;
    gl.draw(&scene.decal(), DECAL)?;
    gl.read_back()
}

/// The decal's own pixels: drawn alone on a cleared target.
fn decal_mask(gl: &mut impl Canvas, scene: &Scene) -> Result<Vec<bool>, String> {
    gl.clear_target(CLEAR, 1.0)?;
    gl.load_projection(&scene.plain())?;
    gl.draw(&scene.decal(), DECAL)?;
    Ok(gl.read_back()?.mask_of(rgba8(DECAL)))
}

/// Writes the image as an RGBA PNG, top row first.
pub fn write_png(path: &Path, image: &Image) -> Result<(), String> {
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
pub type Row = (&'static str, f64, f64, f32, Image, usize);

/// Renders `scene` three ways (none, seed, zshift); returns the rows and the decal's pixel count.
pub fn compare(gl: &mut impl Canvas, scene: &Scene) -> Result<(Vec<Row>, usize), String> {
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

/// Prints the main scene's table: one line per method (δ, element 10, decal pixels lost, and
/// the picture's path when `pictures` is given, where each is written as `<method>.png`), then
/// the terms of zshift's recommendation.
pub fn report(
    gl: &impl Canvas,
    rows: &[Row],
    decal_pixels: usize,
    pictures: Option<&Path>,
) -> Result<(), String> {
    let (rec, _) = recommendation(&MAIN, snapping_of(gl))?;
    println!(
        "decal on a floor sloped dz/dy = {}, glFrustum(±{}, ±{}, n = {}, f = {}), decal centre at Pz = {}, {SIZE}x{SIZE} {}, {decal_pixels} decal pixels",
        MAIN.slope, MAIN.half, MAIN.half, MAIN.n, MAIN.f, MAIN.plane_z(0.0), DEPTH.name()
    );
    println!(
        "{:<8} {:>18} {:>14} {:>17}  picture",
        "method", "delta @ Pz", "element 10", "decal pixels lost"
    );
    for (name, delta, at, m10, image, lost) in rows {
        let path = match pictures {
            Some(dir) => {
                let path = dir.join(format!("{name}.png"));
                write_png(&path, image)?;
                path.display().to_string()
            }
            None => String::new(),
        };
        println!(
            "{name:<8} {:>18} {m10:>14.9} {lost:>8} ({:>5.1}%)  {path}",
            format!("{delta:.4} @ {at}"),
            100.0 * *lost as f64 / decal_pixels as f64,
        );
    }
    let t = rec.terms;
    println!(
        "zshift's recommendation ({:?}, {}): window offset {:.3e} = quantum {:.3e} + 2 x (transform {:.3e} + vertex {:.3e} + interpolation {:.3e} + snap {:.3e}); bleed gap {:.4} eye units",
        snapping_of(gl), gl.renderer(), rec.window_offset, t.quantum, t.transform, t.vertex, t.interpolation, t.snap, rec.bleed_gap
    );
    Ok(())
}

/// The claim the demonstration shows: zshift's decal loses no pixel.
///
/// # Errors
/// How many pixels it lost, or that there is no zshift row.
pub fn verdict(rows: &[Row]) -> Result<(), String> {
    match rows.iter().find(|r| r.0 == "zshift") {
        Some((_, _, _, _, _, 0)) => Ok(()),
        Some((_, _, _, _, _, lost)) => Err(format!("zshift's decal lost {lost} pixels")),
        None => Err("no zshift row".into()),
    }
}

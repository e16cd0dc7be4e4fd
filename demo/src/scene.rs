//! The decal demonstration's scene, its five decal methods, the renders and the pixel counts,
//! shared by the headless demonstration (`src/main.rs`, EGL surfaceless) and the windowed one
//! (`src/bin/decal_window.rs`, glutin + winit).
//!
//! Everything that talks to GL goes through [`Canvas`], which the harness's headless [`Gl`]
//! implements here and the windowed binary implements over its own context, so the two programs
//! draw the same quads with the same projections and count pixels the same way.
//!
//! Conventions as zshift's: OpenGL right-handed eye space looking down −z, NDC depth [−1, 1],
//! column-major matrices.

use zshift::recommend::{
    DepthFormat as RecommendFormat, Recommendation, Scene as RecommendScene, Snapping,
};
use zshift::Frustum;
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Image, Quad};

/// Framebuffer size: large enough to see the pattern, small enough for a software rasterizer.
pub const SIZE: u32 = 256;
/// The depth buffer the scene is drawn and the recommendation computed for.
pub const DEPTH: DepthFormat = DepthFormat::D24;

/// A colour whose channels are exact 8-bit values, so dithering (on by default in GL) cannot
/// change them and each surface reads back as one exact colour.
const fn exact(r: u8, g: u8, b: u8) -> [f32; 4] {
    [r as f32 / 255.0, g as f32 / 255.0, b as f32 / 255.0, 1.0]
}
/// Background (black), floor (blue), plank (grey) and decal (red) colours.
pub const CLEAR: [f32; 4] = exact(0, 0, 0);
pub const FLOOR: [f32; 4] = exact(51, 89, 230);
pub const OCCLUDER: [f32; 4] = exact(191, 191, 178);
pub const DECAL: [f32; 4] = exact(242, 38, 26);
/// What a quad drawn alone for its mask is filled with.
const MASK: [f32; 4] = exact(255, 255, 255);

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
    /// `GL_LESS`, depth writes on, and `glPolygonOffset(factor, units)` with
    /// `GL_POLYGON_OFFSET_FILL` enabled when `polygon_offset` is given (disabled otherwise).
    fn draw(
        &mut self,
        quad: &Quad,
        color: [f32; 4],
        polygon_offset: Option<(f32, f32)>,
    ) -> Result<(), String>;
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
    fn draw(
        &mut self,
        quad: &Quad,
        color: [f32; 4],
        polygon_offset: Option<(f32, f32)>,
    ) -> Result<(), String> {
        let state = DrawState {
            polygon_offset,
            ..DrawState::default()
        };
        self.legacy_draw_quad(quad, color, &state)
    }
    fn read_back(&mut self) -> Result<Image, String> {
        self.read_color()
    }
}

/// The camera, the floor plane and the plank: a symmetric frustum, the eye-space plane
/// `z = z0 + slope·y`, and optionally a plank lying `occluder_gap` eye units above it.
#[derive(Clone, Copy, Debug)]
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
    /// The size of the floor, decal and plank: the floor spans `0.9·size` across, the decal
    /// `0.4·size` (eye units). The scenes are laid out with `size = −z0`, so they fill the
    /// same part of the view at any distance; moving the camera keeps `size`.
    pub size: f64,
    /// A grey plank parallel to the floor, this many eye-space units nearer the camera (along
    /// z), lying across the decal's right side: a decal offset by more than this shows through
    /// it (bleeds). `None`: no plank.
    pub occluder_gap: Option<f64>,
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
        let d = self.size;
        self.quad(0.45 * d, -0.3 * d, 0.35 * d)
    }

    /// Different vertices from the floor's, the same plane: a coplanar decal.
    fn decal(&self) -> Quad {
        let d = self.size;
        self.quad(0.2 * d, -0.15 * d, 0.15 * d)
    }

    /// The plank: over the decal's right side, reaching past its top and bottom edges.
    fn occluder(&self) -> Option<Quad> {
        let d = self.size;
        self.occluder_gap.map(|gap| {
            Quad::on_plane(0.06 * d, 0.14 * d, -0.25 * d, 0.25 * d, |_, y| {
                self.plane_z(y) + gap
            })
        })
    }

    fn plain(&self) -> [f32; 16] {
        let (h, n, f) = (self.half, self.n, self.f);
        zshift::frustum(-h, h, -h, h, n, f)
            .expect("the scene's frustum is valid")
            .to_cols_array()
    }

    /// The same floor, decal and plank with the camera moved `dz` eye units back along its
    /// axis: the animation's frames.
    pub fn moved(&self, dz: f64) -> Scene {
        Scene {
            z0: self.z0 - dz,
            ..*self
        }
    }
}

/// The demonstration's scene: a floor at 45° (dz/dy = −1) under a frustum with f/n = 10^7, the
/// decal's centre 500 units away, a plank 8 units above the floor across the decal.
pub const MAIN: Scene = Scene {
    half: 0.05,
    n: 0.1,
    f: 1e6,
    z0: -500.0,
    slope: -1.0,
    size: 500.0,
    occluder_gap: Some(8.0),
};

/// How a method offsets the decal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Offset {
    /// The plain `glFrustum` matrix.
    None,
    /// The seed's `LoadOffsetMatrix` (000, 4.1) as printed, with the seed's printed minimum δ.
    Seed,
    /// The plain matrix and `glPolygonOffset(factor, units)`.
    Polygon(f32, f32),
    /// zshift's recommendation (`zshift::recommend`) through `zshift::load_offset_matrix`.
    Zshift,
}

/// One method of the comparison: a short name (tables), the picture's two label lines, and
/// the offset.
#[derive(Clone, Copy, Debug)]
pub struct Method {
    pub name: &'static str,
    pub label: [&'static str; 2],
    pub offset: Offset,
}

/// The methods compared, in the picture's order: what engines do today, then zshift.
/// three.js's decal example (examples/webgl_decals.html) sets `polygonOffsetFactor: -4` (units
/// 0); Ogre's GL render systems turn a material's `depth_bias <constant> <slope>` into
/// `glPolygonOffset(-slope, -constant)`, so `depth_bias 1` is `glPolygonOffset(0, -1)`.
pub const METHODS: [Method; 5] = [
    Method {
        name: "none",
        label: ["NO OFFSET", "PLAIN GLFRUSTUM"],
        offset: Offset::None,
    },
    Method {
        name: "seed",
        label: ["LENGYEL 2004, F32", "LOADOFFSETMATRIX"],
        offset: Offset::Seed,
    },
    Method {
        name: "three.js",
        label: ["THREE.JS DECALS", "POLYGONOFFSET(-4,0)"],
        offset: Offset::Polygon(-4.0, 0.0),
    },
    Method {
        name: "ogre",
        label: ["OGRE DEPTH_BIAS 1", "POLYGONOFFSET(0,-1)"],
        offset: Offset::Polygon(0.0, -1.0),
    },
    Method {
        name: "zshift",
        label: ["ZSHIFT", "RECOMMENDED OFFSET"],
        offset: Offset::Zshift,
    },
];

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
/// scene — frustum, viewport, depth format, the decal's eye-space corners (from which
/// `decal_shape` finds its depths, slope and place on the screen), the rasterizer's snapping —
/// in, the offset that its error model guarantees out; also the decal's farthest distance d₂,
/// where the recommended δ applies.
pub fn recommendation(scene: &Scene, snapping: Snapping) -> Result<(Recommendation, f64), String> {
    let (h, n, f) = (scene.half, scene.n, scene.f);
    let frustum = Frustum::new(-h, h, -h, h, n, f).map_err(|e| e.to_string())?;
    let corners = scene
        .decal()
        .corners
        .map(|[x, y, z]| zshift::glam::Vec3::new(x, y, z));
    let shape = zshift::recommend::decal_shape(
        &frustum,
        zshift::projection::ClipDepth::NegOneToOne,
        [SIZE, SIZE],
        &corners,
    )
    .map_err(|e| format!("zshift::recommend::decal_shape: {e}"))?;
    let farthest = shape.depth_range[1];
    let model = RecommendScene {
        pipeline: Default::default(),
        footprint: Some(shape.footprint),
        frustum,
        viewport: [SIZE, SIZE],
        format: RecommendFormat::from_gl_internal_format(DEPTH.gl_enum())
            .map_err(|e| e.to_string())?,
        depth_range: shape.depth_range,
        slope: shape.slope,
        exact_depth: false,
        depth_test: zshift::recommend::DepthTest::Less,
        base: zshift::recommend::Base::InsideFrustum,
        profile: zshift::recommend::RasterizerProfile {
            snapping,
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

/// Draws the floor and the plank with the plain projection, then the decal with `projection`
/// and `polygon_offset`.
fn render(
    gl: &mut impl Canvas,
    scene: &Scene,
    projection: &[f32; 16],
    polygon_offset: Option<(f32, f32)>,
) -> Result<Image, String> {
    gl.clear_target(CLEAR, 1.0)?;
    gl.load_projection(&scene.plain())?;
    gl.draw(&scene.floor(), FLOOR, None)?;
    if let Some(plank) = scene.occluder() {
        gl.draw(&plank, OCCLUDER, None)?;
    }
    gl.load_projection(projection)?;
    gl.draw(&scene.decal(), DECAL, polygon_offset)?;
    gl.read_back()
}

/// The pixels `quad` covers, drawn alone on a cleared target with the plain projection.
fn mask(gl: &mut impl Canvas, scene: &Scene, quad: &Quad) -> Result<Vec<bool>, String> {
    gl.clear_target(CLEAR, 1.0)?;
    gl.load_projection(&scene.plain())?;
    gl.draw(quad, MASK, None)?;
    Ok(gl.read_back()?.mask_of(rgba8(MASK)))
}

/// One method's render of a scene and what its pixels show.
pub struct Row {
    pub method: Method,
    /// The eye-space shift asked for and the eye-space z it applies at (0 for none and for
    /// polygon offsets, which shift window depth instead).
    pub delta: f64,
    pub at: f64,
    /// Element 10 of the decal's projection.
    pub m10: f32,
    pub image: Image,
    /// Decal pixels the floor hid where nothing should (z-fighting): the decal's pixels outside
    /// the plank that do not show the decal's colour.
    pub lost: usize,
    /// Decal pixels drawn over the plank, which lies nearer the camera and should hide them.
    pub bled: usize,
}

/// A scene rendered by every method, with the figures the counts are out of.
pub struct Comparison {
    pub scene: Scene,
    pub rows: Vec<Row>,
    /// The decal's pixels that should show (outside the plank), and those the plank should hide.
    pub visible: usize,
    pub covered: usize,
    /// The decal's own pixels (drawn alone), indexed like [`Image::pixels`] (rows bottom-up).
    pub decal: Vec<bool>,
    pub recommendation: Recommendation,
}

/// Renders `scene` with every method of [`METHODS`] and counts each render's lost and bled
/// decal pixels from what `glReadPixels` returns.
pub fn compare(gl: &mut impl Canvas, scene: &Scene) -> Result<Comparison, String> {
    let pz = scene.plane_z(0.0); // the decal's centre, where the seed's δ is taken
    let (h, n, f) = (scene.half, scene.n, scene.f);
    let decal = mask(gl, scene, &scene.decal())?;
    let plank = match scene.occluder() {
        Some(q) => mask(gl, scene, &q)?,
        None => vec![false; decal.len()],
    };
    let seed_delta = seed_min_delta(scene, pz);
    let seed_matrix = seed_load_offset_matrix(gl, scene, seed_delta as f32, pz as f32)?;
    // The recommendation's δ applies at the decal's farthest point, Pz = −d₂.
    let (rec, farthest) = recommendation(scene, snapping_of(gl))?;
    let far_pz = -farthest;
    let zshift_matrix = zshift::load_offset_matrix(-h, h, -h, h, n, f, rec.delta_at_far, far_pz)
        .map_err(|e| format!("zshift::load_offset_matrix: {e}"))?
        .to_cols_array();
    let red = rgba8(DECAL);
    let mut rows = Vec::new();
    for method in METHODS {
        let (delta, at, projection, polygon_offset) = match method.offset {
            Offset::None => (0.0, pz, scene.plain(), None),
            Offset::Seed => (seed_delta, pz, seed_matrix, None),
            Offset::Polygon(factor, units) => (0.0, pz, scene.plain(), Some((factor, units))),
            Offset::Zshift => (rec.delta_at_far, far_pz, zshift_matrix, None),
        };
        let image = render(gl, scene, &projection, polygon_offset)?;
        let shows = image.mask_of(red);
        let count = |under_plank: bool, showing: bool| {
            (0..decal.len())
                .filter(|&i| decal[i] && plank[i] == under_plank && shows[i] == showing)
                .count()
        };
        let (lost, bled) = (count(false, false), count(true, true));
        let m10 = projection[10];
        rows.push(Row {
            method,
            delta,
            at,
            m10,
            image,
            lost,
            bled,
        });
    }
    let visible = (0..decal.len()).filter(|&i| decal[i] && !plank[i]).count();
    let covered = (0..decal.len()).filter(|&i| decal[i] && plank[i]).count();
    let recommendation = rec;
    Ok(Comparison {
        scene: *scene,
        rows,
        visible,
        covered,
        decal,
        recommendation,
    })
}

/// Prints the comparison: the scene, one line per method (δ, element 10, lost and bled decal
/// pixels), then the terms of zshift's recommendation.
pub fn report(gl: &impl Canvas, c: &Comparison) {
    let s = &c.scene;
    let rec = &c.recommendation;
    let plank = match s.occluder_gap {
        Some(gap) => format!(
            ", a plank {gap} units above the floor over {} more",
            c.covered
        ),
        None => String::new(),
    };
    println!(
        "decal on a floor sloped dz/dy = {}, glFrustum(±{}, ±{}, n = {}, f = {}), decal centre at Pz = {}, {SIZE}x{SIZE} {}: {} decal pixels to show{plank}",
        s.slope, s.half, s.half, s.n, s.f, s.plane_z(0.0), DEPTH.name(), c.visible
    );
    println!(
        "{:<9} {:>22} {:>18} {:>14} {:>16} {:>16}",
        "method", "offset", "delta @ Pz", "element 10", "lost", "bled"
    );
    for r in &c.rows {
        let offset = match r.method.offset {
            Offset::Polygon(factor, units) => format!("glPolygonOffset({factor}, {units})"),
            Offset::None => "none".into(),
            Offset::Seed => "LoadOffsetMatrix".into(),
            Offset::Zshift => "load_offset_matrix".into(),
        };
        println!(
            "{:<9} {offset:>22} {:>18} {:>14.9} {:>7} ({:>5.1}%) {:>7} ({:>5.1}%)",
            r.method.name,
            format!("{:.4} @ {}", r.delta, r.at),
            r.m10,
            r.lost,
            percent(r.lost, c.visible),
            r.bled,
            percent(r.bled, c.covered),
        );
    }
    let t = &rec.terms;
    println!(
        "zshift's recommendation ({:?}, {}): window offset {:.3e} = quantum {:.3e} + 2 x (transform {:.3e} + vertex {:.3e} + interpolation {:.3e} + snap {:.3e}); as glPolygonOffset ({:.2}, {:.2}); bleed gap {:.4} eye units",
        snapping_of(gl), gl.renderer(), rec.window_offset, t.quantum, t.transform, t.vertex, t.interpolation, t.snap,
        rec.polygon_offset[0], rec.polygon_offset[1], rec.bleed_gap
    );
}

/// `100·part/whole`, 0 for an empty whole.
pub fn percent(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        100.0 * part as f64 / whole as f64
    }
}

/// The claim the demonstration shows: zshift's decal loses no pixel and bleeds through nothing.
///
/// # Errors
/// How many pixels it lost and bled, or that there is no zshift row.
pub fn verdict(c: &Comparison) -> Result<(), String> {
    match c.rows.iter().find(|r| r.method.offset == Offset::Zshift) {
        Some(r) if r.lost == 0 && r.bled == 0 => Ok(()),
        Some(r) => Err(format!(
            "zshift's decal lost {} pixels and bled {} through the plank (decal centre at Pz = {})",
            r.lost,
            r.bled,
            c.scene.plane_z(0.0)
        )),
        None => Err("no zshift row".into()),
    }
}

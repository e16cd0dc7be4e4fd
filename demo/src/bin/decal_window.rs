//! The decal demonstration in a window (glutin + winit, X11 — or XWayland — through GLX or EGL),
//! for people with a display: the scene of the headless demonstration (`src/main.rs`), rendered
//! by the window's own OpenGL context with every method of `scene::METHODS` (no offset, the
//! seed's `LoadOffsetMatrix`, `glPolygonOffset` as three.js and Ogre set it, zshift's
//! recommended offset), side by side.
//!
//! ```sh
//! cargo run --release -p zshift-demo --features windowed --bin decal_window
//! cargo run --release -p zshift-demo --features windowed --bin decal_window -- --frames 3 --screenshot shot.png
//! ```
//!
//! Keys: `1` to `5` show one render filling the window (in the order of `scene::METHODS`), `0`
//! all of them, `Esc` quits. The lost and bled decal pixels of each are printed (the same table
//! as the headless demonstration) and shown in the title.
//!
//! Options: `--frames N` draws N frames and exits (for scripted runs, e.g. under Xvfb);
//! `--screenshot PATH` reads the window's back buffer with `glReadPixels` at the last frame
//! (the first one without `--frames`) and writes it as PNG, after checking that each panel
//! shown 1:1 equals, pixel for pixel, the render whose lost pixels were counted; `--egl` asks
//! for EGL first (the default is GLX, with EGL as the fallback).
//!
//! Each method is drawn into a `SIZE × SIZE` FBO with a 24-bit depth renderbuffer, exactly as the
//! headless demonstration draws (the shared `zshift_demo::scene` module holds the scene, the
//! methods and the counting), then blitted into the window: so the depth format is the one the
//! counts and the recommendation assume, whatever depth buffer the window's visual has. Needs an
//! OpenGL compatibility context (fixed-function `glFrustum`, `glLoadMatrixf`, `glBegin`), as
//! legacy engines use. Exits nonzero, with the reason, if no window or context can be made, or
//! if zshift's decal lost a pixel. Conventions as zshift's: OpenGL right-handed eye space
//! looking down −z, NDC depth [−1, 1], column-major matrices.

use std::ffi::c_void;
use std::num::NonZeroU32;
use std::path::PathBuf;

use glow::HasContext;
use glutin::config::{ConfigTemplateBuilder, GlConfig};
use glutin::context::{
    ContextApi, ContextAttributesBuilder, GlProfile, NotCurrentGlContext, PossiblyCurrentContext,
};
use glutin::display::{Display, GetGlDisplay, GlDisplay};
use glutin::surface::{GlSurface, Surface, SwapInterval, WindowSurface};
use glutin_winit::{ApiPreference, DisplayBuilder, GlWindow};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::raw_window_handle::HasWindowHandle;
use winit::window::{Window, WindowId};
use zshift_harness::{Image, Quad};

// The scene, the methods and the renders, shared with the headless demonstration.
use zshift_demo::picture::Picture;
use zshift_demo::scene::{compare, report, verdict, Canvas, Row, DEPTH, MAIN, SIZE};

/// Gap between panels and around them, in pixels.
const GAP: u32 = 8;
/// One panel per method.
const PANELS: usize = zshift_demo::scene::METHODS.len();
/// Window background, distinct from the renders' black clear colour.
const BACKGROUND: [f32; 4] = [0.3, 0.3, 0.3, 1.0];

const GL_SUBPIXEL_BITS: u32 = 0x0D50;
const GL_PROJECTION: u32 = 0x1701;
const GL_PROJECTION_MATRIX: u32 = 0x0BA7;
const GL_MODELVIEW: u32 = 0x1700;
const GL_QUADS: u32 = 0x0007;

/// Fixed-function entry points glow does not wrap (compatibility profile).
struct Fixed {
    matrix_mode: extern "system" fn(u32),
    load_identity: extern "system" fn(),
    frustum: extern "system" fn(f64, f64, f64, f64, f64, f64),
    load_matrixf: extern "system" fn(*const f32),
    begin: extern "system" fn(u32),
    end: extern "system" fn(),
    vertex3f: extern "system" fn(f32, f32, f32),
    color4f: extern "system" fn(f32, f32, f32, f32),
}

impl Fixed {
    /// Loads each entry point from the display; fails naming the first one missing.
    fn load(display: &Display) -> Result<Fixed, String> {
        macro_rules! entry {
            ($name:literal as $ty:ty) => {{
                let p = display.get_proc_address($name);
                if p.is_null() {
                    return Err(format!("the driver does not export {:?}", $name));
                }
                // SAFETY: `p` is the named GL entry point, whose C signature is the field's type.
                unsafe { std::mem::transmute::<*const c_void, $ty>(p) }
            }};
        }
        Ok(Fixed {
            matrix_mode: entry!(c"glMatrixMode" as extern "system" fn(u32)),
            load_identity: entry!(c"glLoadIdentity" as extern "system" fn()),
            frustum: entry!(c"glFrustum" as extern "system" fn(f64, f64, f64, f64, f64, f64)),
            load_matrixf: entry!(c"glLoadMatrixf" as extern "system" fn(*const f32)),
            begin: entry!(c"glBegin" as extern "system" fn(u32)),
            end: entry!(c"glEnd" as extern "system" fn()),
            vertex3f: entry!(c"glVertex3f" as extern "system" fn(f32, f32, f32)),
            color4f: entry!(c"glColor4f" as extern "system" fn(f32, f32, f32, f32)),
        })
    }
}

/// The window's context drawing into its own `SIZE × SIZE` RGBA8 + [`DEPTH`] FBO.
struct WindowCanvas {
    gl: glow::Context,
    fixed: Fixed,
    fbo: glow::Framebuffer,
}

impl WindowCanvas {
    fn new(gl: glow::Context, fixed: Fixed) -> Result<WindowCanvas, String> {
        let fbo = unsafe { framebuffer(&gl, DEPTH.gl_enum(), None)? };
        Ok(WindowCanvas { gl, fixed, fbo })
    }

    /// Fails with every pending GL error, named by `what`.
    fn check(&self, what: &str) -> Result<(), String> {
        zshift_harness::check_gl_errors(&self.gl, what)
    }

    fn bind(&self) {
        unsafe {
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo));
            self.gl.viewport(0, 0, SIZE as i32, SIZE as i32);
        }
    }
}

/// A `SIZE × SIZE` framebuffer with an RGBA8 colour attachment (a texture holding `pixels`
/// when given, else a renderbuffer) and, when `depth` is a format, a depth renderbuffer.
unsafe fn framebuffer(
    gl: &glow::Context,
    depth: u32,
    pixels: Option<&Image>,
) -> Result<glow::Framebuffer, String> {
    let (s, fb) = (SIZE as i32, glow::FRAMEBUFFER);
    let fbo = gl.create_framebuffer()?;
    gl.bind_framebuffer(fb, Some(fbo));
    if let Some(image) = pixels {
        let bytes: Vec<u8> = image.pixels.iter().flatten().copied().collect();
        let tex = gl.create_texture()?;
        gl.bind_texture(glow::TEXTURE_2D, Some(tex));
        gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
        gl.tex_image_2d(
            glow::TEXTURE_2D,
            0,
            glow::RGBA8 as i32,
            s,
            s,
            0,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
            glow::PixelUnpackData::Slice(Some(&bytes)),
        );
        gl.framebuffer_texture_2d(fb, glow::COLOR_ATTACHMENT0, glow::TEXTURE_2D, Some(tex), 0);
    } else {
        let color = gl.create_renderbuffer()?;
        gl.bind_renderbuffer(glow::RENDERBUFFER, Some(color));
        gl.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, s, s);
        gl.framebuffer_renderbuffer(fb, glow::COLOR_ATTACHMENT0, glow::RENDERBUFFER, Some(color));
        let depth_rb = gl.create_renderbuffer()?;
        gl.bind_renderbuffer(glow::RENDERBUFFER, Some(depth_rb));
        gl.renderbuffer_storage(glow::RENDERBUFFER, depth, s, s);
        gl.framebuffer_renderbuffer(
            fb,
            glow::DEPTH_ATTACHMENT,
            glow::RENDERBUFFER,
            Some(depth_rb),
        );
    }
    let status = gl.check_framebuffer_status(fb);
    gl.bind_framebuffer(fb, None);
    match status {
        glow::FRAMEBUFFER_COMPLETE => Ok(fbo),
        other => Err(format!("framebuffer incomplete: status 0x{other:04X}")),
    }
}

impl Canvas for WindowCanvas {
    fn renderer(&self) -> String {
        unsafe { self.gl.get_parameter_string(glow::RENDERER) }
    }
    fn subpixel_bits(&self) -> u32 {
        unsafe { self.gl.get_parameter_i32(GL_SUBPIXEL_BITS) as u32 }
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
        (self.fixed.matrix_mode)(GL_PROJECTION);
        (self.fixed.load_identity)();
        (self.fixed.frustum)(l, r, b, t, n, f);
        let mut m = [0.0f32; 16];
        unsafe {
            self.gl
                .get_parameter_f32_slice(GL_PROJECTION_MATRIX, &mut m)
        };
        self.check("glFrustum + glGetFloatv(GL_PROJECTION_MATRIX)")?;
        Ok(m)
    }
    fn clear_target(&mut self, color: [f32; 4], depth: f64) -> Result<(), String> {
        self.bind();
        unsafe {
            self.gl.color_mask(true, true, true, true);
            self.gl.depth_mask(true);
            self.gl.clear_color(color[0], color[1], color[2], color[3]);
            self.gl.clear_depth_f64(depth);
            self.gl
                .clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
        }
        self.check("clear")
    }
    fn load_projection(&mut self, m: &[f32; 16]) -> Result<(), String> {
        (self.fixed.matrix_mode)(GL_PROJECTION);
        (self.fixed.load_matrixf)(m.as_ptr());
        self.check("glLoadMatrixf")
    }
    fn draw(
        &mut self,
        quad: &Quad,
        color: [f32; 4],
        polygon_offset: Option<(f32, f32)>,
    ) -> Result<(), String> {
        self.bind();
        let f = &self.fixed;
        (f.matrix_mode)(GL_MODELVIEW);
        (f.load_identity)();
        unsafe {
            self.gl.enable(glow::DEPTH_TEST);
            self.gl.depth_func(glow::LESS);
            self.gl.depth_mask(true);
            match polygon_offset {
                Some((factor, units)) => {
                    self.gl.enable(glow::POLYGON_OFFSET_FILL);
                    self.gl.polygon_offset(factor, units);
                }
                None => self.gl.disable(glow::POLYGON_OFFSET_FILL),
            }
        }
        (f.begin)(GL_QUADS);
        (f.color4f)(color[0], color[1], color[2], color[3]);
        for [x, y, z] in quad.corners {
            (f.vertex3f)(x, y, z);
        }
        (f.end)();
        self.check("glBegin(GL_QUADS) .. glEnd")
    }
    fn read_back(&mut self) -> Result<Image, String> {
        self.bind();
        let image = unsafe { read_pixels(&self.gl, glow::COLOR_ATTACHMENT0, SIZE, SIZE) };
        self.check("glReadPixels(GL_RGBA)")?;
        Ok(image)
    }
}

/// `glReadPixels(GL_RGBA, GL_UNSIGNED_BYTE)` of the bound framebuffer's `buffer`, rows bottom-up.
unsafe fn read_pixels(gl: &glow::Context, buffer: u32, width: u32, height: u32) -> Image {
    let mut bytes = vec![0u8; (width * height * 4) as usize];
    gl.finish();
    gl.read_buffer(buffer);
    gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
    gl.read_pixels(
        0,
        0,
        width as i32,
        height as i32,
        glow::RGBA,
        glow::UNSIGNED_BYTE,
        glow::PixelPackData::Slice(Some(&mut bytes)),
    );
    Image {
        width: width as usize,
        height: height as usize,
        pixels: bytes
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect(),
    }
}

/// Which renders the window shows: all side by side, or one filling it.
#[derive(Clone, Copy, PartialEq)]
enum View {
    All,
    One(usize),
}

/// Where each shown panel goes in a `width × height` window: `(row index, x, y, side)`, origin
/// bottom-left, panels square and as large as fits, centred.
fn layout(view: View, width: u32, height: u32) -> Vec<(usize, u32, u32, u32)> {
    let shown: Vec<usize> = match view {
        View::All => (0..PANELS).collect(),
        View::One(i) => vec![i],
    };
    let k = shown.len() as u32;
    let side = (width.saturating_sub((k + 1) * GAP) / k).min(height.saturating_sub(2 * GAP));
    let x0 = width.saturating_sub(k * side + (k - 1) * GAP) / 2;
    let y0 = height.saturating_sub(side) / 2;
    shown
        .into_iter()
        .enumerate()
        .map(|(slot, row)| (row, x0 + slot as u32 * (side + GAP), y0, side))
        .collect()
}

/// Checks that every panel of `shot` shown at 1:1 equals the render it came from, so the
/// picture shows what was counted.
///
/// # Errors
/// A panel that differs (how many pixels), or no panel at 1:1 to check.
fn check_panels(
    shot: &Image,
    panels: &[(usize, u32, u32, u32)],
    rows: &[Row],
) -> Result<usize, String> {
    let mut checked = 0;
    for &(row, x0, y0, side) in panels.iter().filter(|p| p.3 == SIZE) {
        let image = &rows[row].image;
        let differ = (0..side as usize)
            .flat_map(|y| (0..side as usize).map(move |x| (x, y)))
            .filter(|&(x, y)| shot.at(x0 as usize + x, y0 as usize + y) != image.at(x, y))
            .count();
        if differ > 0 {
            return Err(format!(
                "the window's {} panel differs from the counted render in {differ} pixels",
                rows[row].method.name
            ));
        }
        checked += 1;
    }
    match checked {
        0 => Err(
            "no panel is shown 1:1 (window resized?): nothing to check the screenshot against"
                .into(),
        ),
        n => Ok(n),
    }
}

/// The command line: `--frames N`, `--screenshot PATH`, `--egl`.
struct Options {
    frames: Option<u64>,
    screenshot: Option<PathBuf>,
    egl: bool,
}

impl Options {
    fn parse() -> Result<Options, String> {
        let mut options = Options {
            frames: None,
            screenshot: None,
            egl: false,
        };
        let mut args = std::env::args().skip(1);
        while let Some(arg) = args.next() {
            let mut value = || args.next().ok_or(format!("{arg} needs a value"));
            match arg.as_str() {
                "--frames" => {
                    let v = value()?;
                    let n = v.parse().map_err(|e| format!("--frames {v}: {e}"))?;
                    options.frames = Some(n).filter(|&n| n > 0);
                    if options.frames.is_none() {
                        return Err("--frames must be at least 1".into());
                    }
                }
                "--screenshot" => options.screenshot = Some(PathBuf::from(value()?)),
                "--egl" => options.egl = true,
                _ => {
                    return Err(format!(
                        "unknown argument {arg:?} (usage: decal_window [--frames N] [--screenshot PATH] [--egl])"
                    ))
                }
            }
        }
        Ok(options)
    }

    /// The frame whose back buffer the screenshot takes: the last, or the first if unbounded.
    fn screenshot_frame(&self) -> u64 {
        self.frames.unwrap_or(1)
    }
}

/// Everything that lives while the window is open. Fields drop in order: GL objects and the
/// surface before the window whose handle they were made from.
struct Running {
    canvas: WindowCanvas,
    panels: Vec<glow::Framebuffer>,
    rows: Vec<Row>,
    surface: Surface<WindowSurface>,
    context: PossiblyCurrentContext,
    window: Window,
}

struct App {
    options: Options,
    running: Option<Running>,
    view: View,
    frames: u64,
    /// The first error met; the process exits nonzero with it once the loop ends.
    error: Option<String>,
}

impl App {
    /// Opens the window, makes a compatibility context current on it, renders and counts the
    /// methods, and uploads the renders as the panels to show.
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<Running, String> {
        let k = PANELS as u32;
        let (w, h) = (k * SIZE + (k + 1) * GAP, SIZE + 2 * GAP);
        let attributes = Window::default_attributes()
            .with_title("zshift: decal")
            .with_inner_size(PhysicalSize::new(w, h));
        // The fewest samples: glBlitFramebuffer into a multisampled window is an error.
        let preference = match self.options.egl {
            true => ApiPreference::PreferEgl,
            false => ApiPreference::FallbackEgl,
        };
        let (window, config) = DisplayBuilder::new()
            .with_preference(preference)
            .with_window_attributes(Some(attributes))
            .build(event_loop, ConfigTemplateBuilder::new(), |configs| {
                configs
                    .min_by_key(|c| c.num_samples())
                    .expect("the display offers no GL config at all")
            })
            .map_err(|e| format!("no GL display or window: {e}"))?;
        let window = window.ok_or("the display builder made no window")?;
        let handle = window
            .window_handle()
            .map_err(|e| format!("window handle: {e}"))?
            .as_raw();
        let display = config.display();
        let attributes = ContextAttributesBuilder::new()
            .with_context_api(ContextApi::OpenGl(None))
            .with_profile(GlProfile::Compatibility)
            .build(Some(handle));
        let context = unsafe { display.create_context(&config, &attributes) }
            .map_err(|e| format!("no OpenGL compatibility context: {e}"))?;
        let surface_attributes = window
            .build_surface_attributes(Default::default())
            .map_err(|e| format!("window surface attributes: {e}"))?;
        let surface = unsafe { display.create_window_surface(&config, &surface_attributes) }
            .map_err(|e| format!("window surface: {e}"))?;
        let context = context
            .make_current(&surface)
            .map_err(|e| format!("make current: {e}"))?;
        let interval = match self.options.frames {
            Some(_) => SwapInterval::DontWait,
            None => SwapInterval::Wait(NonZeroU32::MIN),
        };
        let _ = surface.set_swap_interval(&context, interval); // a preference, not a need
        let gl =
            unsafe { glow::Context::from_loader_function_cstr(|s| display.get_proc_address(s)) };
        let mut canvas = WindowCanvas::new(gl, Fixed::load(&display)?)?;
        let api = display.version_string();
        println!(
            "{} on {} through {api}",
            unsafe { canvas.gl.get_parameter_string(glow::VERSION) },
            canvas.renderer()
        );
        let comparison = compare(&mut canvas, &MAIN)?;
        report(&canvas, &comparison);
        if let Err(e) = verdict(&comparison) {
            self.error.get_or_insert(e);
        }
        let panels = (comparison.rows.iter())
            .map(|row| unsafe { framebuffer(&canvas.gl, 0, Some(&row.image)) })
            .collect::<Result<Vec<_>, String>>()?;
        canvas.check("panel textures")?;
        window.set_title(&title(&comparison.rows));
        let rows = comparison.rows;
        window.request_redraw();
        Ok(Running {
            canvas,
            panels,
            rows,
            surface,
            context,
            window,
        })
    }

    /// Draws one frame: the panels blitted into the back buffer; the screenshot if this is its
    /// frame; the swap.
    fn redraw(&mut self) -> Result<(), String> {
        let Some(r) = self.running.as_ref() else {
            return Ok(());
        };
        let size = r.window.inner_size();
        let panels = layout(self.view, size.width, size.height);
        let gl = &r.canvas.gl;
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
            gl.viewport(0, 0, size.width as i32, size.height as i32);
            let [red, green, blue, alpha] = BACKGROUND;
            gl.clear_color(red, green, blue, alpha);
            gl.clear(glow::COLOR_BUFFER_BIT);
            for &(row, x, y, side) in &panels {
                gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(r.panels[row]));
                let (x, y, side, s) = (x as i32, y as i32, side as i32, SIZE as i32);
                let filter = glow::NEAREST; // magnified pixels stay pixels: the pattern is the point
                let bits = glow::COLOR_BUFFER_BIT;
                gl.blit_framebuffer(0, 0, s, s, x, y, x + side, y + side, bits, filter);
            }
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        r.canvas.check("blit to the window")?;
        self.frames += 1;
        if let Some(path) = self.options.screenshot.as_ref() {
            if self.frames == self.options.screenshot_frame() {
                let shot = unsafe { read_pixels(gl, glow::BACK, size.width, size.height) };
                r.canvas.check("glReadPixels(GL_BACK)")?;
                let n = check_panels(&shot, &panels, &r.rows)?;
                Picture::from_image(&shot).write_png(path)?;
                println!(
                    "screenshot {} ({}x{}): {n} panel(s) equal the counted renders pixel for pixel",
                    path.display(),
                    size.width,
                    size.height
                );
            }
        }
        r.surface
            .swap_buffers(&r.context)
            .map_err(|e| format!("swap buffers: {e}"))
    }

    /// Records the first error and ends the loop.
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: String) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }
}

/// The window title: each method's lost pixels, and the keys.
fn title(rows: &[Row]) -> String {
    let counts: Vec<String> = (rows.iter())
        .map(|r| format!("{}: {} lost, {} bled", r.method.name, r.lost, r.bled))
        .collect();
    format!(
        "zshift decal | {} | keys 1-{PANELS} one, 0 all, Esc quit",
        counts.join(" | ")
    )
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_none() && self.error.is_none() {
            match self.start(event_loop) {
                Ok(r) => self.running = Some(r),
                Err(e) => self.fail(event_loop, e),
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(r) = self.running.as_ref() {
                    if let (Some(w), Some(h)) =
                        (NonZeroU32::new(size.width), NonZeroU32::new(size.height))
                    {
                        r.surface.resize(&r.context, w, h);
                    }
                    r.window.request_redraw();
                }
            }
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        logical_key,
                        state: ElementState::Pressed,
                        ..
                    },
                ..
            } => {
                self.view = match logical_key.as_ref() {
                    Key::Named(NamedKey::Escape) => return event_loop.exit(),
                    Key::Character("0") => View::All,
                    Key::Character(c) => match c.parse::<usize>() {
                        Ok(k) if (1..=PANELS).contains(&k) => View::One(k - 1),
                        _ => return,
                    },
                    _ => return,
                };
                if let Some(r) = self.running.as_ref() {
                    r.window.request_redraw();
                }
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.redraw() {
                    return self.fail(event_loop, e);
                }
                match self.options.frames {
                    Some(n) if self.frames >= n => event_loop.exit(),
                    Some(_) => self.running.iter().for_each(|r| r.window.request_redraw()),
                    None => {}
                }
            }
            _ => {}
        }
    }
}

fn main() {
    let result = Options::parse().and_then(|options| {
        let event_loop =
            EventLoop::new().map_err(|e| format!("no event loop (no display?): {e}"))?;
        let mut app = App {
            options,
            running: None,
            view: View::All,
            frames: 0,
            error: None,
        };
        event_loop
            .run_app(&mut app)
            .map_err(|e| format!("event loop: {e}"))?;
        app.error.map_or(Ok(()), Err)
    });
    if let Err(e) = result {
        eprintln!("decal_window: {e}");
        std::process::exit(1);
    }
}

//! Headless OpenGL for zshift's rendered tests and sweeps: a real rasterizer (Mesa llvmpipe, or
//! any EGL driver) with no window, an FBO with a chosen depth format, quads drawn with a given
//! projection matrix, and colour and depth read back with `glReadPixels`.
//!
//! Not part of the shipped library: only zshift's tests and examples depend on this crate.
//!
//! # How a context is made
//! EGL on the surfaceless platform (`EGL_PLATFORM_SURFACELESS_MESA`, 0x31DD), or on an
//! enumerated device where there is none (a GPU vendor's EGL; `ZSHIFT_EGL_PLATFORM=device`
//! asks for it), no config where `EGL_KHR_no_config_context` allows, no surface: every draw
//! goes to the [`Gl`]'s own FBO. See `../shared/NOTES.md` for why this recipe (eglChooseConfig
//! finds nothing on Mesa's surfaceless display; the viewport starts at 0×0).
//!
//! # Conventions
//! As zshift's: OpenGL right-handed eye space looking down −z, NDC depth `[−1, 1]` (unless
//! [`Gl::clip_control`] says otherwise), column-major `[f32; 16]` matrices, window depth in
//! `[0, 1]`. The model-view matrix is the identity: [`Quad`] corners are given in eye space,
//! and the vertex shader computes `gl_Position = proj * vec4(eye, 1)`.
//!
//! # Errors
//! Everything that talks to GL returns `Result<_, String>`; the string says which call failed
//! and why (EGL error, GL error code, incomplete framebuffer, shader log), so a test that
//! cannot get a context fails with the reason instead of skipping.
//!
//! # Example
//! ```no_run
//! use zshift_harness::{DepthFormat, DrawState, Gl, Profile, Quad};
//! let mut gl = Gl::new(Profile::Core)?;
//! gl.set_target(64, 64, DepthFormat::D24)?;
//! gl.clear([0.0, 0.0, 0.0, 1.0], 1.0)?;
//! let proj: [f32; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.2, -1.0, 0.0, 0.0, -2.2, 0.0];
//! let quad = Quad::rect(-1.0, 1.0, -1.0, 1.0, -5.0);
//! gl.draw_quad(&quad, &proj, [1.0, 0.0, 0.0, 1.0], &DrawState::default())?;
//! let depth = gl.read_depth()?;
//! # Ok::<(), String>(())
//! ```

use std::ffi::c_void;

use glow::HasContext;
use khronos_egl as egl;

/// The glow crate, re-exported so tests can name GL enums (`zshift_harness::glow::ALWAYS`).
pub use glow;

pub mod coplanar;
mod display;
pub mod draw;
pub mod edges;
pub mod msaa;
pub mod shadow_scene;
pub mod world;

/// `GL_SUBPIXEL_BITS`: bits of sub-pixel precision the rasterizer snaps window x, y to.
const GL_SUBPIXEL_BITS: u32 = 0x0D50;
/// `GL_PROJECTION` matrix mode and `GL_PROJECTION_MATRIX` query (compatibility profile).
const GL_PROJECTION: u32 = 0x1701;
const GL_PROJECTION_MATRIX: u32 = 0x0BA7;
const GL_MODELVIEW: u32 = 0x1700;
const GL_QUADS: u32 = 0x0007;

/// Which OpenGL profile [`Gl::new`] asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// OpenGL 3.3 core (Mesa gives 4.5 core): shaders only.
    Core,
    /// The compatibility profile: fixed-function `glFrustum`, `glLoadMatrixf`, `glBegin` as
    /// legacy engines use them, besides the shader path.
    Compatibility,
}

/// The depth attachment's internal format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DepthFormat {
    /// `GL_DEPTH_COMPONENT16`: 16-bit unsigned normalized.
    D16,
    /// `GL_DEPTH_COMPONENT24`: 24-bit unsigned normalized.
    D24,
    /// `GL_DEPTH_COMPONENT32F`: 32-bit float.
    D32F,
}

impl DepthFormat {
    /// All three formats, in the order above.
    pub const ALL: [DepthFormat; 3] = [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F];

    /// The GL internal format enum.
    pub fn gl_enum(self) -> u32 {
        match self {
            DepthFormat::D16 => glow::DEPTH_COMPONENT16,
            DepthFormat::D24 => glow::DEPTH_COMPONENT24,
            DepthFormat::D32F => glow::DEPTH_COMPONENT32F,
        }
    }

    /// The nominal bits of the format (16, 24, 32).
    pub fn bits(self) -> u32 {
        match self {
            DepthFormat::D16 => 16,
            DepthFormat::D24 => 24,
            DepthFormat::D32F => 32,
        }
    }

    /// A short name for tables: "D16", "D24", "D32F".
    pub fn name(self) -> &'static str {
        match self {
            DepthFormat::D16 => "D16",
            DepthFormat::D24 => "D24",
            DepthFormat::D32F => "D32F",
        }
    }
}

/// `glClipControl` depth mode (GL 4.5 / ARB_clip_control).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClipDepth {
    /// `GL_NEGATIVE_ONE_TO_ONE`: the default, NDC depth `[−1, 1]`.
    NegativeOneToOne,
    /// `GL_ZERO_TO_ONE`: NDC depth `[0, 1]` (for reversed Z with float depth).
    ZeroToOne,
}

/// Four eye-space corners of a planar quad, in order around it (drawn as a triangle fan:
/// triangles 0-1-2 and 0-2-3, so the diagonal 0-2 is shared).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quad {
    /// Corners `[x, y, z]` in eye space (z negative in front of the camera).
    pub corners: [[f32; 3]; 4],
}

impl Quad {
    /// An axis-aligned rectangle `[x0, x1] × [y0, y1]` facing the camera at eye-space `z`.
    pub fn rect(x0: f32, x1: f32, y0: f32, y1: f32, z: f32) -> Self {
        Quad {
            corners: [[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]],
        }
    }

    /// Corners computed by `f(x, y) -> z` at the rectangle's corners (f64, rounded to f32 once):
    /// a plane tilted by giving z as an affine function of eye-space x and y.
    pub fn on_plane(x0: f64, x1: f64, y0: f64, y1: f64, z: impl Fn(f64, f64) -> f64) -> Self {
        let c = |x: f64, y: f64| [x as f32, y as f32, z(x, y) as f32];
        Quad {
            corners: [c(x0, y0), c(x1, y0), c(x1, y1), c(x0, y1)],
        }
    }
}

/// Per-draw fixed-function state. The default is the usual opaque draw: depth test `GL_LESS`,
/// depth writes on, colour writes on, no polygon offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawState {
    /// `glDepthFunc` (e.g. `glow::LESS`, `glow::LEQUAL`, `glow::GREATER`).
    pub depth_func: u32,
    /// `glDepthMask`.
    pub depth_write: bool,
    /// `glColorMask` for all four channels.
    pub color_write: bool,
    /// `glPolygonOffset(factor, units)` with `GL_POLYGON_OFFSET_FILL` enabled, or none.
    pub polygon_offset: Option<(f32, f32)>,
}

impl Default for DrawState {
    fn default() -> Self {
        DrawState {
            depth_func: glow::LESS,
            depth_write: true,
            color_write: true,
            polygon_offset: None,
        }
    }
}

/// A pixel rectangle `[x0, x1) × [y0, y1)` in window coordinates (origin bottom-left, as
/// `glReadPixels` returns rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    /// First column inside.
    pub x0: usize,
    /// First row inside.
    pub y0: usize,
    /// First column past the region.
    pub x1: usize,
    /// First row past the region.
    pub y1: usize,
}

/// Colour pixels read back from the target, RGBA8, rows bottom-up.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width × height` RGBA8 pixels, row by row from the bottom.
    pub pixels: Vec<[u8; 4]>,
}

impl Image {
    /// The pixel at window `(x, y)`.
    pub fn at(&self, x: usize, y: usize) -> [u8; 4] {
        self.pixels[y * self.width + x]
    }

    /// Where the pixel equals `color` (compared on RGB; alpha ignored).
    pub fn mask_of(&self, color: [u8; 4]) -> Vec<bool> {
        self.pixels.iter().map(|p| p[..3] == color[..3]).collect()
    }

    /// How many pixels equal `color` (RGB), optionally only inside `region`.
    pub fn count(&self, color: [u8; 4], region: Option<Region>) -> usize {
        let r = region.unwrap_or(Region {
            x0: 0,
            y0: 0,
            x1: self.width,
            y1: self.height,
        });
        (r.y0..r.y1.min(self.height))
            .flat_map(|y| (r.x0..r.x1.min(self.width)).map(move |x| (x, y)))
            .filter(|&(x, y)| self.at(x, y)[..3] == color[..3])
            .count()
    }

    /// How many pixels inside `mask` do not equal `color` (RGB): e.g. decal pixels lost.
    pub fn count_not_in_mask(&self, mask: &[bool], color: [u8; 4]) -> usize {
        self.pixels
            .iter()
            .zip(mask)
            .filter(|(p, &m)| m && p[..3] != color[..3])
            .count()
    }
}

/// Converts a `[0, 1]` float colour to the RGBA8 value the framebuffer stores.
pub fn rgba8(c: [f32; 4]) -> [u8; 4] {
    c.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The framebuffer every draw goes to.
struct Target {
    fbo: glow::Framebuffer,
    color: glow::Renderbuffer,
    depth: glow::Renderbuffer,
    width: i32,
    height: i32,
    format: DepthFormat,
    /// A multisampled target's colour and the objects that read it sample by sample
    /// ([`msaa::Samples`]); `None` single-sampled (`color` is then the colour).
    samples: Option<msaa::Samples>,
}

/// Fixed-function entry points glow does not wrap (compatibility profile), and glClipControl.
#[allow(clippy::type_complexity)]
struct Legacy {
    matrix_mode: Option<extern "system" fn(u32)>,
    load_identity: Option<extern "system" fn()>,
    frustum: Option<extern "system" fn(f64, f64, f64, f64, f64, f64)>,
    load_matrixf: Option<extern "system" fn(*const f32)>,
    begin: Option<extern "system" fn(u32)>,
    end: Option<extern "system" fn()>,
    vertex3f: Option<extern "system" fn(f32, f32, f32)>,
    color4f: Option<extern "system" fn(f32, f32, f32, f32)>,
    clip_control: Option<extern "system" fn(u32, u32)>,
}

/// A current OpenGL context on this thread, with its own FBO target and quad shader.
///
/// Not `Send`: an EGL context is current on the thread that made it. Each test makes its own.
pub struct Gl {
    egl: egl::Instance<egl::Static>,
    display: egl::Display,
    context: egl::Context,
    gl: glow::Context,
    profile: Profile,
    program: glow::Program,
    vao: glow::VertexArray,
    vbo: glow::Buffer,
    legacy: Legacy,
    target: Option<Target>,
    /// The world-space mesh pipeline of [`world`], made on first use.
    world: Option<(glow::Program, glow::VertexArray, glow::Buffer)>,
    _not_send: std::marker::PhantomData<*const ()>,
}

impl Gl {
    /// Makes a surfaceless EGL context of the given profile current on this thread, and
    /// compiles the quad shader.
    ///
    /// # Errors
    /// The failing EGL step and its error (no surfaceless platform, no context of that
    /// profile, ...), or the shader compiler's log.
    pub fn new(profile: Profile) -> Result<Gl, String> {
        let egl = egl::Instance::new(egl::Static);
        let (display, found) = display::open(&egl)?;
        let extensions = egl
            .query_string(Some(display), egl::EXTENSIONS)
            .map_err(|e| format!("eglQueryString(EGL_EXTENSIONS) failed on {found}: {e}"))?
            .to_string_lossy()
            .into_owned();
        if !extensions.contains("EGL_KHR_surfaceless_context") {
            return Err(format!(
                "EGL on {found} lacks EGL_KHR_surfaceless_context; it offers: {extensions}"
            ));
        }
        let config = display::config(&egl, display, &extensions)?;
        egl.bind_api(egl::OPENGL_API)
            .map_err(|e| format!("eglBindAPI(EGL_OPENGL_API) failed: {e}"))?;
        let attribs: &[egl::Int] = match profile {
            Profile::Core => &[
                egl::CONTEXT_MAJOR_VERSION,
                3,
                egl::CONTEXT_MINOR_VERSION,
                3,
                egl::CONTEXT_OPENGL_PROFILE_MASK,
                egl::CONTEXT_OPENGL_CORE_PROFILE_BIT,
                egl::NONE,
            ],
            Profile::Compatibility => &[
                egl::CONTEXT_OPENGL_PROFILE_MASK,
                egl::CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                egl::NONE,
            ],
        };
        let context = egl
            .create_context(display, config, None, attribs)
            .map_err(|e| format!("eglCreateContext({profile:?}) on {found} failed: {e}"))?;
        if let Err(e) = egl.make_current(display, None, None, Some(context)) {
            let _ = egl.destroy_context(display, context);
            return Err(format!("eglMakeCurrent(EGL_NO_SURFACE) failed: {e}"));
        }
        let load = |name: &str| -> *const c_void {
            egl.get_proc_address(name)
                .map_or(std::ptr::null(), |f| f as *const c_void)
        };
        // SAFETY: the context is current on this thread; EGL returns its entry points.
        let gl = unsafe { glow::Context::from_loader_function(load) };
        let legacy = Legacy::load(&egl);
        let (program, vao, vbo) = match unsafe { quad_pipeline(&gl) } {
            Ok(p) => p,
            Err(e) => {
                let _ = egl.make_current(display, None, None, None);
                let _ = egl.destroy_context(display, context);
                return Err(e);
            }
        };
        Ok(Gl {
            egl,
            display,
            context,
            gl,
            profile,
            program,
            vao,
            vbo,
            legacy,
            target: None,
            world: None,
            _not_send: std::marker::PhantomData,
        })
    }

    /// The profile this context was made with.
    pub fn profile(&self) -> Profile {
        self.profile
    }

    /// The raw glow context, for state this harness does not wrap.
    pub fn glow(&self) -> &glow::Context {
        &self.gl
    }

    /// `GL_RENDERER`, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub fn renderer(&self) -> String {
        unsafe { self.gl.get_parameter_string(glow::RENDERER) }
    }

    /// `GL_VERSION`, e.g. "4.5 (Core Profile) Mesa 22.3.6".
    pub fn version(&self) -> String {
        unsafe { self.gl.get_parameter_string(glow::VERSION) }
    }

    /// `GL_SUBPIXEL_BITS`: window x and y are snapped to `2^-bits` of a pixel before
    /// rasterization (llvmpipe reports 8).
    pub fn subpixel_bits(&self) -> u32 {
        unsafe { self.gl.get_parameter_i32(GL_SUBPIXEL_BITS) as u32 }
    }

    /// Makes (or replaces) the render target: an FBO with an RGBA8 colour renderbuffer and a
    /// depth renderbuffer of `format`, `width × height`, bound, with `glViewport` covering it.
    ///
    /// # Errors
    /// A zero size, a GL error, or an incomplete framebuffer (with its status).
    pub fn set_target(
        &mut self,
        width: u32,
        height: u32,
        format: DepthFormat,
    ) -> Result<(), String> {
        self.set_target_samples(width, height, format, false, 1)
    }

    /// The FBO behind [`Gl::set_target`] and [`Gl::set_target_with_stencil`]: RGBA8 colour and
    /// a depth (or depth-stencil) renderbuffer of `internal` format at `attachment`.
    fn make_target(
        &mut self,
        width: u32,
        height: u32,
        format: DepthFormat,
        internal: u32,
        attachment: u32,
        samples: u32,
    ) -> Result<(), String> {
        if width == 0 || height == 0 {
            return Err("the render target needs a nonzero width and height".into());
        }
        self.drop_target();
        let (w, h) = (width as i32, height as i32);
        let gl = &self.gl;
        unsafe {
            let fbo = gl.create_framebuffer()?;
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
            // Single-sampled: this renderbuffer is the colour. Multisampled: the colour is a
            // multisampled texture (a shader reads its samples one by one) and this renderbuffer
            // the single-sampled copy a sample is read from.
            let color = gl.create_renderbuffer()?;
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(color));
            gl.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, w, h);
            let ms = if samples > 1 {
                Some(msaa::Samples::new(gl, fbo, color, w, h, samples)?)
            } else {
                gl.framebuffer_renderbuffer(
                    glow::FRAMEBUFFER,
                    glow::COLOR_ATTACHMENT0,
                    glow::RENDERBUFFER,
                    Some(color),
                );
                None
            };
            let depth = gl.create_renderbuffer()?;
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(depth));
            if samples > 1 {
                gl.renderbuffer_storage_multisample(
                    glow::RENDERBUFFER,
                    samples as i32,
                    internal,
                    w,
                    h,
                );
            } else {
                gl.renderbuffer_storage(glow::RENDERBUFFER, internal, w, h);
            }
            gl.framebuffer_renderbuffer(
                glow::FRAMEBUFFER,
                attachment,
                glow::RENDERBUFFER,
                Some(depth),
            );
            self.target = Some(Target {
                fbo,
                color,
                depth,
                width: w,
                height: h,
                format,
                samples: ms,
            });
            let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
            if status != glow::FRAMEBUFFER_COMPLETE {
                return Err(format!(
                    "framebuffer with {format:?} (internal format 0x{internal:04X}) incomplete: status 0x{status:04X}"
                ));
            }
            gl.viewport(0, 0, w, h);
            gl.disable(glow::SCISSOR_TEST);
            gl.enable(glow::DEPTH_TEST);
        }
        Ok(())
    }

    /// The depth bits GL reports for the target's depth attachment (16, 24 or 32).
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn depth_bits(&self) -> Result<u32, String> {
        self.require_target()?;
        let bits = unsafe {
            self.gl.get_framebuffer_attachment_parameter_i32(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                glow::FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE,
            )
        };
        self.check("depth_bits")?;
        Ok(bits as u32)
    }

    /// The target's depth format, width and height.
    ///
    /// # Errors
    /// No target.
    pub fn target_info(&self) -> Result<(DepthFormat, u32, u32), String> {
        let t = self.require_target()?;
        Ok((t.format, t.width as u32, t.height as u32))
    }

    /// Clears colour to `color` and depth to `depth` (with writes of both enabled).
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn clear(&mut self, color: [f32; 4], depth: f64) -> Result<(), String> {
        self.require_target()?;
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

    /// `glClipControl(GL_LOWER_LEFT, depth)`: the NDC depth range the clip volume maps to.
    ///
    /// # Errors
    /// The driver lacks glClipControl (GL < 4.5 without ARB_clip_control), or a GL error.
    pub fn clip_control(&mut self, depth: ClipDepth) -> Result<(), String> {
        let f = self
            .legacy
            .clip_control
            .ok_or("glClipControl is not available")?;
        let mode = match depth {
            ClipDepth::NegativeOneToOne => glow::NEGATIVE_ONE_TO_ONE,
            ClipDepth::ZeroToOne => glow::ZERO_TO_ONE,
        };
        f(glow::LOWER_LEFT, mode);
        self.check("glClipControl")
    }

    /// Draws `quad` (eye-space corners) through the shader `gl_Position = proj * vec4(eye, 1)`
    /// in flat `color`, with `state`'s depth func, masks and polygon offset.
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn draw_quad(
        &mut self,
        quad: &Quad,
        proj: &[f32; 16],
        color: [f32; 4],
        state: &DrawState,
    ) -> Result<(), String> {
        self.require_target()?;
        let gl = &self.gl;
        unsafe {
            use_quad_pipeline(gl, (self.program, self.vao, self.vbo), quad);
            let p = gl.get_uniform_location(self.program, "proj");
            gl.uniform_matrix_4_f32_slice(p.as_ref(), false, proj);
            let c = gl.get_uniform_location(self.program, "color");
            gl.uniform_4_f32(c.as_ref(), color[0], color[1], color[2], color[3]);
            self.apply(state);
            gl.draw_arrays(glow::TRIANGLE_FAN, 0, 4);
            gl.bind_vertex_array(None);
            gl.use_program(None);
        }
        self.check("draw_quad")
    }

    /// Compatibility profile: `glMatrixMode(GL_PROJECTION); glLoadIdentity(); glFrustum(..);
    /// glGetFloatv(GL_PROJECTION_MATRIX)` — the matrix the driver itself builds. Leaves it loaded.
    ///
    /// # Errors
    /// Not a compatibility context, or a GL error (e.g. GL_INVALID_VALUE for n ≤ 0).
    pub fn legacy_frustum(
        &mut self,
        l: f64,
        r: f64,
        b: f64,
        t: f64,
        n: f64,
        f: f64,
    ) -> Result<[f32; 16], String> {
        let (mode, ident, frustum) = (
            self.fixed(self.legacy.matrix_mode)?,
            self.fixed(self.legacy.load_identity)?,
            self.fixed(self.legacy.frustum)?,
        );
        mode(GL_PROJECTION);
        ident();
        frustum(l, r, b, t, n, f);
        self.check("glFrustum")?;
        self.legacy_projection()
    }

    /// Compatibility profile: `glGetFloatv(GL_PROJECTION_MATRIX)`.
    ///
    /// # Errors
    /// A GL error.
    pub fn legacy_projection(&mut self) -> Result<[f32; 16], String> {
        let mut m = [0.0f32; 16];
        unsafe {
            self.gl
                .get_parameter_f32_slice(GL_PROJECTION_MATRIX, &mut m)
        };
        self.check("glGetFloatv(GL_PROJECTION_MATRIX)")?;
        Ok(m)
    }

    /// Compatibility profile: `glMatrixMode(GL_PROJECTION); glLoadMatrixf(m)`.
    ///
    /// # Errors
    /// Not a compatibility context, or a GL error.
    pub fn legacy_load_projection(&mut self, m: &[f32; 16]) -> Result<(), String> {
        let (mode, load) = (
            self.fixed(self.legacy.matrix_mode)?,
            self.fixed(self.legacy.load_matrixf)?,
        );
        mode(GL_PROJECTION);
        load(m.as_ptr());
        self.check("glLoadMatrixf")
    }

    /// Compatibility profile: draws `quad` with the fixed-function pipeline (`glBegin(GL_QUADS)`,
    /// model-view identity, the currently loaded projection) in flat `color`.
    ///
    /// # Errors
    /// No target, not a compatibility context, or a GL error.
    pub fn legacy_draw_quad(
        &mut self,
        quad: &Quad,
        color: [f32; 4],
        state: &DrawState,
    ) -> Result<(), String> {
        self.require_target()?;
        let (mode, ident) = (
            self.fixed(self.legacy.matrix_mode)?,
            self.fixed(self.legacy.load_identity)?,
        );
        let (begin, end) = (self.fixed(self.legacy.begin)?, self.fixed(self.legacy.end)?);
        let (vertex, color4) = (
            self.fixed(self.legacy.vertex3f)?,
            self.fixed(self.legacy.color4f)?,
        );
        mode(GL_MODELVIEW);
        ident();
        unsafe { self.apply(state) };
        begin(GL_QUADS);
        color4(color[0], color[1], color[2], color[3]);
        for [x, y, z] in quad.corners {
            vertex(x, y, z);
        }
        end();
        self.check("legacy_draw_quad")
    }

    /// Reads the colour attachment: `glReadPixels(GL_RGBA, GL_UNSIGNED_BYTE)`, rows bottom-up.
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn read_color(&mut self) -> Result<Image, String> {
        let (w, h) = {
            let t = self.require_target()?;
            (t.width, t.height)
        };
        self.read_color_at([0, 0], w as u32, h as u32)
    }

    /// [`Gl::read_color`] of the `width × height` rectangle whose lower-left pixel is `origin`
    /// (a viewport inside a larger framebuffer, without reading the rest).
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn read_color_at(
        &mut self,
        origin: [u32; 2],
        width: u32,
        height: u32,
    ) -> Result<Image, String> {
        if let Some(ms) = self.require_target()?.samples.as_ref() {
            // SAFETY: this context is current on this thread (Gl's invariant); the target's
            // objects are alive while it is set.
            let pixels = unsafe { ms.read_at(&self.gl, origin, width, height) };
            self.check("glReadPixels(GL_RGBA) of each sample")?;
            return Ok(Image {
                width: width as usize,
                height: height as usize * ms.count(),
                pixels,
            });
        }
        // SAFETY: this context is current on this thread (Gl's invariant).
        let pixels = unsafe {
            read_rgba8_at(
                &self.gl,
                origin.map(|c| c as i32),
                width as i32,
                height as i32,
            )
        };
        self.check("glReadPixels(GL_RGBA)")?;
        Ok(Image {
            width: width as usize,
            height: height as usize,
            pixels,
        })
    }

    /// Reads the depth attachment as window depth: `glReadPixels(GL_DEPTH_COMPONENT, GL_FLOAT)`,
    /// rows bottom-up. For D16/D24 GL converts the stored integer `k` to `k / (2^m − 1)`.
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn read_depth(&mut self) -> Result<Vec<f32>, String> {
        let (w, h) = {
            let t = self.require_target()?;
            if t.samples.is_some() {
                return Err("read_depth: the target is multisampled".into());
            }
            (t.width, t.height)
        };
        let mut bytes = vec![0u8; (w * h * 4) as usize];
        unsafe {
            self.gl.finish();
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            self.gl.read_pixels(
                0,
                0,
                w,
                h,
                glow::DEPTH_COMPONENT,
                glow::FLOAT,
                glow::PixelPackData::Slice(Some(&mut bytes)),
            );
        }
        self.check("glReadPixels(GL_DEPTH_COMPONENT)")?;
        Ok(bytes
            .chunks_exact(4)
            .map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }

    /// Fails with every pending GL error, named by `what`.
    ///
    /// # Errors
    /// `"<what>: GL error 0x...."` when `glGetError` reports any.
    pub fn check(&self, what: &str) -> Result<(), String> {
        check_gl_errors(&self.gl, what)
    }

    unsafe fn apply(&self, s: &DrawState) {
        let gl = &self.gl;
        gl.enable(glow::DEPTH_TEST);
        gl.depth_func(s.depth_func);
        gl.depth_mask(s.depth_write);
        gl.color_mask(s.color_write, s.color_write, s.color_write, s.color_write);
        match s.polygon_offset {
            Some((factor, units)) => {
                gl.enable(glow::POLYGON_OFFSET_FILL);
                gl.polygon_offset(factor, units);
            }
            None => gl.disable(glow::POLYGON_OFFSET_FILL),
        }
    }

    fn fixed<F>(&self, f: Option<F>) -> Result<F, String> {
        if self.profile != Profile::Compatibility {
            return Err("fixed-function calls need a Profile::Compatibility context".into());
        }
        f.ok_or_else(|| "the driver does not export a fixed-function entry point".into())
    }

    fn require_target(&self) -> Result<&Target, String> {
        self.target
            .as_ref()
            .ok_or_else(|| "no render target: call Gl::set_target first".into())
    }

    fn drop_target(&mut self) {
        if let Some(t) = self.target.take() {
            unsafe {
                self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
                self.gl.delete_framebuffer(t.fbo);
                self.gl.delete_renderbuffer(t.color);
                self.gl.delete_renderbuffer(t.depth);
                if let Some(ms) = t.samples {
                    ms.delete(&self.gl);
                }
            }
        }
    }
}

impl Drop for Gl {
    fn drop(&mut self) {
        self.drop_target();
        if let Some((program, vao, vbo)) = self.world.take() {
            unsafe {
                self.gl.delete_program(program);
                self.gl.delete_vertex_array(vao);
                self.gl.delete_buffer(vbo);
            }
        }
        unsafe {
            self.gl.delete_program(self.program);
            self.gl.delete_vertex_array(self.vao);
            self.gl.delete_buffer(self.vbo);
        }
        // The display is shared by every context in the process: release this context only
        // (eglTerminate would pull the others' display away).
        let _ = self.egl.make_current(self.display, None, None, None);
        let _ = self.egl.destroy_context(self.display, self.context);
    }
}

impl Legacy {
    // glLoadIdentity and glEnd already have eglGetProcAddress's type, so their transmute is a no-op.
    #[allow(clippy::useless_transmute)]
    fn load(egl: &egl::Instance<egl::Static>) -> Legacy {
        macro_rules! entry {
            ($name:literal) => {
                // SAFETY: the name is a GL entry point whose C signature matches the field's
                // type; a missing one stays None.
                egl.get_proc_address($name)
                    .map(|f| unsafe { std::mem::transmute(f) })
            };
        }
        Legacy {
            matrix_mode: entry!("glMatrixMode"),
            load_identity: entry!("glLoadIdentity"),
            frustum: entry!("glFrustum"),
            load_matrixf: entry!("glLoadMatrixf"),
            begin: entry!("glBegin"),
            end: entry!("glEnd"),
            vertex3f: entry!("glVertex3f"),
            color4f: entry!("glColor4f"),
            clip_control: entry!("glClipControl"),
        }
    }
}

/// Eye-space vertices through the projection matrix (the model-view is the identity).
const VERTEX_SHADER: &str = "#version 330 core
layout(location = 0) in vec3 eye;
uniform mat4 proj;
void main() { gl_Position = proj * vec4(eye, 1.0); }
";

const FRAGMENT_SHADER: &str = "#version 330 core
uniform vec4 color;
out vec4 frag;
void main() { frag = color; }
";

/// The bound read framebuffer's `GL_COLOR_ATTACHMENT0`, `width × height` from the origin, as
/// RGBA8 pixels (rows bottom-up), after `glFinish`; the caller checks GL errors.
///
/// # Safety
/// `gl`'s context must be current on this thread.
pub unsafe fn read_rgba8(gl: &glow::Context, width: i32, height: i32) -> Vec<[u8; 4]> {
    read_rgba8_at(gl, [0, 0], width, height)
}

/// [`read_rgba8`] of the `width × height` rectangle whose lower-left pixel is `origin`.
///
/// # Safety
/// `gl`'s context must be current on this thread.
pub unsafe fn read_rgba8_at(
    gl: &glow::Context,
    origin: [i32; 2],
    width: i32,
    height: i32,
) -> Vec<[u8; 4]> {
    let mut bytes = vec![0u8; (width * height * 4) as usize];
    gl.finish();
    gl.read_buffer(glow::COLOR_ATTACHMENT0);
    gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
    gl.read_pixels(
        origin[0],
        origin[1],
        width,
        height,
        glow::RGBA,
        glow::UNSIGNED_BYTE,
        glow::PixelPackData::Slice(Some(&mut bytes)),
    );
    bytes
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// Drains `glGetError` (up to 9 codes) for any current context, the harness's or a window's.
///
/// # Errors
/// `"<what>: GL error 0x...."` when `glGetError` reports any.
pub fn check_gl_errors(gl: &glow::Context, what: &str) -> Result<(), String> {
    let mut codes = Vec::new();
    loop {
        // SAFETY: glGetError has no preconditions beyond a current context, which every caller
        // of this crate holds.
        let e = unsafe { gl.get_error() };
        if e == glow::NO_ERROR || codes.len() > 8 {
            break;
        }
        codes.push(format!("0x{e:04X}"));
    }
    if codes.is_empty() {
        Ok(())
    } else {
        Err(format!("{what}: GL error {}", codes.join(", ")))
    }
}

/// Compiles the quad shader and makes the VAO/VBO (3 floats per vertex at location 0).
unsafe fn quad_pipeline(
    gl: &glow::Context,
) -> Result<(glow::Program, glow::VertexArray, glow::Buffer), String> {
    flat_colour_pipeline(gl, VERTEX_SHADER)
}

/// Binds a pipeline made by [`flat_colour_pipeline`] and uploads `quad`'s four eye-space corners
/// to its vertex buffer, ready for `glDrawArrays(GL_TRIANGLE_FAN, 0, 4)`.
///
/// # Safety
/// `gl` must be current on this thread and own the pipeline's objects.
pub unsafe fn use_quad_pipeline(
    gl: &glow::Context,
    (program, vao, vbo): (glow::Program, glow::VertexArray, glow::Buffer),
    quad: &Quad,
) {
    let bytes: Vec<u8> = quad
        .corners
        .iter()
        .flatten()
        .flat_map(|v| v.to_ne_bytes())
        .collect();
    gl.use_program(Some(program));
    gl.bind_vertex_array(Some(vao));
    gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
    gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STREAM_DRAW);
}

/// Compiles `vertex_shader` and `fragment_shader` and links them into a program.
///
/// # Safety
/// `gl` must be current on this thread.
///
/// # Errors
/// A compile or link failure, with the driver's log.
pub unsafe fn link_program(
    gl: &glow::Context,
    vertex_shader: &str,
    fragment_shader: &str,
) -> Result<glow::Program, String> {
    link_stages(
        gl,
        &[
            (glow::VERTEX_SHADER, vertex_shader),
            (glow::FRAGMENT_SHADER, fragment_shader),
        ],
    )
}

/// Compiles each `(stage, source)` (`glow::VERTEX_SHADER`, `GEOMETRY_SHADER`, …) and links them
/// into a program.
///
/// # Safety
/// `gl` must be current on this thread.
///
/// # Errors
/// A compile or link failure, with the driver's log.
pub unsafe fn link_stages(
    gl: &glow::Context,
    stages: &[(u32, &str)],
) -> Result<glow::Program, String> {
    let program = gl.create_program()?;
    for &(kind, source) in stages {
        let shader = gl.create_shader(kind)?;
        gl.shader_source(shader, source);
        gl.compile_shader(shader);
        if !gl.get_shader_compile_status(shader) {
            return Err(format!(
                "shader compile failed: {}",
                gl.get_shader_info_log(shader)
            ));
        }
        gl.attach_shader(program, shader);
        gl.delete_shader(shader);
    }
    gl.link_program(program);
    if !gl.get_program_link_status(program) {
        return Err(format!(
            "shader link failed: {}",
            gl.get_program_info_log(program)
        ));
    }
    Ok(program)
}

/// Links `vertex_shader` (GLSL 3.30 core, eye-space position at attribute location 0) with the
/// harness's flat-colour fragment shader (`uniform vec4 color`) and makes the VAO/VBO (3 floats
/// per vertex at location 0). For tests that bring their own vertex transform, such as the
/// shipped `ftransform_mdp.glsl`.
///
/// # Safety
/// `gl` must be current on this thread.
///
/// # Errors
/// A compile or link failure, with the driver's log.
pub unsafe fn flat_colour_pipeline(
    gl: &glow::Context,
    vertex_shader: &str,
) -> Result<(glow::Program, glow::VertexArray, glow::Buffer), String> {
    let program = link_program(gl, vertex_shader, FRAGMENT_SHADER)?;
    let vao = gl.create_vertex_array()?;
    let vbo = gl.create_buffer()?;
    gl.bind_vertex_array(Some(vao));
    gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
    gl.enable_vertex_attrib_array(0);
    gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 12, 0);
    gl.bind_vertex_array(None);
    Ok((program, vao, vbo))
}

/// Depth-stencil targets, for decal methods that need a stencil buffer. Stencil state is not
/// part of [`DrawState`]: set it through [`Gl::glow`] and reset it after use.
impl Gl {
    /// As [`Gl::set_target`], but the depth attachment is a packed depth-stencil renderbuffer
    /// with 8 stencil bits: `GL_DEPTH24_STENCIL8` for [`DepthFormat::D24`],
    /// `GL_DEPTH32F_STENCIL8` for [`DepthFormat::D32F`], attached to
    /// `GL_DEPTH_STENCIL_ATTACHMENT`.
    ///
    /// # Errors
    /// [`DepthFormat::D16`] (GL has no packed 16-bit depth-stencil format), a zero size, a GL
    /// error, or an incomplete framebuffer (with its status).
    pub fn set_target_with_stencil(
        &mut self,
        width: u32,
        height: u32,
        format: DepthFormat,
    ) -> Result<(), String> {
        self.set_target_samples(width, height, format, true, 1)
    }

    /// As [`Gl::set_target`] (or [`Gl::set_target_with_stencil`] where `packed`), with
    /// `samples` samples per pixel (1: single-sampled). [`Gl::read_color_at`] then returns every
    /// sample, unaveraged: the image is `samples` times as tall, sample `s`'s rows after those
    /// of samples `0..s` ([`msaa`]).
    ///
    /// # Errors
    /// As those two; and a target GL does not make with that many samples.
    pub fn set_target_samples(
        &mut self,
        width: u32,
        height: u32,
        format: DepthFormat,
        packed: bool,
        samples: u32,
    ) -> Result<(), String> {
        let (internal, attachment) = match (packed, format) {
            (false, _) => (format.gl_enum(), glow::DEPTH_ATTACHMENT),
            (true, DepthFormat::D24) => (glow::DEPTH24_STENCIL8, glow::DEPTH_STENCIL_ATTACHMENT),
            (true, DepthFormat::D32F) => (glow::DEPTH32F_STENCIL8, glow::DEPTH_STENCIL_ATTACHMENT),
            (true, DepthFormat::D16) => {
                return Err("no packed depth-stencil format with D16".into())
            }
        };
        // A count the context cannot draw makes an incomplete framebuffer: say so by name.
        let most = unsafe { self.gl.get_parameter_i32(glow::MAX_SAMPLES) };
        if samples > 1 && i64::from(samples) > i64::from(most) {
            return Err(format!(
                "{samples} samples asked, but this context draws at most {most} (GL_MAX_SAMPLES)"
            ));
        }
        self.make_target(width, height, format, internal, attachment, samples.max(1))?;
        self.check("set_target_samples")
    }

    /// The stencil bits GL reports for the target (8 after [`Gl::set_target_with_stencil`],
    /// 0 after [`Gl::set_target`]).
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn stencil_bits(&self) -> Result<u32, String> {
        self.require_target()?;
        // Querying the size of an empty attachment is GL_INVALID_OPERATION: ask its type first.
        let kind = unsafe {
            self.gl.get_framebuffer_attachment_parameter_i32(
                glow::FRAMEBUFFER,
                glow::STENCIL_ATTACHMENT,
                glow::FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
            )
        };
        if kind as u32 == glow::NONE {
            self.check("stencil_bits")?;
            return Ok(0);
        }
        let bits = unsafe {
            self.gl.get_framebuffer_attachment_parameter_i32(
                glow::FRAMEBUFFER,
                glow::STENCIL_ATTACHMENT,
                glow::FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE,
            )
        };
        self.check("stencil_bits")?;
        Ok(bits as u32)
    }

    /// The address of a GL entry point (`eglGetProcAddress`), or null: for callers that must
    /// call GL directly, without the harness's per-call `glGetError` (e.g. a benchmark of the
    /// seed's `glFrustum` path). The pointer is valid while this context lives.
    pub fn proc_address(&self, name: &str) -> *const c_void {
        self.egl
            .get_proc_address(name)
            .map_or(std::ptr::null(), |f| f as *const c_void)
    }

    /// Clears the stencil buffer to `value` (with all stencil bits writable).
    ///
    /// # Errors
    /// No target, or a GL error.
    pub fn clear_stencil(&mut self, value: i32) -> Result<(), String> {
        self.require_target()?;
        unsafe {
            self.gl.stencil_mask(0xFF);
            self.gl.clear_stencil(value);
            self.gl.clear(glow::STENCIL_BUFFER_BIT);
        }
        self.check("clear_stencil")
    }
}

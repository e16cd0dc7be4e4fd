//! Measures a [`RasterizerProfile`] in the caller's own OpenGL context.
//!
//! [`probe`] draws a few thousand triangles into a framebuffer of its own (512×512, in 64×64 tiles,
//! one depth format at a time), reads the stored depth back with `glReadPixels` and compares it,
//! pixel by pixel, with the exact depth of the plane each triangle lies in, computed in f64 from
//! the very f32 values the GPU was given. It reaches GL only through the function loader the
//! caller passes (as `glow::Context::from_loader_function_cstr` takes one): the library links
//! no GL. The entry points are a table of plain function pointers checked for NULL when loaded
//! (rather than glow, whose missing functions panic when called), so a missing one is an error
//! that names it.
//!
//! # What it measures
//! * **Snapping** ([`Snapping`]): a steep triangle (depth gradient ≈ 0.014 per pixel) whose
//!   vertices sit at sub-pixel offsets, on `GL_DEPTH_COMPONENT32F`. For every hypothesis — depth
//!   plane set up from the unsnapped positions, or from positions rounded (to nearest, or down) to
//!   `2^-b` pixel for `b` in 0..=12 — the predicted depth of every pixel is computed exactly, and
//!   the hypothesis closest to the stored depths wins. Snapping to `2^-12` pixel moves depth by
//!   1.7·10⁻⁶ here, 17× the f32 noise of the stored depth; finer snapping cannot be told from
//!   none, and its term in the model is as small. If no hypothesis fits to 10⁻⁶, the answer is
//!   the conservative `GL_SUBPIXEL_BITS` the driver reports.
//! * **`resolvable`** (`r`, per format): a gently sloped quad drawn twice, without and with
//!   `glPolygonOffset(0, U)`; `r` = the mean stored difference ÷ `U`, in units of the format's
//!   quantum (UNORM: `1/(2^m − 1)`; D32F: `2^(e − 23)`, `e` the exponent of the primitive's largest
//!   depth, measured at two exponents and the larger kept). `U` makes the offset ≈ 2⁻⁸ of window
//!   depth, so each pixel's difference is known to 1/256 of `r` or better. Wine's wined3d finds the
//!   same scale by bisection over powers of two; the direct difference needs two draws and finds
//!   factors that are not powers of two.
//! * **`plane_error`** (per format): the largest `|stored − exact|` over every pixel whose centre
//!   lies at least a pixel inside one of 48 triangles: perspective planes (f/n = 10, 10³, 10⁵)
//!   facing the camera, gently sloped, steep and grazing (eye-space slopes up to 10), axis depths
//!   from 0.02 to 0.998, corners on screen or up to four viewports off it (in front of the near
//!   plane). Each is drawn as an engine draws: f32 eye-space vertices times an f32 `glFrustum`
//!   matrix in the vertex shader, in a 64×64 tile of its own, the tiles side by side within 512
//!   pixels of the window origin. "Exact" is the plane through the vertices times the matrix in
//!   f64, so the error covers the whole pipeline after the vertex coordinates: the shader's f32
//!   transform, the division by `w`, the viewport transform, plane setup, interpolation and the
//!   conversion to the stored format (`T`, `I` and the quantization of [`crate::recommend`]; not
//!   `V`, the rounding of the coordinates themselves). Units: the format's quantum; D32F in
//!   units of 2⁻²⁴ (its error is mostly absolute). D32F is measured again under reversed Z
//!   (`glClipControl(GL_ZERO_TO_ONE)`, window depths 2·10⁻⁵ to 0.7) into `plane_error_reversed`,
//!   in units of the spacing at the primitive's largest depth.
//! * **`error_ulps`**: the same pixels' error (less one quantum of conversion on UNORM) divided
//!   by `2⁻²⁴·(1 + M)`, `M` the magnitude of the terms of the plane evaluated from the window
//!   origin (see the field): how the error of a steep plane grows with its distance from the
//!   origin, for viewports larger than the tiles. On D32F (whose stored depth is the computed
//!   one) 256 more planes are drawn, in random directions and frusta (f/n 10² to 10⁹, slopes
//!   0.3 to 10): the model takes this figure for its per-quad error `T + I`, and a maximum of
//!   roundings grows with the planes it is taken over (48 planes: 1.40 on llvmpipe; 304: 1.54).
//!   **`error_ulps_reversed`**: the same under reversed Z on D32F, divided by
//!   `2⁻²⁴·(|m10| + M)` (3.15 on llvmpipe).
//! * **`facing_quanta`** (per format, and `facing_quanta_zero_to_one` under
//!   `glClipControl(GL_ZERO_TO_ONE)`): facing quads at 256 depths (four per tile), drawn with the
//!   plain `glFrustum` matrix and again with element 10 moved toward 0 by `k` f32 steps; for each
//!   depth the smallest `k` whose stored depth is below the base's, as a window offset in quanta
//!   (D32F: 2⁻²⁴); the largest over the depths (each its own phase between two stored values).
//!   What a shared-z facing decal needs under `GL_LESS` (not measured on D16). Under reversed Z
//!   (D32F only) the same with element 14 moved away from 0: `facing_reversed`, a relative ε.
//! * **`line_reach`** (`GL_LINES` and polygon-mode lines, width 1, on D32F): 96 lines in every
//!   direction and 48 triangles drawn under `glPolygonMode(GL_LINE)`, in 32 tiles each with its
//!   own plane (window-depth gradient 1/256 per pixel along the steeper axis, in 16 directions);
//!   the largest `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` over every fragment
//!   (0.5006 and 0.5012 pixel on llvmpipe). **`offset_slope`**: `glPolygonOffset(1, 0)` on a plane
//!   with `|gₓ| = |g_y|`, over the gradient (1: GL's `max` rule; √2: a root sum of squares). One
//!   draw batch and one read-back, about 2 ms.
//! * **`near_clip`** ([`NearClip`]): four ground planes (sloped, and a floor) whose triangles
//!   reach 1000 units behind and ahead of the camera (n = 0.1, f = 1000, 16:9), on D24. Each is
//!   drawn as given — the rasterizer clips it at the near plane — and again clipped by the probe
//!   in f64 at twice the near distance, so that nothing is left to clip; each image is compared
//!   with its exact (f64) plane, on the pixels both cover. A clipper that
//!   keeps the plane errs as little as the unclipped drawing (within twice its error plus 2
//!   quanta: [`NearClip::PlanePreserving`]); one that computes the new vertices in f32 errs by
//!   tens of quanta more ([`NearClip::ClippedF32`], the worst case the model must bound).
//!
//! # The caller's GL state
//! The probe needs OpenGL 3.2 or later (core or compatibility profile) current on the calling
//! thread, and leaves no trace in it: it first fails if `glGetError` reports an error pending from
//! the caller's own calls (reading it clears it: the error's detail says so), then saves and
//! afterwards restores the draw and read framebuffer bindings, the renderbuffer, program, vertex
//! array, array buffer and pixel-pack buffer bindings, every viewport and depth range (all of
//! them under `ARB_viewport_array`), the depth function, write mask and clear value, polygon
//! offset factor, units and clamp, polygon mode, line width, the enables it touches (depth test,
//! polygon offset fill and line, cull face, polygon and line smooth, stencil, depth clamp, rasterizer discard, scissor
//! per viewport, every clip distance, depth-bounds test, alpha test in compatibility), every
//! `GL_PACK_*` parameter, `glClipControl` and, in a compatibility context,
//! `GL_DEPTH_SCALE`/`GL_DEPTH_BIAS`. It deletes every object
//! it creates, also on error. Not restored because it never changes them: colour state (its
//! framebuffer has no colour attachment), textures, samplers, stencil values, uniform state of
//! other programs. Not handled: an active transform feedback, query or conditional render of
//! the caller would see (or discard) the probe's draws; end them before probing.
//!
//! # Errors
//! [`crate::ErrorKind::Gl`] with a detail naming what failed: the entry point the loader
//! returned NULL for, a context older than 3.2 or none current, a GL error pending on entry, a
//! shader that does not compile, a depth format the framebuffer refuses (D16, D24 and D32F), or a
//! GL error during a step. `GL_DEPTH_COMPONENT32` (32-bit UNORM, rare in engines) is not measured:
//! its entries keep the worst case (a shader variant of its own would cost a fifth of the run).
//!
//! # Time
//! On Mesa llvmpipe on 2 cores (`ZSHIFT_PROBE_RUNS=5 cargo run --release --example probe`): the
//! first call in a context 80–100 ms, later calls 50–65 ms, both measured while other builds
//! loaded the machine; the first pays llvmpipe's compilation of a shader variant per depth format
//! and polygon-offset state. The facing measurements read back only the pixel rows they need and
//! the 256 varied planes every other pixel. The profile records its own run time in
//! [`RasterizerProfile::probe_seconds`].

mod gl;
mod state;

use std::ffi::{c_void, CStr};
use std::time::Instant;

use crate::depth_chain::DepthChain;
use crate::error::{Error, ErrorKind, Result};
use crate::profile::{NearClip, RasterizerProfile, Snapping};
use crate::projection::ClipDepth;
use gl::*;

/// Width and height of the probe's framebuffer in pixels.
const SIZE: usize = 64;

/// The framebuffer holds `TILES × TILES` tiles of `SIZE × SIZE`: a batch of scenes is drawn,
/// one per tile (its own viewport), and read back with one `glReadPixels`.
const TILES: usize = 8;

/// Measures the rasterizer of the OpenGL context current on this thread. See the module docs.
///
/// `loader` returns the address of a GL entry point by name (`eglGetProcAddress`,
/// `glfwGetProcAddress`, `SDL_GL_GetProcAddress`, glutin's `Display::get_proc_address`), or
/// NULL when it has none.
///
/// # Safety
/// An OpenGL context must be current on this thread, and every non-NULL pointer `loader` returns
/// must be the named entry point of that context (what a GL loader promises).
///
/// # Errors
/// [`ErrorKind::Gl`], as the module docs list; the context's state is restored in every case.
pub unsafe fn probe(loader: impl FnMut(&CStr) -> *const c_void) -> Result<RasterizerProfile> {
    probe_with_figures(loader).map(|(profile, _)| profile)
}

/// The raw figures behind a probed profile, for reports and tests: what each decision was made
/// from.
#[derive(Debug, Clone, PartialEq)]
pub struct Figures {
    /// `GL_RENDERER`, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub renderer: String,
    /// `GL_VERSION`, e.g. "4.5 (Core Profile) Mesa 22.3.6".
    pub version: String,
    /// `GL_SUBPIXEL_BITS` as the driver reports it (what it snaps coverage to; not necessarily
    /// what depth setup uses, which [`RasterizerProfile::snapping`] measures).
    pub subpixel_bits: i32,
    /// Pixels compared with the exact plane for `plane_error`, per format (D16, D24, D32, D32F;
    /// 0 where the format was not measured).
    pub plane_pixels: [usize; 4],
    /// The worst `|stored − exact|` of the ground planes the rasterizer clipped at the near
    /// plane, in D24 quanta, on the pixels compared.
    pub near_clip_error: f64,
    /// The same planes clipped by the probe in f64 (at twice the near distance) before
    /// drawing, on the same pixels: what the rasterizer does without clipping.
    pub near_preclipped_error: f64,
    /// How well the snapping hypotheses fit, in window depth: the largest residual of the
    /// unsnapped hypothesis, and of the best snapped one (`b`, `residual`).
    pub snapping_residual: (f64, u32, f64),
    /// `r` per measured band, for D32F (at window depths ≈ 0.45 and ≈ 0.055, in units of
    /// `2^(e − 23)` at each).
    pub float_resolvable: [f64; 2],
    /// Pixels compared for [`RasterizerProfile::plane_error_reversed`] (0 without
    /// `glClipControl`).
    pub reversed_pixels: usize,
    /// Per format, the worst `(|stored − exact| − q)⁺ / (2⁻²⁴·(1 + M))` (q = 0 for D32F) under
    /// `[−1, 1]`; [`RasterizerProfile::error_ulps`] is the largest.
    pub error_ulps: [f64; 4],
    /// D32F's worst plane error in units of the f32 spacing at each pixel's own depth (not at
    /// the primitive's largest), under `[−1, 1]` and under reversed Z: what a primitive spanning
    /// several binades does to its smallest depths.
    pub float_local_plane_error: [f64; 2],
    /// How many stored depths of facing planes the chain identification compared.
    pub chain_observations: usize,
    /// Line fragments compared for [`RasterizerProfile::line_reach`] (`GL_LINES`, polygon-mode).
    pub line_pixels: [usize; 2],
    /// `glPolygonOffset(1, 0)`'s offset over the gradient on a plane with `g_y = 0` (1 under
    /// either slope rule: the factor's scale); [`RasterizerProfile::offset_slope`] is the
    /// diagonal plane's.
    pub offset_slope_axis: f64,
}

/// [`probe`], with the [`Figures`] it decided from.
///
/// # Safety
/// As [`probe`].
///
/// # Errors
/// As [`probe`].
pub unsafe fn probe_with_figures(
    mut loader: impl FnMut(&CStr) -> *const c_void,
) -> Result<(RasterizerProfile, Figures)> {
    let start = Instant::now();
    let mut gl = Gl::load(&mut loader)?;
    if gl.failed() {
        return Err(Error::new(
            ErrorKind::Gl,
            "a GL error was pending before the probe ran (glGetError); it was read, which \
             clears it: check the caller's GL calls before probing",
        ));
    }
    let (_, _, compatibility) = gl.settle()?;
    let saved = state::Saved::read(&gl, compatibility);
    gl.check("reading the caller's GL state raised a GL error")?;
    saved.prepare(&gl);
    let mut objects = Objects::default();
    let result = measure(&gl, &mut objects);
    objects.delete(&gl);
    saved.restore(&gl);
    let cleanup = gl.check("restoring the caller's GL state raised a GL error");
    let (mut profile, figures) = result?;
    cleanup?;
    profile.probe_seconds = start.elapsed().as_secs_f64();
    Ok((profile, figures))
}

/// The GL objects the probe creates (0 = not created yet).
#[derive(Default)]
struct Objects {
    program: Uint,
    vertex_array: Uint,
    buffer: Uint,
    framebuffer: Uint,
    renderbuffer: Uint,
    /// The location of the vertex shader's `projection` uniform.
    projection: Int,
}

impl Objects {
    unsafe fn delete(&self, gl: &Gl) {
        (gl.BindFramebuffer)(FRAMEBUFFER, 0);
        (gl.UseProgram)(0);
        (gl.BindVertexArray)(0);
        if self.program != 0 {
            (gl.DeleteProgram)(self.program);
        }
        (gl.DeleteVertexArrays)(1, &self.vertex_array);
        (gl.DeleteBuffers)(1, &self.buffer);
        (gl.DeleteFramebuffers)(1, &self.framebuffer);
        (gl.DeleteRenderbuffers)(1, &self.renderbuffer);
    }
}

/// A depth format the probe measures, with its slot in the profile's arrays.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Format {
    Unorm(u32),
    Float,
}

impl Format {
    /// (profile slot, GL internal format, format) in the profile's order: D16, D24, D32, D32F.
    const ALL: [(usize, Enum, Format); 3] = [
        (0, DEPTH_COMPONENT16, Format::Unorm(16)),
        (1, DEPTH_COMPONENT24, Format::Unorm(24)),
        (3, DEPTH_COMPONENT32F, Format::Float),
    ];

    /// The quantum at exact window depth `w`: `1/(2^m − 1)`, or the f32 spacing `2^(e − 23)`.
    fn quantum(self, w: f64) -> f64 {
        match self {
            Format::Unorm(m) => 1.0 / (2f64.powi(m as i32) - 1.0),
            Format::Float => f32_spacing(w),
        }
    }

    /// UNORM bits, 0 for D32F ([`crate::depth_chain::DepthChain::stored`]'s convention).
    fn bits(self) -> u32 {
        match self {
            Format::Unorm(m) => m,
            Format::Float => 0,
        }
    }

    /// A value [`read_depth`] returned as the buffer holds it: the UNORM integer, or the float.
    fn integer(self, value: f64) -> f64 {
        match self {
            Format::Unorm(m) => (value * (2f64.powi(m as i32) - 1.0)).round(),
            Format::Float => value,
        }
    }
}

/// A stored depth the facing measurements read, with the f32 inputs that made it.
struct ChainObservation {
    clip: ClipDepth,
    bits: u32,
    m10: f32,
    m14: f32,
    z: f32,
    stored: f64,
}

/// The one candidate chain that reproduces every observation bit for bit, if any (several may
/// agree where their differences never show; the first in [`DepthChain::candidates`]' order is
/// kept, and any of them predicts every observation).
fn identify_chain(seen: &[ChainObservation]) -> Option<DepthChain> {
    // D16 alone (its base depths only, each hundreds of steps from the next value) cannot tell
    // the candidates' arithmetic apart: the offset steps on D24 or D32F must be among them.
    if seen.iter().all(|o| o.bits == 16) {
        return None;
    }
    DepthChain::candidates().find(|chain| {
        seen.iter().all(|o| {
            chain.stored(o.bits, chain.window_depth(o.clip, o.m10, o.m14, o.z)) == o.stored
        })
    })
}

/// `2^(e − 23)` for the exponent `e` of `|w|` as an f32 (the smallest normal spacing below).
fn f32_spacing(w: f64) -> f64 {
    let w = w.abs().max(f32::MIN_POSITIVE as f64);
    2f64.powi(w.log2().floor() as i32 - 23)
}

/// Everything measured, with the formats in the profile's order.
unsafe fn measure(gl: &Gl, objects: &mut Objects) -> Result<(RasterizerProfile, Figures)> {
    create_objects(gl, objects)?;
    let o = &*objects;
    let mut profile = RasterizerProfile::worst_case();
    profile.measured = true;
    let mut figures = Figures {
        renderer: gl.string(RENDERER),
        version: gl.string(VERSION),
        subpixel_bits: gl.integer(SUBPIXEL_BITS),
        plane_pixels: [0; 4],
        near_clip_error: f64::NAN,
        near_preclipped_error: f64::NAN,
        snapping_residual: (f64::NAN, 0, f64::NAN),
        float_resolvable: [f64::NAN; 2],
        reversed_pixels: 0,
        error_ulps: [f64::NAN; 4],
        float_local_plane_error: [f64::NAN; 2],
        chain_observations: 0,
        line_pixels: [0; 2],
        offset_slope_axis: f64::NAN,
    };
    let mut seen = Vec::new();
    for (slot, internal, format) in Format::ALL {
        if !attach(gl, o, internal)? {
            return Err(Error::new(ErrorKind::Gl, incomplete_detail(internal)));
        }
        let bands = resolvable(gl, o, format)?;
        profile.resolvable[slot] = bands.iter().copied().fold(0.0, f64::max);
        if format == Format::Float {
            figures.float_resolvable = [bands[0], bands[bands.len() - 1]];
        }
        if let Some(q) = facing_quanta(gl, o, format, Facing::NegOneToOne, &mut seen)? {
            profile.facing_quanta[slot] = q;
        }
        if let Some(clip_control) = gl.ClipControl {
            clip_control(LOWER_LEFT, ZERO_TO_ONE);
            let zero_to_one = facing_quanta(gl, o, format, Facing::ZeroToOne, &mut seen);
            let reversed = zero_to_one.and_then(|z| {
                Ok((
                    z,
                    facing_quanta(gl, o, format, Facing::Reversed, &mut seen)?,
                ))
            });
            clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
            let (zero_to_one, reversed) = reversed?;
            if let Some(q) = zero_to_one {
                profile.facing_quanta_zero_to_one[slot] = q;
            }
            if let (Some(q), Format::Float) = (reversed, format) {
                profile.facing_reversed = q;
            }
        }
        let errors = plane_error(gl, o, format, false)?;
        profile.plane_error[slot] = errors.worst;
        figures.plane_pixels[slot] = errors.pixels;
        figures.error_ulps[slot] = errors.error_ulps;
        if format == Format::Float {
            figures.float_local_plane_error[0] = errors.local;
            profile.error_ulps = figures.error_ulps.iter().copied().fold(0.0, f64::max);
            if let Some(reversed) = reversed_plane_error(gl, o)? {
                profile.plane_error_reversed = reversed.worst;
                profile.error_ulps_reversed = reversed.error_ulps;
                figures.reversed_pixels = reversed.pixels;
                figures.float_local_plane_error[1] = reversed.local;
            }
        }
        if format == Format::Float {
            (profile.snapping, figures.snapping_residual) = snapping(gl, o, figures.subpixel_bits)?;
            let lines = line_reach(gl, o)?;
            profile.line_reach = lines.reach;
            profile.offset_slope = lines.slope[0];
            figures.line_pixels = lines.pixels;
            figures.offset_slope_axis = lines.slope[1];
        }
        if internal == DEPTH_COMPONENT24 {
            (
                profile.near_clip,
                figures.near_clip_error,
                figures.near_preclipped_error,
                profile.clip_ulps,
            ) = near_clip(gl, o)?;
        }
    }
    profile.facing_chain = identify_chain(&seen);
    figures.chain_observations = seen.len();
    Ok((profile, figures))
}

fn incomplete_detail(internal: Enum) -> &'static str {
    match internal {
        DEPTH_COMPONENT16 => {
            "the framebuffer is incomplete with a GL_DEPTH_COMPONENT16 renderbuffer"
        }
        DEPTH_COMPONENT24 => {
            "the framebuffer is incomplete with a GL_DEPTH_COMPONENT24 renderbuffer"
        }
        _ => "the framebuffer is incomplete with a GL_DEPTH_COMPONENT32F renderbuffer",
    }
}

/// The engine's own transform: a vertex times a projection matrix, in f32 on the GPU.
const VERTEX_SHADER: &[u8] = b"#version 150\nin vec4 eye;\nuniform mat4 projection;\n\
void main() { gl_Position = projection * eye; }\n\0";
const FRAGMENT_SHADER: &[u8] = b"#version 150\nvoid main() {}\n\0";

unsafe fn create_objects(gl: &Gl, o: &mut Objects) -> Result<()> {
    o.program = (gl.CreateProgram)();
    for (kind, source, detail) in [
        (
            VERTEX_SHADER_KIND,
            VERTEX_SHADER,
            "the probe's vertex shader (GLSL 1.50) did not compile",
        ),
        (
            FRAGMENT_SHADER_KIND,
            FRAGMENT_SHADER,
            "the probe's fragment shader (GLSL 1.50) did not compile",
        ),
    ] {
        let shader = (gl.CreateShader)(kind);
        let text = source.as_ptr().cast();
        (gl.ShaderSource)(shader, 1, &text, std::ptr::null());
        (gl.CompileShader)(shader);
        let mut ok = 0;
        (gl.GetShaderiv)(shader, COMPILE_STATUS, &mut ok);
        (gl.AttachShader)(o.program, shader);
        (gl.DeleteShader)(shader);
        if ok == 0 {
            return Err(Error::new(ErrorKind::Gl, detail));
        }
    }
    (gl.BindAttribLocation)(o.program, 0, c"eye".as_ptr());
    (gl.LinkProgram)(o.program);
    let mut ok = 0;
    (gl.GetProgramiv)(o.program, LINK_STATUS, &mut ok);
    if ok == 0 {
        return Err(Error::new(
            ErrorKind::Gl,
            "the probe's shader program did not link",
        ));
    }
    (gl.GenVertexArrays)(1, &mut o.vertex_array);
    (gl.GenBuffers)(1, &mut o.buffer);
    (gl.GenFramebuffers)(1, &mut o.framebuffer);
    (gl.GenRenderbuffers)(1, &mut o.renderbuffer);
    (gl.UseProgram)(o.program);
    o.projection = (gl.GetUniformLocation)(o.program, c"projection".as_ptr());
    if o.projection < 0 {
        return Err(Error::new(
            ErrorKind::Gl,
            "the probe's linked program has no `projection` uniform (glGetUniformLocation)",
        ));
    }
    (gl.BindVertexArray)(o.vertex_array);
    (gl.BindBuffer)(ARRAY_BUFFER, o.buffer);
    (gl.EnableVertexAttribArray)(0);
    (gl.VertexAttribPointer)(0, 4, FLOAT, 0, 16, std::ptr::null());
    (gl.BindFramebuffer)(FRAMEBUFFER, o.framebuffer);
    (gl.DrawBuffer)(NONE);
    (gl.ReadBuffer)(NONE);
    (gl.Viewport)(0, 0, SIZE as Sizei, SIZE as Sizei);
    (gl.DepthFunc)(ALWAYS);
    gl.check("creating the probe's program, vertex array, buffer or framebuffer raised a GL error")
}

const VERTEX_SHADER_KIND: Enum = gl::VERTEX_SHADER;
const FRAGMENT_SHADER_KIND: Enum = gl::FRAGMENT_SHADER;
const ALWAYS: Enum = 0x0207;
const DEPTH_BUFFER_BIT: u32 = 0x0100;

/// Gives the renderbuffer `internal` storage and attaches it; `false` if the framebuffer is then
/// incomplete (or the format refused).
unsafe fn attach(gl: &Gl, o: &Objects, internal: Enum) -> Result<bool> {
    (gl.BindRenderbuffer)(RENDERBUFFER, o.renderbuffer);
    let side = (SIZE * TILES) as Sizei;
    (gl.RenderbufferStorage)(RENDERBUFFER, internal, side, side);
    let refused = gl.failed();
    (gl.FramebufferRenderbuffer)(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, o.renderbuffer);
    let complete = (gl.CheckFramebufferStatus)(FRAMEBUFFER) == FRAMEBUFFER_COMPLETE;
    gl.check("attaching the probe's depth renderbuffer raised a GL error")?;
    Ok(complete && !refused)
}

/// A triangle's vertices as the vertex buffer holds them (eye space, `w = 1`; or clip
/// coordinates when drawn with [`IDENTITY`]).
type Triangle = [[f32; 4]; 3];

/// A triangle's exact clip coordinates: its f32 vertices times the f32 matrix, in f64.
type ClipTriangle = [[f64; 4]; 3];

/// The identity matrix: vertices are clip coordinates.
const IDENTITY: [f32; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Triangles drawn with one projection matrix (column-major, as `glUniformMatrix4fv` takes it).
struct Scene {
    matrix: [f32; 16],
    triangles: Vec<Triangle>,
}

impl Scene {
    /// Triangles whose vertices are clip coordinates.
    fn clip(triangles: Vec<Triangle>) -> Scene {
        Scene {
            matrix: IDENTITY,
            triangles,
        }
    }

    /// Each triangle's exact clip coordinates: the products of f32 values are exact in f64 and
    /// the sums of four of them err by ~10⁻¹⁶ relative, far below the GPU's f32 arithmetic.
    fn exact(&self) -> Vec<ClipTriangle> {
        let m = self.matrix.map(f64::from);
        self.triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    let v = v.map(f64::from);
                    std::array::from_fn(|row| (0..4).map(|k| m[4 * k + row] * v[k]).sum())
                })
            })
            .collect()
    }
}

/// Clears depth to 1, draws `scene` into the first tile (depth test `GL_ALWAYS`), and reads the
/// stored window depth back exactly (rows bottom-up).
unsafe fn draw(gl: &Gl, o: &Objects, format: Format, scene: &Scene) -> Result<Vec<f64>> {
    let mut tiles = draw_tiles(gl, o, format, std::slice::from_ref(scene))?;
    Ok(tiles.swap_remove(0))
}

/// Draws each scene into a tile of its own (at most `TILES²`) and returns each tile's stored
/// window depth, `SIZE × SIZE` rows bottom-up.
unsafe fn draw_tiles(
    gl: &Gl,
    o: &Objects,
    format: Format,
    scenes: &[Scene],
) -> Result<Vec<Vec<f64>>> {
    let (width, height) = render_tiles(gl, o, scenes)?;
    let depth = read_depth(gl, format, 0, width, height)?;
    Ok((0..scenes.len().min(TILES * TILES))
        .map(|i| {
            let (x, y) = ((i % TILES) * SIZE, (i / TILES) * SIZE);
            (0..SIZE)
                .flat_map(|row| {
                    let start = (y + row) * width + x;
                    depth[start..start + SIZE].iter().copied()
                })
                .collect()
        })
        .collect())
}

/// Draws each scene into a tile of its own (at most `TILES²`, depth test `GL_ALWAYS` into a
/// cleared buffer) and returns the width and height of the framebuffer region the tiles cover.
unsafe fn render_tiles(gl: &Gl, o: &Objects, scenes: &[Scene]) -> Result<(usize, usize)> {
    (gl.Viewport)(0, 0, (SIZE * TILES) as Sizei, (SIZE * TILES) as Sizei);
    (gl.ClearDepth)(1.0);
    (gl.Clear)(DEPTH_BUFFER_BIT);
    let all: Vec<Triangle> = scenes
        .iter()
        .flat_map(|s| s.triangles.iter().copied())
        .collect();
    let bytes = std::mem::size_of_val(all.as_slice());
    (gl.BufferData)(
        ARRAY_BUFFER,
        bytes as isize,
        all.as_ptr().cast(),
        STREAM_DRAW,
    );
    let mut first = 0;
    for (i, scene) in scenes.iter().enumerate().take(TILES * TILES) {
        let (x, y) = ((i % TILES) * SIZE, (i / TILES) * SIZE);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        (gl.UniformMatrix4fv)(o.projection, 1, 0, scene.matrix.as_ptr());
        (gl.DrawArrays)(TRIANGLES, first, 3 * scene.triangles.len() as Sizei);
        first += 3 * scene.triangles.len() as Int;
    }
    gl.check("drawing the probe's triangles raised a GL error")?;
    let columns = scenes.len().clamp(1, TILES);
    let rows = scenes.len().div_ceil(TILES).clamp(1, TILES);
    Ok((columns * SIZE, rows * SIZE))
}

unsafe fn read_depth(
    gl: &Gl,
    format: Format,
    y: usize,
    width: usize,
    height: usize,
) -> Result<Vec<f64>> {
    let mut raw = vec![0u32; width * height];
    let kind = match format {
        Format::Unorm(_) => UNSIGNED_INT,
        Format::Float => FLOAT,
    };
    let (w, h, ptr) = (width as Sizei, height as Sizei, raw.as_mut_ptr().cast());
    (gl.ReadPixels)(0, y as Int, w, h, DEPTH_COMPONENT, kind, ptr);
    gl.check("glReadPixels(GL_DEPTH_COMPONENT) raised a GL error")?;
    Ok(match format {
        Format::Unorm(m) => {
            let steps = 2f64.powi(m as i32) - 1.0;
            let scale = steps / (2f64.powi(32) - 1.0);
            raw.iter()
                .map(|&v| (v as f64 * scale).round() / steps)
                .collect()
        }
        Format::Float => raw.iter().map(|&v| f32::from_bits(v) as f64).collect(),
    })
}

/// A triangle's plane in window space, exactly: the homogeneous weights `a` with `Σ aᵢ·vᵢ` on
/// the ray through NDC point `(x, y)` are the cross product of the rows `Xᵢ − x·Wᵢ` and
/// `Yᵢ − y·Wᵢ`, which is affine in `(x, y)`: `a = X×Y + x·(Y×W) + y·(W×X)`. The point is inside
/// when every `aᵢ` has the sign of `Σ aᵢ·Wᵢ`, and its NDC depth is `Σ aᵢ·Zᵢ / Σ aᵢ·Wᵢ`. Valid
/// for triangles with vertices behind the camera, which a clipper cuts.
struct Plane {
    /// `[constant, ∂/∂x, ∂/∂y]` of each `aᵢ`, of `Σ aᵢ·Wᵢ` and of `Σ aᵢ·Zᵢ`.
    weights: [[f64; 3]; 3],
    w: [f64; 3],
    z: [f64; 3],
    /// NDC depth in `[0, 1]` (`glClipControl(GL_ZERO_TO_ONE)`), stored as is; else `[−1, 1]`.
    zero_to_one: bool,
    /// The largest window depth of the vertices in front of the camera.
    largest: f64,
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl Plane {
    fn new(t: &ClipTriangle) -> Plane {
        Plane::with_mapping(t, false)
    }

    fn with_mapping(t: &ClipTriangle, zero_to_one: bool) -> Plane {
        let column = |k: usize| [t[0][k], t[1][k], t[2][k]];
        let (x, y, z, w) = (column(0), column(1), column(2), column(3));
        let parts = [cross(x, y), cross(y, w), cross(w, x)];
        let weights = std::array::from_fn(|i| parts.map(|p| p[i]));
        let dot = |v: [f64; 3]| parts.map(|p| p[0] * v[0] + p[1] * v[1] + p[2] * v[2]);
        let largest = t
            .iter()
            .filter(|v| v[3] > 0.0)
            .map(|v| {
                let ndc = v[2] / v[3];
                if zero_to_one {
                    ndc
                } else {
                    0.5 * ndc + 0.5
                }
            })
            .fold(0.0, f64::max);
        Plane {
            weights,
            w: dot(w),
            z: dot(z),
            zero_to_one,
            largest,
        }
    }

    /// The exact window depth at window point `(x, y)`, if it lies inside the visible part of
    /// the triangle (in front of the near plane, inside the far one).
    fn depth_at(&self, x: f64, y: f64) -> Option<f64> {
        let s = SIZE as f64;
        let (xn, yn) = (2.0 * x / s - 1.0, 2.0 * y / s - 1.0);
        let eval = |c: &[f64; 3]| c[0] + xn * c[1] + yn * c[2];
        let w = eval(&self.w);
        if w == 0.0 || self.weights.iter().any(|c| eval(c) * w <= 0.0) {
            return None;
        }
        let ndc = eval(&self.z) / w;
        let window = if self.zero_to_one {
            ndc
        } else {
            0.5 * ndc + 0.5
        };
        let lowest = if self.zero_to_one { 0.0 } else { -1.0 + 1e-6 };
        (ndc > lowest && ndc < 1.0 - 1e-6).then_some(window)
    }

    /// The window depth of the plane at tile point `(x, y)`, inside the triangle or not.
    fn extended(&self, x: f64, y: f64) -> f64 {
        let s = SIZE as f64;
        let (xn, yn) = (2.0 * x / s - 1.0, 2.0 * y / s - 1.0);
        let eval = |c: &[f64; 3]| c[0] + xn * c[1] + yn * c[2];
        let ndc = eval(&self.z) / eval(&self.w);
        if self.zero_to_one {
            ndc
        } else {
            0.5 * ndc + 0.5
        }
    }

    /// `M(px, py) = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y` for the pixels of a tile whose corner is at
    /// window `(tx, ty)`: the magnitude of the terms of the plane evaluated from the window
    /// origin (`w₀` its depth extrapolated to window `(0, 0)`, `x`, `y` window coordinates).
    fn magnitude(&self, (tx, ty): (f64, f64)) -> impl Fn(usize, usize) -> f64 {
        let origin = self.extended(-tx, -ty);
        let gx = (self.extended(1.0 - tx, -ty) - origin).abs();
        let gy = (self.extended(-tx, 1.0 - ty) - origin).abs();
        move |px, py| origin.abs() + gx * (tx + px as f64 + 0.5) + gy * (ty + py as f64 + 0.5)
    }

    /// The exact window depth at pixel `(px, py)`'s centre, if the centre and its four
    /// neighbours one pixel away are inside: pixels on an edge, whose coverage is ambiguous, are
    /// left out.
    fn depth_inside(&self, px: usize, py: usize) -> Option<f64> {
        let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
        let window = self.depth_at(x, y)?;
        // Each weight is affine: it keeps its sign a pixel away in x and y when its value
        // exceeds what a one-pixel step in both can change (one NDC pixel is 2/SIZE).
        let (xn, yn) = (2.0 * x / SIZE as f64 - 1.0, 2.0 * y / SIZE as f64 - 1.0);
        let step = 2.0 / SIZE as f64;
        let sign = (self.w[0] + xn * self.w[1] + yn * self.w[2]).signum();
        let margin_ok = self
            .weights
            .iter()
            .all(|c| sign * (c[0] + xn * c[1] + yn * c[2]) > step * (c[1].abs() + c[2].abs()));
        margin_ok.then_some(window)
    }
}

// ---------------------------------------------------------------------------------------------
// Scenes: triangles on eye-space planes, projected with glFrustum in f64 and rounded to f32.
// ---------------------------------------------------------------------------------------------

/// A symmetric `glFrustum(−e·n, e·n, −e·n, e·n, n, f)`.
#[derive(Clone, Copy)]
struct View {
    e: f64,
    n: f64,
    f: f64,
    /// Reversed depth for `glClipControl(GL_ZERO_TO_ONE)`: window depth `n(f − d)/((f − n)d)`.
    reversed: bool,
    /// The vertical half-extent tangent over the horizontal one (0.5625 for 16:9).
    squash: f64,
}

impl View {
    /// The projection matrix, each element computed in f64 and rounded to f32 as an engine
    /// passes it (`glFrustum`'s, or its reversed `[0, 1]` form).
    fn matrix(&self) -> [f32; 16] {
        let (n, f) = (self.n, self.f);
        let (m10, m14) = if self.reversed {
            (n / (f - n), f * n / (f - n))
        } else {
            (-(f + n) / (f - n), -2.0 * f * n / (f - n))
        };
        let (sx, sy) = (1.0 / self.e, 1.0 / (self.e * self.squash));
        [
            sx, 0.0, 0.0, 0.0, 0.0, sy, 0.0, 0.0, 0.0, 0.0, m10, -1.0, 0.0, 0.0, m14, 0.0,
        ]
        .map(|m| m as f32)
    }

    /// The triangle `t` (eye space) as a vertex buffer holds it: f32 coordinates, `w = 1`.
    fn triangle(t: [[f64; 3]; 3]) -> Triangle {
        t.map(|[x, y, z]| [x as f32, y as f32, z as f32, 1.0])
    }

    /// The eye point on the plane `z = −d − sx·x − sy·y` seen at NDC `(xn, yn)`, if it lies
    /// between the near and far planes.
    fn on_plane(&self, xn: f64, yn: f64, d: f64, sx: f64, sy: f64) -> Option<[f64; 3]> {
        let ey = self.e * self.squash;
        let denominator = 1.0 - (self.e * sx * xn + ey * sy * yn);
        if denominator <= 0.0 {
            return None;
        }
        let z = -d / denominator;
        (-z > self.n * 1.001 && -z < self.f * 0.999).then_some([-z * xn * self.e, -z * yn * ey, z])
    }

    /// Window depth at eye distance `d` (for choosing planes by the depth they store).
    fn distance_at_depth(&self, w: f64) -> f64 {
        let (n, f) = (self.n, self.f);
        if self.reversed {
            // w = n(f − d)/((f − n)d)  ⇒  d = f·n/(n + w(f − n))
            f * n / (n + w * (f - n))
        } else {
            // w = f(d − n)/(d(f − n))  ⇒  d = f·n/(f − w(f − n))
            f * n / (f - w * (f - n))
        }
    }
}

/// Triangle corners in NDC: one on screen, one reaching four viewports past it.
const CORNERS: [[[f64; 2]; 3]; 2] = [
    [[-0.93, -0.871], [0.947, -0.613], [-0.207, 0.969]],
    [[-4.1, -3.3], [3.7, -2.9], [0.31, 5.2]],
];

/// Eye-space slopes `(∂z/∂x, ∂z/∂y)` of the plane-error scenes: facing, gentle, steep, grazing.
const SLOPES: [(f64, f64); 4] = [(0.0, 0.0), (0.37, 1.0), (-3.0, 1.9), (10.0, -0.3)];

/// The plane-error scenes of one depth mapping: for each view, axis depth and slope, each
/// corner set shrunk toward the view axis (halved, up to 4 times) until every corner lies
/// between the near and far planes.
fn plane_scenes(reversed: bool) -> Vec<Scene> {
    let views: [(View, [f64; 2]); 3] = if reversed {
        [
            (
                View {
                    e: 0.5,
                    n: 0.1,
                    f: 1e4,
                    reversed,
                    squash: 1.0,
                },
                [0.002, 0.3],
            ),
            (
                View {
                    e: 0.7,
                    n: 1.0,
                    f: 1e6,
                    reversed,
                    squash: 1.0,
                },
                [2e-5, 0.05],
            ),
            (
                View {
                    e: 0.4,
                    n: 0.5,
                    f: 100.0,
                    reversed,
                    squash: 1.0,
                },
                [0.02, 0.7],
            ),
        ]
    } else {
        [
            (
                View {
                    e: 0.5,
                    n: 1.0,
                    f: 10.0,
                    reversed,
                    squash: 1.0,
                },
                [0.02, 0.6],
            ),
            (
                View {
                    e: 0.7,
                    n: 0.1,
                    f: 100.0,
                    reversed,
                    squash: 1.0,
                },
                [0.3, 0.95],
            ),
            (
                View {
                    e: 0.4,
                    n: 1.0,
                    f: 1e5,
                    reversed,
                    squash: 1.0,
                },
                [0.5, 0.998],
            ),
        ]
    };
    let mut out = Vec::new();
    for (view, depths) in views {
        for w in depths {
            let d = view.distance_at_depth(w);
            for (sx, sy) in SLOPES {
                for corners in CORNERS {
                    let fits = (0..5).find_map(|halvings| {
                        let k = 0.5f64.powi(halvings);
                        let t: Option<Vec<[f64; 3]>> = corners
                            .iter()
                            .map(|&[xn, yn]| view.on_plane(k * xn, k * yn, d, sx, sy))
                            .collect();
                        t
                    });
                    if let Some(t) = fits {
                        out.push(Scene {
                            matrix: view.matrix(),
                            triangles: vec![View::triangle([t[0], t[1], t[2]])],
                        });
                    }
                }
            }
        }
    }
    out
}

/// Sloped planes in every direction, as engines draw them: the fixed scenes of
/// [`plane_scenes`] cover a few slopes and views; these add 256 more (under reversed Z too), deterministic
/// pseudo-random (f/n from 10² to 10⁹, aspect 1/1.6 to 1.6, slope 0.3 to 10 in any direction,
/// axis depths log-spread over the range, triangles on screen or reaching up to half a viewport
/// past it). A rounding maximum grows with the number of planes it is taken over, and the
/// figure must hold for planes the probe does not draw: on llvmpipe the fixed scenes alone found
/// 1.40, these 256 more 1.54, and a survey of 804 other planes reaches 1.74 (`tests/gl_scenes.rs`).
fn varied_plane_scenes(reversed: bool) -> Vec<Scene> {
    let mut state: u64 = 0x5EED_2026_1123;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let ratios = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e9];
    let slopes = [0.3, 1.0, 3.0, 10.0];
    let mut out = Vec::new();
    for i in 0..TILES * TILES * 16 {
        if out.len() == 4 * TILES * TILES {
            break;
        }
        let ratio = ratios[i % ratios.len()];
        let n = if next() < 0.5 { 0.1 } else { 1.0 };
        let view = View {
            e: 0.35 + 0.4 * next(),
            n,
            f: n * ratio,
            reversed,
            squash: 0.625 + next(),
        };
        let slope = slopes[(i / ratios.len()) % slopes.len()];
        let angle = std::f64::consts::TAU * next();
        let (sx, sy) = (slope * angle.cos(), slope * angle.sin());
        let d = n * ratio.powf(0.9 * next()).max(1.5);
        let corners: [[f64; 2]; 3] =
            std::array::from_fn(|_| [3.0 * next() - 1.5, 3.0 * next() - 1.5]);
        let t: Option<Vec<[f64; 3]>> = corners
            .iter()
            .map(|&[xn, yn]| view.on_plane(xn, yn, d, sx, sy))
            .collect();
        if let Some(t) = t {
            out.push(Scene {
                matrix: view.matrix(),
                triangles: vec![View::triangle([t[0], t[1], t[2]])],
            });
        }
    }
    out
}

/// The figures of [`plane_error`] for one format and mapping.
struct PlaneErrors {
    /// The worst error in quanta (D32F: 2⁻²⁴ under `[−1, 1]`, the spacing at the primitive's
    /// largest depth under reversed Z), over every scene.
    worst: f64,
    /// Pixels compared.
    pixels: usize,
    /// The worst error in units of the spacing at each pixel's own depth.
    local: f64,
    /// The worst `(|stored − exact| − conversion)⁺ / (2⁻²⁴·(1 + M))` ([`Plane::magnitude`]).
    error_ulps: f64,
}

/// The plane errors of every scene of `format` under one mapping (module docs).
unsafe fn plane_error(gl: &Gl, o: &Objects, format: Format, reversed: bool) -> Result<PlaneErrors> {
    let mut e = PlaneErrors {
        worst: 0.0,
        pixels: 0,
        local: 0.0,
        error_ulps: 0.0,
    };
    let mut scenes = plane_scenes(reversed);
    let fixed = scenes.len();
    if format == Format::Float {
        // D32F stores the computed depth as is: error_ulps comes from it (the UNORM formats'
        // conversion hides a quantum), so the varied planes are drawn there only.
        scenes.extend(varied_plane_scenes(reversed));
    }
    let mut stored_tiles = Vec::new();
    for batch in scenes.chunks(TILES * TILES) {
        stored_tiles.extend(draw_tiles(gl, o, format, batch)?);
    }
    for (i, (scene, stored)) in scenes.iter().zip(stored_tiles).enumerate() {
        let plane = Plane::with_mapping(&scene.exact()[0], reversed);
        // D32F under [−1, 1] errs mostly in absolute terms (u·|m10| from the transform), so its
        // unit is 2⁻²⁴, the spacing at w ≥ ½; under reversed Z the error is relative to the
        // primitive's largest depth, and so is its unit.
        let unit = |exact: f64| match (format, reversed) {
            (Format::Float, false) => F32_UNIT_ROUNDOFF,
            (Format::Float, true) => f32_spacing(plane.largest),
            _ => format.quantum(exact),
        };
        let tile = i % (TILES * TILES);
        let corner = (
            ((tile % TILES) * SIZE) as f64,
            ((tile / TILES) * SIZE) as f64,
        );
        let magnitude = plane.magnitude(corner);
        let m10 = f64::from(scene.matrix[10]).abs();
        // The varied planes are read on every other row and column: their figure is a maximum
        // over planes more than over neighbouring pixels, and a quarter of the pixels keeps the
        // probe's run time down.
        let stride = if i < fixed { 1 } else { 2 };
        for py in (0..SIZE).step_by(stride) {
            for px in (0..SIZE).step_by(stride) {
                let Some(exact) = plane.depth_inside(px, py) else {
                    continue;
                };
                let error = (stored[py * SIZE + px] - exact).abs();
                e.worst = e.worst.max(error / unit(exact));
                e.local = e.local.max(error / format.quantum(exact));
                e.pixels += 1;
                let conversion = match format {
                    Format::Float => 0.0,
                    Format::Unorm(_) => format.quantum(exact),
                };
                // Under [−1, 1] the 1 stands for the transform's own roundings; under reversed Z
                // they are relative to |m10| (the product m10·z) and to the depth itself (in M).
                let constant = if reversed { m10 } else { 1.0 };
                let scale = F32_UNIT_ROUNDOFF * (constant + magnitude(px, py));
                e.error_ulps = e.error_ulps.max((error - conversion).max(0.0) / scale);
            }
        }
    }
    Ok(e)
}

/// The unit roundoff of f32, `2⁻²⁴`.
const F32_UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// [`plane_error`] of D32F under reversed Z (`glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`,
/// reversed projection), where float depth keeps its relative precision; `None` without
/// `glClipControl`.
unsafe fn reversed_plane_error(gl: &Gl, o: &Objects) -> Result<Option<PlaneErrors>> {
    let Some(clip_control) = gl.ClipControl else {
        return Ok(None);
    };
    clip_control(LOWER_LEFT, ZERO_TO_ONE);
    let result = plane_error(gl, o, Format::Float, true);
    clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
    result.map(Some)
}

// ---------------------------------------------------------------------------------------------
// What a facing decal needs: the element-10 offset that always wins a strict depth test
// ---------------------------------------------------------------------------------------------

/// The depth conventions [`facing_quanta`] measures.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Facing {
    NegOneToOne,
    ZeroToOne,
    Reversed,
}

/// The view's matrix (`glFrustum`'s, or its reversed form), or under [`Facing::ZeroToOne`] its
/// `[0, 1]` form (`glClipControl`
/// `GL_ZERO_TO_ONE`, standard depth): `m10 = −f/(f − n)`, `m14 = −fn/(f − n)`.
fn facing_matrix(view: &View, mode: Facing) -> [f32; 16] {
    let mut m = view.matrix();
    if mode == Facing::ZeroToOne {
        let (n, f) = (view.n, view.f);
        m[10] = (-f / (f - n)) as f32;
        m[14] = (-f * n / (f - n)) as f32;
    }
    m
}

/// The most f32 steps of element 10 the search tries (a D24 quantum is one or two).
const FACING_MAX_STEPS: u32 = 16;

/// The window-depth offset, in quanta of `format`, that a decal facing the camera needs to pass
/// `GL_LESS` over its base when both share one f32 z and the decal's element 10 moves toward 0
/// by `k` f32 steps (the rest of the matrix unchanged, as `zshift_recommend_matrix` draws it):
/// for each of 256 depths (window depth 0.02 to 0.9995, two frusta, a tile quadrant each), the smallest
/// `k` whose stored depth is below the base's, its exact window offset `k·ulp(m10)/2` over the
/// quantum (D32F: over 2⁻²⁴); the largest over the depths. Each depth has its own phase between two stored
/// values, so the largest is what the worst phase needs. `None` (not measured) on D16, whose
/// quantum is hundreds of steps (its `q + 2T` is within a few percent of `q` anyway), or if some
/// depth needs more than [`FACING_MAX_STEPS`].
/// With [`Facing::ZeroToOne`] the same under `glClipControl(GL_ZERO_TO_ONE)` (set by the caller) with
/// the `[0, 1]` matrix (`m10 = −f/(f − n)`, `m14 = −fn/(f − n)`), where a step of element 10
/// moves window depth by a whole `ulp(m10)`.
///
/// With [`Facing::Reversed`] (D32F only): reversed depth under `GL_ZERO_TO_ONE`, element 14
/// moved away from 0 by `k` steps (the relative offset of `zshift_recommend_clip`), `GL_GREATER`,
/// 256 window depths from 10⁻⁵ to 0.9 spaced by ratio; the figure is the relative ε
/// `k·ulp(m14)/m14` in units of 2⁻²⁴.
unsafe fn facing_quanta(
    gl: &Gl,
    o: &Objects,
    format: Format,
    mode: Facing,
    seen: &mut Vec<ChainObservation>,
) -> Result<Option<f64>> {
    let reversed = mode == Facing::Reversed;
    if reversed && format != Format::Float {
        return Ok(None);
    }
    let views = [
        View {
            e: 0.5,
            n: 0.1,
            f: 1e3,
            reversed,
            squash: 1.0,
        },
        View {
            e: 0.6,
            n: 1.0,
            f: 1e6,
            reversed,
            squash: 0.5625,
        },
    ];
    // Four planes per tile, one per quadrant (the tile's matrix is its view's): 128 depths per
    // view for the cost of 32 tiles.
    let per_view = TILES * TILES / 2;
    let planes: Vec<(View, f64)> = views
        .iter()
        .flat_map(|&v| {
            let count = 4 * per_view;
            (0..count).map(move |i| {
                let x = i as f64 / (count - 1) as f64;
                let w = if reversed {
                    1e-5 * (0.9f64 / 1e-5).powf(x)
                } else {
                    0.02 + (0.9995 - 0.02) * x
                };
                (v, w)
            })
        })
        .collect();
    const QUADRANTS: [(f64, f64); 4] = [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)];
    let scenes = |k: u32| -> Vec<Scene> {
        planes
            .chunks(4)
            .map(|four| {
                let view = four[0].0;
                let ey = view.e * view.squash;
                let mut triangles = Vec::new();
                for (&(_, w), (cx, cy)) in four.iter().zip(QUADRANTS) {
                    let d = view.distance_at_depth(w);
                    let at = |xn: f64, yn: f64| [(cx + xn) * view.e * d, (cy + yn) * ey * d, -d];
                    let (a, b, c, e) = (
                        at(-0.45, -0.45),
                        at(0.45, -0.45),
                        at(0.45, 0.45),
                        at(-0.45, 0.45),
                    );
                    triangles.push(View::triangle([a, b, c]));
                    triangles.push(View::triangle([a, c, e]));
                }
                let mut matrix = facing_matrix(&view, mode);
                if reversed {
                    matrix[14] = f32::from_bits(matrix[14].to_bits() + k); // m14 > 0: away from 0
                } else {
                    matrix[10] = f32::from_bits(matrix[10].to_bits() - k); // m10 < 0: toward 0
                }
                Scene { matrix, triangles }
            })
            .collect()
    };
    // The stored depth at each quadrant's centre, plane by plane: only the two rows of pixels
    // through the centres of each row of tiles are read back (a 32nd of the tiles).
    let centre = |c: f64| ((c + 1.0) * 0.5 * SIZE as f64) as usize;
    let draw_and_read = |k: u32| -> Result<Vec<f64>> {
        let scenes = scenes(k);
        let (width, height) = render_tiles(gl, o, &scenes)?;
        let mut rows = Vec::new();
        for tile_row in 0..height / SIZE {
            let lower = read_depth(gl, format, tile_row * SIZE + centre(-0.5), width, 1)?;
            let upper = read_depth(gl, format, tile_row * SIZE + centre(0.5), width, 1)?;
            rows.push((lower, upper));
        }
        Ok((0..scenes.len())
            .flat_map(|i| {
                let (lower, upper) = &rows[i / TILES];
                let x = (i % TILES) * SIZE;
                QUADRANTS.map(|(cx, cy)| {
                    let row = if cy < 0.0 { lower } else { upper };
                    row[x + centre(cx)]
                })
            })
            .collect())
    };
    // Every stored value read, with the f32 inputs that made it, for identifying the chain.
    let clip = match mode {
        Facing::NegOneToOne => ClipDepth::NegOneToOne,
        Facing::ZeroToOne => ClipDepth::ZeroToOne,
        Facing::Reversed => ClipDepth::ReversedZeroToOne,
    };
    let mut record = |k: u32, values: &[f64]| {
        for (&(view, w), &value) in planes.iter().zip(values) {
            let m = facing_matrix(&view, mode);
            let Some((m10, m14)) = crate::depth_chain::stepped((m[10], m[14]), reversed, k) else {
                continue;
            };
            seen.push(ChainObservation {
                clip,
                bits: format.bits(),
                m10,
                m14,
                z: -(view.distance_at_depth(w) as f32),
                stored: format.integer(value),
            });
        }
    };
    let base = draw_and_read(0)?;
    record(0, &base);
    if format == Format::Unorm(16) {
        // One D16 quantum is hundreds of steps: only the chain's conversion is checked here.
        return Ok(None);
    }
    let mut needed = vec![None; planes.len()];
    for k in 1..=FACING_MAX_STEPS {
        let decal = draw_and_read(k)?;
        record(k, &decal);
        for (i, d) in decal.iter().enumerate() {
            let wins = if reversed { *d > base[i] } else { *d < base[i] };
            if needed[i].is_none() && wins {
                needed[i] = Some(k);
            }
        }
        if needed.iter().all(Option::is_some) {
            break;
        }
    }
    let mut worst = 0.0f64;
    for (&(view, w), k) in planes.iter().zip(&needed) {
        let Some(k) = k else { return Ok(None) };
        let m = facing_matrix(&view, mode);
        if reversed {
            let m14 = f64::from(m[14]);
            let step = f64::from(f32::from_bits(m[14].to_bits() + 1)) - m14;
            worst = worst.max(f64::from(*k) * step / m14 / F32_UNIT_ROUNDOFF);
            continue;
        }
        let step = f64::from(m[10]).abs() - f64::from(f32::from_bits(m[10].to_bits() - 1)).abs();
        // Window depth moves by the NDC change, halved under [−1, 1].
        let ulp = if mode == Facing::ZeroToOne {
            2.0 * step
        } else {
            step
        };
        // D32F in units of 2⁻²⁴ (the offset is a constant window depth), as `plane_error`.
        let unit = match format {
            Format::Float => F32_UNIT_ROUNDOFF,
            _ => format.quantum(w),
        };
        worst = worst.max(f64::from(*k) * ulp / 2.0 / unit);
    }
    Ok(Some(worst))
}

// ---------------------------------------------------------------------------------------------
// glPolygonOffset's r
// ---------------------------------------------------------------------------------------------

/// The `units` of every offset draw: one value, because a rasterizer may compile a variant per
/// value (llvmpipe does). Up to 4 quanta per unit it keeps D16 below window depth 1 (2^12 × 4 /
/// 65535 ≈ 0.25 above 0.45), and it moves D32 by 2^-20 or more, 30× its f32 pipeline's noise.
const OFFSET_UNITS: f32 = 4096.0;

/// `r` in quanta (module docs): a quad covering the viewport, window depth `lo` to `hi` across x.
unsafe fn resolvable(gl: &Gl, o: &Objects, format: Format) -> Result<Vec<f64>> {
    let bands: &[(f64, f64)] = match format {
        Format::Unorm(_) => &[(0.40, 0.45)],
        Format::Float => &[(0.40, 0.45), (0.050, 0.055)],
    };
    let mut r = Vec::new();
    for &(lo, hi) in bands {
        let z = |w: f64| (2.0 * w - 1.0) as f32;
        let (a, b) = (z(lo), z(hi));
        let quad = Scene::clip(vec![
            [
                [-1.0, -1.0, a, 1.0],
                [1.0, -1.0, b, 1.0],
                [1.0, 1.0, b, 1.0],
            ],
            [
                [-1.0, -1.0, a, 1.0],
                [1.0, 1.0, b, 1.0],
                [-1.0, 1.0, a, 1.0],
            ],
        ]);
        // The unit is the quantum at the primitive's largest depth (for D32F, `2^(e − 23)`).
        let unit = format.quantum(0.5 * b as f64 + 0.5);
        let plain = draw(gl, o, format, &quad)?;
        (gl.Enable)(POLYGON_OFFSET_FILL);
        (gl.PolygonOffset)(0.0, OFFSET_UNITS);
        let offset = draw(gl, o, format, &quad);
        (gl.Disable)(POLYGON_OFFSET_FILL);
        let offset = offset?;
        let sum: f64 = offset.iter().zip(&plain).map(|(o, p)| o - p).sum();
        let mean = sum / plain.len() as f64;
        r.push(mean / OFFSET_UNITS as f64 / unit);
    }
    Ok(r)
}

// ---------------------------------------------------------------------------------------------
// Lines over their faces: where a line fragment takes its depth, and the polygon-offset slope
// ---------------------------------------------------------------------------------------------

/// The window-depth gradient per pixel (along the steeper axis) of the planes the line
/// measurement draws in: steep enough that D32F's spacing (≈ 6·10⁻⁸ at 0.5) is 1.5·10⁻⁵ pixel.
const LINE_GRADIENT: f64 = 1.0 / 256.0;

/// Tiles per line kind (`GL_LINES`, polygon-mode lines), each with its own plane.
const LINE_TILES: usize = 16;

/// What [`line_reach`] measured.
struct LineFigures {
    /// The largest `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` per kind
    /// (`GL_LINES` width 1, polygon-mode lines width 1), pixels.
    reach: [f64; 2],
    /// Fragments compared per kind.
    pixels: [usize; 2],
    /// `glPolygonOffset(1, 0)`'s offset on a plane with `|gₓ| = |g_y| = g`, over `g`
    /// (1: `max(|gₓ|, |g_y|)`; `√2`: their root sum of squares), and the same on a plane with
    /// `g_y = 0` (1 under either rule: the factor's scale).
    slope: [f64; 2],
}

/// A tile's plane, window depth `0.5 + gₓ·(x − 32) + g_y·(y − 32)` in tile pixels.
fn tile_plane(k: usize) -> (f64, f64) {
    // Gradient directions spread over the circle, the larger component always LINE_GRADIENT.
    let theta = std::f64::consts::PI * (2 * k + 1) as f64 / (LINE_TILES as f64);
    let (c, s) = (theta.cos(), theta.sin());
    let big = c.abs().max(s.abs());
    (LINE_GRADIENT * c / big, LINE_GRADIENT * s / big)
}

/// The vertex of tile pixel coordinates `(x, y)` on plane `(gₓ, g_y)`: clip coordinates with
/// `w = 1` (drawn with [`IDENTITY`] into a `SIZE`-pixel tile), `[−1, 1]` depth.
fn tile_vertex(x: f64, y: f64, (gx, gy): (f64, f64)) -> [f32; 4] {
    let half = SIZE as f64 / 2.0;
    let z = 0.5 + gx * (x - half) + gy * (y - half);
    [
        (x / half - 1.0) as f32,
        (y / half - 1.0) as f32,
        (2.0 * z - 1.0) as f32,
        1.0,
    ]
}

/// Measures how far from the pixel a line fragment's depth is taken, per line kind, and
/// `glPolygonOffset`'s slope rule (module docs). Needs D32F attached.
unsafe fn line_reach(gl: &Gl, o: &Objects) -> Result<LineFigures> {
    // A small deterministic generator: sub-pixel endpoints in every direction.
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut lines: Vec<Vec<[f32; 4]>> = Vec::new();
    let mut polygons: Vec<Vec<[f32; 4]>> = Vec::new();
    for k in 0..LINE_TILES {
        let plane = tile_plane(k);
        let mut segments = Vec::new();
        for j in 0..6 {
            // Six directions per tile, each tile turned a little further.
            let phi = std::f64::consts::PI * (j as f64 + k as f64 / LINE_TILES as f64) / 6.0;
            let (cx, cy) = (32.0 + 16.0 * (next() - 0.5), 32.0 + 16.0 * (next() - 0.5));
            let half = 18.0 + 8.0 * next();
            let (dx, dy) = (half * phi.cos(), half * phi.sin());
            segments.push(tile_vertex(cx - dx, cy - dy, plane));
            segments.push(tile_vertex(cx + dx, cy + dy, plane));
        }
        lines.push(segments);
        let mut triangles = Vec::new();
        for _ in 0..3 {
            for _ in 0..3 {
                triangles.push(tile_vertex(4.0 + 56.0 * next(), 4.0 + 56.0 * next(), plane));
            }
        }
        polygons.push(triangles);
    }
    // Slope rule: a filled tile on a diagonal plane and on an axis plane, plain and offset.
    let diagonal = (LINE_GRADIENT, LINE_GRADIENT);
    let axis = (LINE_GRADIENT, 0.0);
    let quad = |plane| {
        let c = [(1.0, 1.0), (63.0, 1.0), (63.0, 63.0), (1.0, 63.0)]
            .map(|(x, y)| tile_vertex(x, y, plane));
        vec![c[0], c[1], c[2], c[0], c[2], c[3]]
    };
    let slope_tiles = [quad(diagonal), quad(axis)];

    let mut all: Vec<[f32; 4]> = Vec::new();
    let mut draws: Vec<(usize, Enum, usize, usize, bool)> = Vec::new(); // tile, mode, first, count, offset
    let mut push = |tile: usize, mode: Enum, vertices: &[[f32; 4]], offset: bool| {
        draws.push((tile, mode, all.len(), vertices.len(), offset));
        all.extend_from_slice(vertices);
    };
    for (k, v) in lines.iter().enumerate() {
        push(k, LINES, v, false);
    }
    for (k, v) in polygons.iter().enumerate() {
        push(LINE_TILES + k, TRIANGLES, v, false);
    }
    for (k, v) in slope_tiles.iter().enumerate() {
        push(2 * LINE_TILES + 2 * k, TRIANGLES, v, false);
        push(2 * LINE_TILES + 2 * k + 1, TRIANGLES, v, true);
    }
    let side = (SIZE * TILES) as Sizei;
    (gl.Viewport)(0, 0, side, side);
    (gl.ClearDepth)(1.0);
    (gl.Clear)(DEPTH_BUFFER_BIT);
    (gl.UniformMatrix4fv)(o.projection, 1, 0, IDENTITY.as_ptr());
    let bytes = std::mem::size_of_val(all.as_slice());
    (gl.BufferData)(
        ARRAY_BUFFER,
        bytes as isize,
        all.as_ptr().cast(),
        STREAM_DRAW,
    );
    for &(tile, mode, first, count, offset) in &draws {
        let (x, y) = ((tile % TILES) * SIZE, (tile / TILES) * SIZE);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        let polygon_lines = (LINE_TILES..2 * LINE_TILES).contains(&tile);
        if polygon_lines {
            (gl.PolygonMode)(FRONT_AND_BACK, LINE);
        }
        if offset {
            (gl.Enable)(POLYGON_OFFSET_FILL);
            (gl.PolygonOffset)(1.0, 0.0);
        }
        (gl.DrawArrays)(mode, first as Int, count as Sizei);
        (gl.PolygonMode)(FRONT_AND_BACK, FILL);
        (gl.Disable)(POLYGON_OFFSET_FILL);
        (gl.PolygonOffset)(0.0, 0.0);
    }
    gl.check("drawing the probe's lines raised a GL error")?;
    let width = SIZE * TILES;
    let rows = (2 * LINE_TILES + 4).div_ceil(TILES);
    let depth = read_depth(gl, Format::Float, 0, width, rows * SIZE)?;
    let at = |tile: usize, px: usize, py: usize| {
        let (x, y) = ((tile % TILES) * SIZE + px, (tile / TILES) * SIZE + py);
        depth[y * width + x]
    };
    let mut reach = [0.0f64; 2];
    let mut pixels = [0usize; 2];
    for kind in 0..2 {
        for k in 0..LINE_TILES {
            let (gx, gy) = tile_plane(k);
            for py in 0..SIZE {
                for px in 0..SIZE {
                    let stored = at(kind * LINE_TILES + k, px, py);
                    if stored >= 0.99 {
                        continue;
                    }
                    let half = SIZE as f64 / 2.0;
                    let (x, y) = (px as f64 + 0.5 - half, py as f64 + 0.5 - half);
                    let exact = 0.5 + gx * x + gy * y;
                    reach[kind] = reach[kind].max((stored - exact).abs() / LINE_GRADIENT);
                    pixels[kind] += 1;
                }
            }
        }
    }
    let mut slope = [0.0; 2];
    for (k, s) in slope.iter_mut().enumerate() {
        let (plain, offset) = (2 * LINE_TILES + 2 * k, 2 * LINE_TILES + 2 * k + 1);
        let (mut sum, mut count) = (0.0, 0usize);
        for py in 4..SIZE - 4 {
            for px in 4..SIZE - 4 {
                sum += at(offset, px, py) - at(plain, px, py);
                count += 1;
            }
        }
        *s = sum / count as f64 / LINE_GRADIENT;
    }
    if pixels.contains(&0) {
        return Err(Error::new(
            ErrorKind::Gl,
            "the probe's lines drew no fragment (GL_LINES or glPolygonMode(GL_LINE))",
        ));
    }
    Ok(LineFigures {
        reach,
        pixels,
        slope,
    })
}

// ---------------------------------------------------------------------------------------------
// Snapping
// ---------------------------------------------------------------------------------------------

/// The finest snapping the probe tells from none: `2^-(12+1)` pixel moves the test triangle's
/// depth by 1.7·10⁻⁶, 17× the f32 noise of its depth (≈ 10⁻⁷); finer grids move it by less
/// than the noise, and their term in the model is as small (they read as unsnapped).
const MAX_SNAP_BITS: u32 = 12;

/// The largest residual (window depth) a snapping hypothesis may leave and still be believed:
/// 10× the f32 noise of the test triangles' depth, below the shift of any `b ≤ 12`.
const SNAP_FIT: f64 = 1e-6;

/// Which snapping hypothesis the stored depth of steep triangles fits best (module docs). When
/// none fits to [`SNAP_FIT`] the rasterizer does something the hypotheses do not describe, and
/// the answer is the conservative `GL_SUBPIXEL_BITS` it reports (8 if it reports none in
/// 1..=12).
unsafe fn snapping(
    gl: &Gl,
    o: &Objects,
    reported_bits: i32,
) -> Result<(Snapping, (f64, u32, f64))> {
    // Window positions with assorted sub-pixel parts; depth grows with x only.
    let sets: [[[f64; 2]; 3]; 2] = [
        [[6.3071, 5.1187], [58.6523, 9.4402], [11.8816, 59.7311]],
        [[4.5939, 7.8023], [60.1252, 3.2765], [33.3388, 61.0909]],
    ];
    let s = SIZE as f64;
    let mut residual = [0.0f64; 2 * (MAX_SNAP_BITS as usize + 1) + 1]; // none, (nearest, down) × b
    for set in sets {
        let t: Triangle = set.map(|[x, y]| {
            let z = 0.9 * (2.0 * x / s - 1.0);
            [
                (2.0 * x / s - 1.0) as f32,
                (2.0 * y / s - 1.0) as f32,
                z as f32,
                1.0,
            ]
        });
        let scene = Scene::clip(vec![t]);
        let stored = draw(gl, o, Format::Float, &scene)?;
        let plane = Plane::new(&scene.exact()[0]);
        let inside: Vec<(usize, usize)> = (0..SIZE * SIZE)
            .map(|i| (i % SIZE, i / SIZE))
            .filter(|&(px, py)| plane.depth_inside(px, py).is_some())
            .collect();
        for (h, slot) in residual.iter_mut().enumerate() {
            let snapped = Plane::new(&snap(&t, h));
            for &(px, py) in &inside {
                let Some(predicted) = snapped.depth_at(px as f64 + 0.5, py as f64 + 0.5) else {
                    continue;
                };
                *slot = slot.max((stored[py * SIZE + px] - predicted).abs());
            }
        }
    }
    let best = (0..residual.len())
        .min_by(|&a, &b| residual[a].total_cmp(&residual[b]))
        .unwrap_or(0);
    let snapped = (1..residual.len())
        .min_by(|&a, &b| residual[a].total_cmp(&residual[b]))
        .unwrap_or(1);
    let figures = (residual[0], ((snapped - 1) / 2) as u32, residual[snapped]);
    let conservative = match reported_bits {
        b @ 1..=12 => b as u32,
        _ => 8,
    };
    Ok(match best {
        _ if residual[best] > SNAP_FIT => (Snapping::SubpixelBits(conservative), figures),
        0 => (Snapping::Unsnapped, figures),
        h => (Snapping::SubpixelBits(((h - 1) / 2) as u32), figures),
    })
}

/// `t` (with w = 1) with its window positions snapped per hypothesis `h`: 0 none; `1 + 2b` to
/// the nearest `2^-b` pixel; `2 + 2b` down to it.
fn snap(t: &Triangle, h: usize) -> ClipTriangle {
    let (b, down) = (h.saturating_sub(1) / 2, h > 0 && (h - 1) % 2 == 1);
    let grid = 2f64.powi(b as i32);
    let s = SIZE as f64;
    t.map(|v| {
        let [x, y, z, w] = v.map(f64::from);
        let snap_ndc = |c: f64| {
            if h == 0 {
                return c;
            }
            let window = (c + 1.0) * s / 2.0 * grid;
            let window = if down { window.floor() } else { window.round() } / grid;
            window * 2.0 / s - 1.0
        };
        [snap_ndc(x), snap_ndc(y), z, w]
    })
}

// ---------------------------------------------------------------------------------------------
// Near-plane clipping
// ---------------------------------------------------------------------------------------------

/// How a triangle crossing the near plane keeps its depth (module docs): each ground plane is
/// drawn twice, once as given (the rasterizer clips it) and once clipped by the probe in f64 at
/// twice the near distance (nothing left for the rasterizer to clip); on the pixels both cover,
/// each is compared with the plane of the coordinates it was given (D24 quanta). Returns the
/// verdict and the two worst errors.
unsafe fn near_clip(gl: &Gl, o: &Objects) -> Result<(NearClip, f64, f64, f64)> {
    let view = NEAR_VIEW;
    let grounds = near_grounds();
    let given = grounds.iter().map(|g| Scene {
        matrix: view.matrix(),
        triangles: vec![View::triangle(*g)],
    });
    let preclipped = grounds.iter().map(|g| Scene {
        matrix: view.matrix(),
        triangles: clip_in_f64(*g, 2.0 * view.n)
            .into_iter()
            .map(View::triangle)
            .collect(),
    });
    // The clipper's error is also measured through off-centre frusta (the view axis inside and
    // outside the screen), where other planes cut the grounds.
    // And on planes in random directions (slopes 0.3 to 10, crossing the view axis 1 to 40 units
    // ahead, reaching 100 times that behind and ahead), through all three frusta: the model
    // takes the largest, a sampled maximum like error_ulps.
    let random = random_clipped_grounds();
    let views: Vec<[f64; 4]> = std::iter::once(CENTRED_NEAR_SIDES)
        .chain(SKEWED_NEAR_SIDES)
        .collect();
    let extra: Vec<([[f64; 3]; 3], [f64; 4])> = grounds
        .iter()
        .flat_map(|g| SKEWED_NEAR_SIDES.iter().map(move |m| (*g, *m)))
        .chain(
            random
                .iter()
                .enumerate()
                .map(|(i, g)| (*g, views[i % views.len()])),
        )
        .collect();
    let (mut worst_given, mut worst_preclipped, mut clip_ulps) = (0.0f64, 0.0f64, 0.0f64);
    // Each ground drawn as given and cut to the frustum in f64 first (nothing left for the
    // rasterizer to clip): the clipper's error is the excess of the first over the second. At
    // most TILES² tiles a draw.
    for batch in extra.chunks(TILES * TILES / 2) {
        let mut scenes = Vec::with_capacity(2 * batch.len());
        for (g, sides) in batch {
            let matrix = near_view_matrix(*sides);
            scenes.push(Scene {
                matrix,
                triangles: vec![View::triangle(*g)],
            });
            scenes.push(Scene {
                matrix,
                triangles: cut_to_frustum(*g, *sides)
                    .into_iter()
                    .map(View::triangle)
                    .collect(),
            });
        }
        let stored = draw_tiles(gl, o, Format::Unorm(24), &scenes)?;
        for (i, (ground, _)) in batch.iter().enumerate() {
            let unclipped = pixel_errors(&scenes[2 * i + 1], &stored[2 * i + 1]);
            clip_ulps = clip_ulps.max(clipper_ulps(
                &view,
                ground,
                &scenes[2 * i],
                &stored[2 * i],
                &unclipped,
            ));
        }
    }
    let scenes: Vec<Scene> = given.chain(preclipped).collect();
    let stored = draw_tiles(gl, o, Format::Unorm(24), &scenes)?;
    let count = grounds.len();
    for i in 0..count {
        let given_errors = pixel_errors(&scenes[i], &stored[i]);
        let preclipped_errors = pixel_errors(&scenes[count + i], &stored[count + i]);
        clip_ulps = clip_ulps.max(clipper_ulps(
            &view,
            &grounds[i],
            &scenes[i],
            &stored[i],
            &preclipped_errors,
        ));
        let both: Vec<(f64, f64)> = given_errors
            .iter()
            .zip(&preclipped_errors)
            .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
            .collect();
        if both.len() < SIZE * SIZE / 8 {
            return Err(Error::new(
                ErrorKind::Gl,
                "a near-clipped ground plane covered less than an eighth of its tile: the \
                 rasterizer drew something else than the probe's triangles",
            ));
        }
        for (a, b) in both {
            worst_given = worst_given.max(a);
            worst_preclipped = worst_preclipped.max(b);
        }
    }
    let clip = if worst_given <= 2.0 * worst_preclipped + 2.0 {
        NearClip::PlanePreserving
    } else {
        NearClip::ClippedF32
    };
    Ok((clip, worst_given, worst_preclipped, clip_ulps))
}

/// The clipper's error on one ground drawn as given, in the model's own units
/// ([`RasterizerProfile::clip_ulps`]): the largest `(|stored − exact| − e − q)⁺·d / (½·2⁻²⁴·L(A))`
/// over the pixels, `e` the error at the same pixel of the same ground cut to the frustum in
/// f64 before drawing (`unclipped`: what the rasterizer errs without clipping), `d` the pixel's
/// eye depth, `q` one D24 quantum of conversion, `A` the
/// magnitudes of the ground's clip coordinates for its reach `R` (the largest eye coordinate of
/// its corners: `A = ((|m0| + |m8|)·R, (|m5| + |m9|)·R, |m10|·R + |m14|, R)`), and `L` the
/// ground plane's form on clip coordinates (`|aₓ|·A_x + |a_y|·A_y + A_z + |a₀|·A_w`, `aₓ`, `a_y`,
/// `a₀` its NDC depth plane) — the model's term `C` with `clip_ulps·u` for its `γ`.
fn clipper_ulps(
    view: &View,
    ground: &[[f64; 3]; 3],
    scene: &Scene,
    stored: &[f64],
    unclipped: &[Option<f64>],
) -> f64 {
    let reach = ground.iter().flatten().fold(0.0f64, |a, c| a.max(c.abs()));
    let m = scene.matrix.map(f64::from);
    let a = [
        (m[0].abs() + m[8].abs()) * reach,
        (m[5].abs() + m[9].abs()) * reach,
        m[10].abs() * reach + m[14].abs(),
        reach,
    ];
    let Some(plane) = scene.exact().first().map(Plane::new) else {
        return 0.0;
    };
    // The NDC depth plane z_n = a₀ + aₓ·xₙ + a_y·yₙ, read off the exact plane's window depth
    // (½·z_n + ½) at three tile points: NDC (0, 0), (1, 0) and (0, 1) are tile pixels
    // SIZE/2 and SIZE.
    let half = SIZE as f64 / 2.0;
    let ndc = |x: f64, y: f64| 2.0 * plane.extended(x, y) - 1.0;
    let a0 = ndc(half, half);
    let (ax, ay) = (ndc(2.0 * half, half) - a0, ndc(half, 2.0 * half) - a0);
    let l = a[2] + ax.abs() * a[0] + ay.abs() * a[1] + a0.abs() * a[3];
    let q = Format::Unorm(24).quantum(0.5);
    let unit = 0.5 * l / 16_777_216.0;
    (0..SIZE * SIZE)
        .filter_map(|i| {
            let exact = plane.depth_inside(i % SIZE, i / SIZE)?;
            let own = unclipped[i]? * q;
            let d = view.distance_at_depth(exact);
            Some(((stored[i] - exact).abs() - own - q).max(0.0) * d / unit)
        })
        .fold(0.0, f64::max)
}

/// Per pixel of a tile, `|stored − exact|` in D24 quanta against the first of the scene's
/// triangles that covers it (by [`Plane::depth_inside`]), or `None`.
fn pixel_errors(scene: &Scene, stored: &[f64]) -> Vec<Option<f64>> {
    let planes: Vec<Plane> = scene.exact().iter().map(Plane::new).collect();
    let q = Format::Unorm(24).quantum(0.5);
    (0..SIZE * SIZE)
        .map(|i| {
            let exact = planes
                .iter()
                .find_map(|p| p.depth_inside(i % SIZE, i / SIZE))?;
            Some((stored[i] - exact).abs() / q)
        })
        .collect()
}

/// Planes in random directions for [`near_clip`]'s clipper figure: slopes 0.3, 1, 3 and 10 in
/// random directions, crossing the view axis 1 to 40 units ahead, each a triangle holding the
/// disc of radius 100 times that distance around the axis point (so it runs behind the camera).
fn random_clipped_grounds() -> Vec<[[f64; 3]; 3]> {
    let mut state: u64 = 0x0C11_2026_1126;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..48)
        .map(|i| {
            let slope = [0.3, 1.0, 3.0, 10.0][i % 4];
            let angle = std::f64::consts::TAU * next();
            let (sx, sy) = (slope * angle.cos(), slope * angle.sin());
            let d = 10f64.powf(1.6 * next());
            let reach = 100.0 * d;
            let on = |x: f64, y: f64| [x, y, -d + sx * x + sy * y];
            [
                on(-1.8 * reach, reach),
                on(1.8 * reach, reach),
                on(0.0, -2.0 * reach),
            ]
        })
        .collect()
}

/// The near-clip view's sides `(l, r, b, t)` on its near plane (n = 0.1, f = 1000).
const CENTRED_NEAR_SIDES: [f64; 4] = [-0.1, 0.1, -0.05625, 0.05625];

/// Off-centre sides with the near-clip view's `n` and `f`: the view axis on screen, off its
/// centre, and the view axis off the screen.
const SKEWED_NEAR_SIDES: [[f64; 4]; 2] = [
    [-0.04, 0.13, -0.067, 0.034],
    [0.015, 0.16, 0.006, 0.062],
];

/// `glFrustum(l, r, b, t, 0.1, 1000)` in f64, each element rounded to f32 (column-major).
fn near_view_matrix([l, r, b, t]: [f64; 4]) -> [f32; 16] {
    let (n, f) = (NEAR_VIEW.n, NEAR_VIEW.f);
    [
        2.0 * n / (r - l),
        0.0,
        0.0,
        0.0,
        0.0,
        2.0 * n / (t - b),
        0.0,
        0.0,
        (r + l) / (r - l),
        (t + b) / (t - b),
        -(f + n) / (f - n),
        -1.0,
        0.0,
        0.0,
        -2.0 * f * n / (f - n),
        0.0,
    ]
    .map(|x| x as f32)
}

/// The part of eye-space triangle `t` inside the frustum of `sides` (n = 0.1, f = 1000), cut
/// in f64 by [`crate::recommend::clip_to_frustum`], as a fan of triangles.
fn cut_to_frustum(t: [[f64; 3]; 3], [l, r, b, tp]: [f64; 4]) -> Vec<[[f64; 3]; 3]> {
    let Ok(frustum) = crate::projection::Frustum::new(l, r, b, tp, NEAR_VIEW.n, NEAR_VIEW.f) else {
        return Vec::new();
    };
    let polygon = crate::recommend::clip_to_frustum(&frustum, &t).unwrap_or_default();
    (2..polygon.len())
        .map(|i| [polygon[0], polygon[i - 1], polygon[i]])
        .collect()
}

/// The near-clip scenes' view: `glFrustum(−0.1, 0.1, −0.05625, 0.05625, 0.1, 1000)` (16:9).
const NEAR_VIEW: View = View {
    e: 1.0,
    n: 0.1,
    f: 1000.0,
    reversed: false,
    squash: 0.5625,
};

/// Ground planes whose triangles reach 1000 (or 10⁴) units behind and ahead of the camera, as
/// eye-space corners: sloped ones seen from 10 units, and floors 1.7 units below the eye seen
/// level and pitched down, turned about the vertical.
fn near_grounds() -> Vec<[[f64; 3]; 3]> {
    let mut out = Vec::new();
    for slope in [-0.5, 1.0, 3.0] {
        let on = |x: f64, y: f64| [x, y, -10.0 + slope * y];
        // the corner ahead of the camera is where the plane runs away from it
        let ahead = if slope < 0.0 { 1000.0 } else { -1000.0 };
        out.push([on(-1000.0, -ahead), on(1000.0, -ahead), on(0.0, ahead)]);
    }
    // Floors 1.7 units below the eye, seen level and pitched down, turned about the vertical,
    // reaching 1000 and 10⁴ units: the ground engines draw.
    for (reach, yaw, pitch) in [
        (1000.0f64, 0.0f64, 0.0f64),
        (1000.0, 0.3, 0.05),
        (1000.0, 0.9, 0.2),
        (1000.0, 1.3, 0.6),
        (10000.0, 0.2, 0.02),
        (10000.0, 0.7, 0.35),
    ] {
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        // World (x, −1.7, z) turned by yaw about y, then pitched down about x.
        let eye = |x: f64, z: f64| {
            let (x, z) = (cy * x + sy * z, -sy * x + cy * z);
            let y = -1.7;
            [x, cp * y - sp * z, sp * y + cp * z]
        };
        // A triangle around the camera holding the disc of radius `reach` (ahead, whatever yaw).
        out.push([
            eye(-1.8 * reach, reach),
            eye(1.8 * reach, reach),
            eye(0.0, -2.0 * reach),
        ]);
    }
    out
}

/// The part of eye-space triangle `t` beyond the plane `z = −depth`, in f64 (one
/// Sutherland–Hodgman pass), as a fan of triangles.
fn clip_in_f64(t: [[f64; 3]; 3], depth: f64) -> Vec<[[f64; 3]; 3]> {
    let inside = |p: &[f64; 3]| -p[2] >= depth;
    let mut polygon = Vec::new();
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        if inside(&a) {
            polygon.push(a);
        }
        if inside(&a) != inside(&b) {
            let s = (-depth - a[2]) / (b[2] - a[2]);
            polygon.push(std::array::from_fn(|k| a[k] + s * (b[k] - a[k])));
        }
    }
    (2..polygon.len())
        .map(|i| [polygon[0], polygon[i - 1], polygon[i]])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle with w = 1 (no perspective): window depth is the screen-space barycentric
    /// blend of the vertices' depths, computed here independently of [`Plane`].
    #[test]
    fn plane_depth_matches_screen_space_barycentrics_without_perspective() {
        let t: Triangle = [
            [-0.8, -0.7, -0.5, 1.0],
            [0.9, -0.6, 0.25, 1.0],
            [-0.1, 0.85, 0.75, 1.0],
        ];
        let plane = Plane::new(&Scene::clip(vec![t]).exact()[0]);
        let window = |v: [f32; 4]| {
            let s = SIZE as f64;
            (
                (v[0] as f64 + 1.0) * s / 2.0,
                (v[1] as f64 + 1.0) * s / 2.0,
                0.5 * v[2] as f64 + 0.5,
            )
        };
        let [a, b, c] = t.map(window);
        let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
        let (x, y) = (30.5, 20.5);
        let la = ((b.0 - x) * (c.1 - y) - (c.0 - x) * (b.1 - y)) / area;
        let lb = ((c.0 - x) * (a.1 - y) - (a.0 - x) * (c.1 - y)) / area;
        let lc = 1.0 - la - lb;
        let expected = la * a.2 + lb * b.2 + lc * c.2;
        let got = plane.depth_at(x, y).unwrap();
        assert!((got - expected).abs() < 1e-14, "{got} vs {expected}");
        assert!(
            plane.depth_at(0.5, 63.5).is_none(),
            "a corner outside the triangle"
        );
    }

    /// With perspective, the depth at a pixel is that of the eye point on the triangle's plane
    /// seen there: found here by intersecting the pixel's ray with the eye-space plane.
    #[test]
    fn plane_depth_matches_the_ray_through_the_pixel() {
        let view = View {
            e: 0.5,
            n: 1.0,
            f: 100.0,
            reversed: false,
            squash: 1.0,
        };
        let eye = [[-3.0, -2.0, -8.0], [4.0, -1.0, -20.0], [0.5, 3.0, -12.0]];
        let scene = Scene {
            matrix: view.matrix(),
            triangles: vec![View::triangle(eye)],
        };
        let plane = Plane::new(&scene.exact()[0]);
        // the eye-space plane through the (f32-rounded) corners
        let p = eye.map(|v| v.map(|c| c as f32 as f64));
        let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let v = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
        let normal = cross(u, v);
        let (x, y) = (33.5, 31.5);
        let (xn, yn) = (2.0 * x / SIZE as f64 - 1.0, 2.0 * y / SIZE as f64 - 1.0);
        let ray = [xn * view.e, yn * view.e, -1.0]; // the eye point at distance d is d·ray
        let d = (normal[0] * p[0][0] + normal[1] * p[0][1] + normal[2] * p[0][2])
            / (normal[0] * ray[0] + normal[1] * ray[1] + normal[2] * ray[2]);
        let (n, f) = (view.n, view.f);
        let expected = f * (d - n) / (d * (f - n));
        let got = plane.depth_at(x, y).unwrap();
        // the matrix is f32-rounded: agreement to a few f32 ulps, not to f64
        assert!((got - expected).abs() < 1e-6, "{got} vs {expected}");
    }

    #[test]
    fn clipping_in_f64_keeps_the_part_beyond_the_plane() {
        let t = [
            [-1000.0, -1000.0, 490.0],
            [1000.0, -1000.0, 490.0],
            [0.0, 1000.0, -510.0],
        ];
        let fan = clip_in_f64(t, 0.2);
        assert_eq!(fan.len(), 1, "one vertex in front: a triangle");
        for v in fan.iter().flatten() {
            assert!(-v[2] >= 0.2 - 1e-12, "{v:?} in front of the clip plane");
            assert!(
                (v[2] - (-10.0 - 0.5 * v[1])).abs() < 1e-9,
                "{v:?} off the plane"
            );
        }
    }

    #[test]
    fn snapping_hypotheses_round_window_positions() {
        let t: Triangle = [
            [0.30, -0.25, 0.0, 1.0],
            [0.5, 0.5, 0.0, 1.0],
            [-0.5, 0.5, 0.0, 1.0],
        ];
        assert_eq!(snap(&t, 0), t.map(|v| v.map(f64::from)));
        // b = 0, nearest: window x = (0.3 + 1)·32 = 41.6 → 42; down: 41
        let window_x = |t: ClipTriangle| (t[0][0] + 1.0) * SIZE as f64 / 2.0;
        assert_eq!(window_x(snap(&t, 1)), 42.0);
        assert_eq!(window_x(snap(&t, 2)), 41.0);
        // b = 2: quarter pixels, 41.6 → 41.5 (nearest), 41.5 (down)
        assert_eq!(window_x(snap(&t, 5)), 41.5);
        assert_eq!(window_x(snap(&t, 6)), 41.5);
    }
}

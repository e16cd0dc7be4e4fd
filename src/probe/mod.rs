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
//!   one) 384 more planes are drawn, in random directions and frusta (f/n 10² to 10⁹, slopes
//!   0.3 to 10; 128 of them through off-centre frusta, the view axis up to 1.3 half-extents off
//!   the screen's centre): the model takes this figure for its per-quad error `T + I`, and a
//!   maximum of roundings grows with the planes it is taken over (48 planes: 1.40 on llvmpipe;
//!   432: 1.54). The same D32F planes under `glClipControl`'s `[0, 1]`, divided by
//!   `2⁻²⁴·(2 + M)`, enter the same figure (1.17 on llvmpipe: the model takes the larger).
//!   **`error_ulps_reversed`**: the same under reversed Z on D32F, divided by
//!   `2⁻²⁴·(|m10| + M)` (4.29 on llvmpipe; 3.15 before the off-centre planes were drawn).
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
//!   (0.5006 and 0.5012 pixel on llvmpipe). **`outline_neighbour`**: 16 triangles under
//!   `glPolygonMode(GL_LINE)`, each with a long side of constant depth and its gradient across
//!   it; the largest `|stored − side's depth| / max(|gₓ|, |g_y|)` over outline fragments beyond
//!   that side, outside the triangle (where a neighbouring face lies): near 0 where the outline
//!   takes its line's depth, as on llvmpipe. **`offset_slope`**: `glPolygonOffset(1, 0)` on a plane
//!   with `|gₓ| = |g_y|`, over the gradient (1: GL's `max` rule; √2: a root sum of squares). One
//!   draw batch and one read-back, about 2 ms. **`line_reach_msaa`**: the same lines and
//!   outlines drawn into a 4× multisampled `GL_DEPTH_COMPONENT32F` texture (and at the context's
//!   largest count up to 16 where larger); each sample copied out (`texelFetch` written as
//!   `gl_FragDepth` into the probe's D32F renderbuffer) and compared with the plane at its
//!   `glGetMultisamplefv` position: the largest `|stored − plane| / max(|gₓ|, |g_y|)` (1.056 and
//!   1.054 on llvmpipe); NaN where no multisampled depth texture can be attached. **`line_reach_wide`**:
//!   the same geometry, 16 of each per tile, single-sampled at `glLineWidth(3)` against the plane
//!   at the pixel centre (1.5006 and 1.5007 on llvmpipe); NaN where the context refuses the width.
//! * **`near_clip`** ([`NearClip`]): four ground planes (sloped, and a floor) whose triangles
//!   reach 1000 units behind and ahead of the camera (n = 0.1, f = 1000, 16:9), on D24. Each is
//!   drawn as given — the rasterizer clips it at the near plane — and again clipped by the probe
//!   in f64 at twice the near distance, so that nothing is left to clip; each image is compared
//!   with its exact (f64) plane, on the pixels both cover. A clipper that
//!   keeps the plane errs as little as the unclipped drawing (within twice its error plus 2
//!   quanta: [`NearClip::PlanePreserving`]); one that computes the new vertices in f32 errs by
//!   tens of quanta more ([`NearClip::ClippedF32`], the worst case the model must bound).
//!   **`clip_ulps`**: the clipper's excess error in the model's units, on those grounds and 48
//!   planes in random directions through three frusta, under `[−1, 1]` and (with
//!   `glClipControl`) `[0, 1]` and reversed Z; the largest (0.86 on llvmpipe).
//!
//! # The caller's GL state
//! The probe needs OpenGL 3.2 or later (core or compatibility profile) current on the calling
//! thread, and leaves no trace in it: it first fails if `glGetError` reports an error pending from
//! the caller's own calls (reading it clears it: the error's detail says so), then saves and
//! afterwards restores the draw and read framebuffer bindings, the renderbuffer, program, vertex
//! array, array buffer and pixel-pack buffer bindings, the active texture unit and unit 0's
//! `GL_TEXTURE_2D_MULTISAMPLE` binding, every viewport and depth range (all of
//! them under `ARB_viewport_array`), the depth function, write mask and clear value, polygon
//! offset factor, units and clamp, polygon mode, line width, the enables it touches (depth test,
//! polygon offset fill and line, cull face, polygon and line smooth, stencil, depth clamp, rasterizer discard, scissor
//! per viewport, multisampling and the sample coverage enables (alpha to coverage and to one,
//! sample coverage, sample mask), every clip distance, depth-bounds test, alpha test in compatibility), every
//! `GL_PACK_*` parameter, `glClipControl` and, in a compatibility context,
//! `GL_DEPTH_SCALE`/`GL_DEPTH_BIAS`. It deletes every object
//! it creates, also on error. Not restored because it never changes them: colour state (its
//! framebuffer has no colour attachment), other textures and units, samplers, stencil values, uniform state of
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
//! loaded the machine, before the multisampled and 3-pixel lines; with them, paired against the
//! build before them on a later machine, the first call 208–238 ms (was 154–170) and later
//! calls 140–163 ms (135–159); the first pays llvmpipe's compilation of a shader variant per depth format
//! and polygon-offset state. The facing measurements read back only the pixel rows they need and
//! the 256 varied planes every other pixel. The profile records its own run time in
//! [`RasterizerProfile::probe_seconds`].

mod dense;
mod draw;
mod facing;
mod gl;
mod lines;
mod msaa_lines;
mod near_clip;
mod plane_error;
mod resolvable;
mod snapping;
mod state;
mod wide_lines;

use std::ffi::{c_void, CStr};
use std::time::Instant;

use crate::depth_chain::DepthChain;
use crate::error::{Error, ErrorKind, Result};
use crate::profile::{NearClip, RasterizerProfile, Snapping};
use crate::projection::ClipDepth;
use dense::*;
use draw::*;
use facing::*;
use gl::*;
use lines::*;
use msaa_lines::msaa_line_reach;
use near_clip::*;
use plane_error::*;
use resolvable::*;
use snapping::*;
use wide_lines::wide_line_reach;

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
    /// `[−1, 1]`; [`RasterizerProfile::error_ulps`] is the largest of these and
    /// `error_ulps_zero_to_one`.
    pub error_ulps: [f64; 4],
    /// D32F's worst `|stored − exact| / (2⁻²⁴·(2 + M))` under `glClipControl`'s `[0, 1]` (NaN
    /// without it): the same planes with `glFrustum`'s depth row in its `[0, 1]` form.
    pub error_ulps_zero_to_one: f64,
    /// D32F's worst plane error in units of the f32 spacing at each pixel's own depth (not at
    /// the primitive's largest), under `[−1, 1]` and under reversed Z: what a primitive spanning
    /// several binades does to its smallest depths.
    pub float_local_plane_error: [f64; 2],
    /// How many stored depths of facing planes the chain identification compared.
    pub chain_observations: usize,
    /// Line fragments compared for [`RasterizerProfile::line_reach`] (`GL_LINES`, polygon-mode).
    pub line_pixels: [usize; 2],
    /// Outline fragments compared for [`RasterizerProfile::outline_neighbour`].
    pub outline_neighbour_pixels: usize,
    /// Line samples compared for [`RasterizerProfile::line_reach_msaa`] (`GL_LINES`,
    /// polygon-mode).
    pub msaa_line_samples: [usize; 2],
    /// Samples compared for [`RasterizerProfile::line_reach_msaa_wide_whole`] (`GL_LINES`,
    /// polygon-mode).
    pub msaa_wide_line_samples: [usize; 2],
    /// Line fragments compared for [`RasterizerProfile::line_reach_wide`] (`GL_LINES`,
    /// polygon-mode).
    pub wide_line_pixels: [usize; 2],
    /// The sample counts [`RasterizerProfile::line_reach_msaa`] was drawn at: 4, and the
    /// context's largest up to 16 (0 where not drawn).
    pub msaa_sample_counts: [i32; 2],
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
        error_ulps_zero_to_one: f64::NAN,
        float_local_plane_error: [f64::NAN; 2],
        chain_observations: 0,
        line_pixels: [0; 2],
        outline_neighbour_pixels: 0,
        msaa_line_samples: [0; 2],
        msaa_wide_line_samples: [0; 2],
        wide_line_pixels: [0; 2],
        msaa_sample_counts: [0; 2],
        offset_slope_axis: f64::NAN,
    };
    let mut seen = Vec::new();
    // Snapping first: the plane errors are measured against the plane the rasterizer sets up,
    // through its snapped window positions (what snapping moves is the model's `S`, not `I`).
    attach(gl, o, DEPTH_COMPONENT32F)?;
    let snap;
    (profile.snapping, figures.snapping_residual, snap) = snapping(gl, o, figures.subpixel_bits)?;
    for (slot, internal, format) in Format::ALL {
        attach(gl, o, internal)?;
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
        let errors = plane_error(gl, o, format, ClipDepth::NegOneToOne, snap)?;
        profile.plane_error[slot] = errors.worst;
        figures.plane_pixels[slot] = errors.pixels;
        figures.error_ulps[slot] = errors.error_ulps;
        if format == Format::Float {
            figures.float_local_plane_error[0] = errors.local;
            profile.error_ulps = figures.error_ulps.iter().copied().fold(0.0, f64::max);
            // The model takes one figure for [-1, 1] and [0, 1] (with its own constant, 2 under
            // [0, 1]): the larger of the two conventions'.
            if let Some(zero_to_one) = zero_to_one_plane_error(gl, o, ClipDepth::ZeroToOne, snap)? {
                figures.error_ulps_zero_to_one = zero_to_one.error_ulps;
                profile.error_ulps = profile.error_ulps.max(zero_to_one.error_ulps);
            }
            if let Some(reversed) =
                zero_to_one_plane_error(gl, o, ClipDepth::ReversedZeroToOne, snap)?
            {
                profile.plane_error_reversed = reversed.worst;
                profile.error_ulps_reversed = reversed.error_ulps;
                figures.reversed_pixels = reversed.pixels;
                figures.float_local_plane_error[1] = reversed.local;
            }
        }
        if format == Format::Float {
            let lines = line_reach(gl, o)?;
            profile.line_reach = lines.reach;
            profile.outline_neighbour = lines.neighbour;
            figures.outline_neighbour_pixels = lines.neighbour_pixels;
            profile.offset_slope = lines.slope[0];
            figures.line_pixels = lines.pixels;
            figures.offset_slope_axis = lines.slope[1];
            let wide = wide_line_reach(gl, o)?;
            profile.line_reach_wide = wide.reach;
            figures.wide_line_pixels = wide.samples;
            let msaa = msaa_line_reach(gl, o)?;
            profile.line_reach_msaa = msaa.measured.reach;
            figures.msaa_line_samples = msaa.measured.samples;
            profile.line_reach_msaa_whole = msaa.measured.whole;
            profile.line_reach_msaa_wide_whole = msaa.wide.whole;
            figures.msaa_wide_line_samples = msaa.wide.samples;
            figures.msaa_sample_counts = msaa.counts;
        }
        if internal == DEPTH_COMPONENT24 {
            (
                profile.near_clip,
                figures.near_clip_error,
                figures.near_preclipped_error,
                profile.clip_ulps,
            ) = near_clip(gl, o, profile.snapping)?;
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
    o.program = link(
        gl,
        VERTEX_SHADER,
        FRAGMENT_SHADER,
        "the probe's shaders (GLSL 1.50) did not compile or link",
    )?;
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

/// Compiles `vertex` and `fragment` (NUL-terminated GLSL) and links them, with the vertex
/// attribute `eye` at location 0; `detail` is the error where either fails.
unsafe fn link(gl: &Gl, vertex: &[u8], fragment: &[u8], detail: &'static str) -> Result<Uint> {
    let program = (gl.CreateProgram)();
    let mut ok = 1;
    for (kind, source) in [
        (VERTEX_SHADER_KIND, vertex),
        (FRAGMENT_SHADER_KIND, fragment),
    ] {
        let shader = (gl.CreateShader)(kind);
        let text = source.as_ptr().cast();
        (gl.ShaderSource)(shader, 1, &text, std::ptr::null());
        (gl.CompileShader)(shader);
        let mut compiled = 0;
        (gl.GetShaderiv)(shader, COMPILE_STATUS, &mut compiled);
        (gl.AttachShader)(program, shader);
        (gl.DeleteShader)(shader);
        ok &= compiled;
    }
    if ok != 0 {
        (gl.BindAttribLocation)(program, 0, c"eye".as_ptr());
        (gl.LinkProgram)(program);
        (gl.GetProgramiv)(program, LINK_STATUS, &mut ok);
    }
    if ok == 0 {
        (gl.DeleteProgram)(program);
        return Err(Error::new(ErrorKind::Gl, detail));
    }
    Ok(program)
}

const VERTEX_SHADER_KIND: Enum = gl::VERTEX_SHADER;
const FRAGMENT_SHADER_KIND: Enum = gl::FRAGMENT_SHADER;
const ALWAYS: Enum = 0x0207;
const DEPTH_BUFFER_BIT: u32 = 0x0100;

/// Gives the renderbuffer `internal` storage and attaches it; an error naming the format if the
/// framebuffer is then incomplete (or the format refused).
unsafe fn attach(gl: &Gl, o: &Objects, internal: Enum) -> Result<()> {
    (gl.BindRenderbuffer)(RENDERBUFFER, o.renderbuffer);
    let side = (SIZE * TILES) as Sizei;
    (gl.RenderbufferStorage)(RENDERBUFFER, internal, side, side);
    let refused = gl.failed();
    (gl.FramebufferRenderbuffer)(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, o.renderbuffer);
    let complete = (gl.CheckFramebufferStatus)(FRAMEBUFFER) == FRAMEBUFFER_COMPLETE;
    gl.check("attaching the probe's depth renderbuffer raised a GL error")?;
    if complete && !refused {
        Ok(())
    } else {
        Err(Error::new(ErrorKind::Gl, incomplete_detail(internal)))
    }
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
        let t: ClipTriangle = [
            [0.30, -0.25, 0.0, 1.0],
            [0.5, 0.5, 0.0, 1.0],
            [-0.5, 0.5, 0.0, 1.0],
        ];
        assert_eq!(snap(&t, 0), t);
        // b = 0, nearest: window x = (0.3 + 1)·32 = 41.6 → 42; down: 41
        let window_x = |t: ClipTriangle| (t[0][0] + 1.0) * SIZE as f64 / 2.0;
        assert_eq!(window_x(snap(&t, 1)), 42.0);
        assert_eq!(window_x(snap(&t, 2)), 41.0);
        // b = 2: quarter pixels, 41.6 → 41.5 (nearest), 41.5 (down)
        assert_eq!(window_x(snap(&t, 5)), 41.5);
        assert_eq!(window_x(snap(&t, 6)), 41.5);
        // The same vertex with w = 2 (clip x 0.6): its window position snaps the same way.
        let w2 = t.map(|v| v.map(|c| 2.0 * c));
        let snapped = snap(&w2, 1);
        assert_eq!(snapped[0][3], 2.0);
        assert!((window_x(snapped.map(|v| v.map(|c| c / 2.0))) - 42.0).abs() < 1e-12);
    }
}

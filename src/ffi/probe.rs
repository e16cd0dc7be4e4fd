//! The rasterizer probe (src/probe/): the C profile record, `zshift_probe` and
//! `zshift_profile_worst_case`.

use std::ffi::{c_char, c_void, CStr};

use super::{checked, null_pointer, ZshiftStatus};
use crate::domain::domain;
use crate::error::Result;
use crate::profile::{NearClip, RasterizerProfile, Snapping};

/// `near_clip` value: a primitive crossing the near plane is clipped with new vertices computed
/// in float, and its depth plane set up from them (the worst case; Mesa llvmpipe).
pub const ZSHIFT_NEAR_CLIP_CLIPPED_F32: i32 = 1;

/// `near_clip` value: a primitive crossing the near plane keeps its plane's depth to within the
/// per-pixel error of one that does not (measured: ground planes clipped by the rasterizer err
/// at most twice, plus 2 D24 quanta, what they do when clipped in double before drawing).
pub const ZSHIFT_NEAR_CLIP_PLANE_PRESERVING: i32 = 2;

/// What a rasterizer does that the offset model needs to know, as `zshift_probe` measures it
/// or `zshift_profile_worst_case` assumes it. Plain data: copy it, store it, pass it to the
/// recommendation.
///
/// Arrays indexed by depth format are in the order D16, D24, D32, D32F
/// (GL_DEPTH_COMPONENT16, 24, 32, 32F).
///
/// A zero-filled record is refused (ZSHIFT_ERR_DOMAIN, `near_clip` 0 is no valid value): fill it
/// with `zshift_probe` or `zshift_profile_worst_case`, then adjust fields if you know better.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftProfile {
    /// Nonzero when `zshift_probe` measured this profile; 0 for the worst case.
    pub measured: u32,
    /// How depth setup treats vertex positions: ZSHIFT_SUBPIXEL_UNSNAPPED (-1) when the depth
    /// plane is set up from unsnapped float positions, else the sub-pixel bits b (0..=16) the
    /// positions are snapped to (2^-b pixel) first. The worst case is 8.
    pub subpixel_bits: i32,
    /// glPolygonOffset's minimum resolvable difference r per format, in units of the format's
    /// quantum: 1/(2^m - 1) for D16/D24/D32, 2^(e - 23) for D32F (e the exponent of the
    /// primitive's largest depth). Finite and > 0. The worst case is 1 (the smallest r known, so
    /// the recommendation's polygon_offset_units suffice on every implementation).
    pub resolvable: [f64; 4],
    /// The largest |stored - exact| window depth of a pixel of a sloped plane, per format, in
    /// units of the format's quantum (for D32F, of 2^-24), under the [-1, 1] mapping; NAN where
    /// not measured (the model's bound applies). Planes drawn as an engine draws them (f32
    /// vertices times an f32 projection in the vertex shader), against the plane through the
    /// vertices times the matrix in double: covers the f32 transform, division by w, viewport
    /// transform, depth setup, interpolation and conversion to the format. NAN or finite >= 0.
    pub plane_error: [f64; 4],
    /// plane_error of D32F under reversed Z (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE),
    /// window depth n(f - d)/((f - n)d)), in units of the float spacing 2^(e - 23) at the
    /// primitive's largest window depth; NAN where not measured. NAN or finite >= 0.
    pub plane_error_reversed: f64,
    /// How the per-pixel error grows with a steep plane's window position: every measured pixel
    /// kept |stored - exact| <= c + error_ulps * 2^-24 * (1 + M), where c is 1 quantum for
    /// D16/D24/D32 and 0 for D32F, and M = |w0| + |dw/dx| * x + |dw/dy| * y (w0 the plane's
    /// window depth extrapolated to window (0, 0), x, y the pixel's window coordinates). NAN
    /// where not measured. NAN or finite >= 0.
    pub error_ulps: f64,
    /// How a primitive crossing the near plane is clipped: ZSHIFT_NEAR_CLIP_CLIPPED_F32 or
    /// ZSHIFT_NEAR_CLIP_PLANE_PRESERVING.
    pub near_clip: i32,
    /// Seconds `zshift_probe` took (0 for the worst case). Informational.
    pub probe_seconds: f64,
    /// The window-depth offset, per format, in quanta (D32F: in units of 2^-24), that a decal
    /// facing the camera needs to pass GL_LESS over its base when
    /// every corner of both has the same float z and the matrices differ only in element 10:
    /// the largest over 256 depths under [-1, 1]. Used for such scenes (exact_depth, strict
    /// test, [-1, 1]) in place of the bound q + 2T. NAN where not measured (the worst case).
    /// NAN or finite >= 0.
    pub facing_quanta: [f64; 4],
    /// facing_quanta under [0, 1] depth (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), standard,
    /// not reversed), used for such scenes under ZSHIFT_CLIP_ZERO_TO_ONE. NAN where not measured.
    /// NAN or finite >= 0.
    pub facing_quanta_zero_to_one: [f64; 4],
    /// Under reversed Z on D32F (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), GL_GREATER): the
    /// relative epsilon (element 14 scaled by 1 + epsilon), in units of 2^-24, that a facing
    /// decal sharing its base's float z needs; used for such scenes under
    /// ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE with D32F. NAN where not measured. NAN or finite >= 0.
    pub facing_reversed: f64,
    /// error_ulps under reversed Z on D32F: every measured pixel kept |computed - exact| <=
    /// error_ulps_reversed * 2^-24 * (|m10| + M), |m10| = n/(f - n). NAN where not measured.
    /// NAN or finite >= 0.
    pub error_ulps_reversed: f64,
    /// The f32 arithmetic from a facing vertex's eye depth to its stored value that the probe
    /// identified (it reproduced every stored depth of the probe's facing planes bit for bit), as
    /// a code 0..=23, or -1: none identified (the worst case). With it a facing decal sharing its
    /// base's float z gets exactly the offset it needs (exact_depth, strict test).
    pub facing_chain: i32,
    /// Under ZSHIFT_NEAR_CLIP_CLIPPED_F32: the clipper's measured error in units of 2^-24 of the
    /// magnitudes of a clipped base's clip coordinates, measured on ground planes reaching 1000
    /// and 10^4 units behind and ahead of the camera and on random planes, under every depth
    /// convention the context has (0.86 on llvmpipe). The model's term C takes 4 times it in
    /// place of its bound 36 (six clip stages of f32 rounding) where smaller: a sampled maximum,
    /// with a margin. NAN where not measured. NAN or finite >= 0.
    pub clip_ulps: f64,
    /// How far from the pixel a 1-pixel line fragment takes its depth, in pixels along the face's
    /// steepest window-depth gradient: the largest |stored - plane at the pixel centre| /
    /// max(|dz/dx|, |dz/dy|) over lines drawn in sloped planes, for GL_LINES of width 1 ([0])
    /// and for triangles drawn under glPolygonMode(GL_LINE) ([1]), single-sampled. The edge
    /// offsets (zshift_edge_offset) take it for their line reach (worst case (w + 1)/2); wider
    /// lines add (w - 1)/2. NAN where not measured. NAN or finite >= 0.
    pub line_reach: [f64; 2],
    /// How far a polygon-mode outline takes its depth off its side's line, onto the
    /// neighbouring face, in pixels of the triangle's max(|dz/dx|, |dz/dy|): the largest
    /// |stored - side's depth| over 1-pixel outline fragments beyond a side of constant depth,
    /// outside its triangle. Near 0 where the outline's depth follows its line (llvmpipe);
    /// zshift_edge_offset then leaves out the neighbour's slope term for polygon-mode lines.
    /// NAN where not measured (the term is kept). NAN or finite >= 0.
    pub outline_neighbour: f64,
    /// How far from a sample a multisampled 1-pixel line's sample takes its depth, in pixels of
    /// max(|dz/dx|, |dz/dy|): the largest |stored - plane at the sample| over every sample of
    /// lines drawn into a multisampled depth texture, at 4 samples and at the context's largest
    /// count up to 16; GL_LINES [0], polygon-mode lines [1]. zshift_edge_offset takes it for its
    /// line reach under MSAA (worst case sqrt(2)*(w + 1)/2); wider lines add sqrt(2)*(w - 1)/2.
    /// llvmpipe: 1.056 and 1.054. NAN where not measured. NAN or finite >= 0.
    pub line_reach_msaa: [f64; 2],
    /// How far from the pixel a 3-pixel line fragment takes its depth, in pixels of
    /// max(|dz/dx|, |dz/dy|): the largest |stored - plane at the pixel centre| over lines drawn
    /// single-sampled at glLineWidth(3); GL_LINES [0], polygon-mode lines [1].
    /// zshift_edge_offset takes the polygon-mode figure for wide outlines (worst case
    /// (w + 1)/2 + 1/8); wider lines add (w - 3)/2. llvmpipe: 1.5006 and 1.5007. NAN where not
    /// measured (a forward-compatible core context refuses the width). NAN or finite >= 0.
    pub line_reach_wide: [f64; 2],
    /// glPolygonOffset's slope rule: the offset of glPolygonOffset(1, 0) on a plane with
    /// |dz/dx| = |dz/dy| = g, over g: 1 for max(|dz/dx|, |dz/dy|) (GL's rule), 1.414 for their
    /// root sum of squares (allowed by Vulkan and Direct3D). The edge offsets' hidden-line gap
    /// multiplies a face's push by it (worst case sqrt(2)). NAN where not measured. NAN or
    /// finite >= 0.
    pub offset_slope: f64,
    /// How far, in any direction, a multisampled 1-pixel line's sample is from the point whose
    /// depth it takes: the largest |stored - plane at the sample| / |grad z| (the whole
    /// gradient) over the line_reach_msaa samples; GL_LINES [0], polygon-mode lines [1].
    /// zshift_edge_offset takes it against a face_angle or a mesh's own faces for 1-pixel lines
    /// (worst case (w + 1)/2 = 1; wider lines take line_reach_msaa_wide_whole). llvmpipe: 0.865
    /// and 0.866. NAN where not measured. NAN or finite >= 0.
    pub line_reach_msaa_whole: [f64; 2],
    /// The same at glLineWidth(3): how far, in any direction, a multisampled 3-pixel line's
    /// sample is from the point whose depth it takes, pixels of |grad z|; GL_LINES [0],
    /// polygon-mode lines [1]. zshift_edge_offset takes it against a face_angle or a mesh's own
    /// faces for multisampled lines wider than 1 (worst case (w + 1)/2 = 2 at width 3), adding
    /// (w - 3)/2 beyond width 3. llvmpipe: 1.656 and 1.652. NAN where not measured. NAN or
    /// finite >= 0.
    pub line_reach_msaa_wide_whole: [f64; 2],
}

/// A GL entry point as a loader returns it (as glad's GLADapiproc and GLFW's GLFWglproc): a
/// function pointer, cast to its real type by the caller, or NULL.
pub type ZshiftGlProc = Option<unsafe extern "C" fn()>;

/// A GL function loader: returns the GL entry point `name` (a NUL-terminated string such as
/// "glReadPixels") of the context current on this thread, or NULL. `user` is passed through
/// unchanged. eglGetProcAddress and glfwGetProcAddress return this type already (wrap them to
/// add the `user` argument); wrap SDL_GL_GetProcAddress or wglGetProcAddress likewise.
pub type ZshiftGlLoader =
    Option<unsafe extern "C" fn(name: *const c_char, user: *mut c_void) -> ZshiftGlProc>;

impl From<RasterizerProfile> for ZshiftProfile {
    fn from(p: RasterizerProfile) -> Self {
        ZshiftProfile {
            measured: p.measured as u32,
            subpixel_bits: match p.snapping {
                Snapping::Unsnapped => super::ZSHIFT_SUBPIXEL_UNSNAPPED,
                Snapping::SubpixelBits(b) => b as i32,
            },
            resolvable: p.resolvable,
            plane_error: p.plane_error,
            plane_error_reversed: p.plane_error_reversed,
            error_ulps: p.error_ulps,
            facing_quanta: p.facing_quanta,
            facing_quanta_zero_to_one: p.facing_quanta_zero_to_one,
            facing_reversed: p.facing_reversed,
            error_ulps_reversed: p.error_ulps_reversed,
            facing_chain: p.facing_chain.map_or(-1, |c| c.code()),
            clip_ulps: p.clip_ulps,
            line_reach: p.line_reach,
            outline_neighbour: p.outline_neighbour,
            line_reach_msaa: p.line_reach_msaa,
            line_reach_wide: p.line_reach_wide,
            offset_slope: p.offset_slope,
            line_reach_msaa_whole: p.line_reach_msaa_whole,
            line_reach_msaa_wide_whole: p.line_reach_msaa_wide_whole,
            near_clip: match p.near_clip {
                NearClip::ClippedF32 => ZSHIFT_NEAR_CLIP_CLIPPED_F32,
                NearClip::PlanePreserving => ZSHIFT_NEAR_CLIP_PLANE_PRESERVING,
            },
            probe_seconds: p.probe_seconds,
        }
    }
}

impl ZshiftProfile {
    /// The Rust profile this record describes, every field validated (for the recommendation's
    /// entry points).
    ///
    /// # Errors
    /// [`crate::ErrorKind::Domain`] naming the first invalid field: `near_clip` not one of the
    /// ZSHIFT_NEAR_CLIP_* values (a zero-filled record), `subpixel_bits` outside -1..=16, a
    /// `resolvable` entry not finite and positive, a `plane_error` entry negative or infinite.
    pub fn to_profile(&self) -> Result<RasterizerProfile> {
        let near_clip = match self.near_clip {
            ZSHIFT_NEAR_CLIP_CLIPPED_F32 => NearClip::ClippedF32,
            ZSHIFT_NEAR_CLIP_PLANE_PRESERVING => NearClip::PlanePreserving,
            _ => {
                return Err(domain(
                    "ZshiftProfile.near_clip is not a ZSHIFT_NEAR_CLIP_* value (a zero-filled \
                     profile?): fill it with zshift_probe or zshift_profile_worst_case",
                ))
            }
        };
        let snapping = match self.subpixel_bits {
            -1 => Snapping::Unsnapped,
            b @ 0..=16 => Snapping::SubpixelBits(b as u32),
            _ => return Err(domain("ZshiftProfile.subpixel_bits is outside -1..=16")),
        };
        if self.resolvable.iter().any(|r| !(r.is_finite() && *r > 0.0)) {
            return Err(domain(
                "a ZshiftProfile.resolvable entry is not finite and > 0",
            ));
        }
        let errors = [
            self.plane_error_reversed,
            self.error_ulps,
            self.facing_reversed,
            self.error_ulps_reversed,
            self.clip_ulps,
            self.line_reach[0],
            self.line_reach[1],
            self.outline_neighbour,
            self.line_reach_msaa[0],
            self.line_reach_msaa[1],
            self.line_reach_wide[0],
            self.line_reach_wide[1],
            self.offset_slope,
            self.line_reach_msaa_whole[0],
            self.line_reach_msaa_whole[1],
            self.line_reach_msaa_wide_whole[0],
            self.line_reach_msaa_wide_whole[1],
        ];
        if self
            .plane_error
            .iter()
            .chain(&errors)
            .chain(&self.facing_quanta)
            .chain(&self.facing_quanta_zero_to_one)
            .any(|e| *e < 0.0 || e.is_infinite())
        {
            return Err(domain(
                "ZshiftProfile.plane_error, plane_error_reversed, error_ulps, error_ulps_reversed, clip_ulps, line_reach, outline_neighbour, line_reach_msaa, line_reach_wide, offset_slope, line_reach_msaa_whole, line_reach_msaa_wide_whole or a facing figure is negative \
                 or infinite \
                 (NAN means not measured)",
            ));
        }
        Ok(RasterizerProfile {
            snapping,
            resolvable: self.resolvable,
            plane_error: self.plane_error,
            plane_error_reversed: self.plane_error_reversed,
            error_ulps: self.error_ulps,
            facing_quanta: self.facing_quanta,
            facing_quanta_zero_to_one: self.facing_quanta_zero_to_one,
            facing_reversed: self.facing_reversed,
            error_ulps_reversed: self.error_ulps_reversed,
            facing_chain: match self.facing_chain {
                -1 => None,
                code => Some(
                    crate::depth_chain::DepthChain::from_code(code).ok_or_else(|| {
                        domain("ZshiftProfile.facing_chain must be -1 or a code in 0..=23")
                            .with_integer("facing_chain", i64::from(code))
                    })?,
                ),
            },
            near_clip,
            clip_ulps: self.clip_ulps,
            line_reach: self.line_reach,
            outline_neighbour: self.outline_neighbour,
            line_reach_msaa: self.line_reach_msaa,
            line_reach_wide: self.line_reach_wide,
            line_reach_msaa_whole: self.line_reach_msaa_whole,
            line_reach_msaa_wide_whole: self.line_reach_msaa_wide_whole,
            offset_slope: self.offset_slope,
            measured: self.measured != 0,
            probe_seconds: if self.probe_seconds.is_finite() {
                self.probe_seconds
            } else {
                0.0
            },
        })
    }
}

/// Writes the worst-case profile to `out`: the recommendation's default assumptions (8
/// sub-pixel bits, r = 1 quantum, per-pixel errors as the model bounds them, near-plane clipping
/// in float), `measured` = 0.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `out` is NULL.
#[no_mangle]
pub extern "C" fn zshift_profile_worst_case(out: *mut ZshiftProfile) -> ZshiftStatus {
    checked(
        out,
        || Ok(ZshiftProfile::from(RasterizerProfile::worst_case())),
        write,
    )
}

/// Measures the rasterizer of the OpenGL context current on the calling thread and writes its
/// profile to `out` (see `ZshiftProfile`). Draws about 250 triangles into a framebuffer of its
/// own (512x512) and reads their depth back: 40-55 ms on Mesa llvmpipe (2 cores). Call it once
/// after making the context current, not per frame.
///
/// GL is reached only through `loader` (called with `user`), never linked. Needs OpenGL 3.2 or
/// later, core or compatibility profile (desktop GL, not GLES). Every GL state it touches is
/// restored and every object it creates deleted, on success and on error; an active transform
/// feedback or query of the caller would see its draws (end them first).
///
/// Errors: ZSHIFT_ERR_NULL_POINTER if `loader` or `out` is NULL; ZSHIFT_ERR_GL if the loader
/// returned NULL for a needed entry point, no context or one older than 3.2 is current, a GL
/// error was pending on entry (it is read, which clears it), D16, D24 or D32F cannot be
/// attached to a framebuffer, or a GL call failed; `zshift_last_error()` names which (e.g.
/// "the GL loader returned NULL for glReadPixels, ..."). `out` is untouched on error.
///
/// # Safety
/// `loader` must return, for each name, NULL or that entry point of the current context.
#[no_mangle]
pub unsafe extern "C" fn zshift_probe(
    loader: ZshiftGlLoader,
    user: *mut c_void,
    out: *mut ZshiftProfile,
) -> ZshiftStatus {
    let Some(loader) = loader else {
        return null_pointer("loader");
    };
    // The user pointer crosses the panic boundary as an address: the probe only passes it back.
    let user = user as usize;
    checked(
        out,
        move || {
            let load = |name: &CStr| -> *const c_void {
                // SAFETY: `name` is NUL-terminated; the caller vouches for the loader.
                let proc = unsafe { loader(name.as_ptr(), user as *mut c_void) };
                proc.map_or(std::ptr::null(), |f| f as *const c_void)
            };
            // SAFETY: the caller promises a current context and a loader for it.
            unsafe { crate::probe::probe(load) }.map(ZshiftProfile::from)
        },
        write,
    )
}

/// Writes the record with `write_unaligned`: `out` needs no alignment.
fn write(out: *mut ZshiftProfile, value: ZshiftProfile) {
    // SAFETY: `checked` has refused NULL; the caller promises a writable ZshiftProfile.
    unsafe { out.write_unaligned(value) }
}

/// The profile a recommendation entry point uses: the caller's `ZshiftProfile` when `profile`
/// is not NULL (validated; it supplies every rasterizer fact, snapping included), else the
/// worst case with `snapping` (from the scene's own `subpixel_bits`).
pub(super) fn profile_or_worst(
    profile: *const ZshiftProfile,
    snapping: Snapping,
) -> Result<RasterizerProfile> {
    if profile.is_null() {
        return Ok(RasterizerProfile {
            snapping,
            ..RasterizerProfile::worst_case()
        });
    }
    // SAFETY: not NULL; the caller promises a readable ZshiftProfile; read_unaligned needs no
    // alignment and the struct is plain data.
    unsafe { profile.read_unaligned() }.to_profile()
}

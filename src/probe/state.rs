//! Every piece of GL state the probe changes, saved before it draws and put back afterwards, so
//! the engine's context is as it was (see [`super`]'s docs for the list and its limits).

use super::gl::*;

/// One capability's `glIsEnabled` value.
struct Capability {
    cap: Enum,
    on: bool,
}

/// The caller's state, as read before the probe changes anything.
pub struct Saved {
    draw_framebuffer: Int,
    read_framebuffer: Int,
    renderbuffer: Int,
    program: Int,
    vertex_array: Int,
    array_buffer: Int,
    pixel_pack_buffer: Int,
    /// `GL_ACTIVE_TEXTURE`, and unit 0's `GL_TEXTURE_BINDING_2D_MULTISAMPLE` (the multisampled
    /// line measurement binds its depth texture there).
    texture: (Int, Int),
    capabilities: Vec<Capability>,
    /// `(x, y, w, h, near, far, scissor on)` per viewport index (one without viewport arrays).
    viewports: Vec<([f32; 4], [f64; 2], bool)>,
    depth_func: Int,
    depth_mask: Boolean,
    depth_clear: f64,
    polygon_offset: [f32; 3],
    polygon_mode: [Int; 2],
    line_width: f32,
    pack: [(Enum, Int); 8],
    clip_control: Option<[Int; 2]>,
    depth_transfer: Option<[f32; 2]>,
    compatibility: bool,
}

/// Capabilities the probe turns on or off; each is restored as it was.
const CAPABILITIES: [Enum; 15] = [
    POLYGON_SMOOTH,
    LINE_SMOOTH,
    POLYGON_OFFSET_LINE,
    DEPTH_TEST,
    POLYGON_OFFSET_FILL,
    CULL_FACE,
    STENCIL_TEST,
    DEPTH_CLAMP,
    RASTERIZER_DISCARD,
    SCISSOR_TEST,
    // Multisampling (on by default; the multisampled line measurement turns it on for its own
    // draws) and what could drop a sample's coverage there.
    MULTISAMPLE,
    SAMPLE_ALPHA_TO_COVERAGE,
    SAMPLE_ALPHA_TO_ONE,
    SAMPLE_COVERAGE,
    SAMPLE_MASK,
];

const PACK_STATE: [Enum; 8] = [
    PACK_SWAP_BYTES,
    PACK_LSB_FIRST,
    PACK_ROW_LENGTH,
    PACK_SKIP_ROWS,
    PACK_SKIP_PIXELS,
    PACK_ALIGNMENT,
    PACK_SKIP_IMAGES,
    PACK_IMAGE_HEIGHT,
];

impl Saved {
    /// Reads the state. The context must have no pending GL error (the caller checks).
    pub unsafe fn read(gl: &Gl, compatibility: bool) -> Saved {
        let mut capabilities: Vec<Capability> = CAPABILITIES
            .iter()
            .map(|&cap| Capability {
                cap,
                on: (gl.IsEnabled)(cap) != 0,
            })
            .collect();
        if compatibility {
            capabilities.push(Capability {
                cap: ALPHA_TEST,
                on: (gl.IsEnabled)(ALPHA_TEST) != 0,
            });
        }
        // User clip distances (clip planes in compatibility): enabled but not written by the
        // probe's shader, they would clip its triangles by undefined values.
        let clip_distances = gl.integer(MAX_CLIP_DISTANCES).clamp(0, 32) as Enum;
        for cap in (0..clip_distances).map(|i| CLIP_DISTANCE0 + i) {
            capabilities.push(Capability {
                cap,
                on: (gl.IsEnabled)(cap) != 0,
            });
        }
        // GL_DEPTH_BOUNDS_TEST_EXT exists only with its extension (asked first, so that no
        // GL_INVALID_ENUM reaches the engine's debug callback).
        if gl.has_extension(b"GL_EXT_depth_bounds_test") {
            capabilities.push(Capability {
                cap: DEPTH_BOUNDS_TEST_EXT,
                on: (gl.IsEnabled)(DEPTH_BOUNDS_TEST_EXT) != 0,
            });
        }
        let mut polygon_offset = [0.0f32; 3];
        (gl.GetFloatv)(POLYGON_OFFSET_FACTOR, &mut polygon_offset[0]);
        (gl.GetFloatv)(POLYGON_OFFSET_UNITS, &mut polygon_offset[1]);
        if gl.PolygonOffsetClamp.is_some() {
            (gl.GetFloatv)(POLYGON_OFFSET_CLAMP, &mut polygon_offset[2]);
        }
        let mut polygon_mode = [FILL as Int; 2];
        (gl.GetIntegerv)(POLYGON_MODE, polygon_mode.as_mut_ptr());
        let mut line_width = 1.0f32;
        (gl.GetFloatv)(LINE_WIDTH, &mut line_width);
        let mut depth_mask = 1;
        (gl.GetBooleanv)(DEPTH_WRITEMASK, &mut depth_mask);
        let mut depth_clear = 1.0;
        (gl.GetDoublev)(DEPTH_CLEAR_VALUE, &mut depth_clear);
        let clip_control = gl
            .ClipControl
            .map(|_| [gl.integer(CLIP_ORIGIN), gl.integer(CLIP_DEPTH_MODE)]);
        let depth_transfer = if compatibility && gl.PixelTransferf.is_some() {
            let mut v = [1.0f32, 0.0];
            (gl.GetFloatv)(DEPTH_SCALE, &mut v[0]);
            (gl.GetFloatv)(DEPTH_BIAS, &mut v[1]);
            Some(v)
        } else {
            None
        };
        let active = gl.integer(ACTIVE_TEXTURE);
        (gl.ActiveTexture)(TEXTURE0);
        let texture = (active, gl.integer(TEXTURE_BINDING_2D_MULTISAMPLE));
        (gl.ActiveTexture)(active as Enum);
        Saved {
            texture,
            draw_framebuffer: gl.integer(DRAW_FRAMEBUFFER_BINDING),
            read_framebuffer: gl.integer(READ_FRAMEBUFFER_BINDING),
            renderbuffer: gl.integer(RENDERBUFFER_BINDING),
            program: gl.integer(CURRENT_PROGRAM),
            vertex_array: gl.integer(VERTEX_ARRAY_BINDING),
            array_buffer: gl.integer(ARRAY_BUFFER_BINDING),
            pixel_pack_buffer: gl.integer(PIXEL_PACK_BUFFER_BINDING),
            viewports: read_viewports(gl),
            depth_func: gl.integer(DEPTH_FUNC),
            depth_mask,
            depth_clear,
            polygon_offset,
            polygon_mode,
            line_width,
            pack: PACK_STATE.map(|p| (p, gl.integer(p))),
            clip_control,
            depth_transfer,
            capabilities,
            compatibility,
        }
    }

    /// Sets what the probe's draws need: its own FBO aside, depth test on with writes,
    /// `[-1, 1]` clip depth, `glDepthRange(0, 1)`, filled polygons, nothing that discards
    /// fragments, tightly packed reads into client memory.
    pub unsafe fn prepare(&self, gl: &Gl) {
        for c in &self.capabilities {
            (gl.Disable)(c.cap);
        }
        (gl.Enable)(DEPTH_TEST);
        (gl.DepthMask)(1);
        (gl.DepthRange)(0.0, 1.0);
        (gl.PolygonMode)(FRONT_AND_BACK, FILL);
        (gl.LineWidth)(1.0);
        if let Some(clip_control) = gl.ClipControl {
            clip_control(LOWER_LEFT, NEGATIVE_ONE_TO_ONE);
        }
        if let Some(transfer) = self.depth_transfer.and(gl.PixelTransferf) {
            transfer(DEPTH_SCALE, 1.0);
            transfer(DEPTH_BIAS, 0.0);
        }
        (gl.BindBuffer)(PIXEL_PACK_BUFFER, 0);
        for p in PACK_STATE {
            (gl.PixelStorei)(p, if p == PACK_ALIGNMENT { 4 } else { 0 });
        }
    }

    /// Puts everything back as [`Saved::read`] found it.
    pub unsafe fn restore(&self, gl: &Gl) {
        (gl.BindFramebuffer)(DRAW_FRAMEBUFFER, self.draw_framebuffer as Uint);
        (gl.BindFramebuffer)(READ_FRAMEBUFFER, self.read_framebuffer as Uint);
        (gl.BindRenderbuffer)(RENDERBUFFER, self.renderbuffer as Uint);
        (gl.UseProgram)(self.program as Uint);
        (gl.BindVertexArray)(self.vertex_array as Uint);
        (gl.BindBuffer)(ARRAY_BUFFER, self.array_buffer as Uint);
        (gl.BindBuffer)(PIXEL_PACK_BUFFER, self.pixel_pack_buffer as Uint);
        let (active, multisample) = self.texture;
        (gl.ActiveTexture)(TEXTURE0);
        (gl.BindTexture)(TEXTURE_2D_MULTISAMPLE, multisample as Uint);
        (gl.ActiveTexture)(active as Enum);
        for c in &self.capabilities {
            if c.on {
                (gl.Enable)(c.cap);
            } else {
                (gl.Disable)(c.cap);
            }
        }
        restore_viewports(gl, &self.viewports);
        (gl.DepthFunc)(self.depth_func as Enum);
        (gl.DepthMask)(self.depth_mask);
        (gl.ClearDepth)(self.depth_clear);
        let [factor, units, clamp] = self.polygon_offset;
        match gl.PolygonOffsetClamp {
            Some(with_clamp) => with_clamp(factor, units, clamp),
            None => (gl.PolygonOffset)(factor, units),
        }
        let [front, back] = self.polygon_mode;
        if front == back || !self.compatibility {
            (gl.PolygonMode)(FRONT_AND_BACK, front as Enum);
        } else {
            (gl.PolygonMode)(FRONT, front as Enum);
            (gl.PolygonMode)(BACK, back as Enum);
        }
        (gl.LineWidth)(self.line_width);
        for (p, v) in self.pack {
            (gl.PixelStorei)(p, v);
        }
        if let (Some(clip_control), Some([origin, mode])) = (gl.ClipControl, self.clip_control) {
            clip_control(origin as Enum, mode as Enum);
        }
        if let (Some(transfer), Some([scale, bias])) = (gl.PixelTransferf, self.depth_transfer) {
            transfer(DEPTH_SCALE, scale);
            transfer(DEPTH_BIAS, bias);
        }
    }
}

/// Every viewport, depth range and per-viewport scissor enable: `glViewport` and `glDepthRange`
/// set all viewports of an `ARB_viewport_array` context, so all are saved where there are several.
unsafe fn read_viewports(gl: &Gl) -> Vec<([f32; 4], [f64; 2], bool)> {
    if let (Some(get_f), Some(get_d), Some(is_on), Some(_), Some(_), Some(_), Some(_)) = (
        gl.GetFloati_v,
        gl.GetDoublei_v,
        gl.IsEnabledi,
        gl.ViewportIndexedf,
        gl.DepthRangeIndexed,
        gl.Enablei,
        gl.Disablei,
    ) {
        let count = gl.integer(MAX_VIEWPORTS);
        if !gl.failed() && count > 1 {
            return (0..count as Uint)
                .map(|i| {
                    let (mut v, mut r) = ([0.0f32; 4], [0.0f64; 2]);
                    get_f(VIEWPORT, i, v.as_mut_ptr());
                    get_d(DEPTH_RANGE, i, r.as_mut_ptr());
                    (v, r, is_on(SCISSOR_TEST, i) != 0)
                })
                .collect();
        }
    }
    let (mut v, mut r) = ([0.0f32; 4], [0.0f64; 2]);
    (gl.GetFloatv)(VIEWPORT, v.as_mut_ptr());
    (gl.GetDoublev)(DEPTH_RANGE, r.as_mut_ptr());
    vec![(v, r, (gl.IsEnabled)(SCISSOR_TEST) != 0)]
}

unsafe fn restore_viewports(gl: &Gl, viewports: &[([f32; 4], [f64; 2], bool)]) {
    let indexed = (
        gl.ViewportIndexedf,
        gl.DepthRangeIndexed,
        gl.Enablei,
        gl.Disablei,
    );
    match (viewports, indexed) {
        ([(v, r, _)], _) => {
            (gl.Viewport)(v[0] as Int, v[1] as Int, v[2] as Sizei, v[3] as Sizei);
            (gl.DepthRange)(r[0], r[1]);
        }
        (all, (Some(viewport), Some(range), Some(enable), Some(disable))) => {
            for (i, (v, r, scissor)) in all.iter().enumerate() {
                viewport(i as Uint, v[0], v[1], v[2], v[3]);
                range(i as Uint, r[0], r[1]);
                if *scissor {
                    enable(SCISSOR_TEST, i as Uint);
                } else {
                    disable(SCISSOR_TEST, i as Uint);
                }
            }
        }
        _ => {}
    }
}

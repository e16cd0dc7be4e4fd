//! A multisampled render target read back sample by sample ([`crate::Gl::set_target_samples`]).
//!
//! The colour is a multisampled texture; reading copies sample `s` of every pixel of a rectangle
//! into a single-sampled renderbuffer (a full-screen triangle whose fragment shader does
//! `texelFetch(tex, ivec2(gl_FragCoord.xy), s)`: no averaging) and reads that with
//! `glReadPixels`. Each sample is then counted on its own, as the depth test judged it: a decal
//! sample lost or shown is seen even where its pixel's other samples hide it in the resolved
//! average.

use glow::HasContext;

/// A full-screen triangle (also [`crate::edges::Msaa`]'s).
pub(crate) const VERTEX_SHADER: &str = "#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
    gl_Position = vec4(p, 0.0, 1.0);
}
";

/// Sample `s` of the multisampled colour at this fragment's pixel.
pub(crate) const FRAGMENT_SHADER: &str = "#version 330 core
uniform sampler2DMS tex;
uniform int s;
out vec4 frag;
void main() { frag = texelFetch(tex, ivec2(gl_FragCoord.xy), s); }
";

/// The multisampled colour of a target and what reads it.
pub(crate) struct Samples {
    /// The target's framebuffer, bound again after a read.
    target: glow::Framebuffer,
    /// `GL_TEXTURE_2D_MULTISAMPLE`, the target's colour attachment.
    texture: glow::Texture,
    /// A single-sampled framebuffer over the target's own colour renderbuffer.
    copy: glow::Framebuffer,
    program: glow::Program,
    vao: glow::VertexArray,
    samples: u32,
}

impl Samples {
    /// Attaches a `samples`× RGBA8 texture of `w × h` as the colour of `target` (bound), and a
    /// framebuffer over `copy_color` (a single-sampled RGBA8 renderbuffer of the same size) to
    /// read samples through; `target` stays bound.
    ///
    /// # Safety
    /// `gl` is current on this thread; `target` and `copy_color` are its live objects.
    pub(crate) unsafe fn new(
        gl: &glow::Context,
        target: glow::Framebuffer,
        copy_color: glow::Renderbuffer,
        w: i32,
        h: i32,
        samples: u32,
    ) -> Result<Samples, String> {
        let texture = gl.create_texture()?;
        gl.bind_texture(glow::TEXTURE_2D_MULTISAMPLE, Some(texture));
        gl.tex_image_2d_multisample(
            glow::TEXTURE_2D_MULTISAMPLE,
            samples as i32,
            glow::RGBA8 as i32,
            w,
            h,
            true,
        );
        gl.framebuffer_texture_2d(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            glow::TEXTURE_2D_MULTISAMPLE,
            Some(texture),
            0,
        );
        let copy = gl.create_framebuffer()?;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(copy));
        gl.framebuffer_renderbuffer(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            glow::RENDERBUFFER,
            Some(copy_color),
        );
        let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(target));
        if status != glow::FRAMEBUFFER_COMPLETE {
            return Err(format!(
                "the sample-copy framebuffer is incomplete: status 0x{status:04X}"
            ));
        }
        let program = crate::link_program(gl, VERTEX_SHADER, FRAGMENT_SHADER)?;
        let vao = gl.create_vertex_array()?;
        Ok(Samples {
            target,
            texture,
            copy,
            program,
            vao,
            samples,
        })
    }

    /// Samples per pixel.
    pub(crate) fn count(&self) -> usize {
        self.samples as usize
    }

    /// Every sample of the `width × height` rectangle at `origin`, sample 0's rows first; the
    /// viewport, scissor box and depth test as they were, the target bound again.
    ///
    /// # Safety
    /// `gl` is current on this thread and these objects are alive.
    pub(crate) unsafe fn read_at(
        &self,
        gl: &glow::Context,
        origin: [u32; 2],
        width: u32,
        height: u32,
    ) -> Vec<[u8; 4]> {
        let mut viewport = [0i32; 4];
        let mut scissor = [0i32; 4];
        gl.get_parameter_i32_slice(glow::VIEWPORT, &mut viewport);
        gl.get_parameter_i32_slice(glow::SCISSOR_BOX, &mut scissor);
        let scissor_on = gl.is_enabled(glow::SCISSOR_TEST);
        let [x, y, w, h] = [origin[0], origin[1], width, height].map(|v| v as i32);
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.copy));
        gl.viewport(x, y, w, h);
        gl.disable(glow::SCISSOR_TEST);
        gl.disable(glow::DEPTH_TEST);
        gl.color_mask(true, true, true, true);
        // The copy fills its triangle whatever mode the last draw left (edges draw lines).
        gl.polygon_mode(glow::FRONT_AND_BACK, glow::FILL);
        gl.use_program(Some(self.program));
        gl.active_texture(glow::TEXTURE0);
        gl.bind_texture(glow::TEXTURE_2D_MULTISAMPLE, Some(self.texture));
        let tex = gl.get_uniform_location(self.program, "tex");
        gl.uniform_1_i32(tex.as_ref(), 0);
        let s_at = gl.get_uniform_location(self.program, "s");
        gl.bind_vertex_array(Some(self.vao));
        let mut out = Vec::with_capacity((w * h) as usize * self.count());
        for s in 0..self.samples {
            gl.uniform_1_i32(s_at.as_ref(), s as i32);
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
            out.extend(crate::read_rgba8_at(gl, [x, y], w, h));
        }
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.target));
        gl.viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
        gl.scissor(scissor[0], scissor[1], scissor[2], scissor[3]);
        if scissor_on {
            gl.enable(glow::SCISSOR_TEST);
        }
        gl.enable(glow::DEPTH_TEST);
        out
    }

    /// Deletes these objects (the target's own are the caller's).
    pub(crate) fn delete(self, gl: &glow::Context) {
        // SAFETY: the caller's context is current on this thread (Gl's invariant).
        unsafe {
            gl.delete_texture(self.texture);
            gl.delete_framebuffer(self.copy);
            gl.delete_program(self.program);
            gl.delete_vertex_array(self.vao);
        }
    }
}

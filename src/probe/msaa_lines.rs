//! Multisampled lines over their faces: where a line's sample takes its depth
//! (`line_reach_msaa`).
//!
//! Under MSAA a rasterizer may take a line sample's depth once per pixel, or at the sample's
//! projection on the line, or along the minor axis; the face under it is evaluated at the
//! sample. The probe draws lines and polygon-mode outlines in 32 gradient directions, 64 per
//! tile ([`dense_tiles`], shared with [`super::wide_lines`]), into a multisampled `GL_DEPTH_COMPONENT32F` texture, copies each
//! sample out
//! (`texelFetch` of a `sampler2DMS` written as `gl_FragDepth` into the probe's own D32F
//! renderbuffer, which stores it exactly, read with `glReadPixels` as every other measurement:
//! no colour state is touched) and compares it with the tile's plane at that sample's position
//! (`glGetMultisamplefv`).

use super::wide_lines::WIDE_PER_TILE;
use super::*;

/// Copies sample `s` of the multisampled depth at this fragment's pixel: a full-screen triangle.
const COPY_VERTEX_SHADER: &[u8] = b"#version 150\nvoid main() {\n\
    vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n\
    gl_Position = vec4(p, 0.0, 1.0);\n}\n\0";
const COPY_FRAGMENT_SHADER: &[u8] = b"#version 150\nuniform sampler2DMS depth;\n\
uniform int s;\n\
void main() { gl_FragDepth = texelFetch(depth, ivec2(gl_FragCoord.xy), s).r; }\n\0";

/// The sample count engines ask for most; the measurement also draws the context's largest up
/// to [`MOST_SAMPLES`], and keeps the larger reach.
const SAMPLES: Int = 4;

/// The largest sample count measured.
const MOST_SAMPLES: Int = 16;

/// What [`msaa_line_reach`] measured.
pub(super) struct MsaaFigures {
    /// Per kind (`GL_LINES` width 1, polygon-mode lines width 1): the largest
    /// `|stored − plane at the sample|` over `max(|gₓ|, |g_y|)` and over `|∇z|`, pixels, the
    /// larger of the sample counts drawn (NaN where none was), and the samples compared.
    pub(super) measured: TileReach,
    /// The same at `glLineWidth(3)` ([`crate::profile::WIDE_LINE_WIDTH`]); unmeasured where the context refuses the width.
    pub(super) wide: TileReach,
    /// The sample counts drawn (0: none).
    pub(super) counts: [Int; 2],
}

/// The objects one multisampled draw makes (0 = not made), deleted together.
#[derive(Default)]
struct Targets {
    texture: Uint,
    multisampled: Uint,
    program: Uint,
}

impl Targets {
    /// Deletes these objects and binds the probe's own framebuffer and program again.
    unsafe fn delete(&self, gl: &Gl, o: &Objects) {
        (gl.BindFramebuffer)(FRAMEBUFFER, o.framebuffer);
        (gl.UseProgram)(o.program);
        (gl.DeleteTextures)(1, &self.texture);
        (gl.DeleteFramebuffers)(1, &self.multisampled);
        if self.program != 0 {
            (gl.DeleteProgram)(self.program);
        }
    }
}

/// Measures how far from the sample a multisampled line sample's depth is taken, per line kind
/// (module docs), at 4 samples and at the context's largest count up to 16: the larger of the
/// two. NaN figures where the context offers fewer than 4 samples of a depth texture, or
/// attaches none.
pub(super) unsafe fn msaa_line_reach(gl: &Gl, o: &Objects) -> Result<MsaaFigures> {
    let most = gl.integer(MAX_DEPTH_TEXTURE_SAMPLES).min(MOST_SAMPLES);
    gl.check("glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES) raised a GL error")?;
    let mut figures = MsaaFigures {
        measured: TileReach::unmeasured(),
        wide: TileReach::unmeasured(),
        counts: [0; 2],
    };
    if most < SAMPLES {
        return Ok(figures);
    }
    let counts = if most > SAMPLES {
        [SAMPLES, most]
    } else {
        [SAMPLES, 0]
    };
    for (i, &count) in counts.iter().enumerate().filter(|(_, &c)| c > 0) {
        let mut targets = Targets::default();
        let result = draw_and_compare(gl, o, count, PER_TILE, &mut targets);
        targets.delete(gl, o);
        // A count the context cannot attach is not measured (the model keeps the worst case).
        let Some(measured) = result? else {
            continue;
        };
        figures.measured.merge(&measured);
        figures.counts[i] = count;
    }
    figures.wide = wide_msaa_reach(gl, o, &figures.counts)?;
    Ok(figures)
}

/// The multisampled reach at [`crate::profile::WIDE_LINE_WIDTH`] pixels, at the sample counts `counts` the 1-pixel lines
/// were drawn at (16 primitives per tile, as [`super::wide_lines`] draws them); unmeasured where
/// the context refuses the width (a forward-compatible core context allows only 1) or draws
/// narrower lines.
unsafe fn wide_msaa_reach(gl: &Gl, o: &Objects, counts: &[Int; 2]) -> Result<TileReach> {
    let mut wide = TileReach::unmeasured();
    if !super::wide_lines::set_wide(gl)? {
        return Ok(wide);
    }
    for &count in counts.iter().filter(|&&c| c > 0) {
        let mut targets = Targets::default();
        let result = draw_and_compare(gl, o, count, WIDE_PER_TILE, &mut targets);
        targets.delete(gl, o);
        match result {
            Ok(Some(measured)) => wide.merge(&measured),
            Ok(None) => {}
            Err(e) => {
                (gl.LineWidth)(1.0);
                return Err(e);
            }
        }
    }
    (gl.LineWidth)(1.0);
    Ok(wide)
}

/// One sample count: draws the line tiles multisampled, copies every sample out and compares
/// it with its plane. Returns what [`reach_in_tiles`] measured.
unsafe fn draw_and_compare(
    gl: &Gl,
    o: &Objects,
    count: Int,
    per_tile: usize,
    t: &mut Targets,
) -> Result<Option<TileReach>> {
    let side = (SIZE * TILES) as Sizei;
    let rows = DENSE_ROWS;
    (gl.GenTextures)(1, &mut t.texture);
    (gl.ActiveTexture)(TEXTURE0);
    (gl.BindTexture)(TEXTURE_2D_MULTISAMPLE, t.texture);
    (gl.TexImage2DMultisample)(
        TEXTURE_2D_MULTISAMPLE,
        count,
        DEPTH_COMPONENT32F,
        side,
        rows as Sizei,
        1,
    );
    (gl.GenFramebuffers)(1, &mut t.multisampled);
    (gl.BindFramebuffer)(FRAMEBUFFER, t.multisampled);
    (gl.FramebufferTexture2D)(
        FRAMEBUFFER,
        DEPTH_ATTACHMENT,
        TEXTURE_2D_MULTISAMPLE,
        t.texture,
        0,
    );
    (gl.DrawBuffer)(NONE);
    (gl.ReadBuffer)(NONE);
    let complete = (gl.CheckFramebufferStatus)(FRAMEBUFFER) == FRAMEBUFFER_COMPLETE;
    if gl.failed() || !complete {
        return Ok(None);
    }
    let mut positions = vec![[0.0f32; 2]; count as usize];
    for (s, p) in positions.iter_mut().enumerate() {
        (gl.GetMultisamplefv)(SAMPLE_POSITION, s as Uint, p.as_mut_ptr());
    }
    (gl.Enable)(MULTISAMPLE);
    let drawn = draw_dense(gl, o, side, rows as Sizei, per_tile);
    (gl.Disable)(MULTISAMPLE);
    drawn?;
    let depth = copy_samples(gl, o, t, count, side, rows as Sizei)?;
    let positions: Vec<[f64; 2]> = positions.iter().map(|p| p.map(f64::from)).collect();
    Ok(Some(reach_in_tiles(
        &depth,
        &positions,
        (side as usize, rows),
        DENSE_TILES,
    )))
}

/// Every sample of the multisampled depth, `count` images of `side × rows`, sample 0's first:
/// each written by a full-screen triangle as `gl_FragDepth` into the probe's framebuffer (its
/// D32F renderbuffer attached, depth test `GL_ALWAYS`) and read back.
unsafe fn copy_samples(
    gl: &Gl,
    o: &Objects,
    t: &mut Targets,
    count: Int,
    side: Sizei,
    rows: Sizei,
) -> Result<Vec<f64>> {
    t.program = link(
        gl,
        COPY_VERTEX_SHADER,
        COPY_FRAGMENT_SHADER,
        "the probe's sample-copy shaders (GLSL 1.50, sampler2DMS) did not compile or link",
    )?;
    (gl.BindFramebuffer)(FRAMEBUFFER, o.framebuffer);
    (gl.UseProgram)(t.program);
    (gl.Uniform1i)((gl.GetUniformLocation)(t.program, c"depth".as_ptr()), 0);
    let at_sample = (gl.GetUniformLocation)(t.program, c"s".as_ptr());
    (gl.Viewport)(0, 0, side, rows);
    let pixels = (side * rows) as usize;
    let mut out = Vec::with_capacity(pixels * count as usize);
    for s in 0..count {
        (gl.Uniform1i)(at_sample, s);
        (gl.DrawArrays)(TRIANGLES, 0, 3);
        let depth = read_depth(gl, Format::Float, 0, side as usize, rows as usize)?;
        out.extend(depth);
    }
    gl.check("copying the probe's depth samples out raised a GL error")?;
    Ok(out)
}

//! Multisampled lines over their faces: where a line's sample takes its depth
//! (`line_reach_msaa`).
//!
//! Under MSAA a rasterizer may take a line sample's depth once per pixel, or at the sample's
//! projection on the line, or along the minor axis; the face under it is evaluated at the
//! sample. The probe draws lines and polygon-mode outlines in 32 gradient directions, 64 per
//! tile ([`dense_tiles`]), into a multisampled `GL_DEPTH_COMPONENT32F` texture, copies each
//! sample out
//! (`texelFetch` of a `sampler2DMS` written as `gl_FragDepth` into the probe's own D32F
//! renderbuffer, which stores it exactly, read with `glReadPixels` as every other measurement:
//! no colour state is touched) and compares it with the tile's plane at that sample's position
//! (`glGetMultisamplefv`).

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

/// Tiles per line kind, each with its own plane: twice the single-sampled measurement's
/// gradient directions, since a multisampled sample's reach depends on how the line, the
/// gradient and the sample pattern line up.
const MSAA_TILES: usize = 32;

/// Lines per `GL_LINES` tile and triangles per polygon-mode tile (overlapping: a later one
/// overwrites an earlier one's samples, all on one plane). On llvmpipe the reach grows with the
/// count and levels off: 1.045 at 16 per tile, 1.0556 at 32, 1.0559 at 64 (6 lines per tile in
/// 16 tiles, as the single-sampled measurement draws, found 0.998).
const PER_TILE: usize = 64;

/// Tile `k`'s plane: gradient directions spread over the circle, the larger component
/// [`LINE_GRADIENT`].
fn msaa_plane(k: usize) -> (f64, f64) {
    let theta = std::f64::consts::PI * (2 * k + 1) as f64 / MSAA_TILES as f64;
    let (c, s) = (theta.cos(), theta.sin());
    let big = c.abs().max(s.abs());
    (LINE_GRADIENT * c / big, LINE_GRADIENT * s / big)
}

/// The multisampled measurement's geometry: per tile [`PER_TILE`] segments 12–20 pixels long
/// in directions spread over the half circle (each tile turned a little further), and as many
/// triangles for polygon-mode outlines, corners at sub-pixel positions.
fn dense_tiles() -> (Tiles, Tiles) {
    let mut next = xorshift();
    let mut lines = Vec::new();
    let mut polygons = Vec::new();
    for k in 0..MSAA_TILES {
        let plane = msaa_plane(k);
        let mut segments = Vec::new();
        for j in 0..PER_TILE {
            let turn = (j as f64 + k as f64 / MSAA_TILES as f64) / PER_TILE as f64;
            let phi = std::f64::consts::PI * turn;
            let centre = (32.0 + 24.0 * (next() - 0.5), 32.0 + 24.0 * (next() - 0.5));
            segments.extend(segment(centre, 6.0 + 4.0 * next(), phi, plane));
        }
        lines.push(segments);
        let mut triangles = Vec::new();
        for _ in 0..PER_TILE {
            let (cx, cy) = (12.0 + 40.0 * next(), 12.0 + 40.0 * next());
            for _ in 0..3 {
                triangles.push(tile_vertex(
                    cx + 20.0 * (next() - 0.5),
                    cy + 20.0 * (next() - 0.5),
                    plane,
                ));
            }
        }
        polygons.push(triangles);
    }
    (lines, polygons)
}

/// What [`msaa_line_reach`] measured.
pub(super) struct MsaaFigures {
    /// The largest `|stored − plane at the sample| / max(|gₓ|, |g_y|)` per kind (`GL_LINES`
    /// width 1, polygon-mode lines width 1), pixels; NaN where not measured.
    pub(super) reach: [f64; 2],
    /// Samples compared per kind.
    pub(super) samples: [usize; 2],
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
        reach: [f64::NAN; 2],
        samples: [0; 2],
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
        let result = draw_and_compare(gl, o, count, &mut targets);
        targets.delete(gl, o);
        // A count the context cannot attach is not measured (the model keeps the worst case).
        let Some((reach, samples)) = result? else {
            continue;
        };
        for kind in 0..2 {
            figures.reach[kind] = if figures.reach[kind].is_nan() {
                reach[kind]
            } else {
                figures.reach[kind].max(reach[kind])
            };
            figures.samples[kind] += samples[kind];
        }
        figures.counts[i] = count;
    }
    Ok(figures)
}

/// One sample count: draws the line tiles multisampled, copies every sample out and compares
/// it with its plane. Returns the reach and the samples compared per kind.
unsafe fn draw_and_compare(
    gl: &Gl,
    o: &Objects,
    count: Int,
    t: &mut Targets,
) -> Result<Option<([f64; 2], [usize; 2])>> {
    let side = (SIZE * TILES) as Sizei;
    let rows = (2 * MSAA_TILES).div_ceil(TILES) * SIZE;
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
    draw_lines(gl, o, side, rows as Sizei)?;
    let depth = copy_samples(gl, o, t, count, side, rows as Sizei)?;
    Ok(Some(compare(&depth, &positions, side as usize, rows)))
}

/// Draws [`dense_tiles`] (the `GL_LINES` tiles, then the polygon-mode ones) with multisampling
/// on, depth test `GL_ALWAYS`, into the bound multisampled framebuffer cleared to 1.
unsafe fn draw_lines(gl: &Gl, o: &Objects, side: Sizei, rows: Sizei) -> Result<()> {
    let (lines, polygons) = dense_tiles();
    let mut all: Vec<[f32; 4]> = Vec::new();
    let mut draws = Vec::new(); // (tile, first, count)
    for (k, v) in lines.iter().chain(&polygons).enumerate() {
        draws.push((k, all.len(), v.len()));
        all.extend_from_slice(v);
    }
    (gl.Viewport)(0, 0, side, rows);
    (gl.ClearDepth)(1.0);
    (gl.Clear)(DEPTH_BUFFER_BIT);
    (gl.BindBuffer)(ARRAY_BUFFER, o.buffer);
    let bytes = std::mem::size_of_val(all.as_slice()) as isize;
    (gl.BufferData)(ARRAY_BUFFER, bytes, all.as_ptr().cast(), STREAM_DRAW);
    (gl.UseProgram)(o.program);
    (gl.UniformMatrix4fv)(o.projection, 1, 0, IDENTITY.as_ptr());
    (gl.Enable)(MULTISAMPLE);
    for (tile, first, count) in draws {
        let (x, y) = tile_origin(tile);
        (gl.Viewport)(x as Int, y as Int, SIZE as Sizei, SIZE as Sizei);
        let outline = tile >= MSAA_TILES;
        if outline {
            (gl.PolygonMode)(FRONT_AND_BACK, LINE);
        }
        let mode = if outline { TRIANGLES } else { LINES };
        (gl.DrawArrays)(mode, first as Int, count as Sizei);
        (gl.PolygonMode)(FRONT_AND_BACK, FILL);
    }
    (gl.Disable)(MULTISAMPLE);
    gl.check("drawing the probe's multisampled lines raised a GL error")
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
) -> Result<Vec<f32>> {
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
        out.extend(depth.iter().map(|&d| d as f32));
    }
    gl.check("copying the probe's depth samples out raised a GL error")?;
    Ok(out)
}

/// The largest `|stored − plane at the sample| / LINE_GRADIENT` per kind over every sample a
/// line or outline wrote (stored below 0.99; cleared to 1), and how many.
fn compare(
    depth: &[f32],
    positions: &[[f32; 2]],
    width: usize,
    rows: usize,
) -> ([f64; 2], [usize; 2]) {
    let mut reach = [0.0f64; 2];
    let mut samples = [0usize; 2];
    let half = SIZE as f64 / 2.0;
    for (s, image) in depth.chunks_exact(width * rows).enumerate() {
        let [sx, sy] = positions[s].map(f64::from);
        for tile in 0..2 * MSAA_TILES {
            let kind = tile / MSAA_TILES;
            let (gx, gy) = msaa_plane(tile % MSAA_TILES);
            let (ox, oy) = tile_origin(tile);
            for py in 0..SIZE {
                for px in 0..SIZE {
                    let stored = f64::from(image[(oy + py) * width + ox + px]);
                    if stored >= 0.99 {
                        continue;
                    }
                    let (x, y) = (px as f64 + sx - half, py as f64 + sy - half);
                    let exact = 0.5 + gx * x + gy * y;
                    reach[kind] = reach[kind].max((stored - exact).abs() / LINE_GRADIENT);
                    samples[kind] += 1;
                }
            }
        }
    }
    (reach, samples)
}

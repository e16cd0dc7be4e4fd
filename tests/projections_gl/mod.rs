//! Shared by `tests/gl_projections.rs` and `examples/precision_table.rs`: drawing through the
//! median-projection GLSL snippet, and measuring the depth step of a projection on the
//! rasterizer. Uses the harness's context, target and readback (`zshift-harness`).

#![allow(dead_code)]

use glow::HasContext;
use zshift::median::FTRANSFORM_MDP_GLSL;
use zshift_harness::{rgba8, DrawState, Gl, Quad};

/// The base surface's colour.
pub const BASE: [f32; 4] = [0.0, 0.0, 1.0, 1.0];
/// The decal's colour.
pub const DECAL: [f32; 4] = [1.0, 0.0, 0.0, 1.0];

/// A program whose vertex shader is the shipped `bindings/glsl/ftransform_mdp.glsl`.
pub struct MdpProgram {
    program: glow::Program,
    vao: glow::VertexArray,
    vbo: glow::Buffer,
}

impl MdpProgram {
    /// Compiles and links the snippet inside a minimal GLSL 3.30 core vertex shader.
    pub fn new(gl: &Gl) -> Result<Self, String> {
        let vs = format!(
            "#version 330 core\nlayout(location = 0) in vec3 eye;\nuniform mat4 proj;\n\
             uniform float median;\nuniform float ndc_offset;\n{FTRANSFORM_MDP_GLSL}\n\
             void main() {{ gl_Position = zshift_ftransform_mdp(proj, vec4(eye, 1.0), median, ndc_offset); }}\n"
        );
        // SAFETY: `gl` is current on this thread (the harness makes it so and never releases it).
        let (program, vao, vbo) = unsafe { zshift_harness::flat_colour_pipeline(gl.glow(), &vs) }
            .map_err(|e| format!("ftransform_mdp.glsl: {e}"))?;
        Ok(Self { program, vao, vbo })
    }

    /// Draws `quad` through `zshift_ftransform_mdp`, with depth test `depth_func` and writes on.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &self,
        gl: &Gl,
        quad: &Quad,
        proj: &[f32; 16],
        median: f32,
        ndc_offset: f32,
        color: [f32; 4],
        depth_func: u32,
    ) -> Result<(), String> {
        let g = gl.glow();
        unsafe {
            zshift_harness::use_quad_pipeline(g, (self.program, self.vao, self.vbo), quad);
            let loc = |name| g.get_uniform_location(self.program, name);
            g.uniform_matrix_4_f32_slice(loc("proj").as_ref(), false, proj);
            g.uniform_1_f32(loc("median").as_ref(), median);
            g.uniform_1_f32(loc("ndc_offset").as_ref(), ndc_offset);
            g.uniform_4_f32(
                loc("color").as_ref(),
                color[0],
                color[1],
                color[2],
                color[3],
            );
            g.enable(glow::DEPTH_TEST);
            g.depth_func(depth_func);
            g.depth_mask(true);
            g.color_mask(true, true, true, true);
            g.disable(glow::POLYGON_OFFSET_FILL);
            g.draw_arrays(glow::TRIANGLE_FAN, 0, 4);
            g.bind_vertex_array(None);
            g.use_program(None);
        }
        gl.check("MdpProgram::draw")
    }
}

/// How a measured projection draws a quad.
pub enum Drawer<'a> {
    /// `gl_Position = proj · eye` (the harness's quad shader).
    Matrix([f32; 16]),
    /// The median snippet with this projection (for x, y) and median distance.
    Median(&'a MdpProgram, [f32; 16], f32),
}

/// Columns of the measuring target.
pub const COLUMNS: usize = 256;

/// Measures the depth step at eye distance `d`: draws `COLUMNS` facing strips, one per pixel
/// column, at distances `d + (127.5 − k)·h` (`h = expected/8`, rounded to f32 as vertex z), stores each
/// with `GL_ALWAYS`, reads the depth back and divides the distance spanned by the number of
/// distinct stored values less one (robust to evaluation noise that makes the stored value
/// go back and forth between neighbours). The target must be `COLUMNS × 2` with the format of interest,
/// the clip control set, and the frustum centred (`m8 = m9 = 0`).
///
/// What [`measure_step`] saw.
pub struct Measured {
    /// The distance spanned divided by the number of distinct stored values less one; `None`
    /// when all columns stored the same value.
    pub step: Option<f64>,
    /// Distinct stored values across the columns.
    pub distinct: usize,
    /// Changes beyond the distinct values: the stored depth went back to an earlier value while
    /// the distance kept falling (f32 evaluation noise on the GPU, not monotone in d).
    pub reversals: usize,
}

/// Measures the depth step at eye distance `d` (see the module docs).
pub fn measure_step(
    gl: &mut Gl,
    drawer: &Drawer,
    d: f64,
    expected: f64,
) -> Result<Measured, String> {
    let proj = match drawer {
        Drawer::Matrix(p) | Drawer::Median(_, p, _) => *p,
    };
    let (sx, sy) = (f64::from(proj[0]), f64::from(proj[5]));
    let h = expected / 8.0;
    gl.clear([0.0, 0.0, 0.0, 1.0], 0.5)?;
    let mut zs = Vec::with_capacity(COLUMNS);
    for k in 0..COLUMNS {
        // Centred on d, so a step that grows with distance averages to its value at d.
        let z = (-(d + (0.5 * (COLUMNS - 1) as f64 - k as f64) * h)) as f32;
        zs.push(z);
        let dk = -f64::from(z);
        // Window x in [k + 0.25, k + 0.75] contains only pixel k's centre.
        let x0 = (-1.0 + 2.0 * (k as f64 + 0.25) / COLUMNS as f64) * dk / sx;
        let x1 = (-1.0 + 2.0 * (k as f64 + 0.75) / COLUMNS as f64) * dk / sx;
        let y = 1.5 * dk / sy;
        let quad = Quad::rect(x0 as f32, x1 as f32, -y as f32, y as f32, z);
        match drawer {
            Drawer::Matrix(p) => {
                let state = zshift_harness::DrawState {
                    depth_func: glow::ALWAYS,
                    ..Default::default()
                };
                gl.draw_quad(&quad, p, [1.0, 1.0, 1.0, 1.0], &state)?;
            }
            Drawer::Median(prog, p, m) => {
                prog.draw(gl, &quad, p, *m, 0.0, [1.0; 4], glow::ALWAYS)?
            }
        }
    }
    let depth = gl.read_depth()?;
    let row = &depth[..COLUMNS]; // bottom row
    let changes = row.windows(2).filter(|w| w[0] != w[1]).count();
    let mut distinct: Vec<u32> = row.iter().map(|v| v.to_bits()).collect();
    distinct.sort_unstable();
    distinct.dedup();
    let span = f64::from(zs[COLUMNS - 1]) - f64::from(zs[0]);
    let step = (distinct.len() > 1).then(|| span / (distinct.len() - 1) as f64);
    Ok(Measured {
        step,
        distinct: distinct.len(),
        reversals: changes + 1 - distinct.len(),
    })
}

/// The f32 spacing of eye-space z at distance `d`: the vertex's own quantisation.
pub fn eye_z_spacing(d: f64) -> f64 {
    let z = d as f32;
    f64::from(z.next_up() - z)
}

/// A base quad and a smaller decal on the same plane through eye distance `d` on the view axis,
/// tilted by `slope` (eye-space dz/dy), with different vertices as real decals have; the decal
/// drawn with `decal_proj` after the base (depth test `GL_LESS`, or `GL_GREATER` with clear 0
/// when `reversed`). Returns the decal pixels lost to the base.
pub fn decal_loss(
    gl: &mut Gl,
    base_proj: &[f32; 16],
    decal_proj: &[f32; 16],
    d: f64,
    slope: f64,
    reversed: bool,
) -> Result<usize, String> {
    let (clear, func) = if reversed {
        (0.0, glow::GREATER)
    } else {
        (1.0, glow::LESS)
    };
    let plane = |_: f64, y: f64| -d + slope * y;
    let (s, t) = (0.45 * d, 0.3 * d);
    let base = Quad::on_plane(-s, s, -s, s, plane);
    let decal = Quad::on_plane(-t, 0.77 * t, -0.91 * t, t, plane);
    let state = DrawState {
        depth_func: func,
        ..Default::default()
    };
    gl.clear([0.0, 0.0, 0.0, 1.0], clear)?;
    gl.draw_quad(&base, base_proj, BASE, &state)?;
    gl.draw_quad(&decal, decal_proj, DECAL, &state)?;
    let image = gl.read_color()?;
    // Where the decal is: draw it alone into a fresh buffer.
    gl.clear([0.0, 0.0, 0.0, 1.0], clear)?;
    gl.draw_quad(&decal, decal_proj, DECAL, &state)?;
    let mask = gl.read_color()?.mask_of(rgba8(DECAL));
    if mask.iter().filter(|&&m| m).count() < 200 {
        return Err("the decal covers too few pixels".into());
    }
    Ok(image.count_not_in_mask(&mask, rgba8(DECAL)))
}

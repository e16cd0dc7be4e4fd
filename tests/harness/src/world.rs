//! Meshes drawn the way engines draw them: vertices in world space, transformed in the vertex
//! shader by an f32 view matrix and then the projection (`proj * (view * vec4(p, 1))`), into a
//! viewport anywhere in the framebuffer, under any `glDepthRange`.
//!
//! [`Gl::draw_quad`] sends eye-space corners and only the projection; this is the other path,
//! where the f32 view transform's roundings (relative to the world coordinates, not to the
//! distance from the camera) reach the rasterizer as they do in an engine.

use glow::HasContext;

use crate::{DrawState, Gl};

const WORLD_VERTEX_SHADER: &str = "#version 330 core
layout(location = 0) in vec3 world;
uniform mat4 view;
uniform mat4 proj;
void main() { gl_Position = proj * (view * vec4(world, 1.0)); }
";

/// Where the viewport lies and how depth is mapped: `glViewport(x, y, w, h)` and
/// `glDepthRange(near, far)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// `glViewport`'s x, y, width, height.
    pub viewport: [i32; 4],
    /// `glDepthRange(near, far)`.
    pub depth_range: [f64; 2],
}

impl Gl {
    /// Sets `glViewport` and `glDepthRange` from `window`, and the scissor box to the viewport so
    /// that clears touch only it (they stay until changed; the target helpers reset the
    /// viewport to the whole target and turn the scissor test off).
    ///
    /// # Errors
    /// A GL error.
    pub fn set_window(&mut self, window: &Window) -> Result<(), String> {
        let [x, y, w, h] = window.viewport;
        unsafe {
            self.gl.viewport(x, y, w, h);
            self.gl.scissor(x, y, w, h);
            self.gl.enable(glow::SCISSOR_TEST);
            self.gl
                .depth_range_f64(window.depth_range[0], window.depth_range[1]);
        }
        self.check("glViewport/glDepthRange")
    }

    /// Draws `triangles` (world-space vertices, three per triangle) through
    /// `gl_Position = proj * (view * vec4(world, 1))` in flat `color`, with `state`'s depth
    /// func, masks and polygon offset.
    ///
    /// # Errors
    /// No target, a shader failure, or a GL error.
    pub fn draw_world(
        &mut self,
        triangles: &[[f32; 3]],
        view: &[f32; 16],
        proj: &[f32; 16],
        color: [f32; 4],
        state: &DrawState,
    ) -> Result<(), String> {
        self.require_target()?;
        if self.world.is_none() {
            self.world =
                Some(unsafe { crate::flat_colour_pipeline(&self.gl, WORLD_VERTEX_SHADER)? });
        }
        let (program, vao, vbo) = self.world.expect("made above");
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|v| v.to_ne_bytes())
            .collect();
        let gl = &self.gl;
        unsafe {
            gl.use_program(Some(program));
            gl.bind_vertex_array(Some(vao));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STREAM_DRAW);
            let v = gl.get_uniform_location(program, "view");
            gl.uniform_matrix_4_f32_slice(v.as_ref(), false, view);
            let p = gl.get_uniform_location(program, "proj");
            gl.uniform_matrix_4_f32_slice(p.as_ref(), false, proj);
            let c = gl.get_uniform_location(program, "color");
            gl.uniform_4_f32(c.as_ref(), color[0], color[1], color[2], color[3]);
            self.apply(state);
            gl.draw_arrays(glow::TRIANGLES, 0, triangles.len() as i32);
            gl.bind_vertex_array(None);
            gl.use_program(None);
        }
        self.check("draw_world")
    }
}

/// A mesh decal as an engine's decal system builds it: every triangle clipped to the square
/// `[x0, x1, z0, z1]` in world x and z, all in f32 (Sutherland–Hodgman, each new vertex
/// `a + t·(b − a)` on an edge of the ground's own triangle), each piece as a fan; with the index
/// of the triangle it came from. Its vertices lie on their triangle's plane only up to those
/// roundings, relative to the triangle's coordinates.
pub fn clip_to_square(triangles: &[[f32; 3]], square: [f32; 4]) -> Vec<(usize, Vec<[f32; 3]>)> {
    let [x0, x1, z0, z1] = square;
    // (coordinate, bound, keep the side above the bound)
    let planes = [(0, x0, true), (0, x1, false), (2, z0, true), (2, z1, false)];
    let mut out = Vec::new();
    for (index, t) in triangles.chunks_exact(3).enumerate() {
        let outside = planes.iter().any(|&(k, bound, above)| {
            t.iter()
                .all(|p| if above { p[k] < bound } else { p[k] > bound })
        });
        if outside {
            continue;
        }
        let mut poly: Vec<[f32; 3]> = t.to_vec();
        for &(k, bound, above) in &planes {
            let inside = |p: &[f32; 3]| if above { p[k] >= bound } else { p[k] <= bound };
            let mut next = Vec::new();
            for i in 0..poly.len() {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                if inside(&a) {
                    next.push(a);
                }
                if inside(&a) != inside(&b) {
                    let t = (bound - a[k]) / (b[k] - a[k]);
                    let mut p = [0, 1, 2].map(|j| a[j] + t * (b[j] - a[j]));
                    p[k] = bound;
                    next.push(p);
                }
            }
            poly = next;
            if poly.len() < 3 {
                break;
            }
        }
        let piece: Vec<[f32; 3]> = (1..poly.len().saturating_sub(1))
            .flat_map(|i| [poly[0], poly[i], poly[i + 1]])
            .collect();
        if !piece.is_empty() {
            out.push((index, piece));
        }
    }
    out
}

/// Eye coordinates of the world point `p` for a camera at `camera` turned by `rotation`
/// (world → eye, rows: right, up, back), in f64.
pub fn eye_of(rotation: &[[f64; 3]; 3], camera: [f64; 3], p: [f64; 3]) -> [f64; 3] {
    let d = [0, 1, 2].map(|k| p[k] - camera[k]);
    rotation.map(|row| row[0] * d[0] + row[1] * d[1] + row[2] * d[2])
}

/// The f32 view matrix (column-major) of that camera, built in f64 as an engine's math library
/// would and rounded once.
pub fn view_matrix(rotation: &[[f64; 3]; 3], camera: [f64; 3]) -> [f32; 16] {
    let mut m = [0.0f32; 16];
    for i in 0..3 {
        for j in 0..3 {
            m[4 * j + i] = rotation[i][j] as f32;
        }
        let r = rotation[i];
        m[12 + i] = -(r[0] * camera[0] + r[1] * camera[1] + r[2] * camera[2]) as f32;
    }
    m[15] = 1.0;
    m
}

/// The rotation world → eye (rows: right, up, back) of a camera looking along `forward` (a unit
/// vector, not vertical) with world y up.
pub fn looking_along(forward: [f64; 3]) -> [[f64; 3]; 3] {
    let n = (forward[2] * forward[2] + forward[0] * forward[0]).sqrt();
    let right = [-forward[2] / n, 0.0, forward[0] / n];
    let up = [
        right[1] * forward[2] - right[2] * forward[1],
        right[2] * forward[0] - right[0] * forward[2],
        right[0] * forward[1] - right[1] * forward[0],
    ];
    [right, up, forward.map(|c| -c)]
}

/// The model-view `V·M` of f32 matrices (column-major) as an engine multiplies it on the CPU: in
/// f32 as glm's `mat4 * mat4` does (each element a sum of four f32 products, left to right), or
/// (`in_f32` false) in f64 and rounded once, as `glm::dmat4` then a conversion to float.
pub fn model_view(v: &[f32; 16], m: &[f32; 16], in_f32: bool) -> [f32; 16] {
    std::array::from_fn(|i| {
        let (col, row) = (i / 4, i % 4);
        let term = |k: usize| (v[4 * k + row], m[4 * col + k]);
        if in_f32 {
            (0..4).fold(0.0f32, |acc, k| acc + term(k).0 * term(k).1)
        } else {
            (0..4)
                .map(|k| f64::from(term(k).0) * f64::from(term(k).1))
                .sum::<f64>() as f32
        }
    })
}

/// The point `p` through the f32 affine matrix `m` (column-major), in f64.
pub fn transformed(m: &[f32; 16], p: [f32; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| {
        (0..3)
            .map(|k| f64::from(m[4 * k + r]) * f64::from(p[k]))
            .sum::<f64>()
            + f64::from(m[12 + r])
    })
}

/// The box `[lo, hi]` of points.
pub fn bounding_box(points: &[[f64; 3]]) -> [[f64; 3]; 2] {
    let lo = [0, 1, 2].map(|k| points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
    let hi = [0, 1, 2].map(|k| {
        points
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max)
    });
    [lo, hi]
}

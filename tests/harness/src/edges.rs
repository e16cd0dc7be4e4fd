//! Edges drawn over their own faces, and the exact reference they are counted against: shared
//! by `tests/gl_lines.rs` (the sweep of `zshift::lines`) and the demonstration's edges picture
//! (`cargo run --release -p zshift-demo -- --edges DIR`), so that both count the same pixels.
//!
//! **Reference** (f64, from the f32 vertices and the f64 matrix, nothing from zshift): an exact
//! z-buffer of the faces at every pixel centre (which triangle is in front and its `1/d`,
//! [`reference()`]), and for every edge that drew a pixel (two ID renders with `gl_PrimitiveID`,
//! forward and reversed order, [`edge_ids`]) its exact depth at the pixel (the point of the edge
//! at the pixel's major-axis coordinate). [`classify`] sorts the pixels: **visible** when the
//! front face contains the edge, or the edge is in front of the front face; **hidden beyond the
//! gap** when every edge that drew it lies behind the front face by more than a gap (eye depth).
//! Pixels on faces steeper than the face-slope limit, of edges whose own gradient along the line
//! exceeds it or that border a face steeper than it, and within 2 pixels of a vertex (where more
//! than two edges meet) are not counted. [`Scene::count`] draws the faces filled and the edges
//! over them ([`Draw`]: an offset on the faces, or the edges' own matrix), reads the colour back
//! with `glReadPixels` and counts the visible pixels lost and the hidden ones shown.
//!
//! Faces are drawn `GL_LESS` (`GL_GREATER` under reversed Z), edges `GL_LEQUAL` (`GL_GEQUAL`),
//! into a [`SIZE`]² target of the [`Gl`]; the vertex shader computes `proj * vec4(eye, 1)`, or
//! for a mesh loaded in world space ([`Scene::view`]) `proj * (view * vec4(p, 1))`.

use glow::HasContext;

use crate::DepthFormat;
use crate::Gl;

pub mod meshes;

pub use meshes::Mesh;

/// The side of every edge scene's target, in pixels.
pub const SIZE: u32 = 256;
/// The faces' flat colour.
pub const FACE: [u8; 3] = [0, 0, 255];
/// The edges' flat colour.
pub const EDGE: [u8; 3] = [255, 255, 255];

/// Eye-space positions through the projection, or (`world` 1) world-space positions through the
/// f32 view matrix first, as engines draw (`proj * (view * p)`).
const VS: &str = "#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 proj;
uniform mat4 view;
uniform int world;
void main() {
    gl_Position = world == 1 ? proj * (view * vec4(position, 1.0)) : proj * vec4(position, 1.0);
}
";

/// A flat colour (`id_mode` 0), or the primitive's ID + 1 in RGB, in drawing order (1) or
/// reversed (2), so that two renders see both of two primitives that share a pixel.
const FS: &str = "#version 330 core
uniform vec4 color;
uniform int id_mode;
uniform int id_count;
out vec4 frag;
void main() {
    if (id_mode == 0) { frag = color; return; }
    int id = id_mode == 1 ? gl_PrimitiveID : id_count - 1 - gl_PrimitiveID;
    id += 1;
    frag = vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), 255.0) / 255.0;
}
";

/// For the polygon-mode ID renders: passes each triangle through with a one-hot weight per
/// corner, so a fragment of an outline knows its side (the corner off the side interpolates
/// two zeros: exactly 0 along the whole side, its wide-line quad and ends included).
const GS_SIDES: &str = "#version 330 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
noperspective out vec3 corner;
void main() {
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
        corner = vec3(i == 0, i == 1, i == 2);
        gl_PrimitiveID = gl_PrimitiveIDIn;
        EmitVertex();
    }
    EndPrimitive();
}
";

/// The outline's triangle and side: `3·triangle + side + 1` in RGB (side 0 from corner 0 to 1,
/// 1 from 1 to 2, 2 from 2 to 0, as [`Mesh::tri_edges`]), in drawing order (`id_mode` 1) or
/// reversed (2).
const FS_SIDES: &str = "#version 330 core
noperspective in vec3 corner;
uniform int id_mode;
uniform int id_count;
out vec4 frag;
void main() {
    int side = corner.z == 0.0 ? 0 : (corner.x == 0.0 ? 1 : 2);
    int tri = id_mode == 1 ? gl_PrimitiveID : id_count - 1 - gl_PrimitiveID;
    int id = 3 * tri + side + 1;
    frag = vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), 255.0) / 255.0;
}
";

/// The exact geometry of a mesh under a frustum: window x, y and 1/d of every vertex.
pub struct Projected {
    /// Window x, y of every vertex.
    pub xy: Vec<[f64; 2]>,
    /// 1/d (d the eye distance) of every vertex: affine in window space.
    pub inv_d: Vec<f64>,
    /// Pixels whose centre is within 2 pixels (each axis) of a vertex.
    pub near_vertex: Vec<bool>,
}

/// `mesh` through the f64 matrix `m` (a perspective projection) into the [`SIZE`]² viewport.
pub fn project(mesh: &Mesh, m: &[f64; 16]) -> Projected {
    let eye: Vec<[f64; 3]> = mesh.verts.iter().map(|v| v.map(f64::from)).collect();
    project_points(&eye, m)
}

/// [`project`] of the mesh's vertices at the eye positions `eye` (f64: the exact eye positions of
/// a mesh drawn in world space, its f32 world positions through its f32 view matrix).
pub fn project_points(eye: &[[f64; 3]], m: &[f64; 16]) -> Projected {
    let s = f64::from(SIZE);
    let mut xy = Vec::new();
    let mut inv_d = Vec::new();
    for &[x, y, z] in eye {
        let w = -z;
        let xn = (m[0] * x + m[8] * z) / w;
        let yn = (m[5] * y + m[9] * z) / w;
        xy.push([(xn + 1.0) * s / 2.0, (yn + 1.0) * s / 2.0]);
        inv_d.push(1.0 / w);
    }
    let n = SIZE as usize;
    let mut near_vertex = vec![false; n * n];
    for v in &xy {
        let (x0, x1) = (
            (v[0] - 2.5).ceil().max(0.0),
            (v[0] + 1.5).floor().min(n as f64 - 1.0),
        );
        let (y0, y1) = (
            (v[1] - 2.5).ceil().max(0.0),
            (v[1] + 1.5).floor().min(n as f64 - 1.0),
        );
        if x0 > x1 || y0 > y1 {
            continue;
        }
        for y in y0 as usize..=y1 as usize {
            for x in x0 as usize..=x1 as usize {
                // |v − (x + 0.5)| < 2 on each axis.
                if (v[0] - x as f64 - 0.5).abs() < 2.0 && (v[1] - y as f64 - 0.5).abs() < 2.0 {
                    near_vertex[y * n + x] = true;
                }
            }
        }
    }
    Projected {
        xy,
        inv_d,
        near_vertex,
    }
}

/// The reference z-buffer: per pixel the front triangle and its 1/d at the centre; per triangle
/// the gradient of 1/d per pixel.
pub struct Reference {
    /// The front triangle at each pixel and its 1/d, `None` where no face covers it.
    pub front: Vec<Option<(usize, f64)>>,
    /// The largest per-pixel gradient of 1/d of each triangle, along x or y.
    pub tri_grad: Vec<f64>,
    /// The length of each triangle's per-pixel gradient of 1/d.
    pub tri_len: Vec<f64>,
}

/// The reference of `mesh` at `off` within each pixel (its centre, or an MSAA sample).
pub fn reference(mesh: &Mesh, p: &Projected, off: [f64; 2]) -> Reference {
    let n = SIZE as usize;
    let mut front: Vec<Option<(usize, f64)>> = vec![None; n * n];
    let mut tri_grad = Vec::new();
    let mut tri_len = Vec::new();
    for (t, tri) in mesh.tris.iter().enumerate() {
        let [a, b, c] = tri.map(|i| i as usize);
        let (pa, pb, pc) = (p.xy[a], p.xy[b], p.xy[c]);
        let area = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pc[0] - pa[0]) * (pb[1] - pa[1]);
        let (ia, ib, ic) = (p.inv_d[a], p.inv_d[b], p.inv_d[c]);
        if area == 0.0 {
            tri_grad.push(f64::INFINITY);
            tri_len.push(f64::INFINITY);
            continue;
        }
        // 1/d is affine on screen: gradient from the three vertices.
        let gx = ((ib - ia) * (pc[1] - pa[1]) - (ic - ia) * (pb[1] - pa[1])) / area;
        let gy = ((ic - ia) * (pb[0] - pa[0]) - (ib - ia) * (pc[0] - pa[0])) / area;
        tri_grad.push(gx.abs().max(gy.abs()));
        tri_len.push(gx.hypot(gy));
        let x0 = pa[0].min(pb[0]).min(pc[0]).floor().max(0.0) as usize;
        let x1 = (pa[0].max(pb[0]).max(pc[0]).ceil() as usize).min(n);
        let y0 = pa[1].min(pb[1]).min(pc[1]).floor().max(0.0) as usize;
        let y1 = (pa[1].max(pb[1]).max(pc[1]).ceil() as usize).min(n);
        for y in y0..y1 {
            for x in x0..x1 {
                let q = [x as f64 + off[0], y as f64 + off[1]];
                let w0 = ((pb[0] - q[0]) * (pc[1] - q[1]) - (pc[0] - q[0]) * (pb[1] - q[1])) / area;
                let w1 = ((pc[0] - q[0]) * (pa[1] - q[1]) - (pa[0] - q[0]) * (pc[1] - q[1])) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let inv = w0 * ia + w1 * ib + w2 * ic;
                let slot = &mut front[y * n + x];
                if slot.is_none_or(|(_, best)| inv > best) {
                    *slot = Some((t, inv));
                }
            }
        }
    }
    Reference {
        front,
        tri_grad,
        tri_len,
    }
}

/// 1/d of edge `e` at the major-axis coordinate of the pixel's sample point (`off` within the
/// pixel: its centre, or an MSAA sample), and its along-line 1/d gradient per major-axis pixel.
pub fn edge_at(
    mesh: &Mesh,
    p: &Projected,
    e: usize,
    x: usize,
    y: usize,
    off: [f64; 2],
) -> (f64, f64) {
    let [a, b] = mesh.edges[e].map(|i| i as usize);
    let (pa, pb) = (p.xy[a], p.xy[b]);
    let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
    let (t, major) = if dx.abs() >= dy.abs() {
        ((x as f64 + off[0] - pa[0]) / dx, dx.abs())
    } else {
        ((y as f64 + off[1] - pa[1]) / dy, dy.abs())
    };
    let t = t.clamp(0.0, 1.0);
    let inv = p.inv_d[a] + t * (p.inv_d[b] - p.inv_d[a]);
    (inv, (p.inv_d[b] - p.inv_d[a]).abs() / major.max(1e-9))
}

/// The edge scenes' GL objects: one program (flat colour or primitive IDs), a vertex array,
/// the mesh's vertex buffer and an index buffer refilled at each draw.
pub struct Renderer {
    program: glow::Program,
    /// The polygon-mode ID program: each fragment's triangle and side ([`GS_SIDES`]).
    sides: glow::Program,
    vao: glow::VertexArray,
    vbo: glow::Buffer,
    ebo: glow::Buffer,
}

impl Renderer {
    /// The program and buffers, in `gl`'s current context.
    pub fn new(gl: &glow::Context) -> Renderer {
        unsafe {
            let program = crate::link_program(gl, VS, FS).unwrap_or_else(|e| panic!("{e}"));
            let sides = crate::link_stages(
                gl,
                &[
                    (glow::VERTEX_SHADER, VS),
                    (glow::GEOMETRY_SHADER, GS_SIDES),
                    (glow::FRAGMENT_SHADER, FS_SIDES),
                ],
            )
            .unwrap_or_else(|e| panic!("{e}"));
            let vao = gl.create_vertex_array().unwrap();
            let vbo = gl.create_buffer().unwrap();
            let ebo = gl.create_buffer().unwrap();
            gl.bind_vertex_array(Some(vao));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 12, 0);
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(ebo));
            Renderer {
                program,
                sides,
                vao,
                vbo,
                ebo,
            }
        }
    }

    /// Loads `mesh`'s vertices (the index buffers come with each draw).
    pub fn load(&self, gl: &glow::Context, mesh: &Mesh) {
        self.load_positions(gl, &mesh.verts);
    }

    /// Loads positions for the mesh's indices: its eye-space vertices, or its world-space ones
    /// (drawn with a view matrix, [`Scene::view`]).
    pub fn load_positions(&self, gl: &glow::Context, positions: &[[f32; 3]]) {
        let bytes: Vec<u8> = positions
            .iter()
            .flatten()
            .flat_map(|v| v.to_ne_bytes())
            .collect();
        unsafe {
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(self.vbo));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
        }
    }

    /// Draws `indices` as `mode` (`TRIANGLES` or `LINES`) with `proj` (after `view` for
    /// world-space positions); `id` 0 flat colour, 1/2 primitive IDs forward / reversed.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &self,
        gl: &glow::Context,
        indices: &[u32],
        mode: u32,
        proj: &[f32; 16],
        view: Option<&[f32; 16]>,
        color: [u8; 3],
        id: i32,
        count: i32,
    ) {
        let bytes: Vec<u8> = indices.iter().flat_map(|v| v.to_ne_bytes()).collect();
        // Triangles' IDs name the side too (polygon-mode outlines).
        let program = if id != 0 && mode == glow::TRIANGLES {
            self.sides
        } else {
            self.program
        };
        unsafe {
            gl.use_program(Some(program));
            gl.bind_vertex_array(Some(self.vao));
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(self.ebo));
            gl.buffer_data_u8_slice(glow::ELEMENT_ARRAY_BUFFER, &bytes, glow::STREAM_DRAW);
            let p = gl.get_uniform_location(program, "proj");
            gl.uniform_matrix_4_f32_slice(p.as_ref(), false, proj);
            let w = gl.get_uniform_location(program, "world");
            gl.uniform_1_i32(w.as_ref(), i32::from(view.is_some()));
            if let Some(view) = view {
                let v = gl.get_uniform_location(program, "view");
                gl.uniform_matrix_4_f32_slice(v.as_ref(), false, view);
            }
            let c = gl.get_uniform_location(program, "color");
            let [r, g, b] = color.map(|x| f32::from(x) / 255.0);
            gl.uniform_4_f32(c.as_ref(), r, g, b, 1.0);
            let m = gl.get_uniform_location(program, "id_mode");
            gl.uniform_1_i32(m.as_ref(), id);
            let k = gl.get_uniform_location(program, "id_count");
            gl.uniform_1_i32(k.as_ref(), count);
            gl.draw_elements(mode, indices.len() as i32, glow::UNSIGNED_INT, 0);
        }
    }
}

/// How one scene's faces and edges are drawn.
#[derive(Clone, Copy)]
pub struct Draw {
    /// `glPolygonOffset(factor, units)` on the faces (signs as passed to GL), or none.
    pub face_offset: Option<(f32, f32)>,
    /// The edges' projection matrix (the faces' own, or one pulled toward the camera).
    pub edge_matrix: [f32; 16],
}

/// Pixels (single-sampled) or samples (MSAA) to count in a scene: indices into the image of
/// every sample plane laid end to end (`sample · SIZE² + pixel`).
pub struct Classes {
    /// Visible edge pixels: they must show an edge.
    pub visible: Vec<usize>,
    /// Hidden edge pixels beyond the gap [`classify`] was given: they must not.
    pub hidden: Vec<usize>,
    /// Edge pixels (samples) left unjudged on a boundary of their front face
    /// ([`BOUNDARY_TIE`]).
    pub ties: usize,
}

/// How close (pixels) to a side of its exact front face a pixel centre or sample lies for the
/// rasterizer to give it to the face across that side: 1/128, twice llvmpipe's 1/256-pixel
/// coverage grid. Where the face across borders none of the edges drawn there, [`classify`]
/// does not judge the sample: the model keeps an edge over the faces it borders, and which of
/// the two faces covers a sample on their common side is the rasterizer's tie. Measured:
/// `ZSHIFT_LINES_SEED=4`, a sphere's sample 0.001 pixel inside its exact front face (a steep
/// one) and 0.2 pixel from the end of that face's edges, covered by the shallower face across
/// the side, whose push under (a) is a third of the steep face's: it lost the steep face's
/// edges with the worst case and the probed profile, for `GL_LINES` and polygon-mode lines
/// under MSAA (the polygon-mode `+ 1` of the MSAA reach had been set from it).
pub const BOUNDARY_TIE: f64 = 1.0 / 128.0;

/// What the edges are drawn as.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    /// `GL_LINES`, one per edge.
    Lines,
    /// The faces again in `glPolygonMode(GL_LINE)`.
    PolygonMode,
}

/// How the edges are drawn: kind, width, MSAA samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variant {
    /// `GL_LINES` or polygon-mode lines.
    pub kind: Primitive,
    /// `glLineWidth`.
    pub width: f32,
    /// MSAA samples (1: single-sampled).
    pub samples: u32,
}

/// The widest a GL rasterizer draws a line asked `width` pixels wide: GL rounds an aliased
/// line's width to the nearest integer (OpenGL 4.6 compatibility profile, 14.5.2.1) and a
/// width halfway may go up (2.5 drawn 3 wide), so the larger of `width` and `⌊width + ½⌋`.
/// The harness's own statement of GL's rule, not read from the library.
pub fn drawn_width(width: f32) -> f64 {
    let w = f64::from(width);
    w.max((w + 0.5).floor())
}

impl Variant {
    /// The sweep's label: `lines`, `polymode`, then ` w<width>` and ` <n>xMSAA` where not 1.
    pub fn name(self) -> String {
        let mut s = String::from(match self.kind {
            Primitive::Lines => "lines",
            Primitive::PolygonMode => "polymode",
        });
        if self.width != 1.0 {
            s += &format!(" w{}", self.width);
        }
        if self.samples > 1 {
            s += &format!(" {}xMSAA", self.samples);
        }
        s
    }
}

/// A 4× multisampled target (colour texture, depth renderbuffer of the sweep's format), read
/// back one sample at a time ([`crate::msaa`]: a full-screen pass copies sample `s`, a
/// `texelFetch` of a `sampler2DMS`, no averaging, into a single-sampled FBO), so every sample is
/// counted on its own against the reference at its own position (`GL_SAMPLE_POSITION`).
pub struct Msaa {
    fbo: glow::Framebuffer,
    depth: glow::Renderbuffer,
    /// The single-sampled colour a sample is copied into.
    copy_color: glow::Renderbuffer,
    samples: crate::msaa::Samples,
    /// The harness's target, bound again after each read.
    target: glow::Framebuffer,
    /// Each sample's position within its pixel.
    pub positions: Vec<[f64; 2]>,
}

impl Msaa {
    /// A `samples`× target of `fmt` beside `gl`'s own, which stays bound.
    pub fn new(gl: &Gl, fmt: DepthFormat, samples: u32) -> Msaa {
        let g = gl.glow();
        let n = SIZE as i32;
        unsafe {
            let target = g
                .get_parameter_framebuffer(glow::DRAW_FRAMEBUFFER_BINDING)
                .expect("the harness's target is bound");
            let copy_color = g.create_renderbuffer().unwrap();
            g.bind_renderbuffer(glow::RENDERBUFFER, Some(copy_color));
            g.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, n, n);
            let fbo = g.create_framebuffer().unwrap();
            g.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
            let colour = crate::msaa::Samples::new(g, fbo, copy_color, n, n, samples)
                .unwrap_or_else(|e| panic!("{e}"));
            let depth = g.create_renderbuffer().unwrap();
            g.bind_renderbuffer(glow::RENDERBUFFER, Some(depth));
            g.renderbuffer_storage_multisample(
                glow::RENDERBUFFER,
                samples as i32,
                fmt.gl_enum(),
                n,
                n,
            );
            g.framebuffer_renderbuffer(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                glow::RENDERBUFFER,
                Some(depth),
            );
            let status = g.check_framebuffer_status(glow::FRAMEBUFFER);
            assert_eq!(status, glow::FRAMEBUFFER_COMPLETE, "MSAA FBO {fmt:?}");
            assert_eq!(
                g.get_parameter_i32(glow::SAMPLES),
                samples as i32,
                "MSAA samples"
            );
            type GetMultisample = extern "system" fn(u32, u32, *mut f32);
            let f = gl.proc_address("glGetMultisamplefv");
            assert!(!f.is_null(), "glGetMultisamplefv");
            // SAFETY: EGL returned this entry point for the current context.
            let get: GetMultisample = std::mem::transmute(f);
            let positions = (0..samples)
                .map(|i| {
                    let mut v = [0f32; 2];
                    get(0x8E50, i, v.as_mut_ptr());
                    [f64::from(v[0]), f64::from(v[1])]
                })
                .collect();
            g.bind_framebuffer(glow::FRAMEBUFFER, Some(target));
            gl.check("MSAA target").unwrap();
            Msaa {
                fbo,
                depth,
                copy_color,
                samples: colour,
                target,
                positions,
            }
        }
    }

    /// Binds the multisampled target for drawing (for other passes than an edge [`Scene`]'s;
    /// [`Msaa::read_samples`] binds the harness's target again).
    pub fn bind(&self, gl: &Gl) {
        unsafe {
            gl.glow()
                .bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo))
        };
    }

    /// Every sample of the multisampled colour, laid end to end; the harness's target bound
    /// again.
    pub fn read_samples(&self, gl: &Gl) -> Vec<[u8; 4]> {
        let g = gl.glow();
        // SAFETY: this context is current (Gl's invariant) and owns these objects.
        unsafe {
            let out = self.samples.read_at(g, [0, 0], SIZE, SIZE);
            g.bind_framebuffer(glow::FRAMEBUFFER, Some(self.target));
            out
        }
    }

    /// Deletes the target's objects; `gl`'s own target bound.
    pub fn delete(self, gl: &Gl) {
        let g = gl.glow();
        unsafe {
            g.bind_framebuffer(glow::FRAMEBUFFER, Some(self.target));
            g.delete_framebuffer(self.fbo);
            g.delete_renderbuffer(self.depth);
            g.delete_renderbuffer(self.copy_color);
        }
        self.samples.delete(g);
    }
}

/// One mesh drawn one way in one context: what [`Scene::render`] and [`Scene::count`] draw.
pub struct Scene<'a> {
    /// The context, its target of the scene's depth format bound.
    pub gl: &'a Gl,
    /// The program and buffers, `mesh` loaded ([`Renderer::load`]).
    pub r: &'a Renderer,
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The faces' projection matrix.
    pub m: [f32; 16],
    /// Reversed Z: clear to 0, faces `GL_GREATER`, edges `GL_GEQUAL`.
    pub reversed: bool,
    /// How the edges are drawn.
    pub variant: Variant,
    /// The multisampled target under MSAA.
    pub msaa: Option<&'a Msaa>,
    /// The triangles' indices, laid end to end.
    pub tri_idx: Vec<u32>,
    /// The edges' indices, laid end to end.
    pub line_idx: Vec<u32>,
    /// The f32 view matrix of a mesh loaded in world space ([`Renderer::load_positions`]), or
    /// `None`: eye-space vertices.
    pub view: Option<[f32; 16]>,
    /// The viewport's lower-left corner in the target (the caller sets `glViewport` and
    /// `glDepthRange`): where [`Scene::read`] reads the [`SIZE`]² image (single-sampled only).
    pub origin: [u32; 2],
}

impl<'a> Scene<'a> {
    /// `mesh` (loaded into `r`) with the index lists of its triangles and edges.
    pub fn new(
        gl: &'a Gl,
        r: &'a Renderer,
        mesh: &'a Mesh,
        m: [f32; 16],
        reversed: bool,
        variant: Variant,
        msaa: Option<&'a Msaa>,
    ) -> Scene<'a> {
        Scene {
            gl,
            r,
            mesh,
            m,
            reversed,
            variant,
            msaa,
            tri_idx: mesh.tris.iter().flatten().copied().collect(),
            line_idx: mesh.edges.iter().flatten().copied().collect(),
            view: None,
            origin: [0, 0],
        }
    }

    /// Where each sample plane of [`Scene::read`] takes its depth: the pixel centre, or the
    /// MSAA sample positions.
    pub fn offsets(&self) -> Vec<[f64; 2]> {
        match self.msaa {
            Some(ms) => ms.positions.clone(),
            None => vec![[0.5, 0.5]],
        }
    }

    /// Binds the multisampled target (if any) for the draws of [`Scene::read`].
    pub fn begin(&self) {
        if let Some(ms) = self.msaa {
            unsafe {
                self.gl
                    .glow()
                    .bind_framebuffer(glow::FRAMEBUFFER, Some(ms.fbo))
            };
        }
    }

    /// The image of every sample plane.
    pub fn read(&self) -> Vec<[u8; 4]> {
        match self.msaa {
            Some(ms) => ms.read_samples(self.gl),
            None => read_at(self.gl, self.origin),
        }
    }

    /// Draws the faces filled with the faces' matrix: flat colour (`id` 0) or primitive IDs
    /// (1/2, of `count` triangles).
    fn draw_faces(&self, id: i32, count: i32) {
        let g = self.gl.glow();
        let view = self.view.as_ref();
        self.r.draw(
            g,
            &self.tri_idx,
            glow::TRIANGLES,
            &self.m,
            view,
            FACE,
            id,
            count,
        );
    }

    /// Draws the edges (`GL_LINES` or the faces in `GL_LINE` mode) at the variant's width.
    pub fn draw_edges(&self, indices: &[u32], proj: &[f32; 16], id: i32, count: i32) {
        let g = self.gl.glow();
        unsafe { g.line_width(self.variant.width) };
        match self.variant.kind {
            Primitive::Lines => self.r.draw(
                g,
                indices,
                glow::LINES,
                proj,
                self.view.as_ref(),
                EDGE,
                id,
                count,
            ),
            Primitive::PolygonMode => unsafe {
                g.polygon_mode(glow::FRONT_AND_BACK, glow::LINE);
                self.r.draw(
                    g,
                    indices,
                    glow::TRIANGLES,
                    proj,
                    self.view.as_ref(),
                    EDGE,
                    id,
                    count,
                );
                g.polygon_mode(glow::FRONT_AND_BACK, glow::FILL);
            },
        }
        unsafe { g.line_width(1.0) };
    }

    /// The faces filled, then the edges over them, drawn as `d` says: the image of every
    /// sample plane.
    pub fn render(&self, d: &Draw) -> Vec<[u8; 4]> {
        let g = self.gl.glow();
        let reversed = self.reversed;
        self.begin();
        unsafe {
            g.color_mask(true, true, true, true);
            g.depth_mask(true);
            g.clear_color(0.0, 0.0, 0.0, 1.0);
            g.clear_depth_f64(if reversed { 0.0 } else { 1.0 });
            g.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            g.enable(glow::DEPTH_TEST);
            g.polygon_mode(glow::FRONT_AND_BACK, glow::FILL);
            g.depth_func(if reversed { glow::GREATER } else { glow::LESS });
            match d.face_offset {
                Some((f, u)) => {
                    g.enable(glow::POLYGON_OFFSET_FILL);
                    g.polygon_offset(f, u);
                }
                None => g.disable(glow::POLYGON_OFFSET_FILL),
            }
        }
        self.draw_faces(0, 0);
        unsafe {
            g.disable(glow::POLYGON_OFFSET_FILL);
            g.depth_func(if reversed { glow::GEQUAL } else { glow::LEQUAL });
        }
        let idx = match self.variant.kind {
            Primitive::Lines => &self.line_idx,
            Primitive::PolygonMode => &self.tri_idx,
        };
        self.draw_edges(idx, &d.edge_matrix, 0, 0);
        self.read()
    }

    /// The front face the rasterizer keeps at each pixel (sample), as `id + 1` (0: none).
    pub fn face_ids(&self) -> Vec<usize> {
        let g = self.gl.glow();
        let reversed = self.reversed;
        self.begin();
        unsafe {
            g.color_mask(true, true, true, true);
            g.clear_color(0.0, 0.0, 0.0, 0.0);
            g.clear_depth_f64(if reversed { 0.0 } else { 1.0 });
            g.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            g.enable(glow::DEPTH_TEST);
            g.depth_func(if reversed { glow::GREATER } else { glow::LESS });
        }
        self.draw_faces(1, self.mesh.tris.len() as i32);
        self.read()
            .iter()
            .map(|px| px[0] as usize | (px[1] as usize) << 8 | (px[2] as usize) << 16)
            .collect()
    }

    /// Draws `d` and counts `c`'s visible pixels lost and hidden pixels shown.
    pub fn count(&self, d: &Draw, c: &Classes) -> (usize, usize) {
        count_in(&self.render(d), c)
    }
}

/// `c`'s visible pixels that show no edge (lost) and hidden ones that show one (shown) in `img`.
pub fn count_in(img: &[[u8; 4]], c: &Classes) -> (usize, usize) {
    let lost = c.visible.iter().filter(|&&i| img[i][..3] != EDGE).count();
    let shown = c.hidden.iter().filter(|&&i| img[i][..3] == EDGE).count();
    (lost, shown)
}

/// The target's colour, [`SIZE`]², rows bottom-up.
pub fn read(gl: &Gl) -> Vec<[u8; 4]> {
    read_at(gl, [0, 0])
}

/// The target's colour in the [`SIZE`]² square whose lower-left pixel is `origin`.
pub fn read_at(gl: &Gl, origin: [u32; 2]) -> Vec<[u8; 4]> {
    let n = SIZE as i32;
    let at = origin.map(|c| c as i32);
    // SAFETY: the harness's context is current on this thread.
    let pixels = unsafe { crate::read_rgba8_at(gl.glow(), at, n, n) };
    gl.check("glReadPixels").unwrap();
    pixels
}

/// The edges that drew each pixel (each sample under MSAA, laid end to end): two ID renders
/// (forward and reversed order).
pub fn edge_ids(scene: &Scene) -> Vec<Vec<usize>> {
    let g = scene.gl.glow();
    let n = SIZE as usize;
    let planes = scene.offsets().len();
    let mut ids = vec![Vec::new(); planes * n * n];
    let lines = scene.variant.kind == Primitive::Lines;
    for mode in [1, 2] {
        scene.begin();
        unsafe {
            g.color_mask(true, true, true, true);
            g.clear_color(0.0, 0.0, 0.0, 0.0);
            g.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            g.disable(glow::DEPTH_TEST);
        }
        let (idx, prims) = if lines {
            (&scene.line_idx, scene.mesh.edges.len())
        } else {
            (&scene.tri_idx, scene.mesh.tris.len())
        };
        let ordered: Vec<u32> = if mode == 1 {
            idx.clone()
        } else {
            let k = if lines { 2 } else { 3 };
            idx.chunks(k).rev().flatten().copied().collect()
        };
        scene.draw_edges(&ordered, &scene.m, mode, prims as i32);
        unsafe { g.enable(glow::DEPTH_TEST) };
        let img = scene.read();
        for (j, px) in img.iter().enumerate() {
            let id = px[0] as usize | (px[1] as usize) << 8 | (px[2] as usize) << 16;
            if id == 0 {
                continue;
            }
            let prim = id - 1;
            // A polygon-mode outline's ID names its triangle's side ([`FS_SIDES`]).
            let e = if lines {
                prim
            } else {
                scene.mesh.tri_edges[prim / 3][prim % 3]
            };
            if !ids[j].contains(&e) {
                ids[j].push(e);
            }
        }
    }
    ids
}

/// The distance (pixels) from `(x, y)` to edge `e` in the window.
pub fn seg_dist(mesh: &Mesh, p: &Projected, e: usize, x: f64, y: f64) -> f64 {
    let [a, b] = mesh.edges[e].map(|i| p.xy[i as usize]);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = (((x - a[0]) * dx + (y - a[1]) * dy) / (dx * dx + dy * dy).max(1e-300)).clamp(0.0, 1.0);
    ((a[0] + t * dx - x).powi(2) + (a[1] + t * dy - y).powi(2)).sqrt()
}

/// The faces an ask promises to keep the edges of: those whose per-pixel 1/d gradient is at
/// most the limit, by its larger component (a window-gradient limit, a mesh's own faces, and
/// a face-slope angle single-sampled, whose line term is `g·Δ` in pixels of that component) or
/// by its length (a face-slope angle under MSAA: its line term is `g·min(Δ, across)`, the
/// angle bounding a face's whole gradient; a face whose larger component is within `g` but
/// whose length is not is steeper than the angle).
#[derive(Clone, Copy, Debug)]
pub enum Limit {
    /// Faces whose larger gradient component is at most this.
    MaxComponent(f64),
    /// Faces whose gradient length is at most this.
    Length(f64),
}

impl Limit {
    /// The limit's gradient.
    pub fn gradient(self) -> f64 {
        match self {
            Limit::MaxComponent(g) | Limit::Length(g) => g,
        }
    }

    /// Triangle `t`'s gradient as this limit measures it.
    fn of(self, rf: &Reference, t: usize) -> f64 {
        match self {
            Limit::MaxComponent(_) => rf.tri_grad[t],
            Limit::Length(_) => rf.tri_len[t],
        }
    }
}

/// Visible and hidden-beyond-`gap` pixels, or samples under MSAA (module docs); `rfs` the
/// reference at each sample plane's position ([`Scene::offsets`]).
#[allow(clippy::too_many_arguments)]
pub fn classify(
    scene: &Scene,
    p: &Projected,
    rfs: &[Reference],
    ids: &[Vec<usize>],
    b: f64,
    limit: Limit,
    gap: f64,
) -> Classes {
    let g = limit.gradient();
    let steep = |rf: &Reference, t: usize| b * limit.of(rf, t) > g;
    let n = SIZE as usize;
    let near_vertex = |x: usize, y: usize| p.near_vertex[y * n + x];
    let offsets = scene.offsets();
    // How far (pixels) a line of the variant's width draws from its edge.
    let w = drawn_width(scene.variant.width);
    let reach = w / 2.0 + 1.0;
    let k = reach.ceil() as usize - 1;
    let (mut visible, mut hidden, mut ties) = (Vec::new(), Vec::new(), 0);
    for (j, edges) in ids.iter().enumerate() {
        if edges.is_empty() {
            continue;
        }
        let (plane, i) = (j / (n * n), j % (n * n));
        let (rf, off) = (&rfs[plane], offsets[plane]);
        let Some((t, inv_front)) = rf.front[i] else {
            continue;
        };
        if steep(rf, t) {
            continue;
        }
        let (x, y) = (i % n, i / n);
        let (sx, sy) = (x as f64 + off[0], y as f64 + off[1]);
        let on_boundary = scene.mesh.tri_edges[t].iter().any(|&side| {
            seg_dist(scene.mesh, p, side, sx, sy) < BOUNDARY_TIE
                && scene.mesh.edge_tris[side].iter().any(|&across| {
                    across != t
                        && !edges
                            .iter()
                            .any(|&e| scene.mesh.edge_tris[e].contains(&across))
                })
        });
        if on_boundary {
            ties += 1;
            continue;
        }
        let around = |r: usize| {
            (x.saturating_sub(r)..=(x + r).min(n - 1)).flat_map(move |xx| {
                (y.saturating_sub(r)..=(y + r).min(n - 1)).map(move |yy| yy * n + xx)
            })
        };
        let mut any_visible = false;
        let mut all_hidden = true;
        for &e in edges {
            let (inv_e, along) = edge_at(scene.mesh, p, e, x, y, off);
            let adjacent = scene.mesh.edge_tris[e].contains(&t);
            // An edge of other faces counts as in front only where it is nearer than the front
            // face by more than a line's reach of the slope limit: within that, its fragment
            // (taken up to the reach away, on its own faces' planes) may lie either side of the
            // front face, which the model does not promise (it keeps an edge over the faces it
            // borders).
            let in_front = inv_e >= inv_front + reach * g / b;
            // An edge of a face steeper than the limit is not guaranteed (the model's contract):
            // the rasterizer may keep that face at a pixel the exact reference gives to its
            // neighbour (measured: a sphere's grazing face at its shared edge, ZSHIFT_LINES_SEED=1).
            let steep_edge =
                b * along > g || scene.mesh.edge_tris[e].iter().any(|&tn| steep(rf, tn));
            if (adjacent || in_front) && !steep_edge {
                any_visible = true;
            }
            // Hidden beyond the gap at this pixel and its neighbours (an occluding fold whose
            // boundary crosses the pixel is not a place where the front face is known).
            let hidden_here = |jj: usize| match rf.front[jj] {
                Some((tj, inv_j)) => {
                    !scene.mesh.edge_tris[e].contains(&tj) && 1.0 / inv_e - 1.0 / inv_j > gap
                }
                None => false,
            };
            if adjacent || !around(k.max(1)).all(hidden_here) || steep_edge {
                all_hidden = false;
            }
        }
        // A visible edge (an edge of a front face of the pixel or a neighbour) within reach of
        // the pixel may have drawn it unseen by the two ID renders (three edges meet there).
        let visible_near = around(k.max(1))
            .filter_map(|jj| rf.front[jj])
            .any(|(tj, _)| {
                scene.mesh.tri_edges[tj]
                    .iter()
                    .any(|&e| seg_dist(scene.mesh, p, e, x as f64 + 0.5, y as f64 + 0.5) < reach)
            });
        if any_visible {
            visible.push(j);
        } else if all_hidden && !near_vertex(x, y) && !visible_near {
            hidden.push(j);
        }
    }
    Classes {
        visible,
        hidden,
        ties,
    }
}

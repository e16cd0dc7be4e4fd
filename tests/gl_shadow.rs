//! Shadow-map acne on a real rasterizer (headless EGL; Mesa llvmpipe in CI): zshift's
//! shadow bias (`zshift::shadow::shadow_bias`) against an exact reference, beside the engines'
//! defaults.
//!
//! Each scene: a 12 × 12 ground (two triangles, world space) with a 1.2 × 2 × 0.8 box standing on
//! it, lit by a directional (orthographic map fitted to the scene) or a spot light (perspective
//! map fitted to it) at 1°–89° elevation, light f/n 10 to 10⁵, maps of 256–2048 texels, D16, D24
//! and D32F under `[−1, 1]`, `[0, 1]` and reversed Z, read by a fragment shader with nearest
//! or 3×3 PCF lookups (manual `texelFetch` comparisons). A camera looks at the ground; for each
//! ground pixel the exact reference (f64: is the point's ray to the light blocked by the box?)
//! says lit or shadowed, and pixels within `a + 1.5` texels (in the map) of a change of that
//! answer are left out (shadow edges). **Acne**: a lit pixel the map darkens (any tap fails).
//! **Leak**: a shadowed pixel the map leaves fully lit (detachment, peter-panning).
//!
//! zshift's bias goes into the map as `glPolygonOffsetClamp(factor, units, clamp)` (its GL
//! output, with the worst-case and the probed profile), the limit angle being the ground's own
//! angle to the light (its axis for a spot); each from `world_reach` alone and with the light's
//! pipeline (its f32 view matrix, the scene's world box, eye-first: both shaders compute
//! `proj * (view * p)`). Every answered scene must show **0 acne pixels**;
//! every refusal must be a scene where bisection finds no acne-free bias below 1 (the map's
//! whole depth range). Bisection over a constant window bias in the lookup (map drawn without
//! bias) gives the smallest acne-free bias; the table prints zshift's bias on the ground ÷ that,
//! and the engines' defaults as `/work/shared/NOTES.md` describes them.
//!
//! Fails (never skips) without GL. `ZSHIFT_SHADOW_SCENES=full` runs every combination (slow);
//! the default a deterministic sample. `--nocapture` prints the table;
//! `ZSHIFT_SHADOW_VERBOSE=1` every scene.

mod gl_common;
// Receivers other than flat ground (a sphere, a terrain): a test of their own.
#[path = "gl_shadow/receivers.rs"]
mod receivers;

use glow::HasContext;
use zshift::orthographic::Ortho;
use zshift::projection::{ClipDepth, Frustum};
use zshift::recommend::RasterizerProfile;
use zshift::shadow::{shadow_bias, shadow_bias_for_receivers, LightProjection, Lookup, ShadowMap};
use zshift::ErrorKind;
use zshift_harness::{ClipDepth as GlClip, Gl, Profile};

const GROUND: f64 = 6.0;
/// The box: min and max corners.
const BOX: [[f64; 3]; 2] = [[0.2, 0.0, -0.9], [1.4, 2.0, -0.1]];
const CAMERA: usize = 160;
const AZIMUTH_DEG: f64 = 30.0;
/// The box of every world position the caster and lookup shaders transform: the ground and
/// the box standing on it.
const WORLD_BOX: [[f64; 3]; 2] = [[-GROUND, 0.0, -GROUND], [GROUND, BOX[1][1], GROUND]];
/// The limit angle passed with explicit receivers: it only skips receivers facing away by more.
const RECEIVER_LIMIT_DEG: f64 = 89.9;

type M4 = [f64; 16];

fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            m[4 * c + r] = (0..4).map(|k| a[4 * k + r] * b[4 * c + k]).sum();
        }
    }
    m
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 4] {
    [0, 1, 2, 3].map(|r| m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r])
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// A right-handed look-at view matrix (column-major), in f64.
fn look_at(eye: [f64; 3], at: [f64; 3], up: [f64; 3]) -> M4 {
    let f = norm(sub(at, eye));
    let s = norm(cross(f, up));
    let u = cross(s, f);
    [
        s[0],
        u[0],
        -f[0],
        0.0,
        s[1],
        u[1],
        -f[1],
        0.0,
        s[2],
        u[2],
        -f[2],
        0.0,
        -dot(s, eye),
        -dot(u, eye),
        dot(f, eye),
        1.0,
    ]
}

fn to_f32(m: &M4) -> [f32; 16] {
    m.map(|x| x as f32)
}

/// Does the segment from `p` in direction `dir` (up to `t_max`) hit the box? Slab test in f64.
fn blocked(p: [f64; 3], dir: [f64; 3], t_max: f64) -> bool {
    let (mut t0, mut t1): (f64, f64) = (1e-9, t_max);
    for k in 0..3 {
        if dir[k].abs() < 1e-300 {
            if p[k] < BOX[0][k] || p[k] > BOX[1][k] {
                return false;
            }
            continue;
        }
        let a = (BOX[0][k] - p[k]) / dir[k];
        let b = (BOX[1][k] - p[k]) / dir[k];
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Directional,
    Spot,
}

#[derive(Debug, Clone, Copy)]
struct Case {
    kind: Kind,
    elevation: f64,
    ratio: f64,
    resolution: u32,
    format: zshift_harness::DepthFormat,
    clip: ClipDepth,
    pcf: u32,
}

impl Case {
    /// The lookup zshift is told about.
    fn lookup(&self) -> Lookup {
        match self.pcf {
            1 => Lookup::Nearest,
            0 => Lookup::Hardware2x2,
            k => Lookup::Pcf(k),
        }
    }

    /// Texels per axis from the lookup point to the farthest texel centre the shader reads
    /// (this file's own statement of its lookups, for the reference's shadow-edge margin).
    fn kernel_reach(&self) -> f64 {
        match self.pcf {
            1 => 0.5,
            0 => 1.0,
            k => f64::from(k) / 2.0,
        }
    }

    /// The map as zshift is asked about it: the case's light, format, lookup and convention,
    /// the light's largest world coordinate as `world_reach`.
    fn shadow_map(
        &self,
        light: &Light,
        limit_angle_deg: f64,
        profile: RasterizerProfile,
        pipeline: zshift::model::Pipeline,
    ) -> ShadowMap {
        ShadowMap {
            light: light.projection,
            clip: self.clip,
            resolution: [self.resolution; 2],
            format: gl_common::format_of(self.format),
            lookup: self.lookup(),
            limit_angle_deg,
            receiver_depths: light.receivers,
            world_reach: light.position.iter().fold(0.0f64, |a, x| a.max(x.abs())),
            elevation_deg: self.elevation,
            profile,
            pipeline,
        }
    }

    fn label(&self) -> String {
        format!(
            "{:?} e={}° f/n={:e} {}² {} {:?} {}",
            self.kind,
            self.elevation,
            self.ratio,
            self.resolution,
            self.format.name(),
            self.clip,
            if self.pcf == 1 {
                "nearest".into()
            } else if self.pcf == 0 {
                "hardware 2x2".into()
            } else {
                format!("PCF{0}x{0}", self.pcf)
            }
        )
    }
}

/// The light of a case: its position, view and projection (f64), the map's texel size in
/// world units at the scene's centre, the ground's light-depth range, world reach.
struct Light {
    position: [f64; 3],
    to_light: [f64; 3],
    view: M4,
    proj: M4,
    proj32: [f32; 16],
    projection: LightProjection,
    receivers: [f64; 2],
    texel_world: f64,
    range: f64,
}

fn corners() -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for x in [-GROUND, GROUND] {
        for z in [-GROUND, GROUND] {
            v.push([x, 0.0, z]);
        }
    }
    for i in 0..8 {
        v.push([BOX[i & 1][0], BOX[(i >> 1) & 1][1], BOX[(i >> 2) & 1][2]]);
    }
    v
}

fn light_of(case: &Case) -> Light {
    let points = corners();
    light_for(case, &points, &points[..4])
}

/// The light of `case` fitted to `points` (every caster and receiver), with the receivers'
/// light-depth range taken over `receivers`.
fn light_for(case: &Case, points: &[[f64; 3]], receivers: &[[f64; 3]]) -> Light {
    let (e, a) = (case.elevation.to_radians(), AZIMUTH_DEG.to_radians());
    let to_light = [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()];
    let h = (2.0 * GROUND * GROUND).sqrt() + 2.0;
    let distance = 2.5 * h + 1.0;
    let position = to_light.map(|c| c * distance);
    let up = if case.elevation > 80.0 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let view = look_at(position, [0.0; 3], up);
    let eye: Vec<[f64; 4]> = points.iter().map(|&p| apply(&view, p)).collect();
    let depth = |p: &[f64; 4]| -p[2];
    let zmax = eye.iter().map(depth).fold(f64::MIN, f64::max);
    let ground: Vec<f64> = receivers.iter().map(|&p| depth(&apply(&view, p))).collect();
    let receivers = [
        ground.iter().cloned().fold(f64::MAX, f64::min) * (1.0 - 1e-6),
        ground.iter().cloned().fold(f64::MIN, f64::max) * (1.0 + 1e-6),
    ];
    let f = zmax * 1.02;
    let n = f / case.ratio;
    let (projection, proj, proj32, texel_world, range) = match case.kind {
        Kind::Directional => {
            let xs = eye.iter().map(|p| p[0].abs()).fold(0.0, f64::max) * 1.01;
            let ys = eye.iter().map(|p| p[1].abs()).fold(0.0, f64::max) * 1.01;
            let o = Ortho::new(-xs, xs, -ys, ys, n, f).unwrap();
            let m = zshift::orthographic::ortho_f64(&o, case.clip);
            let m32 = zshift::orthographic::ortho(&o, case.clip).unwrap();
            (
                LightProjection::Orthographic(o),
                m,
                m32,
                2.0 * xs.max(ys) / f64::from(case.resolution),
                f - n,
            )
        }
        Kind::Spot => {
            let tx = eye.iter().map(|p| p[0].abs() / -p[2]).fold(0.0, f64::max) * 1.01;
            let ty = eye.iter().map(|p| p[1].abs() / -p[2]).fold(0.0, f64::max) * 1.01;
            let fr = Frustum::new(-tx * n, tx * n, -ty * n, ty * n, n, f).unwrap();
            let m = zshift::projection::projection_f64(&fr, case.clip).unwrap();
            let m32 = zshift::projection::projection(&fr, case.clip).unwrap();
            (
                LightProjection::Perspective(fr),
                m,
                m32,
                2.0 * tx.max(ty) * distance / f64::from(case.resolution),
                f - n,
            )
        }
    };
    Light {
        position,
        to_light,
        view,
        proj,
        proj32,
        projection,
        receivers,
        texel_world,
        range,
    }
}

/// Ground and box triangles with their normals.
fn meshes() -> (Vec<[f32; 6]>, Vec<[f32; 6]>) {
    let g = GROUND as f32;
    let up = [0.0, 1.0, 0.0f32];
    let v = |p: [f32; 3], n: [f32; 3]| [p[0], p[1], p[2], n[0], n[1], n[2]];
    let ground = vec![
        v([-g, 0.0, -g], up),
        v([-g, 0.0, g], up),
        v([g, 0.0, g], up),
        v([-g, 0.0, -g], up),
        v([g, 0.0, g], up),
        v([g, 0.0, -g], up),
    ];
    let mut boxed = Vec::new();
    let c = |i: usize| -> [f32; 3] {
        [
            BOX[i & 1][0] as f32,
            BOX[(i >> 1) & 1][1] as f32,
            BOX[(i >> 2) & 1][2] as f32,
        ]
    };
    // Faces as corner indices (bit 0 x, bit 1 y, bit 2 z) and normals.
    let faces: [([usize; 4], [f32; 3]); 6] = [
        ([0, 2, 6, 4], [-1.0, 0.0, 0.0]),
        ([1, 5, 7, 3], [1.0, 0.0, 0.0]),
        ([0, 4, 5, 1], [0.0, -1.0, 0.0]),
        ([2, 3, 7, 6], [0.0, 1.0, 0.0]),
        ([0, 1, 3, 2], [0.0, 0.0, -1.0]),
        ([4, 6, 7, 5], [0.0, 0.0, 1.0]),
    ];
    for (q, n) in faces {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            for i in t {
                boxed.push(v(c(i), n));
            }
        }
    }
    (ground, boxed)
}

const CASTER_VS: &str = "#version 330 core
layout(location = 0) in vec3 world;
layout(location = 1) in vec3 normal;
uniform mat4 view;
uniform mat4 proj;
uniform vec3 light_pos;
uniform int spot;
uniform float along_light; // caster moved toward the light by this (world units)
uniform float along_normal; // caster moved along its normal by this times 1 - N.L
void main() {
    vec3 l = spot == 1 ? normalize(light_pos - world) : normalize(light_pos);
    float inv = 1.0 - clamp(dot(l, normal), 0.0, 1.0);
    vec3 p = world + l * along_light + normal * (along_normal * inv);
    gl_Position = proj * (view * vec4(p, 1.0));
}
";
const CASTER_FS: &str = "#version 330 core
void main() {}
";
const CAMERA_VS: &str = "#version 330 core
layout(location = 0) in vec3 world;
layout(location = 1) in vec3 normal;
uniform mat4 camera;
out vec3 v_world;
out vec3 v_normal;
void main() { v_world = world; v_normal = normal; gl_Position = camera * vec4(world, 1.0); }
";
const CAMERA_FS: &str = "#version 330 core
in vec3 v_world;
in vec3 v_normal;
uniform sampler2D map;
uniform sampler2DShadow smap; // the same map, GL_LINEAR with GL_COMPARE_REF_TO_TEXTURE
uniform mat4 view;
uniform mat4 proj;
uniform vec3 light_pos;
uniform int spot;
uniform int clip;      // 0: [-1,1], 1: [0,1], 2: reversed
uniform int k;         // PCF size (1: nearest; 0: hardware 2x2 comparison)
uniform float beta;    // window-depth bias in the lookup
uniform float r_light; // receiver moved toward the light (world units)
uniform float r_normal; // receiver moved along its normal (world units)
uniform int r_normal_sine; // scale r_normal by sin(theta)
out vec4 colour;
void main() {
    vec3 l = spot == 1 ? normalize(light_pos - v_world) : normalize(light_pos);
    float cosine = clamp(dot(l, v_normal), 0.0, 1.0);
    float rn = r_normal_sine == 1 ? r_normal * sqrt(1.0 - cosine * cosine) : r_normal;
    vec3 p = v_world + l * r_light + v_normal * rn;
    vec4 c = proj * (view * vec4(p, 1.0));
    vec3 ndc = c.xyz / c.w;
    float z = clip == 0 ? ndc.z * 0.5 + 0.5 : ndc.z;
    ivec2 size = textureSize(map, 0);
    if (k == 0) {
        float ref = clip == 2 ? z + beta : z - beta;
        float lit = texture(smap, vec3(ndc.xy * 0.5 + 0.5, ref));
        colour = vec4(lit >= 1.0 ? 1.0 / 255.0 : 0.0, 1.0 / 255.0, 1.0, 1.0);
        return;
    }
    vec2 uv = (ndc.xy * 0.5 + 0.5) * vec2(size);
    ivec2 t = ivec2(floor(uv));
    int h = (k - 1) / 2;
    int pass = 0;
    int total = 0;
    for (int i = -h; i <= k - 1 - h; ++i) {
        for (int j = -h; j <= k - 1 - h; ++j) {
            ivec2 q = clamp(t + ivec2(i, j), ivec2(0), size - 1);
            float stored = texelFetch(map, q, 0).r;
            bool lit = clip == 2 ? z + beta >= stored : z - beta <= stored;
            pass += lit ? 1 : 0;
            total += 1;
        }
    }
    colour = vec4(float(pass) / 255.0, float(total) / 255.0, 1.0, 1.0);
}
";

/// A vertex buffer of `[x, y, z, nx, ny, nz]` vertices.
unsafe fn upload(g: &glow::Context, v: &[[f32; 6]]) -> Result<glow::Buffer, String> {
    let b = g.create_buffer()?;
    g.bind_buffer(glow::ARRAY_BUFFER, Some(b));
    let bytes: Vec<u8> = v.iter().flatten().flat_map(|x| x.to_ne_bytes()).collect();
    g.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
    Ok(b)
}

unsafe fn program(gl: &glow::Context, vs: &str, fs: &str) -> Result<glow::Program, String> {
    let p = gl.create_program()?;
    for (kind, src) in [(glow::VERTEX_SHADER, vs), (glow::FRAGMENT_SHADER, fs)] {
        let s = gl.create_shader(kind)?;
        gl.shader_source(s, src);
        gl.compile_shader(s);
        if !gl.get_shader_compile_status(s) {
            return Err(format!("shader: {}", gl.get_shader_info_log(s)));
        }
        gl.attach_shader(p, s);
    }
    gl.link_program(p);
    if !gl.get_program_link_status(p) {
        return Err(format!("link: {}", gl.get_program_info_log(p)));
    }
    Ok(p)
}

/// Everything the sweep draws with.
struct Rig {
    caster: glow::Program,
    camera: glow::Program,
    vao: glow::VertexArray,
    ground: glow::Buffer,
    boxed: glow::Buffer,
    counts: [i32; 2],
    camera_fbo: glow::Framebuffer,
    clamp_fn: extern "system" fn(f32, f32, f32),
    /// Texture unit 1's sampler: linear filtering with depth comparison (hardware 2×2).
    compare: [glow::Sampler; 2],
}

/// One map's caster-side bias.
#[derive(Debug, Clone, Copy, Default)]
struct CasterBias {
    offset: Option<(f32, f32, f32)>,
    along_light: f32,
    along_normal: f32,
}

/// One lookup's receiver-side bias.
#[derive(Debug, Clone, Copy, Default)]
struct ReceiverBias {
    beta: f32,
    along_light: f32,
    along_normal: f32,
    sine: bool,
}

#[derive(Debug, Clone, Copy, Default)]
struct Count {
    lit: usize,
    acne: usize,
    shadowed: usize,
    leak: usize,
}

impl Rig {
    unsafe fn new(gl: &Gl) -> Result<Rig, String> {
        let g = gl.glow();
        let caster = program(g, CASTER_VS, CASTER_FS)?;
        let camera = program(g, CAMERA_VS, CAMERA_FS)?;
        let vao = g.create_vertex_array()?;
        let (ground_v, box_v) = meshes();
        let ground = upload(g, &ground_v)?;
        let boxed = upload(g, &box_v)?;
        let camera_fbo = g.create_framebuffer()?;
        g.bind_framebuffer(glow::FRAMEBUFFER, Some(camera_fbo));
        let colour = g.create_renderbuffer()?;
        g.bind_renderbuffer(glow::RENDERBUFFER, Some(colour));
        g.renderbuffer_storage(
            glow::RENDERBUFFER,
            glow::RGBA8,
            CAMERA as i32,
            CAMERA as i32,
        );
        g.framebuffer_renderbuffer(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            glow::RENDERBUFFER,
            Some(colour),
        );
        // The camera's own depth buffer: the nearest of several receivers wins each pixel.
        let camera_depth = g.create_renderbuffer()?;
        g.bind_renderbuffer(glow::RENDERBUFFER, Some(camera_depth));
        g.renderbuffer_storage(
            glow::RENDERBUFFER,
            glow::DEPTH_COMPONENT24,
            CAMERA as i32,
            CAMERA as i32,
        );
        g.framebuffer_renderbuffer(
            glow::FRAMEBUFFER,
            glow::DEPTH_ATTACHMENT,
            glow::RENDERBUFFER,
            Some(camera_depth),
        );
        let mut f = gl.proc_address("glPolygonOffsetClamp");
        if f.is_null() {
            f = gl.proc_address("glPolygonOffsetClampEXT");
        }
        if f.is_null() {
            return Err("glPolygonOffsetClamp(EXT) is not available: the sweep needs it to apply zshift's clamp".into());
        }
        // SAFETY: the GL entry point glPolygonOffsetClamp(float, float, float).
        let clamp_fn =
            std::mem::transmute::<*const std::ffi::c_void, extern "system" fn(f32, f32, f32)>(f);
        let mut compare = Vec::new();
        for func in [glow::LEQUAL, glow::GEQUAL] {
            let smp = g.create_sampler()?;
            for (p, v) in [
                (glow::TEXTURE_MIN_FILTER, glow::LINEAR),
                (glow::TEXTURE_MAG_FILTER, glow::LINEAR),
                (glow::TEXTURE_WRAP_S, glow::CLAMP_TO_EDGE),
                (glow::TEXTURE_WRAP_T, glow::CLAMP_TO_EDGE),
                (glow::TEXTURE_COMPARE_MODE, glow::COMPARE_REF_TO_TEXTURE),
                (glow::TEXTURE_COMPARE_FUNC, func),
            ] {
                g.sampler_parameter_i32(smp, p, v as i32);
            }
            compare.push(smp);
        }
        Ok(Rig {
            compare: [compare[0], compare[1]],
            caster,
            camera,
            vao,
            ground,
            boxed,
            counts: [ground_v.len() as i32, box_v.len() as i32],
            camera_fbo,
            clamp_fn,
        })
    }

    unsafe fn bind_mesh(&self, g: &glow::Context, buffer: glow::Buffer) {
        g.bind_vertex_array(Some(self.vao));
        g.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
        g.enable_vertex_attrib_array(0);
        g.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 24, 0);
        g.enable_vertex_attrib_array(1);
        g.vertex_attrib_pointer_f32(1, 3, glow::FLOAT, false, 24, 12);
    }

    /// The ground and the box, as (buffer, vertex count).
    fn ground_and_box(&self) -> [(glow::Buffer, i32); 2] {
        [(self.ground, self.counts[0]), (self.boxed, self.counts[1])]
    }

    /// Renders the map of `case` with `bias` into a new depth texture (the ground and the box).
    unsafe fn map(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        bias: CasterBias,
    ) -> Result<(glow::Texture, glow::Framebuffer), String> {
        self.map_of(gl, case, light, bias, &self.ground_and_box())
    }

    /// Renders the map of `case` with `bias` into a new depth texture: every mesh of `casters`.
    unsafe fn map_of(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        bias: CasterBias,
        casters: &[(glow::Buffer, i32)],
    ) -> Result<(glow::Texture, glow::Framebuffer), String> {
        gl.clip_control(if case.clip == ClipDepth::NegOneToOne {
            GlClip::NegativeOneToOne
        } else {
            GlClip::ZeroToOne
        })?;
        let g = gl.glow();
        let n = case.resolution as i32;
        let tex = g.create_texture()?;
        g.bind_texture(glow::TEXTURE_2D, Some(tex));
        g.tex_storage_2d(glow::TEXTURE_2D, 1, case.format.gl_enum(), n, n);
        for (p, v) in [
            (glow::TEXTURE_MIN_FILTER, glow::NEAREST),
            (glow::TEXTURE_MAG_FILTER, glow::NEAREST),
            (glow::TEXTURE_COMPARE_MODE, glow::NONE),
        ] {
            g.tex_parameter_i32(glow::TEXTURE_2D, p, v as i32);
        }
        let fbo = g.create_framebuffer()?;
        g.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
        g.framebuffer_texture_2d(
            glow::FRAMEBUFFER,
            glow::DEPTH_ATTACHMENT,
            glow::TEXTURE_2D,
            Some(tex),
            0,
        );
        g.draw_buffer(glow::NONE);
        g.read_buffer(glow::NONE);
        let status = g.check_framebuffer_status(glow::FRAMEBUFFER);
        if status != glow::FRAMEBUFFER_COMPLETE {
            return Err(format!("shadow map FBO incomplete: 0x{status:04X}"));
        }
        g.viewport(0, 0, n, n);
        let reversed = case.clip == ClipDepth::ReversedZeroToOne;
        g.enable(glow::DEPTH_TEST);
        g.depth_mask(true);
        g.depth_func(if reversed { glow::GREATER } else { glow::LESS });
        g.clear_depth_f64(if reversed { 0.0 } else { 1.0 });
        g.clear(glow::DEPTH_BUFFER_BIT);
        g.disable(glow::CULL_FACE);
        match bias.offset {
            Some((factor, units, clamp)) => {
                g.enable(glow::POLYGON_OFFSET_FILL);
                (self.clamp_fn)(factor, units, clamp);
            }
            None => g.disable(glow::POLYGON_OFFSET_FILL),
        }
        g.use_program(Some(self.caster));
        let u = |name: &str| g.get_uniform_location(self.caster, name);
        g.uniform_matrix_4_f32_slice(u("view").as_ref(), false, &to_f32(&light.view));
        g.uniform_matrix_4_f32_slice(u("proj").as_ref(), false, &light.proj32);
        let lp = light_uniform(case, light);
        g.uniform_3_f32(u("light_pos").as_ref(), lp[0], lp[1], lp[2]);
        g.uniform_1_i32(u("spot").as_ref(), (case.kind == Kind::Spot) as i32);
        g.uniform_1_f32(u("along_light").as_ref(), bias.along_light);
        g.uniform_1_f32(u("along_normal").as_ref(), bias.along_normal);
        for &(buffer, count) in casters {
            self.bind_mesh(g, buffer);
            g.draw_arrays(glow::TRIANGLES, 0, count);
        }
        g.disable(glow::POLYGON_OFFSET_FILL);
        zshift_harness::check_gl_errors(g, "shadow map")?;
        Ok((tex, fbo))
    }

    /// Looks the ground up from the camera through `map`: per pixel (passing taps, taps).
    unsafe fn look(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        camera: &M4,
        map: glow::Texture,
        bias: ReceiverBias,
    ) -> Result<Vec<[u8; 2]>, String> {
        let ground = [(self.ground, self.counts[0])];
        self.look_at(gl, case, light, camera, map, bias, &ground)
    }

    /// Looks `receivers` up from the camera through `map` (the nearest receiver at each pixel,
    /// by the camera's depth test): per pixel (passing taps, taps).
    #[allow(clippy::too_many_arguments)]
    unsafe fn look_at(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        camera: &M4,
        map: glow::Texture,
        bias: ReceiverBias,
        receivers: &[(glow::Buffer, i32)],
    ) -> Result<Vec<[u8; 2]>, String> {
        gl.clip_control(GlClip::NegativeOneToOne)?;
        let g = gl.glow();
        g.bind_framebuffer(glow::FRAMEBUFFER, Some(self.camera_fbo));
        g.draw_buffer(glow::COLOR_ATTACHMENT0);
        g.viewport(0, 0, CAMERA as i32, CAMERA as i32);
        g.enable(glow::DEPTH_TEST);
        g.depth_mask(true);
        g.depth_func(glow::LESS);
        g.clear_depth_f64(1.0);
        g.clear_color(0.0, 0.0, 0.0, 0.0);
        g.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
        g.use_program(Some(self.camera));
        let u = |name: &str| g.get_uniform_location(self.camera, name);
        g.active_texture(glow::TEXTURE0);
        g.bind_texture(glow::TEXTURE_2D, Some(map));
        g.uniform_1_i32(u("map").as_ref(), 0);
        g.active_texture(glow::TEXTURE1);
        g.bind_texture(glow::TEXTURE_2D, Some(map));
        let reversed = case.clip == ClipDepth::ReversedZeroToOne;
        g.bind_sampler(1, Some(self.compare[reversed as usize]));
        g.uniform_1_i32(u("smap").as_ref(), 1);
        g.active_texture(glow::TEXTURE0);
        g.uniform_matrix_4_f32_slice(u("camera").as_ref(), false, &to_f32(camera));
        g.uniform_matrix_4_f32_slice(u("view").as_ref(), false, &to_f32(&light.view));
        g.uniform_matrix_4_f32_slice(u("proj").as_ref(), false, &light.proj32);
        let lp = light_uniform(case, light);
        g.uniform_3_f32(u("light_pos").as_ref(), lp[0], lp[1], lp[2]);
        g.uniform_1_i32(u("spot").as_ref(), (case.kind == Kind::Spot) as i32);
        g.uniform_1_i32(
            u("clip").as_ref(),
            match case.clip {
                ClipDepth::NegOneToOne => 0,
                ClipDepth::ZeroToOne => 1,
                ClipDepth::ReversedZeroToOne => 2,
            },
        );
        g.uniform_1_i32(u("k").as_ref(), case.pcf as i32);
        g.uniform_1_f32(u("beta").as_ref(), bias.beta);
        g.uniform_1_f32(u("r_light").as_ref(), bias.along_light);
        g.uniform_1_f32(u("r_normal").as_ref(), bias.along_normal);
        g.uniform_1_i32(u("r_normal_sine").as_ref(), bias.sine as i32);
        for &(buffer, count) in receivers {
            self.bind_mesh(g, buffer);
            g.draw_arrays(glow::TRIANGLES, 0, count);
        }
        g.disable(glow::DEPTH_TEST);
        let pixels = zshift_harness::read_rgba8(g, CAMERA as i32, CAMERA as i32);
        zshift_harness::check_gl_errors(g, "camera pass")?;
        Ok(pixels
            .iter()
            .map(|c| if c[2] == 255 { [c[0], c[1]] } else { [0, 0] })
            .collect())
    }
}

/// The light's position (spot) or direction toward it (directional), for the shaders.
fn light_uniform(case: &Case, light: &Light) -> [f32; 3] {
    match case.kind {
        Kind::Spot => light.position.map(|x| x as f32),
        Kind::Directional => light.to_light.map(|x| x as f32),
    }
}

/// The exact answer per camera pixel: None (not counted: off the ground, under the box, off the
/// map, or near a shadow edge), Some(true) lit, Some(false) shadowed.
fn reference(
    case: &Case,
    light: &Light,
    camera: &M4,
    eye: [f64; 3],
    reach: f64,
) -> Vec<Option<bool>> {
    let inverse = invert(camera);
    let light_vp = mul(&light.proj, &light.view);
    let light_inv = invert(&light_vp);
    let n = f64::from(case.resolution);
    let ray_to_light = |p: [f64; 3]| -> ([f64; 3], f64) {
        match case.kind {
            Kind::Directional => (light.to_light, f64::INFINITY),
            Kind::Spot => {
                let d = sub(light.position, p);
                (d, 1.0)
            }
        }
    };
    let shadowed = |p: [f64; 3]| {
        let (d, t) = ray_to_light(p);
        blocked(p, d, t)
    };
    // The map texel position (in texels) of a world point, and back to the ground.
    let to_map = |p: [f64; 3]| -> [f64; 2] {
        let c = apply(&light_vp, p);
        [(c[0] / c[3] * 0.5 + 0.5) * n, (c[1] / c[3] * 0.5 + 0.5) * n]
    };
    let to_ground = |uv: [f64; 2]| -> Option<[f64; 3]> {
        let x = uv[0] / n * 2.0 - 1.0;
        let y = uv[1] / n * 2.0 - 1.0;
        let a = apply(&light_inv, [x, y, -1.0]);
        let b = apply(&light_inv, [x, y, 0.5]);
        let a = [a[0] / a[3], a[1] / a[3], a[2] / a[3]];
        let b = [b[0] / b[3], b[1] / b[3], b[2] / b[3]];
        let d = sub(b, a);
        if d[1].abs() < 1e-300 {
            return None;
        }
        let t = -a[1] / d[1];
        Some([a[0] + t * d[0], 0.0, a[2] + t * d[2]])
    };
    let edge = reach + 1.5;
    let mut out = Vec::with_capacity(CAMERA * CAMERA);
    for py in 0..CAMERA {
        for px in 0..CAMERA {
            let x = (px as f64 + 0.5) / CAMERA as f64 * 2.0 - 1.0;
            let y = (py as f64 + 0.5) / CAMERA as f64 * 2.0 - 1.0;
            let far = apply(&inverse, [x, y, 1.0]);
            let far = [far[0] / far[3], far[1] / far[3], far[2] / far[3]];
            let d = sub(far, eye);
            let t = -eye[1] / d[1];
            let p = [eye[0] + t * d[0], 0.0, eye[2] + t * d[2]];
            let inside_box = p[0] >= BOX[0][0] - 0.05
                && p[0] <= BOX[1][0] + 0.05
                && p[2] >= BOX[0][2] - 0.05
                && p[2] <= BOX[1][2] + 0.05;
            if t.is_nan()
                || t <= 0.0
                || p[0].abs() > GROUND * 0.98
                || p[2].abs() > GROUND * 0.98
                || inside_box
            {
                out.push(None);
                continue;
            }
            let uv = to_map(p);
            if uv.iter().any(|&c| c < edge + 1.0 || c > n - edge - 1.0) {
                out.push(None);
                continue;
            }
            let s = shadowed(p);
            let mut near_edge = false;
            'o: for dx in [-edge, 0.0, edge] {
                for dy in [-edge, 0.0, edge] {
                    if let Some(q) = to_ground([uv[0] + dx, uv[1] + dy]) {
                        if shadowed(q) != s {
                            near_edge = true;
                            break 'o;
                        }
                    }
                }
            }
            out.push(if near_edge { None } else { Some(!s) });
        }
    }
    out
}

fn invert(m: &M4) -> M4 {
    // Gauss-Jordan on the 4×4 (row-major view of the column-major array).
    let mut a = [[0.0f64; 8]; 4];
    for r in 0..4 {
        for c in 0..4 {
            a[r][c] = m[4 * c + r];
        }
        a[r][4 + r] = 1.0;
    }
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        a.swap(c, p);
        let d = a[c][c];
        for x in a[c].iter_mut() {
            *x /= d;
        }
        let pivot = a[c];
        for (r, row) in a.iter_mut().enumerate() {
            if r != c {
                let f = row[c];
                for (x, p) in row.iter_mut().zip(pivot) {
                    *x -= f * p;
                }
            }
        }
    }
    let mut out = [0.0; 16];
    for r in 0..4 {
        for c in 0..4 {
            out[4 * c + r] = a[r][4 + c];
        }
    }
    out
}

fn count(pixels: &[[u8; 2]], truth: &[Option<bool>]) -> Count {
    let mut c = Count::default();
    for (p, t) in pixels.iter().zip(truth) {
        match t {
            Some(true) if p[1] > 0 => {
                c.lit += 1;
                if p[0] < p[1] {
                    c.acne += 1;
                }
            }
            Some(false) if p[1] > 0 => {
                c.shadowed += 1;
                if p[0] == p[1] {
                    c.leak += 1;
                }
            }
            _ => {}
        }
    }
    c
}

/// The ground's window-depth gradient in the map, per texel (f64, from three ground points).
fn ground_slope(case: &Case, light: &Light) -> f64 {
    let vp = mul(&light.proj, &light.view);
    let n = f64::from(case.resolution);
    let per_ndc = if case.clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    let w = |p: [f64; 3]| {
        let c = apply(&vp, p);
        [
            (c[0] / c[3] * 0.5 + 0.5) * n,
            (c[1] / c[3] * 0.5 + 0.5) * n,
            c[2] / c[3] * per_ndc,
        ]
    };
    let (a, b, c) = (w([0.0, 0.0, 0.0]), w([0.5, 0.0, 0.0]), w([0.0, 0.0, 0.5]));
    // Solve z = z0 + gx·x + gy·y through the three.
    let (x1, y1, z1) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let (x2, y2, z2) = (c[0] - a[0], c[1] - a[1], c[2] - a[2]);
    let det = x1 * y2 - x2 * y1;
    let gx = (z1 * y2 - z2 * y1) / det;
    let gy = (x1 * z2 - x2 * z1) / det;
    gx.abs().max(gy.abs())
}

/// The case of combination `c` in `0..81` of light f/n, map size, format and convention.
fn case_of(kind: Kind, elevation: f64, pcf: u32, c: usize) -> Case {
    use zshift_harness::DepthFormat as F;
    let clips = [
        ClipDepth::NegOneToOne,
        ClipDepth::ZeroToOne,
        ClipDepth::ReversedZeroToOne,
    ];
    Case {
        kind,
        elevation,
        ratio: [10.0, 1e3, 1e5][c % 3],
        resolution: [256, 1024, 2048][(c / 3) % 3],
        format: [F::D16, F::D24, F::D32F][(c / 9) % 3],
        clip: clips[(c / 27) % 3],
        pcf,
    }
}

fn cases(full: bool) -> Vec<Case> {
    let mut v = Vec::new();
    let elevations = [1.0, 5.0, 20.0, 45.0, 89.0];
    let mut i = 0usize;
    for kind in [Kind::Directional, Kind::Spot] {
        for &elevation in &elevations {
            for pcf in [1, 0, 3, 5] {
                // The default run: 6 combinations per class for nearest and 3×3 PCF, 3 for the
                // hardware 2×2 comparison and 5×5 PCF.
                let take = if pcf == 1 || pcf == 3 { 6 } else { 3 };
                let combos: Vec<usize> = if full {
                    (0..81).collect()
                } else {
                    (0..take).map(|j| (i * 7 + j * 13) % 81).collect()
                };
                v.extend(combos.into_iter().map(|c| case_of(kind, elevation, pcf, c)));
                i += 1;
            }
        }
    }
    v
}

#[derive(Debug, Clone, Copy)]
struct Engine {
    name: &'static str,
    caster: fn(&Case, &Light) -> CasterBias,
    receiver: fn(&Case, &Light) -> ReceiverBias,
}

fn soft(case: &Case) -> f32 {
    if case.pcf != 1 {
        2.5
    } else {
        1.0
    }
}

/// The engines' defaults, as NOTES.md describes them (signs flipped under reversed Z, where the
/// API's bias moves depth the other way).
fn engines() -> [Engine; 5] {
    let flip = |case: &Case| {
        if case.clip == ClipDepth::ReversedZeroToOne {
            -1.0f32
        } else {
            1.0
        }
    };
    let _ = flip;
    [
        Engine {
            name: "Unity URP",
            caster: |c, l| {
                let s = if c.clip == ClipDepth::ReversedZeroToOne {
                    -1.0
                } else {
                    1.0
                };
                let t = l.texel_world as f32 * soft(c);
                CasterBias {
                    offset: Some((2.5 * s, 1.0 * s, 0.0)),
                    along_light: -t,
                    along_normal: -t,
                }
            },
            receiver: |_, _| ReceiverBias::default(),
        },
        Engine {
            name: "Godot 4",
            caster: |_, _| CasterBias::default(),
            receiver: |_, l| ReceiverBias {
                beta: 0.0,
                along_light: (0.001 * l.range) as f32,
                along_normal: l.texel_world as f32,
                sine: false,
            },
        },
        Engine {
            name: "Filament",
            caster: |c, _| {
                let s = if c.clip == ClipDepth::ReversedZeroToOne {
                    -1.0
                } else {
                    1.0
                };
                CasterBias {
                    offset: Some((2.0 * s, 0.5 * s, 0.0)),
                    along_light: 0.0,
                    along_normal: 0.0,
                }
            },
            receiver: |_, l| ReceiverBias {
                beta: 0.0,
                along_light: 0.001,
                along_normal: l.texel_world as f32,
                sine: true,
            },
        },
        Engine {
            name: "bevy",
            caster: |_, _| CasterBias::default(),
            receiver: |_, l| ReceiverBias {
                beta: 0.0,
                along_light: 0.02,
                along_normal: 1.8 * l.texel_world as f32,
                sine: false,
            },
        },
        Engine {
            name: "three.js",
            caster: |_, _| CasterBias::default(),
            receiver: |_, _| ReceiverBias {
                beta: 0.0005,
                along_light: 0.0,
                along_normal: 0.0,
                sine: false,
            },
        },
    ]
}

#[derive(Default)]
struct Tally {
    scenes: usize,
    acne_scenes: usize,
    worst_acne: f64,
    leak_sum: f64,
    leak_scenes: usize,
    leak_worst: f64,
    ratios: Vec<f64>,
}

impl Tally {
    fn add(&mut self, c: Count) {
        self.scenes += 1;
        if c.shadowed >= 50 {
            self.leak_scenes += 1;
        }
        let acne = c.acne as f64 / c.lit.max(1) as f64;
        if c.acne > 0 {
            self.acne_scenes += 1;
        }
        self.worst_acne = self.worst_acne.max(acne);
        // Leak counted where the box's shadow covers at least 50 counted pixels.
        let leak = if c.shadowed >= 50 {
            c.leak as f64 / c.shadowed as f64
        } else {
            0.0
        };
        self.leak_sum += leak;
        self.leak_worst = self.leak_worst.max(leak);
    }
    fn row(&self, name: &str) -> String {
        let mut r = self.ratios.clone();
        r.sort_by(f64::total_cmp);
        let med = if r.is_empty() {
            f64::NAN
        } else {
            r[r.len() / 2]
        };
        let max = r.last().copied().unwrap_or(f64::NAN);
        format!(
            "| {name} | {} of {} | {:.2} % | {:.2} % | {:.2} % | {} |",
            self.acne_scenes,
            self.scenes,
            100.0 * self.worst_acne,
            100.0 * self.leak_sum / self.leak_scenes.max(1) as f64,
            100.0 * self.leak_worst,
            if r.is_empty() {
                "—".to_string()
            } else {
                format!("{med:.2} (max {max:.2})")
            }
        )
    }
}

fn tally(tallies: &mut Vec<(String, Tally)>, name: &str, class: &str) -> usize {
    let key = format!("{name} [{class}]");
    match tallies.iter().position(|(k, _)| *k == key) {
        Some(i) => i,
        None => {
            tallies.push((key, Tally::default()));
            tallies.len() - 1
        }
    }
}

/// The camera both sweeps look from: its position and its view-projection (f64).
fn camera() -> ([f64; 3], M4) {
    let eye = [-9.0, 9.0, 8.0];
    let v = look_at(eye, [0.5, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let p = zshift::projection::projection_f64(
        &Frustum::new(-0.05, 0.05, -0.05, 0.05, 0.1, 100.0).unwrap(),
        ClipDepth::NegOneToOne,
    )
    .unwrap();
    (eye, mul(&p, &v))
}

#[test]
fn zshift_shadow_bias_is_acne_free_where_it_answers() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow sweep: {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let full = std::env::var("ZSHIFT_SHADOW_SCENES").is_ok_and(|v| v == "full");
    let verbose = std::env::var("ZSHIFT_SHADOW_VERBOSE").is_ok_and(|v| v == "1");
    let all = cases(full);
    let (eye, camera) = camera();
    let mut failures = Vec::new();
    let mut tallies: Vec<(String, Tally)> = Vec::new();
    let mut refusals = 0;
    let mut dominance: std::collections::BTreeMap<String, (usize, usize, Vec<String>)> =
        std::collections::BTreeMap::new();
    let started = std::time::Instant::now();
    for case in &all {
        let light = light_of(case);
        let truth = reference(case, &light, &camera, eye, case.kernel_reach());
        let class = format!(
            "{} {}",
            if case.kind == Kind::Spot {
                "spot"
            } else {
                "directional"
            },
            match case.pcf {
                1 => "nearest",
                0 => "hardware 2x2",
                3 => "PCF 3x3",
                _ => "PCF 5x5",
            }
        );
        let unbiased = unsafe { rig.map(&mut gl, case, &light, CasterBias::default()) }
            .unwrap_or_else(|e| panic!("{e}"));
        let acne_at = |gl: &mut Gl, beta: f64| -> Count {
            let px = unsafe {
                rig.look(
                    gl,
                    case,
                    &light,
                    &camera,
                    unbiased.0,
                    ReceiverBias {
                        beta: beta as f32,
                        ..Default::default()
                    },
                )
            }
            .unwrap_or_else(|e| panic!("{e}"));
            count(&px, &truth)
        };
        // The smallest acne-free constant bias in the lookup (bisection, geometric, below 1).
        let smallest = if acne_at(&mut gl, 0.0).acne == 0 {
            Some(0.0)
        } else {
            let mut hi = 1e-9;
            while acne_at(&mut gl, hi).acne > 0 && hi < 1.0 {
                hi = (hi * 4.0).min(1.0);
            }
            if acne_at(&mut gl, hi).acne > 0 {
                None
            } else {
                let mut lo = hi / 4.0;
                for _ in 0..10 {
                    let mid = (lo * hi).sqrt();
                    if acne_at(&mut gl, mid).acne > 0 {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                Some(hi)
            }
        };
        let slope = ground_slope(case, &light);
        // The ground as zshift's receiver API takes it: a quad in the light's view (f32),
        // counter-clockwise seen from above.
        let ground_quad: Vec<glam::Vec3> = [
            [-GROUND, 0.0, -GROUND],
            [-GROUND, 0.0, GROUND],
            [GROUND, 0.0, GROUND],
            [GROUND, 0.0, -GROUND],
        ]
        .iter()
        .map(|&p| {
            let e = apply(&light.view, p);
            glam::Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32)
        })
        .collect();
        let mut leaks: Vec<(String, usize)> = Vec::new();
        // The light's pipeline as both shaders run it: world positions through the f32 view
        // matrix first, then the projection (`proj * (view * p)`), every position inside the
        // scene's box (the ground and the box standing on it).
        let light_pipeline = zshift::model::Pipeline {
            eye_first: true,
            view: Some(to_f32(&light.view)),
            world_box: Some(WORLD_BOX),
            ..Default::default()
        };
        for (pname, profile, receivers, pipeline) in [
            ("worst", RasterizerProfile::worst_case(), false, None),
            ("probed", probed, false, None),
            (
                "worst, receivers",
                RasterizerProfile::worst_case(),
                true,
                None,
            ),
            ("probed, receivers", probed, true, None),
            (
                "worst, view",
                RasterizerProfile::worst_case(),
                false,
                Some(light_pipeline),
            ),
            ("probed, view", probed, false, Some(light_pipeline)),
            (
                "worst, receivers, view",
                RasterizerProfile::worst_case(),
                true,
                Some(light_pipeline),
            ),
            (
                "probed, receivers, view",
                probed,
                true,
                Some(light_pipeline),
            ),
        ] {
            let limit = if receivers {
                RECEIVER_LIMIT_DEG
            } else {
                90.0 - case.elevation
            };
            let map = case.shadow_map(&light, limit, profile, pipeline.unwrap_or_default());
            let t = tally(&mut tallies, &format!("zshift ({pname})"), &class);
            let answer = if receivers {
                shadow_bias_for_receivers(&map, &[&ground_quad])
            } else {
                shadow_bias(&map)
            };
            match answer {
                Ok(bias) => {
                    let [f, u, c] = bias.gl_polygon_offset;
                    let m = unsafe {
                        rig.map(
                            &mut gl,
                            case,
                            &light,
                            CasterBias {
                                offset: Some((f as f32, u as f32, c as f32)),
                                ..Default::default()
                            },
                        )
                    }
                    .unwrap_or_else(|e| panic!("{e}"));
                    let px = unsafe {
                        rig.look(&mut gl, case, &light, &camera, m.0, ReceiverBias::default())
                    }
                    .unwrap_or_else(|e| panic!("{e}"));
                    unsafe {
                        gl.glow().delete_framebuffer(m.1);
                        gl.glow().delete_texture(m.0);
                    }
                    let got = count(&px, &truth);
                    tallies[t].1.add(got);
                    leaks.push((pname.to_string(), got.leak));
                    let on_ground = {
                        let k = bias.terms.constant + bias.terms.slope_factor * slope;
                        let clamp = c.abs();
                        if clamp > 0.0 {
                            k.min(clamp)
                        } else {
                            k
                        }
                    };
                    if let Some(s) = smallest.filter(|&s| s > 0.0) {
                        tallies[t].1.ratios.push(on_ground / s);
                    }
                    if verbose {
                        println!("{} {pname}: acne {}/{} leak {}/{} bias {on_ground:.3e} smallest {smallest:?}", case.label(), got.acne, got.lit, got.leak, got.shadowed);
                    }
                    if got.acne > 0 {
                        failures.push(format!(
                            "{} ({pname}): {} acne pixels of {} lit at {:?}",
                            case.label(),
                            got.acne,
                            got.lit,
                            bias.gl_polygon_offset
                        ));
                    }
                }
                Err(e) if e.kind() == ErrorKind::Unresolvable => {
                    refusals += 1;
                    if let Some(s) = smallest.filter(|&s| s < 1.0) {
                        failures.push(format!(
                            "{} ({pname}): refused ({e}) but {s:.3e} is acne-free",
                            case.label()
                        ));
                    }
                }
                Err(e) => failures.push(format!("{} ({pname}): {e}", case.label())),
            }
        }
        for engine in engines() {
            let cb = (engine.caster)(case, &light);
            let rb = (engine.receiver)(case, &light);
            let mut rb = rb;
            if case.clip == ClipDepth::ReversedZeroToOne {
                rb.beta = rb.beta.abs();
            }
            let tex = if cb.offset.is_some() || cb.along_light != 0.0 || cb.along_normal != 0.0 {
                Some(
                    unsafe { rig.map(&mut gl, case, &light, cb) }.unwrap_or_else(|e| panic!("{e}")),
                )
            } else {
                None
            };
            let px = unsafe {
                rig.look(
                    &mut gl,
                    case,
                    &light,
                    &camera,
                    tex.map_or(unbiased.0, |m| m.0),
                    rb,
                )
            }
            .unwrap_or_else(|e| panic!("{e}"));
            if let Some(m) = tex {
                unsafe {
                    gl.glow().delete_framebuffer(m.1);
                    gl.glow().delete_texture(m.0);
                }
            }
            let got = count(&px, &truth);
            let t = tally(&mut tallies, engine.name, &class);
            tallies[t].1.add(got);
            // No peer dominates: where the engine is acne-free, zshift's leak (shadowed pixels
            // left lit) must be no larger.
            if got.acne == 0 {
                for (pname, leak) in &leaks {
                    let d = dominance.entry(pname.clone()).or_insert((0, 0, Vec::new()));
                    d.0 += 1;
                    if *leak > got.leak {
                        d.1 += 1;
                        d.2.push(format!(
                            "{} {}: zshift ({pname}) leaks {leak}, {} {}",
                            case.label(),
                            engine.name,
                            engine.name,
                            got.leak
                        ));
                    }
                }
            }
        }
        unsafe {
            gl.glow().delete_framebuffer(unbiased.1);
            gl.glow().delete_texture(unbiased.0);
        }
    }
    tallies.sort_by(|a, b| a.0.cmp(&b.0));
    println!(
        "shadow sweep: {} scenes, {} refusals, {:.1} s on {}",
        all.len(),
        refusals,
        started.elapsed().as_secs_f64(),
        gl.renderer()
    );
    println!("| bias [class] | scenes with acne | worst acne (% of lit) | mean leak (% of shadowed) | worst leak | bias ÷ smallest acne-free (median) |");
    println!("|---|---|---|---|---|---|");
    for (name, t) in &tallies {
        println!("{}", t.row(name));
    }
    println!("no peer dominates? (scene, engine) pairs where the engine is acne-free, and those where zshift leaks more");
    for (pname, (pairs, worse, examples)) in &dominance {
        println!("  zshift ({pname}): {worse} of {pairs} pairs leak more");
        if verbose {
            for e in examples {
                println!("    {e}");
            }
        }
    }
    // Not asserted: zshift leaks more than an acne-free peer in some pairs (docs/shadows.md
    // says where and why); `ZSHIFT_SHADOW_VERBOSE=1` lists them.
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

//! The shadow scene that `tests/gl_shadow.rs` sweeps and the demonstration draws
//! (`cargo run --release -p zshift-demo -- --shadows DIR`): a 12 × 12 ground with a
//! 1.2 × 2 × 0.8 box standing on it, lit by a directional or a spot light ([`Case`], [`Light`]);
//! the GL rig that renders the light's depth map and looks the ground up through it from a
//! camera ([`Rig`]); the exact f64 reference that says, per camera pixel, whether the ground
//! point is lit ([`reference()`]); the count of acne and leak against it ([`count`]); and the
//! shadow-bias defaults of five engines ([`engines`]). In one place so that the test's figures
//! and the demonstration's picture come from the same code.
//!
//! Conventions as zshift's: right-handed world and eye space, column-major `[f64; 16]`
//! matrices ([`M4`]), window depth in `[0, 1]`. Every GL function here needs the harness's
//! context current on the calling thread.

use glow::HasContext;
use zshift::orthographic::Ortho;
use zshift::projection::{ClipDepth, Frustum};
use zshift::recommend::RasterizerProfile;
use zshift::shadow::{LightProjection, Lookup, ShadowMap};

use crate::{ClipDepth as GlClip, Gl};

/// Half the ground's side: the ground is `[-GROUND, GROUND]²` at y = 0.
pub const GROUND: f64 = 6.0;
/// The box: min and max corners.
pub const BOX: [[f64; 3]; 2] = [[0.2, 0.0, -0.9], [1.4, 2.0, -0.1]];
/// The camera's square render, in pixels per side.
pub const CAMERA: usize = 160;
/// The light's azimuth (degrees from +x toward +z) in the grid's cases.
pub const AZIMUTH_DEG: f64 = 30.0;
/// The box of every world position the caster and lookup shaders transform: the ground and
/// the box standing on it.
pub const WORLD_BOX: [[f64; 3]; 2] = [[-GROUND, 0.0, -GROUND], [GROUND, BOX[1][1], GROUND]];
/// The limit angle passed with explicit receivers: it only skips receivers facing away by more.
pub const RECEIVER_LIMIT_DEG: f64 = 89.9;

/// A 4×4 matrix, column-major, in f64.
pub type M4 = [f64; 16];

/// The product `a · b`.
pub fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            m[4 * c + r] = (0..4).map(|k| a[4 * k + r] * b[4 * c + k]).sum();
        }
    }
    m
}

/// `m · (p, 1)`: the homogeneous image of point `p`.
/// The translation by `t` (column-major).
pub fn translation(t: [f64; 3]) -> M4 {
    let mut m = [0.0; 16];
    for k in 0..4 {
        m[5 * k] = 1.0;
    }
    m[12..15].copy_from_slice(&t);
    m
}

pub fn apply(m: &M4, p: [f64; 3]) -> [f64; 4] {
    [0, 1, 2, 3].map(|r| m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r])
}

/// `a − b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
/// `a · b`.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// `a` scaled to unit length.
pub fn norm(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// A right-handed look-at view matrix (column-major), in f64.
pub fn look_at(eye: [f64; 3], at: [f64; 3], up: [f64; 3]) -> M4 {
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

/// `m` rounded to f32, as the shaders take it.
pub fn to_f32(m: &M4) -> [f32; 16] {
    m.map(|x| x as f32)
}

/// Does the segment from `p` in direction `dir` (up to `t_max`) hit the box? Slab test in f64.
pub fn blocked(p: [f64; 3], dir: [f64; 3], t_max: f64) -> bool {
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

/// The light's kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Parallel rays, an orthographic map fitted to the scene.
    Directional,
    /// Rays from a point, a perspective map fitted to the scene.
    Spot,
}

/// One lit scene: the light and its map.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Directional or spot.
    pub kind: Kind,
    /// The light's elevation above the ground, degrees.
    pub elevation: f64,
    /// The light's azimuth, degrees from +x toward +z ([`AZIMUTH_DEG`] in the grid).
    pub azimuth: f64,
    /// The light's far / near.
    pub ratio: f64,
    /// The map's texels per side.
    pub resolution: u32,
    /// The map's depth format.
    pub format: crate::DepthFormat,
    /// The map's clip convention.
    pub clip: ClipDepth,
    /// The lookup: 1 nearest, 0 hardware 2×2 comparison, k ≥ 2 k×k PCF.
    pub pcf: u32,
    /// A disk kernel of this radius in texels (`pcf` is then ignored), or 0.
    pub radius: f64,
    /// The map as a tile of a shadow atlas, or `None`: a texture of its own.
    pub atlas: Option<Atlas>,
    /// The whole scene (ground, box, light, camera) moved this far from the world's origin: the
    /// shaders add it to every position in f32, as an engine's f32 world positions hold it, and
    /// the light's and the camera's f32 matrices are those of the moved scene. The reference
    /// stays where it is (the scene moved by exactly this).
    pub shift: [f64; 3],
}

/// A shadow map drawn as a tile of a larger texture (a shadow atlas), with a depth range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atlas {
    /// The atlas's texels per side.
    pub size: u32,
    /// The tile's lower-left corner in the atlas, texels (`glViewport`'s x, y).
    pub origin: [u32; 2],
    /// `glDepthRange(near, far)` the tile is drawn with; the lookup compares against
    /// `near + (far − near)·w`.
    pub depth_range: [f64; 2],
}

impl Case {
    /// The lookup zshift is told about.
    pub fn lookup(&self) -> Lookup {
        if self.radius > 0.0 {
            return Lookup::Radius(self.radius);
        }
        match self.pcf {
            1 => Lookup::Nearest,
            0 => Lookup::Hardware2x2,
            k => Lookup::Pcf(k),
        }
    }

    /// Texels per axis from the lookup point to the farthest texel centre the shader reads
    /// (this file's own statement of its lookups, for the reference's shadow-edge margin).
    pub fn kernel_reach(&self) -> f64 {
        if self.radius > 0.0 {
            return self.radius + 0.5;
        }
        match self.pcf {
            1 => 0.5,
            0 => 1.0,
            k => f64::from(k) / 2.0,
        }
    }

    /// The map as zshift is asked about it: the case's light, format, lookup and convention,
    /// the light's largest world coordinate as `world_reach`.
    pub fn shadow_map(
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
            format: zshift::recommend::DepthFormat::from_gl_internal_format(self.format.gl_enum())
                .expect("a GL depth format"),
            lookup: self.lookup(),
            limit_angle_deg,
            receiver_depths: light.receivers,
            // The light's position and the models' origin (the scene's, at the shift).
            world_reach: (0..3).fold(0.0f64, |a, k| {
                a.max((light.position[k] + self.shift[k]).abs())
                    .max(self.shift[k].abs())
            }),
            elevation_deg: self.elevation,
            profile,
            pipeline: match self.atlas {
                Some(a) => zshift::model::Pipeline {
                    viewport_origin: a.origin,
                    depth_range: a.depth_range,
                    ..self.moved(light, pipeline)
                },
                None => self.moved(light, pipeline),
            },
        }
    }

    /// `pipeline` with the light's view matrix and the world box of the moved scene
    /// ([`Case::shift`]) where it names a view matrix.
    fn moved(&self, light: &Light, pipeline: zshift::model::Pipeline) -> zshift::model::Pipeline {
        if pipeline.view.is_none() {
            return pipeline;
        }
        let [lo, hi] = WORLD_BOX;
        zshift::model::Pipeline {
            view: Some(to_f32(&self.light_view(light))),
            world_box: Some([
                [0, 1, 2].map(|k| lo[k] + self.shift[k]),
                [0, 1, 2].map(|k| hi[k] + self.shift[k]),
            ]),
            ..pipeline
        }
    }

    /// The light's view matrix of the moved scene: its view after a translation by −shift.
    pub fn light_view(&self, light: &Light) -> M4 {
        mul(&light.view, &translation(self.shift.map(|x| -x)))
    }

    /// The camera's matrix of the moved scene.
    pub fn camera_of(&self, camera: &M4) -> M4 {
        mul(camera, &translation(self.shift.map(|x| -x)))
    }

    /// One line naming the case (light, elevation, f/n, map, format, convention, lookup).
    pub fn label(&self) -> String {
        // The grid's azimuth is left out, so that its labels stay those the docs cite.
        let azimuth = if self.azimuth == AZIMUTH_DEG {
            String::new()
        } else {
            format!(" az={}°", self.azimuth)
        };
        let atlas = self.atlas.map_or(String::new(), |a| {
            format!(
                " tile@{:?} of {}² range {:?}",
                a.origin, a.size, a.depth_range
            )
        });
        format!(
            "{:?} e={}°{azimuth} f/n={:e} {}² {} {:?} {}{atlas}",
            self.kind,
            self.elevation,
            self.ratio,
            self.resolution,
            self.format.name(),
            self.clip,
            if self.radius > 0.0 {
                format!("disk r={}", self.radius)
            } else if self.pcf == 1 {
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
pub struct Light {
    /// The light's position (a spot's apex; a directional light's eye for its view).
    pub position: [f64; 3],
    /// The unit direction toward the light from the scene's centre.
    pub to_light: [f64; 3],
    /// The light's view matrix.
    pub view: M4,
    /// The light's projection matrix.
    pub proj: M4,
    /// The projection as zshift builds it in f32, as the shaders take it.
    pub proj32: [f32; 16],
    /// The projection as zshift is told about it.
    pub projection: LightProjection,
    /// The receivers' light-eye depth range, widened by 1e-6 either way.
    pub receivers: [f64; 2],
    /// A map texel's size in world units at the scene's centre.
    pub texel_world: f64,
    /// The light's far minus near.
    pub range: f64,
}

impl Light {
    /// The light's pipeline as both shaders run it: world positions through the f32 view
    /// matrix first, then the projection (`proj * (view * p)`), every position inside the
    /// scene's box (the ground and the box standing on it).
    pub fn pipeline(&self) -> zshift::model::Pipeline {
        zshift::model::Pipeline {
            eye_first: true,
            view: Some(to_f32(&self.view)),
            world_box: Some(WORLD_BOX),
            ..Default::default()
        }
    }

    /// The ground as zshift's receiver API takes it: a quad in the light's view (f32),
    /// counter-clockwise seen from above.
    pub fn ground_quad(&self) -> Vec<zshift::glam::Vec3> {
        [
            [-GROUND, 0.0, -GROUND],
            [-GROUND, 0.0, GROUND],
            [GROUND, 0.0, GROUND],
            [GROUND, 0.0, -GROUND],
        ]
        .iter()
        .map(|&p| {
            let e = apply(&self.view, p);
            zshift::glam::Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32)
        })
        .collect()
    }
}

/// The scene's corners: the ground's four, then the box's eight.
pub fn corners() -> Vec<[f64; 3]> {
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

/// The light of `case` fitted to the ground and the box.
pub fn light_of(case: &Case) -> Light {
    let points = corners();
    light_for(case, &points, &points[..4])
}

/// The light of `case` fitted to `points` (every caster and receiver), with the receivers'
/// light-depth range taken over `receivers`.
pub fn light_for(case: &Case, points: &[[f64; 3]], receivers: &[[f64; 3]]) -> Light {
    let (e, a) = (case.elevation.to_radians(), case.azimuth.to_radians());
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
pub fn meshes() -> (Vec<[f32; 6]>, Vec<[f32; 6]>) {
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
uniform vec3 shift; // the scene's distance from the world's origin (f32 world positions)
void main() {
    vec3 w = world + shift;
    vec3 l = spot == 1 ? normalize(light_pos - w) : normalize(light_pos);
    float inv = 1.0 - clamp(dot(l, normal), 0.0, 1.0);
    vec3 p = w + l * along_light + normal * (along_normal * inv);
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
uniform vec3 shift; // the scene's distance from the world's origin (f32 world positions)
out vec3 v_world;
out vec3 v_normal;
void main() {
    vec3 w = world + shift;
    v_world = w;
    v_normal = normal;
    gl_Position = camera * vec4(w, 1.0);
}
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
uniform int k;         // PCF size (1: nearest; 0: hardware 2x2 comparison; -1: a disk of `radius`)
uniform float radius;  // texels, with k = -1: 17 taps, the centre and 8 at radius/2 and 8 at radius
uniform float beta;    // window-depth bias in the lookup
uniform float r_light; // receiver moved toward the light (world units)
uniform float r_normal; // receiver moved along its normal (world units)
uniform int r_normal_sine; // scale r_normal by sin(theta)
uniform int atlas;       // 1: the map is a tile of a larger texture
uniform vec2 tile_origin; // the tile's corner in the texture, texels (atlas)
uniform vec2 tile_size;   // the tile's size, texels (atlas)
uniform float depth_lo;   // glDepthRange's near end the map was drawn with
uniform float depth_span; // glDepthRange's far minus near end
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
    // Without an atlas the tile is the texture, depth_lo = 0 and depth_span = 1: every
    // expression below is then exactly the one without them.
    vec2 origin = atlas == 1 ? tile_origin : vec2(0.0);
    vec2 tsize = atlas == 1 ? tile_size : vec2(size);
    if (k == 0) {
        float ref = depth_lo + depth_span * (clip == 2 ? z + beta : z - beta);
        vec2 at = atlas == 1 ? (origin + (ndc.xy * 0.5 + 0.5) * tsize) / vec2(size)
                             : ndc.xy * 0.5 + 0.5;
        float lit = texture(smap, vec3(at, ref));
        colour = vec4(lit >= 1.0 ? 1.0 / 255.0 : 0.0, 1.0 / 255.0, 1.0, 1.0);
        return;
    }
    vec2 uv = origin + (ndc.xy * 0.5 + 0.5) * tsize;
    ivec2 t = ivec2(floor(uv));
    if (k < 0) {
        // A disk kernel: each tap reads the texel its point lies in.
        ivec2 first = ivec2(origin);
        ivec2 last = ivec2(origin + tsize) - 1;
        float zr = depth_lo + depth_span * (clip == 2 ? z + beta : z - beta);
        int pass = 0;
        for (int i = 0; i < 17; ++i) {
            float ring = i == 0 ? 0.0 : (i <= 8 ? 0.5 : 1.0);
            float a = 0.7853981633974483 * float(i) + (i > 8 ? 0.39269908169872414 : 0.0);
            vec2 tap = uv + radius * ring * vec2(cos(a), sin(a));
            ivec2 q = clamp(ivec2(floor(tap)), first, last);
            float stored = texelFetch(map, q, 0).r;
            pass += (clip == 2 ? zr >= stored : zr <= stored) ? 1 : 0;
        }
        colour = vec4(float(pass) / 255.0, 17.0 / 255.0, 1.0, 1.0);
        return;
    }
    ivec2 first = ivec2(origin);
    ivec2 last = ivec2(origin + tsize) - 1;
    float zr = depth_lo + depth_span * (clip == 2 ? z + beta : z - beta);
    int h = (k - 1) / 2;
    int pass = 0;
    int total = 0;
    for (int i = -h; i <= k - 1 - h; ++i) {
        for (int j = -h; j <= k - 1 - h; ++j) {
            ivec2 q = clamp(t + ivec2(i, j), first, last);
            float stored = texelFetch(map, q, 0).r;
            bool lit = clip == 2 ? zr >= stored : zr <= stored;
            pass += lit ? 1 : 0;
            total += 1;
        }
    }
    colour = vec4(float(pass) / 255.0, float(total) / 255.0, 1.0, 1.0);
}
";

/// A vertex buffer of `[x, y, z, nx, ny, nz]` vertices.
///
/// # Safety
/// `g`'s context must be current on this thread.
///
/// # Errors
/// A GL failure.
pub unsafe fn upload(g: &glow::Context, v: &[[f32; 6]]) -> Result<glow::Buffer, String> {
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
pub struct Rig {
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
pub struct CasterBias {
    /// `glPolygonOffsetClamp(factor, units, clamp)`, or none.
    pub offset: Option<(f32, f32, f32)>,
    /// Casters moved toward the light by this (world units).
    pub along_light: f32,
    /// Casters moved along their normal by this times `1 − N·L` (world units).
    pub along_normal: f32,
}

impl CasterBias {
    /// zshift's answer as the map is drawn with it: its `glPolygonOffsetClamp(factor, units,
    /// clamp)` in f32, nothing else.
    pub fn of(bias: &zshift::shadow::ShadowBias) -> Self {
        let [f, u, c] = bias.gl_polygon_offset.map(|x| x as f32);
        Self {
            offset: Some((f, u, c)),
            ..Default::default()
        }
    }
}

/// One lookup's receiver-side bias.
#[derive(Debug, Clone, Copy, Default)]
pub struct ReceiverBias {
    /// A window-depth bias subtracted from the lookup's depth (added under reversed Z).
    pub beta: f32,
    /// The looked-up point moved toward the light by this (world units).
    pub along_light: f32,
    /// The looked-up point moved along its normal by this (world units).
    pub along_normal: f32,
    /// Scale `along_normal` by the sine of the angle to the light.
    pub sine: bool,
}

/// A lookup's camera pixels counted against the reference ([`count`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Count {
    /// Counted pixels the reference says are lit.
    pub lit: usize,
    /// Of those, the ones the map darkens (any tap fails).
    pub acne: usize,
    /// Counted pixels the reference says are shadowed.
    pub shadowed: usize,
    /// Of those, the ones the map leaves fully lit (every tap passes).
    pub leak: usize,
}

impl Rig {
    /// Compiles the shaders, uploads the ground and the box, and makes the camera's
    /// [`CAMERA`]² colour and depth target.
    ///
    /// # Safety
    /// `gl`'s context must be current on this thread.
    ///
    /// # Errors
    /// A GL failure, or no `glPolygonOffsetClamp(EXT)`.
    pub unsafe fn new(gl: &Gl) -> Result<Rig, String> {
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
    ///
    /// # Safety
    /// As [`Rig::new`].
    ///
    /// # Errors
    /// A GL failure.
    pub unsafe fn map(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        bias: CasterBias,
    ) -> Result<(glow::Texture, glow::Framebuffer), String> {
        self.map_of(gl, case, light, bias, &self.ground_and_box())
    }

    /// Renders the map of `case` with `bias` into a new depth texture: every mesh of `casters`.
    ///
    /// # Safety
    /// As [`Rig::new`].
    ///
    /// # Errors
    /// A GL failure.
    pub unsafe fn map_of(
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
        let side = case.atlas.map_or(n, |a| a.size as i32);
        if let Some(a) = case.atlas {
            if a.origin.iter().any(|&o| o + case.resolution > a.size) {
                return Err(format!("the tile {a:?} of {n}² leaves the atlas"));
            }
        }
        let tex = g.create_texture()?;
        g.bind_texture(glow::TEXTURE_2D, Some(tex));
        g.tex_storage_2d(glow::TEXTURE_2D, 1, case.format.gl_enum(), side, side);
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
        let reversed = case.clip == ClipDepth::ReversedZeroToOne;
        g.enable(glow::DEPTH_TEST);
        g.depth_mask(true);
        g.depth_func(if reversed { glow::GREATER } else { glow::LESS });
        g.clear_depth_f64(if reversed { 0.0 } else { 1.0 });
        g.viewport(0, 0, side, side);
        g.clear(glow::DEPTH_BUFFER_BIT);
        match case.atlas {
            Some(a) => {
                g.viewport(a.origin[0] as i32, a.origin[1] as i32, n, n);
                g.depth_range_f64(a.depth_range[0], a.depth_range[1]);
            }
            None => g.viewport(0, 0, n, n),
        }
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
        g.uniform_matrix_4_f32_slice(u("view").as_ref(), false, &to_f32(&case.light_view(light)));
        g.uniform_matrix_4_f32_slice(u("proj").as_ref(), false, &light.proj32);
        let sh = case.shift.map(|x| x as f32);
        g.uniform_3_f32(u("shift").as_ref(), sh[0], sh[1], sh[2]);
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
        g.depth_range_f64(0.0, 1.0);
        crate::check_gl_errors(g, "shadow map")?;
        Ok((tex, fbo))
    }

    /// Looks the ground up through a map drawn with `caster` (through `unbiased`, the map drawn
    /// without bias, when `caster` moves nothing), with `receiver`; deletes the map it drew.
    /// Per pixel (passing taps, taps).
    ///
    /// # Safety
    /// As [`Rig::new`].
    ///
    /// # Errors
    /// A GL failure.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn look_biased(
        &self,
        gl: &mut Gl,
        case: &Case,
        light: &Light,
        camera: &M4,
        unbiased: glow::Texture,
        caster: CasterBias,
        receiver: ReceiverBias,
    ) -> Result<Vec<[u8; 2]>, String> {
        let moves =
            caster.offset.is_some() || caster.along_light != 0.0 || caster.along_normal != 0.0;
        let drawn = if moves {
            Some(self.map(gl, case, light, caster)?)
        } else {
            None
        };
        let px = self.look(
            gl,
            case,
            light,
            camera,
            drawn.map_or(unbiased, |m| m.0),
            receiver,
        );
        if let Some(m) = drawn {
            gl.glow().delete_framebuffer(m.1);
            gl.glow().delete_texture(m.0);
        }
        px
    }

    /// Looks the ground up from the camera through `map`: per pixel (passing taps, taps).
    ///
    /// # Safety
    /// As [`Rig::new`].
    ///
    /// # Errors
    /// A GL failure.
    pub unsafe fn look(
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
    ///
    /// # Safety
    /// As [`Rig::new`].
    ///
    /// # Errors
    /// A GL failure.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn look_at(
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
        g.uniform_matrix_4_f32_slice(
            u("camera").as_ref(),
            false,
            &to_f32(&case.camera_of(camera)),
        );
        g.uniform_matrix_4_f32_slice(u("view").as_ref(), false, &to_f32(&case.light_view(light)));
        g.uniform_matrix_4_f32_slice(u("proj").as_ref(), false, &light.proj32);
        let sh = case.shift.map(|x| x as f32);
        g.uniform_3_f32(u("shift").as_ref(), sh[0], sh[1], sh[2]);
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
        g.uniform_1_i32(
            u("k").as_ref(),
            if case.radius > 0.0 {
                -1
            } else {
                case.pcf as i32
            },
        );
        g.uniform_1_f32(u("radius").as_ref(), case.radius as f32);
        g.uniform_1_f32(u("beta").as_ref(), bias.beta);
        g.uniform_1_f32(u("r_light").as_ref(), bias.along_light);
        g.uniform_1_f32(u("r_normal").as_ref(), bias.along_normal);
        g.uniform_1_i32(u("r_normal_sine").as_ref(), bias.sine as i32);
        let (tile, range) = match case.atlas {
            Some(a) => (
                [
                    a.origin[0] as f32,
                    a.origin[1] as f32,
                    case.resolution as f32,
                ],
                a.depth_range,
            ),
            None => ([0.0, 0.0, case.resolution as f32], [0.0, 1.0]),
        };
        g.uniform_1_i32(u("atlas").as_ref(), case.atlas.is_some() as i32);
        g.uniform_2_f32(u("tile_origin").as_ref(), tile[0], tile[1]);
        g.uniform_2_f32(u("tile_size").as_ref(), tile[2], tile[2]);
        g.uniform_1_f32(u("depth_lo").as_ref(), range[0] as f32);
        g.uniform_1_f32(u("depth_span").as_ref(), (range[1] - range[0]) as f32);
        for &(buffer, count) in receivers {
            self.bind_mesh(g, buffer);
            g.draw_arrays(glow::TRIANGLES, 0, count);
        }
        g.disable(glow::DEPTH_TEST);
        let pixels = crate::read_rgba8(g, CAMERA as i32, CAMERA as i32);
        crate::check_gl_errors(g, "camera pass")?;
        Ok(pixels
            .iter()
            .map(|c| if c[2] == 255 { [c[0], c[1]] } else { [0, 0] })
            .collect())
    }
}

/// The light's position (spot) or direction toward it (directional), for the shaders.
fn light_uniform(case: &Case, light: &Light) -> [f32; 3] {
    match case.kind {
        Kind::Spot => [0, 1, 2].map(|k| (light.position[k] + case.shift[k]) as f32),
        Kind::Directional => light.to_light.map(|x| x as f32),
    }
}

/// The direction from `p` toward `case`'s light and the ray parameter at which it reaches the
/// light: the light's direction and `∞` for a directional light, the segment to the light and 1
/// for a spot.
pub fn toward_light(case: &Case, light: &Light, p: [f64; 3]) -> ([f64; 3], f64) {
    match case.kind {
        Kind::Directional => (light.to_light, f64::INFINITY),
        Kind::Spot => (sub(light.position, p), 1.0),
    }
}

/// The map position (texels) of world point `p` under the light's view-projection `vp`, for a
/// map `n` texels a side.
pub fn map_position(vp: &M4, n: f64, p: [f64; 3]) -> [f64; 2] {
    let c = apply(vp, p);
    [(c[0] / c[3] * 0.5 + 0.5) * n, (c[1] / c[3] * 0.5 + 0.5) * n]
}

/// The light's ray through map position `uv` (texels) of a map `n` texels a side, from the
/// inverse of its view-projection: its point on the near plane and its direction (to NDC depth
/// ½), in world space.
pub fn map_ray(inverse: &M4, n: f64, uv: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let (x, y) = (uv[0] / n * 2.0 - 1.0, uv[1] / n * 2.0 - 1.0);
    let a = apply(inverse, [x, y, -1.0]);
    let b = apply(inverse, [x, y, 0.5]);
    let a = [a[0] / a[3], a[1] / a[3], a[2] / a[3]];
    let b = [b[0] / b[3], b[1] / b[3], b[2] / b[3]];
    (a, sub(b, a))
}

/// The exact answer per camera pixel: None (not counted: off the ground, under the box, off the
/// map, or near a shadow edge), Some(true) lit, Some(false) shadowed.
pub fn reference(
    case: &Case,
    light: &Light,
    camera: &M4,
    eye: [f64; 3],
    reach: f64,
) -> Vec<Option<bool>> {
    reference_lifted(case, light, camera, eye, reach, 0.0)
}

/// [`reference`] for lookups made `lift` above the ground along its normal (a receiver-side
/// normal offset): each pixel's ground point is lifted before its shadow and its map position
/// are taken, so a normal offset's own shift of the shadows is not counted as acne.
pub fn reference_lifted(
    case: &Case,
    light: &Light,
    camera: &M4,
    eye: [f64; 3],
    reach: f64,
    lift: f64,
) -> Vec<Option<bool>> {
    let inverse = invert(camera);
    let light_vp = mul(&light.proj, &light.view);
    let light_inv = invert(&light_vp);
    let n = f64::from(case.resolution);
    let shadowed = |p: [f64; 3]| {
        let (d, t) = toward_light(case, light, p);
        blocked(p, d, t)
    };
    // The map texel position (in texels) of a world point, and back to the ground.
    let to_map = |p: [f64; 3]| map_position(&light_vp, n, p);
    let to_ground = |uv: [f64; 2]| -> Option<[f64; 3]> {
        let (a, d) = map_ray(&light_inv, n, uv);
        if d[1].abs() < 1e-300 {
            return None;
        }
        let t = -a[1] / d[1];
        Some([a[0] + t * d[0], 0.0, a[2] + t * d[2]])
    };
    // Far from the world's origin ([`Case::shift`]) every drawn position is off its exact place
    // by the f32 roundings of coordinates as large as the shift: the caster's `world + shift`
    // and its light view product (about 6u of the shift's size), the camera's one combined
    // matrix (14u), the lookup's interpolated world position and its light view product
    // (about 10u): 32u bounds them. A shadow edge the map draws, seen through the lookup, then
    // lies up to that far (in texels) from the exact one; a pixel within it is not counted: it
    // cannot tell acne from the caster's own place (a seeded draw, `ZSHIFT_SHADOW_SEED=13`,
    // counted such a pixel 10⁵ from the origin on a 3715² map, where that is 24 texels).
    let placement = 32.0
        * (f64::from(f32::EPSILON) / 2.0)
        * case.shift.iter().fold(0.0f64, |a, c| a.max(c.abs()));
    let texels_per_unit = |p: [f64; 3]| {
        let (h, at) = (1e-3, to_map(p));
        (0..3)
            .map(|k| {
                let mut q = p;
                q[k] += h;
                let uv = to_map(q);
                ((uv[0] - at[0]).powi(2) + (uv[1] - at[1]).powi(2)).sqrt() / h
            })
            .sum::<f64>()
    };
    let mut out = Vec::with_capacity(CAMERA * CAMERA);
    for py in 0..CAMERA {
        for px in 0..CAMERA {
            let Some(p) = ground_point(&inverse, eye, px, py) else {
                out.push(None);
                continue;
            };
            let inside_box = p[0] >= BOX[0][0] - 0.05
                && p[0] <= BOX[1][0] + 0.05
                && p[2] >= BOX[0][2] - 0.05
                && p[2] <= BOX[1][2] + 0.05;
            if p[0].abs() > GROUND * 0.98 || p[2].abs() > GROUND * 0.98 || inside_box {
                out.push(None);
                continue;
            }
            let p = [p[0], lift, p[2]];
            let uv = to_map(p);
            let edge = reach + 1.5 + placement * texels_per_unit(p);
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

/// The ground point (world `y = 0`) camera pixel `(px, py)` shows, from the camera matrix's
/// `inverse` and the `eye`; `None` where its ray does not meet the ground in front of the eye.
fn ground_point(inverse: &M4, eye: [f64; 3], px: usize, py: usize) -> Option<[f64; 3]> {
    let d = pixel_ray(inverse, eye, px, py);
    let t = -eye[1] / d[1];
    (t > 0.0).then(|| [eye[0] + t * d[0], 0.0, eye[2] + t * d[2]])
}

/// Per camera pixel, whether its ground point sees the light more than `limit_deg` from the
/// ground's normal: a receiver beyond the limit angle a bias was asked for, which the bias
/// does not promise to cover (shading hides it). Under a spot light the angle varies over the
/// ground, so points farther from the light than the scene's centre lie beyond
/// `90° − elevation`. Pixels that miss the ground: false.
pub fn beyond_limit(
    case: &Case,
    light: &Light,
    camera: &M4,
    eye: [f64; 3],
    limit_deg: f64,
) -> Vec<bool> {
    let inverse = invert(camera);
    let cos_limit = limit_deg.to_radians().cos();
    (0..CAMERA * CAMERA)
        .map(|i| {
            let Some(p) = ground_point(&inverse, eye, i % CAMERA, i / CAMERA) else {
                return false;
            };
            let (l, _) = toward_light(case, light, p);
            let length = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            l[1] / length < cos_limit
        })
        .collect()
}

/// The inverse of `m` (Gauss-Jordan with partial pivoting, f64).
pub fn invert(m: &M4) -> M4 {
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

/// Counts `pixels` (per pixel: passing taps, taps, as [`Rig::look`] returns them) against
/// `truth` ([`reference()`]): a lit pixel with a failing tap is acne, a shadowed pixel whose every
/// tap passes is a leak.
pub fn count(pixels: &[[u8; 2]], truth: &[Option<bool>]) -> Count {
    let mut c = Count::default();
    for (&p, &t) in pixels.iter().zip(truth) {
        match judge(p, t) {
            Some(Verdict::Lit) => c.lit += 1,
            Some(Verdict::Acne) => (c.lit, c.acne) = (c.lit + 1, c.acne + 1),
            Some(Verdict::Shadowed) => c.shadowed += 1,
            Some(Verdict::Leak) => (c.shadowed, c.leak) = (c.shadowed + 1, c.leak + 1),
            None => {}
        }
    }
    c
}

/// One counted camera pixel against the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// Lit, and the map leaves it lit.
    Lit,
    /// Lit, but the map darkens it (a tap fails).
    Acne,
    /// Shadowed, and the map darkens it.
    Shadowed,
    /// Shadowed, but the map leaves it fully lit (every tap passes).
    Leak,
}

/// The verdict on a pixel (passing taps, taps) whose reference answer is `truth`; none where
/// the reference leaves it out or the pixel shows no ground.
pub fn judge(pixel: [u8; 2], truth: Option<bool>) -> Option<Verdict> {
    match truth {
        Some(true) if pixel[1] > 0 => Some(if pixel[0] < pixel[1] {
            Verdict::Acne
        } else {
            Verdict::Lit
        }),
        Some(false) if pixel[1] > 0 => Some(if pixel[0] == pixel[1] {
            Verdict::Leak
        } else {
            Verdict::Shadowed
        }),
        _ => None,
    }
}

/// The direction from `eye` through the centre of camera pixel `(px, py)` (rows bottom-up),
/// `inverse` being the camera's inverse view-projection.
pub fn pixel_ray(inverse: &M4, eye: [f64; 3], px: usize, py: usize) -> [f64; 3] {
    let x = (px as f64 + 0.5) / CAMERA as f64 * 2.0 - 1.0;
    let y = (py as f64 + 0.5) / CAMERA as f64 * 2.0 - 1.0;
    let far = apply(inverse, [x, y, 1.0]);
    let far = [far[0] / far[3], far[1] / far[3], far[2] / far[3]];
    sub(far, eye)
}

/// An engine's default shadow bias: what it does to the casters and to the lookup.
#[derive(Debug, Clone, Copy)]
pub struct Engine {
    /// The engine's name.
    pub name: &'static str,
    /// Its bias in a few words, in capitals (a picture's label).
    pub short: &'static str,
    /// Its caster-side bias for a case and its light.
    pub caster: fn(&Case, &Light) -> CasterBias,
    /// Its receiver-side bias for a case and its light.
    pub receiver: fn(&Case, &Light) -> ReceiverBias,
}

/// Unity's normal and depth bias scale with the filter: 2.5 for a soft (PCF) lookup.
fn soft(case: &Case) -> f32 {
    if case.pcf != 1 {
        2.5
    } else {
        1.0
    }
}

impl Engine {
    /// The engine's caster and receiver bias for `case`, the lookup's window bias made positive
    /// under reversed Z (where the lookup adds it).
    pub fn biases(&self, case: &Case, light: &Light) -> (CasterBias, ReceiverBias) {
        let mut receiver = (self.receiver)(case, light);
        if case.clip == ClipDepth::ReversedZeroToOne {
            receiver.beta = receiver.beta.abs();
        }
        ((self.caster)(case, light), receiver)
    }
}

/// Under reversed Z an API's bias moves depth the other way: its sign.
fn flip(case: &Case) -> f32 {
    if case.clip == ClipDepth::ReversedZeroToOne {
        -1.0
    } else {
        1.0
    }
}

/// The engines' defaults, as NOTES.md describes them (signs flipped under reversed Z, where the
/// API's bias moves depth the other way).
pub fn engines() -> [Engine; 5] {
    [
        Engine {
            name: "Unity URP",
            short: "OFFSET 2.5,1 + NORMAL",
            caster: |c, l| {
                let s = flip(c);
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
            short: "RECEIVER NORMAL 1 TEXEL",
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
            short: "OFFSET 2,0.5 + NORMAL",
            caster: |c, _| {
                let s = flip(c);
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
            short: "DEPTH 0.02 + NORMAL 1.8",
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
            short: "WINDOW BIAS 0.0005",
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

/// The camera both sweeps look from: its position and its view-projection (f64).
pub fn camera() -> ([f64; 3], M4) {
    let eye = [-9.0, 9.0, 8.0];
    let v = look_at(eye, [0.5, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let p = zshift::projection::projection_f64(
        &Frustum::new(-0.05, 0.05, -0.05, 0.05, 0.1, 100.0).unwrap(),
        ClipDepth::NegOneToOne,
    )
    .unwrap();
    (eye, mul(&p, &v))
}

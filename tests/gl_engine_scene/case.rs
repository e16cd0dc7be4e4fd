//! One scene and its exact (f64) geometry: the attachment, the camera, the ground (one quad,
//! a grid, hills) and the decal on it, the window, and what an engine knows of them to tell
//! zshift (its f32 view matrix, `base_reach`, the world box, the pipeline), and the scene's label.

use super::*;

/// Camera height above the ground.
pub(crate) const EYE_HEIGHT: f64 = 1.7;
/// The ground's half extent around the camera.
pub(crate) const GROUND: f64 = 1000.0;
/// The viewport, 16:9: 320×180, or `ZSHIFT_ENGINE_SCENES_VIEWPORT=<w>x<h>` (1920x1080, 3840x2160:
/// the engines' own sizes, slower).
pub(crate) fn viewport() -> [u32; 2] {
    static SIZE: std::sync::OnceLock<[u32; 2]> = std::sync::OnceLock::new();
    *SIZE.get_or_init(|| {
        std::env::var("ZSHIFT_ENGINE_SCENES_VIEWPORT")
            .ok()
            .and_then(|v| {
                let (w, h) = v.split_once('x')?;
                Some([w.parse().ok()?, h.parse().ok()?])
            })
            .unwrap_or([320, 180])
    })
}
/// glm::perspective's vertical field of view (other draws, `ZSHIFT_ENGINE_SCENES_SEED`, take
/// 40° to 100°).
pub(crate) const FOVY_DEG: f64 = 60.0;

/// One convention and attachment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Attachment {
    pub(crate) label: &'static str,
    pub(crate) clip: ClipDepth,
    pub(crate) format: DepthFormat,
    pub(crate) packed: bool,
}

pub(crate) const ATTACHMENTS: [Attachment; 13] = [
    Attachment {
        label: "[-1,1] D24",
        clip: ClipDepth::NegOneToOne,
        format: DepthFormat::D24,
        packed: false,
    },
    Attachment {
        label: "[-1,1] D24S8",
        clip: ClipDepth::NegOneToOne,
        format: DepthFormat::D24,
        packed: true,
    },
    Attachment {
        label: "[0,1] D32F",
        clip: ClipDepth::ZeroToOne,
        format: DepthFormat::D32F,
        packed: false,
    },
    Attachment {
        label: "[0,1] D32F_S8",
        clip: ClipDepth::ZeroToOne,
        format: DepthFormat::D32F,
        packed: true,
    },
    Attachment {
        label: "reversed D32F",
        clip: ClipDepth::ReversedZeroToOne,
        format: DepthFormat::D32F,
        packed: false,
    },
    Attachment {
        label: "reversed D24S8",
        clip: ClipDepth::ReversedZeroToOne,
        format: DepthFormat::D24,
        packed: true,
    },
    Attachment {
        label: "[0,1] D24",
        clip: ClipDepth::ZeroToOne,
        format: DepthFormat::D24,
        packed: false,
    },
    Attachment {
        label: "[-1,1] D32F",
        clip: ClipDepth::NegOneToOne,
        format: DepthFormat::D32F,
        packed: false,
    },
    // OpenGL ES's smallest required depth format, still a mobile engine's default.
    Attachment {
        label: "[-1,1] D16",
        clip: ClipDepth::NegOneToOne,
        format: DepthFormat::D16,
        packed: false,
    },
    // The rest of the cross product of {D24, D24S8, D32F, D32F_S8} and the three conventions.
    Attachment {
        label: "[-1,1] D32F_S8",
        clip: ClipDepth::NegOneToOne,
        format: DepthFormat::D32F,
        packed: true,
    },
    Attachment {
        label: "[0,1] D24S8",
        clip: ClipDepth::ZeroToOne,
        format: DepthFormat::D24,
        packed: true,
    },
    Attachment {
        label: "reversed D24",
        clip: ClipDepth::ReversedZeroToOne,
        format: DepthFormat::D24,
        packed: false,
    },
    Attachment {
        label: "reversed D32F_S8",
        clip: ClipDepth::ReversedZeroToOne,
        format: DepthFormat::D32F,
        packed: true,
    },
];

/// The ground as the engine draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Ground {
    /// One quad of ±[`GROUND`] (two triangles).
    Quad,
    /// A grid of 64×64 cells over ±[`GROUND`].
    Grid,
    /// A terrain with hills: [`HILL_CELLS`]² cells of one unit around the camera, heights from
    /// two waves ([`Case::bumps`]); the decal is a mesh decal over the terrain's triangles, each
    /// piece on its own plane, asked for one plane at a time.
    Hills,
}

impl Ground {
    pub(crate) fn label(self) -> &'static str {
        match self {
            Ground::Quad => "quad",
            Ground::Grid => "grid",
            Ground::Hills => "hills",
        }
    }
}

/// Cells along each side of the hills' terrain (one unit each, centred on the camera's cell).
pub(crate) const HILL_CELLS: u32 = 120;

/// One scene of the sweep.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Case {
    pub(crate) at: Attachment,
    pub(crate) pitch_deg: f64,
    pub(crate) translate: f64,
    /// The camera's heading about the vertical, degrees (0: looking down world −z).
    pub(crate) yaw_deg: f64,
    /// The camera's roll about its view axis, degrees (90: the ground is a wall on screen, seen
    /// along its length when the camera is level).
    pub(crate) roll_deg: f64,
    /// The camera's offset from the ground's centre in world x and z: engines' cameras sit at
    /// coordinates no f32 holds exactly.
    pub(crate) jitter: [f64; 2],
    /// The decal's length along world z over its width (1: a square; a road marking or a skid
    /// mark is long and narrow, [`long_decals`]).
    pub(crate) length: f64,
    /// The ground's half extent over the grid's (1: ±1000 units, times `scale`), moved only to
    /// draw one description's other realizations ([`one_description_many_realizations`]).
    pub(crate) stretch: f64,
    /// The ground's world height under the camera (f32-exact): 0, or with
    /// `ZSHIFT_ENGINE_SCENES_SEED` as far from the origin as the translation (a world whose
    /// ground is not at y = 0).
    pub(crate) ground_y: f64,
    /// The ground's rise per unit of world x (0: level; a hillside otherwise): the ground is the
    /// plane `y = ground_y + tilt·(x − camera x)`, decals lie on it.
    pub(crate) tilt: f64,
    /// The vertical field of view, degrees.
    pub(crate) fovy_deg: f64,
    pub(crate) ground: Ground,
    pub(crate) near: f64,
    pub(crate) far: f64,
    pub(crate) size: f64,
    pub(crate) distance: f64,
    pub(crate) side: f64,
    pub(crate) equal_test: bool,
    pub(crate) origin: [u32; 2],
    pub(crate) depth_range: [f64; 2],
    /// The decal as a mesh decal (an engine's decal system clips the ground's own triangles to
    /// the decal's square, in f32, and draws the pieces) instead of one quad of its corners.
    pub(crate) mesh_decal: bool,
    /// The decal (one quad, not a mesh decal) drawn as engines draw a decal entity: a unit quad
    /// in its own model space through its model matrix `M` (f32, its translation the decal's
    /// world position), the shader's `view` uniform the model-view `V·M` multiplied on the CPU
    /// ([`Case::shader_matrices`]): far from the origin that product cancels two large
    /// translations.
    pub(crate) model_decal: ModelView,
    /// The shader applies one f32 view-projection to world positions, the model matrix first
    /// where there is one: `viewProj * (model * p)` (bevy's `clip_from_world`, Unity's
    /// `UNITY_MATRIX_VP`), `viewProj = P·V` multiplied in f32 on the CPU as glam's `Mat4` does.
    /// zshift is told `eye_first` false with the view and the box ([`Case::pipeline`]);
    /// otherwise the shader computes the eye position first, `proj * (modelView * p)`. A
    /// quarter of the sweep's scenes are drawn both ways (the twin is the same scene).
    pub(crate) combined: bool,
    /// The 64×64 grid drawn as terrain engines draw it: in chunks of 8×8 cells, each in its own
    /// local coordinates (centred on the chunk) through its model matrix, the shader's `view`
    /// the chunk's model-view `V·M` multiplied on the CPU ([`ModelView`]; the quad and the hills
    /// are drawn in world space).
    pub(crate) ground_chunks: ModelView,
    /// World units per metre (1; seeded draws also take 100, an engine in centimetres, 0.3048
    /// and 39.37): every length of the scene (ground, hills, camera height, decal, near and
    /// far planes, translation) is multiplied by it, so a term written for one scale of the
    /// world (an absolute epsilon, a length assumed near 1) shows.
    pub(crate) scale: f64,
    /// The camera's height above the ground under it, in metres before [`Case::scale`]
    /// ([`EYE_HEIGHT`]; seeded draws also take a crouch, 0.5, and a strategy camera, 10).
    pub(crate) eye_height: f64,
    /// The frustum moved off centre, as fractions of its half width and half height (0, 0;
    /// seeded draws also take an engine's temporal anti-aliasing jitter, under half a pixel,
    /// and a VR eye's asymmetric frustum): the projection's elements 8 and 9 nonzero.
    pub(crate) skew: [f64; 2],
    /// Samples per pixel of the target (1; `ZSHIFT_ENGINE_SCENES_MSAA`, and
    /// [`every_sample_holds_under_msaa`]): each read back and judged on its own.
    pub(crate) samples: u32,
    /// The decal may reach behind the near plane (a decal under the camera, part of it behind;
    /// [`decals_reaching_behind_the_camera`]): drawn, not skipped.
    pub(crate) behind: bool,
    /// The decal may run on beyond the far plane (a road marking under a short far plane; some
    /// of it in front, [`decals_reaching_beyond_the_far_plane`]): drawn, not skipped.
    pub(crate) beyond: bool,
}

/// How an engine multiplies a decal entity's model-view `V·M` on the CPU, and what it then tells
/// zshift (the two ways `Pipeline::view` documents).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ModelView {
    /// No model matrix: the decal's world-space vertices through the view matrix.
    None,
    /// In double, rounded once to f32 (`glm::dmat4`): the view matrix and the world box, as for
    /// world-space vertices.
    Double,
    /// In f32 (`glm::mat4`): `world_reach`, the largest coordinate of the camera's position and
    /// of the decal's model origin.
    Float,
}

impl Case {
    pub(crate) fn reversed(&self) -> bool {
        self.at.clip == ClipDepth::ReversedZeroToOne
    }

    pub(crate) fn frustum(&self) -> Frustum {
        let t = self.near * (self.fovy_deg.to_radians() / 2.0).tan();
        let r = t * f64::from(viewport()[0]) / f64::from(viewport()[1]);
        let (x, y) = (self.skew[0] * r, self.skew[1] * t);
        Frustum::new(-r + x, r + x, -t + y, t + y, self.near, self.far).expect("valid frustum")
    }

    /// The ground's half extent around the camera in world units.
    fn ground_half(&self) -> f64 {
        GROUND * self.scale * self.stretch
    }

    pub(crate) fn camera(&self) -> [f64; 3] {
        let (x, z) = (
            self.translate + self.jitter[0],
            self.translate + self.jitter[1],
        );
        [
            x,
            self.ground_y + self.eye_height * self.scale + self.bumps(x, z),
            z,
        ]
    }

    /// The ground's height at world `x`.
    pub(crate) fn height(&self, x: f64) -> f64 {
        self.ground_y + self.tilt * (x - self.camera()[0])
    }

    /// The hills' relief over the plane (0 unless [`Ground::Hills`]): two waves, slopes up to
    /// about 0.75, the same shapes wherever the scene is translated.
    fn bumps(&self, x: f64, z: f64) -> f64 {
        if self.ground != Ground::Hills {
            return 0.0;
        }
        let s = self.scale;
        let (u, v) = ((x - self.translate) / s, (z - self.translate) / s);
        s * ((0.273 * u + 0.4).sin() * (0.191 * v - 1.1).cos() + 0.4 * (0.86 * (u + v)).sin())
    }

    /// The ground's height at world `(x, z)`.
    pub(crate) fn surface(&self, x: f64, z: f64) -> f64 {
        self.height(x) + self.bumps(x, z)
    }

    /// The camera's distance from the ground's plane, along its normal.
    pub(crate) fn clearance(&self) -> f64 {
        self.eye_height * self.scale / (1.0 + self.tilt * self.tilt).sqrt()
    }

    /// The rotation world → eye: the camera turned by `yaw` about the vertical (at 0 it looks
    /// down world −z), then pitched down by `pitch`.
    fn rotation(&self) -> [[f64; 3]; 3] {
        let (s, c) = self.pitch_deg.to_radians().sin_cos();
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (sr, cr) = self.roll_deg.to_radians().sin_cos();
        let roll = [[cr, sr, 0.0], [-sr, cr, 0.0], [0.0, 0.0, 1.0]];
        let pitch = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
        let yaw = [[cy, 0.0, -sy], [0.0, 1.0, 0.0], [sy, 0.0, cy]];
        let product = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
            std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum())
            })
        };
        product(roll, product(pitch, yaw))
    }

    /// Eye coordinates of a world point, in f64.
    pub(crate) fn eye(&self, p: [f64; 3]) -> [f64; 3] {
        eye_of(&self.rotation(), self.camera(), p)
    }

    /// The f32 view matrix (column-major), built in f64 as an engine's math library would and
    /// rounded once.
    fn view(&self) -> [f32; 16] {
        view_matrix(&self.rotation(), self.camera())
    }

    pub(crate) fn ground(&self) -> Vec<[f32; 3]> {
        let cells = i64::from(match self.ground {
            Ground::Quad => 1,
            Ground::Grid => 64,
            Ground::Hills => HILL_CELLS,
        });
        self.cell_triangles(0..cells, 0..cells, [0.0; 3])
    }

    /// The exact world position of the ground's lattice vertex `(i, j)`: one quad of ±1000, the
    /// 64×64 grid over it, or the hills' one-unit cells.
    fn lattice_vertex(&self, i: i64, j: i64) -> [f64; 3] {
        let (cells, half) = match self.ground {
            Ground::Quad => (1, self.ground_half()),
            Ground::Grid => (64, self.ground_half()),
            Ground::Hills => (HILL_CELLS, f64::from(HILL_CELLS / 2) * self.scale),
        };
        let step = 2.0 * half / f64::from(cells);
        let (x, z) = (
            self.translate - half + step * i as f64,
            self.translate - half + step * j as f64,
        );
        [x, self.surface(x, z), z]
    }

    /// The ground's cells `is × js` as two triangles each, their vertices relative to `origin`
    /// (a chunk's centre; 0 for world space) rounded to f32 as the engine stores them.
    fn cell_triangles(
        &self,
        is: std::ops::Range<i64>,
        js: std::ops::Range<i64>,
        origin: [f64; 3],
    ) -> Vec<[f32; 3]> {
        let at = |i, j| {
            let p = self.lattice_vertex(i, j);
            [0, 1, 2].map(|k| (p[k] - origin[k]) as f32)
        };
        let mut t = Vec::new();
        for i in is {
            for j in js.clone() {
                t.extend(quad_triangles(&[
                    at(i, j),
                    at(i + 1, j),
                    at(i + 1, j + 1),
                    at(i, j + 1),
                ]));
            }
        }
        t
    }

    /// The decal's centre on the ground (world): `distance` ahead of the camera along its
    /// heading, `side·distance` to its right.
    pub(crate) fn decal_centre(&self) -> [f64; 2] {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (forward, right) = ([-sy, -cy], [cy, -sy]);
        let c = self.camera();
        let (a, b) = (self.distance, self.side * self.distance);
        [
            c[0] + a * forward[0] + b * right[0],
            c[2] + a * forward[1] + b * right[1],
        ]
    }

    /// A rectangle of half side `half` in world x (`half·length` in z) around the decal's
    /// centre on the ground, moved `lift` along the ground's normal, as world corners.
    pub(crate) fn square(&self, half: f64, lift: f64) -> [[f64; 3]; 4] {
        let [x, z] = self.decal_centre();
        let long = half * self.length;
        let k = 1.0 / (1.0 + self.tilt * self.tilt).sqrt();
        let on = |x: f64, z: f64| [x - self.tilt * k * lift, self.surface(x, z) + k * lift, z];
        [
            on(x - half, z + long),
            on(x + half, z + long),
            on(x + half, z - long),
            on(x - half, z - long),
        ]
    }

    pub(crate) fn decal_world(&self) -> [[f32; 3]; 4] {
        if self.drawn_through() != ModelView::None {
            // What the engine knows of its decal entity's corners: the f32 model matrix applied
            // to the unit quad.
            let m = self.decal_model();
            return MODEL_QUAD.map(|p| transformed(&m, p).map(|c| c as f32));
        }
        self.square(self.size / 2.0, 0.0)
            .map(|p| p.map(|c| c as f32))
    }

    /// What the engine says of its vertex pipeline and framebuffer. The shader computes
    /// `proj * (view * p)`, the eye position first. World-space base and decal through the view
    /// matrix, or a decal entity whose model-view is multiplied in double: that view matrix and
    /// the world box of the base's triangles under the decal (which holds the decal's corners
    /// and its model origin). A model-view multiplied in f32: `world_reach`, the largest
    /// coordinate of the camera's position and of the decal's model origin. One view-projection
    /// ([`Case::combined`]): `eye_first` false, the view and the box as for a model-view in
    /// double (the model matrix is applied in the shader; no model-view is multiplied).
    pub(crate) fn pipeline(&self, world_box: [[f64; 3]; 2]) -> Pipeline {
        let largest = |a: f64, p: &[f64]| p.iter().fold(a, |a, c| a.max(c.abs()));
        let camera_reach = largest(0.0, &self.camera());
        let floats = !self.combined
            && (self.drawn_through() == ModelView::Float || self.chunked() == ModelView::Float);
        let (view, world_box, world_reach) = if floats {
            // Every model's origin: the decal entity's, the chunks' under the decal.
            let mut reach = camera_reach;
            if self.drawn_through() == ModelView::Float {
                let m = self.decal_model();
                reach = largest(reach, &[m[12], m[13], m[14]].map(f64::from));
            }
            if self.chunked() == ModelView::Float {
                for (ci, cj) in self.chunks_under_decal() {
                    reach = largest(
                        reach,
                        &self.chunk_centre(ci, cj).map(|c| f64::from(c as f32)),
                    );
                }
            }
            (None, None, reach)
        } else if self.chunked() != ModelView::None {
            // The chunks' whole extents: centred on their origins, their world corners.
            let mut points: Vec<[f64; 3]> = world_box.to_vec();
            for (ci, cj) in self.chunks_under_decal() {
                points.extend(self.chunk_corners(ci, cj));
            }
            (Some(self.view()), Some(bounding_box(&points)), camera_reach)
        } else {
            (Some(self.view()), Some(world_box), camera_reach)
        };
        Pipeline {
            world_reach,
            eye_first: !self.combined,
            view,
            world_box,
            viewport_origin: self.origin,
            depth_range: self.depth_range,
        }
    }

    /// How the decal is drawn through its own model matrix ([`Case::model_decal`]; mesh decals
    /// and the hills' decals are world-space triangles).
    pub(crate) fn drawn_through(&self) -> ModelView {
        if self.mesh_decal || self.ground == Ground::Hills {
            ModelView::None
        } else {
            self.model_decal
        }
    }

    /// The decal entity's model matrix (column-major, f32 as an engine stores it): the unit
    /// quad [`MODEL_QUAD`] onto the decal's square, x and z along its sides, the translation its
    /// centre on the ground.
    fn decal_model(&self) -> [f32; 16] {
        let q = self.square(self.size / 2.0, 0.0);
        let x_axis = [0, 1, 2].map(|k| q[1][k] - q[0][k]);
        let z_axis = [0, 1, 2].map(|k| q[0][k] - q[3][k]);
        let centre = [0, 1, 2].map(|k| q.iter().map(|c| c[k]).sum::<f64>() / 4.0);
        let mut m = [0.0f32; 16];
        for k in 0..3 {
            m[k] = x_axis[k] as f32;
            m[8 + k] = z_axis[k] as f32;
            m[12 + k] = centre[k] as f32;
        }
        m[5] = 1.0;
        m[15] = 1.0;
        m
    }

    /// How the scene's vertices reach the shader and what zshift is told: world space through
    /// the view (the view and box); a model-view multiplied in double (the view and a box of
    /// the models' extents); in f32 (`world_reach`).
    pub(crate) fn told(&self) -> &'static str {
        let kinds = [self.drawn_through(), self.chunked()];
        if self.combined {
            "view-projection f32, view + box"
        } else if kinds.contains(&ModelView::Float) {
            "model-view f32, world_reach"
        } else if kinds.contains(&ModelView::Double) {
            "model-view double, view + box"
        } else {
            "world space, view + box"
        }
    }

    /// How the ground is drawn through model matrices of its own ([`Case::ground_chunks`]).
    pub(crate) fn chunked(&self) -> ModelView {
        if self.ground == Ground::Grid {
            self.ground_chunks
        } else {
            ModelView::None
        }
    }

    /// A chunk's centre in world space (its model matrix's translation, before f32): chunk
    /// `(ci, cj)` holds the grid's cells `8ci..8ci + 8` in x and `8cj..8cj + 8` in z.
    fn chunk_centre(&self, ci: i64, cj: i64) -> [f64; 3] {
        let side = 2.0 * self.ground_half() / 64.0 * f64::from(CHUNK_CELLS);
        let x = self.translate - self.ground_half() + side * (ci as f64 + 0.5);
        let z = self.translate - self.ground_half() + side * (cj as f64 + 0.5);
        [x, self.height(x), z]
    }

    /// The chunks that hold the cells the decal touches.
    fn chunks_under_decal(&self) -> Vec<(i64, i64)> {
        let chunk = |cell: i64| (cell / i64::from(CHUNK_CELLS)).clamp(0, CHUNKS - 1);
        let [[i0, i1], [j0, j1]] = self.cells_under_decal();
        let mut out = Vec::new();
        for ci in chunk(i0)..=chunk(i1) {
            for cj in chunk(j0)..=chunk(j1) {
                out.push((ci, cj));
            }
        }
        out
    }

    /// The world corners of chunk `(ci, cj)` (on the ground's plane).
    fn chunk_corners(&self, ci: i64, cj: i64) -> Vec<[f64; 3]> {
        let half = self.ground_half() / 64.0 * f64::from(CHUNK_CELLS);
        let [x, _, z] = self.chunk_centre(ci, cj);
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(a, b)| [x + a * half, self.height(x + a * half), z + b * half])
            .collect()
    }

    /// The ground as drawn in chunks ([`Case::ground_chunks`]): per chunk, its triangles in its
    /// local coordinates (f32 of the exact offsets from its centre) and its model matrix.
    pub(crate) fn ground_parts(&self) -> Option<Vec<Chunk>> {
        let kind = self.chunked();
        if kind == ModelView::None {
            return None;
        }
        let cells = i64::from(CHUNK_CELLS);
        let mut parts = Vec::new();
        for ci in 0..CHUNKS {
            for cj in 0..CHUNKS {
                let c = self.chunk_centre(ci, cj);
                let t = self.cell_triangles(
                    ci * cells..(ci + 1) * cells,
                    cj * cells..(cj + 1) * cells,
                    c,
                );
                let mut model = [0.0f32; 16];
                (model[0], model[5], model[10], model[15]) = (1.0, 1.0, 1.0, 1.0);
                model[12..15].copy_from_slice(&c.map(|v| v as f32));
                parts.push((t, model));
            }
        }
        Some(parts)
    }

    /// The decal as drawn: its triangles and where they are given (world-space triangles, or
    /// the unit quad through its model matrix).
    pub(crate) fn decal_draw(&self) -> (Vec<[f32; 3]>, Placement) {
        match self.drawn_through() {
            ModelView::None => (self.decal_triangles(), None),
            kind => (
                quad_triangles(&MODEL_QUAD),
                Some((self.decal_model(), kind)),
            ),
        }
    }

    /// The two matrices of the shader's `proj * (view * p)` for a mesh placed as `placement`
    /// and projected by `proj`: eye first, the model-view and `proj`; [`Case::combined`], the
    /// model matrix (the identity for world space: `I·p` is exact in f32) and the f32 product
    /// `proj·V`, so that the shader computes `viewProj * (model * p)`.
    pub(crate) fn shader_matrices(&self, placement: Placement, proj: &[f32; 16]) -> [[f32; 16]; 2] {
        let view = self.view();
        if self.combined {
            let model = placement.map_or(IDENTITY, |(m, _)| m);
            return [model, zshift_harness::world::model_view(proj, &view, true)];
        }
        let model_view = placement.map_or(view, |(m, kind)| model_view(&view, &m, kind));
        [model_view, *proj]
    }

    /// The decal's triangles as drawn: the quad of its corners, or the mesh decal
    /// ([`Case::mesh_decal`]).
    pub(crate) fn decal_triangles(&self) -> Vec<[f32; 3]> {
        if self.mesh_decal || self.ground == Ground::Hills {
            clip_to_square(&self.ground(), self.decal_square(1.0))
                .into_iter()
                .flat_map(|(_, piece)| piece)
                .collect()
        } else {
            quad_triangles(&self.decal_world())
        }
    }

    /// The decal's square in world x and z, scaled by `scale` about its centre, as f32 bounds
    /// `[x0, x1, z0, z1]` (what a decal system clips the ground's triangles to).
    pub(crate) fn decal_square(&self, scale: f64) -> [f32; 4] {
        let half = scale * self.size / 2.0;
        let long = half * self.length;
        let [cx, cz] = self.decal_centre();
        [cx - half, cx + half, cz - long, cz + long].map(|v| v as f32)
    }

    /// Every decal corner between the near and far planes (a decal partly off screen at the
    /// sides is drawn: the rasterizer clips it, and the model knows from its corners).
    pub(crate) fn decal_in_depth(&self) -> bool {
        let (.., n, f) = self.frustum().parameters();
        let depths = self.decal_world().map(|p| -self.eye(p.map(f64::from))[2]);
        let in_front_of_far = |d: &f64| *d < f * 0.99;
        (if self.beyond {
            depths.iter().any(in_front_of_far) && depths.iter().any(|&d| d > f * 1.01)
        } else {
            depths.iter().all(in_front_of_far)
        }) && if self.behind {
            depths.iter().any(|&d| d > n * 1.01)
        } else {
            depths.iter().all(|&d| d > n * 1.01)
        }
    }

    /// Whether the decal reaches behind the near plane (some of it in front): drawn only when
    /// [`Case::behind`] allows it.
    pub(crate) fn crosses_near(&self) -> bool {
        Case {
            behind: true,
            ..*self
        }
        .decal_in_depth()
            && !Case {
                behind: false,
                ..*self
            }
            .decal_in_depth()
    }

    pub(crate) fn framebuffer(&self) -> [u32; 2] {
        [
            self.origin[0] + viewport()[0] + 8,
            self.origin[1] + viewport()[1] + 8,
        ]
    }

    pub(crate) fn window(&self) -> Window {
        Window {
            viewport: [
                self.origin[0] as i32,
                self.origin[1] as i32,
                viewport()[0] as i32,
                viewport()[1] as i32,
            ],
            depth_range: self.depth_range,
        }
    }

    pub(crate) fn tests(&self) -> (u32, DepthTest) {
        match (self.reversed(), self.equal_test) {
            (false, false) => (glow::LESS, DepthTest::Less),
            (false, true) => (glow::LEQUAL, DepthTest::LessEqual),
            (true, false) => (glow::GREATER, DepthTest::Greater),
            (true, true) => (glow::GEQUAL, DepthTest::GreaterEqual),
        }
    }

    /// The world positions of the grid's vertices around the cells the decal touches (a decal
    /// system knows them: it projects onto them).
    fn decal_cell_corners(&self) -> Vec<[f64; 3]> {
        let [[i0, i1], [j0, j1]] = self.cells_under_decal();
        let mut out = Vec::new();
        for i in i0..=i1 + 1 {
            for j in j0..=j1 + 1 {
                out.push(self.lattice_vertex(i, j));
            }
        }
        out
    }

    /// The 64×64 grid's cells the decal touches: the first and last cell index in x and in z.
    fn cells_under_decal(&self) -> [[i64; 2]; 2] {
        let step = 2.0 * self.ground_half() / 64.0;
        let [cx, cz] = self.decal_centre();
        let half = self.size / 2.0;
        let cell = |v: f64| ((v - (self.translate - self.ground_half())) / step).floor() as i64;
        [
            [cell(cx - half), cell(cx + half)],
            [cell(cz - half), cell(cz + half)],
        ]
    }

    /// What the engine passes as `base_reach`: the largest |x|, |y| or |z| of the eye-space
    /// vertices of the ground triangles under the decal, or 0 when those lie inside the frustum
    /// (the rasterizer clips none of them). One quad: its corners. A grid: the cells the decal
    /// touches.
    pub(crate) fn base_reach(&self) -> f64 {
        if self.ground == Ground::Quad {
            return self.quad_reach();
        }
        self.reach_of(&self.decal_cell_corners())
    }

    /// The `base_reach` of triangles with these world vertices: the largest |x|, |y| or |z| of
    /// their eye coordinates if the rasterizer clips any (a vertex outside the frustum), else 0.
    pub(crate) fn reach_of(&self, vertices: &[[f64; 3]]) -> f64 {
        let fr = self.frustum();
        let (l, r, b, t, n, f) = fr.parameters();
        let mut reach = 0.0f64;
        let mut clipped = false;
        for &p in vertices {
            let e = self.eye(p);
            let d = -e[2];
            let inside = d > n
                && d < f
                && e[0] / d > l / n
                && e[0] / d < r / n
                && e[1] / d > b / n
                && e[1] / d < t / n;
            clipped |= !inside;
            reach = e.iter().fold(reach, |a, c| a.max(c.abs()));
        }
        if clipped {
            reach
        } else {
            0.0
        }
    }

    /// What the engine passes as `world_box`: the world-space box of the ground's vertices
    /// under the decal, which holds the decal's corners too. One quad: its corners, the whole
    /// ground. A grid: the cells the decal touches (no other vertex reaches the decal's pixels).
    pub(crate) fn world_box(&self) -> [[f64; 3]; 2] {
        let (g, ground) = (self.translate, self.ground_half());
        if self.ground == Ground::Quad {
            let (y0, y1) = (self.height(g - ground), self.height(g + ground));
            return [
                [g - ground, y0.min(y1), g - ground],
                [g + ground, y0.max(y1), g + ground],
            ];
        }
        bounding_box(&self.decal_cell_corners())
    }

    /// The ground quad cut to the frustum in f64 (`zshift::recommend::clip_to_frustum_stored`,
    /// on its eye-space corners, inside by what storing it in world space can move a vertex)
    /// and carried back to world space as an engine stores it (f32), as triangles of a fan;
    /// `None` for the grid. (Cut by the plain `clip_to_frustum`, 2⁻¹⁶ inside, a vertex 0.47
    /// ahead of a camera 367 units from the origin landed 0.008 pixel outside the screen's
    /// edge, llvmpipe clipped a sliver off its triangle, and one pixel of the sliver was 0.37
    /// pixel of depth gradient off the plane: a decal pixel lost, `ZSHIFT_ENGINE_SCENES_SEED=14`.)
    pub(crate) fn cut_ground(&self) -> Option<Vec<[f32; 3]>> {
        if self.ground != Ground::Quad {
            return None;
        }
        let eye: Vec<[f64; 3]> = self.quad_corners().map(|p| self.eye(p)).to_vec();
        // Stored in world space: cut inside by what that storage can move a vertex.
        let pipeline = self.pipeline(self.world_box());
        let cut =
            zshift::recommend::clip_to_frustum_stored(&self.frustum(), &eye, &pipeline).ok()?;
        let (r, c) = (self.rotation(), self.camera());
        let world: Vec<[f32; 3]> = cut
            .iter()
            .map(|e| [0, 1, 2].map(|j| ((0..3).map(|i| r[i][j] * e[i]).sum::<f64>() + c[j]) as f32))
            .collect();
        Some(
            (1..world.len().saturating_sub(1))
                .flat_map(|i| [world[0], world[i], world[i + 1]])
                .collect(),
        )
    }

    /// The ground quad's world corners (f64), in order around it.
    fn quad_corners(&self) -> [[f64; 3]; 4] {
        let (g, ground) = (self.translate, self.ground_half());
        [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]].map(|[sx, sz]| {
            let x = g + sx * ground;
            [x, self.height(x), g + sz * ground]
        })
    }

    /// The largest |x|, |y| or |z| of the ground quad's eye-space corners.
    fn quad_reach(&self) -> f64 {
        self.quad_corners()
            .iter()
            .map(|&p| self.eye(p).iter().fold(0.0f64, |a, c| a.max(c.abs())))
            .fold(0.0, f64::max)
    }

    pub(crate) fn label(&self) -> String {
        format!(
            "{} pitch {}° yaw {}°{} T {}{:+?}{} {} n {} f {} decal {}@{}{} {} vp@{:?} range {:?}",
            self.at.label,
            self.pitch_deg,
            self.yaw_deg,
            tag(self.roll_deg != 0.0, || format!(" roll {}°", self.roll_deg)),
            self.translate,
            self.jitter,
            tag(self.ground_y != 0.0 || self.fovy_deg != FOVY_DEG, || {
                format!(
                    " ground y {} fovy {}° units {} eye {} skew {:?}",
                    self.ground_y, self.fovy_deg, self.scale, self.eye_height, self.skew
                )
            }) + &tag(self.tilt != 0.0, || format!(" hillside {}", self.tilt)),
            self.ground.label().to_string()
                + if self.mesh_decal {
                    " mesh"
                } else if self.drawn_through() == ModelView::Double {
                    " model"
                } else if self.drawn_through() == ModelView::Float {
                    " model f32"
                } else {
                    ""
                }
                + match self.chunked() {
                    ModelView::None => "",
                    ModelView::Double => " chunks",
                    ModelView::Float => " chunks f32",
                }
                + if self.combined { " viewproj" } else { "" },
            self.near,
            self.far,
            self.size,
            self.distance,
            if self.side != 0.0 { " side" } else { "" },
            if self.equal_test { "EQUAL" } else { "strict" },
            self.origin,
            self.depth_range
        ) + &tag(self.samples > 1, || format!(" {}xMSAA", self.samples))
            + &tag(self.length != 1.0, || format!(" long ×{}", self.length))
            + &tag(self.stretch != 1.0, || format!(" ground ×{}", self.stretch))
    }
}

/// A part of a label: `text` where `on`, else nothing.
pub(crate) fn tag(on: bool, text: impl FnOnce() -> String) -> String {
    if on {
        text()
    } else {
        String::new()
    }
}

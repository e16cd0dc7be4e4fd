//! Edges drawn over their own faces on a real rasterizer (headless EGL; Mesa llvmpipe in CI):
//! `zshift::lines` against a reference of which face is in front at every edge pixel.
//!
//! Meshes: a UV sphere, a tilted torus, a 64 × 64 terrain with hills (wider than the view) and a
//! chamfered box (eye-space f32 vertices, every triangle edge drawn), f/n 10, 10³ and 10⁶, the
//! mesh near, in the middle and far in the depth range, on D16, D24 and D32F under `[−1, 1]`,
//! `[0, 1]` and reversed Z; faces `GL_LESS` (`GL_GREATER`), edges `GL_LEQUAL` (`GL_GEQUAL`);
//! 1-pixel `GL_LINES` and polygon-mode lines; both methods (faces pushed back by
//! `glPolygonOffset`, edges pulled forward through element 10/14); the worst-case profile
//! (unsnapped, as llvmpipe sets its depth plane up) and the profile `zshift::probe` measures in
//! the same context; width-3 lines (a compatibility context) and 4× MSAA (every sample checked
//! against its own reference) in fewer scenes. The default run draws one scene in [`SAMPLE`]
//! (every mesh, f/n and position in turn), the width-3 and MSAA variants one in [`SAMPLE_MORE`];
//! `ZSHIFT_LINES_FULL=1` draws the whole grid (`ZSHIFT_LINES_SHARD=<i>/<n>` one `n`th of its
//! cells, for processes side by side); `ZSHIFT_LINES_SEED=<n>` another draw
//! ([`Variation`]); `ZSHIFT_LINES_VARIANT=<text>` only the variants whose name contains it
//! (`MSAA`, `w3`, `polymode`); `ZSHIFT_LINES_WIDE=<w>` the wide variants `w` pixels wide instead
//! of 3 (`w2`, `w5` in their names); `ZSHIFT_LINES_ONLY=<text>` only the scenes whose label contains it,
//! and with `ZSHIFT_LINES_VERBOSE=1` each scene's zshift ÷ smallest working offset, and each lost
//! pixel of a failing scene and the offsets that keep it.
//!
//! **Refusals**: in every answered scene with a smallest working offset, zshift is asked again
//! with `hidden_separation` half its gap (it must refuse), and the smallest offset that keeps
//! every visible edge is checked for hidden pixels beyond that separation: the counts of
//! refusals so confirmed, and of those where that offset does both (zshift's gap is
//! conservative there), are printed.
//!
//! **Reference** (f64, from the f32 vertices and the f64 matrix, nothing from `zshift::lines`):
//! an exact z-buffer of the faces at every pixel centre (which triangle is in front and its
//! `1/d`), and for every edge that drew a pixel (two ID renders with `gl_PrimitiveID`, forward
//! and reversed order) its exact depth at the pixel (the point of the edge at the pixel's
//! major-axis coordinate). A pixel is **visible** when the front face contains the edge, or the
//! edge is in front of the front face; **hidden beyond the gap** when every edge that drew it lies
//! behind the front face by more than zshift's hidden-line gap (eye depth). Pixels on faces
//! steeper than the face-slope limit (window gradient above the model's `g`), of edges whose own
//! gradient along the line exceeds `g` or that border a face steeper than `g`, and within 2
//! pixels of a vertex (where more than two edges meet) are not counted. Asserted: 0 visible pixels lost and 0 hidden pixels shown in
//! every scene zshift answers. Printed: the peers' constants beside zshift (lost over the visible
//! pixels; shown over every hidden-edge pixel, behind its front face by any amount, as the
//! issue's figures count them), and zshift's offset ÷ the smallest working one (bisection on a
//! common scale of the offset) per class.
//!
//! `cargo test --release --test gl_lines -- --nocapture` prints the table. Fails (never skips)
//! without GL.
//!
//! `engine::edges_drawn_as_engines_draw` (`tests/gl_lines/engine.rs`): the same meshes in world
//! space far from the origin, through an f32 view matrix, in a viewport inside a larger
//! framebuffer, under `glDepthRange` sub-ranges.

mod gl_common;
// The same meshes drawn as engines draw them (world space, a viewport inside a larger
// framebuffer, glDepthRange): a test of its own.
#[path = "gl_lines/engine.rs"]
mod engine;
// How wide GL draws a line between integer widths, against the width the model takes.
#[path = "gl_lines/width.rs"]
mod width;

use zshift::lines::{
    recommend, recommend_for_mesh, EdgeMethod, Edges, FaceSlope, LineKind, MeshDraw,
};
use zshift::precision::DepthFormat as Format;
use zshift::projection::{projection, projection_f64, ClipDepth, Frustum};
use zshift::recommend::{DepthTest, RasterizerProfile};
use zshift_harness::draw::Xorshift;
use zshift_harness::edges::meshes::{chamfered_box, finish, place, sphere, terrain, torus};
use zshift_harness::edges::{
    classify, edge_at, edge_ids, project, reference, Draw, Limit, Mesh, Msaa, Primitive, Reference,
    Renderer, Scene, Variant, EDGE, SIZE,
};
use zshift_harness::{ClipDepth as GlClip, DepthFormat, Gl, Profile};

/// The default run draws 1-pixel lines and polygon-mode lines in one scene in `SAMPLE` of the
/// grid, a different choice of scenes per format and convention (`ZSHIFT_LINES_FULL=1`: all).
const SAMPLE: usize = 11;
/// The default run draws the width-3 and MSAA variants in one scene in `SAMPLE_MORE`.
const SAMPLE_MORE: usize = 29;
/// The face-slope limit the engine passes: faces up to 60° from the view axis.
const ANGLE_DEG: f64 = 60.0;

/// A mesh generator: the sweep's meshes at a size and a distance.
type MeshMaker = fn(f64, f64) -> Mesh;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Conv {
    Std,
    ZeroOne,
    Reversed,
}

impl Conv {
    fn clip(self) -> ClipDepth {
        match self {
            Conv::Std => ClipDepth::NegOneToOne,
            Conv::ZeroOne => ClipDepth::ZeroToOne,
            Conv::Reversed => ClipDepth::ReversedZeroToOne,
        }
    }
    fn name(self) -> &'static str {
        match self {
            Conv::Std => "[-1,1]",
            Conv::ZeroOne => "[0,1]",
            Conv::Reversed => "rev",
        }
    }
}

/// The variants of the sweep: 1-pixel `GL_LINES` and polygon-mode lines; width-3 `GL_LINES`
/// (the context is a compatibility one, where `glLineWidth(3)` is valid); the same under 4×
/// MSAA; width-3 polygon-mode lines, and 1-pixel ones under 4× MSAA. The default run draws the
/// first two in one scene in [`SAMPLE`], the others in one in [`SAMPLE_MORE`].
const VARIANTS: [Variant; 8] = [
    Variant {
        kind: Primitive::Lines,
        width: 1.0,
        samples: 1,
    },
    Variant {
        kind: Primitive::PolygonMode,
        width: 1.0,
        samples: 1,
    },
    Variant {
        kind: Primitive::Lines,
        width: 3.0,
        samples: 1,
    },
    Variant {
        kind: Primitive::Lines,
        width: 1.0,
        samples: 4,
    },
    Variant {
        kind: Primitive::Lines,
        width: 3.0,
        samples: 4,
    },
    Variant {
        kind: Primitive::PolygonMode,
        width: 3.0,
        samples: 1,
    },
    Variant {
        kind: Primitive::PolygonMode,
        width: 1.0,
        samples: 4,
    },
    Variant {
        kind: Primitive::PolygonMode,
        width: 3.0,
        samples: 4,
    },
];

/// zshift's name for how the edges are drawn.
fn line_kind(kind: Primitive) -> LineKind {
    match kind {
        Primitive::Lines => LineKind::Lines,
        Primitive::PolygonMode => LineKind::PolygonMode,
    }
}

/// The draw for `method` with every offset scaled by `s` (s = 1: zshift's).
fn scaled(rec: &zshift::lines::EdgeRecommendation, m: &[f32; 16], clip: ClipDepth, s: f64) -> Draw {
    let sign = if clip == ClipDepth::ReversedZeroToOne {
        -1.0
    } else {
        1.0
    };
    match rec.method {
        EdgeMethod::PolygonOffset => Draw {
            face_offset: Some((
                (sign * s * rec.polygon_offset[0]) as f32,
                (sign * s * rec.polygon_offset[1]) as f32,
            )),
            edge_matrix: *m,
        },
        EdgeMethod::Matrix => Draw {
            face_offset: None,
            edge_matrix: if clip == ClipDepth::ReversedZeroToOne && rec.relative_epsilon > 0.0 {
                let mut out = *m;
                out[14] = (f64::from(m[14]) * (1.0 + s * rec.relative_epsilon)) as f32;
                if s == 1.0 {
                    rec.matrix
                } else {
                    out
                }
            } else if s == 1.0 {
                rec.matrix
            } else {
                zshift::matrix_in::offset_ndc(m, clip, -s * rec.ndc_offset).unwrap()
            },
        },
    }
}

/// What the sweeps tell zshift about a mesh over eye depths `depths`: the format, the variant's
/// line kind, width and samples, the profile, the face-slope limit, the edge pass's test.
fn edges_for(
    fmt: DepthFormat,
    conv: Conv,
    variant: Variant,
    profile: RasterizerProfile,
    depths: [f64; 2],
) -> Edges {
    let mut edges = Edges::new([SIZE, SIZE], zshift_format(fmt), depths);
    edges.kind = line_kind(variant.kind);
    edges.line_width = f64::from(variant.width);
    edges.samples = variant.samples;
    edges.profile = profile;
    edges.face_slope = FaceSlope::Angle(ANGLE_DEG.to_radians());
    edges.depth_test = if conv == Conv::Reversed {
        DepthTest::GreaterEqual
    } else {
        DepthTest::LessEqual
    };
    edges
}

/// The worst-case profile with this context's snapping, and the profile the probe measures in it.
fn profiles(gl: &Gl) -> [(&'static str, RasterizerProfile); 2] {
    let worst = RasterizerProfile {
        snapping: gl_common::snapping_of(gl),
        ..RasterizerProfile::worst_case()
    };
    [("worst", worst), ("probed", gl_common::probed(gl))]
}

/// The ways zshift is asked: the face-slope limit as an angle with the worst-case and the probed
/// profile, and with the probed profile the mesh's own steepest face within that angle's gradient
/// (`zshift::steepest_face`; `true`).
fn asks(
    profiles: &[(&'static str, RasterizerProfile); 2],
) -> [(&'static str, RasterizerProfile, bool); 3] {
    [
        (profiles[0].0, profiles[0].1, false),
        (profiles[1].0, profiles[1].1, false),
        ("probed mesh", profiles[1].1, true),
    ]
}

/// zshift's answer for `edges`: with the mesh's own steepest faces (`lines::recommend_for_mesh`)
/// where `mesh` is given, else from the face-slope limit alone.
fn ask(
    m: &[f32; 16],
    clip: ClipDepth,
    edges: &Edges,
    method: EdgeMethod,
    mesh: Option<&MeshDraw>,
) -> zshift::Result<zshift::lines::EdgeRecommendation> {
    match mesh {
        Some(draw) => recommend_for_mesh(m, clip, edges, method, draw).map(|(r, _)| r),
        None => recommend(m, clip, edges, method),
    }
}

/// The triangles of `mesh` as `GL_TRIANGLES` indices.
/// The faces an ask promises to keep the edges of (harness [`Limit`]): against a face-slope
/// angle under MSAA, those whose whole gradient is within the angle's `g` (the line term is
/// `g·min(Δ, across)`: every face within the angle has `|∇z| ≤ g`); a mesh's own faces
/// (`from_mesh`) and single-sampled lines, those whose larger component is.
fn limit_of(edges: &Edges, from_mesh: bool, g: f64) -> Limit {
    if !from_mesh && edges.samples > 1 && matches!(edges.face_slope, FaceSlope::Angle(_)) {
        Limit::Length(g)
    } else {
        Limit::MaxComponent(g)
    }
}

fn triangle_indices(mesh: &Mesh) -> Vec<u32> {
    mesh.tris.iter().flatten().copied().collect()
}

/// `make`'s mesh near eye distance `d0`, moved to lie inside `[1.1n, 0.95f]` (its depth extent
/// per unit of distance taken from a unit mesh), its radius `radius_factor` of its distance;
/// and that distance.
fn placed(make: MeshMaker, n: f64, f: f64, d0: f64, radius_factor: f64) -> (Mesh, f64) {
    let (lo, hi) = make(0.3, 1.0).depth_range();
    let d = d0.max(1.1 * n / lo).min(0.95 * f / hi);
    (make(radius_factor * d, d), d)
}

#[derive(Default)]
struct Class {
    scenes: usize,
    answered: usize,
    refused: usize,
    lost: usize,
    shown: usize,
    visible: usize,
    hidden: usize,
    ratios: Vec<f64>,
    none_needed: usize,
    peer_scenes: usize,
    peer_visible: usize,
    peer_hidden: usize,
    peers: Vec<(usize, usize)>,
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

const PEERS: [(&str, f32, f32); 5] = [
    ("(1,1)", 1.0, 1.0),
    ("(2,2)", 2.0, 2.0),
    ("(0,4)", 0.0, 4.0),
    ("(0,8)", 0.0, 8.0),
    ("(1,0)", 1.0, 0.0),
];
const SEED_SHIFTS: [f64; 2] = [1e-3, 1e-2];

/// `ZSHIFT_LINES_SEED=<n>`: another draw of the sweep (0, the default, is the grid CI runs):
/// f/n anywhere in the decade above each of the grid's, the mesh's position in the depth range
/// moved by up to ±0.07 of its log, its radius 0.2–0.4 of its distance (0.3) and the frustum's
/// half width 0.3–0.9 of the near distance (0.5).
struct Variation(Xorshift);

impl Variation {
    fn from_env() -> Self {
        let seed = zshift_harness::draw::seed("ZSHIFT_LINES_SEED");
        Variation(Xorshift(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15)))
    }

    /// A number in [0, 1) (53 bits), or `None` for the default grid (seed 0, state 0).
    fn unit(&mut self) -> Option<f64> {
        if self.0 .0 == 0 {
            return None;
        }
        Some((self.0.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    fn ratio_factor(&mut self) -> f64 {
        self.unit().map_or(1.0, |r| 10f64.powf(0.9 * r))
    }

    fn position_shift(&mut self) -> f64 {
        self.unit().map_or(0.0, |r| 0.14 * (r - 0.5))
    }

    fn radius_factor(&mut self) -> f64 {
        self.unit().map_or(0.3, |r| 0.2 + 0.2 * r)
    }

    fn half_width(&mut self) -> f64 {
        self.unit().map_or(0.5, |r| 0.3 + 0.6 * r)
    }
}

#[test]
fn edges_over_faces_sweep() {
    let full = std::env::var_os("ZSHIFT_LINES_FULL").is_some_and(|v| v != "0");
    let mut draw = Variation::from_env();
    // `ZSHIFT_LINES_VARIANT=<text>`: only the variants whose name contains it ("MSAA", "w3").
    let only = std::env::var("ZSHIFT_LINES_VARIANT").ok();
    // `ZSHIFT_LINES_WIDE=<w>`: the wide variants drawn `w` pixels wide instead of 3.
    let wide = std::env::var("ZSHIFT_LINES_WIDE").ok().map(|w| {
        w.parse::<f32>()
            .ok()
            .filter(|w| *w > 1.0)
            .unwrap_or_else(|| panic!("ZSHIFT_LINES_WIDE={w}: expected a width above 1, e.g. 2"))
    });
    // `ZSHIFT_LINES_ONLY=<text>`: only the scenes whose label contains it (for looking at one).
    let only_scene = std::env::var("ZSHIFT_LINES_ONLY").ok();
    // `ZSHIFT_LINES_VERBOSE=1`: each scene's ratio, and each lost pixel of a failing scene.
    let verbose = std::env::var_os("ZSHIFT_LINES_VERBOSE").is_some();
    // `ZSHIFT_LINES_SHARD=<i>/<n>`: only the cells (format, convention, f/n, position, mesh)
    // whose index is i modulo n.
    let (shard, shards) = gl_common::shard("ZSHIFT_LINES_SHARD");
    let mut gl =
        Gl::new(Profile::Compatibility).unwrap_or_else(|e| panic!("no OpenGL context: {e}"));
    let renderer = Renderer::new(gl.glow());
    let profiles = profiles(&gl);
    let probed = profiles[1].1;
    println!(
        "probed line_reach {:?}, line_reach_msaa {:?}, line_reach_wide {:?}, offset_slope {}",
        probed.line_reach, probed.line_reach_msaa, probed.line_reach_wide, probed.offset_slope
    );
    let mut classes: Vec<(String, Class)> = Vec::new();
    let mut failures = Vec::new();
    let mut refusals = Refusals::default();
    // Edge samples on a boundary of their front face, left unjudged (`BOUNDARY_TIE`).
    let mut ties = 0usize;
    // Mesh asks not made: the angle that sets their limit was refused.
    let mut angle_refused = 0usize;
    let meshes: [(&str, MeshMaker); 4] = [
        ("sphere", sphere),
        ("torus", torus),
        ("terrain", terrain),
        ("chamfered box", chamfered_box),
    ];
    for (fi, fmt) in DepthFormat::ALL.into_iter().enumerate() {
        gl.set_target(SIZE, SIZE, fmt).unwrap();
        let msaa = Msaa::new(&gl, fmt, 4);
        for (ci, conv) in [Conv::Std, Conv::ZeroOne, Conv::Reversed]
            .into_iter()
            .enumerate()
        {
            gl.clip_control(if conv == Conv::Std {
                GlClip::NegativeOneToOne
            } else {
                GlClip::ZeroToOne
            })
            .unwrap_or_else(|e| panic!("glClipControl is needed: {e}"));
            for (ri, ratio) in [10.0f64, 1e3, 1e6].into_iter().enumerate() {
                let ratio = ratio * draw.ratio_factor();
                let n = 1.0f64;
                let f = n * ratio;
                for (pi, (pos, frac)) in [("near", 0.15), ("mid", 0.5), ("far", 0.85)]
                    .into_iter()
                    .enumerate()
                {
                    let frac = frac + draw.position_shift();
                    let d0 = (n * ratio.powf(frac)).max(1.6 * n).min(0.7 * f);
                    for (mi, (_, make)) in meshes.iter().enumerate() {
                        // The default run samples one scene in SAMPLE (the meshes in turn at
                        // every f/n and position); ZSHIFT_LINES_FULL=1 runs the whole grid.
                        let idx = (ri * 3 + pi) * meshes.len() + mi;
                        let cell = ((fi * 3 + ci) * 9 + ri * 3 + pi) * meshes.len() + mi;
                        if cell % shards != shard {
                            continue;
                        }
                        let variants: Vec<Variant> = VARIANTS
                            .into_iter()
                            .map(|v| match wide {
                                Some(width) if v.width > 1.0 => Variant { width, ..v },
                                _ => v,
                            })
                            .filter(|v| only.as_ref().is_none_or(|o| v.name().contains(o.as_str())))
                            .filter(|v| {
                                let turn = idx + 5 * (fi * 3 + ci);
                                full || if v.width == 1.0 && v.samples == 1 {
                                    turn % SAMPLE == 0
                                } else {
                                    (turn + 3) % SAMPLE_MORE == 0
                                }
                            })
                            .collect();
                        if variants.is_empty() {
                            continue;
                        }
                        let (mesh, d) = placed(*make, n, f, d0, draw.radius_factor());
                        // The terrain (wider than the view) does not fit in [n, f] at f/n 10:
                        // its near rows cross the near plane, a case the model leaves out.
                        if mesh
                            .verts
                            .iter()
                            .any(|v| -f64::from(v[2]) < 1.01 * n || -f64::from(v[2]) > 0.99 * f)
                        {
                            continue;
                        }
                        let t = draw.half_width() * n;
                        let frustum = Frustum::new(-t, t, -t, t, n, f).unwrap();
                        let clip = conv.clip();
                        let m = projection(&frustum, clip).unwrap();
                        let mf = projection_f64(&frustum, clip).unwrap();
                        let p = project(&mesh, &mf);
                        let rf = reference(&mesh, &p, [0.5, 0.5]);
                        let rf_msaa: Vec<Reference> = if variants.iter().any(|v| v.samples > 1) {
                            msaa.positions
                                .iter()
                                .map(|&o| reference(&mesh, &p, o))
                                .collect()
                        } else {
                            Vec::new()
                        };
                        let b = f * n / (f - n);
                        let (dmin, dmax) = mesh.depth_range();
                        renderer.load(gl.glow(), &mesh);
                        // The mesh as zshift reads it: eye-space vertices, so its clip matrix is m.
                        let indices = triangle_indices(&mesh);
                        let draw = MeshDraw {
                            clip_matrix: &m,
                            positions: &mesh.verts,
                            indices: &indices,
                        };
                        for &variant in &variants {
                            let kind = variant.kind;
                            let (ms, rfs) = if variant.samples > 1 {
                                (Some(&msaa), &rf_msaa[..])
                            } else {
                                (None, std::slice::from_ref(&rf))
                            };
                            let scene = Scene::new(
                                &gl,
                                &renderer,
                                &mesh,
                                m,
                                conv == Conv::Reversed,
                                variant,
                                ms,
                            );
                            let ids = edge_ids(&scene);
                            for method in [EdgeMethod::PolygonOffset, EdgeMethod::Matrix] {
                                for (pname, profile, from_mesh) in asks(&profiles) {
                                    let mut edges =
                                        edges_for(fmt, conv, variant, profile, [dmin, dmax]);
                                    // The mesh's own steepest faces within the angle's
                                    // gradient; the pixels judged are those of faces within the
                                    // angle's gradient, whichever way zshift is asked.
                                    let mut g_angle = f64::NAN;
                                    if from_mesh {
                                        let Ok(r) = recommend(&m, clip, &edges, method) else {
                                            angle_refused += 1;
                                            continue;
                                        };
                                        g_angle = r.face_gradient;
                                    }
                                    let label = format!(
                                        "{} {} {} {} {pname}",
                                        conv.name(),
                                        fmt.name(),
                                        variant.name(),
                                        if method == EdgeMethod::Matrix {
                                            "(b) matrix"
                                        } else {
                                            "(a) polygon offset"
                                        }
                                    );
                                    let where_ = format!("{label} {} f/n {ratio} {pos}", mesh.name);
                                    if only_scene
                                        .as_ref()
                                        .is_some_and(|o| !where_.contains(o.as_str()))
                                    {
                                        continue;
                                    }
                                    let class = class_of(&mut classes, &label);
                                    class.scenes += 1;
                                    let rec = match ask(
                                        &m,
                                        clip,
                                        &edges,
                                        method,
                                        from_mesh.then_some(&draw),
                                    ) {
                                        Ok(r) => r,
                                        Err(e) => {
                                            class.refused += 1;
                                            if e.kind() != zshift::ErrorKind::Unresolvable {
                                                failures.push(format!("{where_}: {e}"));
                                            }
                                            continue;
                                        }
                                    };
                                    class.answered += 1;
                                    let g = if from_mesh {
                                        g_angle
                                    } else {
                                        rec.face_gradient
                                    };
                                    let limit = limit_of(&edges, from_mesh, g);
                                    let c =
                                        classify(&scene, &p, rfs, &ids, b, limit, rec.hidden_gap);
                                    class.visible += c.visible.len();
                                    class.hidden += c.hidden.len();
                                    ties += c.ties;
                                    let (lost, shown) =
                                        scene.count(&scaled(&rec, &m, clip, 1.0), &c);
                                    class.lost += lost;
                                    class.shown += shown;
                                    if lost + shown > 0 {
                                        failures.push(format!("{where_}: {lost} of {} visible lost, {shown} of {} hidden shown (gap {:.3e}, {rec:?})", c.visible.len(), c.hidden.len(), rec.hidden_gap));
                                        if verbose {
                                            let faces = scene.face_ids();
                                            let img = scene.render(&scaled(&rec, &m, clip, 1.0));
                                            let n = SIZE as usize;
                                            let offsets = scene.offsets();
                                            for &j in
                                                c.visible.iter().filter(|&&j| img[j][..3] != EDGE)
                                            {
                                                let (plane, i) = (j / (n * n), j % (n * n));
                                                let front = rfs[plane].front[i];
                                                let grad = front.map(|(t, _)| {
                                                    (
                                                        b * rfs[plane].tri_grad[t],
                                                        b * rfs[plane].tri_len[t],
                                                    )
                                                });
                                                let edges_here: Vec<String> = ids[j].iter().map(|&e| {
                                                    let (inv_e, along) = edge_at(scene.mesh, &p, e, i % n, i / n, offsets[plane]);
                                                    let grads: Vec<String> = scene.mesh.edge_tris[e].iter().map(|&t| format!("{:.3e}", b * rfs[plane].tri_grad[t])).collect();
                                                    format!("edge {e} tris {:?} (gradients {}) 1/d {inv_e:.9e} along {:.3e}", scene.mesh.edge_tris[e], grads.join(", "), b * along)
                                                }).collect();
                                                println!("  lost pixel ({}, {}) sample {plane}: colour {:?}, front {front:?} (rasterized: face {}) grad (max, length) {grad:?} of g {g:.3e}; {}", i % n, i / n, img[j], faces[j] as i64 - 1, edges_here.join("; "));
                                            }
                                            let scales: Vec<String> =
                                                [1.1, 1.25, 1.5, 2.0, 4.0, 16.0, 256.0]
                                                    .iter()
                                                    .map(|&k| {
                                                        format!(
                                                            "×{k}: {}",
                                                            scene
                                                                .count(
                                                                    &scaled(&rec, &m, clip, k),
                                                                    &c
                                                                )
                                                                .0
                                                        )
                                                    })
                                                    .collect();
                                            println!(
                                                "  lost at larger offsets: {}",
                                                scales.join(", ")
                                            );
                                        }
                                    }
                                    // The smallest working scale of zshift's offset (0 lost), in
                                    // log2 steps.
                                    let works =
                                        |s: f64| scene.count(&scaled(&rec, &m, clip, s), &c).0 == 0;
                                    let (mut lo, mut hi) = (-24.0f64, 0.0f64);
                                    if works(lo.exp2()) {
                                        // Edges survive with no offset to speak of (a tie
                                        // passes): no smallest working offset to compare with.
                                        class.none_needed += 1;
                                        hi = f64::NAN;
                                    } else {
                                        for _ in 0..9 {
                                            let mid = 0.5 * (lo + hi);
                                            if works(mid.exp2()) {
                                                hi = mid
                                            } else {
                                                lo = mid
                                            }
                                        }
                                    }
                                    if hi.is_finite() {
                                        class.ratios.push((-hi).exp2());
                                        if verbose {
                                            println!(
                                                "{where_}: zshift ÷ smallest working {:.3} (window offset {:.3e}, line term {:.3e})",
                                                (-hi).exp2(),
                                                rec.window_offset,
                                                rec.line_term
                                            );
                                        }
                                    }
                                    // (ZSHIFT_LINES_FULL only: the refusal scenes below confirm
                                    // refusals where they can be.)
                                    // (Only where zshift's own offset held: a scene that failed above is
                                    // already a failure, and its bisection found no smaller offset.)
                                    if hi.is_finite() && full && lost + shown == 0 {
                                        // A refusal asked for: hidden edges must not show from
                                        // half the reported gap on. Confirmed when the smallest
                                        // offset that keeps every visible edge (the best one for
                                        // hidden edges: showing grows with the offset) shows
                                        // one of them.
                                        let sep = 0.5 * rec.hidden_gap;
                                        edges.hidden_separation = sep;
                                        match ask(&m, clip, &edges, method, from_mesh.then_some(&draw)) {
                                            Err(e) if e.kind() == zshift::ErrorKind::Unresolvable => {
                                                let cs = classify(&scene, &p, rfs, &ids, b, limit, sep);
                                                let (l, shown) = scene
                                                    .count(&scaled(&rec, &m, clip, hi.exp2()), &cs);
                                                if l > 0 {
                                                    failures.push(format!("{where_}: the smallest working offset lost {l} visible pixels on the second look"));
                                                }
                                                refusals.asked += 1;
                                                if shown > 0 {
                                                    refusals.confirmed += 1;
                                                } else if cs.hidden.is_empty() {
                                                    refusals.no_hidden_edge += 1;
                                                } else {
                                                    refusals.conservative += 1;
                                                }
                                            }
                                            other => failures.push(format!(
                                                "{where_}: hidden_separation {sep:e} below the gap {:e} not refused: {other:?}",
                                                rec.hidden_gap
                                            )),
                                        }
                                    }
                                    // The peers, once per scene, against the same visible pixels
                                    // and every hidden-edge pixel (behind its front face by any
                                    // amount), as the figures count them.
                                    if pname == "worst"
                                        && (kind == Primitive::Lines
                                            || method == EdgeMethod::PolygonOffset)
                                    {
                                        let all = classify(&scene, &p, rfs, &ids, b, limit, 0.0);
                                        let class = class_of(&mut classes, &label);
                                        class.peer_scenes += 1;
                                        class.peer_visible += all.visible.len();
                                        class.peer_hidden += all.hidden.len();
                                        let sign = if conv == Conv::Reversed { -1.0 } else { 1.0 };
                                        for (k, &(_, fa, un)) in PEERS.iter().enumerate() {
                                            let draw = Draw {
                                                face_offset: Some((sign * fa, sign * un)),
                                                edge_matrix: m,
                                            };
                                            let (l, s) = scene.count(&draw, &all);
                                            class.peers[k].0 += l;
                                            class.peers[k].1 += s;
                                        }
                                        for (k, &delta) in SEED_SHIFTS.iter().enumerate() {
                                            let em =
                                                zshift::matrix_in::offset_shift(&m, clip, delta, d)
                                                    .unwrap_or(m);
                                            let (l, s) = scene.count(
                                                &Draw {
                                                    face_offset: None,
                                                    edge_matrix: em,
                                                },
                                                &all,
                                            );
                                            class.peers[PEERS.len() + k].0 += l;
                                            class.peers[PEERS.len() + k].1 += s;
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        msaa.delete(&gl);
    }
    println!(
        "\n{} run (ZSHIFT_LINES_FULL=1 for the full grid); the peers' shown counts every hidden-edge pixel, zshift's only those beyond its reported gap",
        if full { "full grid".to_string() } else { format!("sampled, one scene in {SAMPLE}") },
    );
    println!("\n| class | scenes | answered | visible px lost | hidden px shown beyond gap | zshift ÷ smallest working (median, max; scenes needing none) | (1,1) lost/shown | (2,2) | (0,4) | (0,8) | (1,0) | δ=1e-3 | δ=1e-2 |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (label, c) in &mut classes {
        let pct = |x: usize, of: usize| 100.0 * x as f64 / of.max(1) as f64;
        let peers: Vec<String> = c
            .peers
            .iter()
            .map(|&(l, s)| {
                if c.peer_scenes == 0 {
                    "–".to_string()
                } else {
                    format!(
                        "{:.1}%/{:.1}%",
                        pct(l, c.peer_visible),
                        pct(s, c.peer_hidden)
                    )
                }
            })
            .collect();
        let max = c.ratios.iter().copied().fold(0.0, f64::max);
        println!(
            "| {label} | {} | {} | {} of {} | {} of {} | {:.2}, {:.1}; {} | {} |",
            c.scenes,
            c.answered,
            c.lost,
            c.visible,
            c.shown,
            c.hidden,
            median(&mut c.ratios),
            max,
            c.none_needed,
            peers.join(" | ")
        );
    }
    // Per profile and method over every class.
    for pname in ["worst", "probed", "probed mesh"] {
        for method in ["(a)", "(b)"] {
            for conv in ["[-1,1]", "[0,1]", "rev"] {
                let mut r: Vec<f64> = classes
                    .iter()
                    .filter(|(l, _)| {
                        l.starts_with(conv) && l.contains(method) && l.ends_with(pname)
                    })
                    .flat_map(|(_, c)| c.ratios.iter().copied())
                    .collect();
                println!(
                    "{pname} {method} {conv}: median ratio {:.2} over {} scenes",
                    median(&mut r),
                    r.len()
                );
            }
        }
    }
    println!(
        "refusals asked (hidden_separation = gap/2): {}; confirmed (the smallest offset keeping every visible edge shows a hidden one beyond the separation): {}; conservative (that offset does both): {}; no hidden edge beyond the separation in the scene: {}",
        refusals.asked, refusals.confirmed, refusals.conservative, refusals.no_hidden_edge
    );
    let judged: usize = classes.iter().map(|(_, c)| c.visible + c.hidden).sum();
    println!("mesh asks not made (the angle that sets their limit refused): {angle_refused}");
    println!(
        "edge samples on a side of their front face whose other face borders none of their edges (left unjudged, BOUNDARY_TIE): {ties}, beside {judged} judged"
    );
    assert!(
        failures.is_empty(),
        "{} scenes failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Refusals the sweep asks for, and what the bisection says of each.
#[derive(Default)]
struct Refusals {
    asked: usize,
    confirmed: usize,
    conservative: usize,
    no_hidden_edge: usize,
}

fn class_of<'a>(classes: &'a mut Vec<(String, Class)>, label: &str) -> &'a mut Class {
    let idx = match classes.iter().position(|(l, _)| l == label) {
        Some(i) => i,
        None => {
            classes.push((
                label.to_string(),
                Class {
                    peers: vec![(0, 0); PEERS.len() + SEED_SHIFTS.len()],
                    ..Default::default()
                },
            ));
            classes.len() - 1
        }
    };
    &mut classes[idx].1
}

fn zshift_format(f: DepthFormat) -> Format {
    Format::from_gl_internal_format(f.gl_enum()).unwrap()
}

/// Two sheets of a thin slab drawn as a hidden-line drawing: a front sheet (a 6 × 6 grid,
/// `2r` wide) and, `t` behind it along its normal, a back sheet (a 7 × 7 grid, `1.7r` wide, so
/// that its edges lie under no front edge and wholly behind the front sheet), tilted 30° about x
/// and 10° about y (the slab's sides, grazing, are left out). Tilted 55° (nearer the 60° limit
/// the model pays for) no refusal was confirmed: a hidden pixel is counted only where the edge
/// is behind the front face at the pixel and its neighbours, a pixel's slope that thin slabs
/// do not clear.
fn sheets(r: f64, d: f64, t: f64) -> Mesh {
    let mut verts = Vec::new();
    let mut tris = Vec::new();
    for (cells, half, z) in [(6u32, r, 0.0), (7u32, 0.85 * r, -t)] {
        let base = verts.len() as u32;
        for j in 0..=cells {
            for i in 0..=cells {
                let (u, v) = (i as f64 / cells as f64 - 0.5, j as f64 / cells as f64 - 0.5);
                verts.push(place(
                    [2.0 * half * u, 2.0 * half * v, z],
                    30f64.to_radians(),
                    10f64.to_radians(),
                    d,
                ));
            }
        }
        let w = cells + 1;
        for j in 0..cells {
            for i in 0..cells {
                let a = base + j * w + i;
                tris.push([a, a + 1, a + w + 1]);
                tris.push([a, a + w + 1, a + w]);
            }
        }
    }
    finish("slab sheets", verts, tris)
}

/// **Refusals confirmed by bisection.** Thin slabs drawn as hidden-line drawings (hidden edges
/// `t = k·G` behind the front face, `G` zshift's hidden-line gap for the scene, `k` ⅛, ¼, ½;
/// also 1/16 and ¾ with `ZSHIFT_LINES_FULL`),
/// with `hidden_separation = 0.7·t` (below `G`, so zshift must refuse; the back sheet's edges
/// lie at least about `0.8·t` behind the front sheet in eye depth). Each refusal is then checked:
/// the smallest common scale of zshift's offset (without the separation) that keeps every
/// visible edge — the best offset along that ray for the hidden edges, since what shows grows
/// with the offset — is drawn, and the refusal is **confirmed** when hidden-edge pixels beyond
/// the separation show there, **unconfirmed** otherwise (that offset does both: zshift's gap is
/// conservative). For (a) the search runs along zshift's (factor, units) ray only. D16, D24 and
/// D32F; `[−1, 1]` and reversed Z; f/n 10³, the slab in the middle and far; both methods and
/// profiles; 1-pixel `GL_LINES`.
#[test]
fn refusals_confirmed_by_bisection() {
    let full = std::env::var_os("ZSHIFT_LINES_FULL").is_some_and(|v| v != "0");
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no OpenGL context: {e}"));
    let renderer = Renderer::new(gl.glow());
    let profiles = profiles(&gl);
    let variant = VARIANTS[0];
    let mut failures = Vec::new();
    let mut rows: Vec<(String, [usize; 4])> = Vec::new();
    let ks: &[f64] = if full {
        &[0.0625, 0.125, 0.25, 0.5, 0.75]
    } else {
        &[0.125, 0.25, 0.5]
    };
    for fmt in [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F] {
        gl.set_target(SIZE, SIZE, fmt).unwrap();
        for conv in [Conv::Std, Conv::Reversed] {
            gl.clip_control(if conv == Conv::Std {
                GlClip::NegativeOneToOne
            } else {
                GlClip::ZeroToOne
            })
            .unwrap();
            let (n, f) = (1.0f64, 1e3f64);
            let t = 0.5 * n;
            let frustum = Frustum::new(-t, t, -t, t, n, f).unwrap();
            let clip = conv.clip();
            let m = projection(&frustum, clip).unwrap();
            let mf = projection_f64(&frustum, clip).unwrap();
            let b = f * n / (f - n);
            for (pos, d) in [("mid", 31.6), ("far", 355.0)] {
                for method in [EdgeMethod::PolygonOffset, EdgeMethod::Matrix] {
                    for (pname, profile) in profiles {
                        let label = format!(
                            "{} {} {} {pname}",
                            conv.name(),
                            fmt.name(),
                            if method == EdgeMethod::Matrix {
                                "(b)"
                            } else {
                                "(a)"
                            }
                        );
                        let edges_of = |mesh: &Mesh| {
                            let (dmin, dmax) = mesh.depth_range();
                            edges_for(fmt, conv, variant, profile, [dmin, dmax])
                        };
                        let radius = 0.25 * d;
                        let g0 =
                            match recommend(&m, clip, &edges_of(&sheets(radius, d, 0.0)), method) {
                                Ok(r) => r.hidden_gap,
                                Err(e) => {
                                    failures.push(format!("{label} {pos}: {e}"));
                                    continue;
                                }
                            };
                        for &k in ks {
                            let thick = k * g0;
                            let mesh = sheets(radius, d, thick);
                            let mut edges = edges_of(&mesh);
                            let where_ = format!("{label} {pos} t = {k}·G = {thick:.3e}");
                            let rec = match recommend(&m, clip, &edges, method) {
                                Ok(r) => r,
                                Err(e) => {
                                    failures.push(format!("{where_}: {e}"));
                                    continue;
                                }
                            };
                            let sep = 0.7 * thick;
                            edges.hidden_separation = sep;
                            let row = match rows.iter().position(|(l, _)| *l == label) {
                                Some(i) => i,
                                None => {
                                    rows.push((label.clone(), [0; 4]));
                                    rows.len() - 1
                                }
                            };
                            match recommend(&m, clip, &edges, method) {
                                Err(e) if e.kind() == zshift::ErrorKind::Unresolvable => {}
                                other => {
                                    failures.push(format!(
                                        "{where_}: hidden_separation {sep:e} below the gap {:e} not refused: {other:?}",
                                        rec.hidden_gap
                                    ));
                                    continue;
                                }
                            }
                            rows[row].1[0] += 1;
                            let p = project(&mesh, &mf);
                            let rf = reference(&mesh, &p, [0.5, 0.5]);
                            renderer.load(gl.glow(), &mesh);
                            let scene = Scene::new(
                                &gl,
                                &renderer,
                                &mesh,
                                m,
                                conv == Conv::Reversed,
                                variant,
                                None,
                            );
                            let ids = edge_ids(&scene);
                            let rfs = std::slice::from_ref(&rf);
                            let g = rec.face_gradient;
                            let c =
                                classify(&scene, &p, rfs, &ids, b, limit_of(&edges, false, g), sep);
                            // zshift's own offset (no separation) keeps every visible edge.
                            let (lost, _) = scene.count(&scaled(&rec, &m, clip, 1.0), &c);
                            if lost > 0 {
                                failures.push(format!("{where_}: {lost} visible lost"));
                            }
                            let works = |s: f64| scene.count(&scaled(&rec, &m, clip, s), &c).0 == 0;
                            let (mut lo, mut hi) = (-24.0f64, 0.0f64);
                            if works(lo.exp2()) {
                                hi = lo;
                            } else {
                                for _ in 0..9 {
                                    let mid = 0.5 * (lo + hi);
                                    if works(mid.exp2()) {
                                        hi = mid
                                    } else {
                                        lo = mid
                                    }
                                }
                            }
                            let (_, shown) = scene.count(&scaled(&rec, &m, clip, hi.exp2()), &c);
                            if shown > 0 {
                                rows[row].1[1] += 1;
                            } else if c.hidden.is_empty() {
                                rows[row].1[3] += 1;
                            } else {
                                rows[row].1[2] += 1;
                            }
                            if std::env::var_os("ZSHIFT_LINES_VERBOSE").is_some() {
                                println!(
                                    "{where_}: gap {:.3e}, separation {sep:.3e}, smallest working scale 2^{hi:.2}: {shown} of {} hidden pixels beyond the separation shown, {} visible",
                                    rec.hidden_gap,
                                    c.hidden.len(),
                                    c.visible.len()
                                );
                            }
                        }
                    }
                }
            }
        }
    }
    println!("\n| refusal class (slab sheets, f/n 10³, mid and far) | refused | confirmed | unconfirmed (the smallest working offset also hides every hidden edge beyond the separation) | no hidden pixel beyond the separation |");
    println!("|---|---|---|---|---|");
    let mut total = [0usize; 4];
    for (label, r) in &rows {
        println!("| {label} | {} | {} | {} | {} |", r[0], r[1], r[2], r[3]);
        for i in 0..4 {
            total[i] += r[i];
        }
    }
    println!(
        "| all | {} | {} | {} | {} |",
        total[0], total[1], total[2], total[3]
    );
    assert!(
        failures.is_empty(),
        "{} refusal scenes failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

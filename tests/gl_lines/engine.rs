//! Edges drawn the way engines draw them: the mesh's vertices in world space, far from the
//! world's origin, through the engine's f32 view matrix in the vertex shader
//! (`proj * (view * p)`), into a viewport inside a larger framebuffer, under `glDepthRange`
//! sub-ranges; zshift told all of it (`Edges::pipeline`: the view matrix and the box of the
//! world positions, eye-first, the viewport's origin, the depth range).
//!
//! Each scene takes the sweep's mesh (eye space, as the sweep places it), a camera rotation and
//! a position `T` units from the origin, and stores the world positions `R⁻¹·eye + camera` as
//! f32 with the f32 view matrix `[R | −R·camera]`. Lines: 1-pixel, polygon-mode and width-3,
//! and 1-pixel and polygon-mode lines under 4× MSAA (in a viewport at the framebuffer's origin,
//! where the harness's multisampled target is). The reference is the exact geometry drawn:
//! the f64 product of the f32 view matrix and the f32 world positions, projected in f64
//! ([`project_points`]); the counting is the sweep's ([`classify`]).

use super::*;
use zshift::model::Pipeline;
use zshift_harness::edges::{project_points, Mesh};
use zshift_harness::world::Window;

/// Scenes per depth format and convention.
const SCENES_PER_ATTACHMENT: usize = 12;
/// Camera positions' distances from the world's origin.
const TRANSLATIONS: [f64; 4] = [0.0, 100.0, 1e3, 1e4];
/// Viewport origins in the framebuffer (pixels).
const ORIGINS: [[u32; 2]; 3] = [[0, 0], [700, 300], [1500, 900]];
/// `glDepthRange`s.
const RANGES: [[f64; 2]; 3] = [[0.0, 1.0], [0.25, 0.75], [0.5, 1.0]];

/// `a · b` of two column-major matrices, in f64, rounded to f32 (an engine's MVP).
fn times(a: &[f32; 16], b: &[f32; 16]) -> [f32; 16] {
    let mut out = [0.0f32; 16];
    for c in 0..4 {
        for r in 0..4 {
            out[4 * c + r] = (0..4)
                .map(|k| f64::from(a[4 * k + r]) * f64::from(b[4 * c + k]))
                .sum::<f64>() as f32;
        }
    }
    out
}

/// A rigid view `[R | −R·c]` (column-major, f64) with `R` a yaw then a pitch, and its rows.
fn view_of(yaw: f64, pitch: f64, camera: [f64; 3]) -> ([f64; 16], [[f64; 3]; 3]) {
    let (sy, cy) = yaw.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let r = [
        [cy, 0.0, -sy],
        [sy * sp, cp, cy * sp],
        [sy * cp, -sp, cy * cp],
    ];
    let mut v = [0.0f64; 16];
    for k in 0..3 {
        for j in 0..3 {
            v[4 * j + k] = r[k][j];
        }
        v[12 + k] = -(0..3).map(|j| r[k][j] * camera[j]).sum::<f64>();
    }
    v[15] = 1.0;
    (v, r)
}

/// The mesh in world space: f32 world positions (`Rᵀ·eye + camera`), the f32 view matrix, and
/// the exact eye positions of what is drawn (the f32 view times the f32 positions, in f64).
fn in_world(
    mesh: &Mesh,
    yaw: f64,
    pitch: f64,
    camera: [f64; 3],
) -> (Vec<[f32; 3]>, [f32; 16], Vec<[f64; 3]>) {
    let (view, r) = view_of(yaw, pitch, camera);
    let view32 = view.map(|x| x as f32);
    let world: Vec<[f32; 3]> = mesh
        .verts
        .iter()
        .map(|v| {
            let e = v.map(f64::from);
            [0, 1, 2].map(|j| ((0..3).map(|k| r[k][j] * e[k]).sum::<f64>() + camera[j]) as f32)
        })
        .collect();
    let eye = world
        .iter()
        .map(|p| {
            [0, 1, 2].map(|k| {
                (0..3)
                    .map(|j| f64::from(view32[4 * j + k]) * f64::from(p[j]))
                    .sum::<f64>()
                    + f64::from(view32[12 + k])
            })
        })
        .collect();
    (world, view32, eye)
}

/// The box `[lo, hi]` of `points`.
fn bounds(points: &[[f32; 3]]) -> [[f64; 3]; 2] {
    let lo = [0, 1, 2].map(|k| {
        points
            .iter()
            .map(|p| f64::from(p[k]))
            .fold(f64::INFINITY, f64::min)
    });
    let hi = [0, 1, 2].map(|k| {
        points
            .iter()
            .map(|p| f64::from(p[k]))
            .fold(f64::NEG_INFINITY, f64::max)
    });
    [lo, hi]
}

#[test]
fn edges_drawn_as_engines_draw() {
    let mut gl =
        Gl::new(Profile::Compatibility).unwrap_or_else(|e| panic!("no OpenGL context: {e}"));
    let renderer = Renderer::new(gl.glow());
    let profiles = profiles(&gl);
    let meshes: [MeshMaker; 4] = [sphere, torus, terrain, chamfered_box];
    // 1-pixel, polygon-mode and width-3 lines, and 1-pixel and polygon-mode lines under 4× MSAA.
    let variants = [
        VARIANTS[0],
        VARIANTS[1],
        VARIANTS[2],
        VARIANTS[3],
        VARIANTS[6],
    ];
    let (mut scenes, mut answered, mut visible, mut hidden, mut unoffset_lost) = (0, 0, 0, 0, 0);
    let mut refused = 0;
    let mut failures = Vec::new();
    // `ZSHIFT_LINES_SEED=<n>`: other rotations and distances from the origin.
    let mut draw = Variation::from_env();
    let mut turn = 0usize;
    for fmt in DepthFormat::ALL {
        for conv in [Conv::Std, Conv::ZeroOne, Conv::Reversed] {
            for _ in 0..SCENES_PER_ATTACHMENT {
                turn += 1;
                let make = meshes[turn % 4];
                let ratio: f64 = [10.0, 1e3, 1e6][(turn / 4) % 3] * draw.ratio_factor();
                let frac = [0.15, 0.5, 0.85][(turn / 12) % 3] + draw.position_shift();
                let t = TRANSLATIONS[(turn / 2) % 4] * (1.0 + draw.unit().unwrap_or(0.0));
                let range = RANGES[(turn / 5) % 3];
                let variant = variants[(turn / 7) % variants.len()];
                // The harness's multisampled target sits at the framebuffer's origin.
                let origin = if variant.samples > 1 {
                    [0, 0]
                } else {
                    ORIGINS[turn % 3]
                };
                let (n, f) = (1.0f64, ratio);
                let d0 = (n * ratio.powf(frac)).max(1.6 * n).min(0.7 * f);
                let (mesh, _) = placed(make, n, f, d0, 0.3);
                let camera = [0.6 * t, 0.3 * t + 1.7, -0.74 * t];
                let spin = draw.unit().unwrap_or(0.37 * turn as f64);
                let (yaw, pitch) = (0.59 + 6.3 * spin, 0.05 * (turn % 5) as f64);
                let (world, view32, eye) = in_world(&mesh, yaw, pitch, camera);
                let (dmin, dmax) = eye
                    .iter()
                    .fold((f64::MAX, 0.0f64), |(a, b), e| (a.min(-e[2]), b.max(-e[2])));
                if dmin < 1.01 * n || dmax > 0.99 * f {
                    continue; // the terrain at f/n 10 crosses the near plane: not modelled
                }
                let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, n, f).unwrap();
                let clip = conv.clip();
                let m = projection(&frustum, clip).unwrap();
                let mf = projection_f64(&frustum, clip).unwrap();
                let p = project_points(&eye, &mf);

                let b = f * n / (f - n);
                gl.set_target(SIZE + origin[0], SIZE + origin[1], fmt)
                    .unwrap();
                gl.clip_control(if conv == Conv::Std {
                    GlClip::NegativeOneToOne
                } else {
                    GlClip::ZeroToOne
                })
                .unwrap();
                gl.set_window(&Window {
                    viewport: [origin[0] as i32, origin[1] as i32, SIZE as i32, SIZE as i32],
                    depth_range: range,
                })
                .unwrap();
                renderer.load_positions(gl.glow(), &world);
                // The mesh as zshift reads it: its world positions through the engine's
                // projection times view, as an f32 MVP.
                let mvp = times(&m, &view32);
                let indices = triangle_indices(&mesh);
                let draw = MeshDraw {
                    clip_matrix: &mvp,
                    positions: &world,
                    indices: &indices,
                };
                // A multisampled target beside this scene's own (it rebinds that one after reads).
                let msaa = (variant.samples > 1).then(|| Msaa::new(&gl, fmt, variant.samples));
                let rfs: Vec<Reference> = match &msaa {
                    Some(ms) => ms
                        .positions
                        .iter()
                        .map(|&o| reference(&mesh, &p, o))
                        .collect(),
                    None => vec![reference(&mesh, &p, [0.5, 0.5])],
                };
                let mut scene = Scene::new(
                    &gl,
                    &renderer,
                    &mesh,
                    m,
                    conv == Conv::Reversed,
                    variant,
                    msaa.as_ref(),
                );
                scene.view = Some(view32);
                scene.origin = origin;
                let ids = edge_ids(&scene);
                scenes += 1;
                let pipeline = Pipeline {
                    world_reach: camera.iter().fold(0.0f64, |a, c| a.max(c.abs())),
                    eye_first: true,
                    view: Some(view32),
                    world_box: Some(bounds(&world)),
                    viewport_origin: origin,
                    depth_range: range,
                };
                for method in [EdgeMethod::PolygonOffset, EdgeMethod::Matrix] {
                    for (pname, profile, from_mesh) in asks(&profiles) {
                        let edges = Edges {
                            pipeline,
                            ..edges_for(fmt, conv, variant, profile, [dmin, dmax])
                        };
                        // The mesh's own steepest faces within the angle's gradient; the pixels
                        // judged are the angle's.
                        let mut g_angle = f64::NAN;
                        if from_mesh {
                            let Ok(r) = recommend(&m, clip, &edges, method) else {
                                continue;
                            };
                            g_angle = r.face_gradient;
                        }
                        let where_ = format!(
                            "{} {} {} {method:?} {pname} {} f/n {ratio} at {frac} T {t} viewport@{origin:?} range {range:?}",
                            conv.name(),
                            fmt.name(),
                            variant.name(),
                            mesh.name
                        );
                        let rec = match ask(&m, clip, &edges, method, from_mesh.then_some(&draw)) {
                            Ok(r) => r,
                            Err(e) if e.kind() == zshift::ErrorKind::Unresolvable => {
                                refused += 1;
                                continue;
                            }
                            Err(e) => {
                                failures.push(format!("{where_}: {e}"));
                                continue;
                            }
                        };
                        answered += 1;
                        let g = if from_mesh {
                            g_angle
                        } else {
                            rec.face_gradient
                        };
                        let c = classify(
                            &scene,
                            &p,
                            &rfs,
                            &ids,
                            b,
                            limit_of(&edges, from_mesh, g),
                            rec.hidden_gap,
                        );
                        visible += c.visible.len();
                        hidden += c.hidden.len();
                        let (lost, shown) = scene.count(&scaled(&rec, &m, clip, 1.0), &c);
                        if lost + shown > 0 {
                            failures.push(format!(
                                "{where_}: {lost} of {} visible lost, {shown} of {} hidden shown",
                                c.visible.len(),
                                c.hidden.len()
                            ));
                        }
                        if method == EdgeMethod::Matrix && pname == "worst" {
                            let plain = Draw {
                                face_offset: None,
                                edge_matrix: m,
                            };
                            unoffset_lost += scene.count(&plain, &c).0;
                        }
                    }
                }
                drop(scene);
                if let Some(ms) = msaa {
                    ms.delete(&gl);
                }
            }
        }
    }
    gl.set_target(SIZE, SIZE, DepthFormat::D24).unwrap();
    gl.set_window(&Window {
        viewport: [0, 0, SIZE as i32, SIZE as i32],
        depth_range: [0.0, 1.0],
    })
    .unwrap();
    println!(
        "edges drawn as engines draw: {scenes} scenes, {answered} answers, {refused} refusals, {visible} visible and {hidden} hidden-edge pixels judged, 0 expected lost/shown; {unoffset_lost} visible lost without an offset"
    );
    assert!(
        answered > scenes,
        "too few answers: {answered} of {scenes} scenes"
    );
    assert!(
        unoffset_lost > 0,
        "no edge lost without an offset: the check cannot fail"
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

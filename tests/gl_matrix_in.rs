//! `zshift::matrix_in` on a real rasterizer (headless EGL; Mesa llvmpipe in CI): the base is
//! drawn with the engine's own matrix, built by glam (OpenGL `[−1, 1]`, Direct3D `[0, 1]`,
//! Vulkan's y flip, reversed infinite, orthographic) or by the tweaked-infinite formula, and the
//! decal with the matrix zshift derives from it (the recommendation, and an eye shift of the
//! recommendation's `delta_at_far`, and the recommendation from the probed profile with the
//! decal's corners projected through the engine's matrix). No decal pixel may be lost to the base. A control
//! draws the decal with the base's own matrix and must lose pixels on the sloped planes, so the
//! experiment can fail. Fails (never skips) without GL.

mod gl_common;

use glam::camera::rh::proj as rh;
use zshift::matrix_in::{offset_shift, recommend, Decal};
use zshift::orthographic::Ortho;
use zshift::projection::ClipDepth;
use zshift_harness::coplanar::{Setup, BASE, CLEAR, DECAL};
use zshift_harness::{rgba8, ClipDepth as GlClip, DepthFormat, DrawState, Gl, Profile, Quad};

const SIZE: u32 = 96;

fn context() -> Gl {
    Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no OpenGL context (EGL surfaceless): {e}"))
}

/// Decal pixels lost to the base (of the pixels the decal covers) with the base drawn through
/// `base` and the decal through `decal`, under `clip`'s depth test and clear value.
fn lost(
    gl: &mut Gl,
    s: &Setup,
    clip: ClipDepth,
    base: &[f32; 16],
    decal: &[f32; 16],
) -> (usize, usize) {
    lost_in(gl, s, clip, base, decal, [0, 0], [0.0, 1.0])
}

/// [`lost`] with the setup's viewport at `origin` in a framebuffer that holds it, under
/// `glDepthRange(depth_range)` (clears touch the viewport only).
fn lost_in(
    gl: &mut Gl,
    s: &Setup,
    clip: ClipDepth,
    base: &[f32; 16],
    decal: &[f32; 16],
    origin: [u32; 2],
    depth_range: [f64; 2],
) -> (usize, usize) {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let [x, y] = origin;
    gl.set_target(x + s.size, y + s.size, s.format)
        .expect("target");
    gl.set_window(&zshift_harness::world::Window {
        viewport: [x as i32, y as i32, s.size as i32, s.size as i32],
        depth_range,
    })
    .expect("viewport");
    gl.clip_control(if clip == ClipDepth::NegOneToOne {
        GlClip::NegativeOneToOne
    } else {
        GlClip::ZeroToOne
    })
    .expect("glClipControl");
    let clear_depth = if reversed { 0.0 } else { 1.0 };
    let always = DrawState {
        depth_func: glow::ALWAYS,
        ..DrawState::default()
    };
    let test = DrawState {
        depth_func: if reversed { glow::GREATER } else { glow::LESS },
        ..DrawState::default()
    };
    let draw = |gl: &mut Gl, quad: &Quad, m: &[f32; 16], color, state: &DrawState| {
        gl.draw_quad(quad, m, color, state).expect("draw");
    };
    gl.clear(CLEAR, clear_depth).unwrap();
    draw(gl, &s.decal(), decal, DECAL, &always);
    let mask = gl.read_color().unwrap().mask_of(rgba8(DECAL));
    let covered = mask.iter().filter(|&&m| m).count();
    assert!(covered > 0, "{}: the decal covers no pixel", s.label());
    gl.clear(CLEAR, clear_depth).unwrap();
    draw(gl, &s.base(), base, BASE, &test);
    draw(gl, &s.decal(), decal, DECAL, &test);
    let image = gl.read_color().unwrap();
    (image.count_not_in_mask(&mask, rgba8(DECAL)), covered)
}

/// A perspective matrix an engine builds for the setup's frustum (60° square, n = 1).
struct Engine {
    name: &'static str,
    clip: ClipDepth,
    build: fn(f32) -> [f32; 16],
}

const FOVY: f32 = std::f32::consts::FRAC_PI_3;

fn engines() -> Vec<Engine> {
    vec![
        Engine {
            name: "glam opengl::perspective [-1,1]",
            clip: ClipDepth::NegOneToOne,
            build: |f| rh::opengl::perspective(FOVY, 1.0, 1.0, f).to_cols_array(),
        },
        Engine {
            name: "glam directx::perspective [0,1]",
            clip: ClipDepth::ZeroToOne,
            build: |f| rh::directx::perspective(FOVY, 1.0, 1.0, f).to_cols_array(),
        },
        Engine {
            name: "glam vulkan::perspective [0,1] y-flip",
            clip: ClipDepth::ZeroToOne,
            build: |f| rh::vulkan::perspective(FOVY, 1.0, 1.0, f).to_cols_array(),
        },
        Engine {
            name: "glam directx::perspective_infinite_reverse",
            clip: ClipDepth::ReversedZeroToOne,
            build: |_| rh::directx::perspective_infinite_reverse(FOVY, 1.0, 1.0).to_cols_array(),
        },
        Engine {
            name: "tweaked infinite 2^-22 [-1,1]",
            clip: ClipDepth::NegOneToOne,
            build: |_| {
                let t = (30f64).to_radians().tan();
                let fr = zshift::Frustum::new(-t, t, -t, t, 1.0, f64::INFINITY).unwrap();
                zshift::projection::tweaked_infinite(&fr, 2f64.powi(-22)).unwrap()
            },
        },
    ]
}

fn decal_of(gl: &Gl, s: &Setup) -> Decal {
    let (d1, d2) = s.decal_depth_range();
    Decal {
        depth_test: None,
        pipeline: Default::default(),
        footprint: None,
        viewport: [s.size, s.size],
        format: gl_common::format_of(s.format),
        depth_range: [d1, d2],
        slope: s.slope,
        exact_depth: s.slope == 0.0,
        snapping: gl_common::snapping_of(gl),
        base: zshift::recommend::Base::InsideFrustum,
        profile: None,
    }
}

#[test]
fn decals_over_the_engines_own_perspective_matrices_lose_no_pixel() {
    let mut gl = context();
    let probed = gl_common::probed(&gl);
    let mut tighter = 0;
    let mut control_lost = 0;
    let mut rows = 0;
    for e in engines() {
        let formats: &[DepthFormat] = if e.clip == ClipDepth::ReversedZeroToOne {
            &[DepthFormat::D32F]
        } else {
            &[DepthFormat::D24, DepthFormat::D32F]
        };
        for &format in formats {
            for (ratio, p) in [(100.0, 0.2), (1e4, 0.9)] {
                for slope in [0.0, 3.0] {
                    let s = gl_common::setup(format, ratio, p, slope, SIZE);
                    let base = (e.build)(ratio as f32);
                    let label = format!("{} {} {}", e.name, s.label(), format.name());
                    let rec = recommend(&base, e.clip, &decal_of(&gl, &s))
                        .unwrap_or_else(|err| panic!("{label}: {err}"));
                    let (hit, of) = lost(&mut gl, &s, e.clip, &base, &rec.matrix);
                    assert_eq!(
                        hit, 0,
                        "{label}: recommended decal matrix lost {hit} of {of} pixels"
                    );
                    let (_, d2) = s.decal_depth_range();
                    let shifted = offset_shift(&base, e.clip, rec.delta_at_far, d2)
                        .unwrap_or_else(|err| panic!("{label}: {err}"));
                    let (hit, of) = lost(&mut gl, &s, e.clip, &base, &shifted);
                    assert_eq!(
                        hit, 0,
                        "{label}: eye shift delta_at_far lost {hit} of {of} pixels"
                    );
                    // The tightest description: the probed profile and the decal's corners,
                    // projected through the engine's own matrix (y flip and reversed included).
                    let corners = s.decal().corners.map(|[x, y, z]| glam::Vec3::new(x, y, z));
                    let shape =
                        zshift::matrix_in::decal_shape(&base, e.clip, [s.size, s.size], &corners)
                            .unwrap_or_else(|err| panic!("{label}: decal_shape: {err}"));
                    let tight = Decal {
                        depth_range: shape.depth_range,
                        slope: shape.slope,
                        footprint: Some(shape.footprint),
                        profile: Some(probed),
                        ..decal_of(&gl, &s)
                    };
                    let rec_tight = recommend(&base, e.clip, &tight)
                        .unwrap_or_else(|err| panic!("{label}: {err}"));
                    let (hit, of) = lost(&mut gl, &s, e.clip, &base, &rec_tight.matrix);
                    assert_eq!(
                        hit, 0,
                        "{label}: the probed profile with corners lost {hit} of {of} pixels"
                    );
                    tighter += usize::from(rec_tight.window_offset < rec.window_offset);
                    if slope > 0.0 {
                        control_lost += lost(&mut gl, &s, e.clip, &base, &base).0;
                    }
                    rows += 1;
                }
            }
        }
    }
    assert!(rows >= 30, "{rows} configurations");
    assert!(
        tighter * 2 > rows,
        "the probed profile with corners was tighter in only {tighter} of {rows}"
    );
    assert!(
        control_lost > 0,
        "no z-fighting without an offset: the experiment cannot fail"
    );
}

/// Orthographic decals in a viewport far from the framebuffer's origin and under `glDepthRange`
/// sub-ranges, zshift told both (`Decal::pipeline`): 0 pixels lost at the recommendation; the
/// same scenes lose pixels without an offset.
/// The orthographic base matrix an engine builds (glam) for the setup's square box and `clip`.
fn ortho_base(s: &Setup, clip: ClipDepth) -> [f32; 16] {
    let h = (s.axis_depth() * s.tan_half) as f32;
    let (n, f) = (s.n as f32, s.f as f32);
    match clip {
        ClipDepth::NegOneToOne => rh::opengl::orthographic(-h, h, -h, h, n, f),
        ClipDepth::ZeroToOne => rh::directx::orthographic(-h, h, -h, h, n, f),
        ClipDepth::ReversedZeroToOne => rh::directx::orthographic(-h, h, -h, h, f, n),
    }
    .to_cols_array()
}

#[test]
fn orthographic_decals_in_a_viewport_and_a_depth_range_lose_no_pixel() {
    let mut gl = context();
    let mut control_lost = 0;
    let mut scenes = 0;
    for clip in [
        ClipDepth::NegOneToOne,
        ClipDepth::ZeroToOne,
        ClipDepth::ReversedZeroToOne,
    ] {
        for format in [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F] {
            for (origin, depth_range) in [
                ([3500, 1900], [0.0, 1.0]),
                ([0, 0], [0.5, 1.0]),
                ([1200, 700], [0.0, 0.5]),
                ([2900, 0], [0.25, 0.75]),
            ] {
                for (ratio, p) in [(100.0, 0.3), (1e3, 0.8)] {
                    for slope in [0.0, 1.0, 3.0] {
                        let s = gl_common::setup(format, ratio, p, slope, SIZE);
                        let base = ortho_base(&s, clip);
                        let label = format!(
                            "ortho {clip:?} {} viewport at {origin:?} range {depth_range:?}",
                            s.label()
                        );
                        let mut decal = decal_of(&gl, &s);
                        decal.pipeline.viewport_origin = origin;
                        decal.pipeline.depth_range = depth_range;
                        let rec = recommend(&base, clip, &decal)
                            .unwrap_or_else(|err| panic!("{label}: {err}"));
                        let (hit, of) =
                            lost_in(&mut gl, &s, clip, &base, &rec.matrix, origin, depth_range);
                        assert_eq!(
                            hit, 0,
                            "{label}: recommended decal matrix lost {hit} of {of} pixels"
                        );
                        control_lost +=
                            lost_in(&mut gl, &s, clip, &base, &base, origin, depth_range).0;
                        scenes += 1;
                    }
                }
            }
        }
    }
    println!("{scenes} orthographic scenes in viewports and depth ranges: 0 pixels lost; {control_lost} lost without an offset");
    assert!(
        control_lost > 0,
        "no z-fighting without an offset: the experiment cannot fail"
    );
}

#[test]
fn orthographic_decals_at_the_recommendation_lose_no_pixel() {
    let mut gl = context();
    let mut control_lost = 0;
    for (clip, formats) in [
        (
            ClipDepth::NegOneToOne,
            &[DepthFormat::D16, DepthFormat::D24][..],
        ),
        (
            ClipDepth::ZeroToOne,
            &[DepthFormat::D24, DepthFormat::D32F][..],
        ),
        (ClipDepth::ReversedZeroToOne, &[DepthFormat::D32F][..]),
    ] {
        for &format in formats {
            for (ratio, p) in [(100.0, 0.3), (1e3, 0.8)] {
                for slope in [0.0, 1.0, 3.0] {
                    let s = gl_common::setup(format, ratio, p, slope, SIZE);
                    let base = ortho_base(&s, clip);
                    let label = format!("ortho {clip:?} {}", s.label());
                    let rec = recommend(&base, clip, &decal_of(&gl, &s))
                        .unwrap_or_else(|err| panic!("{label}: {err}"));
                    let (hit, of) = lost(&mut gl, &s, clip, &base, &rec.matrix);
                    assert_eq!(
                        hit, 0,
                        "{label}: recommended decal matrix lost {hit} of {of} pixels"
                    );
                    // The recommendation against the exact depth step (same at every distance
                    // for UNORM): how many steps the f32 terms ask for.
                    let ortho = Ortho::new(-1.0, 1.0, -1.0, 1.0, s.n, s.f).unwrap();
                    let (_, d2) = s.decal_depth_range();
                    let step = ortho
                        .depth_step(clip, gl_common::format_of(format), d2)
                        .unwrap();
                    let one_step = offset_shift(&base, clip, step, d2).unwrap();
                    let (one_hit, _) = lost(&mut gl, &s, clip, &base, &one_step);
                    println!(
                        "{label}: recommended {:.2} steps (lost 0 of {of}); one step loses {one_hit}",
                        rec.delta_at_far / step
                    );
                    control_lost += lost(&mut gl, &s, clip, &base, &base).0;
                }
            }
        }
    }
    assert!(
        control_lost > 0,
        "no z-fighting without an offset: the experiment cannot fail"
    );
}

/// An isometric camera: an orthographic projection (±6 units, near 1, far 100) looking down
/// 35.26° at a 45° heading from 50 units, over a terrain with hills (32×32 cells of half a
/// unit, slopes up to about 0.57, below the view's angle: nothing hides the decal), its
/// vertices in world space through the f32 view matrix, the scene 0, 10³ or 10⁴ units from the
/// world origin.
struct Isometric {
    translate: f64,
    /// The world → eye rotation (rows: right, up, back) and the camera's position.
    rotation: [[f64; 3]; 3],
    camera: [f64; 3],
}

impl Isometric {
    fn new(translate: f64) -> Self {
        let (yaw, pitch) = (45f64.to_radians(), 35.264f64.to_radians());
        let forward = [
            -yaw.sin() * pitch.cos(),
            -pitch.sin(),
            -yaw.cos() * pitch.cos(),
        ];
        let target = [translate, 0.3 * translate, translate];
        let camera = [0, 1, 2].map(|k| target[k] - 50.0 * forward[k]);
        Isometric {
            translate,
            rotation: zshift_harness::world::looking_along(forward),
            camera,
        }
    }

    fn height(&self, x: f64, z: f64) -> f64 {
        let (u, v) = (x - self.translate, z - self.translate);
        0.3 * self.translate
            + 0.4 * (0.8 * u + 0.3).sin() * (0.7 * v - 0.4).cos()
            + 0.12 * (1.5 * (u - v)).sin()
    }

    fn terrain(&self) -> Vec<[f32; 3]> {
        let at = |i: u32, j: u32| {
            let (x, z) = (
                self.translate - 8.0 + 0.5 * f64::from(i),
                self.translate - 8.0 + 0.5 * f64::from(j),
            );
            [x as f32, self.height(x, z) as f32, z as f32]
        };
        let mut t = Vec::new();
        for i in 0..32 {
            for j in 0..32 {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                t.extend([a, b, c, a, c, d]);
            }
        }
        t
    }

    fn eye(&self, p: [f64; 3]) -> [f64; 3] {
        zshift_harness::world::eye_of(&self.rotation, self.camera, p)
    }

    /// The f32 view matrix (column-major), built in f64 and rounded once.
    fn view(&self) -> [f32; 16] {
        zshift_harness::world::view_matrix(&self.rotation, self.camera)
    }

    /// The square of half side `half` around `centre` (offsets from the translation).
    fn square(&self, centre: [f64; 2], half: f64) -> [f32; 4] {
        let (x, z) = (self.translate + centre[0], self.translate + centre[1]);
        [x - half, x + half, z - half, z + half].map(|v| v as f32)
    }
}

/// One draw of a pass: triangles, projection, colour, state.
type Pass<'a> = (&'a [[f32; 3]], &'a [f32; 16], [f32; 4], &'a DrawState);

/// Where and how a decal scene is drawn: a `px`-square viewport at `origin` of the framebuffer
/// under `glDepthRange(range)`, the depth format and clip convention, the shader's view (or
/// model-view) matrix, the plain projection and every pass's depth test.
struct Drawn<'a> {
    px: u32,
    origin: [u32; 2],
    range: [f64; 2],
    format: DepthFormat,
    clip: ClipDepth,
    view: &'a [f32; 16],
    base: &'a [f32; 16],
    state: DrawState,
}

/// What a decal scene gave: the decal's pixels, those lost with its matrix and with the plain
/// one, and those shown over the occluder (among the pixels both cover).
struct Judged {
    pixels: usize,
    lost: zshift_harness::coplanar::Count,
    control: zshift_harness::coplanar::Count,
    shown: zshift_harness::coplanar::Count,
}

impl Drawn<'_> {
    /// Draws the base, then the decal with `decal_proj`, and again with the occluder between
    /// them, each read back.
    fn judge(
        &self,
        gl: &mut Gl,
        base_tris: &[[f32; 3]],
        decal_tris: &[[f32; 3]],
        decal_proj: &[f32; 16],
        occluder: &[[f32; 3]],
    ) -> Judged {
        use zshift_harness::coplanar::{Count, OCCLUDER};
        let [x, y] = self.origin;
        gl.set_target(x + self.px, y + self.px, self.format)
            .expect("target");
        gl.clip_control(if self.clip == ClipDepth::NegOneToOne {
            GlClip::NegativeOneToOne
        } else {
            GlClip::ZeroToOne
        })
        .expect("glClipControl");
        let side = self.px as i32;
        gl.set_window(&zshift_harness::world::Window {
            viewport: [x as i32, y as i32, side, side],
            depth_range: self.range,
        })
        .expect("viewport");
        let clear = if self.clip == ClipDepth::ReversedZeroToOne {
            0.0
        } else {
            1.0
        };
        let always = DrawState {
            depth_func: glow::ALWAYS,
            ..DrawState::default()
        };
        let (base, state) = (self.base, &self.state);
        let mut draw = |passes: &[Pass]| {
            gl.clear(CLEAR, clear).expect("clear");
            for (tris, proj, color, st) in passes {
                gl.draw_world(tris, self.view, proj, *color, st)
                    .expect("draw");
            }
            gl.read_color_at(self.origin, self.px, self.px)
                .expect("read")
        };
        let mask = draw(&[(decal_tris, base, DECAL, &always)]).mask_of(rgba8(DECAL));
        let over = |proj| {
            [
                (base_tris, base, BASE, state),
                (decal_tris, proj, DECAL, state),
            ]
        };
        let lost = Count::decal_missing(&draw(&over(decal_proj)), &mask);
        let control = Count::decal_missing(&draw(&over(base)), &mask);
        let covered = draw(&[(occluder, base, OCCLUDER, &always)]).mask_of(rgba8(OCCLUDER));
        let both: Vec<bool> = covered.iter().zip(&mask).map(|(a, b)| *a && *b).collect();
        let shown = Count::decal_shown(
            &draw(&[
                (base_tris, base, BASE, state),
                (occluder, base, OCCLUDER, state),
                (decal_tris, decal_proj, DECAL, state),
            ]),
            &both,
        );
        Judged {
            pixels: mask.iter().filter(|&&m| m).count(),
            lost,
            control,
            shown,
        }
    }
}

impl Judged {
    /// Asserts the decal covered more than `least` pixels, lost none and showed none over the
    /// occluder at `rec`'s gap.
    fn assert_kept(&self, label: &str, least: usize, rec: &zshift::recommend::ClipRecommendation) {
        assert!(
            self.pixels > least,
            "{label}: the decal covers too few pixels"
        );
        assert_eq!(
            self.lost.hit, 0,
            "{label}: lost {} of {} decal pixels ({rec:?})",
            self.lost.hit, self.lost.of
        );
        assert_eq!(
            self.shown.hit, 0,
            "{label}: {} of {} decal pixels shown over an occluder {} in front",
            self.shown.hit, self.shown.of, rec.bleed_gap
        );
    }
}

#[test]
fn isometric_mesh_decals_over_hills_lose_no_pixel() {
    use zshift_harness::world::clip_to_square;
    const PX: u32 = 256;
    let mut gl = context();
    let snapping = gl_common::snapping_of(&gl);
    let (mut scenes, mut control_lost) = (0, 0);
    let mut gaps = Vec::new();
    for clip in [
        ClipDepth::NegOneToOne,
        ClipDepth::ZeroToOne,
        ClipDepth::ReversedZeroToOne,
    ] {
        let base = match clip {
            ClipDepth::NegOneToOne => rh::opengl::orthographic(-6.0, 6.0, -6.0, 6.0, 1.0, 100.0),
            ClipDepth::ZeroToOne => rh::directx::orthographic(-6.0, 6.0, -6.0, 6.0, 1.0, 100.0),
            ClipDepth::ReversedZeroToOne => {
                rh::directx::orthographic(-6.0, 6.0, -6.0, 6.0, 100.0, 1.0)
            }
        }
        .to_cols_array();
        let reversed = clip == ClipDepth::ReversedZeroToOne;
        for (format, equal) in [
            (DepthFormat::D16, false),
            (DepthFormat::D24, false),
            (DepthFormat::D32F, false),
            (DepthFormat::D16, true),
            (DepthFormat::D24, true),
            (DepthFormat::D32F, true),
        ] {
            // Every pass drawn with the strict test, or with GL_LEQUAL (GL_GEQUAL reversed).
            let (func, state) = depth_test(reversed, equal);
            for translate in [0.0, 1e3, 1e4] {
                for (k, (centre, half)) in
                    // Three inside the view, two across its right and left edges (±6 units
                    // along the camera's right, (1, 0, −1)/√2 in world x and z): their terrain
                    // triangles cross the box's side planes and the rasterizer clips them.
                    [
                        ([0.0, 0.0], 1.25),
                        ([2.3, -1.7], 0.5),
                        ([-3.1, 1.4], 1.0),
                        ([4.1, -4.1], 1.0),
                        ([-4.2, 4.2], 0.6),
                    ]
                    .into_iter()
                    .enumerate()
                {
                    // The framebuffer as engines set it: the viewport at the origin, or inside a
                    // larger framebuffer (an editor pane), under glDepthRange(0, 1) or a sub-range.
                    let (origin, range) = [
                        ([0u32, 0u32], [0.0, 1.0]),
                        ([1700, 900], [0.5, 1.0]),
                        ([3500, 1900], [0.0, 0.5]),
                    ][k % 3];
                    let scene = Isometric::new(translate);
                    let (terrain, view) = (scene.terrain(), scene.view());
                    let label = format!(
                        "isometric {clip:?} {format:?} test 0x{func:04X} T {translate} decal {centre:?} ±{half} viewport at {origin:?} range {range:?}"
                    );
                    let pieces = clip_to_square(&terrain, scene.square(centre, half));
                    let decal: Vec<[f32; 3]> =
                        pieces.iter().flat_map(|(_, p)| p.iter().copied()).collect();
                    // One plane per terrain triangle under the decal: its eye depths, its slope
                    // (|nx| + |ny|)/|nz| in eye space, the view matrix and its box.
                    let planes: Vec<Decal> = pieces
                        .iter()
                        .map(|(i, _)| {
                            let world: Vec<[f64; 3]> = terrain[3 * i..3 * i + 3]
                                .iter()
                                .map(|p| p.map(f64::from))
                                .collect();
                            let e: Vec<[f64; 3]> = world.iter().map(|&p| scene.eye(p)).collect();
                            let (a, b) = (
                                [0, 1, 2].map(|k| e[1][k] - e[0][k]),
                                [0, 1, 2].map(|k| e[2][k] - e[0][k]),
                            );
                            let n = [
                                a[1] * b[2] - a[2] * b[1],
                                a[2] * b[0] - a[0] * b[2],
                                a[0] * b[1] - a[1] * b[0],
                            ];
                            let depths = e.iter().map(|p| -p[2]);
                            Decal {
                                viewport: [PX, PX],
                                format: gl_common::format_of(format),
                                depth_range: [
                                    depths.clone().fold(f64::INFINITY, f64::min),
                                    depths.fold(f64::NEG_INFINITY, f64::max),
                                ],
                                slope: (n[0].abs() + n[1].abs()) / n[2].abs(),
                                exact_depth: false,
                                snapping,
                                base: zshift::recommend::Base::InsideFrustum,
                                profile: None,
                                footprint: None,
                                depth_test: Some(
                                    zshift::recommend::DepthTest::from_gl(func)
                                        .expect("a depth test"),
                                ),
                                pipeline: zshift::model::Pipeline {
                                    world_reach: scene
                                        .camera
                                        .iter()
                                        .fold(0.0f64, |m, c| m.max(c.abs())),
                                    eye_first: true,
                                    view: Some(view),
                                    world_box: Some(zshift_harness::world::bounding_box(&world)),
                                    viewport_origin: origin,
                                    depth_range: range,
                                },
                            }
                        })
                        .collect();
                    let rec = zshift::planes::recommend_planes(&base, clip, &planes)
                        .unwrap_or_else(|e| panic!("{label}: {e}"));
                    // The occluder: the terrain under a square 1.5 times the decal's, the gap
                    // (and a hair) toward the camera along the view axis.
                    let toward = scene.rotation[2].map(|c| c * rec.bleed_gap * (1.0 + 1e-6));
                    let occluder: Vec<[f32; 3]> =
                        clip_to_square(&terrain, scene.square(centre, 1.5 * half))
                            .into_iter()
                            .flat_map(|(_, p)| p)
                            .map(|p| [0, 1, 2].map(|k| (f64::from(p[k]) + toward[k]) as f32))
                            .collect();
                    let drawn = Drawn {
                        px: PX,
                        origin,
                        range,
                        format,
                        clip,
                        view: &view,
                        base: &base,
                        state,
                    };
                    let judged = drawn.judge(&mut gl, &terrain, &decal, &rec.matrix, &occluder);
                    judged.assert_kept(&label, 50, &rec);
                    control_lost += judged.control.hit;
                    gaps.push(rec.bleed_gap / 50.0);
                    scenes += 1;
                }
            }
        }
    }
    summarize(
        &format!("{scenes} isometric mesh decals over hills (world space, 0 to 10^4 from the origin; viewports inside larger framebuffers, glDepthRange sub-ranges)"),
        "gap / 50 units",
        &mut gaps,
        control_lost,
    );
}

/// A decal on a vehicle far from the world's origin: the vehicle's flank (the base) and the
/// decal both in its model space, drawn through one model-view `V·M` multiplied in f32 as glm's
/// `mat4 * mat4` does (the camera 1.5 units to the side and 4 out, the vehicle turned 33.7°, up
/// to 10⁵ units from the origin). The engine tells zshift that model-view and the model-space
/// box (`Pipeline::view` documents it: however the product was multiplied, both go through the
/// same rounded matrix). Every convention, D16/D24/D32F, strict and `…EQUAL` tests: no decal
/// pixel lost, none shown over an occluder parallel to the flank at the reported gap.
#[test]
fn a_decal_on_a_vehicle_through_its_model_view_loses_no_pixel() {
    const PX: u32 = 256;
    let mut gl = context();
    let snapping = gl_common::snapping_of(&gl);
    let (mut scenes, mut control_lost) = (0, 0);
    let mut gaps = Vec::new();
    // The flank (z = 0.9 in model space, facing +z) and the decal on it, as triangles.
    let quad = |x0: f32, x1: f32, y0: f32, y1: f32| {
        let c = [[x0, y0, 0.9], [x1, y0, 0.9], [x1, y1, 0.9], [x0, y1, 0.9]];
        vec![c[0], c[1], c[2], c[0], c[2], c[3]]
    };
    let flank = quad(-2.0, 2.0, -1.0, 1.0);
    let decal = quad(-0.5, 0.7, -0.4, 0.5);
    let frustum = zshift::projection::Frustum::new(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0).unwrap();
    for translate in [0.0, 1e3, 1e4, 1e5] {
        // The vehicle: turned 33.7° about y, at (T, 1, T); its model matrix in f32.
        let (s, c) = 33.7f64.to_radians().sin_cos();
        let origin = [translate, 1.0, translate];
        let model: [f32; 16] = [
            c as f32,
            0.0,
            -s as f32,
            0.0,
            0.0,
            1.0,
            0.0,
            0.0,
            s as f32,
            0.0,
            c as f32,
            0.0,
            origin[0] as f32,
            origin[1] as f32,
            origin[2] as f32,
            1.0,
        ];
        // The camera: 1.5 to the side and 4 out from the flank (world), looking at the vehicle.
        let out = [4.0 * s, 0.3, 4.0 * c];
        let camera = [
            origin[0] + out[0] + 1.5 * c,
            origin[1] + out[1],
            origin[2] + out[2] - 1.5 * s,
        ];
        let forward = {
            let d = [0, 1, 2].map(|k| origin[k] - camera[k]);
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            d.map(|v| v / n)
        };
        let view = zshift_harness::world::view_matrix(
            &zshift_harness::world::looking_along(forward),
            camera,
        );
        // V·M in f32, as glm's mat4 * mat4.
        let model_view = zshift_harness::world::model_view(&view, &model, true);
        let to_eye = |p: &[f32; 3]| zshift_harness::world::transformed(&model_view, *p);
        // The camera in model space, for the occluder's lift along the flank's normal.
        let height = {
            let eye_origin = to_eye(&[0.0, 0.0, 0.9]);
            let eye_normal = [0, 1, 2].map(|r| f64::from(model_view[8 + r]));
            -(0..3).map(|k| eye_origin[k] * eye_normal[k]).sum::<f64>()
        };
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            let base = zshift::projection::projection(&frustum, clip).unwrap();
            let reversed = clip == ClipDepth::ReversedZeroToOne;
            for format in [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F] {
                for equal in [false, true] {
                    let (func, state) = depth_test(reversed, equal);
                    let label =
                        format!("vehicle {clip:?} {format:?} test 0x{func:04X} T {translate}");
                    let corners: Vec<glam::Vec3> = [0, 1, 2, 5]
                        .iter()
                        .map(|&i| {
                            let e = to_eye(&decal[i]);
                            glam::Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32)
                        })
                        .collect();
                    let shape =
                        zshift::matrix_in::decal_shape(&base, clip, [PX, PX], &corners).unwrap();
                    let asked = Decal {
                        viewport: [PX, PX],
                        format: gl_common::format_of(format),
                        depth_range: shape.depth_range,
                        slope: shape.slope,
                        exact_depth: false,
                        snapping,
                        base: zshift::recommend::Base::InsideFrustum,
                        profile: None,
                        footprint: Some(shape.footprint),
                        depth_test: Some(
                            zshift::recommend::DepthTest::from_gl(func).expect("a depth test"),
                        ),
                        pipeline: zshift::model::Pipeline {
                            // The largest coordinate of the camera and the model's origin in the
                            // space the shader receives vertices in: the vehicle's.
                            world_reach: 5.0,
                            eye_first: true,
                            view: Some(model_view),
                            world_box: Some([[-2.0, -1.0, 0.9], [2.0, 1.0, 0.9]]),
                            ..zshift::model::Pipeline::default()
                        },
                    };
                    let rec =
                        recommend(&base, clip, &asked).unwrap_or_else(|e| panic!("{label}: {e}"));
                    // The occluder: the flank moved along its normal so that it is the gap (and
                    // a hair) in front at the decal's nearest pixel, more at the others.
                    let lift =
                        (rec.bleed_gap * height / shape.depth_range[0] * (1.0 + 1e-6)) as f32;
                    let occluder: Vec<[f32; 3]> =
                        flank.iter().map(|p| [p[0], p[1], p[2] + lift]).collect();
                    let drawn = Drawn {
                        px: PX,
                        origin: [0, 0],
                        range: [0.0, 1.0],
                        format,
                        clip,
                        view: &model_view,
                        base: &base,
                        state,
                    };
                    let judged = drawn.judge(&mut gl, &flank, &decal, &rec.matrix, &occluder);
                    judged.assert_kept(&label, 500, &rec);
                    control_lost += judged.control.hit;
                    gaps.push(rec.bleed_gap / shape.depth_range[0]);
                    scenes += 1;
                }
            }
        }
    }
    summarize(
        &format!(
            "{scenes} decals on a vehicle through its f32 model-view, 0 to 10^5 from the origin"
        ),
        "gap / distance",
        &mut gaps,
        control_lost,
    );
}

/// The strict depth test toward the camera, or its `…EQUAL` form (`GL_GREATER`/`GL_GEQUAL`
/// reversed), and the draw state of every pass with it.
fn depth_test(reversed: bool, equal: bool) -> (u32, DrawState) {
    let func = match (reversed, equal) {
        (false, false) => glow::LESS,
        (false, true) => glow::LEQUAL,
        (true, false) => glow::GREATER,
        (true, true) => glow::GEQUAL,
    };
    let state = DrawState {
        depth_func: func,
        ..DrawState::default()
    };
    (func, state)
}

/// Prints what a sweep of judged decal scenes gave (every scene asserted kept already): the
/// median and largest gap (as `gap`), the pixels lost without an offset; and asserts some were
/// (else the experiment could not fail).
fn summarize(scenes: &str, gap: &str, gaps: &mut [f64], control_lost: usize) {
    gaps.sort_by(f64::total_cmp);
    println!(
        "{scenes}: 0 pixels lost, 0 shown over an occluder at the gap; {gap} median {:.2e}, max {:.2e}; {control_lost} lost without an offset",
        gaps[gaps.len() / 2],
        gaps[gaps.len() - 1]
    );
    assert!(
        control_lost > 0,
        "no z-fighting without an offset: the experiment cannot fail"
    );
}

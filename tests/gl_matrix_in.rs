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

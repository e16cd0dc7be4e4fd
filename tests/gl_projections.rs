//! The projections on a real rasterizer (headless EGL, Mesa llvmpipe via `zshift-harness`): reversed Z
//! with `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)`, `GL_GREATER` and D32F; `[0, 1]` depth;
//! the tweaked infinite projection; Kooima's median projection through the shipped GLSL; the
//! polygon-offset conversion; and the measured depth step beside the predicted one.
//! Fails with the reason when no GL context can be made; never skips.

mod gl_common;
mod projections_gl;

use projections_gl::{eye_z_spacing, measure_step, Drawer, MdpProgram, BASE, COLUMNS, DECAL};
use zshift::clip_offset::{ndc_offset_matrix, offset_projection, offset_tweaked_infinite};
use zshift::polygon_offset::{bias_of_shift, BiasApi};
use zshift::precision::{DepthFormat, DepthMapping};
use zshift::projection::{projection, tweaked_infinite, ClipDepth, MIN_INFINITE_TWEAK};
use zshift::Frustum;
use zshift_harness::{
    rgba8, ClipDepth as GlClip, DepthFormat as GlFormat, DrawState, Gl, Profile, Quad,
};

const SIZE: u32 = 96;

fn context() -> Gl {
    Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no headless GL context (EGL surfaceless): {e}"))
}

fn frustum(n: f64, f: f64) -> Frustum {
    Frustum::new(-0.5 * n, 0.5 * n, -0.5 * n, 0.5 * n, n, f).unwrap()
}

fn decal_loss(
    gl: &mut Gl,
    base_proj: &[f32; 16],
    decal_proj: &[f32; 16],
    d: f64,
    reversed: bool,
) -> usize {
    projections_gl::decal_loss(gl, base_proj, decal_proj, d, 0.0, reversed).unwrap()
}

#[test]
fn reversed_z_float_needs_the_offset_in_element_14() {
    let mut gl = context();
    gl.set_target(SIZE, SIZE, GlFormat::D32F).unwrap();
    gl.clip_control(GlClip::ZeroToOne).unwrap();
    for far in [1000.0, f64::INFINITY] {
        let fr = frustum(0.1, far);
        let plain = projection(&fr, ClipDepth::ReversedZeroToOne).unwrap();
        let mapping = DepthMapping::projection(0.1, far, ClipDepth::ReversedZeroToOne).unwrap();
        for d in [0.7, 30.0, 900.0] {
            // Four float steps at d, as an eye-space shift, through element 14.
            let delta = 4.0 * mapping.depth_step(d, DepthFormat::Float32).unwrap();
            let offset = offset_projection(&fr, ClipDepth::ReversedZeroToOne, delta, -d).unwrap();
            let lost_offset = decal_loss(&mut gl, &plain, &offset, d, true);
            let lost_none = decal_loss(&mut gl, &plain, &plain, d, true);
            // Lengyel's recipe as written: scale element 10 by 1 + ε with the same ε.
            let eps = delta / (d - delta);
            let mut scaled10 = plain;
            scaled10[10] *= (1.0 + eps) as f32;
            let lost_scaled10 = decal_loss(&mut gl, &plain, &scaled10, d, true);
            println!("reversed D32F f={far} d={d}: lost with element-14 offset {lost_offset}, none {lost_none}, element 10 scaled {lost_scaled10}");
            assert_eq!(
                lost_offset, 0,
                "f={far} d={d}: the relative offset lost pixels"
            );
            assert!(
                lost_none > 0,
                "f={far} d={d}: coplanar decal did not z-fight (test is void)"
            );
            assert!(
                lost_scaled10 > 0,
                "f={far} d={d}: scaling element 10 unexpectedly worked"
            );
            if far.is_infinite() {
                assert_eq!(plain[10], 0.0);
                assert_eq!(
                    scaled10, plain,
                    "element 10 is 0: scaling it changes nothing"
                );
            }
        }
    }
}

#[test]
fn zero_to_one_depth_takes_a_constant_offset_through_element_10() {
    let mut gl = context();
    for format in [GlFormat::D24, GlFormat::D32F] {
        gl.set_target(SIZE, SIZE, format).unwrap();
        gl.clip_control(GlClip::ZeroToOne).unwrap();
        let fr = frustum(0.1, 1000.0);
        let plain = projection(&fr, ClipDepth::ZeroToOne).unwrap();
        let mapping = DepthMapping::projection(0.1, 1000.0, ClipDepth::ZeroToOne).unwrap();
        let fmt = if format == GlFormat::D24 {
            DepthFormat::Unorm24
        } else {
            DepthFormat::Float32
        };
        for d in [0.7, 30.0, 900.0] {
            let delta = 2.0 * mapping.depth_step(d, fmt).unwrap();
            let offset = offset_projection(&fr, ClipDepth::ZeroToOne, delta, -d).unwrap();
            let lost = decal_loss(&mut gl, &plain, &offset, d, false);
            println!("[0,1] {format:?} d={d}: lost {lost}");
            assert_eq!(lost, 0, "{format:?} d={d}");
        }
    }
}

#[test]
fn tweaked_infinite_projection_draws_what_the_plain_one_loses() {
    let mut gl = context();
    gl.set_target(SIZE, SIZE, GlFormat::D24).unwrap();
    gl.clip_control(GlClip::NegativeOneToOne).unwrap();
    let fr = frustum(1.0, f64::INFINITY);
    let plain = projection(&fr, ClipDepth::NegOneToOne).unwrap();
    let tweaked = tweaked_infinite(&fr, MIN_INFINITE_TWEAK).unwrap();
    for d in [1e8, 1e12, 1e20] {
        let s = 0.45 * d;
        let quad = Quad::rect(-s as f32, s as f32, -s as f32, s as f32, -d as f32);
        let mut drawn = Vec::new();
        for m in [&plain, &tweaked] {
            gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
            gl.draw_quad(&quad, m, BASE, &DrawState::default()).unwrap();
            drawn.push(gl.read_color().unwrap().count(rgba8(BASE), None));
        }
        println!(
            "infinite far, d={d:e}: plain draws {} px, tweaked {} px",
            drawn[0], drawn[1]
        );
        assert!(
            drawn[1] > 5000,
            "d={d}: the tweaked projection lost the far quad"
        );
        assert!(
            drawn[0] < drawn[1],
            "d={d}: the plain infinite projection did not lose it"
        );
    }
    // Its offset variant separates a coplanar decal.
    let mapping = DepthMapping::tweaked_infinite(1.0, MIN_INFINITE_TWEAK).unwrap();
    for d in [3.0, 300.0] {
        let delta = 2.0 * mapping.depth_step(d, DepthFormat::Unorm24).unwrap();
        let offset = offset_tweaked_infinite(&fr, MIN_INFINITE_TWEAK, delta, -d).unwrap();
        assert_eq!(
            decal_loss(&mut gl, &tweaked, &offset, d, false),
            0,
            "tweaked d={d}"
        );
    }
}

#[test]
fn median_projection_glsl_compiles_maps_depth_and_takes_an_offset() {
    let mut gl = context();
    let prog = MdpProgram::new(&gl).unwrap_or_else(|e| panic!("{e}"));
    gl.set_target(SIZE, SIZE, GlFormat::D24).unwrap();
    gl.clip_control(GlClip::NegativeOneToOne).unwrap();
    let proj = projection(&frustum(0.1, 100.0), ClipDepth::NegOneToOne).unwrap();
    let median = 10.0f32;
    let mapping = DepthMapping::median(f64::from(median)).unwrap();
    for d in [0.05, 3.0, 10.0, 250.0] {
        let s = 0.45 * d;
        let quad = Quad::rect(-s as f32, s as f32, -s as f32, s as f32, -d as f32);
        gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
        prog.draw(&gl, &quad, &proj, median, 0.0, BASE, glow::LESS)
            .unwrap();
        let coverage = gl.read_color().unwrap().count(rgba8(BASE), None);
        let depth =
            gl.read_depth().unwrap()[(SIZE as usize / 2) * SIZE as usize + SIZE as usize / 2];
        let want = mapping.window_depth(d).unwrap();
        println!("median {median} d={d}: window depth {depth} (predicted {want}), {coverage} px");
        assert!(
            (f64::from(depth) - want).abs() <= 4.0 / 16_777_215.0,
            "d={d}: depth {depth} vs {want}"
        );
        // x and y are the standard projection's: same coverage as the matrix path.
        gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
        gl.draw_quad(
            &quad,
            &proj,
            BASE,
            &DrawState {
                depth_func: glow::ALWAYS,
                ..Default::default()
            },
        )
        .unwrap();
        if (0.1..=100.0).contains(&d) {
            assert_eq!(
                gl.read_color().unwrap().count(rgba8(BASE), None),
                coverage,
                "d={d}: coverage"
            );
        }
    }
    // The depth offset uniform: a coplanar decal wins with two D24 steps, and z-fights without.
    for d in [2.0, 10.0, 400.0] {
        let delta = 2.0 * mapping.depth_step(d, DepthFormat::Unorm24).unwrap();
        let c = zshift::median::ndc_offset(f64::from(median), delta, -d).unwrap() as f32;
        let (s, t) = (0.45 * d, 0.3 * d);
        let base = Quad::rect(-s as f32, s as f32, -s as f32, s as f32, -d as f32);
        let decal = Quad::on_plane(-t, 0.77 * t, -0.91 * t, t, |_, _| -d);
        let mut decal_px = |with_base: bool, offset: f32| {
            gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
            if with_base {
                prog.draw(&gl, &base, &proj, median, 0.0, BASE, glow::LESS)
                    .unwrap();
            }
            prog.draw(&gl, &decal, &proj, median, offset, DECAL, glow::LESS)
                .unwrap();
            gl.read_color().unwrap().count(rgba8(DECAL), None)
        };
        let alone = decal_px(false, 0.0);
        let with_offset = decal_px(true, c);
        let without = decal_px(true, 0.0);
        println!("median d={d}: decal {alone} px alone, {with_offset} over the base with offset {c:e}, {without} without");
        assert_eq!(with_offset, alone, "d={d}: the offset decal lost pixels");
        assert!(
            without < alone,
            "d={d}: coplanar decal did not z-fight (test is void)"
        );
    }
}

#[test]
fn polygon_offset_units_match_the_conversion() {
    let mut gl = context();
    gl.set_target(SIZE, SIZE, GlFormat::D24).unwrap();
    gl.clip_control(GlClip::NegativeOneToOne).unwrap();
    let fr = frustum(0.1, 1000.0);
    let proj = projection(&fr, ClipDepth::NegOneToOne).unwrap();
    let mapping = DepthMapping::projection(0.1, 1000.0, ClipDepth::NegOneToOne).unwrap();
    let q = 1.0 / 16_777_215.0;
    for (d, steps) in [(5.0, 3.0), (200.0, 7.0)] {
        let delta = steps * mapping.depth_step(d, DepthFormat::Unorm24).unwrap();
        let units =
            bias_of_shift(&mapping, DepthFormat::Unorm24, BiasApi::OpenGl, delta, -d).unwrap();
        let s = 0.45 * d;
        let quad = Quad::rect(-s as f32, s as f32, -s as f32, s as f32, -d as f32);
        let centre = (SIZE as usize / 2) * SIZE as usize + SIZE as usize / 2;
        let mut depths = Vec::new();
        for offset in [None, Some((0.0f32, units as f32))] {
            gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
            let state = DrawState {
                polygon_offset: offset,
                ..Default::default()
            };
            gl.draw_quad(&quad, &proj, BASE, &state).unwrap();
            depths.push(f64::from(gl.read_depth().unwrap()[centre]));
        }
        let moved = (depths[1] - depths[0]) / q;
        println!("glPolygonOffset(0, {units:.3}) at d={d}: stored depth moved {moved:.3} steps");
        // GL leaves r to the implementation; with r >= 1/(2^24 - 1) the shift is at least δ.
        // llvmpipe applies r = 2/(2^24 - 1): twice the units, to within one step.
        assert!(
            moved <= units + 1e-6,
            "d={d}: moved {moved} steps, less than the {units} asked"
        );
        assert!(
            (moved - 2.0 * units).abs() <= 1.0 + 1e-6,
            "d={d}: moved {moved} steps, llvmpipe's 2·{units} expected"
        );
    }
}

/// The measured depth step against distance, beside the prediction, for the conventions of
/// the precision table (the example `precision_table` prints all of it).
#[test]
fn measured_depth_step_matches_the_prediction() {
    let mut gl = context();
    let (n, f) = (0.5, 1000.0);
    let prog = MdpProgram::new(&gl).unwrap_or_else(|e| panic!("{e}"));
    let std_proj = projection(&frustum(n, f), ClipDepth::NegOneToOne).unwrap();
    let rows: Vec<(&str, GlFormat, GlClip, DepthMapping, DepthFormat, Drawer)> = vec![
        (
            "standard D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            DepthMapping::projection(n, f, ClipDepth::NegOneToOne).unwrap(),
            DepthFormat::Unorm24,
            Drawer::Matrix(std_proj),
        ),
        (
            "standard D32F",
            GlFormat::D32F,
            GlClip::NegativeOneToOne,
            DepthMapping::projection(n, f, ClipDepth::NegOneToOne).unwrap(),
            DepthFormat::Float32,
            Drawer::Matrix(std_proj),
        ),
        (
            "reversed D32F",
            GlFormat::D32F,
            GlClip::ZeroToOne,
            DepthMapping::projection(n, f64::INFINITY, ClipDepth::ReversedZeroToOne).unwrap(),
            DepthFormat::Float32,
            Drawer::Matrix(
                projection(&frustum(n, f64::INFINITY), ClipDepth::ReversedZeroToOne).unwrap(),
            ),
        ),
        (
            "tweaked infinite D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            DepthMapping::tweaked_infinite(n, MIN_INFINITE_TWEAK).unwrap(),
            DepthFormat::Unorm24,
            Drawer::Matrix(
                tweaked_infinite(&frustum(n, f64::INFINITY), MIN_INFINITE_TWEAK).unwrap(),
            ),
        ),
        (
            "median m=10 D24",
            GlFormat::D24,
            GlClip::NegativeOneToOne,
            DepthMapping::median(10.0).unwrap(),
            DepthFormat::Unorm24,
            Drawer::Median(&prog, std_proj, 10.0),
        ),
    ];
    for (name, glf, clip, mapping, fmt, drawer) in &rows {
        gl.set_target(COLUMNS as u32, 2, *glf).unwrap();
        gl.clip_control(*clip).unwrap();
        for d in [2.0, 20.0, 200.0] {
            let predicted = mapping.depth_step(d, *fmt).unwrap();
            let m = measure_step(&mut gl, drawer, d, predicted).unwrap();
            let measured = m
                .step
                .unwrap_or_else(|| panic!("{name} d={d}: every column stored one value"));
            let floor = eye_z_spacing(d);
            let ratio = measured / predicted.max(floor);
            println!("{name:22} d={d:6}: predicted {predicted:.3e}, measured {measured:.3e}, eye-z ulp {floor:.1e}, ratio {ratio:.3}, reversals {}", m.reversals);
            assert!((0.6..=1.6).contains(&ratio), "{name} d={d}: measured {measured:e} vs predicted {predicted:e} (eye-z spacing {floor:e})");
        }
    }
}

#[test]
fn perspective_frames_the_field_of_view() {
    let mut gl = context();
    gl.set_target(SIZE, SIZE / 2, GlFormat::D24).unwrap();
    gl.clip_control(GlClip::NegativeOneToOne).unwrap();
    let (fovy, aspect) = (60.0f64, 2.0f64);
    let m = zshift::projection::perspective(fovy, aspect, 0.1, 100.0)
        .unwrap()
        .to_cols_array();
    for d in [0.5, 40.0] {
        // Half the view's height and width at distance d: the middle half of each axis.
        let half_h = 0.5 * d * (fovy.to_radians() / 2.0).tan();
        let half_w = half_h * aspect;
        let quad = Quad::rect(
            -half_w as f32,
            half_w as f32,
            -half_h as f32,
            half_h as f32,
            -d as f32,
        );
        gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).unwrap();
        gl.draw_quad(&quad, &m, BASE, &DrawState::default())
            .unwrap();
        let px = gl.read_color().unwrap().count(rgba8(BASE), None);
        assert_eq!(px, (SIZE as usize / 2) * (SIZE as usize / 4), "d={d}");
        // Its offset variant moves depth only: every element but 10 is unchanged.
        let off = zshift::clip_offset::offset_projection(
            &zshift::projection::perspective_frustum(fovy, aspect, 0.1, 100.0).unwrap(),
            ClipDepth::NegOneToOne,
            0.01 * d,
            -d,
        )
        .unwrap();
        for i in (0..16).filter(|&i| i != 10) {
            assert_eq!(off[i].to_bits(), m[i].to_bits());
        }
    }
}

/// One relative ε (element 14) serves decals at every distance under reversed Z with float depth,
/// and shifts far decals hundreds of times less than the constant offset that also serves them.
#[test]
fn one_relative_epsilon_serves_every_distance_under_reversed_float() {
    use zshift::clip_offset::relative_offset_matrix;
    use zshift::plan::{range_offset, OffsetKind};
    use zshift::projection::projection_f64;
    let mut gl = context();
    gl.set_target(SIZE, SIZE, GlFormat::D32F).unwrap();
    gl.clip_control(GlClip::ZeroToOne).unwrap();
    let fr = frustum(0.5, f64::INFINITY);
    let mapping =
        DepthMapping::projection(0.5, f64::INFINITY, ClipDepth::ReversedZeroToOne).unwrap();
    let (fmt, steps) = (DepthFormat::Float32, 8.0);
    let relative = range_offset(&mapping, fmt, OffsetKind::Relative, 1.0, 500.0, steps).unwrap();
    let constant = range_offset(&mapping, fmt, OffsetKind::Ndc, 1.0, 500.0, steps).unwrap();
    println!(
        "relative eps {:e}: shift {:e} at 1, {:e} at 500",
        relative.offset, relative.shift_near, relative.shift_far
    );
    println!(
        "constant c {:e}: shift {:e} at 1, {:e} at 500",
        constant.offset, constant.shift_near, constant.shift_far
    );
    assert!(relative.shift_far * 100.0 < constant.shift_far);
    let plain = projection(&fr, ClipDepth::ReversedZeroToOne).unwrap();
    // A rasterizer that snaps window positions to 2^-b pixel before setting depth up moves a
    // sloped plane's depth by S = 2^-(b+1)·|∂w/∂y| per pixel (src/model/snap.rs). On this plane
    // w ∝ 1 + s·yₙ·t (t = 0.5) and the decal reaches 1.82 d, so S/w ≤ 2^-(b+1)·s·t·(2/SIZE)·1.82
    // at every distance: a relative ε still serves them all, with those f32 steps (2^-24) more.
    // llvmpipe sets depth up unsnapped: none.
    let snapping = gl_common::snapping_of(&gl);
    let snap_steps = |slope: f64| match snapping {
        zshift::recommend::Snapping::Unsnapped => 0.0,
        zshift::recommend::Snapping::SubpixelBits(b) => {
            2f64.powi(-(b as i32) - 1)
                * slope
                * 0.5
                * (2.0 / f64::from(SIZE))
                * 1.82
                * 2f64.powi(24)
        }
    };
    for d in [1.0, 30.0, 500.0] {
        for slope in [0.0, 3.0] {
            let steps = steps + snap_steps(slope);
            let relative =
                range_offset(&mapping, fmt, OffsetKind::Relative, 1.0, 500.0, steps).unwrap();
            let decal = relative_offset_matrix(
                &projection_f64(&fr, ClipDepth::ReversedZeroToOne).unwrap(),
                relative.offset,
            )
            .unwrap();
            let lost = projections_gl::decal_loss(&mut gl, &plain, &decal, d, slope, true).unwrap();
            assert_eq!(
                lost, 0,
                "d={d} slope={slope}: one relative epsilon ({steps:.1} f32 steps) lost pixels"
            );
        }
    }
}

/// `[0, 1]` depth has its own ε bound: `1/(2^m − 1)·(f − n)/f`, half the `[−1, 1]` NDC quantum
/// over a smaller `|m10|`. Element 10 scaled by exactly `1 − ε_min` separates a facing decal.
#[test]
fn zero_to_one_min_epsilon_separates_a_facing_decal_on_d24() {
    use zshift::projection::projection_f64;
    let mut gl = context();
    gl.set_target(SIZE, SIZE, GlFormat::D24).unwrap();
    gl.clip_control(GlClip::ZeroToOne).unwrap();
    let fr = frustum(0.1, 1000.0);
    let m64 = projection_f64(&fr, ClipDepth::ZeroToOne).unwrap();
    let plain = projection(&fr, ClipDepth::ZeroToOne).unwrap();
    let mapping = DepthMapping::projection(0.1, 1000.0, ClipDepth::ZeroToOne).unwrap();
    for d in [0.7, 30.0, 900.0] {
        let eps = mapping.min_epsilon(d, DepthFormat::Unorm24).unwrap();
        // m10·(1 − ε) = m10 − c with c = −ε·m10 < 0 (toward the camera).
        let decal = ndc_offset_matrix(&m64, eps * m64[10]).unwrap();
        let lost = decal_loss(&mut gl, &plain, &decal, d, false);
        println!("[0,1] D24 d={d}: eps_min {eps:e}, lost {lost}");
        assert_eq!(lost, 0, "d={d}");
    }
}

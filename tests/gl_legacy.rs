//! The legacy drop-in checked against Mesa itself, in a compatibility-profile context:
//! `zshift_frustum` equals `glFrustum` + `glGetFloatv(GL_PROJECTION_MATRIX)`, and the seed's
//! `LoadOffsetMatrix` (seed 000: f32 ε, `m[10] *= 1 + ε`, `glLoadMatrixf`) loses an offset on
//! D24 that `zshift_load_offset_matrix` keeps. Everything is drawn with the fixed-function
//! pipeline (`glBegin(GL_QUADS)`), as a legacy engine draws. Fails (never skips) without GL.

use zshift::ffi::{zshift_frustum, zshift_load_offset_matrix, ZSHIFT_OK};
use zshift_harness::{rgba8, DepthFormat, DrawState, Gl, Profile, Quad};

fn compat() -> Gl {
    Gl::new(Profile::Compatibility).unwrap_or_else(|e| {
        panic!("no compatibility-profile OpenGL context (EGL surfaceless): {e}")
    })
}

/// Distance in f32 steps between two finite floats of the same sign (0 when equal).
fn ulps(a: f32, b: f32) -> u32 {
    if a == b {
        return 0;
    }
    assert_eq!(
        a.is_sign_negative(),
        b.is_sign_negative(),
        "{a} and {b} differ in sign"
    );
    a.to_bits().abs_diff(b.to_bits())
}

/// Frusta with f ≥ 2n, where Mesa's float evaluation of glFrustum is itself accurate.
#[test]
fn zshift_frustum_equals_mesa_glfrustum_within_one_ulp() {
    let mut gl = compat();
    let frusta = [
        (-1.0, 1.0, -1.0, 1.0, 1.0, 100.0),
        (
            -0.5773502691896257,
            0.5773502691896257,
            -0.4330127018922193,
            0.4330127018922193,
            0.1,
            1e5,
        ),
        (-0.3, 0.7, -0.2, 0.5, 0.25, 1e6),
        (-2.0, 1.0, 0.5, 3.0, 3.0, 7.5),
        (-1e-3, 1e-3, -1e-3, 1e-3, 1e-3, 1e4),
    ];
    let mut worst = 0;
    for (l, r, b, t, n, f) in frusta {
        let mesa = gl.legacy_frustum(l, r, b, t, n, f).expect("glFrustum");
        let mut ours = [0.0f32; 16];
        assert_eq!(
            zshift_frustum(l, r, b, t, n, f, ours.as_mut_ptr()),
            ZSHIFT_OK
        );
        for i in 0..16 {
            let d = ulps(ours[i], mesa[i]);
            worst = worst.max(d);
            assert!(d <= 1, "glFrustum({l}, {r}, {b}, {t}, {n}, {f}) element {i}: zshift {} vs Mesa {} ({d} ulps)", ours[i], mesa[i]);
        }
    }
    println!("largest difference from Mesa's glFrustum: {worst} ulp");
}

/// Where f/n is within a few f32 ulps of 1, Mesa evaluates glFrustum in float and `f − n`
/// cancels; zshift's element 10 stays the f32 nearest `−(f+n)/(f−n)` (here `f − n` is exact in
/// f64 by Sterbenz, so f64 gives the reference). Printed, to show the drop-in is no worse.
#[test]
fn near_degenerate_frustum_mesa_cancels_zshift_does_not() {
    let mut gl = compat();
    let (n, f) = (3.0, 3.000001);
    let mesa = gl
        .legacy_frustum(-2.0, 1.0, 0.5, 3.0, n, f)
        .expect("glFrustum");
    let mut ours = [0.0f32; 16];
    assert_eq!(
        zshift_frustum(-2.0, 1.0, 0.5, 3.0, n, f, ours.as_mut_ptr()),
        ZSHIFT_OK
    );
    let exact = (-(f + n) / (f - n)) as f32;
    println!(
        "f/n = 1 + 3.3e-7: element 10 exact {exact:e}, zshift {:e}, Mesa {:e} ({} ulps off)",
        ours[10],
        mesa[10],
        ulps(mesa[10], exact)
    );
    assert_eq!(ours[10], exact);
}

/// The seed's LoadOffsetMatrix, as its C source does it: ε computed in double (f and n are
/// GLdouble), stored in a GLfloat, then `matrix[10] *= 1.0F + epsilon` in float arithmetic.
fn seed_load_offset_matrix(
    gl: &mut Gl,
    fr: (f64, f64, f64, f64, f64, f64),
    delta: f32,
    pz: f32,
) -> [f32; 16] {
    let (l, r, b, t, n, f) = fr;
    let mut matrix = gl.legacy_frustum(l, r, b, t, n, f).expect("glFrustum");
    let epsilon = (-2.0 * f * n * f64::from(delta)
        / ((f + n) * f64::from(pz) * f64::from(pz + delta))) as f32;
    matrix[10] *= 1.0f32 + epsilon;
    gl.legacy_load_projection(&matrix).expect("glLoadMatrixf");
    matrix
}

/// Draws the base with glFrustum and the decal with `decal` loaded; returns lost decal pixels.
fn lost_pixels(
    gl: &mut Gl,
    fr: (f64, f64, f64, f64, f64, f64),
    decal: &[f32; 16],
    base_q: &Quad,
    decal_q: &Quad,
) -> (usize, usize) {
    let (l, r, b, t, n, f) = fr;
    let (blue, red) = ([0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 0.0, 1.0]);
    gl.clear([0.0; 4], 1.0).unwrap();
    gl.legacy_load_projection(decal).unwrap();
    let always = DrawState {
        depth_func: zshift_harness::glow::ALWAYS,
        ..DrawState::default()
    };
    gl.legacy_draw_quad(decal_q, red, &always).unwrap();
    let mask = gl.read_color().unwrap().mask_of(rgba8(red));
    gl.clear([0.0; 4], 1.0).unwrap();
    gl.legacy_frustum(l, r, b, t, n, f).unwrap();
    gl.legacy_draw_quad(base_q, blue, &DrawState::default())
        .unwrap();
    gl.legacy_load_projection(decal).unwrap();
    gl.legacy_draw_quad(decal_q, red, &DrawState::default())
        .unwrap();
    let image = gl.read_color().unwrap();
    (
        image.count_not_in_mask(&mask, rgba8(red)),
        mask.iter().filter(|&&m| m).count(),
    )
}

#[test]
fn the_seeds_load_offset_matrix_loses_the_offset_on_d24_where_zshift_keeps_it() {
    let mut gl = compat();
    gl.set_target(64, 64, DepthFormat::D24).expect("D24 target");
    let mut seed_lost_total = 0;
    for (f, depth) in [
        (100.0, 50.0),
        (1e3, 100.0),
        (1e4, 2e3),
        (1e4, 9e3),
        (1e5, 3e4),
        (1e6, 5e5),
    ] {
        let e = 0.5773502691896257;
        let fr = (-e, e, -e, e, 1.0, f);
        let pz = -depth as f32;
        // The seed's own minimum shift (eq. 4.1.9 with the corrected k of seed 002): one step.
        let delta = zshift::min_delta_toward(1.0, f, 24, f64::from(pz)).unwrap();
        let x = 0.4 * depth * e;
        let base_q = Quad::rect(-x as f32, x as f32, -x as f32, x as f32, pz);
        let decal_q = Quad::rect(
            -0.5 * x as f32,
            0.6 * x as f32,
            -0.55 * x as f32,
            0.45 * x as f32,
            pz,
        );
        let plain = gl
            .legacy_frustum(fr.0, fr.1, fr.2, fr.3, fr.4, fr.5)
            .unwrap();
        let seed = seed_load_offset_matrix(&mut gl, fr, delta as f32, pz);
        let mut ours = [0.0f32; 16];
        assert_eq!(
            zshift_load_offset_matrix(
                fr.0,
                fr.1,
                fr.2,
                fr.3,
                fr.4,
                fr.5,
                delta,
                f64::from(pz),
                ours.as_mut_ptr()
            ),
            ZSHIFT_OK
        );
        let (seed_lost, of) = lost_pixels(&mut gl, fr, &seed, &base_q, &decal_q);
        let (ours_lost, _) = lost_pixels(&mut gl, fr, &ours, &base_q, &decal_q);
        println!(
            "f/n={f:.0e} Pz={pz} delta={delta:.3e}: plain m10={:e}; seed m10={:e} ({} ulps), lost {seed_lost}/{of}; zshift m10={:e} ({} ulps), lost {ours_lost}/{of}",
            plain[10], seed[10], ulps(seed[10], plain[10]), ours[10], ulps(ours[10], plain[10])
        );
        assert_eq!(
            ours_lost, 0,
            "f/n={f}: zshift_load_offset_matrix lost {ours_lost} of {of} pixels"
        );
        seed_lost_total += seed_lost;
    }
    assert!(
        seed_lost_total > 0,
        "the seed's f32 LoadOffsetMatrix never lost a pixel: the test cannot tell them apart"
    );
}

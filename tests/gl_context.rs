//! A real OpenGL context can be made with no window (EGL surfaceless): prints what it is.
//! Fails, with the reason, if no context can be made — it never skips.

use zshift_harness::{DepthFormat, Gl, Profile};

#[test]
fn core_and_compatibility_contexts_exist() {
    for profile in [Profile::Core, Profile::Compatibility] {
        let mut gl = Gl::new(profile).unwrap_or_else(|e| panic!("no {profile:?} GL context: {e}"));
        println!(
            "{profile:?}: renderer {:?}, version {:?}, GL_SUBPIXEL_BITS {}",
            gl.renderer(),
            gl.version(),
            gl.subpixel_bits()
        );
        assert!(!gl.renderer().is_empty(), "GL_RENDERER is empty");
        for format in DepthFormat::ALL {
            gl.set_target(8, 8, format)
                .unwrap_or_else(|e| panic!("{format:?} target: {e}"));
            let bits = gl.depth_bits().expect("depth bits");
            println!("  {format:?}: GL reports {bits} depth bits");
            assert_eq!(
                bits,
                format.bits(),
                "{format:?} attachment reports {bits} bits"
            );
        }
    }
}

/// A facing quad drawn through the shader path covers the viewport's middle and writes the
/// window depth of its plane: checks draw, colour and depth readback end to end.
#[test]
fn a_drawn_quad_reads_back() {
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no GL context: {e}"));
    gl.set_target(16, 16, DepthFormat::D32F).expect("target");
    gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).expect("clear");
    // glFrustum(-1, 1, -1, 1, 1, 3) by hand: m10 = -(3+1)/(3-1) = -2, m14 = -2*3*1/(3-1) = -3.
    let proj = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -2.0, -1.0, 0.0, 0.0, -3.0, 0.0,
    ];
    // At z = -2 the quad [-1, 1]^2 projects to NDC [-0.5, 0.5]^2: window pixels 4..12.
    let quad = zshift_harness::Quad::rect(-1.0, 1.0, -1.0, 1.0, -2.0);
    let red = [1.0, 0.0, 0.0, 1.0];
    gl.draw_quad(&quad, &proj, red, &Default::default())
        .expect("draw");
    let image = gl.read_color().expect("colour");
    assert_eq!(
        image.count(zshift_harness::rgba8(red), None),
        64,
        "the quad covers 8x8 pixels"
    );
    let depth = gl.read_depth().expect("depth");
    // NDC z = (-2*-2 - 3)/2 = 0.5, window depth 0.75 (exact in f32).
    assert_eq!(depth[8 * 16 + 8], 0.75);
    assert_eq!(depth[0], 1.0);
}

/// The depth-stencil target attaches and reports 8 stencil bits (the stencil decal method in
/// the report needs it); a plain target reports none.
#[test]
fn depth_stencil_targets_have_eight_stencil_bits() {
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no GL context: {e}"));
    for format in [DepthFormat::D24, DepthFormat::D32F] {
        gl.set_target_with_stencil(8, 8, format)
            .unwrap_or_else(|e| panic!("{format:?} + stencil: {e}"));
        assert_eq!(gl.stencil_bits().expect("stencil bits"), 8, "{format:?}");
        assert_eq!(gl.depth_bits().expect("depth bits"), format.bits());
        gl.clear_stencil(1).expect("clear stencil");
    }
    assert!(gl.set_target_with_stencil(8, 8, DepthFormat::D16).is_err());
    gl.set_target(8, 8, DepthFormat::D24).expect("plain target");
    assert_eq!(gl.stencil_bits().expect("stencil bits"), 0);
}

/// A 4× multisampled target (packed depth-stencil, as engines attach) reads back each sample
/// on its own: a quad whose edges cross pixels between sample positions covers some samples of
/// those pixels and not others, its inside every sample, the corner none.
#[test]
fn a_multisampled_target_reads_back_every_sample() {
    let mut gl = Gl::new(Profile::Core).unwrap_or_else(|e| panic!("no GL context: {e}"));
    gl.set_target_samples(16, 16, DepthFormat::D24, true, 4)
        .expect("4x target");
    gl.clear([0.0, 0.0, 0.0, 1.0], 1.0).expect("clear");
    let proj = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -2.0, -1.0, 0.0, 0.0, -3.0, 0.0,
    ];
    // At z = -2, x and y in [-0.55, 0.55] project to window 5.8..10.2: edges inside pixels.
    let quad = zshift_harness::Quad::rect(-0.55, 0.55, -0.55, 0.55, -2.0);
    let red = zshift_harness::rgba8([1.0, 0.0, 0.0, 1.0]);
    gl.draw_quad(&quad, &proj, [1.0, 0.0, 0.0, 1.0], &Default::default())
        .expect("draw");
    let image = gl.read_color().expect("colour");
    assert_eq!(
        (image.width, image.height),
        (16, 64),
        "four 16x16 sample images"
    );
    let red_at = |s: usize, x: usize, y: usize| image.at(x, 16 * s + y)[..3] == red[..3];
    assert!((0..4).all(|s| red_at(s, 8, 8)), "inside: every sample");
    assert!((0..4).all(|s| !red_at(s, 0, 0)), "the corner: none");
    let partial = (0..16 * 16)
        .filter(|i| {
            let covered = (0..4).filter(|&s| red_at(s, i % 16, i / 16)).count();
            covered > 0 && covered < 4
        })
        .count();
    assert!(
        partial > 0,
        "no pixel with some samples covered: not multisampled"
    );
    // About 4.4 x 4.4 pixels of area: 77 samples of 4 per pixel.
    let samples = image.count(red, None);
    assert!((60..=96).contains(&samples), "{samples} samples covered");
}

//! The engine's pipeline in the model (no GL): planes containing the view direction answered,
//! packed depth-stencil formats, glDepthRange, the viewport's origin, world-space vertices, and
//! refusals that name the field. References are this file's own arithmetic (the format's
//! quantum, Walker's window depth), never zshift's numbers.

use glam::Vec3;
use zshift::matrix_in::{decal_shape, recommend, Decal};
use zshift::model::Pipeline;
use zshift::precision::DepthFormat;
use zshift::projection::{projection, ClipDepth, Frustum};
use zshift::recommend::{Base, Snapping};

/// glm::perspective(60°, 16/9, 0.1, 1000) as a frustum, and its f32 matrix.
fn camera() -> (Frustum, [f32; 16]) {
    let t = 0.1 * (30f64).to_radians().tan();
    let f = Frustum::new(-t * 16.0 / 9.0, t * 16.0 / 9.0, -t, t, 0.1, 1000.0).unwrap();
    let m = projection(&f, ClipDepth::NegOneToOne).unwrap();
    (f, m)
}

/// A 2×2 decal on the ground 1.7 below a level camera, 10 ahead (eye space).
fn ground_decal() -> [Vec3; 4] {
    [(-1.0, -9.0), (1.0, -9.0), (1.0, -11.0), (-1.0, -11.0)].map(|(x, z)| Vec3::new(x, -1.7, z))
}

fn decal(
    m: &[f32; 16],
    pipeline: Pipeline,
) -> zshift::Result<zshift::recommend::ClipRecommendation> {
    let shape = decal_shape(m, ClipDepth::NegOneToOne, [1920, 1080], &ground_decal())?;
    recommend(
        m,
        ClipDepth::NegOneToOne,
        &Decal {
            viewport: [1920, 1080],
            format: DepthFormat::from_gl_internal_format(0x88F0)?, // GL_DEPTH24_STENCIL8
            depth_range: shape.depth_range,
            slope: shape.slope,
            exact_depth: false,
            snapping: Snapping::SubpixelBits(8),
            base: Base::InsideFrustum,
            profile: None,
            footprint: Some(shape.footprint),
            depth_test: None,
            pipeline,
        },
    )
}

#[test]
fn a_level_camera_over_ground_is_answered() {
    let (_, m) = camera();
    let shape = decal_shape(&m, ClipDepth::NegOneToOne, [1920, 1080], &ground_decal()).unwrap();
    assert!(
        shape.slope.is_infinite(),
        "the ground contains the view direction"
    );
    let r = decal(&m, Pipeline::default()).unwrap();
    // Walker's window depth at the decal's nearest point (9 ahead), and one D24 step: the offset
    // is a few steps, the bleed gap a small part of the distance.
    let q = 1.0 / 16_777_215.0;
    assert!(r.window_offset > q && r.window_offset < 40.0 * q, "{r:?}");
    assert!(r.bleed_gap < 0.01 * 9.0, "{r:?}");
    // Only a plane through the eye (edge-on in the image) is refused.
    let through_eye = [(-1.0, -9.0), (1.0, -9.0), (1.0, -11.0)].map(|(x, z)| Vec3::new(x, 0.0, z));
    let e = decal_shape(&m, ClipDepth::NegOneToOne, [1920, 1080], &through_eye).unwrap_err();
    assert!(e.to_string().contains("through the eye"), "{e}");
}

#[test]
fn packed_depth_stencil_formats_store_depth_as_the_depth_only_ones() {
    assert_eq!(
        DepthFormat::from_gl_internal_format(0x88F0).unwrap(),
        DepthFormat::Unorm24
    );
    assert_eq!(
        DepthFormat::from_gl_internal_format(0x8CAD).unwrap(),
        DepthFormat::Float32
    );
    let e = DepthFormat::from_gl_internal_format(0x1234).unwrap_err();
    assert!(e.to_string().contains("GL_DEPTH24_STENCIL8"), "{e}");
    // Unsized (GL_DEPTH_COMPONENT, GL_DEPTH_STENCIL): the message says how to read the size.
    for unsized_format in [0x1902, 0x84F9] {
        let e = DepthFormat::from_gl_internal_format(unsized_format).unwrap_err();
        assert_eq!(e.kind(), zshift::ErrorKind::Domain);
        assert!(
            e.to_string()
                .contains("GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE"),
            "{e}"
        );
    }
}

#[test]
fn a_depth_sub_range_makes_each_stored_step_larger_in_unit_depth() {
    let (_, m) = camera();
    let full = decal(&m, Pipeline::default()).unwrap();
    let half = decal(
        &m,
        Pipeline {
            depth_range: [0.0, 0.5],
            ..Pipeline::default()
        },
    )
    .unwrap();
    // D24 under glDepthRange(0, 0.5): one stored step is 2/(2^24 − 1) of unit window depth.
    assert_eq!(full.terms.quantum, 1.0 / 16_777_215.0);
    assert_eq!(half.terms.quantum, 2.0 / 16_777_215.0);
    assert!(half.window_offset > full.window_offset);
    // Near 1 the stored depths are larger, and so are the roundings relative to them.
    let upper = decal(
        &m,
        Pipeline {
            depth_range: [0.5, 1.0],
            ..Pipeline::default()
        },
    )
    .unwrap();
    assert!(upper.terms.transform > half.terms.transform);
}

#[test]
fn a_viewport_far_from_the_framebuffer_origin_extrapolates_further() {
    let (_, m) = camera();
    let at_origin = decal(&m, Pipeline::default()).unwrap();
    let inside = decal(
        &m,
        Pipeline {
            viewport_origin: [3500, 1900],
            ..Pipeline::default()
        },
    )
    .unwrap();
    assert!(inside.terms.interpolation > at_origin.terms.interpolation);
}

#[test]
fn world_space_vertices_far_from_the_origin_cost_more_and_the_matrices_tell_how_much() {
    let (_, m) = camera();
    let eye_space = decal(&m, Pipeline::default()).unwrap();
    let far = |reach: f64| Pipeline {
        world_reach: reach,
        eye_first: true,
        ..Pipeline::default()
    };
    let near_origin = decal(&m, far(10.0)).unwrap();
    let far_away = decal(&m, far(1e4)).unwrap();
    assert!(eye_space.terms.vertex < near_origin.terms.vertex);
    assert!(near_origin.terms.vertex < far_away.terms.vertex);
    // The same camera 10⁴ from the origin, level, with its view matrix and the ground's box:
    // the ground's y row sums only the camera's height, so the error off the ground is small.
    let mut view = [0.0f32; 16];
    for i in 0..4 {
        view[5 * i] = 1.0;
    }
    view[12] = -1e4;
    view[13] = -1.7;
    view[14] = -1e4;
    let with_matrices = decal(
        &m,
        Pipeline {
            view: Some(view),
            world_box: Some([[9e3, 0.0, 9e3], [1.1e4, 0.0, 1.1e4]]),
            ..far(1e4)
        },
    )
    .unwrap();
    assert!(
        with_matrices.terms.vertex < 0.01 * far_away.terms.vertex,
        "{} vs {}",
        with_matrices.terms.vertex,
        far_away.terms.vertex
    );
}

#[test]
fn bad_pipelines_are_refused_naming_the_field() {
    let (_, m) = camera();
    let refuse = |p: Pipeline| decal(&m, p).unwrap_err().to_string();
    let e = refuse(Pipeline {
        depth_range: [0.6, 0.5],
        ..Pipeline::default()
    });
    assert!(e.contains("depth_range_far = 0.5"), "{e}");
    let e = refuse(Pipeline {
        world_reach: -1.0,
        ..Pipeline::default()
    });
    assert!(e.contains("world_reach = -1"), "{e}");
    let e = refuse(Pipeline {
        view: Some([0.0; 16]),
        ..Pipeline::default()
    });
    assert!(e.contains("view_matrix and world_box go together"), "{e}");
    let e = refuse(Pipeline {
        view: Some([1.0; 16]),
        world_box: Some([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        ..Pipeline::default()
    });
    assert!(e.contains("world_box"), "{e}");
}

/// A decal 49 to 51 units below an orthographic camera (glOrtho(±6, ±6, 1, 100)), slope 1.2, D24,
/// 1024², asked with `pipeline` and the decal pass's `test`.
fn orthographic_decal(
    pipeline: Pipeline,
    test: Option<zshift::recommend::DepthTest>,
) -> zshift::Result<zshift::recommend::ClipRecommendation> {
    let o = zshift::orthographic::Ortho::new(-6.0, 6.0, -6.0, 6.0, 1.0, 100.0)?;
    let m = zshift::orthographic::ortho(&o, ClipDepth::NegOneToOne)?;
    recommend(
        &m,
        ClipDepth::NegOneToOne,
        &Decal {
            viewport: [1024, 1024],
            format: DepthFormat::Unorm24,
            depth_range: [49.0, 51.0],
            slope: 1.2,
            exact_depth: false,
            snapping: Snapping::SubpixelBits(8),
            base: Base::InsideFrustum,
            profile: None,
            footprint: None,
            depth_test: test,
            pipeline,
        },
    )
}

/// An orthographic decal (an isometric camera) drawn from world space: the f32 view
/// transform's term grows with the camera's distance from the world origin (`world_reach`),
/// stays near the eye-space term with a view matrix and a box near the origin, and is
/// answered, not refused.
#[test]
fn orthographic_decals_take_world_space_vertices() {
    let ask = |pipeline: Pipeline| orthographic_decal(pipeline, None).unwrap();
    let eye = ask(Pipeline::default());
    let near = ask(Pipeline {
        world_reach: 50.0,
        ..Pipeline::default()
    });
    let far = ask(Pipeline {
        world_reach: 1e4,
        ..Pipeline::default()
    });
    assert!(near.terms.vertex > eye.terms.vertex, "{near:?} {eye:?}");
    // The part that does not shrink with distance, 4√3·W, dominates far from the origin: it
    // grows about as W (10⁴/50 = 200 times the reach, most of it in the term).
    let ratio = far.terms.vertex / near.terms.vertex;
    assert!(ratio > 20.0 && ratio < 250.0, "{ratio}");
    assert!(far.window_offset > near.window_offset);
    // A 24-bit step is 2^-24 of the unit depth: the far offset is many of them.
    assert!(far.window_offset * 16_777_216.0 > 10.0, "{far:?}");
}

/// An orthographic decal under GL_LEQUAL: no quantum in the offset (a tie passes), one more in
/// the gap; a depth test of the other direction is refused, naming it.
#[test]
fn orthographic_decals_take_an_equal_test_of_their_convention() {
    let ask = |test| orthographic_decal(Pipeline::default(), test);
    let q = 1.0 / 16_777_215.0; // the D24 quantum in unit window depth
    let strict = ask(None).unwrap();
    let equal = ask(Some(zshift::recommend::DepthTest::LessEqual)).unwrap();
    assert!(
        (strict.window_offset - equal.window_offset - q).abs() < 1e-6 * q,
        "{strict:?} {equal:?}"
    );
    // (R2) in eye units over the span 99: 2Δw − q strict, 2Δw + q with a tie passing.
    let span = 99.0;
    assert!(
        (strict.bleed_gap - (2.0 * strict.window_offset - q) * span).abs()
            < 1e-9 * strict.bleed_gap
    );
    assert!(
        (equal.bleed_gap - (2.0 * equal.window_offset + q) * span).abs() < 1e-9 * equal.bleed_gap
    );
    let e = ask(Some(zshift::recommend::DepthTest::Greater)).unwrap_err();
    assert!(e.to_string().contains("GL_LESS or GL_LEQUAL"), "{e}");
    assert!(e.to_string().contains("depth_func = 0x0204"), "{e}");
}

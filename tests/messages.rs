//! Every refusal of the front door (`zshift_decal_matrix` with a `ZshiftDecal`) and of
//! `zshift_recommend` (a `ZshiftScene`) names the field as the C caller spells it, its value,
//! and, where the rule is a bound, the bound and its value; the output stays untouched. Each case
//! breaks one field of a valid record.

use std::ffi::CStr;

use zshift::ffi::{
    zshift_decal_matrix, zshift_last_error, zshift_recommend, ZshiftDecal, ZshiftDepthTest,
    ZshiftFormat, ZshiftPipeline, ZshiftRecommendation, ZshiftScene, ZSHIFT_CLIP_NEG_ONE_TO_ONE,
    ZSHIFT_OK,
};

fn detail() -> String {
    // SAFETY: zshift_last_error returns a NUL-terminated string valid until the next call.
    unsafe { CStr::from_ptr(zshift_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// glFrustum(±0.1, ±0.05625, 0.1, 1000) as zshift builds it.
fn projection() -> [f32; 16] {
    let mut m = [0.0f32; 16];
    assert_eq!(
        zshift::ffi::zshift_frustum(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0, m.as_mut_ptr()),
        ZSHIFT_OK
    );
    m
}

fn valid_decal() -> ZshiftDecal {
    ZshiftDecal {
        viewport_width: 1280,
        viewport_height: 720,
        format: ZshiftFormat { value: 0x81A6 },
        subpixel_bits: 8,
        decal_near: 10.0,
        decal_far: 12.0,
        slope: 1.0,
        exact_depth: 0,
        base_reach: 0.0,
        profile: std::ptr::null(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        depth_func: ZshiftDepthTest { value: 0 },
        pipeline: ZshiftPipeline::zeroed(),
    }
}

/// Refused with every `needles` in the detail, output untouched.
fn refused(decal: &ZshiftDecal, needles: &[&str]) {
    let m = projection();
    let mut out = [7.0f32; 16];
    let status = zshift_decal_matrix(
        m.as_ptr(),
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        decal,
        out.as_mut_ptr(),
    );
    assert_ne!(status, ZSHIFT_OK, "{decal:?} was accepted");
    assert_eq!(out, [7.0f32; 16], "a refused call wrote its output");
    let d = detail();
    for needle in needles {
        assert!(d.contains(needle), "detail {d:?} lacks {needle:?}");
    }
}

#[test]
fn the_front_door_names_the_field_its_value_and_the_bound() {
    let m = projection();
    let mut out = [0.0f32; 16];
    assert_eq!(
        zshift_decal_matrix(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            &valid_decal(),
            out.as_mut_ptr()
        ),
        ZSHIFT_OK
    );
    let with = |f: &dyn Fn(&mut ZshiftDecal)| {
        let mut d = valid_decal();
        f(&mut d);
        d
    };
    refused(&with(&|d| d.viewport_width = 0), &["viewport_width = 0"]);
    refused(
        &with(&|d| d.format.value = 0x1234),
        &["format = 0x1234", "GL_DEPTH24_STENCIL8"],
    );
    refused(
        &with(&|d| d.format.value = 0x1902),
        &[
            "format = 0x1902",
            "unsized",
            "GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE",
        ],
    );
    refused(
        &with(&|d| d.subpixel_bits = 40),
        &["subpixel_bits = 40", "0..=32"],
    );
    // n as read back from the f32 matrix.
    refused(
        &with(&|d| d.decal_near = 0.0),
        &["decal_near = 0", "near plane n = 0.0999"],
    );
    refused(
        &with(&|d| d.decal_far = 2000.0),
        &["decal_far = 2000", "far plane f = 99"],
    );
    refused(
        &with(&|d| d.decal_far = 5.0),
        &["decal_far = 5", "decal_near = 10"],
    );
    refused(&with(&|d| d.slope = f64::NAN), &["slope = NaN"]);
    refused(&with(&|d| d.base_reach = -1.0), &["base_reach = -1"]);
    refused(
        &with(&|d| d.depth_func.value = 0x0207),
        &["depth_func = 0x0207"],
    );
    refused(
        &with(&|d| {
            d.pipeline.depth_range_near = 0.6;
            d.pipeline.depth_range_far = 0.5;
        }),
        &["depth_range_far = 0.5", "depth_range_near = 0.6"],
    );
    // glDepthRange(1, 0), reversed depth without glClipControl: the remedy is named.
    refused(
        &with(&|d| {
            d.pipeline.depth_range_near = 1.0;
            d.pipeline.depth_range_far = 0.0;
        }),
        &[
            "inverted glDepthRange",
            "glClipControl",
            "ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE",
        ],
    );
    // A depth range end outside [0, 1] is refused as such.
    refused(
        &with(&|d| {
            d.pipeline.depth_range_near = 0.0;
            d.pipeline.depth_range_far = 1.5;
        }),
        &["depth_range_far = 1.5"],
    );
    refused(
        &with(&|d| d.pipeline.world_reach = -2.0),
        &["world_reach = -2"],
    );
    let view = [1.0f32; 16];
    refused(
        &with(&|d| d.pipeline.view_matrix = view.as_ptr()),
        &["world_box"],
    );
    refused(
        &with(&|d| d.decal_corner_count = 4),
        &["decal_corner_count = 4", "NULL"],
    );
    // A decal whose nearest point lies within its own offset of the near plane (D16, eye-space
    // vertices, nothing clipped): the message blames neither a clipped base nor world-space
    // rounding, and says to pull the near plane in, not out.
    let at_near = with(&|d| {
        d.format.value = 0x81A5;
        d.decal_near = 0.100_000_1;
        d.decal_far = 0.2;
    });
    refused(
        &at_near,
        &[
            "nearest point lies within that offset",
            "pull the near plane in",
        ],
    );
    let m = projection();
    let mut out = [0.0f32; 16];
    zshift_decal_matrix(
        m.as_ptr(),
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        &at_near,
        out.as_mut_ptr(),
    );
    let said = detail();
    assert!(
        !said.contains("world-space") && !said.contains("move the near plane out"),
        "{said}"
    );
    // A decal under the camera, reaching behind it, is answered from the part on screen; so is
    // one running on beyond the far plane (1000 here): the part in front counts.
    let under: [f32; 12] = [
        -1.0, -1.7, 2.0, 1.0, -1.7, 2.0, 1.0, -1.7, -6.0, -1.0, -1.7, -6.0,
    ];
    let road: [f32; 12] = [
        -1.0, -1.7, -990.0, 1.0, -1.7, -990.0, 1.0, -1.7, -1010.0, -1.0, -1.7, -1010.0,
    ];
    let by_corners = |corners: &[f32; 12], world_reach: f64| {
        with(&|d| {
            d.decal_near = 0.0;
            d.decal_far = 0.0;
            d.slope = 0.0;
            d.decal_corners = corners.as_ptr();
            d.decal_corner_count = 4;
            d.pipeline.world_reach = world_reach;
        })
    };
    // Corners in a triangle strip's order (0, 1, 3, 2), as engines keep a quad: the same decal.
    let strip: [f32; 12] = [
        -1.0, -1.7, -9.0, 1.0, -1.7, -9.0, -1.0, -1.7, -11.0, 1.0, -1.7, -11.0,
    ];
    for corners in [&under, &road, &strip] {
        let status = zshift_decal_matrix(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            &by_corners(corners, 0.0),
            out.as_mut_ptr(),
        );
        assert_eq!(status, ZSHIFT_OK, "{}", detail());
    }
    // A decal the rasterizer clips (reaching behind the camera) whose clipping cannot be
    // bounded, world-space rounding far from the origin: the message is about the decal and
    // its corners, not a base the caller never described.
    refused(
        &by_corners(&under, 1e7),
        &["clipping of the decal", "decal_corners", "pass its corners"],
    );
    assert!(!detail().contains("base_reach"), "{}", detail());
}

#[test]
fn the_scene_record_names_the_field_its_value_and_the_bound() {
    let valid = ZshiftScene {
        l: -0.1,
        r: 0.1,
        b: -0.05625,
        t: 0.05625,
        n: 0.1,
        f: 1000.0,
        viewport_width: 1280,
        viewport_height: 720,
        depth_format: 0x81A6,
        decal_near: 10.0,
        decal_far: 12.0,
        slope: 1.0,
        exact_depth: 0,
        subpixel_bits: 8,
        depth_func: ZshiftDepthTest { value: 0 },
        base_reach: 0.0,
        profile: std::ptr::null(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        pipeline: ZshiftPipeline::zeroed(),
    };
    let refused = |s: ZshiftScene, needles: &[&str]| {
        let mut out = std::mem::MaybeUninit::<ZshiftRecommendation>::zeroed();
        assert_ne!(
            zshift_recommend(&s, out.as_mut_ptr()),
            ZSHIFT_OK,
            "{s:?} was accepted"
        );
        let d = detail();
        for needle in needles {
            assert!(d.contains(needle), "detail {d:?} lacks {needle:?}");
        }
    };
    refused(
        ZshiftScene {
            decal_near: 0.05,
            ..valid
        },
        &["decal_near = 0.05", "near plane n = 0.1"],
    );
    refused(
        ZshiftScene {
            decal_far: 1e4,
            ..valid
        },
        &["decal_far = 10000", "far plane f = 1000"],
    );
    refused(
        ZshiftScene {
            depth_format: 0x1234,
            ..valid
        },
        &["depth_format = 0x1234"],
    );
    refused(
        ZshiftScene {
            exact_depth: 1,
            ..valid
        },
        &["exact_depth", "slope"],
    );
}

/// A decal over several planes (`zshift_decal_matrix_planes`): the planes' largest offset,
/// refusals said of their plane (its field named as for one decal), of `count`, of NULL, with
/// the output untouched.
#[test]
fn a_decal_over_planes_names_the_plane_and_its_field() {
    use zshift::ffi::{zshift_decal_matrix_planes, zshift_recommend_for_planes};
    let m = projection();
    let near = valid_decal();
    let far = ZshiftDecal {
        decal_near: 40.0,
        decal_far: 45.0,
        slope: 3.0,
        ..valid_decal()
    };
    let one = |d: &ZshiftDecal| {
        let mut out = [0.0f32; 16];
        assert_eq!(
            zshift_decal_matrix(m.as_ptr(), ZSHIFT_CLIP_NEG_ONE_TO_ONE, d, out.as_mut_ptr()),
            ZSHIFT_OK
        );
        out
    };
    let (a, b) = (one(&near), one(&far));
    // NDC depth is −m10 + m14/d: an offset toward the camera raises element 10, the larger
    // offset is the larger element.
    let expected = if a[10] >= b[10] { a } else { b };
    assert_ne!(a[10], b[10]);
    let planes = [near, far];
    let mut out = [0.0f32; 16];
    assert_eq!(
        zshift_decal_matrix_planes(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            planes.as_ptr(),
            2,
            out.as_mut_ptr()
        ),
        ZSHIFT_OK
    );
    assert_eq!(out, expected);
    let mut rec = std::mem::MaybeUninit::<ZshiftRecommendation>::zeroed();
    assert_eq!(
        zshift_recommend_for_planes(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            planes.as_ptr(),
            2,
            rec.as_mut_ptr()
        ),
        ZSHIFT_OK
    );
    // SAFETY: written by the call that returned ZSHIFT_OK.
    let rec = unsafe { rec.assume_init() };
    assert!(rec.bleed_gap > 0.0 && rec.bleed_gap < 45.0, "{rec:?}");

    let refused_planes = |planes: *const ZshiftDecal, count: u32, needles: &[&str]| {
        let mut out = [7.0f32; 16];
        let status = zshift_decal_matrix_planes(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            planes,
            count,
            out.as_mut_ptr(),
        );
        assert_ne!(status, ZSHIFT_OK);
        assert_eq!(out, [7.0f32; 16], "a refused call wrote its output");
        let d = detail();
        for needle in needles {
            assert!(d.contains(needle), "detail {d:?} lacks {needle:?}");
        }
    };
    let broken = [
        near,
        ZshiftDecal {
            decal_far: 2000.0,
            ..near
        },
    ];
    refused_planes(broken.as_ptr(), 2, &["plane 1: ", "decal_far = 2000"]);
    refused_planes(planes.as_ptr(), 0, &["count = 0"]);
    refused_planes(std::ptr::null(), 2, &["decals"]);

    // A plane just beyond the near plane, and one whose clipped base asks an offset that
    // would move it past: each is answered alone, together the refusal names the plane that
    // set the offset and the remedy.
    let close = ZshiftDecal {
        decal_near: 0.125,
        decal_far: 0.13,
        slope: 0.0,
        ..near
    };
    // A terrain triangle under the decal but behind the camera: nothing of it is drawn.
    let behind: [f32; 9] = [-1.0, -1.7, 2.0, 1.0, -1.7, 2.0, 0.0, -1.7, 0.5];
    let nothing = ZshiftDecal {
        decal_near: 0.0,
        decal_far: 0.0,
        slope: 0.0,
        decal_corners: behind.as_ptr(),
        decal_corner_count: 3,
        ..near
    };
    let mut named = 0;
    for reach in [1e4, 1e5, 1e6, 1e7] {
        let clipped = ZshiftDecal {
            decal_near: 50.0,
            decal_far: 51.0,
            base_reach: reach,
            ..far
        };
        let mut out = [0.0f32; 16];
        let alone = zshift_decal_matrix(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            &clipped,
            out.as_mut_ptr(),
        );
        let pair = [close, clipped];
        let together = zshift_decal_matrix_planes(
            m.as_ptr(),
            ZSHIFT_CLIP_NEG_ONE_TO_ONE,
            pair.as_ptr(),
            2,
            out.as_mut_ptr(),
        );
        if alone == ZSHIFT_OK && together != ZSHIFT_OK {
            refused_planes(
                pair.as_ptr(),
                2,
                &["plane 0: ", "largest_plane = 1", "its own plane's matrix"],
            );
            // A piece of which nothing is drawn (a terrain triangle behind the camera, given
            // raw) is left out, and the planes keep the caller's numbers.
            let with_nothing = [close, nothing, clipped];
            refused_planes(
                with_nothing.as_ptr(),
                3,
                &["plane 0: ", "largest_plane = 2"],
            );
            named += 1;
        }
    }
    assert!(
        named > 0,
        "no base reach made the far plane's offset too large"
    );

    // Left out, a piece changes nothing; with nothing drawn at all, the call says so.
    let mut out = [0.0f32; 16];
    let three = [near, nothing, far];
    let status = zshift_decal_matrix_planes(
        m.as_ptr(),
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        three.as_ptr(),
        3,
        out.as_mut_ptr(),
    );
    assert_eq!(status, ZSHIFT_OK, "{}", detail());
    assert_eq!(out, expected);
    // So is a triangle wholly off screen at the side, within the depth range.
    let right: [f32; 9] = [100.0, -1.7, -10.0, 101.0, -1.7, -10.0, 100.0, -1.7, -11.0];
    let aside = ZshiftDecal {
        decal_corners: right.as_ptr(),
        ..nothing
    };
    let mut beside = [0.0f32; 16];
    let three = [near, aside, far];
    let status = zshift_decal_matrix_planes(
        m.as_ptr(),
        ZSHIFT_CLIP_NEG_ONE_TO_ONE,
        three.as_ptr(),
        3,
        beside.as_mut_ptr(),
    );
    assert_eq!(status, ZSHIFT_OK, "{}", detail());
    assert_eq!(beside, expected);
    refused_planes(
        [nothing, aside].as_ptr(),
        2,
        &["nothing of the decal is drawn"],
    );
}

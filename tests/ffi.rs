//! The C ABI contract, called the way C calls it: status codes, NULL pointers, untouched outputs
//! on error, unaligned outputs, messages for every status.

use std::ffi::CStr;

use zshift::ffi::*;

const SENTINEL: f64 = -12345.678;

#[test]
fn scalar_functions_return_ok_and_write_the_rust_result() {
    let mut out = SENTINEL;
    assert_eq!(zshift_epsilon(1.0, 100.0, 0.5, -10.0, &mut out), ZSHIFT_OK);
    assert_eq!(out, zshift::epsilon(1.0, 100.0, 0.5, -10.0).unwrap());
    assert_eq!(zshift_min_epsilon(1.0, 100.0, 24, &mut out), ZSHIFT_OK);
    assert_eq!(out, zshift::min_epsilon(1.0, 100.0, 24).unwrap());
    assert_eq!(
        zshift_min_delta_toward(1.0, 100.0, 24, -10.0, &mut out),
        ZSHIFT_OK
    );
    assert!(out > 0.0);
    assert_eq!(
        zshift_max_delta_away(1.0, 100.0, 24, -10.0, &mut out),
        ZSHIFT_OK
    );
    assert!(out < 0.0);
    assert_eq!(zshift_window_depth(1.0, 100.0, 100.0, &mut out), ZSHIFT_OK);
    assert_eq!(out, 1.0);
    assert_eq!(
        zshift_depth_resolution(1.0, 100.0, 16, 50.0, &mut out),
        ZSHIFT_OK
    );
    assert!(out > 0.0);
}

#[test]
fn errors_leave_the_output_untouched_and_name_the_class() {
    let cases: [(ZshiftStatus, ZshiftStatus); 9] = [
        (
            call(|o| zshift_epsilon(f64::NAN, 100.0, 0.5, -10.0, o)),
            ZSHIFT_ERR_NOT_FINITE,
        ),
        (
            call(|o| zshift_epsilon(1.0, f64::NEG_INFINITY, 0.5, -10.0, o)),
            ZSHIFT_ERR_NOT_FINITE,
        ),
        (
            call(|o| zshift_epsilon(-1.0, 100.0, 0.5, -10.0, o)),
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            call(|o| zshift_epsilon(1.0, 100.0, 10.0, -10.0, o)),
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            call(|o| zshift_min_epsilon(1.0, 100.0, 0, o)),
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            call(|o| zshift_min_delta_toward(1.0, 100.0, 24, -200.0, o)),
            ZSHIFT_ERR_DOMAIN,
        ),
        (
            call(|o| zshift_max_delta_away(1.0, 1e6, 16, -1e6, o)),
            ZSHIFT_ERR_UNRESOLVABLE,
        ),
        (
            call(|o| zshift_window_depth(1.0, 100.0, f64::INFINITY, o)),
            ZSHIFT_ERR_NOT_FINITE,
        ),
        (
            call(|o| zshift_depth_resolution(1.0, 100.0, 40, 5.0, o)),
            ZSHIFT_ERR_DOMAIN,
        ),
    ];
    for (i, (got, want)) in cases.into_iter().enumerate() {
        assert_eq!(got, want, "case {i}");
    }
}

/// Runs `f` on a sentinel-filled output and checks the output was not touched on error.
fn call(f: impl FnOnce(*mut f64) -> ZshiftStatus) -> ZshiftStatus {
    let mut out = SENTINEL;
    let status = f(&mut out);
    if status != ZSHIFT_OK {
        assert_eq!(out.to_bits(), SENTINEL.to_bits(), "output written on error");
    }
    status
}

#[test]
fn null_outputs_are_refused() {
    let null = std::ptr::null_mut();
    assert_eq!(
        zshift_epsilon(1.0, 100.0, 0.5, -10.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_min_epsilon(1.0, 100.0, 24, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_min_delta_toward(1.0, 100.0, 24, -10.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_max_delta_away(1.0, 100.0, 24, -10.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_window_depth(1.0, 100.0, 5.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_depth_resolution(1.0, 100.0, 24, 5.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    let null = std::ptr::null_mut();
    assert_eq!(
        zshift_frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
    assert_eq!(
        zshift_load_offset_matrix(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, 0.1, -5.0, null),
        ZSHIFT_ERR_NULL_POINTER
    );
}

#[test]
fn matrices_are_written_whole_or_not_at_all_even_unaligned() {
    // 16 floats at an odd byte offset: the ABI must not assume alignment.
    let mut bytes = [0xAAu8; 65];
    let out = bytes[1..].as_mut_ptr().cast::<f32>();
    let status = zshift_load_offset_matrix(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, 2.0, -2.0, out);
    assert_eq!(status, ZSHIFT_ERR_DOMAIN, "Pz + delta = 0 must be refused");
    assert!(bytes.iter().all(|&b| b == 0xAA), "output touched on error");

    let status = zshift_load_offset_matrix(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, 0.1, -5.0, out);
    assert_eq!(status, ZSHIFT_OK);
    let got: Vec<f32> = bytes[1..]
        .chunks(4)
        .map(|c| f32::from_ne_bytes(c.try_into().unwrap()))
        .collect();
    let want = zshift::load_offset_matrix(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, 0.1, -5.0).unwrap();
    assert_eq!(got, want.to_cols_array().to_vec());
    assert_eq!(bytes[0], 0xAA, "wrote before the buffer");

    let mut m = [7.0f32; 16];
    let status = zshift_frustum(-1.0, 1.0, -1.0, 1.0, 1.0, f64::NAN, m.as_mut_ptr());
    assert_eq!(status, ZSHIFT_ERR_NOT_FINITE);
    assert_eq!(m, [7.0; 16]);
    let status = zshift_frustum(-1.0, 1.0, -1.0, 1.0, 1.0, f64::INFINITY, m.as_mut_ptr());
    assert_eq!(status, ZSHIFT_OK);
    assert_eq!((m[10], m[14]), (-1.0, -2.0));
}

/// Input records are read field by field when aligned and as a block when not: both give the
/// same matrix, and the block read sees every field (a corner count with a NULL pointer is
/// refused from either).
#[test]
fn input_records_read_the_same_aligned_or_not() {
    let mut scene: ZshiftScene = unsafe { std::mem::zeroed() };
    (scene.l, scene.r, scene.b, scene.t, scene.n, scene.f) = (-0.1, 0.1, -0.075, 0.075, 0.1, 1e3);
    (scene.viewport_width, scene.viewport_height) = (1920, 1080);
    scene.depth_format = 0x81A6;
    (scene.decal_near, scene.decal_far, scene.slope) = (40.0, 60.0, 1.0);
    scene.subpixel_bits = 8;
    let mut engine = [0.0f32; 16];
    assert_eq!(
        zshift_frustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1e3, engine.as_mut_ptr()),
        ZSHIFT_OK
    );
    let mut decal: ZshiftDecal = unsafe { std::mem::zeroed() };
    (decal.viewport_width, decal.viewport_height) = (1920, 1080);
    decal.format = ZSHIFT_FORMAT_UNORM24;
    decal.subpixel_bits = 8;
    (decal.decal_near, decal.decal_far, decal.slope) = (40.0, 60.0, 1.0);

    // Each record copied to an odd byte offset.
    fn shifted<T>(record: &T, buffer: &mut Vec<u8>) -> *const T {
        let size = std::mem::size_of::<T>();
        buffer.resize(size + 1, 0);
        // SAFETY: `record` is `size` readable bytes; the buffer has room after its first byte.
        unsafe {
            std::ptr::copy_nonoverlapping(
                (record as *const T).cast::<u8>(),
                buffer[1..].as_mut_ptr(),
                size,
            )
        };
        buffer[1..].as_ptr().cast::<T>()
    }
    let (mut scene_bytes, mut decal_bytes) = (Vec::new(), Vec::new());
    let (mut aligned, mut unaligned) = ([0.0f32; 16], [1.0f32; 16]);
    assert_eq!(
        zshift_recommend_matrix(&scene, aligned.as_mut_ptr()),
        ZSHIFT_OK
    );
    let odd_scene = shifted(&scene, &mut scene_bytes);
    assert_eq!(
        zshift_recommend_matrix(odd_scene, unaligned.as_mut_ptr()),
        ZSHIFT_OK
    );
    assert_eq!(aligned, unaligned);
    let clip = ZSHIFT_CLIP_NEG_ONE_TO_ONE;
    assert_eq!(
        zshift_decal_matrix(engine.as_ptr(), clip, &decal, aligned.as_mut_ptr()),
        ZSHIFT_OK
    );
    let odd_decal = shifted(&decal, &mut decal_bytes);
    let status = zshift_decal_matrix(engine.as_ptr(), clip, odd_decal, unaligned.as_mut_ptr());
    assert_eq!(status, ZSHIFT_OK);
    assert_eq!(aligned, unaligned);

    // The last field reaches the reader both ways.
    scene.decal_corner_count = 4;
    decal.decal_corner_count = 4;
    for record in [
        &scene as *const ZshiftScene,
        shifted(&scene, &mut scene_bytes),
    ] {
        assert_eq!(
            zshift_recommend_matrix(record, aligned.as_mut_ptr()),
            ZSHIFT_ERR_DOMAIN
        );
    }
    for record in [
        &decal as *const ZshiftDecal,
        shifted(&decal, &mut decal_bytes),
    ] {
        let status = zshift_decal_matrix(engine.as_ptr(), clip, record, aligned.as_mut_ptr());
        assert_eq!(status, ZSHIFT_ERR_DOMAIN);
    }
}

#[test]
fn every_status_has_a_distinct_message_and_unknown_codes_are_safe() {
    let codes = [
        ZSHIFT_OK,
        ZSHIFT_ERR_NULL_POINTER,
        ZSHIFT_ERR_NOT_FINITE,
        ZSHIFT_ERR_DOMAIN,
        ZSHIFT_ERR_UNRESOLVABLE,
        ZSHIFT_ERR_OVERFLOW,
        ZSHIFT_ERR_INTERNAL,
        ZSHIFT_ERR_GL,
    ];
    let mut seen = std::collections::HashSet::new();
    for code in codes {
        let text = unsafe { CStr::from_ptr(zshift_status_message(code)) }
            .to_str()
            .unwrap();
        assert!(!text.is_empty());
        assert!(seen.insert(text), "two statuses share the message {text:?}");
    }
    for code in [-1, 8, i32::MAX, i32::MIN] {
        let text = unsafe { CStr::from_ptr(zshift_status_message(ZshiftStatus(code))) };
        assert_eq!(text.to_str().unwrap(), "unknown zshift status");
    }
    let version = unsafe { CStr::from_ptr(zshift_version()) }
        .to_str()
        .unwrap();
    assert_eq!(version, env!("CARGO_PKG_VERSION"));
}

/// `zshift_last_error`: the detail of the last failed call on this thread, naming the input and
/// its value; "" after a success; each thread has its own.
#[test]
fn last_error_names_the_input_and_is_per_thread() {
    fn last() -> String {
        // SAFETY: never NULL, NUL-terminated, valid until the next zshift call on this thread.
        unsafe { CStr::from_ptr(zshift_last_error()) }
            .to_str()
            .unwrap()
            .to_owned()
    }
    let mut m = [0.0f32; 16];
    assert_eq!(
        zshift_frustum(-1.0, 1.0, -1.0, 1.0, 0.0, 10.0, m.as_mut_ptr()),
        ZSHIFT_ERR_DOMAIN
    );
    assert_eq!(
        last(),
        "the near plane distance n must be greater than 0 (n = 0)"
    );
    let other = std::thread::spawn(|| {
        let mut x = 0.0;
        let before = last();
        let st = zshift_window_depth_clip(1.0, 10.0, ZshiftClip { value: 5 }, 2.0, &mut x);
        (before, st, last())
    })
    .join()
    .unwrap();
    assert_eq!(other.0, "", "a new thread starts with no error");
    assert_eq!(other.1, ZSHIFT_ERR_DOMAIN);
    assert!(other.2.ends_with("(clip = 5)"), "{}", other.2);
    assert!(
        last().ends_with("(n = 0)"),
        "another thread's error leaked here"
    );
    assert_eq!(
        zshift_frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, m.as_mut_ptr()),
        ZSHIFT_OK
    );
    assert_eq!(last(), "", "a success clears the detail");
}

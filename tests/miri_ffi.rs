//! The FFI layer's unsafe code (`src/ffi/`: unaligned scalar and struct stores, byte copies of
//! matrices and arrays, the unaligned read of a `ZshiftScene`, static C strings) exercised so
//! that Miri can check it: `scripts/miri` runs this file under `cargo +nightly miri test --test
//! miri_ffi`. It also runs in the ordinary `cargo test`.
//!
//! Miri reports any out-of-bounds, misaligned or uninitialised access as an error, so the
//! outputs here are allocations of exactly the size the header promises, at every alignment.

mod abi;

use abi::{call_checked, call_null, edge_inputs, entry, random_inputs, Inputs, Kind, CATALOGUE};
use zshift::ffi::{zshift_recommend, zshift_recommend_matrix, ZshiftRecommendation, ZshiftScene};

#[test]
fn every_function_writes_exactly_its_output_at_every_alignment() {
    for entry in CATALOGUE {
        let Kind::Writes {
            elem, len, call, ..
        } = entry.kind
        else {
            continue;
        };
        let bytes = elem.size() * len;
        for misalign in 0..8 {
            // Exactly `bytes` usable bytes after `misalign`: a write past them is a Miri error.
            let mut buf = vec![0u8; misalign + bytes];
            // SAFETY: `misalign + bytes` bytes are allocated.
            let status = unsafe { call(&Inputs::VALID, buf.as_mut_ptr().add(misalign)) };
            assert_eq!(status, 0, "{} failed on the valid inputs", entry.name);
            assert!(
                buf[misalign..].iter().any(|&b| b != 0),
                "{} wrote nothing",
                entry.name
            );
        }
    }
}

#[test]
fn every_function_checks_its_contract_on_edge_and_random_inputs() {
    // Miri interprets every call (about 0.2 s per input for all 29 functions): a third of the
    // edge inputs and a few random ones keep `scripts/miri` near two minutes.
    let (step, random) = if cfg!(miri) { (3, 20) } else { (1, 600) };
    let mut all = edge_inputs();
    all.extend(random_inputs(0x3141_5926, random));
    for (k, inputs) in all.iter().enumerate().step_by(step) {
        for entry in CATALOGUE {
            call_checked(entry, inputs, k);
            call_null(entry, inputs);
        }
    }
}

/// The scene is read (unaligned) before anything is written, so an output that overlaps the
/// scene gets the same answer as a separate one, and a misaligned scene reads correctly.
#[test]
fn a_scene_may_be_misaligned_and_overlap_the_output() {
    let scene = Inputs::VALID.scene;
    let size = std::mem::size_of::<ZshiftScene>();
    let expected = abi::call_checked(entry("zshift_recommend"), &Inputs::VALID, 0);
    let expected_matrix = abi::call_checked(entry("zshift_recommend_matrix"), &Inputs::VALID, 0);
    let (abi::Outcome::Status(0, want), abi::Outcome::Status(0, want_m)) =
        (expected, expected_matrix)
    else {
        panic!("the valid scene must be accepted")
    };
    let out_size = std::mem::size_of::<ZshiftRecommendation>();
    for misalign in 0..8 {
        for shift in [0usize, 1, 7, 8, 24] {
            // One buffer holding the scene at `misalign`, the output `shift` bytes later.
            let mut buf = vec![0u8; misalign + shift + size.max(out_size)];
            // SAFETY: the scene's bytes fit in `buf` at `misalign`; ZshiftScene is plain data.
            unsafe {
                buf.as_mut_ptr()
                    .add(misalign)
                    .cast::<ZshiftScene>()
                    .write_unaligned(scene)
            };
            let base = buf.as_mut_ptr();
            // SAFETY: scene and output lie inside `buf`; the header allows any alignment.
            let status = unsafe {
                zshift_recommend(base.add(misalign).cast(), base.add(misalign + shift).cast())
            };
            assert_eq!(status.0, 0);
            assert_eq!(
                &buf[misalign + shift..misalign + shift + out_size],
                &want[..]
            );

            let mut buf = vec![0u8; misalign + shift + size.max(64)];
            // SAFETY: as above.
            unsafe {
                buf.as_mut_ptr()
                    .add(misalign)
                    .cast::<ZshiftScene>()
                    .write_unaligned(scene)
            };
            let base = buf.as_mut_ptr();
            // SAFETY: as above; the matrix is 64 bytes.
            let status = unsafe {
                zshift_recommend_matrix(
                    base.add(misalign).cast(),
                    base.add(misalign + shift).cast(),
                )
            };
            assert_eq!(status.0, 0);
            assert_eq!(&buf[misalign + shift..misalign + shift + 64], &want_m[..]);
        }
    }
}

#[test]
fn a_null_scene_is_refused() {
    let mut out = [0f32; 16];
    assert_eq!(
        zshift_recommend_matrix(std::ptr::null(), out.as_mut_ptr()).0,
        1
    );
    let mut rec = std::mem::MaybeUninit::<ZshiftRecommendation>::uninit();
    assert_eq!(zshift_recommend(std::ptr::null(), rec.as_mut_ptr()).0, 1);
}

#[test]
fn the_strings_are_static_and_terminated() {
    for entry in CATALOGUE {
        if let Kind::Text(call) = entry.kind {
            for status in [-1, 0, 1, 2, 3, 4, 5, 6, 7, i32::MIN, i32::MAX] {
                let p = call(&Inputs {
                    status,
                    ..Inputs::VALID
                });
                // SAFETY: the header promises a static NUL-terminated string.
                let text = unsafe { std::ffi::CStr::from_ptr(p) };
                // zshift_last_error is "" when no call has failed on this thread.
                assert!(
                    !text.to_bytes().is_empty() || entry.name == "zshift_last_error",
                    "{}",
                    entry.name
                );
            }
        }
    }
}

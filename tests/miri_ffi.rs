//! The FFI layer's unsafe code (`src/ffi.rs`: unaligned scalar stores, byte copies of matrices,
//! static C strings) exercised so that Miri can check it: `scripts/miri` runs this file under
//! `cargo +nightly miri test --test miri_ffi`. It also runs in the ordinary `cargo test`.
//!
//! Miri reports any out-of-bounds, misaligned or uninitialised access as an error, so the
//! outputs here are allocations of exactly the size the header promises, at every alignment.

mod abi;

use abi::{call_checked, call_null, edge_inputs, random_inputs, Inputs, Kind, CATALOGUE};

#[test]
fn every_function_writes_exactly_its_output_at_every_alignment() {
    for entry in CATALOGUE {
        let Kind::Writes { elem, len, call } = entry.kind else {
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
fn every_function_checks_its_contract_on_the_edge_inputs() {
    let mut all = edge_inputs();
    all.extend(random_inputs(0x3141_5926, 100));
    for (k, inputs) in all.iter().enumerate() {
        for entry in CATALOGUE {
            call_checked(entry, inputs, k);
            call_null(entry, inputs);
        }
    }
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
                assert!(!text.to_bytes().is_empty(), "{}", entry.name);
            }
        }
    }
}

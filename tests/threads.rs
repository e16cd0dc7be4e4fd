//! Every exported function is reentrant and thread-safe: called from many threads at once, on
//! the same inputs in different orders, each gives bit-for-bit what it gives on one thread.
//!
//! The functions are listed once, in `tests/abi/mod.rs`; a new one is covered by adding it there.

mod abi;

use std::ffi::CStr;
use std::sync::{Arc, Barrier};

use abi::{call_checked, edge_inputs, random_inputs, Inputs, Outcome, CATALOGUE};

const THREADS: usize = 8;

/// Every (function, inputs) pair, with the inputs shared by all threads.
fn workload() -> Vec<Inputs> {
    let mut inputs = edge_inputs();
    inputs.extend(random_inputs(0x5eed_7a11, 400));
    inputs
}

/// What each function answers for each input, on this thread alone.
fn single_threaded(inputs: &[Inputs]) -> Vec<Vec<Outcome>> {
    CATALOGUE
        .iter()
        .map(|entry| inputs.iter().map(|i| call_checked(entry, i, 0)).collect())
        .collect()
}

#[test]
fn every_function_gives_the_same_answer_on_many_threads_at_once() {
    let inputs = Arc::new(workload());
    let expected = Arc::new(single_threaded(&inputs));
    let ok = expected
        .iter()
        .flatten()
        .filter(|o| matches!(o, Outcome::Status(0, _)))
        .count();
    assert!(
        ok > inputs.len(),
        "the workload must exercise the success paths, not only errors"
    );

    let start = Arc::new(Barrier::new(THREADS));
    let handles: Vec<_> = (0..THREADS)
        .map(|thread| {
            let (inputs, expected, start) = (inputs.clone(), expected.clone(), start.clone());
            std::thread::spawn(move || {
                start.wait(); // all threads enter the library together
                for round in 0..3 {
                    // Each thread walks the work in its own order and with its own output
                    // misalignment, so different functions overlap in time.
                    for step in 0..inputs.len() {
                        let k = (step * (2 * thread + 1) + round * 7) % inputs.len();
                        for (e, entry) in CATALOGUE.iter().enumerate() {
                            if entry.name == "zshift_last_error" {
                                continue; // depends on the thread's previous call: below
                            }
                            let got = call_checked(entry, &inputs[k], thread + round);
                            // This thread's last error is its own last call's: "" on success.
                            let detail =
                                unsafe { CStr::from_ptr(zshift::ffi::zshift_last_error()) };
                            if let Outcome::Status(status, _) = got {
                                assert_eq!(
                                    detail.to_bytes().is_empty(),
                                    status == 0,
                                    "{}: last error {detail:?} after status {status}",
                                    entry.name
                                );
                            }
                            assert_eq!(
                                got, expected[e][k],
                                "{} differs on thread {thread} for {:?}",
                                entry.name, inputs[k]
                            );
                        }
                    }
                }
            })
        })
        .collect();
    for h in handles {
        h.join().expect("a thread found a difference");
    }
}

#[test]
fn every_writing_function_refuses_a_null_output_on_any_thread() {
    let handles: Vec<_> = (0..THREADS)
        .map(|_| {
            std::thread::spawn(|| {
                for i in edge_inputs() {
                    for entry in CATALOGUE {
                        abi::call_null(entry, &i);
                    }
                }
            })
        })
        .collect();
    for h in handles {
        h.join().expect("a thread found a difference");
    }
}

/// The catalogue that every hardening test walks must list every function the header declares,
/// so a new exported function is hardened as soon as it is declared (or this test says so).
#[test]
fn the_catalogue_lists_every_function_in_the_header() {
    let header = include_str!("../include/zshift.h");
    let mut declared: Vec<&str> = header
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .zip(
            header
                .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .skip(1),
        )
        .filter(|(name, _)| name.starts_with("zshift_"))
        .map(|(name, _)| name)
        .collect();
    declared.retain(|name| {
        header.contains(&format!(" {name}(")) || header.contains(&format!("*{name}("))
    });
    declared.sort();
    declared.dedup();
    let mut listed: Vec<&str> = CATALOGUE.iter().map(|e| e.name).collect();
    listed.extend(abi::COVERED_ELSEWHERE);
    listed.sort();
    assert_eq!(
        declared, listed,
        "add the missing functions to tests/abi/mod.rs"
    );
}

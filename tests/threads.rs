//! Every exported function is reentrant and thread-safe: called from many threads at once, on
//! the same inputs in different orders, each gives bit-for-bit what it gives on one thread.
//!
//! The functions are listed once, in `tests/abi/mod.rs`; a new one is covered by adding it there.

mod abi;

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
                            let got = call_checked(entry, &inputs[k], thread + round);
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

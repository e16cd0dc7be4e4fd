//! Fuzzes every exported `zshift_*` function (the catalogue in `tests/abi/mod.rs`) with
//! arbitrary inputs. Run with `scripts/fuzz [seconds]`.
//!
//! Each input drives every function once, its output at an arbitrary misalignment inside a
//! sentinel-filled buffer, and once more with a NULL output. A failure is any crash or panic
//! (libfuzzer-sys aborts on a panic before zshift's own catch_unwind can hide it), a status
//! outside the header's codes, a NaN or infinity in an OK result, a byte written outside the
//! output or on an error, and the cross-checks below between functions.
//!
//! Purely random doubles almost never land in a frustum, so the fuzzer's bytes drive the
//! catalogue's generator (`abi::draw`): plausible values derived from the planes (a depth
//! inside [n, f], a shift a fraction of it), with some fields replaced by raw bits or edge
//! values (±0, subnormals, ±MAX, ±∞, NaN), which reaches both the success and the error paths.
#![no_main]

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

#[path = "../../tests/abi/mod.rs"]
mod abi;

use abi::{call_checked, call_null, Inputs, Kind, Outcome, Source, CATALOGUE};

/// The fuzzer's bytes as a stream of words (zeros once they run out).
struct Bytes<'a>(Unstructured<'a>);

impl Source for Bytes<'_> {
    fn next_u64(&mut self) -> u64 {
        self.0.arbitrary().unwrap_or(0)
    }
}

fuzz_target!(|data: &[u8]| {
    let mut src = Bytes(Unstructured::new(data));
    let inputs = abi::draw(&mut src);
    let misalign = src.below(8) as usize;
    let outcomes: Vec<Outcome> = CATALOGUE
        .iter()
        .map(|e| call_checked(e, &inputs, misalign))
        .collect();
    for e in CATALOGUE {
        call_null(e, &inputs);
    }
    cross_check(&inputs, &outcomes);
});

/// The OK result of the function named `name`, as f64s (f32s widened), if it succeeded.
fn result(outcomes: &[Outcome], name: &str) -> Option<Vec<f64>> {
    let k = CATALOGUE.iter().position(|e| e.name == name)?;
    let Kind::Writes { elem, .. } = CATALOGUE[k].kind else {
        return None;
    };
    outcomes[k].values(elem)
}

/// Asserts that two matrices agree bit for bit outside the listed elements.
fn same_but(a: &[f64], b: &[f64], except: &[usize], what: &str, i: &Inputs) {
    for k in (0..16).filter(|k| !except.contains(k)) {
        assert_eq!(
            a[k].to_bits(),
            b[k].to_bits(),
            "{what}: element {k} differs, {i:?}"
        );
    }
}

/// Relations between functions and signs that hold for every valid input (header docs).
fn cross_check(i: &Inputs, outcomes: &[Outcome]) {
    let get = |name| result(outcomes, name);
    if let Some(m) = get("zshift_load_offset_matrix") {
        let plain = get("zshift_frustum").expect("offset matrix OK but plain frustum failed");
        same_but(&m, &plain, &[10], "load_offset_matrix vs frustum", i);
        // delta > 0 (toward the camera) raises element 10, delta < 0 lowers it, never the reverse.
        assert!(
            i.delta <= 0.0 || m[10] >= plain[10],
            "offset went the wrong way, {i:?}"
        );
        assert!(
            i.delta >= 0.0 || m[10] <= plain[10],
            "offset went the wrong way, {i:?}"
        );
    }
    if let (Some(m), Some(plain)) = (get("zshift_offset_projection"), get("zshift_projection")) {
        same_but(&m, &plain, &[10, 14], "offset_projection vs projection", i);
    }
    if let (Some(m), Some(plain)) = (
        get("zshift_offset_tweaked_infinite"),
        get("zshift_tweaked_infinite"),
    ) {
        same_but(
            &m,
            &plain,
            &[10],
            "offset_tweaked_infinite vs tweaked_infinite",
            i,
        );
    }
    if let Some(e) = get("zshift_epsilon") {
        assert!(
            e[0] * i.delta <= 0.0,
            "epsilon must have the opposite sign of delta, {i:?}"
        );
    }
    for name in ["zshift_window_depth", "zshift_window_depth_clip"] {
        if let Some(w) = get(name) {
            assert!(
                (0.0..=1.0).contains(&w[0]),
                "{name} {} outside [0, 1], {i:?}",
                w[0]
            );
        }
    }
    for name in [
        "zshift_min_epsilon",
        "zshift_depth_step",
        "zshift_min_ndc_offset",
        "zshift_min_epsilon_clip",
    ] {
        if let Some(x) = get(name) {
            assert!(x[0] >= 0.0, "{name} {} negative, {i:?}", x[0]);
        }
    }
    if let Some(s) = get("zshift_depth_resolution") {
        assert!(
            s[0] >= 0.0 && s[0] <= i.d,
            "depth step {} outside [0, d], {i:?}",
            s[0]
        );
    }
    if let Some(t) = get("zshift_min_delta_toward") {
        assert!(
            t[0] >= 0.0 && t[0] <= -i.pz,
            "min delta toward {} outside [0, -pz], {i:?}",
            t[0]
        );
        // Seed 002's corrected eq. 4.1.9 is Walker's depth step at d = -pz, bit for bit.
        let mut step = f64::NAN;
        let status = zshift::ffi::zshift_depth_resolution(i.n, i.f, i.bits, -i.pz, &mut step);
        assert_eq!(
            status.0, 0,
            "depth step failed where min delta toward succeeded, {i:?}"
        );
        assert_eq!(
            step.to_bits(),
            t[0].to_bits(),
            "min delta toward != depth step, {i:?}"
        );
    }
    if let Some(a) = get("zshift_max_delta_away") {
        assert!(a[0] <= 0.0, "max delta away {} positive, {i:?}", a[0]);
    }
    if let Some(p) = get("zshift_tight_planes") {
        assert!(
            0.0 < p[0] && p[0] < p[1],
            "tight planes {p:?} not 0 < n < f, {i:?}"
        );
    }
}

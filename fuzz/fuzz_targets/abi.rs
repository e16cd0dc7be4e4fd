//! Fuzzes every exported `zshift_*` function (the catalogue in `tests/abi/mod.rs`) with
//! arbitrary inputs. Run with `scripts/fuzz [seconds]`.
//!
//! Each input drives every function once, its output at an arbitrary misalignment inside a
//! sentinel-filled buffer, and once more with a NULL output. A failure is any crash or panic
//! (libfuzzer-sys aborts on a panic before zshift's own catch_unwind can hide it), a status
//! outside the header's codes, a NaN or infinity in an OK result, a byte written outside the
//! output or on an error, and the cross-checks below between functions.
//!
//! Purely random doubles almost never land in a frustum, so each field is drawn either as raw
//! bits, as an edge value (±0, subnormals, ±MAX, ±∞, NaN), or as a plausible value derived from
//! the planes (a depth inside [n, f], a shift a fraction of it), which reaches the success paths.
#![no_main]

use arbitrary::{Result, Unstructured};
use libfuzzer_sys::fuzz_target;

#[path = "../../tests/abi/mod.rs"]
mod abi;

use abi::{call_checked, call_null, Inputs, Outcome, CATALOGUE, EDGES};

/// Raw bits, an edge value, or (half the time) the plausible value `plausible` makes.
fn pick(
    u: &mut Unstructured,
    plausible: impl FnOnce(&mut Unstructured) -> Result<f64>,
) -> Result<f64> {
    Ok(match u.int_in_range(0..=3u8)? {
        0 => f64::from_bits(u.arbitrary()?),
        1 => EDGES[u.choose_index(EDGES.len())?],
        _ => plausible(u)?,
    })
}

/// 10^e for e uniform-ish in [lo, hi].
fn decades(u: &mut Unstructured, lo: f64, hi: f64) -> Result<f64> {
    let t = u.arbitrary::<u16>()? as f64 / u16::MAX as f64;
    Ok(10f64.powf(lo + t * (hi - lo)))
}

/// A fraction in [0, 1], with both ends likely.
fn unit(u: &mut Unstructured) -> Result<f64> {
    Ok(match u.arbitrary::<u16>()? {
        0..=99 => 0.0,
        100..=199 => 1.0,
        x => x as f64 / u16::MAX as f64,
    })
}

fn inputs(u: &mut Unstructured) -> Result<Inputs> {
    let n = pick(u, |u| decades(u, -30.0, 30.0))?;
    let f = pick(u, |u| {
        Ok(match u.int_in_range(0..=7u8)? {
            0 => f64::INFINITY,
            1 => n * (1.0 + decades(u, -16.0, -1.0)?),
            _ => n * decades(u, 0.0, 12.0)?,
        })
    })?;
    let far = if f.is_finite() { f } else { n * 1e12 };
    let inside = |u: &mut Unstructured| Ok(n + unit(u)? * (far - n));
    let d = pick(u, inside)?;
    let pz = pick(u, |u| Ok(-inside(u)?))?;
    let delta = pick(u, |u| {
        Ok(match u.int_in_range(0..=3u8)? {
            // Just short of the eye: Pz + delta -> 0-, where epsilon and element 10 overflow.
            0 => pz.abs() * (1.0 - decades(u, -17.0, -1.0)?),
            1 => -pz.abs() * decades(u, -16.0, 3.0)?,
            _ => pz.abs() * decades(u, -16.0, 0.0)?,
        })
    })?;
    let half = |u: &mut Unstructured| Ok(n * decades(u, -3.0, 3.0)?);
    let (l, r, b, t) = (
        pick(u, |u| Ok(-half(u)?))?,
        pick(u, half)?,
        pick(u, |u| Ok(-half(u)?))?,
        pick(u, half)?,
    );
    let bits = if u.ratio(1, 8)? {
        u.arbitrary()?
    } else {
        u.int_in_range(1..=32)?
    };
    let status = if u.ratio(1, 2)? {
        u.int_in_range(-1..=7)?
    } else {
        u.arbitrary()?
    };
    Ok(Inputs {
        l,
        r,
        b,
        t,
        n,
        f,
        delta,
        pz,
        d,
        bits,
        status,
    })
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(inputs) = inputs(&mut u) else { return };
    let misalign = u.arbitrary::<u8>().unwrap_or(0) as usize;
    let outcomes: Vec<Outcome> = CATALOGUE
        .iter()
        .map(|e| call_checked(e, &inputs, misalign))
        .collect();
    for entry in CATALOGUE {
        call_null(entry, &inputs);
    }
    cross_check(&inputs, &outcomes);
});

/// The OK result of the function named `name`, as f64s (f32s widened), if it succeeded.
fn result(outcomes: &[Outcome], name: &str) -> Option<Vec<f64>> {
    let k = CATALOGUE.iter().position(|e| e.name == name)?;
    let abi::Kind::Writes { elem, .. } = CATALOGUE[k].kind else {
        return None;
    };
    match &outcomes[k] {
        Outcome::Status(0, bytes) => Some(
            bytes
                .chunks(elem.size())
                .map(|c| match elem {
                    abi::Elem::F32 => f32::from_ne_bytes(c.try_into().unwrap()) as f64,
                    abi::Elem::F64 => f64::from_ne_bytes(c.try_into().unwrap()),
                })
                .collect(),
        ),
        _ => None,
    }
}

/// Relations between functions and signs that hold for every valid input (header docs).
fn cross_check(i: &Inputs, outcomes: &[Outcome]) {
    let get = |name| result(outcomes, name);
    if let Some(m) = get("zshift_load_offset_matrix") {
        let plain = get("zshift_frustum").expect("offset matrix OK but plain frustum failed");
        for k in (0..16).filter(|&k| k != 10) {
            assert_eq!(
                m[k].to_bits(),
                plain[k].to_bits(),
                "element {k} differs from the plain matrix, {i:?}"
            );
        }
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
    if let Some(e) = get("zshift_epsilon") {
        assert!(
            e[0] * i.delta <= 0.0,
            "epsilon must have the opposite sign of delta, {i:?}"
        );
    }
    if let Some(w) = get("zshift_window_depth") {
        assert!(
            (0.0..=1.0).contains(&w[0]),
            "window depth {} outside [0, 1], {i:?}",
            w[0]
        );
    }
    if let Some(e) = get("zshift_min_epsilon") {
        assert!(e[0] > 0.0, "min epsilon {} not positive, {i:?}", e[0]);
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
}

//! The catalogue of every exported `zshift_*` function, shared by the hardening tests
//! (`tests/threads.rs`, `tests/miri_ffi.rs`) and the fuzz target (`fuzz/fuzz_targets/abi.rs`).
//!
//! Adding an exported function is one line in [`CATALOGUE`]: name its inputs (fields of
//! [`Inputs`]; add a field there if it needs a new one) and the shape of what it writes.
//! The checks ([`call_checked`]) are the same for every function: a bad status, a NaN or
//! infinity in an OK result, a write outside the output, or any write on an error fails.
#![allow(dead_code)] // each test file uses a different part of the catalogue

use std::ffi::{c_char, CStr};

use zshift::ffi;

/// The named inputs the exported functions take. Each function reads the fields it needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs {
    pub l: f64,
    pub r: f64,
    pub b: f64,
    pub t: f64,
    pub n: f64,
    pub f: f64,
    pub delta: f64,
    pub pz: f64,
    pub d: f64,
    pub bits: u32,
    pub status: i32,
}

impl Inputs {
    /// A valid call for every function: a symmetric frustum, n = 0.1, f = 1000, 24 bits,
    /// a point 50 units away shifted 0.01 toward the camera.
    pub const VALID: Inputs = Inputs {
        l: -0.1,
        r: 0.1,
        b: -0.075,
        t: 0.075,
        n: 0.1,
        f: 1000.0,
        delta: 0.01,
        pz: -50.0,
        d: 50.0,
        bits: 24,
        status: 0,
    };

    /// The number of f64 fields, for code that sets them by index.
    pub const F64_FIELDS: usize = 9;

    /// The f64 field number `i` (in declaration order).
    pub fn field_mut(&mut self, i: usize) -> &mut f64 {
        match i {
            0 => &mut self.l,
            1 => &mut self.r,
            2 => &mut self.b,
            3 => &mut self.t,
            4 => &mut self.n,
            5 => &mut self.f,
            6 => &mut self.delta,
            7 => &mut self.pz,
            _ => &mut self.d,
        }
    }
}

/// The element type of an output buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Elem {
    F32,
    F64,
}

impl Elem {
    pub fn size(self) -> usize {
        match self {
            Elem::F32 => 4,
            Elem::F64 => 8,
        }
    }
}

/// How a function answers.
#[derive(Clone, Copy)]
pub enum Kind {
    /// Returns a status and writes `len` elements through its last argument on success.
    Writes {
        elem: Elem,
        len: usize,
        call: unsafe fn(&Inputs, *mut u8) -> i32,
    },
    /// Returns a static NUL-terminated string, never NULL.
    Text(fn(&Inputs) -> *const c_char),
}

/// One exported function.
#[derive(Clone, Copy)]
pub struct Entry {
    pub name: &'static str,
    pub kind: Kind,
}

/// `writes!(zshift_fn(field, ...) -> [F32; 16])`: an entry for a function that takes the named
/// [`Inputs`] fields, then an output pointer to that many elements.
macro_rules! writes {
    ($name:ident($($arg:ident),*) -> [$elem:ident; $len:expr]) => {
        Entry {
            name: stringify!($name),
            kind: Kind::Writes {
                elem: Elem::$elem,
                len: $len,
                call: |i: &Inputs, out: *mut u8| ffi::$name($(i.$arg,)* out.cast()).0,
            },
        }
    };
}

/// `text!(zshift_fn(field, ...))`: an entry for a function that returns a static C string.
macro_rules! text {
    ($name:ident($($arg:ident),*)) => {
        Entry {
            name: stringify!($name),
            kind: Kind::Text(|_i: &Inputs| ffi::$name($(ffi::ZshiftStatus(_i.$arg)),*)),
        }
    };
}

/// Every exported function, one line each.
pub const CATALOGUE: &[Entry] = &[
    writes!(zshift_frustum(l, r, b, t, n, f) -> [F32; 16]),
    writes!(zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz) -> [F32; 16]),
    writes!(zshift_epsilon(n, f, delta, pz) -> [F64; 1]),
    writes!(zshift_min_epsilon(n, f, bits) -> [F64; 1]),
    writes!(zshift_min_delta_toward(n, f, bits, pz) -> [F64; 1]),
    writes!(zshift_max_delta_away(n, f, bits, pz) -> [F64; 1]),
    writes!(zshift_window_depth(n, f, d) -> [F64; 1]),
    writes!(zshift_depth_resolution(n, f, bits, d) -> [F64; 1]),
    text!(zshift_status_message(status)),
    text!(zshift_version()),
];

/// The byte every output buffer is filled with before a call; an error must leave it there.
pub const SENTINEL: u8 = 0xA5;
/// Bytes of guard before and after the output, which no call may touch.
pub const GUARD: usize = 8;
/// The largest status code the header defines.
pub const MAX_STATUS: i32 = 6;

/// What one checked call gave: the status and the bytes written (empty on error), or the text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    Status(i32, Vec<u8>),
    Text(Vec<u8>),
}

/// Calls `entry` with its output `misalign` bytes past an 8-aligned address (0..8), inside a
/// sentinel-filled buffer with guards, and checks the contract every function shares:
/// a defined status that is never ZSHIFT_ERR_INTERNAL; on OK, every element finite and
/// nothing written outside the output; on error, nothing written at all. Text functions must
/// return a non-NULL, NUL-terminated UTF-8 string. Panics (a test failure) on any breach.
pub fn call_checked(entry: &Entry, inputs: &Inputs, misalign: usize) -> Outcome {
    match entry.kind {
        Kind::Writes { elem, len, call } => {
            let bytes = elem.size() * len;
            // u64 storage makes the buffer 8-aligned, so `misalign` is the true misalignment.
            let mut storage = vec![0u64; (2 * GUARD + bytes + 8).div_ceil(8)];
            let buf: &mut [u8] = bytemuck_bytes(&mut storage);
            buf.fill(SENTINEL);
            let start = GUARD + misalign % 8;
            // SAFETY: `start + bytes` lies inside `buf`; the function writes at most `bytes`.
            let status = unsafe { call(inputs, buf.as_mut_ptr().add(start)) };
            check_status(entry.name, inputs, status, buf, start, bytes, elem)
        }
        Kind::Text(call) => Outcome::Text(check_text(entry.name, call(inputs))),
    }
}

/// Calls a writing `entry` with a NULL output: it must answer ZSHIFT_ERR_NULL_POINTER.
pub fn call_null(entry: &Entry, inputs: &Inputs) {
    if let Kind::Writes { call, .. } = entry.kind {
        // SAFETY: NULL is the documented "no output" case the function must refuse.
        let status = unsafe { call(inputs, std::ptr::null_mut()) };
        assert_eq!(status, 1, "{} with NULL output, {inputs:?}", entry.name);
    }
}

fn check_status(
    name: &str,
    inputs: &Inputs,
    status: i32,
    buf: &[u8],
    start: usize,
    bytes: usize,
    elem: Elem,
) -> Outcome {
    assert!(
        (0..=MAX_STATUS).contains(&status) && status != 6,
        "{name} returned status {status} for {inputs:?}"
    );
    let mut outside = buf[..start].iter().chain(&buf[start + bytes..]);
    assert!(
        outside.all(|&b| b == SENTINEL),
        "{name} wrote outside its output for {inputs:?}"
    );
    let out = &buf[start..start + bytes];
    if status != 0 {
        assert!(
            out.iter().all(|&b| b == SENTINEL),
            "{name} wrote its output on error {status} for {inputs:?}"
        );
        return Outcome::Status(status, Vec::new());
    }
    for (k, chunk) in out.chunks(elem.size()).enumerate() {
        let finite = match elem {
            Elem::F32 => f32::from_ne_bytes(chunk.try_into().unwrap()).is_finite(),
            Elem::F64 => f64::from_ne_bytes(chunk.try_into().unwrap()).is_finite(),
        };
        assert!(
            finite,
            "{name} returned OK with a non-finite element {k} for {inputs:?}"
        );
    }
    Outcome::Status(0, out.to_vec())
}

fn check_text(name: &str, p: *const c_char) -> Vec<u8> {
    assert!(!p.is_null(), "{name} returned NULL");
    // SAFETY: the header promises a static NUL-terminated string.
    let text = unsafe { CStr::from_ptr(p) };
    assert!(
        text.to_str().is_ok(),
        "{name} returned text that is not UTF-8"
    );
    assert!(
        !text.to_bytes().is_empty(),
        "{name} returned an empty string"
    );
    text.to_bytes().to_vec()
}

/// The bytes of a u64 slice (a stand-in for bytemuck, to keep dev-dependencies few).
fn bytemuck_bytes(words: &mut [u64]) -> &mut [u8] {
    // SAFETY: u8 has no alignment or validity requirements; the length covers the same memory.
    unsafe { std::slice::from_raw_parts_mut(words.as_mut_ptr().cast(), words.len() * 8) }
}

/// Values at the edges of every domain rule: zeros, signs, subnormals, the extremes, NaN.
pub const EDGES: [f64; 14] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    f64::MIN_POSITIVE,
    -f64::MIN_POSITIVE,
    5e-324,
    f64::MAX,
    -f64::MAX,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    1e300,
    -1e-300,
];

/// Depth-buffer bit counts at and around the valid range 1..=32.
pub const EDGE_BITS: [u32; 7] = [0, 1, 16, 24, 32, 33, u32::MAX];

/// A deterministic set of inputs: the valid call, then each f64 field of it replaced by each
/// edge value, each bit count, and each status code around the defined ones.
pub fn edge_inputs() -> Vec<Inputs> {
    let mut all = vec![Inputs::VALID];
    for field in 0..Inputs::F64_FIELDS {
        for &x in &EDGES {
            let mut i = Inputs::VALID;
            *i.field_mut(field) = x;
            all.push(i);
        }
    }
    for &bits in &EDGE_BITS {
        all.push(Inputs {
            bits,
            ..Inputs::VALID
        });
    }
    for status in [-1, 0, 1, 2, 3, 4, 5, 6, 7, i32::MIN, i32::MAX] {
        all.push(Inputs {
            status,
            ..Inputs::VALID
        });
    }
    all
}

/// A small xorshift generator, so the tests need no random-number crate and repeat exactly.
pub struct XorShift(pub u64);

impl XorShift {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Log-uniform in [lo, hi).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + self.unit() * (hi.ln() - lo.ln())).exp()
    }
}

/// `count` mostly valid inputs with planes, depths and shifts spread over many decades, one in
/// eight with a field replaced by an edge value.
pub fn random_inputs(seed: u64, count: usize) -> Vec<Inputs> {
    let mut rng = XorShift(seed | 1);
    (0..count)
        .map(|_| {
            let n = rng.log_uniform(1e-6, 1e3);
            let f = if rng.unit() < 0.1 {
                f64::INFINITY
            } else {
                n * rng.log_uniform(1.0001, 1e8)
            };
            let far = if f.is_finite() { f } else { n * 1e9 };
            let d = n + rng.unit() * (far - n);
            let w = n * rng.log_uniform(0.01, 10.0);
            let h = n * rng.log_uniform(0.01, 10.0);
            let cx = w * (rng.unit() - 0.5);
            let mut i = Inputs {
                l: cx - w,
                r: cx + w,
                b: -h,
                t: h,
                n,
                f,
                delta: d * rng.log_uniform(1e-9, 0.9) * if rng.unit() < 0.8 { 1.0 } else { -1.0 },
                pz: -d,
                d,
                bits: [16, 24, 32][(rng.next_u64() % 3) as usize],
                status: (rng.next_u64() % 9) as i32 - 1,
            };
            if rng.next_u64() % 8 == 0 {
                let field = (rng.next_u64() % Inputs::F64_FIELDS as u64) as usize;
                *i.field_mut(field) = EDGES[(rng.next_u64() % EDGES.len() as u64) as usize];
            }
            i
        })
        .collect()
}

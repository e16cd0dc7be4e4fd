//! The catalogue of every exported `zshift_*` function, shared by the hardening tests
//! (`tests/threads.rs`, `tests/miri_ffi.rs`) and the fuzz target (`fuzz/fuzz_targets/abi.rs`).
//!
//! Adding an exported function is one line in [`CATALOGUE`]: name its inputs (fields of
//! [`Inputs`]; add a field there, to [`Inputs::VALID`] and to [`plausible`] if it needs a new
//! one) and the shape of what it writes. The checks ([`call_checked`]) are the same for every
//! function: a bad status, a NaN or infinity in an OK result, a write outside the output, or any
//! write on an error fails.
#![allow(dead_code)] // each test file uses a different part of the catalogue

use std::ffi::{c_char, CStr};

use zshift::ffi::{
    self, ZshiftBiasApi, ZshiftClip, ZshiftDecal, ZshiftFormat, ZshiftOffsetKind,
    ZshiftRecommendation, ZshiftScene,
};

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
    pub fovy: f64,
    pub aspect: f64,
    pub tweak: f64,
    pub median: f64,
    pub bias: f64,
    pub nearest: f64,
    pub farthest: f64,
    pub lo: f64,
    pub hi: f64,
    pub steps: f64,
    pub bits: u32,
    pub status: i32,
    pub clip: ZshiftClip,
    pub format: ZshiftFormat,
    pub api: ZshiftBiasApi,
    pub kind: ZshiftOffsetKind,
    pub scene: ZshiftScene,
    /// The engine's own projection for the matrix-in entry points.
    pub matrix: Matrix,
    /// What the engine knows about a decal, for the matrix-in recommendation.
    pub decal: ZshiftDecal,
    /// An NDC offset toward the camera.
    pub ndc: f64,
}

/// A column-major float[16], passed by pointer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Matrix(pub [f32; 16]);

/// `glFrustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000)` as f32 (what VALID_SCENE describes).
const VALID_MATRIX: Matrix = Matrix([
    1.0,
    0.0,
    0.0,
    0.0,
    0.0,
    1.333_333_3,
    0.0,
    0.0,
    0.0,
    0.0,
    -1.000_2,
    -1.0,
    0.0,
    0.0,
    -0.200_02,
    0.0,
]);

// SAFETY: the only pointers in the inputs are the scenes' and decals' `profile` fields, NULL
// in every input (no shared data behind them), so sharing the inputs between threads is sound.
unsafe impl Send for Inputs {}
unsafe impl Sync for Inputs {}

const VALID_DECAL: ZshiftDecal = ZshiftDecal {
    pipeline: zshift::ffi::ZshiftPipeline::zeroed(),
    depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
    decal_corners: std::ptr::null(),
    decal_corner_count: 0,
    viewport_width: 1920,
    viewport_height: 1080,
    format: ZshiftFormat { value: 0x81A6 },
    subpixel_bits: 8,
    decal_near: 49.0,
    decal_far: 51.0,
    slope: 0.5,
    exact_depth: 0,
    base_reach: 0.0,
    profile: std::ptr::null(),
};

const VALID_SCENE: ZshiftScene = ZshiftScene {
    pipeline: zshift::ffi::ZshiftPipeline::zeroed(),
    decal_corners: std::ptr::null(),
    decal_corner_count: 0,
    l: -0.1,
    r: 0.1,
    b: -0.075,
    t: 0.075,
    n: 0.1,
    f: 1000.0,
    viewport_width: 1920,
    viewport_height: 1080,
    depth_format: 0x81A6,
    decal_near: 49.0,
    decal_far: 51.0,
    slope: 0.5,
    exact_depth: 0,
    subpixel_bits: 8,
    depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
    base_reach: 0.0,
    profile: std::ptr::null(),
};

impl Inputs {
    /// A valid call for every function: a frustum with n = 0.1, f = 1000, 24 bits, a point 50
    /// units away shifted 0.01 toward the camera, a 1920x1080 D24 decal scene.
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
        fovy: 60.0,
        aspect: 4.0 / 3.0,
        tweak: 1e-6,
        median: 10.0,
        bias: -2.0,
        nearest: 0.5,
        farthest: 800.0,
        lo: 10.0,
        hi: 100.0,
        steps: 1.0,
        bits: 24,
        status: 0,
        clip: ZshiftClip { value: 0 },
        format: ZshiftFormat { value: 0x81A6 }, // ZSHIFT_FORMAT_UNORM24 = GL_DEPTH_COMPONENT24
        api: ZshiftBiasApi { value: 0 },
        kind: ZshiftOffsetKind { value: 0 },
        scene: VALID_SCENE,
        matrix: VALID_MATRIX,
        decal: VALID_DECAL,
        ndc: 1e-5,
    };

    /// Every f64 input, the scene's included, for code that sets them by index.
    pub fn f64_fields(&mut self) -> Vec<&mut f64> {
        let s = &mut self.scene;
        vec![
            &mut self.l,
            &mut self.r,
            &mut self.b,
            &mut self.t,
            &mut self.n,
            &mut self.f,
            &mut self.delta,
            &mut self.pz,
            &mut self.d,
            &mut self.fovy,
            &mut self.aspect,
            &mut self.tweak,
            &mut self.median,
            &mut self.bias,
            &mut self.nearest,
            &mut self.farthest,
            &mut self.lo,
            &mut self.hi,
            &mut self.steps,
            &mut s.l,
            &mut s.r,
            &mut s.b,
            &mut s.t,
            &mut s.n,
            &mut s.f,
            &mut s.decal_near,
            &mut s.decal_far,
            &mut s.slope,
            &mut self.ndc,
            &mut self.decal.decal_near,
            &mut self.decal.decal_far,
            &mut self.decal.slope,
            &mut s.pipeline.depth_range_near,
            &mut s.pipeline.depth_range_far,
            &mut s.pipeline.world_reach,
            &mut self.decal.pipeline.depth_range_near,
            &mut self.decal.pipeline.world_reach,
        ]
    }

    /// Every integer input (as i32 views of u32 and i32 fields), for code that sets them.
    pub fn int_fields(&mut self) -> Vec<IntField<'_>> {
        let s = &mut self.scene;
        vec![
            IntField::U(&mut self.bits),
            IntField::I(&mut self.status),
            IntField::I(&mut self.clip.value),
            IntField::U(&mut self.format.value),
            IntField::I(&mut self.api.value),
            IntField::I(&mut self.kind.value),
            IntField::U(&mut s.viewport_width),
            IntField::U(&mut s.viewport_height),
            IntField::U(&mut s.depth_format),
            IntField::U(&mut s.exact_depth),
            IntField::I(&mut s.subpixel_bits),
            IntField::U(&mut s.pipeline.viewport_x),
            IntField::U(&mut s.pipeline.eye_first),
            IntField::U(&mut self.decal.depth_func.value),
            IntField::U(&mut self.decal.pipeline.viewport_y),
        ]
    }
}

/// A mutable integer input of either signedness.
pub enum IntField<'a> {
    U(&'a mut u32),
    I(&'a mut i32),
}

impl IntField<'_> {
    pub fn set(&mut self, bits: u32) {
        match self {
            IntField::U(x) => **x = bits,
            IntField::I(x) => **x = bits as i32,
        }
    }
}

/// How a field is passed: numbers by value, the scene by pointer.
pub trait Arg {
    type C;
    fn arg(&self) -> Self::C;
}

macro_rules! by_value {
    ($($t:ty),*) => { $(impl Arg for $t { type C = $t; fn arg(&self) -> $t { *self } })* };
}
by_value!(
    f64,
    u32,
    i32,
    ZshiftClip,
    ZshiftFormat,
    ZshiftBiasApi,
    ZshiftOffsetKind
);

impl Arg for Matrix {
    type C = *const f32;
    fn arg(&self) -> *const f32 {
        self.0.as_ptr()
    }
}

impl Arg for ZshiftDecal {
    type C = *const ZshiftDecal;
    fn arg(&self) -> *const ZshiftDecal {
        self
    }
}

impl Arg for ZshiftScene {
    type C = *const ZshiftScene;
    fn arg(&self) -> *const ZshiftScene {
        self
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
        /// Elements the header allows to be +INFINITY in an OK result.
        inf_ok: &'static [usize],
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
/// [`Inputs`] fields, then an output pointer to that many elements. `, +inf at [k, ..]` names
/// elements the header documents as possibly +INFINITY.
macro_rules! writes {
    ($name:ident($($arg:ident),*) -> [$elem:ident; $len:expr]) => {
        writes!($name($($arg),*) -> [$elem; $len], +inf at [])
    };
    ($name:ident($($arg:ident),*) -> [$elem:ident; $len:expr], +inf at [$($k:expr),*]) => {
        Entry {
            name: stringify!($name),
            kind: Kind::Writes {
                elem: Elem::$elem,
                len: $len,
                call: |i: &Inputs, out: *mut u8| ffi::$name($(i.$arg.arg(),)* out.cast()).0,
                inf_ok: &[$($k),*],
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

/// A ZshiftRecommendation is a struct of doubles, checked as such.
const RECOMMENDATION: usize = std::mem::size_of::<ZshiftRecommendation>() / 8;

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
    text!(zshift_last_error()),
    writes!(zshift_perspective(fovy, aspect, n, f) -> [F32; 16]),
    writes!(zshift_projection(l, r, b, t, n, f, clip) -> [F32; 16]),
    writes!(zshift_offset_projection(l, r, b, t, n, f, clip, delta, pz) -> [F32; 16]),
    writes!(zshift_offset_perspective(fovy, aspect, n, f, clip, delta, pz) -> [F32; 16]),
    writes!(zshift_tweaked_infinite(l, r, b, t, n, tweak) -> [F32; 16]),
    writes!(zshift_offset_tweaked_infinite(l, r, b, t, n, tweak, delta, pz) -> [F32; 16]),
    writes!(zshift_median_ndc_offset(median, delta, pz) -> [F64; 1]),
    writes!(zshift_window_depth_clip(n, f, clip, d) -> [F64; 1]),
    writes!(zshift_depth_step(n, f, clip, format, d) -> [F64; 1]),
    writes!(zshift_median_depth_step(median, format, d) -> [F64; 1]),
    writes!(zshift_min_ndc_offset(n, f, clip, format, d) -> [F64; 1]),
    writes!(zshift_min_epsilon_clip(n, f, clip, format, d) -> [F64; 1]),
    writes!(zshift_min_relative_epsilon(n, f, clip, format, d) -> [F64; 1]),
    writes!(zshift_bias_of_shift(n, f, clip, format, api, delta, pz) -> [F64; 1]),
    writes!(zshift_shift_of_bias(n, f, clip, format, api, bias, pz) -> [F64; 1]),
    writes!(zshift_tight_planes(nearest, farthest) -> [F64; 2], +inf at [1]), // f may be +∞
    writes!(zshift_range_offset(n, f, clip, format, kind, lo, hi, steps) -> [F64; 3]),
    writes!(zshift_recommend(scene) -> [F64; RECOMMENDATION]),
    writes!(zshift_recommend_matrix(scene) -> [F32; 16]),
    writes!(zshift_recommend_clip(scene, clip) -> [F64; RECOMMENDATION]),
    writes!(zshift_recommend_clip_matrix(scene, clip) -> [F32; 16]),
    writes!(zshift_offset_matrix(matrix, clip, delta, d) -> [F32; 16]),
    writes!(zshift_offset_matrix_ndc(matrix, clip, ndc) -> [F32; 16]),
    writes!(zshift_decal_matrix(matrix, clip, decal) -> [F32; 16]),
    writes!(zshift_recommend_for_matrix(matrix, clip, decal) -> [F64; RECOMMENDATION]),
    // One plane, the catalogue's decal: the same checks as zshift_decal_matrix's.
    Entry {
        name: "zshift_decal_matrix_planes",
        kind: Kind::Writes {
            elem: Elem::F32,
            len: 16,
            call: |i: &Inputs, out: *mut u8| {
                ffi::zshift_decal_matrix_planes(
                    i.matrix.arg(),
                    i.clip.arg(),
                    &i.decal,
                    1,
                    out.cast(),
                )
                .0
            },
            inf_ok: &[],
        },
    },
    Entry {
        name: "zshift_recommend_for_planes",
        kind: Kind::Writes {
            elem: Elem::F64,
            len: RECOMMENDATION,
            call: |i: &Inputs, out: *mut u8| {
                ffi::zshift_recommend_for_planes(
                    i.matrix.arg(),
                    i.clip.arg(),
                    &i.decal,
                    1,
                    out.cast(),
                )
                .0
            },
            inf_ok: &[],
        },
    },
    writes!(zshift_ortho(l, r, b, t, n, f, clip) -> [F32; 16]),
    writes!(zshift_offset_ortho(l, r, b, t, n, f, clip, delta) -> [F32; 16]),
    writes!(zshift_ortho_depth_step(n, f, clip, format, d) -> [F64; 1]),
    Entry {
        name: "zshift_clip_to_frustum",
        kind: Kind::Writes {
            elem: Elem::F64,
            len: 30,
            // A ground quad running behind the camera, cut to at most 10 vertices.
            call: |i: &Inputs, out: *mut u8| {
                let mut count = 0u32;
                let (p, n) = (GROUND_QUAD.as_ptr(), 4);
                ffi::zshift_clip_to_frustum(
                    i.l,
                    i.r,
                    i.b,
                    i.t,
                    i.n,
                    i.f,
                    p,
                    n,
                    out.cast(),
                    10,
                    &mut count,
                )
                .0
            },
            inf_ok: &[],
        },
    },
    Entry {
        name: "zshift_clip_to_frustum_stored",
        kind: Kind::Writes {
            elem: Elem::F64,
            len: 30,
            // The same quad, stored in world space within 10⁴ of the origin.
            call: |i: &Inputs, out: *mut u8| {
                let stored = ffi::ZshiftPipeline {
                    world_reach: 1e4,
                    eye_first: 1,
                    ..ffi::ZshiftPipeline::default()
                };
                let mut count = 0u32;
                let (p, n) = (GROUND_QUAD.as_ptr(), 4);
                ffi::zshift_clip_to_frustum_stored(
                    i.l,
                    i.r,
                    i.b,
                    i.t,
                    i.n,
                    i.f,
                    &stored,
                    p,
                    n,
                    out.cast(),
                    10,
                    &mut count,
                )
                .0
            },
            inf_ok: &[],
        },
    },
];

/// A ground quad z = -10 - y/2 running behind the camera, for the cuts (eye space, x y z).
const GROUND_QUAD: [f64; 12] = [
    -1e3, -1e3, 490.0, 1e3, -1e3, 490.0, 1e3, 1e3, -510.0, -1e3, 1e3, -510.0,
];

/// The entry named `name`.
pub fn entry(name: &str) -> &'static Entry {
    CATALOGUE
        .iter()
        .find(|e| e.name == name)
        .expect("no such exported function")
}

/// The byte every output buffer is filled with before a call; an error must leave it there.
pub const SENTINEL: u8 = 0xA5;
/// Bytes of guard before and after the output, which no call may touch.
pub const GUARD: usize = 8;
/// The largest status code the header defines (ZSHIFT_ERR_GL).
pub const MAX_STATUS: i32 = 7;

/// Exported functions the catalogue cannot call generically, each covered by its own test:
/// `zshift_probe` needs a current GL context, and the record `zshift_profile_worst_case`
/// writes holds NaN ("not measured") by design. `tests/gl_probe.rs` checks both: NULL pointers,
/// the output untouched on error, the last-error detail. The edge and shadow-bias calls write
/// records of mixed element types (floats and doubles, signed biases) that the generic byte
/// checks cannot read as one array: `tests/c/abi_test.c` (`test_edges`, `test_shadow_bias`)
/// checks their NULL pointers, untouched outputs and details (the sanitizer stage does not call them
/// yet). `zshift_steepest_face` and `zshift_edge_offset_for_mesh` read a mesh (strided positions,
/// indices) and write such records: `test_steepest_face` there.
pub const COVERED_ELSEWHERE: &[&str] = &[
    "zshift_probe",
    "zshift_profile_worst_case",
    "zshift_edge_offset",
    "zshift_edge_planes",
    "zshift_steepest_face",
    "zshift_edge_offset_for_mesh",
    "zshift_shadow_bias",
    "zshift_shadow_bias_receivers",
];

/// What one checked call gave: the status and the bytes written (empty on error), or the text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    Status(i32, Vec<u8>),
    Text(Vec<u8>),
}

impl Outcome {
    /// The OK result as f64s (f32s widened exactly), if the call succeeded.
    pub fn values(&self, elem: Elem) -> Option<Vec<f64>> {
        match self {
            Outcome::Status(0, bytes) => Some(
                bytes
                    .chunks(elem.size())
                    .map(|c| match elem {
                        Elem::F32 => f32::from_ne_bytes(c.try_into().unwrap()) as f64,
                        Elem::F64 => f64::from_ne_bytes(c.try_into().unwrap()),
                    })
                    .collect(),
            ),
            _ => None,
        }
    }
}

/// Calls `entry` with its output `misalign` bytes past an 8-aligned address (0..8), inside a
/// sentinel-filled buffer with guards, and checks the contract every function shares:
/// a defined status that is never ZSHIFT_ERR_INTERNAL; on OK, every element finite and
/// nothing written outside the output; on error, nothing written at all. Text functions must
/// return a non-NULL, NUL-terminated, non-empty UTF-8 string. Panics (a test failure) on any
/// breach.
pub fn call_checked(entry: &Entry, inputs: &Inputs, misalign: usize) -> Outcome {
    match entry.kind {
        Kind::Writes {
            elem,
            len,
            call,
            inf_ok,
        } => {
            let bytes = elem.size() * len;
            // u64 storage makes the buffer 8-aligned, so `misalign` is the true misalignment.
            let mut storage = vec![0u64; (2 * GUARD + bytes + 8).div_ceil(8)];
            let buf: &mut [u8] = as_bytes(&mut storage);
            buf.fill(SENTINEL);
            let start = GUARD + misalign % 8;
            // SAFETY: `start + bytes` lies inside `buf`; the function writes at most `bytes`.
            let status = unsafe { call(inputs, buf.as_mut_ptr().add(start)) };
            let shape = Shape {
                elem,
                bytes,
                inf_ok,
            };
            check_status(entry.name, inputs, status, buf, start, shape)
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

/// What a writing function's output looks like.
struct Shape {
    elem: Elem,
    bytes: usize,
    inf_ok: &'static [usize],
}

fn check_status(
    name: &str,
    inputs: &Inputs,
    status: i32,
    buf: &[u8],
    start: usize,
    shape: Shape,
) -> Outcome {
    let Shape {
        elem,
        bytes,
        inf_ok,
    } = shape;
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
    let outcome = Outcome::Status(0, out.to_vec());
    for (k, x) in outcome.values(elem).unwrap().iter().enumerate() {
        assert!(
            x.is_finite() || (*x == f64::INFINITY && inf_ok.contains(&k)),
            "{name} returned OK with a non-finite element {k} ({x}) for {inputs:?}"
        );
    }
    outcome
}

fn check_text(name: &str, p: *const c_char) -> Vec<u8> {
    assert!(!p.is_null(), "{name} returned NULL");
    // SAFETY: the header promises a static NUL-terminated string.
    let text = unsafe { CStr::from_ptr(p) };
    assert!(
        text.to_str().is_ok(),
        "{name} returned text that is not UTF-8"
    );
    // zshift_last_error is "" after a successful call; every other text is a fixed sentence.
    assert!(
        !text.to_bytes().is_empty() || name == "zshift_last_error",
        "{name} returned an empty string"
    );
    text.to_bytes().to_vec()
}

/// The bytes of a u64 slice (a stand-in for bytemuck, to keep dev-dependencies few).
fn as_bytes(words: &mut [u64]) -> &mut [u8] {
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

/// Integers at and around every enumeration and range (bits 1..=32, clip 0..=2, GL formats...).
pub const EDGE_INTS: [u32; 12] = [
    0,
    1,
    2,
    3,
    4,
    24,
    32,
    33,
    0x81A5,
    0x8CAC,
    u32::MAX, // -1 as i32 (ZSHIFT_SUBPIXEL_UNSNAPPED)
    i32::MIN as u32,
];

/// A deterministic set of inputs: the valid call, then each field of it (scalar or scene)
/// replaced by each edge value of its type.
pub fn edge_inputs() -> Vec<Inputs> {
    let mut all = vec![Inputs::VALID];
    let (floats, ints) = {
        let mut v = Inputs::VALID;
        (v.f64_fields().len(), v.int_fields().len())
    };
    for k in 0..floats {
        for &x in &EDGES {
            let mut i = Inputs::VALID;
            *i.f64_fields()[k] = x;
            all.push(i);
        }
    }
    for k in 0..ints {
        for &x in &EDGE_INTS {
            let mut i = Inputs::VALID;
            i.int_fields()[k].set(x);
            all.push(i);
        }
    }
    all
}

/// A stream of random words: the test's xorshift generator, or the fuzzer's bytes.
pub trait Source {
    fn next_u64(&mut self) -> u64;

    /// Uniform in [0, 1], with both ends drawn now and then.
    fn unit(&mut self) -> f64 {
        match self.next_u64() % 64 {
            0 => 0.0,
            1 => 1.0,
            _ => (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64,
        }
    }

    /// Uniform in 0..n.
    fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n.max(1)
    }

    /// True once in `n` draws.
    fn one_in(&mut self, n: u64) -> bool {
        self.below(n) == 0
    }

    /// Log-uniform in [lo, hi].
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + self.unit() * (hi.ln() - lo.ln())).exp()
    }
}

/// A small xorshift generator, so the tests need no random-number crate and repeat exactly.
pub struct XorShift(pub u64);

impl Source for XorShift {
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

/// Inputs that mostly satisfy every function's domain, over many decades: planes n in
/// [1e-12, 1e12] with f/n up to 1e10, barely above 1, or f = +∞; depths inside [n, f]; shifts
/// from 1e-16 of the depth to just short of the eye, either way; valid enumerations.
pub fn plausible(src: &mut impl Source) -> Inputs {
    let n = src.log_uniform(1e-12, 1e12);
    let f = match src.below(8) {
        0 => f64::INFINITY,
        1 => n * (1.0 + src.log_uniform(1e-15, 1e-2)),
        _ => n * src.log_uniform(1.0001, 1e10),
    };
    let far = if f.is_finite() { f } else { n * 1e12 };
    let d = n + src.unit() * (far - n);
    let pz = -(n + src.unit() * (far - n));
    let delta = match src.below(4) {
        // Just short of the eye: Pz + delta -> 0-, where epsilon and element 10 overflow.
        0 => -pz * (1.0 - src.log_uniform(1e-17, 1e-1)),
        1 => pz * src.log_uniform(1e-16, 1e3),
        _ => -pz * src.log_uniform(1e-16, 1.0),
    };
    let (a, b) = (n + src.unit() * (far - n), n + src.unit() * (far - n));
    let w = n * src.log_uniform(1e-3, 1e3);
    let h = n * src.log_uniform(1e-3, 1e3);
    let cx = w * (src.unit() - 0.5);
    let slope = if src.one_in(3) {
        0.0
    } else {
        src.log_uniform(1e-3, 10.0)
    };
    let mut i = Inputs {
        l: cx - w,
        r: cx + w,
        b: -h,
        t: h,
        n,
        f,
        delta,
        pz,
        d,
        fovy: 180.0 * src.unit(),
        aspect: src.log_uniform(1e-3, 1e3),
        tweak: if src.one_in(2) {
            src.unit()
        } else {
            2.4e-7 * src.log_uniform(1.0, 1e4)
        },
        median: src.log_uniform(1e-6, 1e6),
        bias: src.log_uniform(1e-3, 1e6) * if src.one_in(2) { -1.0 } else { 1.0 },
        nearest: n,
        farthest: n * src.log_uniform(1.0, 1e10),
        lo: a.min(b),
        hi: a.max(b),
        steps: if src.one_in(2) {
            1.0 + src.below(8) as f64
        } else {
            src.log_uniform(1.0, 1e3)
        },
        bits: 1 + src.below(32) as u32,
        status: src.below(9) as i32 - 1,
        clip: ZshiftClip {
            value: src.below(3) as i32,
        },
        format: ZshiftFormat {
            value: [0x81A5, 0x81A6, 0x81A7, 0x8CAC][src.below(4) as usize],
        },
        api: ZshiftBiasApi {
            value: src.below(3) as i32,
        },
        kind: ZshiftOffsetKind {
            value: src.below(2) as i32,
        },
        scene: VALID_SCENE,
        matrix: VALID_MATRIX,
        decal: VALID_DECAL,
        ndc: src.log_uniform(1e-9, 1e-1),
    };
    i.scene = ZshiftScene {
        pipeline: Default::default(),
        decal_corners: std::ptr::null(),
        decal_corner_count: 0,
        l: i.l,
        r: i.r,
        b: i.b,
        t: i.t,
        n,
        f,
        viewport_width: 1 + src.below(4096) as u32,
        viewport_height: 1 + src.below(4096) as u32,
        depth_format: [0x81A5, 0x81A6, 0x81A7, 0x8CAC][src.below(4) as usize],
        decal_near: a.min(b),
        decal_far: a.max(b),
        slope,
        exact_depth: (slope == 0.0 && src.one_in(2)) as u32,
        subpixel_bits: src.below(14) as i32 - 1,
        depth_func: zshift::ffi::ZshiftDepthTest { value: 0 },
        base_reach: 0.0,
        profile: std::ptr::null(),
    };
    i
}

/// [`plausible`] inputs with some fields made wild (raw bits or an edge value): none in a
/// quarter of the draws, about one field, one in eight, or half of them in the others.
pub fn draw(src: &mut impl Source) -> Inputs {
    let mut i = plausible(src);
    let one_in = [0, 32, 8, 2][src.below(4) as usize];
    if one_in == 0 {
        return i;
    }
    for x in i.f64_fields() {
        if src.one_in(one_in) {
            *x = if src.one_in(2) {
                f64::from_bits(src.next_u64())
            } else {
                EDGES[src.below(EDGES.len() as u64) as usize]
            };
        }
    }
    for mut x in i.int_fields() {
        if src.one_in(one_in) {
            x.set(if src.one_in(2) {
                src.next_u64() as u32
            } else {
                EDGE_INTS[src.below(EDGE_INTS.len() as u64) as usize]
            });
        }
    }
    i
}

/// `count` inputs drawn by [`draw`] from a seeded xorshift generator.
pub fn random_inputs(seed: u64, count: usize) -> Vec<Inputs> {
    let mut rng = XorShift(seed | 1);
    (0..count).map(|_| draw(&mut rng)).collect()
}

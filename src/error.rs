//! The one error type of the crate: what went wrong, and which input caused it.

use std::fmt;

/// The class of a failure. Each kind maps to one C status code in [`crate::ffi`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// An input is NaN, or an infinity where only a finite value (or `f = +∞`) is allowed.
    NotFinite,
    /// An input is finite but outside the function's domain (`n ≤ 0`, `f ≤ n`, `l = r`,
    /// `Pz` outside `[−f, −n]`, `Pz + δ ≥ 0`, depth bits outside `1..=32`, ...).
    Domain,
    /// The inputs are valid but the quantity asked for does not exist: for example no shift
    /// away from the camera can change the stored depth (`k·|Pz| ≥ 1` in eq. 4.1.10).
    Unresolvable,
    /// The inputs are valid but the result is too large for its type (f64, or f32 for matrices).
    Overflow,
    /// The caller's OpenGL context could not do what the probe ([`crate::probe`]) needs: an
    /// entry point the loader returned NULL for, a context older than 3.2, a depth format the
    /// framebuffer refuses, a GL error; the detail names it.
    Gl,
}

/// A failed computation: its [`ErrorKind`] and a sentence naming the offending input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Error {
    kind: ErrorKind,
    detail: &'static str,
}

impl Error {
    pub(crate) const fn new(kind: ErrorKind, detail: &'static str) -> Self {
        Self { kind, detail }
    }

    /// The class of failure.
    pub const fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// A sentence that names the input at fault and the rule it broke.
    pub const fn detail(&self) -> &'static str {
        self.detail
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.detail)
    }
}

impl std::error::Error for Error {}

/// `Result` with this crate's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

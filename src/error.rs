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

/// The value of the input an [`Error`] names, kept so the message can quote it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Value {
    /// A real number, by its bits (so `Error` stays `Eq` and `Hash`).
    Real(u64),
    /// An integer count or code.
    Integer(i64),
    /// A GL enum or other code best read in hexadecimal.
    Code(u32),
}

/// A failed computation: its [`ErrorKind`], a sentence naming the offending input and the rule
/// it broke, and (where known) the input's name and value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Error {
    kind: ErrorKind,
    detail: &'static str,
    input: Option<(&'static str, Value)>,
    /// The bound the input broke, by name and value (`n = 0.1`), where the check knew it.
    bound: Option<(&'static str, u64)>,
    /// Which of several like inputs the error is about (`plane 3` of a decal over several
    /// planes), said before the detail.
    item: Option<(&'static str, u32)>,
    /// A remedy that applies where the error arose (said after the detail and its input).
    note: Option<&'static str>,
}

impl Error {
    pub(crate) const fn new(kind: ErrorKind, detail: &'static str) -> Self {
        Self {
            kind,
            detail,
            input: None,
            bound: None,
            item: None,
            note: None,
        }
    }

    /// The error about item `index` of several (`name index: detail`), keeping the input it
    /// names.
    pub(crate) const fn for_item(mut self, name: &'static str, index: u32) -> Self {
        self.item = Some((name, index));
        self
    }

    /// This error with a remedy that applies where it arose, said last.
    pub(crate) const fn with_note(mut self, note: &'static str) -> Self {
        self.note = Some(note);
        self
    }

    /// This error, quoting the real input `name` (as the caller spells it; empty when the
    /// detail already names it) and its value.
    pub(crate) const fn with_value(mut self, name: &'static str, value: f64) -> Self {
        self.input = Some((name, Value::Real(value.to_bits())));
        self
    }

    /// This error, quoting the bound the input broke: `name` (as the caller knows it, e.g. `n`,
    /// the near plane) and its value.
    pub(crate) const fn with_bound(mut self, name: &'static str, value: f64) -> Self {
        self.bound = Some((name, value.to_bits()));
        self
    }

    /// This error, quoting the integer input `name` and its value.
    pub(crate) const fn with_integer(mut self, name: &'static str, value: i64) -> Self {
        self.input = Some((name, Value::Integer(value)));
        self
    }

    /// This error, quoting the input `name`, a code such as a GL enum, in hexadecimal.
    pub(crate) const fn with_code(mut self, name: &'static str, value: u32) -> Self {
        self.input = Some((name, Value::Code(value)));
        self
    }

    /// This error with the index of the item it is about, and an integer input named `name`,
    /// renumbered by `index` (a plane of a list the caller gave, from the list it was asked
    /// of with some left out).
    pub(crate) fn renumbered(mut self, name: &'static str, index: impl Fn(u32) -> u32) -> Self {
        if let Some((item, i)) = self.item {
            self.item = Some((item, index(i)));
        }
        if let Some((input, Value::Integer(i))) = self.input {
            if input == name {
                let renumbered = u32::try_from(i).map_or(i, |i| i64::from(index(i)));
                self.input = Some((input, Value::Integer(renumbered)));
            }
        }
        self
    }

    /// The class of failure.
    pub const fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// A sentence that names the input at fault and the rule it broke (without its value: the
    /// [`Display`](fmt::Display) form adds it, as in `"... (n = -1)"`).
    pub const fn detail(&self) -> &'static str {
        self.detail
    }

    /// Whether this is the refusal of a decal (or a mesh decal's piece) of which nothing is
    /// drawn: wholly behind the near plane, beyond the far plane or off screen
    /// ([`crate::matrix_in::decal_shape`]). Such a piece of a decal over several planes can be
    /// left out of [`crate::planes::recommend_planes`], as the C entry points
    /// `zshift_decal_matrix_planes` and `zshift_recommend_for_planes` leave it out themselves.
    pub fn draws_nothing(&self) -> bool {
        crate::footprint::draws_nothing(self)
    }

    /// The name of the input at fault and its value, where the check that failed knew them.
    pub fn input(&self) -> Option<(&'static str, f64)> {
        self.input.map(|(name, value)| {
            let x = match value {
                Value::Real(bits) => f64::from_bits(bits),
                Value::Integer(i) => i as f64,
                Value::Code(c) => f64::from(c),
            };
            (name, x)
        })
    }
}

impl fmt::Display for Error {
    /// The detail, then the input and its value: `the near plane distance n must be greater
    /// than 0 (n = -1)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some((name, index)) = self.item {
            write!(f, "{name} {index}: ")?;
        }
        f.write_str(self.detail)?;
        if let Some(input) = self.input {
            match input {
                ("", Value::Real(bits)) => write!(f, " (got {}", f64::from_bits(bits))?,
                (name, Value::Real(bits)) => write!(f, " ({name} = {}", f64::from_bits(bits))?,
                (name, Value::Integer(i)) => write!(f, " ({name} = {i}")?,
                (name, Value::Code(c)) => write!(f, " ({name} = 0x{c:04X}")?,
            }
            if let Some((name, bits)) = self.bound {
                write!(f, "; {name} = {}", f64::from_bits(bits))?;
            }
            f.write_str(")")?;
        }
        if let Some(note) = self.note {
            write!(f, "; {note}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Error {}

/// `Result` with this crate's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

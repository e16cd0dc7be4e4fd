//! The detail of the last failed call on this thread (libgit2's `git_error_last` style): which
//! input, its value and why, as a sentence. Set by the one checked entry pattern.

use std::cell::{Cell, RefCell};
use std::ffi::{c_char, CString};

thread_local! {
    /// The sentence `zshift_last_error` returns; empty after a successful call.
    static LAST: RefCell<CString> = RefCell::new(CString::default());
    /// Whether `LAST` holds a sentence: const-initialised, so the fast entry points read it
    /// with one thread-local load and touch `LAST` only after an error.
    static HOLDS: Cell<bool> = const { Cell::new(false) };
}

/// Records `detail` (an interior NUL, which no zshift message has, would end the C string
/// early: it is replaced).
pub(super) fn set(detail: &str) {
    let text = CString::new(detail.replace('\0', " ")).unwrap_or_default();
    LAST.with(|last| *last.borrow_mut() = text);
    HOLDS.with(|holds| holds.set(true));
}

/// Forgets the last error: the call succeeded.
#[inline]
pub(super) fn clear() {
    if HOLDS.with(Cell::get) {
        forget();
    }
}

#[cold]
fn forget() {
    LAST.with(|last| *last.borrow_mut() = CString::default());
    HOLDS.with(|holds| holds.set(false));
}

/// The message of a caught panic, if it carried one.
pub(super) fn panic_text(panic: &(dyn std::any::Any + Send)) -> &str {
    if let Some(s) = panic.downcast_ref::<&str>() {
        s
    } else if let Some(s) = panic.downcast_ref::<String>() {
        s
    } else {
        "no message"
    }
}

/// What went wrong in the last zshift call made on this thread that returned a status: a
/// NUL-terminated English sentence naming the input at fault, its value and the rule it broke,
/// such as "the near plane distance n must be greater than 0 (n = -1)". The empty string ""
/// when that call succeeded (or none has been made). Never NULL.
///
/// The string belongs to zshift and stays valid until the next zshift call on the same thread;
/// copy it to keep it. Each thread has its own. `zshift_status_message`, `zshift_version` and
/// this function leave it unchanged.
#[no_mangle]
pub extern "C" fn zshift_last_error() -> *const c_char {
    // The CString lives in the thread-local until the next call replaces it.
    LAST.with(|last| last.borrow().as_ptr())
}

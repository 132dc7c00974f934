//! rigor for the browser: one C-ABI call, with a few lines of JavaScript glue in
//! `web/src/worker.js` (no wasm-bindgen). The page writes a request (UTF-8 JSON, see
//! `rigor::render::web::respond`) into memory from [`rigor_alloc`], calls
//! [`rigor_check`], and reads the answer at [`rigor_answer_ptr`]. The clock for the
//! checker's time budget is imported from the page (`env.rigor_now_ms`, milliseconds
//! on a monotonic clock), since `wasm32-unknown-unknown` has none of its own.

use std::cell::RefCell;
use std::time::Duration;

#[link(wasm_import_module = "env")]
extern "C" {
    /// `performance.now()` of the worker.
    fn rigor_now_ms() -> f64;
}

fn clock() -> Duration {
    // SAFETY: an imported function with no arguments that returns a number.
    let ms = unsafe { rigor_now_ms() };
    Duration::from_secs_f64(if ms.is_finite() { ms.max(0.0) } else { 0.0 } / 1000.0)
}

thread_local! {
    /// The last answer, kept until the next call.
    static ANSWER: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// `len` bytes for the caller to write a request into (freed by [`rigor_check`]).
#[no_mangle]
pub extern "C" fn rigor_alloc(len: usize) -> *mut u8 {
    let mut v = Vec::<u8>::with_capacity(len.max(1));
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Checks the request of `len` bytes at `ptr` (from [`rigor_alloc`] with the same
/// `len`, freed here) and returns the length of the answer.
///
/// # Safety
/// `ptr` must come from `rigor_alloc(len)` and hold `len` initialised bytes.
#[no_mangle]
pub unsafe extern "C" fn rigor_check(ptr: *mut u8, len: usize) -> usize {
    // SAFETY: the caller passes a buffer from `rigor_alloc(len)` that it filled; the
    // vector takes it back (capacity as allocated) and frees it.
    let bytes = unsafe { Vec::from_raw_parts(ptr, len, len.max(1)) };
    let request = String::from_utf8_lossy(&bytes);
    let answer = rigor::render::web::respond(&request, Some(clock));
    ANSWER.with(|a| {
        *a.borrow_mut() = answer.into_bytes();
        a.borrow().len()
    })
}

/// Where the last answer starts (valid until the next [`rigor_check`]).
#[no_mangle]
pub extern "C" fn rigor_answer_ptr() -> *const u8 {
    ANSWER.with(|a| a.borrow().as_ptr())
}

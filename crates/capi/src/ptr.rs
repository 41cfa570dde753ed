//! The crate's only `unsafe`: C pointers to references, NULL checked.

use crate::SpStatus;

/// `&T` from a C pointer; [`SpStatus::NullPointer`] for NULL.
///
/// # Safety
/// A non-NULL `p` must point to a valid, aligned `T` that nothing writes during the call.
pub(crate) unsafe fn get<'a, T>(p: *const T) -> Result<&'a T, SpStatus> {
    // SAFETY: the caller's contract (the function's documented precondition).
    unsafe { p.as_ref() }.ok_or(SpStatus::NullPointer)
}

/// `&mut T` from a C pointer; [`SpStatus::NullPointer`] for NULL.
///
/// # Safety
/// A non-NULL `p` must point to a valid, aligned `T` that nothing else accesses during the
/// call.
pub(crate) unsafe fn get_mut<'a, T>(p: *mut T) -> Result<&'a mut T, SpStatus> {
    // SAFETY: the caller's contract (the function's documented precondition).
    unsafe { p.as_mut() }.ok_or(SpStatus::NullPointer)
}

/// `&[T]` of `n` elements from a C pointer; [`SpStatus::NullPointer`] for NULL (even with
/// `n == 0`).
///
/// # Safety
/// A non-NULL `p` must point to `n` valid, aligned, initialised `T` that nothing writes during
/// the call.
pub(crate) unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], SpStatus> {
    if p.is_null() {
        return Err(SpStatus::NullPointer);
    }
    // SAFETY: `p` is non-NULL, and the caller's contract gives `n` valid elements.
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

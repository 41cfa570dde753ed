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

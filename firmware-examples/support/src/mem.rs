//! Byte-at-a-time memory copy and fill for the ARM run-time ABI's `__aeabi_memcpy*`,
//! `__aeabi_memset*` and `__aeabi_memclr*` (what LLVM calls on ARM for every struct copy and
//! zeroing), replacing compiler-builtins' word-at-a-time versions: about 560 bytes of flash
//! become about 60. compiler-builtins defines these with weak linkage precisely so that a
//! program can replace them; `memmove` and the C names stay compiler-builtins' (these images
//! do not call them).
//!
//! Speed is not what the images need (the largest copy is one request of at most 941 bytes,
//! a few microseconds), flash is. Volatile accesses keep LLVM from recognising the loops as a
//! copy/fill idiom and compiling them into a call to themselves.

/// Copies `n` bytes from `src` to `dst`.
///
/// # Safety
///
/// `src` readable and `dst` writable for `n` bytes, not overlapping.
#[inline(never)]
unsafe fn copy(dst: *mut u8, src: *const u8, n: usize) {
    let mut i = 0;
    while i < n {
        // SAFETY: i < n, within both regions (the caller's contract).
        unsafe { dst.add(i).write_volatile(src.add(i).read_volatile()) };
        i += 1;
    }
}

/// Fills `n` bytes at `dst` with `c`.
///
/// # Safety
///
/// `dst` writable for `n` bytes.
#[inline(never)]
unsafe fn fill(dst: *mut u8, n: usize, c: u8) {
    let mut i = 0;
    while i < n {
        // SAFETY: i < n, within the region (the caller's contract).
        unsafe { dst.add(i).write_volatile(c) };
        i += 1;
    }
}

macro_rules! aeabi_copy {
    ($($name:ident),*) => {$(
        /// ARM run-time ABI copy (see the module docs).
        ///
        /// # Safety
        ///
        /// As C's `memcpy`: `src` readable and `dst` writable for `n` bytes, not overlapping.
        #[unsafe(no_mangle)]
        pub unsafe extern "aapcs" fn $name(dst: *mut u8, src: *const u8, n: usize) {
            // SAFETY: the caller's contract.
            unsafe { copy(dst, src, n) }
        }
    )*};
}

macro_rules! aeabi_fill {
    ($($name:ident),*) => {$(
        /// ARM run-time ABI fill (note the argument order: size, then value).
        ///
        /// # Safety
        ///
        /// As C's `memset`: `dst` writable for `n` bytes.
        #[unsafe(no_mangle)]
        pub unsafe extern "aapcs" fn $name(dst: *mut u8, n: usize, c: i32) {
            // SAFETY: the caller's contract.
            unsafe { fill(dst, n, c as u8) }
        }
    )*};
}

macro_rules! aeabi_clear {
    ($($name:ident),*) => {$(
        /// ARM run-time ABI zeroing.
        ///
        /// # Safety
        ///
        /// `dst` writable for `n` bytes.
        #[unsafe(no_mangle)]
        pub unsafe extern "aapcs" fn $name(dst: *mut u8, n: usize) {
            // SAFETY: the caller's contract.
            unsafe { fill(dst, n, 0) }
        }
    )*};
}

aeabi_copy!(__aeabi_memcpy, __aeabi_memcpy4, __aeabi_memcpy8);
aeabi_fill!(__aeabi_memset, __aeabi_memset4, __aeabi_memset8);
aeabi_clear!(__aeabi_memclr, __aeabi_memclr4, __aeabi_memclr8);

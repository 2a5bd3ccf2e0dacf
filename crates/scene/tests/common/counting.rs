//! A global allocator that reports every change in the bytes held to a counter of the test's
//! choosing (per thread or per process), for tests of peak memory. Included by path by the
//! test files that install it, so the other test binaries do not carry it.
use std::alloc::{GlobalAlloc, Layout, System};

/// The system allocator, calling `.0` with each change in bytes held.
pub struct Counting(pub fn(isize));

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            (self.0)(layout.size() as isize);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            (self.0)(layout.size() as isize);
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        (self.0)(-(layout.size() as isize));
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, size) };
        if !q.is_null() {
            // The difference only: large blocks grow and shrink in place (mremap).
            (self.0)(size as isize - layout.size() as isize);
        }
        q
    }
}

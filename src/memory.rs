//! Heap accounting for the studies and memory hints. [`CountingAlloc`] is a global allocator
//! that counts the bytes in use and their peak, so a run can report its own peak heap even
//! when several runs share one process (the process's peak RSS cannot be attributed to one
//! run): two relaxed atomics per allocation. The library never installs it; the `tribofe`
//! binary does (feature `count-alloc`, on by default), and a host program may. Without it the
//! counters read `None`.

use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

#[cfg(feature = "count-alloc")]
pub use counting::CountingAlloc;

#[cfg(feature = "count-alloc")]
mod counting {
    use super::{IN_USE, PEAK};
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::Ordering::Relaxed;

    /// The counting allocator (the system allocator underneath). Install it in a program with
    /// `#[global_allocator] static A: tribofe::memory::CountingAlloc = tribofe::memory::CountingAlloc;`
    pub struct CountingAlloc;

    /// Counts `bytes` more in use (when the allocation succeeded) and raises the peak.
    fn grow(p: *mut u8, bytes: usize) {
        if !p.is_null() {
            let now = IN_USE.fetch_add(bytes, Relaxed) + bytes;
            PEAK.fetch_max(now, Relaxed);
        }
    }

    // SAFETY: every call is forwarded to the system allocator unchanged; the counters only
    // observe sizes.
    unsafe impl GlobalAlloc for CountingAlloc {
        unsafe fn alloc(&self, l: Layout) -> *mut u8 {
            let p = System.alloc(l);
            grow(p, l.size());
            p
        }
        // Forwarded so that large zeroed blocks come from calloc's fresh zero pages: the default
        // writes the zeros itself, touching every page once more (20 ms per 74 MB array).
        unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
            let p = System.alloc_zeroed(l);
            grow(p, l.size());
            p
        }
        unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
            System.dealloc(p, l);
            IN_USE.fetch_sub(l.size(), Relaxed);
        }
        unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
            let q = System.realloc(p, l, new);
            if new >= l.size() {
                grow(q, new - l.size());
            } else if !q.is_null() {
                IN_USE.fetch_sub(l.size() - new, Relaxed);
            }
            q
        }
    }
}

/// Starts a new measurement: the peak becomes the heap in use now (after the frees started
/// by [`drop_in_background`], so an earlier run's memory is not counted in this one).
pub fn reset_peak() {
    wait_for_background_drops();
    PEAK.store(IN_USE.load(Relaxed), Relaxed);
}

/// Peak heap since the last [`reset_peak`], bytes; None unless [`CountingAlloc`] is the
/// program's allocator.
pub fn peak_bytes() -> Option<usize> {
    installed().then(|| PEAK.load(Relaxed))
}

/// Whether the counters see the allocations: any program has allocated by the time it asks.
fn installed() -> bool {
    PEAK.load(Relaxed) > 0
}

static PENDING: std::sync::Mutex<Vec<std::thread::JoinHandle<()>>> = std::sync::Mutex::new(Vec::new());

/// Blocks smaller than this are freed in place: a thread costs more than their munmap.
pub const BACKGROUND_DROP_BYTES: usize = 64 << 20;

/// Frees `x`, holding about `bytes` of heap, on a thread of its own when it is large.
/// Returning a large block to the OS (munmap) costs 0.1-0.2 s per GB on this VM, on one core,
/// time the caller spends on its next step instead (the 1e6-DOF strip's factor and pattern:
/// 0.13-0.22 s). Freed here when small or when no thread starts.
pub fn drop_in_background<T: Send + 'static>(x: T, bytes: usize) {
    if bytes < BACKGROUND_DROP_BYTES {
        return;
    }
    if let Ok(handle) = std::thread::Builder::new().name("tribofe-free".into()).spawn(move || drop(x)) {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        pending.retain(|h| !h.is_finished()); // dropping a finished handle releases its thread
        pending.push(handle);
    }
}

/// Waits until the memory given to [`drop_in_background`] is freed.
pub fn wait_for_background_drops() {
    let pending = std::mem::take(&mut *PENDING.lock().unwrap_or_else(|e| e.into_inner()));
    pending.into_iter().for_each(|h| {
        let _ = h.join();
    });
}

/// Heap in use now, bytes; None unless [`CountingAlloc`] is the program's allocator.
pub fn in_use_bytes() -> Option<usize> {
    installed().then(|| IN_USE.load(Relaxed))
}

/// Asks Linux to back the not yet touched pages of a large vector's buffer with transparent
/// huge pages (the system is in `madvise` mode): first-touch page faults cost ~60 ms per
/// 74 MB with 4 KiB pages, twice that when two threads fault concurrently, ~15 ms with 2 MiB
/// pages. Only a hint: contents and layout are unchanged; no-op below 8 MiB or elsewhere.
pub fn advise_huge_pages<T>(v: &Vec<T>) {
    let bytes = v.capacity() * std::mem::size_of::<T>();
    if bytes < 8 << 20 {
        return;
    }
    #[cfg(target_os = "linux")]
    {
        const PAGE: usize = 4096;
        let p = v.as_ptr() as usize;
        let (start, end) = ((p + PAGE - 1) & !(PAGE - 1), (p + bytes) & !(PAGE - 1));
        // SAFETY: [start, end) lies inside the vector's own allocation and is page aligned;
        // MADV_HUGEPAGE only changes how its pages are backed, never their contents, and a
        // failure (e.g. THP disabled) just leaves normal pages.
        unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
    }
}

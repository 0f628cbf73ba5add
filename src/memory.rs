//! Heap accounting for the studies: a global allocator that counts the bytes in use and their
//! peak, so a run can report its own peak heap even when several runs share one process
//! (the process's peak RSS cannot be attributed to one run). Two relaxed atomics per
//! allocation; nothing else changes.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

/// Counts `bytes` more in use (when the allocation succeeded) and raises the peak.
fn grow(p: *mut u8, bytes: usize) {
    if !p.is_null() {
        let now = IN_USE.fetch_add(bytes, Relaxed) + bytes;
        PEAK.fetch_max(now, Relaxed);
    }
}

unsafe impl GlobalAlloc for Counting {
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

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Starts a new measurement: the peak becomes the heap in use now (after the frees started
/// by [`drop_in_background`], so an earlier run's memory is not counted in this one).
pub fn reset_peak() {
    wait_for_background_drops();
    PEAK.store(IN_USE.load(Relaxed), Relaxed);
}

/// Peak heap since the last [`reset_peak`], bytes.
pub fn peak_bytes() -> usize {
    PEAK.load(Relaxed)
}

static PENDING: std::sync::Mutex<Vec<std::thread::JoinHandle<()>>> = std::sync::Mutex::new(Vec::new());

/// Frees `x` on a thread of its own. Returning a large block to the OS (munmap) costs
/// 0.1-0.2 s per GB on this VM, on one core, time the caller spends on its next step instead
/// (the 1e6-DOF strip's factor and pattern: 0.13-0.22 s). Freed here when no thread starts.
pub fn drop_in_background<T: Send + 'static>(x: T) {
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

/// Heap in use now, bytes.
pub fn in_use_bytes() -> usize {
    IN_USE.load(Relaxed)
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

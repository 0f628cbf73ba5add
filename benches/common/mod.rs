//! What the whole-process benchmarks share.

/// CPU time (user + sys) of this process (`RUSAGE_SELF`, every thread) or of its finished
/// children so far (`RUSAGE_CHILDREN`), s.
pub fn cpu(who: libc::c_int) -> f64 {
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: getrusage writes into the struct we own.
    unsafe { libc::getrusage(who, &mut u) };
    let tv = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    tv(u.ru_utime) + tv(u.ru_stime)
}

/// CPU time of the finished child processes so far, s.
pub fn children_cpu() -> f64 {
    cpu(libc::RUSAGE_CHILDREN)
}

//! Any bytes through the Gmsh reader: it must return Ok or Err, never panic, hang or
//! allocate without bound. Run: `cargo +nightly fuzz run parse fuzz/corpus/parse` (from the repo root).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = tribofe::io::gmsh::parse(data, Path::new("fuzz.msh"));
});

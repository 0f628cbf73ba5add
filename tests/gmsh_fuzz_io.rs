//! Robustness of the Gmsh reader without a fuzzer: many thousand mutations of the committed
//! meshes (truncations, byte flips, changed counts and numbers, spliced and repeated pieces)
//! go through `parse`, which must return, without panicking, within a time and memory bound,
//! and name the line or byte of what it rejects. Deterministic; more iterations with
//! `TRIBOFE_ROBUSTNESS_ITERS=1000000 cargo test --release --test gmsh_fuzz_io`.
//! A panicking input is saved under `target/tmp/` to become a regression test.
//! (The coverage-guided counterpart is `fuzz/fuzz_targets/parse.rs`.)

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tribofe::io::gmsh;
use tribofe::Error;

// The peak-memory assertions need the counting allocator.
#[global_allocator]
static ALLOCATOR: tribofe::memory::CountingAlloc = tribofe::memory::CountingAlloc;

// Heap accounting comes from the library's counting allocator (tribofe::memory). This file
// holds one test, so no other thread allocates meanwhile.

/// xorshift64*: small, deterministic, good enough to pick mutations.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const NUMBERS: [&str; 14] = [
    "0",
    "-1",
    "1",
    "2",
    "3",
    "15",
    "18446744073709551615",
    "9223372036854775808",
    "2147483648",
    "4294967296",
    "nan",
    "1e400",
    "-0",
    "99999999",
];
const PIECES: [&[u8]; 8] = [
    b"$Nodes\n",
    b"$EndNodes\n",
    b"$Elements\n",
    b"$EndElements\n",
    b"$Entities\n",
    b"\n",
    b"\"",
    b"$MeshFormat\n4.1 1 8\n",
];
const WORDS: [u64; 8] = [0, 1, 2, 3, u32::MAX as u64, i32::MAX as u64, u64::MAX, 1 << 40];

/// One random mutation of `seed` (several for some inputs).
fn mutate(rng: &mut Rng, seed: &[u8], other: &[u8]) -> Vec<u8> {
    let mut b = seed.to_vec();
    for _ in 0..1 + rng.below(3) {
        let n = b.len().max(1);
        let at = rng.below(n).min(b.len());
        match rng.below(9) {
            0 => b.truncate(at),
            1 => {
                if at < b.len() {
                    b[at] ^= 1 << rng.below(8);
                }
            }
            2 => {
                if at < b.len() {
                    b[at] = [0u8, 0xff, b'\n', b' ', b'$', b'-', b'9', b'"'][rng.below(8)];
                }
            }
            3 => {
                // Replace the number token nearest after `at` (counts, tags, types, coordinates).
                if let Some(s) = b[at..].iter().position(|c| c.is_ascii_digit()).map(|i| at + i) {
                    let e = b[s..]
                        .iter()
                        .position(|c| !(c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'-')))
                        .map_or(b.len(), |i| s + i);
                    b.splice(s..e, NUMBERS[rng.below(NUMBERS.len())].bytes());
                }
            }
            4 => {
                // Binary counts and tags: overwrite 4 or 8 bytes with an extreme value.
                let w = WORDS[rng.below(WORDS.len())].to_le_bytes();
                let len = if rng.below(2) == 0 { 4 } else { 8 };
                let len = len.min(b.len() - at);
                b[at..at + len].copy_from_slice(&w[..len]);
            }
            5 => {
                let end = (at + rng.below(64)).min(b.len());
                b.drain(at..end);
            }
            6 => {
                let end = (at + rng.below(256)).min(b.len());
                let piece = b[at..end].to_vec();
                let to = rng.below(b.len() + 1);
                b.splice(to..to, piece);
            }
            7 => {
                b.splice(at..at, PIECES[rng.below(PIECES.len())].iter().copied());
            }
            _ => {
                // Splice: this file's head with another file's tail.
                let from = rng.below(other.len().max(1)).min(other.len());
                b.truncate(at);
                b.extend_from_slice(&other[from..]);
            }
        }
    }
    b
}

fn seeds() -> Vec<(PathBuf, Vec<u8>)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths: Vec<PathBuf> =
        std::fs::read_dir(root.join("fuzz/corpus/parse")).unwrap().map(|e| e.unwrap().path()).collect();
    paths.extend(
        ["v41_ascii", "v41_bin", "v22_ascii", "v22_bin"]
            .map(|f| root.join(format!("meshes/block_regular_{f}.msh"))),
    );
    paths.sort();
    paths.into_iter().map(|p| (p.clone(), std::fs::read(&p).unwrap())).collect()
}

#[test]
fn mutated_meshes_never_panic() {
    let iters: usize =
        std::env::var("TRIBOFE_ROBUSTNESS_ITERS").ok().and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let seeds = seeds();
    assert!(seeds.len() >= 12);
    for (p, s) in &seeds {
        gmsh::parse(s, p).unwrap_or_else(|e| panic!("seed does not parse: {e}"));
    }
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut ok, mut slowest, mut worst_ratio) = (0usize, Duration::ZERO, 0.0f64);
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for i in 0..iters {
        // Mostly tiny seeds (fast); the 1203-node block one time in 16.
        let big = rng.below(16) == 0;
        let pool: Vec<&(PathBuf, Vec<u8>)> =
            seeds.iter().filter(|(_, s)| (s.len() > 20_000) == big).collect();
        let (seed_path, seed) = pool[rng.below(pool.len())];
        let other = &seeds[rng.below(seeds.len())].1;
        let input = mutate(&mut rng, seed, other);

        let base = tribofe::memory::in_use_bytes().unwrap();
        tribofe::memory::reset_peak();
        let t = Instant::now();
        let result = std::panic::catch_unwind(|| gmsh::parse(&input, Path::new("m.msh")));
        let dt = t.elapsed();
        let peak = tribofe::memory::peak_bytes().unwrap() - base;

        let Ok(result) = result else {
            std::panic::set_hook(quiet);
            let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
            let out = dir.join(format!("gmsh-crash-{i}.msh"));
            std::fs::write(&out, &input).unwrap();
            panic!(
                "parse panicked on mutation {i} of {}; input saved to {}",
                seed_path.display(),
                out.display()
            );
        };
        match result {
            Ok(m) => {
                ok += 1;
                assert!(m.n_elements() > 0 && m.validate().is_ok());
            }
            Err(Error::Parse { at, .. }) => {
                assert!(at.starts_with("line ") || at.starts_with("byte "), "{at}")
            }
            Err(Error::Mesh(msg)) => assert!(msg.starts_with("m.msh: "), "{msg}"),
            Err(e) => panic!("unexpected error kind on mutation {i}: {e}"),
        }
        slowest = slowest.max(dt);
        worst_ratio = worst_ratio.max(peak as f64 / input.len().max(1) as f64);
        assert!(
            peak < 200 * input.len() + (1 << 20),
            "mutation {i}: {peak} bytes allocated for a {}-byte input",
            input.len()
        );
    }
    std::panic::set_hook(quiet);
    eprintln!("{iters} mutated inputs: {ok} parsed, {} rejected, no panic; slowest {slowest:?}, peak heap {worst_ratio:.1} x input", iters - ok);
    assert!(slowest < Duration::from_secs(2), "a parse took {slowest:?}");
}

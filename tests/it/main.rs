//! The integration tests as one binary: each file of this folder is a module (run one with
//! `cargo test --release --test it MODULE::`). One crate to compile and link instead of one
//! per file: on the shared 2-core machine 41 s of compiler CPU instead of 56 s, and 80 MB of
//! test executables instead of 789 MB (issue 32). tests/gmsh_fuzz_io.rs stays a binary of its
//! own: it installs the counting global allocator and measures the heap of a process where no
//! other test allocates meanwhile.

#[path = "../common/mod.rs"]
mod common;

mod analytical;
mod assumption5;
mod bounds;
mod check;
mod cli_smoke;
mod contact_area;
mod convergence;
mod dynamics;
mod dynamics_defaults;
mod dynamics_velocity;
mod edges;
mod elements;
mod embed;
mod engine;
mod folder_safety;
mod fracture;
mod friction;
mod gmsh_io;
mod handoff;
mod inputs;
mod inputs_dynamic;
mod layering;
mod lean;
mod mesh_geometry;
mod observer;
mod operator;
mod out_of_plane;
mod paper_rule;
mod parallel;
mod precursors;
mod precursors_fe;
mod rate_state;
mod run_bounds;
mod rupture_scene;
mod side_push;
mod slide_fields;
mod stability;
mod sweep;
mod user_round;
mod writers_io;

//! Command lines shared by the process tests that run every subcommand (cli_smoke, user_round).
#![allow(dead_code)] // not every test binary that includes `common` runs these

/// A quick `edges` study (short block, one refinement, one t/L and h/L) into `ed`.
pub const EDGES_QUICK: &[&str] = &[
    "edges",
    "--length",
    "0.05",
    "--mu",
    "0.3",
    "--refine",
    "2",
    "--t-over-l",
    "0.04",
    "--h-over-l",
    "0.1",
    "--out",
    "ed",
];

/// A quick `precursors --fe --dc` scan (short block, one D_c) into `pd`.
pub const DC_QUICK: &[&str] = &[
    "precursors",
    "--fe",
    "--dc",
    "1e-6",
    "--length",
    "0.05",
    "--thickness",
    "0.004",
    "--h",
    "0.002",
    "--out",
    "pd",
];

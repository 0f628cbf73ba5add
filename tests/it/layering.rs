//! The library's layering (docs/layout.md) as a test: every `crate::X` a module of src/ uses in
//! code (comments and the `#[cfg(test)]` tail of a file left out) names a layer below its own.
//! An upward import, or a cycle, fails here with the file and the line.

use std::path::Path;

/// The layers, lowest first; a module may use only modules of a lower rank (and itself).
/// Ranks 0 and 1 sit beside everything: what uses nothing of the crate (the error enum, the
/// numeric helpers), then what uses only those (the cancel token, progress, the allocator
/// type, the laws, the paper's 1D model). `scene` sits
/// below `interface`: the interface is condensed from the scene's block and plate, and the
/// scene needs nothing of the interface.
const RANKS: &[(&str, u32)] = &[
    ("error", 0),
    ("numeric", 0),
    ("cancel", 1),
    ("progress", 1),
    ("memory", 1),
    ("law", 1),
    ("precursors", 1),
    ("linalg", 2),
    ("fem", 3),
    ("analytical", 4),
    ("io", 5),
    ("scene", 6),
    ("interface", 7),
    ("dynamics", 8),
    ("studies", 9),
    ("report", 10),
    ("api", 11),
];

fn rank(m: &str) -> Option<u32> {
    RANKS.iter().find(|r| r.0 == m).map(|r| r.1)
}

/// The top-level modules named after `crate::` in a code line, with `use crate::{a::.., b}`
/// lists read to their first segments.
fn uses(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + 7..];
        if let Some(list) = rest.strip_prefix('{') {
            let (mut depth, mut start) = (0, true);
            let mut word = String::new();
            for c in list.chars() {
                if start && depth == 0 && (c.is_alphanumeric() || c == '_') {
                    word.push(c);
                    continue;
                }
                if !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                    start = false;
                }
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => start = true,
                    c if c.is_whitespace() => {}
                    _ => start = false,
                }
            }
            if !word.is_empty() {
                out.push(word);
            }
        } else {
            let w: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            out.push(w);
        }
    }
    out
}

/// Code of a file with comments and the trailing `#[cfg(test)]` module removed, joined so
/// that a `use crate::{...}` spread over lines reads as one.
fn code_of(text: &str) -> Vec<(usize, String)> {
    let mut lines = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let t = l.trim_start();
        if t.starts_with("#[cfg(test)]") {
            break;
        }
        if t.starts_with("//") {
            continue;
        }
        let code = t.split(" //").next().unwrap_or("");
        lines.push((i + 1, code.to_string()));
    }
    // Join a statement's continuation lines onto its first line (for `use` lists).
    let mut joined: Vec<(usize, String)> = Vec::new();
    for (n, l) in lines {
        match joined.last_mut() {
            Some((_, prev)) if prev.starts_with("use ") && !prev.trim_end().ends_with(';') => {
                prev.push_str(&l)
            }
            _ => joined.push((n, l)),
        }
    }
    joined
}

fn walk(dir: &Path, files: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, files);
        } else if p.extension().is_some_and(|x| x == "rs") {
            files.push(p);
        }
    }
}

/// Every upward use in src/: (file, line, from, to).
fn upward(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    walk(src, &mut files);
    let mut bad = Vec::new();
    for f in files {
        let rel = f.strip_prefix(src).unwrap();
        let top = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        // The binary (cli/, main.rs) sits on top and lib.rs lists everything.
        if matches!(top.as_str(), "cli" | "main" | "lib") {
            continue;
        }
        let own =
            rank(&top).unwrap_or_else(|| panic!("{}: a top-level module missing from RANKS", rel.display()));
        for (n, code) in code_of(&std::fs::read_to_string(&f).unwrap()) {
            for m in uses(&code) {
                match rank(&m) {
                    Some(r) if m != top && r >= own => {
                        bad.push(format!("src/{}:{n}: {top} (rank {own}) uses {m} (rank {r})", rel.display()))
                    }
                    _ => {}
                }
            }
        }
    }
    bad
}

#[test]
fn no_module_of_src_imports_a_layer_above_its_own() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let bad = upward(&src);
    assert!(bad.is_empty(), "upward imports (see docs/layout.md):\n{}", bad.join("\n"));
}

#[test]
fn the_checker_sees_plain_and_listed_imports() {
    // A test that cannot fail is a defect: the reader must see both forms.
    assert_eq!(uses("use crate::scene::Scene;"), vec!["scene"]);
    assert_eq!(uses("use crate::{fem::{a, b}, report, Error};"), vec!["fem", "report", "Error"]);
    assert_eq!(uses("let x = crate::studies::check::run(s)?;"), vec!["studies"]);
    let code = code_of(
        "// crate::report\nuse crate::{\n    io,\n    report::x,\n};\n#[cfg(test)]\nuse crate::studies;\n",
    );
    assert_eq!(code.len(), 1);
    assert_eq!(uses(&code[0].1), vec!["io", "report"]);
}

/// The files of src/ whose code calls K u (`apply_k`): the one explicit integrator
/// (src/dynamics/explicit.rs and its unit tests, issue 46) and the dynamic slide's static
/// field (one product per event start, no time loop). A second central-difference loop needs
/// K u at every step, so it would show here.
fn k_u_callers(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    walk(src, &mut files);
    let mut out: Vec<String> = files
        .iter()
        .filter(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            code_of(&text).iter().any(|(_, l)| l.contains(".apply_k(") || l.contains(".apply_k_by_elements("))
        })
        .map(|f| f.strip_prefix(src).unwrap().to_string_lossy().replace('\\', "/"))
        .collect();
    out.sort();
    out
}

#[test]
fn every_dynamic_path_steps_through_the_one_integrator() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let callers = k_u_callers(&src);
    let allowed = ["dynamics/explicit.rs", "dynamics/explicit/tests.rs", "studies/dynamic_slide/setup.rs"];
    let extra: Vec<&String> = callers.iter().filter(|c| !allowed.contains(&c.as_str())).collect();
    assert!(
        extra.is_empty(),
        "K u is computed outside the one explicit integrator (a second time loop?): {extra:?}"
    );
    assert!(callers.iter().any(|c| c == "dynamics/explicit.rs"), "{callers:?}");
}

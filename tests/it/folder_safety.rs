//! Issue 45, user data lost: an output folder is tribofe's only by its run.toml's manifest
//! (every listed file there with its size and SHA-256), a rerun replaces only the listed
//! files, a user's file of an output's name is refused, `--write-scene` writes only a new
//! regular file (or with --force an existing one) once the run has finished, and `sweep
//! --merge` joins only verified shards of one sweep.

use std::path::Path;
use std::process::Command;

// The command runners and the refusal check are user_round's.
use super::user_round::{ok, refused, tribofe};

/// The cheapest check: a short block, coarse mesh, no converged run, no fields.
fn check_args(out: &str) -> Vec<&str> {
    vec!["check", "--length", "0.05", "--h", "0.001", "--no-converged", "--no-fields", "--out", out]
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A sweep shard of two points (as meshed, coarse) into `out`; `thick` the swept thicknesses.
fn shard_args<'a>(i: &'a str, thick: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "sweep",
        "--as-meshed",
        "--h",
        "0.001",
        "--length",
        "0.05",
        "--thickness",
        thick,
        "--shard",
        i,
        "--out",
        out,
    ]
}

#[test]
fn the_manifest_lists_every_file_with_size_and_hash() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &check_args("ck"));
    let t: toml::Table = read(&d.join("ck/run.toml")).parse().unwrap();
    let m = t["manifest"].as_table().unwrap();
    assert_eq!(m["algorithm"].as_str(), Some("sha256"));
    let files = m["files"].as_array().unwrap();
    let mut names: Vec<&str> = files.iter().map(|f| f["path"].as_str().unwrap()).collect();
    names.sort();
    let mut on_disk: Vec<String> = std::fs::read_dir(d.join("ck"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "run.toml")
        .collect();
    on_disk.sort();
    assert_eq!(names, on_disk);
    for f in files {
        let bytes = std::fs::read(d.join("ck").join(f["path"].as_str().unwrap())).unwrap();
        assert_eq!(f["size"].as_integer(), Some(bytes.len() as i64));
        assert_eq!(f["sha256"].as_str().unwrap(), tribofe::io::outdir::sha256_hex(&bytes));
    }
}

#[test]
fn a_users_file_and_subfolder_survive_a_rerun() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The first run writes a field file the second does not: it goes, as its record says.
    ok(d, &["check", "--length", "0.05", "--h", "0.001", "--no-converged", "--fields", "vtu", "--out", "ck"]);
    assert!(d.join("ck/fields_FN0.vtu").exists());
    std::fs::write(d.join("ck/notes.txt"), "my notes").unwrap();
    std::fs::create_dir(d.join("ck/mine")).unwrap();
    std::fs::write(d.join("ck/mine/data.csv"), "1,2\n").unwrap();
    ok(d, &check_args("ck"));
    assert_eq!(read(&d.join("ck/notes.txt")), "my notes");
    assert_eq!(read(&d.join("ck/mine/data.csv")), "1,2\n");
    assert!(!d.join("ck/fields_FN0.vtu").exists(), "a listed file the rerun does not write is removed");
    assert!(d.join("ck/summary.csv").exists());
    // The folder is still tribofe's (its own files match): a third run goes through too.
    ok(d, &check_args("ck"));
    assert_eq!(read(&d.join("ck/notes.txt")), "my notes");
}

#[test]
fn a_copied_run_file_or_shard_does_not_make_a_folder_tribofes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &check_args("ck"));
    // A user's folder with a run.toml copied from a real run (its listed files absent).
    std::fs::create_dir(d.join("proj")).unwrap();
    std::fs::write(d.join("proj/notes.txt"), "my notes").unwrap();
    std::fs::copy(d.join("ck/run.toml"), d.join("proj/run.toml")).unwrap();
    refused(d, &check_args("proj"), &["proj", "--force", "missing"]);
    assert_eq!(read(&d.join("proj/notes.txt")), "my notes");
    assert_eq!(read(&d.join("proj/run.toml")), read(&d.join("ck/run.toml")));
    // A run.toml without a manifest (an older tribofe's, or a hand-made marker).
    std::fs::write(d.join("proj/run.toml"), "# written by tribofe 0.1.0\n[tribofe]\n").unwrap();
    refused(d, &check_args("proj"), &["proj", "manifest", "--force"]);
    assert_eq!(read(&d.join("proj/notes.txt")), "my notes");
    // A shard's run file and table (a real shard's, copied) beside the user's notes.
    std::fs::remove_file(d.join("proj/run.toml")).unwrap();
    ok(d, &shard_args("1/2", "0.002,0.004", "sh"));
    for f in ["run_1of2.toml", "sweep_1of2.csv"] {
        std::fs::copy(d.join("sh").join(f), d.join("proj").join(f)).unwrap();
    }
    refused(d, &check_args("proj"), &["proj", "notes.txt", "--force"]);
    refused(d, &shard_args("2/2", "0.002,0.004", "proj"), &["proj", "notes.txt", "--force"]);
    assert_eq!(read(&d.join("proj/notes.txt")), "my notes");
    assert!(!d.join("proj/summary.csv").exists() && !d.join("proj/sweep_2of2.csv").exists());
    // A symbolic link as --out is refused; its target is untouched.
    std::os::unix::fs::symlink(d.join("ck"), d.join("link")).unwrap();
    let before = read(&d.join("ck/summary.csv"));
    refused(d, &check_args("link"), &["symbolic link"]);
    assert_eq!(read(&d.join("ck/summary.csv")), before);
}

#[test]
fn an_edited_listed_file_makes_the_folder_not_tribofes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &check_args("ck"));
    std::fs::write(d.join("ck/summary.csv"), "my edit\n").unwrap();
    refused(d, &check_args("ck"), &["summary.csv", "--force"]);
    assert_eq!(read(&d.join("ck/summary.csv")), "my edit\n");
    // A listed file replaced by a symbolic link is not the file tribofe wrote either.
    std::fs::remove_file(d.join("ck/summary.csv")).unwrap();
    std::os::unix::fs::symlink("/dev/null", d.join("ck/summary.csv")).unwrap();
    refused(d, &check_args("ck"), &["summary.csv", "symbolic link"]);
    assert!(std::fs::symlink_metadata(d.join("ck/summary.csv")).unwrap().file_type().is_symlink());
    // --force is the way past it; the link (not a regular file) is still never written over.
    let mut forced = check_args("ck");
    forced.push("--force");
    refused(d, &forced, &["summary.csv", "symbolic link"]);
    std::fs::remove_file(d.join("ck/summary.csv")).unwrap();
    std::fs::write(d.join("ck/summary.csv"), "my edit\n").unwrap();
    ok(d, &forced);
    assert_ne!(read(&d.join("ck/summary.csv")), "my edit\n", "--force replaced the edited file");
    ok(d, &check_args("ck"));
}

#[test]
fn a_users_file_named_like_an_output_is_refused_and_kept() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &check_args("ck"));
    let summary = read(&d.join("ck/summary.csv"));
    // The user's file has the name of a file the next run (with fields) writes.
    std::fs::write(d.join("ck/fields_FN0.vtu"), "mine").unwrap();
    let args =
        ["check", "--length", "0.05", "--h", "0.001", "--no-converged", "--fields", "vtu", "--out", "ck"];
    refused(d, &args, &["fields_FN0.vtu", "--force", "nothing was written"]);
    assert_eq!(read(&d.join("ck/fields_FN0.vtu")), "mine");
    assert_eq!(read(&d.join("ck/summary.csv")), summary, "the previous results stand");
    // A folder of that name is refused even with --force.
    std::fs::remove_file(d.join("ck/fields_FN0.vtu")).unwrap();
    std::fs::create_dir(d.join("ck/fields_FN0.vtu")).unwrap();
    let mut forced = args.to_vec();
    forced.push("--force");
    refused(d, &forced, &["fields_FN0.vtu", "folder"]);
    assert!(d.join("ck/fields_FN0.vtu").is_dir());
    // No temporary left beside or inside the folder.
    let hidden = |p: &Path| {
        std::fs::read_dir(p)
            .unwrap()
            .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().starts_with('.'))
            .count()
    };
    assert_eq!(hidden(d) + hidden(&d.join("ck")), 0);
}

#[test]
fn write_scene_writes_a_new_regular_file_only() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let with = |target: &str, out: &str| {
        let mut a = check_args(out);
        a.extend(["--write-scene", target]);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let run = |a: &[String]| tribofe(d, &a.iter().map(String::as_str).collect::<Vec<_>>());
    let code = |a: &[String]| {
        let o = run(a);
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    // A FIFO (opening it would block; renaming over it would replace it).
    assert!(Command::new("mkfifo").arg(d.join("fifo")).status().unwrap().success());
    // An existing file, a folder, links to a FIFO and to a file.
    std::fs::write(d.join("old.toml"), "mine").unwrap();
    std::fs::create_dir(d.join("folder")).unwrap();
    std::os::unix::fs::symlink(d.join("fifo"), d.join("to_fifo")).unwrap();
    std::os::unix::fs::symlink(d.join("old.toml"), d.join("to_old")).unwrap();
    for (target, word) in [
        ("fifo", "not a regular file"),
        ("old.toml", "exists"),
        ("folder", "folder"),
        ("to_fifo", "symbolic link"),
        ("to_old", "symbolic link"),
    ] {
        let (c, err) = code(&with(target, "o"));
        assert_eq!(c, Some(2), "{target}: {err}");
        assert!(err.contains("--write-scene") && err.contains(word), "{target}: {err}");
        assert!(!d.join("o").exists(), "{target}: refused before any work, nothing written");
    }
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(d.join("fifo")).unwrap().file_type().is_fifo());
    assert_eq!(read(&d.join("old.toml")), "mine");
    assert!(d.join("folder").is_dir() && std::fs::read_dir(d.join("folder")).unwrap().next().is_none());
    // /dev/null is refused, even with --force (as root a rename would make it a file).
    let mut a = with("/dev/null", "o");
    a.push("--force".into());
    let (c, err) = code(&a);
    assert!(c == Some(2) && err.contains("not a regular file"), "{err}");
    assert!(std::fs::metadata("/dev/null").unwrap().file_type().is_char_device());
    // A new file is written; an existing regular file is replaced with --force only.
    ok(d, &with("new.toml", "o").iter().map(String::as_str).collect::<Vec<_>>());
    assert!(read(&d.join("new.toml")).contains("[block]"));
    let mut a = with("old.toml", "o");
    a.push("--force".into());
    ok(d, &a.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(read(&d.join("old.toml")).contains("[block]"));
}

#[test]
fn a_refused_run_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(d, &["slide", "--write-scene", "my.toml", "--law", "nonsense", "--out", "o"], &["--law"]);
    refused(d, &["check", "--n-force", "-1", "--write-scene", "my.toml", "--out", "o"], &["--n-force"]);
    assert!(!d.join("my.toml").exists() && !d.join("o").exists());
    // Refused past the scene (the size limit): still nothing.
    refused(d, &["check", "--max-dofs", "100", "--write-scene", "my.toml", "--out", "o"], &["--max-dofs"]);
    assert!(!d.join("my.toml").exists() && !d.join("o").exists());
    let left: Vec<_> = std::fs::read_dir(d).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn sweep_merge_joins_only_verified_shards_of_one_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Two sweeps' shards: the same grid size, other thicknesses.
    ok(d, &shard_args("1/2", "0.002,0.004", "a"));
    ok(d, &shard_args("2/2", "0.002,0.004", "a"));
    ok(d, &shard_args("2/2", "0.002,0.006", "b"));
    let err = refused(
        d,
        &["sweep", "--merge", "a/sweep_1of2.csv", "b/sweep_2of2.csv", "--out", "m"],
        &["--merge", "different sweeps"],
    );
    assert!(err.contains("sweep_1of2.csv") && err.contains("sweep_2of2.csv"), "{err}");
    assert!(!d.join("m").exists());
    // A shard table edited after its run, or without its run file, is refused.
    std::fs::create_dir(d.join("g")).unwrap();
    std::fs::copy(d.join("a/sweep_1of2.csv"), d.join("g/sweep_1of2.csv")).unwrap();
    std::fs::write(d.join("g/sweep_2of2.csv"), read(&d.join("a/sweep_2of2.csv")) + "garbage\n").unwrap();
    std::fs::copy(d.join("a/run_2of2.toml"), d.join("g/run_2of2.toml")).unwrap();
    refused(d, &["sweep", "--merge", "g", "--out", "m"], &["--merge", "run file"]);
    assert!(!d.join("m").exists());
    // One sweep's shards join into a folder with a manifest; a user's sweep.csv is kept.
    ok(d, &["sweep", "--merge", "a", "--out", "a"]);
    let t: toml::Table = read(&d.join("a/run.toml")).parse().unwrap();
    assert_eq!(t["manifest"]["files"][0]["path"].as_str(), Some("sweep.csv"));
    assert!(d.join("a/sweep_1of2.csv").exists(), "the shards stay");
    std::fs::create_dir(d.join("mine")).unwrap();
    std::fs::write(d.join("mine/sweep.csv"), "my table\n").unwrap();
    refused(d, &["sweep", "--merge", "a", "--out", "mine"], &["sweep.csv", "--force"]);
    assert_eq!(read(&d.join("mine/sweep.csv")), "my table\n");
}

#[test]
fn a_file_past_the_size_limit_fails_cleanly() {
    use std::os::unix::process::CommandExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_tribofe"));
    cmd.current_dir(d).args(check_args("ck"));
    // SAFETY: setrlimit is async-signal-safe; the child only lowers its own file-size limit.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit { rlim_cur: 4096, rlim_max: 4096 };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let o = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    // SIGXFSZ is ignored: the write fails (EFBIG), status 4, the temporary folder removed.
    assert_eq!(o.status.code(), Some(4), "{:?}: {err}", o.status);
    let left: Vec<_> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `chattr` on `path` (`+a`, `-a`...); false where the file system or the process cannot.
fn chattr(flag: &str, path: &Path) -> bool {
    Command::new("chattr").arg(flag).arg(path).output().is_ok_and(|o| o.status.success())
}

/// Clears the attributes it set, whatever the test's outcome (else the tempdir stays).
struct Unlock(Vec<std::path::PathBuf>);

impl Drop for Unlock {
    fn drop(&mut self) {
        for p in &self.0 {
            chattr("-ia", p);
        }
    }
}

/// An append-only or immutable folder (`chattr +a`/`+i`, which stop root too): in an
/// append-only parent the run's hidden temporary `.<name>.tmp-<pid>` could be made but not
/// removed nor renamed into place, and stayed for good (exit 4, after the work); in a locked
/// `--out`, or with a locked file of the previous run, the commit stopped half-way. Each is
/// refused before any work, naming the folder or file and the attribute, and nothing is left.
#[test]
fn locked_folders_are_refused_before_work_and_leave_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let parent = d.join("p");
    std::fs::create_dir(&parent).unwrap();
    let mut unlock = Unlock(vec![]);
    if !chattr("+a", &parent) {
        eprintln!("skipped: chattr +a is not available here (file system or capability)");
        return;
    }
    unlock.0.push(parent.clone());
    let entries = |p: &Path| -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(p)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    for force in [false, true] {
        let mut args = check_args("p/o");
        if force {
            args.push("--force");
        }
        refused(d, &args, &["p", "append-only (chattr +a)", "temporary"]);
        assert!(entries(&parent).is_empty(), "left {:?}", entries(&parent));
    }
    chattr("-a", &parent);
    // A previous run's folder made append-only, then one of its files immutable.
    ok(d, &check_args("p/o"));
    let out = parent.join("o");
    let before: Vec<(String, String)> = entries(&out).into_iter().map(|n| (read(&out.join(&n)), n)).collect();
    for (flag, target, word) in
        [("+a", out.clone(), "append-only (chattr +a)"), ("+i", out.join("summary.csv"), "summary.csv")]
    {
        assert!(chattr(flag, &target));
        unlock.0.push(target.clone());
        for force in [false, true] {
            let mut args = check_args("p/o");
            args.extend(["--fn-ratios", "0.2"]);
            if force {
                args.push("--force");
            }
            refused(d, &args, &["p/o", word]);
            let now: Vec<(String, String)> =
                entries(&out).into_iter().map(|n| (read(&out.join(&n)), n)).collect();
            assert_eq!(now, before, "{flag} {}: the folder changed", target.display());
            assert_eq!(entries(&parent), vec!["o".to_string()], "a temporary was left");
        }
        chattr("-ia", &target);
    }
}

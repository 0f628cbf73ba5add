"""Self-test of validation/readme_numbers.py: it passes on the checkout, and fails, naming the
doc, the line and both values, when a number in a copy of README.md or docs/findings.md goes
stale or an unregistered number enters a checked table.

    python3 -m pytest -q validation/test_readme_numbers.py
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SCRIPT = os.path.join(HERE, "readme_numbers.py")


def copy_checkout(dst):
    """The two docs and the committed outputs they are checked against (validation/ without
    its big field files is enough: the script reads tables, logs and run.toml files)."""
    os.makedirs(os.path.join(dst, "docs"))
    shutil.copy(os.path.join(ROOT, "README.md"), dst)
    shutil.copytree(os.path.join(ROOT, "docs"), os.path.join(dst, "docs"), dirs_exist_ok=True)
    shutil.copytree(
        os.path.join(ROOT, "validation"),
        os.path.join(dst, "validation"),
        ignore=shutil.ignore_patterns("*.vtu", "*.msh", "*.svg", "*.png", "__pycache__"),
    )
    # Links from the docs to source files must still resolve in the copy.
    for name in ("src", "examples", "tests", "python", ".ci"):
        if os.path.exists(os.path.join(ROOT, name)) and not os.path.exists(os.path.join(dst, name)):
            os.symlink(os.path.join(ROOT, name), os.path.join(dst, name))
    return dst


def run(root):
    return subprocess.run([sys.executable, SCRIPT, "--root", root], capture_output=True, text=True)


def replace_once(path, old, new):
    with open(path) as f:
        text = f.read()
    assert text.count(old) == 1, f"{old!r} occurs {text.count(old)} times in {path}"
    with open(path, "w") as f:
        f.write(text.replace(old, new))
    return text[: text.index(old)].count("\n") + 1


def test_passes_on_the_checkout():
    r = run(ROOT)
    assert r.returncode == 0, r.stdout + r.stderr
    assert " numbers checked, 0 stale" in r.stdout


def test_a_stale_readme_number_fails(tmp_path):
    root = copy_checkout(str(tmp_path / "c"))
    # The README's normal force, as it was before this check: 85.438 against the committed 85.516.
    line = replace_once(os.path.join(root, "README.md"), "(N = 85.516 N/m", "(N = 85.438 N/m")
    r = run(root)
    assert r.returncode == 1
    assert f"README.md:{line}: stale number '85.438'" in r.stderr
    assert "85.5163" in r.stderr  # the committed value
    assert "1 stale" in r.stdout


def test_a_stale_findings_table_value_fails(tmp_path):
    root = copy_checkout(str(tmp_path / "c"))
    line = replace_once(os.path.join(root, "docs", "findings.md"), "| 14 (10); 2 |", "| 17 (10); 2 |")
    r = run(root)
    assert r.returncode == 1
    assert f"docs/findings.md:{line}: stale number '17'" in r.stderr


def test_an_unregistered_number_in_a_findings_table_fails(tmp_path):
    root = copy_checkout(str(tmp_path / "c"))
    line = replace_once(os.path.join(root, "README.md"), "| 1.8 % | `tribofe check`", "| 1.8 % (paper mesh: 0.96604) | `tribofe check`")
    r = run(root)
    assert r.returncode == 1
    assert f"README.md:{line}: number '0.96604' in a checked table is not registered" in r.stderr


def test_a_changed_committed_output_fails(tmp_path):
    root = copy_checkout(str(tmp_path / "c"))
    replace_once(os.path.join(root, "validation", "check", "run.toml"),
                 "n_force_n_per_m = 85.51633705056356\n\n[[results.cases]]\nf_force_n_per_m = 35",
                 "n_force_n_per_m = 85.6\n\n[[results.cases]]\nf_force_n_per_m = 35")
    r = run(root)
    assert r.returncode == 1
    assert "stale number '85.516'" in r.stderr


if __name__ == "__main__":  # without pytest
    import tempfile

    test_passes_on_the_checkout()
    for t in (test_a_stale_readme_number_fails, test_a_stale_findings_table_value_fails,
              test_an_unregistered_number_in_a_findings_table_fails, test_a_changed_committed_output_fails):
        with tempfile.TemporaryDirectory() as d:
            import pathlib

            t(pathlib.Path(d))
    print("ok")

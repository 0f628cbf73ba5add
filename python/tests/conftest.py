"""Shared fixtures: the `tribofe` command built from the same checkout (TRIBOFE_BIN, or the
release binary in cargo's target folder), to compare the package against it."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def tribofe_bin() -> Path:
    env = os.environ.get("TRIBOFE_BIN")
    if env:
        path = Path(env)
    else:
        meta = subprocess.run(
            ["cargo", "metadata", "--format-version", "1", "--no-deps"],
            cwd=ROOT, check=True, capture_output=True, text=True,
        )
        path = Path(json.loads(meta.stdout)["target_directory"]) / "release" / "tribofe"
    if not path.exists():
        pytest.fail(f"the tribofe command is not built at {path}: run `cargo build --release` first")
    return path


def run_cli(binary: Path, *args: str, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([str(binary), *args], capture_output=True, text=True, cwd=cwd, timeout=600)


def assert_interrupt_stops(tmp_path: Path, call: str, after: float) -> None:
    """Runs `call` (Python source) in a fresh interpreter in `tmp_path`, sends SIGINT `after`
    seconds into it (the clock starts once the import is done) and asserts that it ends with
    KeyboardInterrupt within a second (0.5 s more for the interpreter to exit), leaving no
    file."""
    script = textwrap.dedent(
        f"""
        import signal, time, tribofe
        # The interrupt key's Python handler even where the parent left SIGINT ignored.
        signal.signal(signal.SIGINT, signal.default_int_handler)
        print("ready", flush=True)
        t0 = time.monotonic()
        try:
            {call}
            print("finished", time.monotonic() - t0)
        except KeyboardInterrupt as e:
            print("interrupted", type(e).__name__, time.monotonic() - t0, flush=True)
        """
    )
    p = subprocess.Popen([sys.executable, "-c", script], cwd=tmp_path, stdout=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline().strip() == "ready"
        time.sleep(after)
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=30)
    finally:
        p.kill()  # never leave the run behind
    waited = time.monotonic() - sent
    assert out.startswith("interrupted"), out
    assert waited < 1.0 + 0.5, f"took {waited:.2f} s after SIGINT at {after} s (1 s asked, 0.5 s for the interpreter to exit)"
    assert list(tmp_path.iterdir()) == []

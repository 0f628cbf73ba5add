"""Shared fixtures: the `tribofe` command built from the same checkout (TRIBOFE_BIN, or the
release binary in cargo's target folder), to compare the package against it."""

import json
import os
import subprocess
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

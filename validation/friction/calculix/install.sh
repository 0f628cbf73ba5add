#!/usr/bin/env bash
# Install what the CalculiX friction cross-check needs (idempotent): ccx (Debian calculix-ccx),
# numpy and matplotlib.
set -euo pipefail
SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
if ! command -v ccx >/dev/null; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q calculix-ccx
fi
PY="${PYTHON:-python3}"
"$PY" -c 'import numpy, matplotlib' 2>/dev/null || "$PY" -m pip install -q numpy matplotlib
# ccx -v exits non-zero even when it works.
(ccx -v 2>&1 || true) | grep -m1 -i version

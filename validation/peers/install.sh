#!/usr/bin/env bash
# Install what the peer scripts need (idempotent; Debian 12 + Python 3 with pip).
#   apt: calculix-ccx (ccx 2.20), libsuitesparse-dev (CHOLMOD headers/libs for
#        scikit-sparse), time (GNU time for wall time and peak RSS)
#   pip: scikit-fem, numpy, scipy, matplotlib, scikit-sparse<0.5
# Tested with: scikit-fem 12.0.2, numpy 2.4.6, scipy 1.17.1, matplotlib 3.11.2,
#              scikit-sparse 0.4.16, CalculiX 2.20-1, libsuitesparse 5.12.0.
set -euo pipefail
SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
need=()
command -v ccx >/dev/null || need+=(calculix-ccx)
[ -x /usr/bin/time ] || need+=(time)
[ -e /usr/include/suitesparse/cholmod.h ] || need+=(libsuitesparse-dev)
if [ ${#need[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q "${need[@]}"
fi
PY="${PYTHON:-python3}"
"$PY" -m pip install -q 'scikit-fem>=10' numpy scipy matplotlib
# scikit-sparse 0.4.x builds against Debian 12's SuiteSparse 5; 0.5 needs newer.
"$PY" -c 'import sksparse.cholmod' 2>/dev/null || "$PY" -m pip install -q 'scikit-sparse<0.5'
"$PY" - <<'PYEOF'
import numpy, scipy, skfem, matplotlib, sksparse
print(f"numpy {numpy.__version__}, scipy {scipy.__version__}, scikit-fem {skfem.__version__}, "
      f"matplotlib {matplotlib.__version__}, scikit-sparse {sksparse.__version__}")
PYEOF
# ccx -v exits with 201 even when it works.
(ccx -v 2>&1 || true) | grep -m1 -i version

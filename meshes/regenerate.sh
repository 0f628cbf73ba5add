#!/usr/bin/env bash
# Regenerates every committed .msh from its .geo: MSH 4.1 and 2.2, ASCII and binary.
# Needs gmsh (Debian: apt-get install -y gmsh; the committed files come from gmsh 4.8.4).
# Usage: meshes/regenerate.sh [OUT_DIR]   (default: next to the .geo files)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-}"
for geo in "$here"/*.geo "$here"/tiny/*.geo; do
  base="$(basename "$geo" .geo)"
  dir="${out:-$(dirname "$geo")}"
  mkdir -p "$dir"
  for v in 41 22; do
    gmsh "$geo" -2 -format "msh$v" -o "$dir/${base}_v${v}_ascii.msh" > /dev/null
    gmsh "$geo" -2 -format "msh$v" -bin -o "$dir/${base}_v${v}_bin.msh" > /dev/null
  done
done

#!/usr/bin/env bash
# Builds the talus tool (Release, build/) and runs the main demo job.
# Usage: bash scripts/demo.sh [OUTPUT_DIR]     (default: talus-out/ in the repo root)
set -euo pipefail

if [[ $# -gt 1 ]] || [[ "${1:-}" == -h || "${1:-}" == --help ]]; then
  echo "usage: $0 [OUTPUT_DIR]" >&2
  exit 2
fi

repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# A relative OUTPUT_DIR is taken relative to the caller's directory.
if [[ $# -eq 1 ]]; then
  out_dir=$1
  [[ "$out_dir" == /* ]] || out_dir="$PWD/$out_dir"
else
  out_dir="$repo_root/talus-out"
fi

cd "$repo_root"
bash scripts/setup.sh

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
# The executable build/experiments/talus comes from target talus_cli (the
# name `talus` belongs to the umbrella library target).
cmake --build build -j"$(nproc)" --target talus_cli

talus=build/experiments/talus
if [[ ! -x "$talus" ]]; then
  echo "demo.sh: $talus was not built." >&2
  exit 1
fi

mkdir -p "$out_dir"
"$talus" terrain fit data/terrain/west_bijou_escarpment_nasadem25m.asc --smoothing 1
"$talus" experiment terrain-gallery --out "$out_dir"

echo
echo "Figures are in: $out_dir"
find "$out_dir" -type f \( -name '*.png' -o -name '*.svg' -o -name '*.pdf' \) | sort | sed 's/^/  /'

#!/usr/bin/env bash
# Builds the narrated notebooks (notebooks_cpp/, Release, build/) and renders
# them all: each writes OUTPUT_DIR/NN_name/report.md with its figures, then
# the index page OUTPUT_DIR/index.md links them.
# Usage: bash scripts/notebooks.sh [--quick] [OUTPUT_DIR]
#   (default: talus-out/notebooks in the repo root; --quick: small grids, as CI runs them)
set -euo pipefail

usage() { echo "usage: $0 [--quick] [OUTPUT_DIR]" >&2; exit 2; }
quick=()
out_dir=
for arg in "$@"; do
  case "$arg" in
    --quick) quick=(--quick) ;;
    -h|--help) usage ;;
    -*) usage ;;
    *) [[ -z "$out_dir" ]] || usage; out_dir=$arg ;;
  esac
done

repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if [[ -n "$out_dir" ]]; then
  [[ "$out_dir" == /* ]] || out_dir="$PWD/$out_dir"
else
  out_dir="$repo_root/talus-out/notebooks"
fi

cd "$repo_root"
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target notebooks

mkdir -p "$out_dir"
status=0
for program in build/notebooks_cpp/[0-9][0-9]_*; do
  [[ -x "$program" && -f "$program" ]] || continue
  name=$(basename "$program")
  start=$(date +%s%N)
  if "$program" "${quick[@]}" --out "$out_dir" > "$out_dir/$name.log" 2>&1; then
    result=ok
  else
    result="FAILED (see $out_dir/$name.log)"
    status=1
  fi
  tenths=$(( ($(date +%s%N) - start) / 100000000 ))
  printf '%-26s %4d.%d s  %s\n' "$name" $((tenths / 10)) $((tenths % 10)) "$result"
done
build/notebooks_cpp/notebooks_index --out "$out_dir" > /dev/null || status=1
echo "Notebooks: $out_dir/index.md"
exit $status

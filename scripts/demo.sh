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
# name `talus` belongs to the umbrella library target); talus_python is
# `import talus` for the Jupyter notebooks (step 5).
cmake --build build -j"$(nproc)" --target talus_cli talus_python

talus=build/experiments/talus
if [[ ! -x "$talus" ]]; then
  echo "demo.sh: $talus was not built." >&2
  exit 1
fi

# The demo owns its output folders: start them afresh (talus itself never
# replaces files it did not write, e.g. those of an older talus without a
# manifest).
rm -rf "$out_dir/plan" "$out_dir/optimal-profile" "$out_dir/global-search" \
       "$out_dir/terrain-gallery" "$out_dir/notebooks-python"
mkdir -p "$out_dir"
terrain=data/terrain/mount_st_helens_usgs30m.asc
vehicle=data/vehicles/rover.yaml

# 1. The terrain model: fit the B-patch to a real DEM (USGS, 30 m cells).
"$talus" terrain fit "$terrain" --smoothing 1

# 2. The main job: a time-optimal plan across Mount St. Helens, from 10 % to
#    90 % of the DEM's diagonal (south-west of the crater to its north-east),
#    where the rover's limits bind: the routes bend round the crater and the
#    profile drops below the 15 m/s cap wherever the ground curves. Global
#    minimum-time search for distinct candidates, local optimisation of each
#    B-spline path for the travel time of its exact time-optimal velocity
#    profile (Ipopt with the adjoint gradient), best trajectory and both
#    figures.
"$talus" plan --terrain "$terrain" --vehicle "$vehicle" \
  --start 558903,5109462 --goal 566487,5120478 \
  --out "$out_dir/plan" > "$out_dir/plan.json"
python3 - "$out_dir/plan.json" <<'PY' 2>/dev/null || head -c 600 "$out_dir/plan.json"
import json, sys
s = json.load(open(sys.argv[1]))
print(f"plan: {s['status']}, travel time {s['travel_time']:.2f} s "
      f"(best global candidate's own profile {s['global_travel_time']:.2f} s, "
      f"improvement {s['improvement_percent']:.2f} %)")
PY

# 3. The experiments' figures: the profile under its limit curve, the global
#    search on a volcano, and the terrain gallery.
for experiment in optimal-profile global-search terrain-gallery; do
  "$talus" experiment "$experiment" --out "$out_dir"
done

# 4. The narrated notebooks (notebooks_cpp/): one Markdown page with figures
#    each, linked from notebooks/index.md (about 15 s once built).
bash scripts/notebooks.sh "$out_dir/notebooks"

# 5. The Jupyter notebooks (python/notebooks/), executed and rendered to HTML
#    with their figures (about 40 s).
PYTHONPATH="$repo_root/build/python" /usr/bin/python3 python/notebooks/run_notebooks.py \
  python/notebooks/*.ipynb --html "$out_dir/notebooks-python"

echo
echo "Results are in: $out_dir"
find "$out_dir" -type f \( -name '*.png' -o -name 'report.md' -o -name 'summary.json' -o -name 'trajectory.csv' -o -name '*.html' \) | sort | sed 's/^/  /'

#!/usr/bin/env bash
# Builds Talus and runs the whole test suite.
# Usage: bash scripts/test.sh              Release build in build/
#        bash scripts/test.sh --sanitize   ASan+UBSan build in build-sanitize/
set -euo pipefail

usage() { echo "usage: $0 [--sanitize]" >&2; exit 2; }

sanitize=0
for arg in "$@"; do
  case "$arg" in
    --sanitize) sanitize=1 ;;
    -h|--help) usage ;;
    *) echo "test.sh: unknown argument '$arg'" >&2; usage ;;
  esac
done

repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"

bash scripts/setup.sh

jobs=$(nproc)
if [[ $sanitize -eq 1 ]]; then
  build_dir=build-sanitize
  export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # -O1 -g1: ASan's recommended optimisation, and line tables (enough for its stack traces);
  # compiling a test file this way takes about half as long as at -O2 -g.
  # The notebooks are not built here: their runs are Release-only (below).
  cmake -S . -B "$build_dir" -DTALUS_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DTALUS_BUILD_BENCHMARKS=OFF \
        -DTALUS_BUILD_NOTEBOOKS=OFF
else
  build_dir=build
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
fi

exclude=()
if [[ $sanitize -eq 1 ]]; then
  # The experiment runs (Experiment.*) drive the CLI end to end over minutes of CPU under
  # ASan, and the notebooks (Notebook.*, not built here) walk through the library with their
  # own checks; the Release stage runs both, and their library code runs here in the unit
  # tests. The install-consumer test (InstallConsumer.*) checks packaging, not memory: a
  # minute of CMake and compiler here, and the Release stage runs it.
  # Six tests whose minutes under ASan are numerical iterations over code that lighter tests
  # run here too (measured under ASan: 285 of 1,290 CPU seconds): the simultaneous NLP's
  # convergence studies (SimultaneousStage.StraightLineOnAPlane runs the same NLP), the sweep
  # over three job counts (the other SweepCli tests run the runner), the layered navigation end
  # to end (SweepCli.NavigateJob runs `talus navigate`, LayeredNavigation the library) and the
  # coarse-to-fine search against the full one on every case (GlobalSearchMulti's other tests).
  # The Release stage runs all six.
  heavy='SimultaneousStage\.(ConvergesByIpopts|AgreesWithTheNested|StartsFromAnInfeasible)'
  heavy+='|SweepCli\.ResultsDoNotDependOnTheJobCount|CliNavigate\.PlansCoarseAndNavigatesFine'
  heavy+='|GlobalSearchMulti\.SameBestCandidateAsTheFullSearch'
  exclude=(-E "^(Experiment|InstallConsumer)\.|^(${heavy})")
fi

start=$SECONDS
cmake --build "$build_dir" -j"$jobs"
built=$SECONDS
ctest --test-dir "$build_dir" --output-on-failure -j"$jobs" "${exclude[@]}"
echo "test.sh: $build_dir built in $((built - start)) s, tested in $((SECONDS - built)) s"

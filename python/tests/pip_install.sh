#!/usr/bin/env bash
# `pip install --no-build-isolation .` of the checkout into a fresh venv (Debian's packages,
# offline), then the whole pytest suite against that installed package, not the build folder.
# CTest's Python.pipInstall runs it with the build folder of its own build, which setup.py
# reuses (TALUS_CMAKE_BUILD_DIR): the install then costs no second build of the library.
# Usage: pip_install.sh SOURCE_DIR CMAKE_BUILD_DIR
set -euo pipefail
source_dir=$(cd "$1" && pwd)
build_dir=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

/usr/bin/python3 -m venv --system-site-packages "$work/venv"
(cd "$source_dir" &&
  TALUS_CMAKE_BUILD_DIR="$build_dir" "$work/venv/bin/pip" install --quiet --no-build-isolation \
    --no-index --no-cache-dir .)

unset PYTHONPATH
cd "$work"
TALUS_INSTALLED_IN="$work/venv" "$work/venv/bin/python" -m pytest -q -p no:cacheprovider \
  "$source_dir/python/tests"

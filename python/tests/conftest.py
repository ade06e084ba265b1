"""Shared fixtures of the Python bindings' tests.

CTest (python/CMakeLists.txt) runs `/usr/bin/python3 -m pytest python/tests` with
PYTHONPATH=<build>/python and sets TALUS_DATA_DIR, TALUS_REFERENCE (the C++
helper tests/reference.cpp), TALUS_CLI (the `talus` tool, when built),
TALUS_BUILD_DIR, TALUS_PYTHON_INSTALL_DIR and TALUS_EXAMPLES_DIR.
"""
import os
import pathlib
import subprocess

import pytest

import talus

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parent.parent


def env_path(name, default=None):
    value = os.environ.get(name)
    return pathlib.Path(value) if value else default


@pytest.fixture(scope="session")
def data_dir():
    return env_path("TALUS_DATA_DIR", SOURCE / "data")


@pytest.fixture(scope="session")
def rover(data_dir):
    return data_dir / "vehicles" / "rover.yaml"


@pytest.fixture(scope="session")
def west_bijou(data_dir):
    return data_dir / "terrain" / "west_bijou_escarpment_nasadem25m.asc"


def number_text(x):
    """A float as text that C++ strtod reads back to the same double."""
    return repr(float(x))


@pytest.fixture(scope="session")
def reference():
    """Runs the C++ helper and returns {name: float or list of floats or str}."""
    exe = env_path("TALUS_REFERENCE")
    if exe is None or not exe.exists():
        pytest.skip("TALUS_REFERENCE (the talus_python_reference helper) is not built")

    def run(*args):
        out = subprocess.run([str(exe), *map(str, args)], check=True, capture_output=True,
                             text=True).stdout
        values = {}
        for line in out.splitlines():
            name, *fields = line.split(" ")
            try:
                numbers = [float(f) for f in fields]
            except ValueError:
                values[name] = " ".join(fields)
                continue
            values[name] = numbers[0] if len(numbers) == 1 and not name.endswith(
                (".s", ".v", ".a", ".t", ".v_max", ".control_points")) else numbers
        return values

    return run


@pytest.fixture(scope="session")
def cli():
    """Runs the `talus` CLI: returns (exit code, stdout, stderr)."""
    exe = env_path("TALUS_CLI")
    if exe is None or not exe.exists():
        pytest.skip("TALUS_CLI (the talus tool) is not built (TALUS_BUILD_EXPERIMENTS=OFF)")

    # The tests compare numbers, not figures: with no gnuplot on its PATH the CLI skips them
    # (about 0.7 s per run).
    env = {**os.environ, "PATH": ""}

    def run(*args):
        r = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, env=env)
        return r.returncode, r.stdout, r.stderr

    return run


def cli_error(stderr):
    """The message of the CLI's one-line error, without the `talus: error: ` prefix."""
    prefix = "talus: error: "
    assert stderr.startswith(prefix) and stderr.endswith("\n"), stderr
    return stderr[len(prefix):-1]


@pytest.fixture()
def plane_asc(tmp_path):
    """Writes the grid z = slope * x (nodes every `h` m from (x0, y0)) and returns its path."""

    def write(name, ncols, nrows, h, x0, y0, slope):
        import numpy as np
        x = x0 + h * np.arange(ncols)
        z = np.tile(slope * x, (nrows, 1))
        path = tmp_path / name
        talus.write_esri_ascii(talus.ElevationGrid.from_array(z, h, x0, y0), str(path))
        return path

    return write

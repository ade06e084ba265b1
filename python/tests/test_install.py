"""`cmake --install` puts an importable module under the prefix."""
import os
import pathlib
import subprocess
import sys

import pytest


def test_the_installed_module_imports_from_the_prefix(tmp_path):
    build = os.environ.get("TALUS_BUILD_DIR")
    folder = os.environ.get("TALUS_PYTHON_INSTALL_DIR")
    if not build or not folder:
        pytest.skip("TALUS_BUILD_DIR / TALUS_PYTHON_INSTALL_DIR are set by CTest")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix), "--component", "python"],
                   check=True, capture_output=True)
    site = prefix / folder
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    r = subprocess.run([sys.executable, "-c", "import talus; print(talus.__file__); "
                        "print(talus.baseline_names())"], capture_output=True, text=True,
                       env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    module, names = r.stdout.splitlines()
    assert pathlib.Path(module).parent == site
    assert "hait" in names


def test_pip_installed_the_module_the_suite_imports():
    """Under `pip_install.sh` (CTest's Python.pipInstall) the suite must test the installed
    package: the module and its metadata come from the venv, not from the build folder."""
    venv = os.environ.get("TALUS_INSTALLED_IN")
    if not venv:
        pytest.skip("TALUS_INSTALLED_IN is set by python/tests/pip_install.sh")
    import importlib.metadata

    import talus
    assert pathlib.Path(talus.__file__).resolve().is_relative_to(pathlib.Path(venv).resolve())
    assert importlib.metadata.version("talus") == talus.__version__

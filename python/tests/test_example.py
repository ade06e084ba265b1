"""python/examples/plan.py runs and writes its figure."""
import os
import pathlib
import subprocess
import sys

EXAMPLES = pathlib.Path(os.environ.get("TALUS_EXAMPLES_DIR",
                                       pathlib.Path(__file__).resolve().parents[1] / "examples"))


def test_the_plan_example_writes_a_png(tmp_path):
    out = tmp_path / "example"
    r = subprocess.run([sys.executable, str(EXAMPLES / "plan.py"), "--candidates", "1",
                        "--out", str(out)], capture_output=True, text=True,
                       env={**os.environ, "MPLBACKEND": "Agg"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("Talus plan: ok")
    png = (out / "plan.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20000

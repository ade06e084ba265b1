"""The CLI's progress line: drawn on a terminal (a pseudo-terminal here), absent
on a pipe and with --quiet; the JSON on stdout is the same either way."""
import json
import os
import subprocess
import threading

import pytest

from conftest import env_path, number_text

START, GOAL = (557000.0, 4373500.0), (557800.0, 4374200.0)  # about 1.07 km on West Bijou


def run(args, terminal):
    exe = env_path("TALUS_CLI")
    if exe is None or not exe.exists():
        pytest.skip("TALUS_CLI (the talus tool) is not built")
    env = {**os.environ, "PATH": ""}  # no gnuplot: no figures
    if not terminal:
        r = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, env=env)
        return r.returncode, r.stdout, r.stderr
    primary, secondary = os.openpty()
    chunks = []

    def drain():  # read while the command writes: a full terminal buffer would block it
        while True:
            try:
                chunk = os.read(primary, 65536)
            except OSError:  # EIO: the terminal's other side is closed
                return
            if not chunk:
                return
            chunks.append(chunk)

    reader = threading.Thread(target=drain)
    reader.start()
    try:
        r = subprocess.run([str(exe), *map(str, args)], stdout=subprocess.PIPE,
                           stderr=secondary, text=True, env=env, timeout=60)
    finally:
        os.close(secondary)
        reader.join(timeout=10)
        os.close(primary)
    return r.returncode, r.stdout, b"".join(chunks).decode()


def plan_args(west_bijou, rover, out):
    return ["plan", "--terrain", west_bijou, "--vehicle", rover,
            "--start", ",".join(map(number_text, START)),
            "--goal", ",".join(map(number_text, GOAL)), "--candidates", 1, "--out", out]


def test_plan_draws_its_progress_line_on_a_terminal_only(west_bijou, rover, tmp_path):
    code, out, err = run(plan_args(west_bijou, rover, tmp_path / "tty"), terminal=True)
    assert code == 0, err
    assert "talus plan: fitting the surface" in err
    assert "talus plan: local optimisation, candidate 1 of 1" in err
    assert "\r" in err and err.endswith("\r\x1b[K")  # rewritten in place, cleared at the end
    on_terminal = json.loads(out)

    code, out, err = run(plan_args(west_bijou, rover, tmp_path / "pipe"), terminal=False)
    assert code == 0, err
    assert err == ""
    assert json.loads(out)["travel_time"] == on_terminal["travel_time"]

    code, out, err = run(plan_args(west_bijou, rover, tmp_path / "quiet") + ["--quiet"],
                         terminal=True)
    assert code == 0, err
    assert err == ""


def test_simulate_and_sweep_show_progress_on_a_terminal_only(west_bijou, data_dir, tmp_path):
    rover_sim = data_dir / "vehicles" / "rover_sim.yaml"
    code, _, err = run(plan_args(west_bijou, rover_sim, tmp_path / "plan"), terminal=False)
    assert code == 0, err
    simulate = ["simulate", "--terrain", west_bijou, "--vehicle", rover_sim,
                "--trajectory", tmp_path / "plan" / "trajectory.csv"]
    code, out, err = run(simulate + ["--out", tmp_path / "sim_tty"], terminal=True)
    assert code in (0, 2), err
    assert "talus simulate: driving the trajectory, t = " in err
    code, out, err = run(simulate + ["--out", tmp_path / "sim_pipe"], terminal=False)
    assert code in (0, 2), err
    assert err == ""

    config = tmp_path / "noop.yaml"
    config.write_text("job: noop\ndesign: grid\nparameters:\n  value: [1, 2, 3]\n")
    code, out, err = run(["sweep", config, "--out", tmp_path / "sweep_tty", "--jobs", 1],
                         terminal=True)
    assert code == 0, err
    assert "sweep: 3/3 done, 0 failed, 0 running" in err or "sweep: 2/3 done" in err, err
    code, out, err = run(["sweep", config, "--out", tmp_path / "sweep_quiet", "--jobs", 1,
                          "--quiet"], terminal=True)
    assert code == 0, err
    assert err == ""

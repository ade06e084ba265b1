"""Hardening (issue 39): the bindings are safe from several Python threads, and hostile
YAML is an InputError, not a dead interpreter. Each case runs in a child interpreter,
so a regression (a segfault, or MUMPS's "Fortran runtime error") fails this test
instead of killing the test session."""
import subprocess
import sys
import textwrap

PLAN_IN_THREADS = textwrap.dedent("""
    import sys, threading
    import numpy as np
    import talus

    terrain, rover = sys.argv[1], sys.argv[2]
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(terrain))
    vehicle = talus.load_vehicle(rover)
    start, goal = (557000.0, 4373500.0), (557800.0, 4374200.0)

    def plan():
        options = talus.PlannerOptions()
        options.global_search.candidates = 2
        return talus.plan(talus.PlanningProblem(surface, vehicle, start, goal), options)

    serial = plan()
    assert serial.status == talus.PlannerStatus.OK, serial.brief_report()
    results, errors = [None] * 3, []

    def run(k):
        try:
            results[k] = plan()
        except Exception as e:  # reported below, with the thread's number
            errors.append((k, repr(e)))

    threads = [threading.Thread(target=run, args=(k,)) for k in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for r in results:
        assert r.travel_time() == serial.travel_time(), (r.travel_time(), serial.travel_time())
        assert np.array_equal(r.best().path.curve().control_points,
                              serial.best().path.curve().control_points)
    print("same", serial.travel_time())
""")


def run_child(script, *args):
    return subprocess.run([sys.executable, "-c", script, *map(str, args)],
                          capture_output=True, text=True, timeout=600)


def test_three_threads_planning_at_once_give_the_serial_answer(west_bijou, rover):
    child = run_child(PLAN_IN_THREADS, west_bijou, rover)
    assert child.returncode == 0, f"exit {child.returncode}\n{child.stdout}\n{child.stderr}"
    assert child.stdout.startswith("same "), child.stdout


HOSTILE_YAML = textwrap.dedent("""
    import talus
    bomb = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\\n" + "".join(
        f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * 10) + "]\\n" for k in range(1, 10))
    for text, fragment in [("x: &a [1, *a]\\n", "cycle"), (bomb, "aliases expanded"),
                           ("x: " + "[" * 500 + "]" * 500 + "\\n", "levels deep")]:
        try:
            talus.parse_vehicle(text, "hostile.yaml")
        except talus.InputError as e:
            assert fragment in str(e) and str(e).startswith("hostile.yaml:"), str(e)
        else:
            raise AssertionError("accepted: " + text[:60])
    print("refused")
""")


def test_hostile_yaml_is_an_input_error_not_a_crash():
    child = run_child(HOSTILE_YAML)
    assert child.returncode == 0, f"exit {child.returncode}\n{child.stdout}\n{child.stderr}"
    assert child.stdout.strip() == "refused"

#!/usr/bin/env python3
"""Executes Jupyter notebooks top to bottom and fails on the first cell that raises.

    run_notebooks.py NOTEBOOK.ipynb ... [--html DIR]

Each notebook runs in a fresh `python3` kernel (nbclient) with this folder as its working
directory, so its `import talus` sees the same environment as this script (PYTHONPATH or an
installed package). A notebook's own `assert`s are its checks: a failed one fails the run.
With --html, each executed notebook is also written as DIR/NAME.html (nbconvert), figures
included. The notebooks in the repository are kept without outputs.
"""
import argparse
import os
import pathlib
import sys
import time

import nbclient
import nbformat


def execute(path, html_dir):
    book = nbformat.read(str(path), as_version=4)
    start = time.monotonic()
    client = nbclient.NotebookClient(book, timeout=900, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    try:
        client.execute()
    except nbclient.exceptions.CellExecutionError as error:
        print(f"{path.name}: a cell failed\n{error}", file=sys.stderr)
        return False
    print(f"{path.name}: {len(book.cells)} cells ran in {time.monotonic() - start:.1f} s")
    if html_dir is not None:
        from nbconvert import HTMLExporter
        html, _ = HTMLExporter().from_notebook_node(book)
        html_dir.mkdir(parents=True, exist_ok=True)
        (html_dir / f"{path.stem}.html").write_text(html)
    return True


def main():
    # ipykernel imports its debugger, which warns about Python's frozen modules on every start.
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")
    # The kernels run in the notebooks' folder: a relative PYTHONPATH (PYTHONPATH=build/python)
    # is made absolute here, where it was meant.
    if os.environ.get("PYTHONPATH"):
        os.environ["PYTHONPATH"] = os.pathsep.join(
            str(pathlib.Path(entry).resolve()) if entry else entry
            for entry in os.environ["PYTHONPATH"].split(os.pathsep))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="+", type=pathlib.Path)
    parser.add_argument("--html", type=pathlib.Path, help="write each as DIR/NAME.html")
    args = parser.parse_args()
    ok = [execute(path.resolve(), args.html) for path in args.notebooks]
    return 0 if all(ok) else 1


if __name__ == "__main__":
    sys.exit(main())

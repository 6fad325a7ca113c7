#!/usr/bin/env python3
"""Executes the example notebooks (nbclient, a fresh kernel each, in the
repository's root) and fails on the first cell that raises.

    python examples/run.py              # run them all
    python examples/run.py --write      # and store their outputs in place
    python examples/run.py terrell-rotation.ipynb
"""
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

HERE = Path(__file__).resolve().parent


def run(path: Path, write: bool) -> None:
    book = nbformat.read(path, as_version=4)
    NotebookClient(book, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(HERE.parent)}}).execute()
    if write:
        nbformat.write(book, path)
    print(f"ran {path.name}")


def main(argv):
    write = "--write" in argv
    names = [a for a in argv if not a.startswith("--")]
    paths = [HERE / n for n in names] if names else sorted(HERE.glob("*.ipynb"))
    for p in paths:
        run(p, write)


if __name__ == "__main__":
    main(sys.argv[1:])

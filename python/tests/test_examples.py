"""The example notebooks under examples/ run to the end (nbclient, a fresh
kernel each): a cell that raises, including the notebooks' own asserts on
what they measure, fails the test."""

from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BOOKS = sorted(p.name for p in EXAMPLES.glob("*.ipynb"))


def test_there_are_examples():
    assert len(BOOKS) >= 3


@pytest.mark.parametrize("name", BOOKS)
def test_the_notebook_runs(name):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    book = nbformat.read(EXAMPLES / name, as_version=4)
    client = nbclient.NotebookClient(
        book, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(EXAMPLES.parent)}}
    )
    client.execute()
    errors = [o for c in book.cells if c.cell_type == "code" for o in c.get("outputs", []) if o.output_type == "error"]
    assert not errors

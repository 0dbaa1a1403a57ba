#!/usr/bin/python3
"""Writes the classroom notebooks from their cells, without outputs (run with /usr/bin/python3).

  svgf_walkthrough.ipynb   each SVGF pass on a real frame, in the order of filters/svgf/README.md
  speed_vs_accuracy.ipynb  the metrics of `rtdr eval`: charts and the trade-off
  asvgf_walkthrough.ipynb  A-SVGF's gradient samples, lambda and alpha_i on the moving shadows of `pillars`,
                           beside SVGF's lagging history, in the order of filters/asvgf/README.md
  trmv_walkthrough.ipynb   TRMV's four motion vectors (surface, shadow, glossy, dual) on fence, glossy and
                           occlusion, one vector rebuilt by hand, and where each one fails (filters/trmv/README.md)

All four read their data from environment variables (defaults: what tools/demo.sh, the README's commands and
the commands in each notebook's first cell write), so the test suite can run them on a tiny sequence:
tests/run_notebooks.sh. Each notebook's cells are in <notebook>_cells.py; the first code cell of each starts with
common_cell.py's COMMON.
"""
import os

import nbformat
from nbformat.v4 import new_notebook

from asvgf_walkthrough_cells import ASVGF_WALKTHROUGH
from speed_vs_accuracy_cells import SPEED
from svgf_walkthrough_cells import WALKTHROUGH
from trmv_walkthrough_cells import TRMV_WALKTHROUGH

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, cells):
    for i, cell in enumerate(cells):  # fixed ids, so regenerating gives the same bytes
        cell["id"] = f"{name.split('.')[0]}-{i:02d}"
    nb = new_notebook(cells=cells, metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                               "language": "python"}})
    path = os.path.join(HERE, name)
    with open(path, "w") as f:
        nbformat.write(nb, f)
    print("wrote", path)


if __name__ == "__main__":
    write("svgf_walkthrough.ipynb", WALKTHROUGH)
    write("speed_vs_accuracy.ipynb", SPEED)
    write("asvgf_walkthrough.ipynb", ASVGF_WALKTHROUGH)
    write("trmv_walkthrough.ipynb", TRMV_WALKTHROUGH)

"""Remove outputs and execution counts from notebooks in place: tools/strip_outputs.py NB [NB ...]."""
import sys

import nbformat


def strip(path):
    nb = nbformat.read(path, as_version=4)
    changed = False
    for cell in nb.cells:
        if cell.cell_type == "code":
            if cell.get("outputs") or cell.get("execution_count") is not None:
                changed = True
            cell["outputs"] = []
            cell["execution_count"] = None
        for key in ("collapsed", "scrolled", "execution"):
            if key in cell.get("metadata", {}):
                del cell["metadata"][key]
                changed = True
    nb.metadata.pop("widgets", None)
    nbformat.write(nb, path)
    return changed


if __name__ == "__main__":
    for p in sys.argv[1:]:
        if strip(p):
            print(f"stripped {p}")

"""Writes the type stub of pcl_ncut_seg (__init__.pyi) from the module as built: the keyword
parameters of segment(), Segmenter() and set() and the Segmenter's parameter attributes come
from parameter_table() (names, kinds, choices, off words, defaults) and parameter_shorthands(),
the docstrings from the objects themselves. The build runs it; the tests run it again and
compare, so an installed stub always says what the installed module takes.

    python3 -m pcl_ncut_seg._stub [OUTPUT]      (default: standard output)
"""
import inspect
import math
import sys

import pcl_ncut_seg

# What the package defines besides the parameters: the signatures, as the stub gives them.
FUNCTIONS = {
    "parameter_table": "() -> list[dict[str, Any]]",
    "parameter_shorthands": "() -> list[dict[str, Any]]",
    "default_parameters": "(paper: bool = False) -> dict[str, Any]",
    "as_arrays": "(cloud: _Cloud, normals: npt.ArrayLike | None = None) -> tuple[Any, Any]",
    "segment_colors": "(labels: npt.ArrayLike) -> npt.NDArray[np.uint8]",
    "colorize": "(cloud: _O3DCloud, labels: npt.ArrayLike) -> _O3DCloud",
    "read_file": "(path: str | os.PathLike[str], samples: int = 0, seed: int = 1) -> "
                 "tuple[npt.NDArray[np.float32], tuple[float, ...], int | None, str]",
}
METHODS = {
    "get": "(self, name: str) -> Any",
    "get_labels": "(self) -> npt.NDArray[np.int32]",
    "get_centrality": "(self) -> npt.NDArray[np.float32]",
    "get_supernode_labels": "(self, refined: bool = True) -> npt.NDArray[np.int32]",
    "get_local_maxima": "(self) -> npt.NDArray[np.int64]",
    "get_saddles": "(self) -> npt.NDArray[np.int64]",
    "get_hierarchy": "(self) -> dict[str, npt.NDArray[Any]]",
    "get_supernode_segments": "(self) -> npt.NDArray[np.int32]",
    "get_supernode_graph": "(self) -> dict[str, Any]",
}
PROPERTIES = {
    "parameters": "dict[str, Any]",
    "num_points": "int",
    "num_segments": "int",
    "num_supernodes": "int",
    "num_refined_supernodes": "int",
    "noise_test": "dict[str, Any]",
    "view_test": "dict[str, Any]",
    "phase_times": "dict[str, float]",
    "analysis_count": "int",
}
KIND_TYPES = {"integer": "int", "real": "float", "switch": "bool", "boolean": "bool"}

HEADER = '''# The type stub of pcl_ncut_seg {version}, written by pcl_ncut_seg/_stub.py from the
# module's parameter table when the module was built. Do not edit: rebuild.
import os
from typing import Any, Literal, TypeVar

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = {all}

_Cloud = Any
"""What segment() takes: an (N, 3) or (H, W, 3) float32 or float64 array, anything numpy
reads as one (__array__), or an open3d.geometry.PointCloud or open3d.t.geometry.PointCloud."""
_O3DCloud = TypeVar("_O3DCloud")
'''


def parameter_type(row):
    """The type of a parameter's Python value: None where the row has an off word."""
    if row["kind"] == "choice":
        text = "Literal[" + ", ".join(repr(c) for c in row["choices"]) + "]"
    else:
        text = KIND_TYPES[row["kind"]]
    return text + " | None" if row["off"] is not None else text


def keyword_rows():
    """The table's rows in the order of the keywords (default_parameters()'s order)."""
    rows = {row["name"]: row for row in pcl_ncut_seg.parameter_table()}
    return [rows[name] for name in pcl_ncut_seg.default_parameters()]


def keywords(with_defaults):
    """The keyword-only parameters: paper, the shorthands, then every row (its default, or ...
    where leaving it out means 'unchanged')."""
    out = ["paper: bool = " + ("False" if with_defaults else "...")]
    out += [f"{s['name']}: Literal[True] = ..." for s in pcl_ncut_seg.parameter_shorthands()]
    for row in keyword_rows():
        value = row["default"]
        literal = not (isinstance(value, float) and not math.isfinite(value))  # no inf in a stub
        default = repr(value) if with_defaults and literal else "..."
        out.append(f"{row['name']}: {parameter_type(row)} = {default}")
    return out


def own_doc(obj):
    """obj's docstring without the signature line pybind11 puts first."""
    doc = inspect.cleandoc(getattr(obj, "__doc__", None) or "")
    first, _, rest = doc.partition("\n")
    if "(" in first and "->" in first and rest.strip():
        doc = rest.strip()
    return doc


def docstring(doc, indent):
    doc = doc.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = doc.splitlines() or [""]
    body = "\n".join((indent + line).rstrip() for line in lines[1:])
    return f'{indent}"""{lines[0]}' + (f"\n{body}\n{indent}" if body else "") + '"""'


def function(name, signature_head, parameters, result, doc, indent=""):
    """def name(signature_head, *, parameters) -> result, one parameter a line."""
    lines = [f"{indent}def {name}("]
    lines += [f"{indent}    {p}," for p in signature_head]
    if parameters:
        lines.append(f"{indent}    *,")
        lines += [f"{indent}    {p}," for p in parameters]
    lines.append(f"{indent}) -> {result}:")
    lines.append(docstring(doc, indent + "    "))
    return "\n".join(lines)


def stub():
    seg = pcl_ncut_seg.Segmenter
    out = [HEADER.format(version=pcl_ncut_seg.__version__, all=repr(list(pcl_ncut_seg.__all__)))]
    out.append(function("segment", ["points: _Cloud", "normals: npt.ArrayLike | None = None",
                                    "sensor_origin: npt.ArrayLike | None = None"],
                        keywords(True), "npt.NDArray[np.int32]", own_doc(pcl_ncut_seg.segment)))
    for name, signature in FUNCTIONS.items():
        out.append(f"def {name}{signature}:\n"
                   + docstring(own_doc(getattr(pcl_ncut_seg, name)), "    "))
    out.append("class Segmenter:\n" + docstring(own_doc(seg), "    "))
    out.append(function("__init__", ["self"], keywords(True), "None",
                        "Parameters by name (the project's defaults for the others; paper=True: "
                        "the paper's settings).", "    "))
    out.append(function("set", ["self"], keywords(False), "None", own_doc(seg.set), "    "))
    out.append(function("segment", ["self", "points: _Cloud | None = None",
                                    "normals: npt.ArrayLike | None = None",
                                    "sensor_origin: npt.ArrayLike | None = None"],
                        keywords(False), "npt.NDArray[np.int32]", own_doc(seg.segment), "    "))
    for name, signature in METHODS.items():
        out.append(f"    def {name}{signature}:\n"
                   + docstring(own_doc(getattr(seg, name)), "        "))
    for name, kind in PROPERTIES.items():
        out.append(f"    @property\n    def {name}(self) -> {kind}:\n"
                   + docstring(own_doc(getattr(seg, name)), "        "))
    for row in keyword_rows():
        name, kind = row["name"], parameter_type(row)
        out.append(f"    @property\n    def {name}(self) -> {kind}:\n"
                   + docstring(own_doc(getattr(seg, name)), "        ")
                   + f"\n    @{name}.setter\n    def {name}(self, value: {kind}) -> None: ...")
    return "\n\n".join(out) + "\n"


def main(argv):
    text = stub()
    if len(argv) > 1:
        with open(argv[1], "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main(sys.argv)

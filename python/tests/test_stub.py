"""The type stub (__init__.pyi) beside the module that is imported: up to date with the module,
and saying what the module takes, with every name and default read from the module's
parameter table at run time."""
import ast
import math
import os
import re
import subprocess
import sys

import pytest

import pcl_ncut_seg
from pcl_ncut_seg import _stub

PACKAGE = os.path.dirname(pcl_ncut_seg.__file__)
KIND_TYPES = {"integer": int, "real": float, "switch": bool, "boolean": bool, "choice": str}


def read_stub():
    with open(os.path.join(PACKAGE, "__init__.pyi"), encoding="utf-8") as f:
        return f.read()


def stub_tree():
    return ast.parse(read_stub())


def functions(body):
    """name -> the def (the getter for a property), from a module's or a class' body."""
    out = {}
    for node in body:
        if isinstance(node, ast.FunctionDef):
            setter = any(isinstance(d, ast.Attribute) and d.attr == "setter"
                         for d in node.decorator_list)
            out.setdefault(node.name, node)
            if setter:
                out[node.name + ".setter"] = node
    return out


def keyword_defaults(fn):
    return {a.arg: d for a, d in zip(fn.args.kwonlyargs, fn.args.kw_defaults)}


def expected_keywords():
    return (["paper"] + [s["name"] for s in pcl_ncut_seg.parameter_shorthands()]
            + list(pcl_ncut_seg.default_parameters()))


def test_the_stub_and_py_typed_are_installed_and_up_to_date():
    assert os.path.isfile(os.path.join(PACKAGE, "py.typed"))
    assert read_stub() == _stub.stub(), "stale __init__.pyi: rebuild the package"


def test_module_functions_match():
    defs = functions(stub_tree().body)
    public = {n for n in pcl_ncut_seg.__all__ if callable(getattr(pcl_ncut_seg, n))}
    assert set(defs) == public - {"Segmenter"}
    assert "Segmenter" in {n.name for n in stub_tree().body if isinstance(n, ast.ClassDef)}


def check_parameter(row, annotation, default):
    text = ast.unparse(annotation)
    assert ("None" in text) == (row["off"] is not None), (row["name"], text)
    if row["kind"] == "choice":
        literal = annotation.left if isinstance(annotation, ast.BinOp) else annotation
        assert [ast.literal_eval(e) for e in literal.slice.elts] == row["choices"], row["name"]
    else:
        assert KIND_TYPES[row["kind"]].__name__ in text, (row["name"], text)
    if default is None:
        return
    if isinstance(default, ast.Constant) and default.value is Ellipsis:  # only for inf or NaN
        assert isinstance(row["default"], float) and not math.isfinite(row["default"])
    else:
        value = ast.literal_eval(default)
        assert value == row["default"] and type(value) is type(row["default"]), row["name"]


def test_segment_and_segmenter_take_the_tables_keywords_with_its_defaults():
    tree = stub_tree()
    segmenter = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Segmenter")
    methods = functions(segmenter.body)
    rows = {row["name"]: row for row in pcl_ncut_seg.parameter_table()}
    for fn, with_defaults in ((functions(tree.body)["segment"], True),
                              (methods["__init__"], True), (methods["set"], False),
                              (methods["segment"], False)):
        defaults = keyword_defaults(fn)
        assert list(defaults) == expected_keywords(), fn.name
        for arg in fn.args.kwonlyargs:
            if arg.arg in rows:
                default = defaults[arg.arg] if with_defaults else None
                check_parameter(rows[arg.arg], arg.annotation, default)
                if not with_defaults:
                    assert defaults[arg.arg].value is Ellipsis  # left out: unchanged
        if with_defaults:
            assert defaults["paper"].value is False


def test_segmenter_attributes_match():
    segmenter = next(n for n in stub_tree().body
                     if isinstance(n, ast.ClassDef) and n.name == "Segmenter")
    methods = functions(segmenter.body)
    runtime = {n for n in dir(pcl_ncut_seg.Segmenter) if not n.startswith("_")}
    assert {n for n in methods if not n.startswith("_") and "." not in n} == runtime
    for row in pcl_ncut_seg.parameter_table():
        getter, setter = methods[row["name"]], methods[row["name"] + ".setter"]
        check_parameter(row, getter.returns, None)
        assert ast.unparse(setter.args.args[1].annotation) == ast.unparse(getter.returns)
        assert ast.get_docstring(getter).startswith(row["help"])


def run_mypy_tool(tmp_path, config_flag, *args):
    """python -m <args> in tmp_path (away from the sources), as a checker sees the package
    that is imported here; open3d has no stubs of its own."""
    pytest.importorskip("mypy", reason="mypy is not importable (apt-get install python3-mypy)")
    config = tmp_path / "mypy.ini"
    config.write_text("[mypy]\nignore_missing_imports = True\n")
    env = dict(os.environ, PYTHONPATH=os.path.dirname(PACKAGE))
    return subprocess.run([sys.executable, "-m", *args, config_flag, str(config)],
                          cwd=tmp_path, env=env, capture_output=True, text=True)


def test_stubtest_finds_the_stub_true_to_the_module(tmp_path):
    # The class' metaclass (pybind11's) is no stub's business: only that error is allowed.
    (tmp_path / "allow.txt").write_text("pcl_ncut_seg.Segmenter\n")
    run = run_mypy_tool(tmp_path, "--mypy-config-file", "mypy.stubtest", "--allowlist", str(tmp_path / "allow.txt"),
                        "pcl_ncut_seg")
    assert run.returncode == 0, run.stdout + run.stderr


def test_a_type_checker_knows_the_parameters(tmp_path):
    rows = pcl_ncut_seg.parameter_table()
    number = next(r["name"] for r in rows if r["kind"] == "integer")
    choice = next(r for r in rows if r["kind"] == "choice")
    good = [f"pcl_ncut_seg.segment(points, {number}=3)",
            f"seg = pcl_ncut_seg.Segmenter({choice['name']}={choice['choices'][0]!r})",
            f"seg.{number} = 4",
            "labels: npt.NDArray[np.int32] = seg.segment(points)"]
    bad = [f"pcl_ncut_seg.segment(points, {number}='many')",
           f"pcl_ncut_seg.Segmenter({choice['name']}='no such choice')",
           "pcl_ncut_seg.segment(points, no_such_parameter=1)",
           f"seg.{number} = 'many'"]
    lines = ["import numpy as np", "import numpy.typing as npt", "import pcl_ncut_seg",
             "points = np.zeros((10, 3))"] + good + bad
    (tmp_path / "use.py").write_text("\n".join(lines) + "\n")
    run = run_mypy_tool(tmp_path, "--config-file", "mypy", "use.py")
    flagged = {int(m) for m in re.findall(r"^use\.py:(\d+): error", run.stdout, re.M)}
    first_bad = len(lines) - len(bad) + 1
    assert flagged == set(range(first_bad, len(lines) + 1)), run.stdout

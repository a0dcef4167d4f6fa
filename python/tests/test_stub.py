"""The type stub (__init__.pyi) beside the module that is imported: up to date with the module,
and saying what the module takes, with every name and default read from the module's
parameter table at run time."""
import ast
import math
import os

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

"""The type stubs (waam_twin/_core.pyi) match the module: the same classes, functions, methods and properties, and
the same parameter names; and every public name has a docstring."""
import ast
import inspect
import pathlib
import re

import waam_twin as wt
from waam_twin import _core


def stub_tree():
    return ast.parse((pathlib.Path(_core.__file__).parent / "_core.pyi").read_text())


def runtime_params(function):
    """The parameter names of a pybind11 function, from the signature line pybind11 puts first in __doc__."""
    first = function.__doc__.splitlines()[0]
    match = re.match(r"\w+\((.*)\) ->", first)
    assert match, first
    return [p.split(":")[0].strip() for p in match.group(1).split(",") if p.strip()]


def stub_params(node):
    return [a.arg for a in node.args.args if a.arg != "self"]


def test_stubs_name_what_the_module_has():
    tree = stub_tree()
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    runtime = {n for n in dir(_core) if not n.startswith("__")}
    assert set(functions) | set(classes) == runtime
    for name, node in functions.items():
        assert stub_params(node) == runtime_params(getattr(_core, name)), name
    for name, node in classes.items():
        cls = getattr(_core, name)
        if issubclass(cls, Exception):
            continue
        members = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
        members.update({t.id: None for n in node.body if isinstance(n, ast.AnnAssign) for t in [n.target]})
        public = {m for m in vars(cls) if not m.startswith("_")}
        if cls is _core.CheckResult:
            public.add("violations")  # added by the package (waam_twin/__init__.py)
        assert set(m for m in members if not m.startswith("_")) == public, name
        for member, fn in members.items():
            attr = inspect.getattr_static(cls, member, None)
            if fn is not None and not member.startswith("_") and callable(attr) and not isinstance(attr, property):
                assert stub_params(fn) == runtime_params(getattr(cls, member))[1:], f"{name}.{member}"


def test_every_public_name_has_a_docstring():
    for name in wt.__all__:
        obj = getattr(wt, name)
        assert obj.__doc__ and len(obj.__doc__.strip()) > 20, name
    assert "as `waam plan` does" in wt.plan.__doc__

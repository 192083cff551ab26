# SPDX-License-Identifier: Apache-2.0
# The type stubs (mrhaptics/__init__.pyi) name exactly what the module has, with docstrings.
import ast
import inspect
import pathlib

import pytest

import mrhaptics

STUB = pathlib.Path(mrhaptics.__file__).with_name("__init__.pyi")


def stub_names():
    """{top-level name: set of public member names (for classes) or None}."""
    tree = ast.parse(STUB.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name for n in node.body
                                if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
        elif isinstance(node, ast.AnnAssign) and not node.target.id.startswith("_") or (
                isinstance(node, ast.AnnAssign) and node.target.id == "__version__"):
            names[node.target.id] = None
    return names


def public_members(cls):
    return {name for name in dir(cls) if not name.startswith("_")}


def test_stub_names_are_the_module_names():
    assert set(stub_names()) == set(mrhaptics.__all__)


@pytest.mark.parametrize("cls", ["Engine", "Result", "Session"])
def test_stub_members_are_the_class_members(cls):
    assert stub_names()[cls] == public_members(getattr(mrhaptics, cls))


@pytest.mark.parametrize("name", sorted(set(mrhaptics.__all__) - {"__version__"}))
def test_every_public_name_has_a_docstring(name):
    obj = getattr(mrhaptics, name)
    assert inspect.getdoc(obj), name
    for member in (public_members(obj) if inspect.isclass(obj) else ()):
        assert inspect.getdoc(getattr(obj, member)), f"{name}.{member}"

"""The typed stub installed beside the module names what the module has, and everything has a docstring."""
import ast
import pathlib

import terrasynth


def stub_names():
    stub = pathlib.Path(terrasynth.__file__).with_name("terrasynth.pyi")
    assert stub.is_file(), f"{stub}: the build copies python/terrasynth.pyi beside the module"
    tree = ast.parse(stub.read_text())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
    return top, members


def public(obj):
    return {n for n in dir(obj) if not n.startswith("_")}


def test_the_stub_names_every_public_function_class_and_member():
    top, members = stub_names()
    module_top = {n for n in public(terrasynth) if callable(getattr(terrasynth, n))}
    assert top == module_top
    for cls in ("Project", "Session"):
        assert members[cls] == public(getattr(terrasynth, cls)), cls


def test_everything_public_has_a_docstring():
    assert terrasynth.__doc__ and terrasynth.__version__
    for owner in (terrasynth, terrasynth.Project, terrasynth.Session):
        for name in public(owner):
            member = getattr(owner, name)
            lines = [line for line in (member.__doc__ or "").splitlines() if line.strip()]
            # pybind11 puts a function's signature first: the docstring is what follows it.
            if not isinstance(member, (property, type)):
                lines = lines[1:]
            assert lines, f"{getattr(owner, '__name__', owner)}.{name} has no docstring"

"""The layer rules of docs/internals.md, read from the source (ast, so imports inside functions count):

* no import cycle among velpoly's modules, not even through an import inside a function;
* matplotlib is imported only under velpoly/render/ (the kernel, the reports and html.py import none);
* only the command line prints or exits: no ``print(``, ``exit(``, ``quit(``, ``sys.exit``, and no
  ``sys.stdout`` / ``sys.stderr`` outside velpoly/cli.py and velpoly/__main__.py (the ``python -m
  velpoly`` shim that calls cli.main; doctests are strings, not code, so they may print);
* every module is in one layer of LAYERS, and docs/internals.md names it (its layer table says the same
  layers as LAYERS); no import upwards but the few docs/internals.md lists;
* no module uses another module's private name (``from .x import _y``, ``x._y``);
* no function or method over 60 lines unless its docstring says why ("Long because ...").
"""
from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "velpoly"
COMMAND_LINE = {"velpoly.cli", "velpoly.__main__"}   # the only modules that print or exit
# every rule reads the same trees: parsed and walked once per worker (the module's tests on one worker)
pytestmark = pytest.mark.xdist_group("layers")


@functools.cache
def _parsed(path: str, text: str) -> tuple[ast.Module, tuple]:
    tree = ast.parse(text, path)
    return tree, tuple(ast.walk(tree))


def tree(path: Path) -> ast.Module:
    """The module's syntax tree, parsed once for each text it has (read only)."""
    return _parsed(str(path), path.read_text(encoding="utf-8"))[0]


def nodes(path: Path) -> tuple:
    """``ast.walk`` of the module's tree, in its order, walked once for each text the file has."""
    return _parsed(str(path), path.read_text(encoding="utf-8"))[1]


def modules(package: Path) -> dict[str, Path]:
    """Every module of the package under ``package``: dotted name -> file."""
    out = {}
    for path in sorted(package.rglob("*.py")):
        parts = path.relative_to(package.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def imported(name: str, path: Path, node) -> list[str]:
    """The modules an import statement names (``from . import x`` names the package and ``x``)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if node.level:   # relative: from the module's package, one level up for each dot after the first
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        base = ".".join(package[:len(package) - node.level + 1])
        target = base + ("." + node.module if node.module else "")
    else:
        target = node.module
    return [target] + [f"{target}.{a.name}" for a in node.names]


def import_graph(package: Path = PACKAGE) -> tuple[dict[str, set], dict[str, list]]:
    """(module -> the package's modules it imports anywhere in its code, module -> [(line, module
    named)] for every import, also of modules outside the package)."""
    mods = modules(package)
    edges, named = {}, {}
    for name, path in mods.items():
        edges[name], named[name] = set(), []
        for node in nodes(path):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                for target in imported(name, path, node):
                    named[name].append((node.lineno, target))
                    if target in mods and target != name:
                        edges[name].add(target)
    return edges, named


def cycles(edges: dict[str, set]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each as a sorted list."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def test_no_import_cycle_not_even_inside_functions():
    edges, _ = import_graph()
    # the walk sees imports inside functions: to_dict imports the constructions where it needs them
    assert "velpoly.poles" in edges["velpoly.solution"] and "velpoly.polygons" in edges["velpoly.solution"]
    found = cycles(edges)
    assert not found, "import cycles: " + "; ".join(" <-> ".join(c) for c in found)


def package(tmp_path: Path, **files: str) -> Path:
    """A package ``pkg`` under ``tmp_path`` of the modules ``files`` (name -> source), for the rules' own tests."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    for name, text in {"__init__": "", **files}.items():
        (pkg / f"{name}.py").write_text(text)
    return pkg


def test_the_cycle_finder_finds_a_cycle_through_a_function_level_import(tmp_path):
    pkg = package(tmp_path, a="from .b import f\n", b="def f():\n    from . import c\n", c="import pkg.a\n",
                  d="from .a import f\n")
    edges, _ = import_graph(pkg)
    assert cycles(edges) == [["pkg.a", "pkg.b", "pkg.c"]]


def test_matplotlib_only_under_render():
    _, named = import_graph()
    outside = [f"{mod} line {line}" for mod, imports in named.items() for line, target in imports
               if target.split(".")[0] == "matplotlib" and not mod.startswith("velpoly.render")]
    assert not outside, "matplotlib imported outside velpoly/render/: " + ", ".join(outside)
    assert any(t.startswith("matplotlib") for _, t in named["velpoly.render.sweep"])   # the rule sees them


def output_calls(tree) -> list[tuple[int, str]]:
    """Where code prints or exits: calls of print/exit/quit, and any use of sys.exit, sys.stdout or
    sys.stderr (also as ``from sys import ...``)."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("print", "exit", "quit"):
            out.append((node.lineno, node.func.id + "("))
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "sys" \
                and node.attr in ("exit", "stdout", "stderr"):
            out.append((node.lineno, "sys." + node.attr))
        elif isinstance(node, ast.ImportFrom) and node.module == "sys":
            out += [(node.lineno, "from sys import " + a.name) for a in node.names
                    if a.name in ("exit", "stdout", "stderr")]
    return out


def test_only_the_command_line_prints_or_exits():
    found = []
    for name, path in modules(PACKAGE).items():
        if name in COMMAND_LINE:
            continue
        found += [f"{name} line {line}: {what}"
                  for line, what in output_calls(tree(path))]
    assert not found, "output outside velpoly/cli.py: " + "; ".join(found)


@pytest.mark.parametrize("code, hits", [
    ("print('x')", 1), ("import sys\nsys.stderr.write('x')", 1), ("from sys import exit", 1),
    ("def f():\n    '''>>> print(1)'''\n", 0), ("s = 'print(x)'", 0)])
def test_the_output_rule_sees_prints_and_not_doctests(code, hits):
    assert len(output_calls(ast.parse(code))) == hits


# The layers of docs/internals.md, from the bottom; a module under a package named here (velpoly.loader.*)
# is in its package's layer. Every module is named (test_every_module_is_in_a_layer_and_in_the_docs).
LAYERS = (
    ("kernel", ("errors", "names", "model", "loader", "geometry", "rigid", "jet", "constraints", "dyads", "pose",
                "kinematics", "motion", "driver", "solution", "sweeps", "centrodes", "arguments", "fileio", "frozen")),
    ("constructions", ("polygons", "poles", "reference")),
    ("comparison and tables", ("tables", "compare", "report")),
    ("figures", ("render", "html")),
    ("commands", ("cli", "gallery", "__main__")),
)
# The imports upwards docs/internals.md lists, each inside the one function that needs it.
UPWARDS = {
    ("velpoly.solution", "velpoly.poles"), ("velpoly.solution", "velpoly.polygons"),   # to_dict's sections
    ("velpoly.solution", "velpoly.report"),          # Solution._repr_html_, a notebook's view
    ("velpoly.model", "velpoly.render"),             # Mechanism._repr_svg_, a notebook's view
    ("velpoly.loader.reference", "velpoly.reference"),      # the [reference] keys' check
    ("velpoly.loader.drawing", "velpoly.render.options"),   # the [drawing] table's rules (no matplotlib)
}


def layer_of(module: str) -> int | None:
    parts = module.split(".")
    if len(parts) < 2:
        return 0   # the package itself: its __init__ imports errors only, the API's names on first use
    for rank, (_, names) in enumerate(LAYERS):
        if parts[1] in names:
            return rank
    return None


def test_no_import_upwards_but_the_listed_ones():
    edges, _ = import_graph()
    upwards = {(m, t) for m, targets in edges.items() for t in targets
               if layer_of(m) is not None and layer_of(t) is not None and layer_of(t) > layer_of(m)}
    assert upwards - UPWARDS == set(), "imports upwards (docs/internals.md's layers): " + ", ".join(
        f"{m} -> {t}" for m, t in sorted(upwards - UPWARDS))


DOCS = PACKAGE.parent / "docs" / "internals.md"


def test_every_module_is_in_a_layer_and_in_the_docs():
    """Each module has its layer in LAYERS and a row (under loader/, a mention in loader/'s row) in
    docs/internals.md's module table; the docs' layer table lists LAYERS' names, layer by layer."""
    mods = modules(PACKAGE)
    assert [m for m in mods if layer_of(m) is None] == [], "modules in no layer of LAYERS"
    rows = [line for line in DOCS.read_text(encoding="utf-8").splitlines() if line.startswith("| ")]
    loader_row = next(r for r in rows if r.startswith("| `loader/`"))
    missing = []
    for path in mods.values():
        rel = path.relative_to(PACKAGE).as_posix()
        if path.name == "__init__.py" or (rel.startswith("loader/") and f"`{path.name}`" in loader_row):
            continue
        if not any(f"`{rel}`" in r.split(" | ")[0] for r in rows):
            missing.append(rel)
    assert missing == [], "modules docs/internals.md's table does not name: " + ", ".join(missing)
    layer_rows = {r.split(" | ")[0].strip("| "): r.split(" | ")[1] for r in rows if r.count(" | ") == 2}
    for layer, names in LAYERS:
        documented = {n.removesuffix(".py").removesuffix("/") for n in re.findall(r"`([^`]+)`", layer_rows[layer])}
        assert documented == set(names), f"layer {layer}: docs {sorted(documented)}, LAYERS {sorted(names)}"


# Private names of another module in use, each with the helper whose files they are in (issue 19).
FOREIGN_PRIVATE_ALLOWED: set[tuple[str, str]] = set()


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def foreign_private_names(package: Path = PACKAGE) -> set[tuple[str, str]]:
    """(module, dotted private name) for each ``from .x import _y`` and ``x._y`` where ``x`` is another
    module of the package (dunder names are not private)."""
    mods = modules(package)
    out = set()
    for name, path in mods.items():
        walked = nodes(path)
        aliases = {}   # local name -> the package's module it is bound to
        for node in walked:
            if isinstance(node, ast.ImportFrom):
                base = imported(name, path, node)[0]
                out |= {(name, f"{base}.{a.name}") for a in node.names if _private(a.name) and base != name}
                aliases.update({a.asname or a.name: f"{base}.{a.name}" for a in node.names
                                if f"{base}.{a.name}" in mods})
            elif isinstance(node, ast.Import):
                aliases.update({a.asname: a.name for a in node.names if a.asname and a.name in mods})
        out |= {(name, f"{aliases[node.value.id]}.{node.attr}") for node in walked
                if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and _private(node.attr)
                and aliases.get(node.value.id, name) != name}
    return out


def test_no_module_uses_another_modules_private_names():
    found = foreign_private_names()
    assert found - FOREIGN_PRIVATE_ALLOWED == set(), "private names used across modules: " + ", ".join(
        f"{m} uses {n}" for m, n in sorted(found - FOREIGN_PRIVATE_ALLOWED))
    assert FOREIGN_PRIVATE_ALLOWED - found == set(), "no longer used: drop it from FOREIGN_PRIVATE_ALLOWED"


def test_the_private_name_rule_sees_both_forms(tmp_path):
    pkg = package(tmp_path, a="def _f():\n    pass\n\n\ndef g():\n    _f()\n",
                  b="from .a import _f\nfrom . import a\nimport pkg.a as c\na.g()\nc.g()\nx = a.__name__\n")
    assert foreign_private_names(pkg) == {("pkg.b", "pkg.a._f")}
    (pkg / "b.py").write_text("from . import a\nimport pkg.a as c\nc._f()\n")
    assert foreign_private_names(pkg) == {("pkg.b", "pkg.a._f")}


# Functions over LONGEST lines that the helper owning their file is asked to split (issue 19, item 4);
# the test fails when one is split (drop it here then) as when a new one appears.
LONGEST = 60
LONG_ALLOWED: set[str] = set()


def long_functions(package: Path = PACKAGE, longest: int = LONGEST) -> dict[str, int]:
    """Every function or method (nested ones too) over ``longest`` lines, from its ``def`` to its
    last line, whose docstring does not say why ("Long because ..."): dotted name -> lines."""
    out = {}

    def walk(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = child.end_lineno - child.lineno + 1
                if lines > longest and "long because" not in (ast.get_docstring(child) or "").lower():
                    out[f"{prefix}.{child.name}"] = lines
                walk(child, f"{prefix}.{child.name}")
            else:
                walk(child, f"{prefix}.{child.name}" if isinstance(child, ast.ClassDef) else prefix)
    for name, path in modules(package).items():
        walk(tree(path), name)
    return out


def test_no_function_over_60_lines_unless_its_docstring_says_why():
    found = long_functions()
    new = {k: v for k, v in found.items() if k not in LONG_ALLOWED}
    assert new == {}, "functions over 60 lines (split them, or say why in the docstring): " + ", ".join(
        f"{k} ({v} lines)" for k, v in sorted(new.items()))
    assert LONG_ALLOWED - set(found) == set(), "now short (or explained): drop it from LONG_ALLOWED"


def test_the_length_rule_counts_lines_and_reads_the_why(tmp_path):
    body = "".join(f"    x{i} = {i}\n" for i in range(60))   # with its def, a function of 61 lines
    pkg = package(tmp_path, a=(
        f"def f():\n{body}\n\ndef g():\n{body[:body.rindex('    x')]}\n\nclass C:\n    def h(self):\n{body.replace('    ', '        ')}"
        f"\n\ndef k():\n    'One sequence. Long because it is one.'\n{body}"))
    assert long_functions(pkg) == {"pkg.a.f": 61, "pkg.a.C.h": 61}

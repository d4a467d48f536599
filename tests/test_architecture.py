"""The package is a pipeline: imports point down it, never back, and never in a circle.

Read with the standard library's ``ast`` over every module of the package (imports
inside functions and under ``TYPE_CHECKING`` included), so a deferred import cannot
hide a circle.
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "davies_sym"

#: The stages in pipeline order; a module may import its own stage and the ones before.
STAGES = (
    "errors",
    "caches",
    "option_types",
    "progress",
    "fan_out",
    "algebra",
    "losses",
    "topology",
    "geometry",
    "network",
    "efficiency",
    "machines",
    "emit",
    "calibration",
    "synthesis",
    "atlas",
    "cli",
    "__init__",
)


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _stage(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _imports() -> dict[str, list[tuple[str, tuple[str, ...], int]]]:
    """module -> [(imported module, names, line)] for every import of the package itself."""
    out: dict[str, list[tuple[str, tuple[str, ...], int]]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        module = _module_name(path)
        is_package = path.name == "__init__.py"
        found = out.setdefault(module, [])
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = module.split(".")
                    base = base[: len(base) - node.level + (1 if is_package else 0)]
                    target = ".".join([*base, node.module] if node.module else base)
                else:
                    target = node.module or ""
                if target.split(".")[0] == "davies_sym":
                    found.append((target, tuple(a.name for a in node.names), node.lineno))
            elif isinstance(node, ast.Import):
                found += [(a.name, (), node.lineno) for a in node.names if a.name.split(".")[0] == "davies_sym"]
    return out


def test_every_stage_is_a_package_with_a_docstring_saying_what_it_owns() -> None:
    for stage in STAGES:
        if stage in ("errors", "caches", "option_types", "progress", "fan_out", "__init__"):
            assert (PACKAGE / f"{stage}.py").exists()
            continue
        init = PACKAGE / stage / "__init__.py"
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8")))
        assert doc and len(doc) > 80, f"{stage}/__init__.py needs a docstring saying what the stage owns"
    found = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert found <= set(STAGES), f"a package outside the pipeline: {found - set(STAGES)}"


def test_no_import_circle() -> None:
    graph = nx.DiGraph()
    for module, imports in _imports().items():
        graph.add_node(module)
        for target, names, _ in imports:
            # `from package import module` imports the module; otherwise the named module.
            for name in names or ("",):
                submodule = f"{target}.{name}"
                graph.add_edge(
                    module, submodule if (PACKAGE.parent / (submodule.replace(".", "/") + ".py")).exists() else target
                )
    cycles = list(nx.simple_cycles(graph))
    # A package's __init__ importing its own modules is how a package exposes them,
    # not a circle through the code.
    cycles = [
        c
        for c in cycles
        if not any(m.count(".") < 2 and c[(i + 1) % len(c)].startswith(m + ".") for i, m in enumerate(c))
    ]
    assert not cycles, f"import circles: {cycles}"


def test_imports_point_down_the_pipeline() -> None:
    wrong = []
    for module, imports in _imports().items():
        rank = STAGES.index(_stage(module))
        for target, _, line in imports:
            if target == "davies_sym" and module != "davies_sym":
                wrong.append(f"{module}:{line} imports the package root (import the stage module instead)")
            elif STAGES.index(_stage(target)) > rank:
                wrong.append(f"{module}:{line} imports {target}, a later stage")
    assert not wrong, "\n".join(wrong)


def test_no_stage_reaches_into_another_stages_private_names() -> None:
    wrong = []
    for module, imports in _imports().items():
        for target, names, line in imports:
            if _stage(target) != _stage(module):
                wrong += [f"{module}:{line} imports {target}.{n}" for n in names if n.startswith("_")]
    assert not wrong, "\n".join(wrong)


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.py")), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_modules_stay_small(path: Path) -> None:
    """A module of one job stays readable: at most 450 lines."""
    assert len(path.read_text(encoding="utf-8").splitlines()) <= 450


def test_public_api_is_listed() -> None:
    import davies_sym

    assert set(davies_sym.__all__) >= {
        "load",
        "loads",
        "analyse",
        "derive",
        "Train",
        "Analysis",
        "VariantSet",
        "DaviesError",
        "InputError",
        "TopologyError",
        "GeometryError",
    }
    for name in davies_sym.__all__:
        assert hasattr(davies_sym, name), name


def _kind_modules() -> set[str]:
    """The modules that may test a coupling's class: those of the kind classes (and their
    bases) the registry holds, and the registry, which answers the stages' questions by
    kind (`davies_sym.topology.coupling_kinds`)."""
    from davies_sym.topology.coupling_kinds import KINDS
    from davies_sym.topology.couplings import Coupling

    modules = {"davies_sym.topology.coupling_kinds"}
    modules |= {base.__module__ for kind in KINDS.values() for base in kind.__mro__ if issubclass(base, Coupling)}
    return {m.removeprefix("davies_sym.").replace(".", "/") + ".py" for m in modules}


def _coupling_classes() -> set[str]:
    from davies_sym.topology.coupling_kinds import KINDS
    from davies_sym.topology.couplings import Coupling

    return {base.__name__ for kind in KINDS.values() for base in kind.__mro__ if issubclass(base, Coupling)}


def _classes_tested(node: ast.Call) -> set[str]:
    """The class names ``isinstance(x, C)`` or ``isinstance(x, (C, D))`` tests."""
    if not (isinstance(node.func, ast.Name) and node.func.id == "isinstance" and len(node.args) == 2):
        return set()
    second = node.args[1]
    parts = second.elts if isinstance(second, ast.Tuple) else [second]
    return {p.id if isinstance(p, ast.Name) else p.attr for p in parts if isinstance(p, (ast.Name, ast.Attribute))}


def test_no_stage_dispatches_on_a_coupling_class() -> None:
    """What a coupling kind is lives in its kind module: a stage asks the registry for a
    train's meshes or bearings, and a coupling for its own members, never tests its class."""
    classes = _coupling_classes()
    assert {"GearMesh", "Revolute", "Prismatic", "SkewMesh"} <= classes
    kind_modules = _kind_modules()
    assert {"topology/gear_mesh.py", "topology/couplings.py", "topology/coupling_kinds.py"} <= kind_modules
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        if relative in kind_modules:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and _classes_tested(node) & classes:
                found.append(f"{relative}:{node.lineno}")
    assert not found, f"isinstance on a coupling class outside the kind modules: {found}"

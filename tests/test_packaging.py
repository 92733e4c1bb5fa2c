"""What imports under ``axlebox``: its own modules, the five subpackages and the configs, and
nothing else of the checkout (issue 35: the old ``__path__`` extension made ``axlebox.tests``,
``axlebox.build...`` and ``axlebox.axlebox`` importable, the last with a second ParameterError)."""
import importlib
import pkgutil

import pytest

import axlebox

SUBPACKAGES = ("geometry", "fem", "mbs", "bearing", "pipelines", "configs")


@pytest.mark.parametrize("name", SUBPACKAGES)
def test_the_subpackages_import_under_axlebox(name):
    mod = importlib.import_module(f"axlebox.{name}")
    assert mod.__name__ == f"axlebox.{name}"


@pytest.mark.parametrize("name", ["tests", "benchmarks", "docs", "build", "axlebox"])
def test_nothing_else_of_the_checkout_imports_under_axlebox(name):
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(f"axlebox.{name}")


def test_the_package_folder_holds_only_its_own_modules():
    """``axlebox.__path__`` is the package's own folder; what it lists is private modules and the
    command line's entry, and ParameterError is one class wherever it is reached from."""
    assert len(axlebox.__path__) == 1
    names = {m.name for m in pkgutil.iter_modules(axlebox.__path__)}
    assert names <= {"__main__", "_cache", "_figures", "_files", "_numba", "_params", "_progress",
                     "_threads"}, names
    from axlebox._params import ParameterError
    from axlebox.mbs.vehicle.config import ParameterError as via_mbs
    assert axlebox.ParameterError is ParameterError is via_mbs


def test_each_shipped_config_is_summed_up_in_a_whole_sentence():
    """`axlebox configs` lists each shipped config by the first sentence of its opening comment:
    an abbreviation's full stop ("its Fig. 1b") does not end it."""
    from axlebox import configs
    for name in configs.names():
        s = configs.summary(name)
        assert s.endswith(".") and s.count("(") == s.count(")"), (name, s)
    assert "Fig. 1b" in configs.summary("field_64kmh")
    assert configs.summary("field_64kmh").endswith("64.5 km/h.")


def _sibling_imports(package) -> dict[str, set[str]]:
    """Each module of ``package`` -> the sibling modules it imports, at any depth of its code
    (lazy imports inside functions and ``if TYPE_CHECKING:`` blocks count: both tie the files)."""
    import ast
    import pathlib
    graph = {}
    for path in pathlib.Path(package.__path__[0]).glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                deps |= {node.module.split(".")[0]} if node.module else {a.name for a in node.names}
        graph[path.stem] = deps - {path.stem}
    return graph


def test_the_diagnostics_import_one_way():
    """Issue 57: the thresholds import nothing of the diagnosis, and the modules import in one
    direction, thresholds -> indicators -> verdict -> criterion -> pair (before, criterion,
    verdict, channel, coherence, gate, own and wheel imported each other in a circle)."""
    import graphlib

    import axlebox.bearing.diagnostics as diagnostics
    graph = _sibling_imports(diagnostics)
    order = list(graphlib.TopologicalSorter(graph).static_order())    # CycleError on a circle
    assert graph["thresholds"] == set()
    for indicator in ("channel", "coherence", "gate", "own", "wheel"):
        assert "thresholds" in graph[indicator] or indicator == "own", indicator
        assert order.index(indicator) < order.index("verdict"), indicator
    assert order.index("thresholds") < order.index("verdict") < order.index("criterion") \
        < order.index("pair")



def _mbs_imports(root) -> dict[str, set[str]]:
    """Each module of the mbs folder ``root`` (``folder.module``) -> the modules of it that it
    imports, at any depth of its code (lazy imports and ``if TYPE_CHECKING:`` blocks count),
    relative or absolute (``axlebox.mbs...``), a package standing for its ``__init__``."""
    import ast

    def known(m):                # a name imported from a module is not a module
        where = root / "/".join(m)
        return bool(m) and (where.is_dir() or where.with_suffix(".py").is_file())
    graph = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        here = parts[:-1] if parts[-1] == "__init__" else parts
        package = here if parts[-1] == "__init__" else here[:-1]
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                base = list(package[:len(package) - (node.level - 1)]) + (node.module or "").split(".")
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("axlebox.mbs"):
                base = node.module.split(".")[2:]
            elif isinstance(node, ast.Import):
                deps |= {".".join(m) for a in node.names if a.name.startswith("axlebox.mbs")
                         for m in [a.name.split(".")[2:]] if known(m)}
                continue
            else:
                continue
            base = [b for b in base if b]
            deps |= {".".join(m) for m in [base] + [base + [a.name] for a in node.names] if known(m)}
        graph[".".join(here) or "__init__"] = deps - {".".join(here)}
    return graph


#: what each folder of mbs/ may import of the others (issue 68): the kernels below the solver, the
#: solver below the vehicle; the track, the wheel-rail contact and the post-processing below the
#: vehicle, each importing no other folder (the kernels read the wheel-rail element's kernel)
MBS_LAYERS = {"wheelrail": set(), "track": set(), "post": set(), "kernel": {"wheelrail"},
              "solver": {"kernel", "wheelrail"}, "vehicle": {"solver", "kernel", "track", "wheelrail"}}


def _upward(graph) -> list[str]:
    """The imports of ``graph`` that break :data:`MBS_LAYERS` (the package's ``__init__``
    imports nothing of it)."""
    bad = []
    for module, deps in sorted(graph.items()):
        folder = module.split(".")[0]
        allowed = set() if module == "__init__" else MBS_LAYERS.get(folder, set()) | {folder}
        bad += [f"{module} imports {d}" for d in sorted(deps) if d.split(".")[0] not in allowed]
    return bad


def test_mbs_is_laid_out_by_role_and_imports_one_way():
    """mbs/ is folders by role, each with its ``__init__``, and nothing else but that
    ``__init__``; no folder imports one above it (:data:`MBS_LAYERS`) and no modules import each
    other in a circle (issue 68 cut the one between the track's irregularity and roughness)."""
    import graphlib
    import pathlib

    import axlebox.mbs as mbs
    root = pathlib.Path(mbs.__path__[0])
    assert {p.name for p in root.glob("*.py")} == {"__init__.py"}
    assert {p.name for p in root.iterdir() if p.is_dir() and p.name != "__pycache__"} == set(MBS_LAYERS)
    assert all((root / d / "__init__.py").is_file() for d in MBS_LAYERS)
    graph = _mbs_imports(root)
    assert {"kernel.system", "solver.integrate", "track.roughness", "vehicle.config"} <= set(graph)
    assert "kernel.body" in graph["solver.system"] and "track.bed" in graph["vehicle.config"]
    list(graphlib.TopologicalSorter(graph).static_order())               # CycleError on a circle
    assert _upward(graph) == []


def test_the_one_way_check_bites(tmp_path):
    """An upward import is seen however it is written: a kernel importing the solver (relative,
    inside a function), the track the vehicle's config (absolute, for types only), and two
    modules of the track importing each other."""
    import graphlib

    for d in MBS_LAYERS:
        (tmp_path / d).mkdir()
        (tmp_path / d / "__init__.py").write_text("")
    (tmp_path / "solver" / "system.py").write_text("from ..kernel import body\n")
    (tmp_path / "kernel" / "body.py").write_text("def f():\n    from ..solver import system\n")
    (tmp_path / "vehicle" / "config.py").write_text("from axlebox.mbs.track.bed import MODELS\n")
    (tmp_path / "track" / "bed.py").write_text(
        "if TYPE_CHECKING:\n    from axlebox.mbs.vehicle.config import Track\n")
    (tmp_path / "track" / "a.py").write_text("from . import b\n")
    (tmp_path / "track" / "b.py").write_text("from .a import x\n")
    graph = _mbs_imports(tmp_path)
    assert graph["solver.system"] == {"kernel", "kernel.body"}
    assert _upward(graph) == ["kernel.body imports solver", "kernel.body imports solver.system",
                              "track.bed imports vehicle.config"]
    with pytest.raises(graphlib.CycleError):
        list(graphlib.TopologicalSorter(graph).static_order())


def test_every_folder_of_the_package_is_installed():
    """pyproject's package list names every folder that holds an ``__init__.py`` (a folder left
    out is missing from the wheel, though an editable install finds it)."""
    import pathlib
    import tomllib

    top = pathlib.Path(__file__).resolve().parents[1]
    listed = set(tomllib.loads((top / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    for sub in SUBPACKAGES:
        folder = top / ("axlebox" if sub == "axlebox" else sub)
        for init in folder.rglob("__init__.py"):
            rel = init.parent.relative_to(folder).parts
            assert ".".join(("axlebox", sub) + rel) in listed, init

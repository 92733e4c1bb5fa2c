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
    assert names <= {"__main__", "_cache", "_files", "_numba", "_params", "_threads"}, names
    from axlebox._params import ParameterError
    from axlebox.mbs.config import ParameterError as via_mbs
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

"""The bearing core reads its plain arrays by name (issue 49): every slot of the parameter vector,
the state, the ring motion, the contact outputs and the defect table is declared once
(bearing/kernel/layout.py, a model's own module) and no code of the bearing package or of the car's
bearing code indexes one by a number; its kernels are in parts of at most about 80 lines, and
one module knows the list of models."""
import ast
import pytest

from axlebox._cache import package_dir

BEARING = package_dir("bearing")
MBS = package_dir("mbs")
DECLARATIONS = {"layout.py", "vec.py"}        # the layout itself, and 3-vector components
CAR_BEARING_CODE = ("kernel/bearings.py", "vehicle/bearings.py", "kernel/exchange.py")


def _bearing_modules():
    """Every module of the bearing package but the diagnosis (which reads records, not slots)."""
    return [p for p in sorted(BEARING.rglob("*.py")) if "diagnostics" not in p.relative_to(BEARING).parts]


def _modules():
    mods = [p for p in _bearing_modules() if p.name not in DECLARATIONS]
    return mods + [MBS / n for n in CAR_BEARING_CODE]


def _numeric_indices(tree):
    """Subscripts whose index holds a bare integer (``x[3]``, ``y[:, 0]``, ``z[0:2]``); a
    shape's entries are not slots."""
    for node in ast.walk(tree):
        if not isinstance(node, ast.Subscript):
            continue
        if isinstance(node.value, ast.Attribute) and node.value.attr in ("shape", "strides"):
            continue
        parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        for e in parts:
            bounds = (e.lower, e.upper, e.step) if isinstance(e, ast.Slice) else (e,)
            if any(isinstance(b, ast.Constant) and type(b.value) is int for b in bounds):
                yield node
                break


@pytest.mark.parametrize("path", _modules(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_no_slot_is_read_by_number(path):
    found = [f"line {n.lineno}: {ast.unparse(n)}" for n in _numeric_indices(ast.parse(path.read_text()))]
    assert not found, "\n".join(found)


def test_the_check_bites():
    code = "def f(P, y, ring, D):\n    return P[0] + y[b0 + 6] + ring[1, 4] + D[d, 0] + y[:, 2:5].sum()\n"
    assert len(list(_numeric_indices(ast.parse(code)))) == 4     # not b0 + 6: an offset's sum
    assert not list(_numeric_indices(ast.parse("n = x.shape[0]\nv = y[RATE + RHO]\n")))


def _kernels(path):
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.FunctionDef) and any(
                "kernel" in ast.unparse(d) or "njit" in ast.unparse(d) or "overload" in ast.unparse(d)
                for d in node.decorator_list):
            yield node


@pytest.mark.parametrize("path", _modules(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_each_kernel_part_reads_on_one_screen(path):
    long = [(n.name, n.end_lineno - n.lineno + 1) for n in _kernels(path)
            if n.end_lineno - n.lineno + 1 > 80]
    assert not long, long


def test_one_module_knows_the_list_of_models():
    """bearing/models/__init__.py imports the models; the shared parts do not (the dispatch reads
    the registry, not the models; a model's numpy twin, bearing/kernel/numpy_twin.py, is the
    DTRB's own)."""
    from axlebox.bearing import models
    names = set(models.MODELS)
    importers = {}
    for path in _bearing_modules():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                got = {(node.module or "").split(".")[-1]} | {a.name for a in node.names}
                if node.level and got & names:
                    importers.setdefault(path.relative_to(BEARING).as_posix(), set()).update(got & names)
    allowed = {"models/__init__.py", "kernel/numpy_twin.py"} | {f"models/{n}.py" for n in names}
    assert set(importers) <= allowed, importers
    assert "models/__init__.py" in importers

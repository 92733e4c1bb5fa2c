"""The bearing models' contract (bearing/models/__init__.py, issue 58): what the shared parts read
from a model's module or from its parameters is declared once, in the registry's ``CONTRACT`` or
on ``RollerBearing`` (bearing/models/params.py); every model keeps it; a model that does not is
refused when the registry is imported, naming the model and what it lacks."""
import ast
import dataclasses
import math
import subprocess
import sys
import textwrap
import types

import numpy as np
import pytest

from axlebox._cache import package_dir
from axlebox._params import ParameterError
from axlebox.bearing import catalogue, models
from axlebox.bearing.rig import RIG_METHODS, RigConfig
from axlebox.bearing.models.params import GIVEN_BY_MODEL, RollerBearing

#: the modules that read a model or its parameters without knowing which model it is
CONSUMERS = {
    "bearing": ("catalogue.py", "defects.py", "frequencies.py", "models/__init__.py",
                "statics/quasistatic.py", "statics/equilibrium.py", "statics/stiffness.py",
                "kernel/layout.py"),
    "pipelines": ("config_reference.py",),
}
CONTRACT = tuple(part.name for part in models.CONTRACT)    # ordered: the same test ids on every worker


# ---- what a module reads from a model or its parameters (by the names it gives them) ------------

def _is_models(node) -> bool:
    """``MODELS`` or ``<registry>.MODELS``."""
    return (isinstance(node, ast.Name) and node.id == "MODELS") or \
        (isinstance(node, ast.Attribute) and node.attr == "MODELS")


def _model_expr(node, names) -> bool:
    """An expression that is a model's module: a name bound to one, ``module(p)`` or
    ``<registry>.module(p)``, ``MODELS[...]``."""
    if isinstance(node, ast.Name):
        return node.id in names
    if isinstance(node, ast.Call):
        f = node.func
        return (isinstance(f, ast.Name) and f.id == "module") or \
            (isinstance(f, ast.Attribute) and f.attr == "module")
    return isinstance(node, ast.Subscript) and _is_models(node.value)


def _model_names(tree) -> set[str]:
    """The names a module binds to a model's module: ``for name, m in MODELS.items()``, ``for m
    in MODELS.values()`` (loops and comprehensions), ``m = MODELS[...]``, ``m = module(p)``."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.For, ast.comprehension)) and isinstance(node.iter, ast.Call) \
                and isinstance(node.iter.func, ast.Attribute) and _is_models(node.iter.func.value):
            how, t = node.iter.func.attr, node.target
            if how == "items" and isinstance(t, ast.Tuple) and isinstance(t.elts[1], ast.Name):
                names.add(t.elts[1].id)
            elif how == "values" and isinstance(t, ast.Name):
                names.add(t.id)
        elif isinstance(node, ast.Assign) and _model_expr(node.value, set()):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return names


def _params_expr(node, models_, params_) -> bool:
    """Parameters: ``p`` (every consumer's name for them), a name bound to ``<model>.Params(...)``,
    or that call itself."""
    if isinstance(node, ast.Name):
        return node.id in params_
    return isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
        node.func.attr == "Params" and _model_expr(node.func.value, models_)


def reads(source: str) -> tuple[set[str], set[str]]:
    """``(module attributes, parameter attributes)`` the source reads from a model."""
    tree = ast.parse(source)
    models_ = _model_names(tree)
    params_ = {"p"}
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and _params_expr(node.value, models_, set()):
            params_.update(t.id for t in node.targets if isinstance(t, ast.Name))
    on_module, on_params = set(), set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.Attribute) or not isinstance(node.ctx, ast.Load) \
                or node.attr.startswith("__"):
            continue
        if _model_expr(node.value, models_):
            on_module.add(node.attr)
        elif _params_expr(node.value, models_, params_):
            on_params.add(node.attr)
    return on_module, on_params


def undeclared(on_module, on_params) -> list[str]:
    """What is read but declared neither in the registry's CONTRACT nor on RollerBearing."""
    return sorted([f"module.{n}" for n in on_module if n not in CONTRACT]
                  + [f"params.{n}" for n in on_params if not hasattr(RollerBearing, n)])


def _consumers():
    return [(package_dir(pkg) / rel, f"{pkg}/{rel}") for pkg, rels in CONSUMERS.items() for rel in rels]


@pytest.mark.parametrize("path, name", _consumers(), ids=[n for _, n in _consumers()])
def test_what_the_shared_parts_read_from_a_model_is_declared(path, name):
    on_module, on_params = reads(path.read_text())
    assert not undeclared(on_module, on_params), name


def test_the_readers_are_read():
    """The collection finds what each consumer is known to read (so that a consumer renamed
    its variables, or a collection that finds nothing, fails here, not silently)."""
    got = {name: reads(path.read_text()) for path, name in _consumers()}
    assert {"SUMMARY", "DEFAULTS", "Params"} <= got["bearing/catalogue.py"][0]
    assert {"SUMMARY", "DEFAULTS", "Params"} <= got["pipelines/config_reference.py"][0]
    assert {"NAME", "DT_MAX", "pack", "nominal_state", "orders", "BORE", "ring_stiffness"} \
        <= got["bearing/models/__init__.py"][0]
    assert "guess" in got["bearing/statics/equilibrium.py"][0]
    assert {"alpha_o", "clearance_n", "D_m", "Z"} <= got["bearing/statics/quasistatic.py"][1]
    assert {"D_o", "D_i", "L_e", "r_b"} <= got["bearing/defects.py"][1]
    assert {"alpha_o", "gamma"} <= got["bearing/frequencies.py"][1]
    assert {"L_e", "E_r"} <= got["bearing/catalogue.py"][1]
    assert {"alpha_m", "alpha_i", "alpha_c"} <= got["bearing/kernel/layout.py"][1]
    every = set().union(*(p for _, p in got.values()))
    assert set(GIVEN_BY_MODEL) <= every, set(GIVEN_BY_MODEL) - every     # none declared for nothing


def test_an_undeclared_read_is_found():
    """The check can fail: a consumer reading a name no model declares, from either side."""
    src = textwrap.dedent("""
        from . import models
        def f(p):
            return p.alpha_x + models.module(p).FOO + p.L_e
        def g():
            return [m.BAR for m in models.MODELS.values()] + [m.Params().beta_y
                                                               for _, m in models.MODELS.items()]
        q = models.MODELS["dtrb"].BAZ
        """)
    on_module, on_params = reads(src)
    assert undeclared(on_module, on_params) == ["module.BAR", "module.BAZ", "module.FOO",
                                                "params.alpha_x", "params.beta_y"]


# ---- every model keeps the contract -------------------------------------------------------------

KINDS = {"str": str, "number": float, "dict": dict}


@pytest.mark.parametrize("name", list(models.MODELS))
def test_each_model_keeps_the_contract(name):
    m = models.MODELS[name]
    for part in models.CONTRACT:
        v = getattr(m, part.name)
        if part.kind == "callable":
            assert callable(v), part.name
        elif part.kind == "class":
            assert issubclass(v, RollerBearing) and dataclasses.is_dataclass(v), part.name
        else:
            assert isinstance(v, KINDS[part.kind] if part.kind != "number" else (int, float)), part.name
    assert m.NAME == name and m.SUMMARY.strip() and m.DEFAULTS.strip() and 0 < m.BORE < 1
    assert set(m.DT_MAX) == set(models.SCHEMES)
    for steps in m.DT_MAX.values():
        assert steps and all(isinstance(k, str) and 0 < v < 1e-3 for k, v in steps.items())
    p = m.Params()
    assert type(p) is m.Params and models.module(p) is m and models.name(p) == name
    for attr in GIVEN_BY_MODEL:
        assert math.isfinite(getattr(p, attr)), attr
    v = m.pack(p)
    assert isinstance(v, np.ndarray) and v.ndim == 1 and v.dtype == np.float64 and np.isfinite(v).all()
    y = m.nominal_state(p, 10.0)
    assert y.shape == (models.n_state(p),) and np.isfinite(y).all()
    o = m.orders(p)
    assert 0 < o.FTF < 0.5 < o.BPFO < o.BPFI
    for scheme in models.SCHEMES:      # the registry's methods are the model's steps, by scheme
        assert models.methods(dataclasses.replace(p, model=scheme)) == m.DT_MAX[scheme]
    assert models.from_table(models.to_table(p)) == p


@pytest.mark.parametrize("name", list(models.MODELS))
def test_each_model_is_taken_by_name_and_its_steps_held(name):
    """``[bearing] type`` picks it; the rig refuses each method above the model's step, naming
    the field; the catalogue has it under its name (any case) with its orders and bore."""
    m = models.MODELS[name]
    assert type(models.from_table({"type": name})) is m.Params
    for scheme, steps in m.DT_MAX.items():
        p = m.Params(model=scheme)
        for method, dt in steps.items():
            if method in RIG_METHODS and 2 * dt <= 1e-4:          # RigConfig's own range of dt
                with pytest.raises(ParameterError, match=rf"RigConfig\.dt = {2 * dt:g} is not allowed"):
                    RigConfig(bearing=p, method=method, dt=2 * dt, fs_out=1 / (2 * dt))
    entry = catalogue.lookup(f" {name.upper()} ")
    assert entry.name == name and entry.bore == m.BORE and entry.orders == models.orders(m.Params())


def test_the_schemes_are_the_model_field_choices():
    (field,) = [f for f in dataclasses.fields(RollerBearing) if f.name == "model"]
    assert field.metadata["choices"] == models.SCHEMES


@pytest.mark.parametrize("attr", GIVEN_BY_MODEL)
def test_what_a_model_gives_is_refused_until_it_does(attr):
    """The base class declares what each model gives, refusing by the class's own name."""
    @dataclasses.dataclass(frozen=True)
    class Halfway(RollerBearing):
        pass
    with pytest.raises(NotImplementedError, match=rf"^Halfway does not give {attr} \("):
        getattr(Halfway(), attr)


# ---- a model that breaks it is refused ----------------------------------------------------------

def _fake(**changes):
    """A model module: the DTRB's declarations under the name "fake", with ``changes``
    (None: the name removed)."""
    m = types.ModuleType("fake_model")
    for part in models.CONTRACT:
        setattr(m, part.name, getattr(models.MODELS["dtrb"], part.name))
    m.NAME = "fake"
    for k, v in changes.items():
        if v is None:
            delattr(m, k)
        else:
            setattr(m, k, v)
    return m


def test_the_fake_model_passes_as_it_is():
    assert models.check(_fake(), "fake").NAME == "fake"


@dataclasses.dataclass(frozen=True)
class _NoAngles(RollerBearing):
    """Parameters that give none of GIVEN_BY_MODEL."""


class _NoRows(RollerBearing):
    """Parameters that give every number of GIVEN_BY_MODEL, and no row."""

    rows = 0
    alpha_o = alpha_i = alpha_m = clearance_n = 0.0
    L_e = D_o = D_i = 0.04


@pytest.mark.parametrize("changes, message", [
    *[({n: None}, rf"bearing model 'fake' \('fake_model'\) does not declare {n}: ") for n in CONTRACT],
    ({"NAME": 3}, r"NAME = 3 is not allowed: expected a non-empty string"),
    ({"NAME": "other"}, r"NAME = 'other' is not allowed: expected 'fake'"),
    ({"SUMMARY": ""}, r"SUMMARY = '' is not allowed"),
    ({"BORE": -0.1}, r"BORE = -0.1 is not allowed: expected a number > 0"),
    ({"guess": 1.0}, r"guess = 1.0 is not allowed: expected a function"),
    ({"Params": dict}, r"Params = <class 'dict'> is not allowed: expected a dataclass"),
    ({"DT_MAX": {"dynamic": {"rk4": 1e-5}}}, r"DT_MAX's keys \('dynamic',\) are not allowed"),
    ({"DT_MAX": {"dynamic": {"rk4": 1e-5}, "quasi-dynamic": {"imex": 1e-4}, "implicit": {}}},
     r"DT_MAX's keys \('dynamic', 'quasi-dynamic', 'implicit'\) are not allowed: expected dynamic, "
     r"quasi-dynamic, the schemes"),
    ({"DT_MAX": {"dynamic": {"rk4": 0.0}, "quasi-dynamic": {"imex": 1e-4}}},
     r"DT_MAX\['dynamic'\] = \{'rk4': 0.0\} is not allowed"),
    ({"DT_MAX": {"dynamic": {}, "quasi-dynamic": {"imex": 1e-4}}}, r"DT_MAX\['dynamic'\]"),
    ({"Params": _NoAngles}, r"'fake'.*_NoAngles does not give rows"),
    ({"Params": _NoRows}, r"'fake'.*_NoRows\(\)\.rows = 0 is not allowed: expected an integer >= 1"),
], ids=[f"no-{n}" for n in CONTRACT] + ["NAME-kind", "NAME-key", "SUMMARY-empty", "BORE", "guess",
                                         "Params-kind", "DT_MAX-scheme", "DT_MAX-extra", "DT_MAX-step",
                                         "DT_MAX-empty", "Params-angles", "Params-rows"])
def test_a_model_that_breaks_the_contract_is_refused_by_name(changes, message):
    with pytest.raises(models.ModelError, match=message):
        models.check(_fake(**changes), "fake")


def test_the_registry_checks_its_models_when_imported():
    """The single-row CRB's module with its ``guess`` taken away as it loads (the CRB: no other
    model takes its parts from it): importing the registry fails, naming the model and the
    missing name."""
    code = textwrap.dedent("""
        import importlib.abc, sys
        from importlib.machinery import PathFinder

        class Strip(importlib.abc.MetaPathFinder):
            def find_spec(self, name, path, target=None):
                if name != "axlebox.bearing.models.crb":
                    return None
                spec = PathFinder.find_spec(name, path)
                run = spec.loader.exec_module
                def exec_module(module):
                    run(module)
                    del module.guess
                spec.loader.exec_module = exec_module
                return spec

        sys.meta_path.insert(0, Strip())
        try:
            import axlebox.bearing.models
        except TypeError as err:
            print(type(err).__name__, err)
        else:
            print("imported")
        """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    assert r.stdout.startswith("ModelError bearing model 'crb' ('axlebox.bearing.models.crb') "
                               "does not declare guess: "), r.stdout

"""Compiling ahead (pipelines/ahead.py): the second process compiles for a stand-in car (rigid
bodies, no statics, bearings at a nominal load), which helps only if the kernels' types are the
real car's, and only if :func:`axlebox.mbs.solver.integrate.run_signature` gives the types the run
then calls with.  Both checked here on the validation car; that a run that found its kernels
compiled by the second process gives the run's bits is the kernel reference's check run cold
(tests/test_kernel_reference.py, and test_install.py's demo in a fresh cache)."""
import numba
import pytest

from axlebox.mbs.kernel import integrate as ki
from axlebox.mbs.solver import integrate
from axlebox.pipelines import ahead, simulate

CONFIG = "validation_48kmh"


@pytest.fixture(scope="module")
def cfg():
    return simulate.load_config(CONFIG, 0.0004)


def _types(model, s):
    W = model.W
    return tuple(numba.typeof(a) for a in (model.S, W, model.B, integrate.exchange_of(model, s)))


def test_the_rigid_stand_in_has_the_flexible_cars_kernel_types(cfg):
    flexible = ahead.stand_in(cfg, simulate.reduced_bodies(cfg, log=lambda *_: None))
    rigid = ahead.stand_in(cfg)
    assert any(b.n_modes for b in flexible.bodies) and not any(b.n_modes for b in rigid.bodies)
    s = cfg.settings()
    assert _types(rigid, s) == _types(flexible, s)
    assert integrate.run_signature(rigid, s)[1] == integrate.run_signature(flexible, s)[1]


def test_the_run_calls_its_kernel_with_the_signature_compiled_ahead(cfg, tmp_path):
    s = cfg.settings()
    expected = integrate.run_signature(ahead.stand_in(cfg), s)[1]
    simulate.run(cfg, tmp_path / "run.h5", log=lambda *_: None, ahead=False)
    assert expected in ki.run_leapfrog.signatures, (expected, ki.run_leapfrog.signatures)


@pytest.mark.skipif(bool(__import__("axlebox._numba", fromlist=["x"]).user_cache_dir()),
                    reason="the user chose numba's cache folder: ahead.wanted cannot look into it")
def test_a_warm_cache_starts_no_second_process(cfg, monkeypatch):
    """After the run above (or any session's), the run's kernel is in the cache: nothing to gain."""
    monkeypatch.delenv(ahead.ENV, raising=False)
    integrate.compile_run(ahead.stand_in(cfg), cfg.settings())
    assert not ahead.wanted()
    assert isinstance(ahead.start(cfg), ahead.NoAhead)
    monkeypatch.setenv(ahead.ENV, "0")
    assert not ahead.wanted()


def test_a_bad_setting_is_refused_naming_it(monkeypatch):
    from axlebox._params import ParameterError
    monkeypatch.setenv(ahead.ENV, "yes")
    with pytest.raises(ParameterError, match="AXLEBOX_COMPILE_AHEAD = 'yes' is not allowed"):
        ahead.wanted()

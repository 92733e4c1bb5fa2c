"""The single-row cylindrical roller bearing (bearing/models/crb.py, issue 58 item 6): one row of the
DCRB pair alone, declared by one module and one registry line.  Against closed forms: its static
load distribution with clearance against Harris's, its BPFO line on the rig against the kinematic
order; and against the DCRB it was cut from: alone under half the load, its row carries what each
of the pair's rows carries."""
import numpy as np
import pytest

from axlebox.bearing import models
from axlebox.bearing.defects import WIDTH, Defect
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.kernel import dispatch, layout
from axlebox.bearing.kernel.evaluate import rates
from axlebox.bearing.kernel.layout import Q_O
from axlebox.bearing.models.crb import CrbParams
from axlebox.bearing.models.dcrb import DcrbParams
from axlebox.bearing.rig import RigConfig, load, simulate
from axlebox.bearing.spectra import envelope_spectrum
from axlebox.bearing.statics import equilibrium, loaddist, stiffness

F_S = shaft_hz(48.0, 0.42)                        # 5.05 Hz
BAND = (500.0, 4500.0)                            # as the DCRB's rig tests
NO_DEFECTS = np.zeros((0, WIDTH))
F_ROW = 27e3                                      # N: the DCRB rig's 54 kN over its two rows


def test_one_row_sizes_the_kernels_arrays_and_shares_the_dcrbs_machine_code():
    """The model's ``rows`` sizes the state (12 slots a roller and a cage: 12 (Z + 1)), and the
    CRB runs on the DCRB's tag: the same contact law, so the same compiled kernels."""
    p = CrbParams()
    assert (p.rows, p.Z) == (1, 15)
    assert models.n_state(p) == 12 * (p.Z + 1) == models.nominal_state(p, 10.0).size
    rollers, cages = layout.views(models.nominal_state(p, 10.0), p.Z)
    assert rollers.shape == (1, 15, layout.N_ROLLER) and cages.shape == (1, layout.N_CAGE)
    assert type(dispatch.tag(p)) is type(dispatch.tag(DcrbParams()))
    assert models.pack(p)[layout.N_ROWS] == 1.0


def _static(p, F):
    """Uncrowned (a crown has no closed form), at rest under ``F`` down on the outer ring: the
    ring's radial approach and each row's outer-raceway loads."""
    P = models.pack(p)
    y, uo = equilibrium.static_state(p, P, NO_DEFECTS, (0.0, 0.0, -F), 1e-3)
    _, _, Qc, _ = rates(dispatch.tag(p), 0.0, y, equilibrium.ring_motion(1e-3, uo), P, NO_DEFECTS)
    return -uo[2], Qc[:, :, Q_O]


@pytest.fixture(scope="module")
def single():
    return _static(CrbParams(crown_drop=0.0), F_ROW)


def test_static_load_distribution_with_clearance_is_harris(single):
    """Harris and Kotzalas (Essential Concepts of Bearing Technology, 2007, sec. 7.2, eqs.
    7.19-7.21, 7.24), as for the DCRB (tests/test_dcrb.py): ``Q_max = K_n (delta_r - P_d / 2)^n``,
    a roller at psi ``Q_max (1 - (1 - cos psi) / (2 eps))^n``, ``eps = (1 - P_d / (2 delta_r)) /
    2``, the row's load ``Z Q_max J_r(eps)``.  Q_max within 1 %, the roller loads within 1 % of
    Q_max, the radial integral (a continuum for 15 rollers) within 3 % of the load."""
    p = CrbParams(crown_drop=0.0)
    d_r, Qo = single
    assert Qo.shape == (1, p.Z)
    E = stiffness.e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    K_n = stiffness.series(stiffness.k_line(E, p.L_we), stiffness.k_line(E, p.L_we))
    Q_max, Q_psi, eps = loaddist.radial_rollers(d_r, p.u_r, K_n, p.Z)
    assert Qo[0].max() == pytest.approx(Q_max, rel=0.01)
    assert np.abs(Qo[0] - Q_psi).max() < 0.01 * Q_max
    assert p.Z * Qo[0].max() * loaddist.J_r(eps) == pytest.approx(F_ROW, rel=0.03)
    assert 0.0 < eps < 0.5                                     # clearance: under half loaded


def test_one_row_alone_under_half_the_load_carries_what_each_row_of_the_pair_does(single):
    """The DCRB's rows under a radial load through the centre share it evenly: each of them is
    then the CRB under half the load, roller for roller (the same rollers, clearance and crown;
    within 0.1 % of the heaviest roller's load, the static start's tolerance)."""
    d_r, Qo = single
    d_pair, Q_pair = _static(DcrbParams(crown_drop=0.0), 2 * F_ROW)
    assert d_r == pytest.approx(d_pair, rel=1e-3)
    for row in (0, 1):
        assert np.abs(Q_pair[row] - Qo[0]).max() < 1e-3 * Qo.max()


def test_rig_outer_ring_defect_rings_at_bpfo():
    """A 30 x 2 mm outer-ring defect at the top of its row on the rig under the row's 27 kN (RK4,
    1e-5 s): the envelope spectrum's highest line in 5-300 Hz is within one bin of the kinematic
    BPFO (radial contacts, bearing/frequencies.py) and stands above 50 times the floor, as the
    DCRB's does (tests/test_dcrb.py)."""
    p = CrbParams()
    r = simulate(RigConfig(bearing=p, duration=0.6, F_r=F_ROW, defects=(Defect(W=2e-3, L=30e-3, row=1),)))
    assert r.Q.shape[1:3] == (1, p.Z) and r.cage.shape[1] == 1
    bpfo = models.orders(p).BPFO * F_S
    f, A = envelope_spectrum(r.acceleration[r.time >= 0.05, 2], r.fs, BAND)
    m = (f > 5) & (f < 300)
    assert abs(f[m][np.argmax(A[m])] - bpfo) <= f[1]
    near = np.abs(f - bpfo) <= f[1]
    assert A[near].max() > 50 * np.median(A[m])


def test_the_rig_command_runs_the_crb_and_refuses_a_second_row(tmp_path, capsys):
    """``axlebox bearing simulate --type crb``: the defect goes on its one row by default; a
    defect on row 2 is refused in one line naming the field and the bearing's rows (exit 2)."""
    from axlebox.pipelines import cli
    out = tmp_path / "rig.h5"
    assert cli.main(["bearing", "simulate", "--type", "crb", "--duration", "0.005", "--radial-load",
                     "27e3", "--defect-width", "2", "--defect-length", "30", "--out", str(out)]) == 0
    assert capsys.readouterr().out.startswith(f"wrote {out}: CRB, ")
    r = load(out)
    assert isinstance(r.config.bearing, CrbParams) and r.Q.shape[1:3] == (1, 15)
    assert r.config.defects[0].row == 1
    assert cli.main(["bearing", "simulate", "--type", "crb", "--duration", "0.005", "--defect-width", "2",
                     "--defect-row", "2", "--out", str(tmp_path / "no.h5")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Defect.row = 2 is not allowed" in err and "1 row" in err

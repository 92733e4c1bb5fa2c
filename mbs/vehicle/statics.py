"""Static (steady running) equilibrium: positions at which every body's acceleration vanishes
with the velocities held at the running state (all bodies at the forward speed, wheelsets
spinning).  On smooth tangent track this is the car standing on its wheels, seen from the
moving frame; it is the start of every run so no transient of settling springs pollutes the
signals.

Unknowns per body: translation, a small rotation (applied to the quaternion) and the modal
coordinates; a spinning body's frame pitch and spin are left out (its frame does not pitch, and
free rolling sets the spin).  On a line (mbs/kernel/trajectory.py) the equilibrium is the steady
running of the car on its track frames, at rest on them: a body moved there keeps the inertial
velocity of its new place on its frame, and each wheelset's spin is an unknown too (in a curve
the wheels' rolling radii differ, and the spin that rolls them freely with them).

Newton's method on the accelerations with a finite-difference Jacobian; least squares takes
care of the neutral directions (the car's position along the track).
"""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from axlebox._params import ParameterError

from ..kernel.speed import G_LINE
from ..kernel.trajectory import FR_W
from ..solver.system import Model


def _on_line(model: Model) -> bool:
    return model.S.glob[G_LINE] != 0.0


def _index(model: Model):
    """Columns (position perturbations; on a line the spin rates too) and rows (acceleration
    equations) kept."""
    bi = model.S.bi
    cols, rows = [], []
    line = _on_line(model)
    for k in range(bi.shape[0]):
        ip, iv, n, s = (int(x) for x in bi[k, :4])
        rot = [0, 2] if s else [0, 1, 2]
        # on a line the first body stays where it is along its frame: there the place along
        # the track is not quite neutral (a body ahead of its frame's origin is off its curve),
        # and the spins balance the longitudinal forces
        cols += [(k, "r", a) for a in range(3) if not (line and k == 0 and a == 0)] + \
            [(k, "th", a) for a in rot] + [(k, "q", j) for j in range(n)]
        rows += [iv + a for a in range(3)] + [iv + 3 + a for a in rot] + [iv + 6 + j for j in range(n)]
        if s and line:                 # a curve's radius difference asks its own spin
            cols.append((k, "spin", 0))
            rows.append(iv + 4)
    return cols, np.array(rows)


def _frame_rates(model: Model, y) -> np.ndarray:
    """Each body's track frame's angular velocity at t = 0 (its own axes), (nb, 3)."""
    model.kinematics(0.0, y)
    return model.W.frm[:, FR_W:FR_W + 3].copy()


def _apply(model: Model, y: np.ndarray, cols, dx: np.ndarray, wF=None) -> np.ndarray:
    """``y`` moved by ``dx`` along ``cols``; on a line (``wF`` the frames' rates) with the
    velocities that keep each body at rest on its track frame as it was (its inertial velocity
    and angular velocity follow its place and axes there)."""
    y = y.copy()
    bi = model.S.bi
    rotv = {}
    for (k, what, a), d in zip(cols, dx):
        ip, iv, s = int(bi[k, 0]), int(bi[k, 1]), int(bi[k, 3])
        if what == "r":
            y[ip + a] += d
            if wF is not None:         # u = v_0 + omega_F x r + r'
                e = np.zeros(3)
                e[a] = d
                y[iv:iv + 3] += np.cross(wF[k], e)
        elif what == "q":
            y[ip + 7 + s + a] += d
        elif what == "spin":
            y[iv + 4] += d
        else:
            rotv.setdefault(k, np.zeros(3))[a] += d
    if not rotv:
        return y
    # A <- A exp(th~): a rotation about body axes, every rotated body at once (scipy's stack of
    # rotations works each element as it works one)
    ks = np.array(list(rotv))
    ip, iv = bi[ks, 0].astype(int), bi[ks, 1].astype(int)
    q = y[ip[:, None] + 3 + np.arange(4)]                  # (w, x, y, z) each
    old = Rotation.from_quat(q[:, [1, 2, 3, 0]])
    rot = old * Rotation.from_rotvec(np.array(list(rotv.values())))
    y[ip[:, None] + 3 + np.arange(4)] = rot.as_quat()[:, [3, 0, 1, 2]]
    if wF is not None:                 # omega = omega_rel + A_rel^T omega_F
        y[iv[:, None] + 3 + np.arange(3)] += rot.inv().apply(wF[ks]) - old.inv().apply(wF[ks])
    return y


def equilibrium(model: Model, y0=None, *, tol: float = 1e-6, accept: float = 1e-3,
                max_iter: int = 30, log=None) -> np.ndarray:
    """Positions in equilibrium (velocities as in ``y0``).  The residual is each acceleration
    times its diagonal mass (N, N m, modal force), converged when the largest is below
    ``tol`` times the system's weight.  The tables' piecewise-linear look-up makes the residual
    kink at grid points, where Newton can stall: a stall below ``accept`` times the weight is
    taken (0.1 % of the weight, far below the dynamic loads) and logged; above it is an error."""
    y = np.array(model.y0 if y0 is None else y0, float)
    cols, rows = _index(model)
    wF = _frame_rates(model, y) if _on_line(model) else None
    n = len(cols)
    h = np.full(n, 1e-7)
    wmass = np.zeros(model.n_states)
    bi = model.S.bi
    for k, b in enumerate(model.bodies):
        iv, nm = int(bi[k, 1]), b.n_modes
        wmass[iv:iv + 3] = b.mass
        wmass[iv + 3:iv + 6] = np.diag(b.inertia_origin)
        wmass[iv + 6:iv + 6 + nm] = np.diag(b.Me)
    wmass = wmass[rows]
    weight = sum(b.mass for b in model.bodies) * np.linalg.norm(model.system.gravity)
    tol = tol * max(weight, 1.0)

    def res(yy):
        return model.rhs(0.0, yy)[rows] * wmass

    r = res(y)
    history = []
    for it in range(max_iter):
        err = np.abs(r).max()
        history.append(err)
        if err < tol:
            if log:
                log(f"statics: in equilibrium after {it} iterations (largest residual {err:.3g} N, "
                    f"{err / max(weight, 1.0):.1e} of the weight)")
            return y
        # a stall (three iterations that gain under 1 %) below the accepted level ends the search
        if it >= 3 and err < accept * max(weight, 1.0) and err > 0.99 * history[-4]:
            break
        J = np.empty((len(rows), n))
        for j in range(n):
            dx = np.zeros(n)
            dx[j] = h[j]
            J[:, j] = (res(_apply(model, y, cols, dx, wF)) - r) / h[j]
        dx = np.linalg.lstsq(J, -r, rcond=1e-12)[0]
        # damped step: the Hertz contact stiffens with load, a full step can lift a wheel
        lam = 1.0
        for _ in range(12):
            yt = _apply(model, y, cols, lam * dx, wF)
            rt = res(yt)
            if np.isfinite(rt).all() and np.abs(rt).max() < err:
                break
            lam *= 0.5
        y, r = yt, rt
    err = np.abs(r).max()
    if err < accept * max(weight, 1.0):
        if log:
            log(f"statics: in equilibrium within tolerance after {len(history)} iterations: the "
                f"largest residual {err:.3g} N is {err / weight:.1e} of the weight (accepted below "
                f"{accept:g}: far under the run's dynamic loads; the contact tables' "
                f"piecewise-linear look-up keeps Newton from going lower)")
        return y
    worst = model.state_owner(int(rows[np.abs(r).argmax()]))
    raise ParameterError(f"statics: no equilibrium after {max_iter} iterations (largest "
                         f"residual {np.abs(r).max():.3e} in {worst})")

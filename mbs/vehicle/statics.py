"""Static (steady running) equilibrium: positions at which every body's acceleration vanishes
with the velocities held at the running state (all bodies at the forward speed, wheelsets
spinning).  On smooth tangent track this is the car standing on its wheels, seen from the
moving frame; it is the start of every run so no transient of settling springs pollutes the
signals.

Unknowns per body: translation, a small rotation (applied to the quaternion) and the modal
coordinates; a spinning body's frame pitch and spin are left out (its frame does not pitch, and
free rolling sets the spin).  Newton's method on the accelerations with a finite-difference
Jacobian; least squares takes care of the neutral directions (the car's position along the
track).
"""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from axlebox._params import ParameterError

from ..solver.system import Model


def _index(model: Model):
    """Columns (position perturbations) and rows (acceleration equations) kept."""
    bi = model.S.bi
    cols, rows = [], []
    for k in range(bi.shape[0]):
        ip, iv, n, s = (int(x) for x in bi[k, :4])
        rot = [0, 2] if s else [0, 1, 2]
        cols += [(k, "r", a) for a in range(3)] + [(k, "th", a) for a in rot] + \
            [(k, "q", j) for j in range(n)]
        rows += [iv + a for a in range(3)] + [iv + 3 + a for a in rot] + [iv + 6 + j for j in range(n)]
    return cols, np.array(rows)


def _apply(model: Model, y: np.ndarray, cols, dx: np.ndarray) -> np.ndarray:
    y = y.copy()
    bi = model.S.bi
    rotv = {}
    for (k, what, a), d in zip(cols, dx):
        ip, s = int(bi[k, 0]), int(bi[k, 3])
        if what == "r":
            y[ip + a] += d
        elif what == "q":
            y[ip + 7 + s + a] += d
        else:
            rotv.setdefault(k, np.zeros(3))[a] += d
    for k, th in rotv.items():
        ip = int(bi[k, 0])
        # A <- A exp(th~): a rotation about body axes
        w, x, yy, z = y[ip + 3:ip + 7]
        rot = Rotation.from_quat([x, yy, z, w]) * Rotation.from_rotvec(th)
        x, yy, z, w = rot.as_quat()
        y[ip + 3:ip + 7] = (w, x, yy, z)
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
                log(f"statics: converged in {it} iterations (largest residual {err:.3g} N)")
            return y
        # a stall (three iterations that gain under 1 %) below the accepted level ends the search
        if it >= 3 and err < accept * max(weight, 1.0) and err > 0.99 * history[-4]:
            break
        J = np.empty((len(rows), n))
        for j in range(n):
            dx = np.zeros(n)
            dx[j] = h[j]
            J[:, j] = (res(_apply(model, y, cols, dx)) - r) / h[j]
        dx = np.linalg.lstsq(J, -r, rcond=1e-12)[0]
        # damped step: the Hertz contact stiffens with load, a full step can lift a wheel
        lam = 1.0
        for _ in range(12):
            yt = _apply(model, y, cols, lam * dx)
            rt = res(yt)
            if np.isfinite(rt).all() and np.abs(rt).max() < err:
                break
            lam *= 0.5
        y, r = yt, rt
    err = np.abs(r).max()
    if err < accept * max(weight, 1.0):
        if log:
            log(f"statics: stalled after {len(history)} iterations at a residual of {err:.3g} N "
                f"({err / weight:.1e} of the weight): taken")
        return y
    worst = model.state_owner(int(rows[np.abs(r).argmax()]))
    raise ParameterError(f"statics: no equilibrium after {max_iter} iterations (largest "
                         f"residual {np.abs(r).max():.3e} in {worst})")

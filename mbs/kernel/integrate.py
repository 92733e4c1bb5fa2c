"""Fixed-step integrators over :func:`axlebox.mbs.kernel.system.rhs`, whole runs in numba.

* ``run_rk4``: classical Runge-Kutta 4; ``run_leapfrog``: the explicit central-difference
  (leapfrog) step of explicit finite elements and discrete elements, one right-hand side a step (Belytschko,
  Liu and Moran, Nonlinear Finite Elements for Continua and Structures, 2000, sec. 6.2.1,
  Box 6.1), in its kick-drift form::

      u_{n+1/2} = u_{n-1/2} + h a(t_n, q_n, u_{n-1/2})
      q_{n+1}   = q_n + h B(q_n) u_{n+1/2}

  with ``q' = B(q) u`` the position rates (identity but for the quaternion).  The velocity
  states hold ``u_{n-1/2}``, so forces that depend on velocity (damping, friction, creep) see
  it half a step late, as in Box 6.1.  Stable below ``w h = 2 (sqrt(1 + z^2) - z)`` on a mode of
  frequency w and damping ratio z: one evaluation a step against RK4's four, for a step
  ``2 / 2.8`` of RK4's on the stiffest (roller) mode.
* ``run_galpha``: the first-order generalized-alpha method of Jansen, Whiting and Hulbert
  (Comput. Methods Appl. Mech. Engrg. 190 (2000) 305-319, eqs. 2.1-2.3 and 20-22) on
  ``y' = F(t, y)``, second-order accurate and unconditionally stable for linear problems, with
  high-frequency damping set by ``rho_inf``:

      alpha_m = (3 - rho) / (2 (1 + rho)),  alpha_f = 1 / (1 + rho),  gamma = 1/2 + alpha_m - alpha_f
      y_{n+1} = y_n + h yd_n + gamma h (yd_{n+1} - yd_n)
      yd_{n+am} = F(t_{n+af}, y_{n+af})

  solved for ``yd_{n+1}`` by modified Newton with the iteration matrix
  ``alpha_m I - alpha_f gamma h dF/dy``.  The Jacobian comes from finite differences over column
  groups (columns whose rows do not overlap share one evaluation: the body coupling pattern);
  it is refreshed only when Newton slows down or fails, and a step that fails with a fresh
  Jacobian is retried in 2, 4, ... 64 sub-steps.  Newton needs a right-hand side continuous in
  the state: hence FASTSIM's cut-back slip step in the vehicle (``wheelrail.fastsim_update``).

With bearings, the leapfrog exchanges with them once a step (:mod:`.exchange`): the step is the
exchange step, and each bearing advances its own states in its own sub-steps inside the
right-hand side (:func:`.system.rhs_exchange`); RK4 and generalized-alpha carry the
bearings' states in ``y`` with the bodies'.

Both write outputs every ``n_sub`` steps into :class:`Outputs`: sensor accelerations, wheel and
element outputs, and the whole state every ``state_every`` outputs; :class:`Guard` says what
stops a run.  They return a status (0 done, 1 not finite, 2 runaway, 3 Newton failed), the
number of outputs written, and the offending state index.  (Named tuples numba compiles, as the
system's ``S``, ``W``, ``B`` and ``X``: fields by name, no positions to keep in step; they cost
nothing measurable, benchmarks/README.md "Grouped arguments".)
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import njit

from axlebox._threads import fit_threads
from axlebox.bearing.kernel.vec import copy1, copy2, copy3

from axlebox.mbs.wheelrail.element_kernel import OUT_CLAMP

from .exchange import FIRST, LINEAR
from .body import BI_N, BI_POS, BI_SPIN, BI_VEL
from .system import frames, rhs, rhs_exchange, rhs_held

OK, NOT_FINITE, RUNAWAY, NO_CONVERGENCE, DERAILED = 0, 1, 2, 3, 4
#: the stops after which the output that showed them is kept
KEEP_LAST = (NOT_FINITE, RUNAWAY, DERAILED)

#: a chunk's output buffers: times ``t`` (k), sensor accelerations ``sens`` (k, n_sensors, 3),
#: wheel-rail ``wh`` and element ``el`` outputs, state snapshots ``y`` every ``state_every``
#: outputs; the buffers' first row holds output ``base`` (all of the run: 0, or a streamed chunk's)
Outputs = namedtuple("Outputs", ["t", "sens", "wh", "el", "y", "state_every", "base"])
#: what stops a run: a state not finite, or a body velocity (states ``nq .. nend``) beyond ``vmax``
Guard = namedtuple("Guard", ["nq", "nend", "vmax"])
#: generalized-alpha's modified Newton: ``rho_inf``; the Jacobian's column ``groups`` (``n_groups``)
#: and coupling ``pattern``, the states' ``scale``; the tolerances ``atol`` (per state) and
#: ``rtol``, ``max_iter`` iterations; ``stats`` its counters [steps, Newton iterations,
#: Jacobians, RHS evaluations, halved steps]
Newton = namedtuple("Newton", ["rho_inf", "groups", "n_groups", "pattern", "scale", "atol", "rtol",
                               "max_iter", "stats"])


@njit(cache=True)
def _check(y, G):
    """Non-finite anywhere, or a body velocity beyond the :class:`Guard` ``G``'s limit."""
    for i in range(y.shape[0]):
        if not math.isfinite(y[i]):
            return NOT_FINITE, i
    for i in range(G.nq, G.nend):
        if abs(y[i]) > G.vmax:
            return RUNAWAY, i
    return OK, -1


@njit(cache=True)
def _output(k, t, ys, y, W, G, O):
    """Record output ``k`` from the evaluation just made at (t, ``ys``: the state it was made
    at) in row ``k - O.base`` of the :class:`Outputs` ``O``; then check the state ``y``."""
    r = k - O.base
    every = O.state_every
    O.t[r] = t
    copy2(O.sens[r], W.sensout)
    copy2(O.wh[r], W.whout)
    copy2(O.el[r], W.elout)
    if k % every == 0:
        copy1(O.y[k // every - (O.base + every - 1) // every], ys)
    # a wheel off its contact table has climbed its flange past where the profiles' geometry
    # was computed (or left the rail): what follows would be extrapolation, so the run stops
    for w in range(W.whout.shape[0]):
        if W.whout[w, OUT_CLAMP] > 0.0:
            return DERAILED, w
    return _check(y, G)


@njit(cache=True)
def _normalise(y, bi):
    for b in range(bi.shape[0]):
        ip = bi[b, 0]
        s = math.sqrt(y[ip + 3] ** 2 + y[ip + 4] ** 2 + y[ip + 5] ** 2 + y[ip + 6] ** 2)
        for a in range(4):
            y[ip + 3 + a] /= s


@njit(cache=True)
def _rk4_step(t, y, k1, k2, k3, k4, yt, h, S, W, B):
    """The rest of one RK4 step from ``k1 = F(t, y)``."""
    N = y.shape[0]
    for i in range(N):
        yt[i] = y[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, yt, k2, S, W, B)
    for i in range(N):
        yt[i] = y[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, yt, k3, S, W, B)
    for i in range(N):
        yt[i] = y[i] + h * k3[i]
    rhs(t + h, yt, k4, S, W, B)
    for i in range(N):
        y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True)
def _kick_drift(y, a, hk, h, t, S, W):
    """One leapfrog step of the bodies from the accelerations ``a`` just evaluated at ``y``:
    velocities first (kick, by ``hk``: ``h``, or ``h / 2`` on the first step from ``u_0``), then
    positions at the new velocities (drift, by ``h``; on a line with the track frames at ``t``,
    the step's middle); ``a``'s position rows are reused.  The bearings' states are not touched:
    the exchange advanced them (:mod:`.exchange`)."""
    bi = S.bi
    for b in range(bi.shape[0]):
        iv = bi[b, BI_VEL]
        for i in range(iv, iv + 6 + bi[b, BI_N]):
            y[i] += hk * a[i]
    frames(t, y, a, S, W)
    for b in range(bi.shape[0]):
        ip = bi[b, BI_POS]
        for i in range(ip, ip + 7 + bi[b, BI_SPIN] + bi[b, BI_N]):
            y[i] += h * a[i]


@njit(cache=True, nogil=True)
def run_rk4(y, t0, h, n_sub, n_out, k0, k_last, S, W, B, G, O, threads):
    """Advance ``y`` in place through outputs ``k0 .. n_out - 1`` by RK4; output ``k`` is at
    ``t0 + (k - k0) n_sub h``, recorded from the step's first evaluation there into ``O``
    (:class:`Outputs`); no step follows the output ``k_last``; ``G`` (:class:`Guard`) stops it.
    ``threads``: numba's thread count as a watcher fits it, applied at every output
    (:func:`axlebox._threads.fit_threads`; the GIL is released for the watcher to run).
    (Apart from :func:`run_leapfrog` so that a run compiles only its own method.)"""
    N = y.shape[0]
    k1, k2, k3, k4, yt = np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(N)
    for k in range(k0, n_out):
        fit_threads(threads)
        for j in range(n_sub):
            t = t0 + ((k - k0) * n_sub + j) * h
            rhs(t, y, k1, S, W, B)
            if j == 0:
                st, i = _output(k, t, y, y, W, G, O)
                if st != OK:
                    return st, k, i
                if k == k_last:
                    break
            _rk4_step(t, y, k1, k2, k3, k4, yt, h, S, W, B)
            _normalise(y, S.bi)
    return OK, n_out, -1


@njit(cache=True, nogil=True)
def run_leapfrog(y, t0, h, n_sub, n_out, k0, k_last, S, W, B, X, G, O, start, threads):
    """:func:`run_rk4`'s contract by the leapfrog: with ``start`` the velocities in ``y`` are
    ``u_0`` and the first kick is by ``h / 2``; after that they are ``u_{n-1/2}``, half a step
    behind the positions, and a run continued from ``y`` (``start`` False) goes on exactly as if
    it had not stopped.  Its bearings exchange with the bodies every step (``X``:
    :class:`.exchange.Exchange`), and between exchanges the bodies take ``X.m`` steps of
    ``h / X.m`` with the loads held.  ``threads``: as :func:`run_rk4`'s."""
    N = y.shape[0]
    k1 = np.empty(N)
    ys = np.empty(N)                          # the state an output's evaluation was made at
    rs = np.empty_like(X.ring)
    for k in range(k0, n_out):
        fit_threads(threads)
        for j in range(n_sub):
            t = t0 + ((k - k0) * n_sub + j) * h
            if j == 0 and (k % O.state_every == 0 or k == k_last):
                copy1(ys, y)                  # the exchange moves the bearings' states on
                copy3(rs, X.ring)
                first = X.flags[FIRST]
            rhs_exchange(t, y, k1, S, W, B, X)
            if j == 0:
                st, i = _output(k, t, ys, y, W, G, O)
                if st != OK:
                    return st, k, i
                if k == k_last:               # the run ends at the state this output was made
                    copy1(y, ys)              # at: a run continued from it makes this exchange
                    copy3(X.ring, rs)         # again
                    X.flags[FIRST] = first
                    break
            first = start and k == k0 and j == 0
            hb = h / X.m                      # the bodies' step (co-simulation: X.m > 1)
            _kick_drift(y, k1, 0.5 * hb if first else hb, hb, t + 0.5 * hb, S, W)
            for i in range(1, X.m):
                _normalise(y, S.bi)
                rhs_held(t + i * hb, y, k1, S, W, B, X, i / X.m if X.hold == LINEAR else 0.0)
                _kick_drift(y, k1, hb, hb, t + (i + 0.5) * hb, S, W)
            _normalise(y, S.bi)
    return OK, n_out, -1


@njit(cache=True)
def jacobian_fd(t, y, f0, S, W, B, nw, J):
    """``J = dF/dy`` by forward differences, one evaluation per column group of ``nw``
    (:class:`Newton`)."""
    groups, pattern = nw.groups, nw.pattern
    N = y.shape[0]
    yp = y.copy()
    fp = np.empty(N)
    eps = np.empty(N)
    for j in range(N):
        eps[j] = 1e-7 * max(abs(y[j]), nw.scale[j])
    J[:, :] = 0.0
    for g in range(nw.n_groups):
        for j in range(N):
            if groups[j] == g:
                yp[j] = y[j] + eps[j]
        rhs(t, yp, fp, S, W, B)
        for j in range(N):
            if groups[j] == g:
                yp[j] = y[j]
                for i in range(N):
                    if pattern[i, j]:
                        J[i, j] = (fp[i] - f0[i]) / eps[j]


@njit(cache=True)
def _iteration_matrix(Jf, h, am, af, ga, Minv):
    """``Minv = (alpha_m I - alpha_f gamma h dF/dy)^-1``."""
    N = Jf.shape[0]
    A = np.empty((N, N))
    for a in range(N):
        for c in range(N):
            A[a, c] = -af * ga * h * Jf[a, c]
        A[a, a] += am
    Minv[:, :] = np.linalg.inv(A)


@njit(cache=True)
def _ga_newton(t, y, ydn, yd, h, am, af, ga, Minv, S, W, B, nw, y1, ya, f):
    """Modified Newton (``nw``: :class:`Newton`) for ``yd_{n+1}`` of one step; 0 converged, 1
    slow (converged late),
    -1 failed.  Converged when the estimated remaining error ``theta / (1 - theta) * |dy|``
    (theta: the observed contraction rate) is below the tolerance (Hairer and Wanner, Solving
    ODEs II, sec. IV.8); a rate theta >= 1 after the first iteration is divergence."""
    N = y.shape[0]
    atol, rtol, max_iter, stats = nw.atol, nw.rtol, nw.max_iter, nw.stats
    for i in range(N):
        yd[i] = ydn[i]
    prev = 0.0
    for it in range(max_iter):
        for i in range(N):
            y1[i] = y[i] + h * ydn[i] + ga * h * (yd[i] - ydn[i])
            ya[i] = y[i] + af * (y1[i] - y[i])
        rhs(t + af * h, ya, f, S, W, B)
        stats[3] += 1
        stats[1] += 1
        for i in range(N):
            f[i] = ydn[i] + am * (yd[i] - ydn[i]) - f[i]     # residual
        err = 0.0
        for i in range(N):
            s = 0.0
            for c in range(N):
                s -= Minv[i, c] * f[c]
            yd[i] += s
            e = ga * h * abs(s) / (atol[i] + rtol * abs(y1[i]))
            if e > err:
                err = e
        if not math.isfinite(err):
            return -1
        if err < 1e-3:           # far below the tolerance: rate estimate not needed
            return 1 if it >= max_iter - 2 else 0
        if it > 0:
            theta = err / prev
            if theta >= 1.0:
                return -1
            if theta / (1.0 - theta) * err < 1.0:
                return 1 if it >= max_iter - 2 else 0
        prev = err
    return -1


@njit(cache=True, nogil=True)
def run_galpha(y, t0, h, n_sub, n_out, k0, k_last, S, W, B, G, O, nw, threads):
    """:func:`run_rk4`'s contract by generalized-alpha (first order) with modified Newton
    (``nw``: :class:`Newton`, whose ``stats`` it counts in).  The Jacobian is kept
    while Newton converges fast and rebuilt when it slows down or fails.  A step that fails with a
    fresh Jacobian is retried as 2, 4, ... 64 sub-steps (contact loss and return are the usual
    cause); only then does the run stop with NO_CONVERGENCE.  ``threads``: as :func:`run_rk4`'s."""
    N = y.shape[0]
    rho_inf, stats = nw.rho_inf, nw.stats
    am = 0.5 * (3.0 - rho_inf) / (1.0 + rho_inf)
    af = 1.0 / (1.0 + rho_inf)
    ga = 0.5 + am - af
    ydn = np.empty(N)
    rhs(t0, y, ydn, S, W, B)
    stats[3] += 1
    yd = np.empty(N)
    y1 = np.empty(N)
    ya = np.empty(N)
    f = np.empty(N)
    ys = np.empty(N)
    yds = np.empty(N)
    Jf = np.empty((N, N))
    Minv = np.empty((N, N))
    h_M = -1.0                  # the step Minv was formed for
    have = False                # Jf exists
    stale = False
    for k in range(k0, n_out):
        fit_threads(threads)
        for j in range(n_sub):
            t = t0 + ((k - k0) * n_sub + j) * h
            if j == 0:
                rhs(t, y, f, S, W, B)
                stats[3] += 1
                st, i = _output(k, t, y, y, W, G, O)
                if st != OK:
                    return st, k, i
                if k == k_last:
                    break
            ys[:] = y
            yds[:] = ydn
            m = 1
            while True:                          # m sub-steps of h / m
                hm = h / m
                ok = True
                for q in range(m):
                    tq = t + q * hm
                    fresh = False
                    for attempt in range(2):
                        if not have or stale or attempt > 0:
                            rhs(tq, y, f, S, W, B)
                            jacobian_fd(tq, y, f, S, W, B, nw, Jf)
                            stats[2] += 1
                            stats[3] += 1 + nw.n_groups
                            have = True
                            stale = False
                            fresh = True
                            h_M = -1.0
                        if hm != h_M:
                            _iteration_matrix(Jf, hm, am, af, ga, Minv)
                            h_M = hm
                        r = _ga_newton(tq, y, ydn, yd, hm, am, af, ga, Minv, S, W, B, nw, y1, ya, f)
                        if r >= 0:
                            stale = r == 1
                            break
                        if fresh:
                            break
                    if r < 0:
                        ok = False
                        break
                    for i in range(N):
                        y[i] = y[i] + hm * ydn[i] + ga * hm * (yd[i] - ydn[i])
                        ydn[i] = yd[i]
                    _normalise(y, S.bi)
                    stats[0] += 1
                if ok:
                    break
                y[:] = ys
                ydn[:] = yds
                if m >= 64:
                    return NO_CONVERGENCE, k, -1
                m *= 2
                stats[4] += 1
    return OK, n_out, -1

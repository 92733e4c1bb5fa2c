"""The rows a contact puts into the implicit step's blocks (numba; bearing/kernel/implicit.py solves
them, bearing/kernel/quasidynamic.py reads them): its damping ``c J^T J`` in the rates, and under
``"imex2"`` its tangent stiffness in approach and tilt and its friction's secant damping.

``J`` is the gradient of the contact's approach rate in the roller's rates ``(rho', phi',
eta', theta_t', theta_s', omega_s)`` (:func:`roller_grad`) and, for a pocket, in its cage's
rates ``(v_x, v_y, v_z, omega_x, omega_z, phi_c')`` (:func:`cage_grad`); a contact's damping
force is ``-c J u`` (u the rates).  Each roller's rows go to its own block (``(6, BLK)``,
:data:`.layout.BLK_ROLLER` ...), which it zeroes when it first writes it in an evaluation
(its flag, :data:`.layout.BLK_NONE` ..., says what it holds): the car's rollers out of contact
cost no block at all.
"""
from __future__ import annotations

from axlebox._numba import kernel

from .layout import BLK, BLK_CAGE, BLK_CAGE_CAGE, BLK_COUPLED, BLK_NONE, BLK_OWN, BLK_ROLLER
from .vec import EY, ZERO6, cross, dot


@kernel
def roller_grad(n, r, fr):
    """Gradient of the approach rate ``(v_roller(r) - ...) . n`` of a contact at ``r`` from the
    centre of roller ``fr`` (bearing/kernel/roller.py ``roller_frame``) in its six rates."""
    return (dot(fr.er, n), fr.Rr * dot(fr.et, n) + dot(cross(EY, r), n), dot(EY, n),
            dot(cross(fr.et, r), n), dot(cross(fr.bx, r), n), dot(cross(fr.ax, r), n))


@kernel
def cage_grad(n, rel):
    """The same gradient in the cage's rates, for a contact at ``rel`` from the cage's centre
    (the cage side of the contact, hence the sign)."""
    nx, ny, nz = n
    mx, my, mz = cross(rel, n)
    return (-nx, -ny, -nz, -mx, -mz, -my)


@kernel
def _touch(blk, flag, jk, cage):
    """Zero the parts of roller ``jk``'s block that this evaluation writes first."""
    f = flag[jk]
    if f == BLK_NONE:
        for a in range(6):
            for b in range(BLK_CAGE if not cage else BLK):
                blk[jk, a, b] = 0.0
        flag[jk] = BLK_COUPLED if cage else BLK_OWN
    elif cage and f == BLK_OWN:
        for a in range(6):
            for b in range(BLK_CAGE, BLK):
                blk[jk, a, b] = 0.0
        flag[jk] = BLK_COUPLED


@kernel
def rows(blk, cblk, flag, jk, c, Jr, Jc, cage):
    """``c J^T J`` into roller ``jk``'s block: its own rates, and for a pocket (``cage``) the
    coupling to its cage and the cage's own (the roller's share, and the row's cage block
    ``cblk``, summed as the contacts come: a roller's :data:`.layout.Touch` taken apart, its arrays
    passed one by one: as the group, the imex sub-step took 7 % longer, benchmarks/README.md)."""
    _touch(blk, flag, jk, cage)
    for a in range(6):
        ca = c * Jr[a]
        for b in range(6):
            blk[jk, a, BLK_ROLLER + b] += ca * Jr[b]
        if cage:
            for b in range(6):
                blk[jk, a, BLK_CAGE + b] += ca * Jc[b]
                blk[jk, a, BLK_CAGE_CAGE + b] += c * Jc[a] * Jc[b]
                cblk[a, b] += c * Jc[a] * Jc[b]


@kernel
def _add6(a, b, sb):
    """``a + sb b`` of two 6-tuples."""
    a0, a1, a2, a3, a4, a5 = a
    b0, b1, b2, b3, b4, b5 = b
    return (a0 + sb * b0, a1 + sb * b1, a2 + sb * b2, a3 + sb * b3, a4 + sb * b4, a5 + sb * b5)


@kernel
def tilt_rows(blk, cblk, flag, jk, kdk, kkk, Jd, Jk, Jdc, Jkc, cage):
    """A line contact's stiffness in its tilt ``kap`` (``kkk = dm1/dkap``) and between tilt and
    approach (``kdk = dQ/dkap = dm1/dd0``): ``kdk (Jd^T Jk + Jk^T Jd) + kkk Jk^T Jk``, ``Jd`` /
    ``Jk`` the gradients of the approach and of ``kap`` in the roller's rates, ``Jdc`` / ``Jkc``
    in the cage's.  The cross term as the difference of two squares,
    ``(A + B)^T (A + B) - (A - B)^T (A - B) = 2 (A^T B + B^T A)``."""
    rows(blk, cblk, flag, jk, kkk, Jk, Jkc, cage)
    if kdk != 0.0:
        rows(blk, cblk, flag, jk, 0.5 * kdk, _add6(Jd, Jk, 1.0), _add6(Jdc, Jkc, 1.0), cage)
        rows(blk, cblk, flag, jk, -0.5 * kdk, _add6(Jd, Jk, -1.0), _add6(Jdc, Jkc, -1.0), cage)


@kernel
def friction_rows(blk, cblk, flag, jk, cf, t1, n, r, fr, rel, cage):
    """The friction's secant damping ``cf`` (:func:`axlebox.bearing.kernel.contact.slip_damping`) in the
    contact plane spanned by the unit ``t1`` and ``t1 x n``, for the implicit kick: the
    regularised friction is stiff in the slip (the roller spin's eigenvalue near -1.3e5 1/s holds
    an explicit step under 1.5e-5 s)."""
    for t in (t1, cross(t1, n)):
        rows(blk, cblk, flag, jk, cf, roller_grad(t, r, fr), cage_grad(t, rel) if cage else ZERO6, cage)


@kernel
def tilt_grad(sign):
    """The gradient of a raceway contact's tilt ``kap = sign theta_t + ...`` in a roller's
    rates."""
    return (0.0, 0.0, 0.0, sign, 0.0, 0.0)



def dense(w, Z_: int):
    """The blocks of an evaluation (bearing/kernel/evaluate.py ``Work``) as one array ``(n, Z + 1, 6,
    12)``, n the rows: ``[j, k, :, :6]`` roller k's own, ``[j, k, :, 6:]`` its coupling to the cage of row
    j, ``[j, Z, :, :6]`` that cage's own (zero where an evaluation wrote nothing), for tests and
    analysis (the kernels read the blocks where they lie)."""
    import numpy as np

    rows = w.cblk.shape[0]
    G = np.zeros((rows, Z_ + 1, 6, 12))
    for j in range(rows):
        for k in range(Z_):
            jk = j * Z_ + k
            if w.flag[jk] != BLK_NONE:
                G[j, k, :, :BLK_CAGE] = w.blk[jk, :, BLK_ROLLER:BLK_ROLLER + 6]
            if w.flag[jk] == BLK_COUPLED:
                G[j, k, :, BLK_CAGE:] = w.blk[jk, :, BLK_CAGE:BLK_CAGE + 6]
        G[j, Z_, :, :BLK_CAGE] = w.cblk[j]
    return G

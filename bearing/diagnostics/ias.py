"""The shaft's speed over a record from the record itself: tacholess instantaneous angular speed
(IAS) along the ridge of a family of lines locked to the shaft.

Every line whose frequency is a fixed multiple of the shaft's rate (an order) follows the speed:
a bearing fault's envelope family (BPFO, BPFI, 2BSF and their harmonics), a wheel's flat or
out-of-roundness (whole orders of the shaft in the envelope).  Where the speed changes, such a
family draws ridges across the time-frequency plane whose frequency over their order is the
shaft's speed; followed from the user's nominal speed, they give the speed over the record
without a tacho.  The method is the two-step one of Urbanek, Barszcz and Antoni, Mech. Syst.
Signal Process. 38 (2013) 96-102: a coarse ridge in the short-time Fourier transform, then a fine
reading on the record demodulated by the coarse speed; here the fine reading is the same ridge
again in the angle domain (the record resampled on the coarse speed, where its lines stand
straight and longer frames resolve them), not the phase of one harmonic (their second step, and
Combet and Gelman, Mech. Syst. Signal Process. 21 (2007) 2590-2606), which needs one line
standing alone over the noise at every instant: a bearing's envelope lines, each hit a little off
its place, do not.  Every harmonic of a family votes for one speed (the multi-order approach of
Leclère, André and Antoni, Mech. Syst. Signal Process. 81 (2016) 375-386), and the ridge is the
path of dynamic programming through the map (Iatsenko, McClintock and Stefanovska, Signal
Process. 125 (2016) 290-303):

1. each channel's envelope (:func:`.envelope.envelope`: band of highest spectral kurtosis, wide
   enough for the harmonics searched; the impulses ring fixed resonances, so the band is taken in
   time), decimated to four samples a period of the highest harmonic searched;
2. the envelopes resampled to the current estimate of the angle (:func:`.ordertrack.to_angle`;
   at first the nominal speed's, a constant), an STFT over frames of ``L`` turns (Hann, 3/4
   overlapping), each bin's power over its frame's median in blocks of bins (the floor): ``W``,
   1/ln 2 on average on noise (an exponential power over its median), both sides averaged;
3. for each family (order ``o``, harmonics ``m = 1..K``) the multi-order map
   ``S(frame, c) = mean_m W(frame, m o c)`` over the speed's ratio ``c`` to the current estimate,
   on a logarithmic grid, and the same map with each harmonic's ``W`` capped at ``K thr / 2``
   (``thr``: :func:`frame_threshold`), so that a family stands only where half its harmonics do
   and one strong line of another family, met by one harmonic, does not carry it;
4. its ridge: the path through the capped map that maximises its sum less :data:`JUMP_COST`
   noise means per unit of ``|d ln c|`` from frame to frame (Viterbi); each frame's point the
   full map's highest cell within a line's width of the path, refined by a parabola; a path whose
   time-mean is off the nominal (another family's lines, read at another speed) is taken out of
   the map and the next one followed, :data:`PEEL` times at most;
5. the family: a *coherent* ridge first (standing over ``thr`` in :data:`HOLD` of the frames,
   never changing by more than :data:`JUMP` a turn), then the one nearest the nominal speed,
   among those whose time-mean lies within :data:`NOMINAL_TOL` of it: the user's speed is the
   record's mean, which tells a family from its aliases (the DTRB's 2BSF, 7.57 orders, reads a
   BPFO ridge, 8.72 orders, at 1.15 times the speed; BPFI at 0.77; the other side's bearing's
   lines likewise), then the strongest;
6. the estimate times ``c`` (linear between the frames where the ridge stands, each already its
   window's average of the speed; beyond the end frames the line through those within a frame),
   the angle its running integral (:func:`.ordertrack.angle_from_speed`); then again on that
   clock with longer frames and a narrower grid (:data:`LADDER`).

The final speed is the estimate smoothed by a local straight line over one last frame (Hann
weights: it neither rings at a step, as a spline does, nor bends a constant acceleration), its
mean set to the nominal speed (the user's speed, or the file's): a family's ridge reads the
shaft's speed times its slip (a bearing's rollers slip by a few per cent), and the lines then lie
where a reading at the given speed puts them.

Whether it changes is judged on the speed smoothed over :data:`SETTLE` final frames: it is
``"constant"`` within :data:`.speed.TRACK_SPREAD` plus :data:`RESOLVE` times what the estimate
cannot tell from a constant speed (its own scatter, the first step's frames about the final
speed, averaged over those frames; or the line's own wander frame by frame, a slipping bearing's
line being locked to the shaft on average only), and then read at the given speed as before.
Where no family stands at the given speed, ``"no ridge"``: nothing in the record tells the speed,
and it is read at the given one.  A change is trusted (``"changing"``, read on its clock) where
the ridge stands in :data:`HOLD` of the last step's frames, never jumps (the first step's, by
more than :data:`JUMP` a turn) and no other coherent family's ridge tells another course of the
speed (frame by frame, each over its mean, by more than :data:`AGREE`); else ``"untrusted"`` with
the reason, which the diagnosis turns into "undecided".
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.signal import resample_poly, stft
from scipy.stats import gamma

from axlebox._params import ParameterError

from ..frequencies import FaultOrders
from . import ordertrack
from .envelope import _signal, check_fs, envelope, select_band

#: samples a turn of the angle-domain envelope
PER_REV = 256
#: the iterations: (frame in turns, lowest and highest ratio of the speed to the current estimate);
#: the first searches a quarter to two and a half times the nominal speed (a record whose mean is
#: the nominal: a ramp from rest reaches twice it), the next ones the coarse estimate's error
LADDER = ((3.0, 0.25, 2.5), (6.0, 0.8, 1.25), (6.0, 0.92, 1.08))
#: the shortest frame, in turns (a record of four of them at least)
MIN_TURNS = 1.0
#: cells of the ratio grid
GRID = 400
#: a bearing family's harmonics (the fault-line search's, :mod:`.faultlines`) and the wheel's orders
BEARING_HARMONICS = 3
WHEEL_ORDERS = 8
#: the ridge's cost of changing: noise means (1/ln 2 of a whitened power) per unit of ``|d ln c|``
#: between frames: a ridge rising at 0.15 a frame (a train's most at 20 km/h, 3/4 turn apart)
#: pays 3 noise means, less than a held ridge stands over noise (frame_threshold, 5-7)
JUMP_COST = 20.0
#: ridges taken out of a family's map, each another family's read off the nominal speed, before
#: the family's own is given up
PEEL = 3
#: false-alarm probability of one frame's highest cell on noise
P_FA = 1e-3
#: share of frames where the ridge must stand
HOLD = 0.6
#: a change of ln c a shaft turn beyond which the ridge jumped (a train at 20 km/h braking at
#: 2.5 m/s^2, an emergency brake, loses 22 % of its speed a turn: ln 1/0.78 = 0.25)
JUMP = 0.25
#: the time-mean of a family's ridge over the nominal speed: within this, the family is locked to
#: the shaft at the given speed (a bearing's slip, a worn wheel's radius)
NOMINAL_TOL = 0.10
#: two families' speeds (each over its mean) agree within this, frame by frame (median)
AGREE = 0.03
#: the frames the speed's change is judged over
SETTLE = 4
#: a change counts where it exceeds TRACK_SPREAD and this many times what the estimate cannot tell
#: from a constant speed (module docstring)
RESOLVE = 4.0


@dataclass(frozen=True)
class Family:
    """Lines locked to the shaft: ``order`` (multiples of the shaft's rate) and its first
    ``harmonics``."""

    name: str
    order: float
    harmonics: int


def families(orders, wheel: bool = True) -> tuple[Family, ...]:
    """The families of one or two bearings' :class:`FaultOrders` (a pair: each side's, named by
    side where they differ) and the wheel's whole orders."""
    pair = tuple(orders) if isinstance(orders, (tuple, list)) else (orders, orders)
    out = []
    for side, o in zip(("left", "right"), pair):
        if not isinstance(o, FaultOrders):
            raise ParameterError(f"orders = {o!r} is not allowed: expected FaultOrders")
        tag = "" if pair[0] == pair[1] else f" ({side} bearing)"
        if tag == "" and side == "right":
            continue
        out += [Family(f"BPFO{tag}", o.BPFO, BEARING_HARMONICS),
                Family(f"BPFI{tag}", o.BPFI, BEARING_HARMONICS),
                Family(f"2BSF{tag}", 2.0 * o.BSF, BEARING_HARMONICS)]
    if wheel:
        out.append(Family("shaft orders", 1.0, WHEEL_ORDERS))
    return tuple(out)


def frame_threshold(harmonics: int, n_cells: float, p_fa: float = P_FA) -> float:
    """The map's value (in whitened power) that the highest of ``n_cells`` independent noise
    cells exceeds with probability ``p_fa``: a whitened power is exponential with mean
    ``1 / ln 2`` (its median is 1), the mean of ``K`` of them Gamma(K) over K."""
    q = (1.0 - p_fa) ** (1.0 / max(1.0, n_cells))
    return float(gamma.ppf(q, harmonics) / harmonics / np.log(2.0))


@dataclass(frozen=True)
class Ridge:
    """One family's ridge in one step: ``c`` at each frame (refined), the capped map there (it
    stands where that reaches ``threshold``), the time-mean of ``c``."""

    family: Family
    c: np.ndarray
    value: np.ndarray
    threshold: float
    mean_c: float
    level: float = 0.0      # the full map's median along the ridge
    hop: float = 1.0        # turns between frames

    def jump(self) -> tuple[float, int]:
        """The largest change of ``ln c`` a turn between frames where it stands, and the frame
        after it (``(0, -1)`` where it stands in fewer than two)."""
        h = np.flatnonzero(self.held)
        if h.size < 2:
            return 0.0, -1
        rate = np.abs(np.diff(np.log(self.c[h]))) / (np.diff(h) * self.hop)
        k = int(np.argmax(rate))
        return float(rate[k]), int(h[k + 1])

    @property
    def coherent(self) -> bool:
        """It stands in :data:`HOLD` of the frames and never jumps (:data:`JUMP`)."""
        return bool(self.held.mean() >= HOLD and self.jump()[0] <= JUMP)

    @property
    def held(self) -> np.ndarray:
        return self.value >= self.threshold



@dataclass(frozen=True)
class SpeedEstimate:
    """The shaft's speed over a record from the record (module docstring).

    ``status``: ``"changing"`` (trusted; read on its clock), ``"constant"`` (read at the given
    speed as before), ``"no ridge"`` (nothing locked to the shaft stands: read at the given
    speed) or ``"untrusted"`` (``reason`` says why; the verdict is undecided); ``family``: the
    ridge's; ``t``/``f_hz``: the frames' instants (s) and the speed there (Hz, its mean the
    nominal); ``angle``: the shaft's angle (turns) at each sample on that speed (None unless
    ``"changing"``); ``held``: share of frames where the ridge stands; ``spread``: the speed's
    range over its mean; ``scatter``: the ridge's relative scatter about its spline; ``ratio``:
    the ridge's own mean over the nominal (its slip)."""

    status: str
    reason: str
    nominal_hz: float
    family: str | None = None
    t: np.ndarray = field(default=None, repr=False)
    f_hz: np.ndarray = field(default=None, repr=False)
    angle: np.ndarray | None = field(default=None, repr=False)
    held: float = 0.0
    spread: float = 0.0
    scatter: float = 0.0
    ratio: float = 1.0

    @property
    def source(self) -> str:
        """Where the speed came from, in words (the windows' JSON Lines)."""
        return f"estimated from the record ({self.family} ridge)" if self.family else "given"

    def to_dict(self) -> dict:
        return {"status": self.status, "reason": self.reason, "family": self.family,
                "nominal_hz": self.nominal_hz, "held": self.held, "spread": self.spread,
                "scatter": self.scatter, "ratio": self.ratio,
                "min_hz": None if self.f_hz is None else float(np.min(self.f_hz)),
                "max_hz": None if self.f_hz is None else float(np.max(self.f_hz))}


#: frames of an STFT taken at once (the memory of a long record's spectra stays bounded)
CHUNK = 512


def _whitened(envs, angle, fs, L, top):
    """``(orders, W, frame centres in turns)``: the envelopes ``envs`` read on ``angle``, their
    STFT over frames of ``L`` turns (Hann, 3/4 overlapping; :data:`CHUNK` frames at a time),
    each bin's power over its frame's floor (:func:`_floor`), both sides averaged, up to ``top``
    orders (float32: orders x frames)."""
    n = max(16, int(round(L * PER_REV)))
    hop = n - 3 * n // 4
    recs = [ordertrack.to_angle(e, fs, angle, PER_REV) for e in envs]
    size = min(r.x.size for r in recs)
    frames = 1 + (size - n) // hop if size >= n else 0
    o = np.fft.rfftfreq(4 * n, 1.0 / PER_REV)
    keep = min(o.size, int(np.searchsorted(o, top)) + 2)
    W = np.zeros((keep, max(frames, 0)), dtype=np.float32)
    for k0 in range(0, frames, CHUNK):
        k1 = min(frames, k0 + CHUNK)
        for r in recs:
            seg = r.x[k0 * hop:(k1 - 1) * hop + n]
            _, _, Z = stft(seg, PER_REV, window="hann", nperseg=n, noverlap=3 * n // 4, nfft=4 * n,
                           boundary=None, padded=False, detrend="constant")
            P = np.abs(Z[:keep, :k1 - k0]) ** 2
            W[:, k0:k1] += (P / _floor(P, 8 * int(np.ceil(4 * L))) / len(recs)).astype(np.float32)
    th = recs[0].angle0 + (np.arange(frames) * hop + n / 2) / PER_REV
    return o[:keep], W, th


def _family_maps(o, W, fam: Family, grid, L):
    """``(S, capped S, threshold)``: the family's multi-order map (frames x grid) of the whitened
    spectra ``W`` at ``orders`` ``o``, and the frame threshold of its highest cell
    (:func:`frame_threshold` over the cells the highest harmonic's span of the grid covers); in
    the capped map each harmonic counts up to ``K threshold / 2`` at most, so that a ridge stands
    only where at least half the family's harmonics do (one strong line of another family, met
    by one harmonic, does not)."""
    K = fam.harmonics
    thr = frame_threshold(K, max(1.0, K * fam.order * (grid[-1] - grid[0]) * L))
    cap = np.float32(0.5 * K * thr)
    S = np.zeros((W.shape[1], grid.size), dtype=np.float32)
    Sc = np.zeros_like(S)
    for m in range(1, K + 1):
        q = m * fam.order * grid
        j = np.clip(np.searchsorted(o, q) - 1, 0, o.size - 2)
        w = ((q - o[j]) / (o[j + 1] - o[j])).astype(np.float32)
        Wm = W[j].T * (1 - w) + W[j + 1].T * w
        S += Wm
        Sc += np.minimum(Wm, cap)
    return S / K, Sc / K, thr


def _floor(P: np.ndarray, block: int) -> np.ndarray:
    """Each frame's (column's) noise floor: the median of blocks of ``block`` bins, linear
    between the blocks' centres (a family's lines, one every ``o`` orders, a minority in each)."""
    nb = max(1, P.shape[0] // block)
    med = np.median(P[:nb * block].reshape(nb, block, -1), axis=1)
    centres = (np.arange(nb) + 0.5) * block
    rows = np.arange(P.shape[0])
    out = np.empty_like(P)
    for j in range(P.shape[1]):
        out[:, j] = np.interp(rows, centres, med[:, j])
    return np.maximum(out, np.finfo(float).tiny)


def _best_before(D: np.ndarray, cost: float) -> tuple[np.ndarray, np.ndarray]:
    """For each cell ``i``: ``max_j D[j] - cost |i - j|`` and the ``j`` that gives it, in O(G):
    the L1 distance transform, one running maximum from each side (``max_{j<=i} (D[j] + cost j)
    - cost i``, and its mirror)."""
    idx = np.arange(D.size)
    out = []
    for sign, sl in ((1.0, slice(None)), (-1.0, slice(None, None, -1))):
        A = (D + sign * cost * idx)[sl]
        run = np.maximum.accumulate(A)
        at = np.maximum.accumulate(np.where(A >= run, np.arange(A.size), 0))
        out.append((run[sl] - sign * cost * idx, (at if sign > 0 else A.size - 1 - at)[sl]))
    (fv, fi), (bv, bi) = out
    take = bv > fv
    return np.where(take, bv, fv), np.where(take, bi, fi)


def _viterbi(S: np.ndarray, cost: float) -> np.ndarray:
    """The path (a grid index a frame) maximising the summed ``S`` less ``cost`` per grid step
    moved between frames (dynamic programming; the step's maximum by :func:`_best_before`)."""
    J, G = S.shape
    D = S[0].astype(float)
    back = np.zeros((J, G), dtype=np.int32)
    for j in range(1, J):
        best, back[j] = _best_before(D, cost)
        D = S[j] + best
    path = np.empty(J, dtype=np.int64)
    path[-1] = int(np.argmax(D))
    for j in range(J - 1, 0, -1):
        path[j - 1] = back[j, path[j]]
    return path


def _ridge(S, Sc, grid, fam, t_frames, t, threshold, L) -> Ridge:
    """The path of the capped map ``Sc`` (Viterbi), each frame refined on the full map ``S``:
    its highest cell within a line's width of the path (the fundamental's bin, ``1 / L``
    orders), then a parabola through that cell and its two neighbours."""
    lg = np.log(grid)
    step = lg[1] - lg[0]
    p = _viterbi(Sc, JUMP_COST / np.log(2.0) * step)
    rows = np.arange(S.shape[0])
    half = max(3, int(np.ceil(np.log1p(1.0 / (fam.order * L)) / step)))
    span = np.clip(p[:, None] + np.arange(-half, half + 1)[None, :], 0, grid.size - 1)
    p = span[rows, np.argmax(S[rows[:, None], span], axis=1)]
    val = Sc[rows, p]
    lo, hi = np.clip(p - 1, 0, grid.size - 1), np.clip(p + 1, 0, grid.size - 1)
    a, b, c = S[rows, lo], S[rows, p], S[rows, hi]
    den = a - 2 * b + c
    off = np.where((den < 0) & (p > 0) & (p < grid.size - 1), 0.5 * (a - c) / np.where(den < 0, den, -1), 0.0)
    cc = np.exp(lg[p] + np.clip(off, -0.5, 0.5) * step)
    mean_c = float(np.mean(np.interp(t, t_frames, cc)))
    return Ridge(fam, cc, val, threshold, mean_c, float(np.median(S[rows, p])), L / 4.0)


def _near_ridge(S, Sc, grid, fam, t_frames, t, threshold, L, cur) -> Ridge:
    """The family's ridge whose time-mean lies within :data:`NOMINAL_TOL` of the current speed:
    the strongest path first; where that is another family's lines read at another speed (off
    the nominal), its cells are taken out (a line's width either side) and the next strongest
    path taken, :data:`PEEL` times at most.  ``cur``: the current estimate's mean over the
    nominal speed."""
    Sc = Sc.copy()
    lg = np.log(grid)
    half = max(3, int(np.ceil(np.log1p(1.0 / (fam.order * L)) / (lg[1] - lg[0]))))
    floor = float(np.median(Sc))
    rows = np.arange(S.shape[0])
    for _ in range(PEEL):
        r = _ridge(S, Sc, grid, fam, t_frames, t, threshold, L)
        if _near(r, cur) or not r.held.any():
            return r
        p = np.searchsorted(lg, np.log(r.c))
        for k in range(-half, half + 1):
            Sc[rows, np.clip(p + k, 0, grid.size - 1)] = floor
    return r


def _through(x_frames, y, held, x_eval, L):
    """``y`` at the frames ``x_frames`` where the ridge is ``held`` (all where fewer than two),
    linear between them (each frame is already its Hann window's average of the speed: no
    overshoot at a step), and beyond the end frames the least-squares line through those within
    ``L`` of the end (a constant acceleration)."""
    k = held if held.sum() >= 2 else np.ones_like(held)
    xk, yk = x_frames[k], y[k]
    xe = np.asarray(x_eval, float)
    v = np.interp(xe, xk, yk)
    for end, side in ((xk[0], xe < xk[0]), (xk[-1], xe > xk[-1])):
        if side.any():
            near = np.abs(xk - end) <= L
            if near.sum() >= 2:
                a, b = np.polyfit(xk[near] - end, yk[near], 1)
                v[side] = b + a * (xe[side] - end)
    return v


def _local_line(x, y, x_eval, width):
    """``y(x)`` (``x`` increasing) smoothed by a local straight line at each ``x_eval`` through
    the points within ``width / 2``, Hann-weighted (a kernel that does not ring at a step, as a
    spline does, and keeps a constant acceleration, also at the ends)."""
    out = np.empty(len(x_eval))
    lo = np.searchsorted(x, np.asarray(x_eval) - width / 2)
    hi = np.searchsorted(x, np.asarray(x_eval) + width / 2)
    for i, x0 in enumerate(x_eval):
        xs, ys = x[lo[i]:hi[i]], y[lo[i]:hi[i]]
        u = (xs - x0) / width
        w = np.cos(np.pi * u) ** 2
        if np.count_nonzero(w > 0) < 3:
            out[i] = np.interp(x0, x, y)
            continue
        sw, swx, swy = w.sum(), (w * u).sum(), (w * ys).sum()
        swxx, swxy = (w * u * u).sum(), (w * u * ys).sum()
        det = sw * swxx - swx * swx
        out[i] = swy / sw if det <= 1e-12 * sw * sw else (swxx * swy - swx * swxy) / det
    return out


def _near(r: Ridge, cur: float) -> bool:
    """Whether ridge ``r`` (over an estimate whose mean is ``cur`` times the nominal speed) has
    its time-mean within :data:`NOMINAL_TOL` of the nominal speed."""
    return abs(np.log(r.mean_c * cur)) <= np.log1p(NOMINAL_TOL)


def _rank(r: Ridge, cur: float):
    """The order families are chosen in: a coherent ridge first, then the one nearest the
    nominal speed (a family and its aliases read the same lines at speeds in the ratio of their
    orders: the nominal tells them apart; to 1 %, a bearing's slip), then the strongest."""
    return r.coherent, -round(abs(float(np.log(r.mean_c * cur))), 2), r.level


def estimate(x_left, x_right, fs: float, nominal_hz: float, orders, *, wheel: bool = True,
             spread_limit: float = 0.005) -> SpeedEstimate:
    """The shaft's speed over the record ``(x_left, x_right)`` at ``fs`` from the record itself,
    starting at ``nominal_hz`` (the record's mean, as the user gave it), from the families of the
    bearing ``orders`` (one :class:`FaultOrders` or a (left, right) pair) and, with ``wheel``, the
    wheel's whole orders (module docstring).  ``spread_limit``: the speed's range over its mean
    within which the record counts as at a constant speed (:data:`.speed.TRACK_SPREAD`)."""
    fs = check_fs(fs)
    if not (np.isfinite(nominal_hz) and nominal_hz > 0):
        raise ParameterError(f"nominal_hz = {nominal_hz!r} is not allowed: expected a shaft speed > 0 Hz")
    xs = [_signal(x_left, "left channel"), _signal(x_right, "right channel")]
    fams = families(orders, wheel)
    n = xs[0].size
    t = np.arange(n) / fs
    turns = nominal_hz * n / fs
    top = max(f.order * f.harmonics for f in fams)
    # the envelopes carry the families' harmonics up to ``top`` orders at the first step's
    # highest speed: read at four samples a period of that (decimated behind scipy's
    # anti-alias filter), the rest of the rate is only cost
    q = max(1, int(fs / (4.0 * top * LADDER[0][2] * nominal_hz)))
    envs = []
    for x in xs:
        width = min(2.0 * top * nominal_hz, 0.45 * fs)
        try:
            band = select_band(x, fs, min_width_hz=width)
        except ParameterError:          # a record too short for a band that wide: all of it
            band = None
        e = envelope(x, fs, band)
        envs.append(resample_poly(e - e.mean(), 1, q) if q > 1 else e - e.mean())
    fs_e = fs / q
    t_e = np.arange(envs[0].size) / fs_e
    f_cur = np.full(t_e.size, float(nominal_hz))
    angle = nominal_hz * t_e
    first = last = None
    for L, lo, hi in LADDER:
        L = min(L, turns / 4.0)
        if L < MIN_TURNS:
            return SpeedEstimate("no ridge", f"the record holds {turns:.3g} shaft turns: too few to "
                                 f"follow a line locked to the shaft ({4 * MIN_TURNS:g} at least)",
                                 float(nominal_hz))
        grid = np.exp(np.linspace(np.log(lo), np.log(hi), GRID))
        o, W, th = _whitened(envs, angle, fs_e, L, 1.05 * top * hi)
        if th.size < 4:
            return SpeedEstimate("no ridge", f"the record holds {turns:.3g} shaft turns: too few "
                                 "frames to follow a line locked to the shaft", float(nominal_hz))
        t_frames = np.interp(th, angle, t_e)
        cur = float(np.mean(f_cur)) / nominal_hz
        ridges = []
        for fam in fams:            # one family's maps at a time: a long record's are large
            S, Sc, thr = _family_maps(o, W, fam, grid, L)
            ridges.append(_near_ridge(S, Sc, grid, fam, t_frames, t_e, thr, L, cur))
        del W
        near = [r for r in ridges if _near(r, cur) and r.held.sum() >= 3]
        if first is None:
            first = (near, t_frames)
        if not near:
            return SpeedEstimate("no ridge", "no line locked to the shaft at the given speed stands "
                                 "out of the record's noise", float(nominal_hz))
        best = max(near, key=lambda r: _rank(r, cur))
        corr = _through(th, best.c, best.held, angle, L)
        f_cur = f_cur * np.clip(corr, lo, hi)
        angle = ordertrack.angle_from_speed(t_e, f_cur)
        last = (best, t_frames, L)
    return _decide(t, t_e, f_cur, angle, float(nominal_hz), first, last, spread_limit)


def _decide(t, t_e, f_cur, angle, nominal_hz, first, last, spread_limit) -> SpeedEstimate:
    """The estimate's final profile at the record's instants ``t`` (from ``f_cur`` at the
    envelopes' ``t_e``) and whether it is trusted (module docstring)."""
    best, t_frames, L = last
    fam = best.family
    # the final speed: the estimate smoothed by a local line over the last step's frame (what the
    # earlier, shorter frames left of their noise goes), its mean the nominal speed
    # (on points L/16 apart: the estimate is linear between frames L/4 apart)
    dense = np.linspace(angle[0], angle[-1], max(64, int(16 * (angle[-1] - angle[0]) / L)))
    a_t = np.interp(t, t_e, angle)
    f_fin = np.interp(a_t, dense, _local_line(dense, np.interp(dense, angle, f_cur), dense, L))
    f_fin = np.maximum(f_fin, 1e-3 * nominal_hz)
    angle = ordertrack.angle_from_speed(t, f_fin)
    scale = nominal_hz * (t[-1] - t[0]) / (angle[-1] - angle[0])
    f_fin, angle = f_fin * scale, angle * scale
    held = best.held
    f_frames = np.interp(t_frames, t, f_fin)
    # whether it changes: the profile over SETTLE final frames (a local line), where the frames'
    # own wander (a slipping bearing's line, noise) has averaged out, over the frames it stands in
    a_frames = np.interp(t_frames, t, angle)
    f_in = _local_line(a_frames[held], f_frames[held], a_frames[held], SETTLE * L)
    spread = float((f_in.max() - f_in.min()) / nominal_hz)
    # the first step's ridge of the family, each frame about the final profile: the estimate's
    # scatter frame by frame; the final profile averages LADDER's last frame over the first's
    ones, t1 = first
    one = next((r for r in ones if r.family == fam), max(ones, key=lambda r: _rank(r, 1.0)))
    h1 = one.held
    res = np.log(nominal_hz * one.c[h1] / scale / np.interp(t1[h1], t, f_fin / scale))
    scatter = float(np.std(res)) if h1.sum() > 2 else float("inf")
    # what the estimate cannot tell from a constant speed: its noise (the first step's frames
    # about the final profile, averaged over SETTLE frames of the last) or the line's own wander
    # frame by frame about the settled profile (a slipping bearing's line is locked to the shaft
    # only on average; robust: a step's frames aside)
    r = f_frames[held] / f_in - 1.0
    wander = 1.4826 * float(np.median(np.abs(r - np.median(r))))
    resolved = spread_limit + RESOLVE * max(scatter * np.sqrt(min(LADDER[0][0], L) / (SETTLE * L)),
                                            wander)
    common = dict(nominal_hz=nominal_hz, family=fam.name, t=t_frames, f_hz=f_frames,
                  held=float(held.mean()), spread=spread, scatter=scatter, ratio=float(1.0 / scale))
    other = _disagree(one, ones)
    if spread <= resolved and not other:
        return SpeedEstimate("constant", f"the speed read from the {fam.name} ridge is constant "
                             f"within {max(spread, 1e-4):.2%} (resolved: {resolved:.2%})", **common)
    whole = float((f_fin.max() - f_fin.min()) / nominal_hz)
    if spread <= resolved:
        return SpeedEstimate("untrusted", f"the {fam.name} ridge reads a constant speed, but {other}",
                             **common)
    changes = (f"the speed changes by {whole:.0%} of its mean over the record ({f_fin.min():.3g} to "
               f"{f_fin.max():.3g} Hz read from the {fam.name} ridge)")
    why = _distrust(best, one, t1) or other
    if why:
        return SpeedEstimate("untrusted", f"{changes}, but {why}", **common)
    return SpeedEstimate("changing", changes, angle=angle, **common)


def _distrust(best: Ridge, one: Ridge, t1) -> str:
    """Why the ridge is not to be trusted, or ``""``: it stands in too few frames (``best``, the
    last step's) or it jumps (``one``, the first step's, at frames ``t1`` s)."""
    name = best.family.name
    if best.held.mean() < HOLD:
        return (f"the {name} ridge stands in only {best.held.mean():.0%} of the record "
                f"({HOLD:.0%} needed)")
    rate, k = one.jump()
    if rate > JUMP:
        h = np.flatnonzero(one.held)
        j = h[np.searchsorted(h, k) - 1]
        return (f"the {name} ridge jumps by {np.expm1(abs(np.log(one.c[k] / one.c[j]))):.0%} "
                f"at {t1[k]:.3g} s")
    return ""


def _disagree(one: Ridge, ones) -> str:
    """``""``, or which other coherent family's ridge (of the first step's, ``ones``) tells
    another course of the speed than ``one``'s: each over its own mean (a family's slip is its
    own), frame by frame where both stand, by more than :data:`AGREE` (median).  A ridge that
    hops between the lines of other families is no family's and is not heard."""
    for r in ones:
        if r.family == one.family or not r.coherent:
            continue
        both = one.held & r.held
        if both.sum() < 3:
            continue
        d = np.log(r.c[both] / r.mean_c) - np.log(one.c[both] / one.mean_c)
        if np.median(np.abs(d - np.median(d))) > AGREE or np.abs(np.median(d)) > AGREE:
            return (f"the {r.family.name} ridge tells another speed (a median "
                    f"{np.median(np.abs(d)):.1%} from the {one.family.name} ridge's)")
    return ""

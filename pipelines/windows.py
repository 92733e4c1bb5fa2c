"""A long record (a trip between stations) read in windows of whole shaft turns: each window with
its speed range, its lines, indicators and verdict (:func:`.diagnose.analyse_record`, order-tracked
within the window where its own speed changes), one JSON object a line (JSON Lines) that says
which speed the window was read at (``shaft_hz``, its range ``speed_hz``) and where it came from
(``speed_source``: the file's shaft angle, a speed channel, a tacho, a profile, ``given``, or
``estimated from the record (<family> ridge)``: without a source the speed is read once over the
whole record, :func:`.speed.from_record`, and every window on that clock; a change the record
does not tell with trust makes every window undecided, ``speed_note`` says why); and the
record's summary: the pair of words most windows give, with the share of the read windows that
agree.  A window that cannot be read (too short for the analysis, a refusal of its samples) is
marked ``"not read"`` with the reason; it counts in neither the verdicts nor the shares.
"""
from __future__ import annotations

import json
import math
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axlebox._files import write_text
from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.channel import jsonable

from .diagnose import READ_OPTIONS, analyse_record, read_input
from .speed import Speed

#: the options of :func:`.diagnose.side_bearings` among :func:`.diagnose.analyse_record`'s
BEARING_OPTIONS = ("orders_text", "bore", "bearing", "orders_left", "orders_right", "bearing_left",
                   "bearing_right", "bore_left", "bore_right")


@dataclass
class Windowed:
    """``rows``: one dict a window (JSON-ready); ``summary``: the record's verdict."""

    rows: list[dict]
    turns: float
    overlap: float
    info: dict = field(default_factory=dict)
    speed: tuple = ()          # (t s, shaft Hz) over the record, for the figure

    @property
    def read(self) -> list[dict]:
        return [r for r in self.rows if "not_read" not in r]

    @property
    def summary(self) -> dict:
        """The words (left, right) most read windows give, the share that agree, the count of
        each pair and of windows not read."""
        pairs = Counter((r["words"]["left"], r["words"]["right"]) for r in self.read)
        out = {"windows": len(self.rows), "read": len(self.read), "not_read": len(self.rows) - len(self.read),
               "turns": self.turns, "overlap": self.overlap,
               "counts": [{"left": a, "right": b, "windows": n} for (a, b), n in pairs.most_common()]}
        if pairs:
            (left, right), n = pairs.most_common(1)[0]
            out.update(words={"left": left, "right": right}, share=n / len(self.read))
        else:
            out.update(words=None, share=0.0)
        return out

    def jsonl(self) -> str:
        """One JSON object a window, then the summary (``{"summary": ...}``), a line each."""
        lines = [json.dumps(jsonable(r), allow_nan=False) for r in self.rows]
        return "\n".join(lines + [json.dumps(jsonable({"summary": self.summary}), allow_nan=False)]) + "\n"

    def plot(self, path):
        """The figure of the speed and the verdicts over time: the shaft speed (each window's
        span drawn at its speeds), then each window's words for the two sides at its centre;
        written to ``path`` (PNG), the figure returned."""
        from axlebox._figures import subplots
        words = ("healthy", "pseudo-fault", "undecided", "real fault", "faults on both sides", "not read")
        fig, (a0, a1) = subplots(2, 1, figsize=(8, 5.5), sharex=True, height_ratios=(1, 1.2))
        if len(self.speed):
            a0.plot(self.speed[0], self.speed[1], color="0.3", lw=1.0, label="shaft speed")
        for r in self.rows:
            a0.plot([r["t0_s"], r["t1_s"]], r["speed_hz"], color="C0", alpha=0.5, lw=3)
        a0.set_ylabel("shaft speed, Hz")
        a0.set_title(f"{Path(self.info.get('file', '')).name}: windows of {self.turns:g} turns "
                     f"({self.overlap:g} overlap)")
        for side, mk, dx in (("left", "o", -0.01), ("right", "s", 0.01)):
            xs = [0.5 * (r["t0_s"] + r["t1_s"]) for r in self.rows]
            ys = [words.index(r["words"][side]) if "words" in r else len(words) - 1 for r in self.rows]
            a1.plot(xs, np.array(ys) + dx * 10, mk, ms=8, fillstyle="none" if side == "left" else "full",
                    label=f"{side} ({self.info.get(side, side)})")
        a1.set_yticks(range(len(words)), words)
        a1.set_ylim(-0.5, len(words) - 0.5)
        a1.set_xlabel("time from the record's first sample read, s")
        a1.legend(loc="upper right", fontsize=8)
        a1.grid(axis="y", color="0.9")
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        return fig

    def write(self, path) -> Path:
        path = Path(path)
        if not path.parent.is_dir():
            raise FileNotFoundError(f"--windows-out: folder {str(path.parent)!r} does not exist")
        return write_text(path, self.jsonl())


def bounds(angle: np.ndarray, turns: float, overlap: float) -> list[tuple[int, int]]:
    """Sample ranges ``[i0, i1)`` of windows of ``turns`` shaft turns, each starting
    ``turns (1 - overlap)`` turns after the last, over a record whose shaft is at ``angle``
    (turns, increasing) at each sample; the last window ends within the record."""
    if not (math.isfinite(turns) and turns > 0):
        raise ParameterError(f"--window-turns = {turns!r} is not allowed: expected a number of turns > 0")
    if not (math.isfinite(overlap) and 0 <= overlap < 1):
        raise ParameterError(f"--window-overlap = {overlap!r} is not allowed: expected a share in [0, 1)")
    span = angle[-1] - angle[0]
    if span < turns:
        raise ParameterError(f"--window-turns = {turns:g} is not allowed: the record holds {span:.3g} "
                             "turns; expected at most that")
    step = turns * (1.0 - overlap)
    starts = angle[0] + step * np.arange(int(math.floor((span - turns) / step + 1e-9)) + 1)
    i0 = np.searchsorted(angle, starts)
    i1 = np.searchsorted(angle, starts + turns)
    return [(int(a), int(b)) for a, b in zip(i0, i1)]


def analyse_windows(path, turns: float, overlap: float = 0.5, **options) -> Windowed:
    """Read ``path`` once (:func:`.diagnose.read_input`) and analyse each window of ``turns``
    shaft turns (``overlap`` of a window shared with the next); the rest of ``options`` as
    :func:`.diagnose.analyse_record` takes them."""
    from . import speed as sp
    from .diagnose import rotor_of, shaft_speed, side_bearings
    rec, speed = read_input(path, **{k: v for k, v in options.items() if k in READ_OPTIONS})
    rest = {k: v for k, v in options.items() if k not in READ_OPTIONS or k == "wheel_radius"}
    est = None
    if speed is None:        # the options' or the file's speed: constant, or read from the record
        f = shaft_speed(rec, rest.get("shaft"), rest.get("speed_kmh"), rest.get("wheel_radius", 0.42),
                        rest.get("rpm"))
        if rec.kind != "axlebox-result" and rest.get("order_tracking", "auto") in ("auto", "on"):
            # read once over the whole record: a window is too short for a ridge, and every
            # window must be read on the same clock
            b = side_bearings(rec, **{k: rest[k] for k in BEARING_OPTIONS if k in rest})
            scale = rest.get("scale", 1.0)
            speed, est = sp.from_record(rec.left * scale, rec.right * scale, rec.fs, f,
                                        (b["left"][0].orders, b["right"][0].orders),
                                        rotor_of(rest.get("shaft"), rest.get("rpm")))
    angle = speed.angle if speed is not None else np.arange(rec.left.size) * f / rec.fs
    source = speed.source if speed is not None else ("given" if rec.kind != "axlebox-result"
                                                     else "the file's speed")
    rows = []
    left, right = rec.left, rec.right
    for k, (i0, i1) in enumerate(bounds(angle, turns, overlap)):
        row = {"window": k, "t0_s": i0 / rec.fs, "t1_s": i1 / rec.fs,
               "turns": float(angle[i1 - 1] - angle[i0]), "speed_source": source}
        sub = (sp.Speed(angle[i0:i1], speed.source, speed.rotor, speed.f_hz, speed.estimate)
               if speed is not None else None)
        if sub is not None:
            st = sub.stats(rec.fs)
            row["speed_hz"] = [st["min_hz"], st["max_hz"]]
        else:
            row["speed_hz"] = [float(f)] * 2
        if est is not None and est.status == "untrusted":
            row["speed_note"] = f"{est.reason}; {sp.GIVE}"
        rec.left, rec.right = left[i0:i1], right[i0:i1]
        try:
            info, res = analyse_record(rec, sub, estimate=est if sub is None else None, **rest)
        except ParameterError as err:
            row["not_read"] = str(err)
        else:
            v = res.verdict
            spi = info["speed"] or {}
            row.update(order_tracked=bool(spi.get("order_tracked")),
                       **({"second_look": spi["second_look"]} if "second_look" in spi else {}),
                       shaft_hz=info["shaft_hz"], words=dict(v.words), **v.row())
        finally:
            rec.left, rec.right = left, right
        rows.append(row)
    step = max(1, angle.size // 2000)
    return Windowed(rows, float(turns), float(overlap),
                    {"file": str(path), "kind": rec.kind, "left": rec.names[0], "right": rec.names[1],
                     "fs_hz": rec.fs, "speed": None if speed is None else speed.source,
                     "speed_estimate": None if est is None else est.to_dict(), "notes": rec.notes},
                    (np.arange(angle.size)[::step] / rec.fs, Speed(angle, "").hz(rec.fs)[::step]))


def run_windows(path, turns: float, overlap: float = 0.5, *, out=None, figures=None, log=print,
                **options) -> Windowed:
    """The command: :func:`analyse_windows`, a line a window, the summary, the JSON Lines and
    (``figures``, a folder) the figure of the speed and the verdicts over time."""
    if out is not None and not Path(out).parent.is_dir():
        raise FileNotFoundError(f"--windows-out: folder {str(Path(out).parent)!r} does not exist")
    w = analyse_windows(path, turns, overlap, **options)
    log(f"{Path(path).name}: {len(w.rows)} windows of {turns:g} shaft turns ({overlap:g} overlap); speed "
        f"from {w.info['speed'] or 'the options or the file (constant)'}")
    if w.info.get("speed_estimate"):
        e = w.info["speed_estimate"]
        log(f"speed from the record: {e['status']}: {e['reason']}")
    for r in w.rows:
        head = (f"window {r['window']}: {r['t0_s']:.3f}-{r['t1_s']:.3f} s, {r['turns']:.2f} turns, shaft "
                f"{r['speed_hz'][0]:.4g}-{r['speed_hz'][1]:.4g} Hz")
        if "not_read" in r:
            log(f"{head}: not read: {r['not_read']}")
        else:
            how = " (order-tracked)" if r["order_tracked"] else ""
            if r.get("second_look"):
                how = " (order-tracked; both sides faulty there, read in time as here)"
            log(f"{head}{how}: left {r['words']['left']}, "
                f"right {r['words']['right']} ({r['rule']}); lines: {r['lines'] or 'none'}")
    s = w.summary
    if s["words"] is None:
        log(f"summary: no window read ({s['not_read']} not read)")
    else:
        log(f"summary: left {s['words']['left']}, right {s['words']['right']} in {s['share']:.0%} of "
            f"{s['read']} windows read ({s['not_read']} not read)")
    if out is not None:
        log(f"wrote {w.write(out)}")
    if figures is not None:
        Path(figures).mkdir(parents=True, exist_ok=True)
        png = Path(figures) / f"{Path(path).stem}_windows.png"
        w.plot(png)
        log(f"wrote {png}")
    return w

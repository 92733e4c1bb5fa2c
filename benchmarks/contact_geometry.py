"""Contact geometry tables and track irregularity records: wall time and peak memory.

Run: python3 benchmarks/contact_geometry.py   (prints a markdown table)
"""
import resource
import time
import tracemalloc

from axlebox.mbs.track import irregularity as track
from axlebox.mbs.wheelrail.conicity import equivalent_conicity
from axlebox.mbs.wheelrail.geometry import TrackLayout, contact_table
from axlebox.mbs.wheelrail.standard import chn60, s1002, uic60


def timed(f, *args, **kw):
    tracemalloc.start()
    t0 = time.perf_counter()
    out = f(*args, **kw)
    wall = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
    tracemalloc.stop()
    return out, wall, peak


def main():
    rows = []
    for name, rail, b2b in (("S1002 / 60E1 1:40, 1435 / 1360", uic60(), 1.360),
                            ("S1002 / CHN60 1:40, 1435 / 1353", chn60(), 1.353)):
        for n in (121, 241):
            t, wall, peak = timed(contact_table, s1002(), rail, TrackLayout(back_to_back=b2b),
                                  y_max=0.010, n=n)
            rows.append((f"contact table {name}, {n} positions +-10 mm", wall, peak))
        _, wall, peak = timed(equivalent_conicity, t, [0.001, 0.002, 0.003, 0.004, 0.005, 0.006],
                              "klingel")
        rows.append((f"Klingel conicity at 6 amplitudes, {name}", wall, peak))
    for length in (1000.0, 10000.0):
        p = track.IrregularityParams(grade=5, length=length, lambda_min=1.0, lambda_max=80.0)
        rec, wall, peak = timed(track.generate, p)
        rows.append((f"FRA class 5 record, {length / 1e3:g} km, 1-80 m, step {p.step:g} m", wall, peak))
    print("| task | wall s | peak traced MB |")
    print("| --- | --- | --- |")
    for task, wall, peak in rows:
        print(f"| {task} | {wall:.2f} | {peak:.1f} |")
    print(f"\npeak resident memory of the process: "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")


if __name__ == "__main__":
    main()

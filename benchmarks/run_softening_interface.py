#!/usr/bin/python3
"""A softening interface between two bodies (parameters/
softening_interface.prm): a layer on a base joined by the paper's layer law
p(r) (rising as 2000 r to r = 0.002, softening as 4 - 100 (r - 0.002) to
the rigid limit r = 0.006), the layer's top pressed by a tilted platen
D(x, t) = 0.004 (1 + x / 4) t, so that a softening front moves along the
interface from x = 4 toward x = 0.

The 1D estimate treats every vertical line as two columns in series with
the layer between them, C = 0.5 / 1000 + 0.25 / 500 = 0.001: D = r + C p(r),
solved branch by branch, p_1D(x, t) = p(r(D(x, t))), the force
F_1D(t) = int_0^4 p_1D dx, the front x_f(t) where D = 0.006 (the peak of the
law). While the whole interface is on the rising branch (t <= 0.75) the
two bodies carry the linearly varying load exactly as the columns do (a
linear field), and F = F_1D to round-off; beyond, the bodies spread the
load between the columns and the front lags the estimate.

Prints the table of doc/benchmarks.md (t, F, F_1D, the front: the
smallest x of a node past the peak, and x_f) and with --figure FILE draws
the pressure profiles and the force-displacement curve against the 1D
estimate. --check (the ctest): F = F_1D to 1e-9 for t <= 0.75, the forces
on the two sides balanced to 1e-9 in every step, the front moving toward
x = 0 without going back, and |F - F_1D| / F_1D within 1.5 times its
observed largest value (OBSERVED).

    benchmarks/run_softening_interface.py [--executable build/viscoplastic_contact]
        [--figure doc/figures/softening_interface.png] [--check]
"""

import argparse
import csv
import glob
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
sys.path.insert(0, os.path.join(TOP, "scripts"))
from vc_scripts import set_prm_entries  # noqa: E402

C, PEAK, LIMIT = 0.001, 0.002, 0.006
# The largest |F - F_1D| / F_1D observed (t = 1.3, as the front reaches
# the mesh's coarser part).
OBSERVED = 3.65e-4


def law(r):
    if r <= 0:
        return 0.0
    if r <= PEAK:
        return 2000 * r
    return 4 - 100 * (r - PEAK)


def pressure_1d(D):
    """p from D = r + C p(r), branch by branch."""
    r = D / (1 + 2000 * C)
    if r <= PEAK:
        return law(max(r, 0.0))
    # 4 - 100 (r - PEAK): D = r (1 - 100 C) + C (4 + 100 PEAK).
    r = (D - C * (4 + 100 * PEAK)) / (1 - 100 * C)
    if r <= LIMIT:
        return law(r)
    return (D - LIMIT) / C


def platen(x, t):
    return 0.004 * (1 + x / 4) * t


def force_1d(t, n=4000):
    h = 4.0 / n
    return sum(h * pressure_1d(platen((k + 0.5) * h, t)) for k in range(n))


def front_1d(t):
    """Where D = r + C p(r) = PEAK + 4 C: x = 4 (D / (0.004 t) - 1), in [0, 4]."""
    if t == 0:
        return 4.0
    return min(4.0, max(0.0, 4 * ((PEAK + 4 * C) / (0.004 * t) - 1)))


def run(executable, folder):
    output = os.path.join(folder, "output")
    entries = {(("Output",), "Output directory"): output,
               (("Output",), "Write vtu"): "false"}
    prm_file = os.path.join(TOP, "parameters", "softening_interface.prm")
    with open(prm_file) as f:
        text = set_prm_entries(f.read(), entries).replace(
            "../meshes/", os.path.join(TOP, "meshes") + "/")
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("The run failed:\n%s%s" % (result.stdout[-2000:], result.stderr))
    with open(os.path.join(output, "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    profiles = {}
    for name in sorted(glob.glob(os.path.join(output, "contact_profile_*.csv"))):
        with open(name) as f:
            rows = list(csv.DictReader(f))
        profiles[float(rows[0]["time"])] = sorted(
            (float(r["x"]), float(r["contact_pressure"]), float(r["u_nu"])) for r in rows)
    return series, profiles


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--figure")
    parser.add_argument("--check", action="store_true")
    arguments = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        series, profiles = run(arguments.executable, folder)

    rows = []
    for s in series:
        t = float(s["time"])
        F = float(s["total_contact_force"])
        rows.append({"t": t, "F": F, "F 1D": force_1d(t),
                     "balance": abs(float(s["pair_force_zone_1_y"])
                                    + float(s["opposite_force_zone_1_y"])),
                     "compliance": int(s["compliance_nodes"]),
                     "limit": int(s["unilateral_nodes"])})
    fronts = {}
    for t, profile in profiles.items():
        past = [x for x, _, r in profile if r > PEAK]
        if past:
            fronts[t] = min(past)

    print("| t | F | F_1D | difference | nodes on the law, at the limit | front | 1D front |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        if r["t"] in fronts or abs(r["t"] * 4 - round(r["t"] * 4)) < 1e-9:
            print("| %.2f | %.5g | %.5g | %.2e | %d, %d | %s | %.3g |"
                  % (r["t"], r["F"], r["F 1D"], (r["F"] - r["F 1D"]) / r["F 1D"],
                     r["compliance"], r["limit"],
                     ("%.3g" % fronts[r["t"]]) if r["t"] in fronts else "",
                     front_1d(r["t"])))

    if arguments.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
        for t, profile in sorted(profiles.items()):
            line, = left.plot([x for x, _, _ in profile], [p for _, p, _ in profile], "o",
                              markersize=3.5, label="t = %g" % t)
            xs = [4 * k / 200 for k in range(201)]
            left.plot(xs, [pressure_1d(platen(x, t)) for x in xs], "-",
                      color=line.get_color(), linewidth=1)
        left.set_xlabel("x")
        left.set_ylabel("interface pressure")
        left.set_title("program (dots) and 1D columns (lines)")
        left.legend(fontsize=8)
        right.plot([r["t"] * 0.006 for r in rows], [r["F"] for r in rows], "o",
                   markersize=3.5, label="program")
        ts = [2 * k / 200 for k in range(201)]
        right.plot([t * 0.006 for t in ts], [force_1d(t, 800) for t in ts], "-",
                   label="1D columns")
        right.set_xlabel("mean platen displacement")
        right.set_ylabel("force (per unit thickness)")
        right.legend()
        fig.tight_layout()
        fig.savefig(arguments.figure, dpi=110)

    if arguments.check:
        failures = []
        for r in rows:
            if r["t"] <= 0.75 + 1e-12 and abs(r["F"] - r["F 1D"]) > 1e-9 * r["F 1D"]:
                failures.append("t = %g: F = %.10g, not the 1D force %.10g (rising branch)"
                                % (r["t"], r["F"], r["F 1D"]))
            if r["balance"] > 1e-9 * max(1.0, r["F"]):
                failures.append("t = %g: the forces on the two sides differ by %.2e"
                                % (r["t"], r["balance"]))
        ordered = [fronts[t] for t in sorted(fronts)]
        if any(b > a + 1e-12 for a, b in zip(ordered, ordered[1:])):
            failures.append("the front goes back: %s" % ordered)
        largest = max(abs(r["F"] - r["F 1D"]) / r["F 1D"] for r in rows if r["t"] > 0)
        if largest > 1.5 * OBSERVED:
            failures.append("|F - F_1D| / F_1D reaches %.3g, above 1.5 x %.3g"
                            % (largest, OBSERVED))
        if failures:
            sys.exit("\n".join(failures))
        print("F = F_1D to 1e-9 on the rising branch, the two sides balanced, the front "
              "moving toward x = 0, |F - F_1D| / F_1D at most %.3g." % largest)


if __name__ == "__main__":
    main()

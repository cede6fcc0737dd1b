#!/usr/bin/python3
"""Adhesion with a bonding field: the adhesion column against its ODE, the
peeling strip, and what adhesion costs per step.

The column (parameters/adhesion_column.prm) is in uniaxial strain: its top
pulled up by V t, K = M / H, the separation s of its base and the bonding
beta satisfy

    K (V t - s) = gamma beta^2 min(s, L),
    beta' = -kappa (beta gamma min(s, L)^2 - epsilon)+,   beta(0) = 1,

so s(beta, t) = K V t / (K + gamma beta^2) while that is below L, else
V t - gamma beta^2 L / K: one ODE in beta, solved here by the classical
Runge-Kutta method with 4 x 10^5 steps (its error is below 1e-9, far
below the scheme's). The force P = K (V t - s) rises, peaks where the bond
gives way and falls as beta decays; the debonding time is when beta has
fallen to 1/2 (the program's beta_n^2 = P_n / (gamma min(s_n, L)) from
its force, linear between the steps). The scheme takes each step's
bonding from the last step (first order in k).

--order runs k = 1/16 ... 1/256 and prints the largest error of P over the
steps relative to the peak force and the error of the debonding time, with
their observed orders; --check (also run by ctest) requires the last orders
within [0.9, 1.1] (observed 1.00 and 1.00) and the last errors within 1.5
times the observed ones (5.09e-3 and 3.55e-3). --figure draws
doc/figures/adhesion_column.png (the force-separation curve and the
bonding against the ODE) and doc/figures/peeling_strip.png (the bonding
along the strip of parameters/peeling_strip.prm at a few times and the
peel force). --cost times the peeling strip in 2D (two global
refinements, 256 x 16 cells) and 3D (one, 64 x 4 x 8) with its debonding
glue and with a static one (Debonding rate = 0: a fixed piecewise-linear
law, the kind of the paper's), in pairs run one after
the other (the machine is shared: only ratios measured side by side mean
anything), and prints the median ratio of the time per step.

    benchmarks/run_adhesion_column.py [--executable build/viscoplastic_contact]
        [--check] [--order] [--figure] [--cost] [--pairs 3]
"""

import argparse
import csv
import glob
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import time_per_step  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
E, NU, V = 1000.0, 0.3, 0.02
GAMMA, LENGTH, ENERGY, RATE = 1000.0, 0.01, 0.001, 10.0
K = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))  # plane strain, H = 1
END_TIME = 2.0
# The observed errors at k = 1/256 the check bounds (by 1.5 times).
OBSERVED_FORCE_ERROR, OBSERVED_TIME_ERROR = 5.09e-3, 3.55e-3


def separation(beta, t):
    a = GAMMA * beta * beta
    s = K * V * t / (K + a)
    return s if s <= LENGTH else V * t - a * LENGTH / K


def bonding_rate(beta, t):
    R = min(separation(beta, t), LENGTH)
    return -RATE * max(0.0, beta * GAMMA * R * R - ENERGY)


def reference(steps=400000):
    """(times, beta, P) of the ODE on a fine uniform grid."""
    h = END_TIME / steps
    beta, times, betas, forces = 1.0, [0.0], [1.0], [0.0]
    for n in range(steps):
        t = n * h
        k1 = bonding_rate(beta, t)
        k2 = bonding_rate(beta + 0.5 * h * k1, t + 0.5 * h)
        k3 = bonding_rate(beta + 0.5 * h * k2, t + 0.5 * h)
        k4 = bonding_rate(beta + h * k3, t + h)
        beta = max(0.0, beta + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4))
        times.append(t + h)
        betas.append(beta)
        forces.append(K * (V * (t + h) - separation(beta, t + h)))
    return times, betas, forces


def interpolate(times, values, t):
    step = times[1] - times[0]
    n = min(int(t / step), len(times) - 2)
    theta = (t - times[n]) / step
    return (1 - theta) * values[n] + theta * values[n + 1]


def debonding_time(times, betas):
    """When the bonding has fallen to 1/2 (linear between the samples)."""
    for n in range(len(betas) - 1):
        if betas[n] >= 0.5 > betas[n + 1]:
            return times[n] + (times[n + 1] - times[n]) * (betas[n] - 0.5) \
                / (betas[n] - betas[n + 1])
    sys.exit("the bonding never fell to 1/2")


def bonding_of_force(t, P):
    """beta from the tension: beta^2 = P / (gamma min(s, L)), s = V t - P / K."""
    return math.sqrt(P / (GAMMA * min(V * t - P / K, LENGTH))) if t > 0 else 1.0


def set_entry(text, entry, value):
    pattern = r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry)
    if not re.search(pattern, text):
        sys.exit("no entry %s" % entry)
    return re.sub(pattern, r"\g<1> %s " % value, text)


def run(executable, scene, entries, folder, method=None, vtu=False,
        refinements=0):
    """The scene with the entries set (and the back end and the global
    refinements of its mesh, if given), into folder; returns the rows of
    its time series and its standard output."""
    with open(os.path.join(TOP, "parameters", scene)) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*set Mesh file\s*=\s*)\.\./",
                  r"\g<1>%s/" % os.path.abspath(TOP), text)
    if refinements:
        text = re.sub(r"(?m)^(subsection Geometry)$",
                      r"\g<1>\n  set Global refinements = %d" % refinements, text)
    for entry, value in dict({"Output directory": os.path.join(folder, "output")},
                             **entries).items():
        text = set_entry(text, entry, value)
    text = re.sub(r"(?m)^(subsection Output)$",
                  r"\g<1>\n  set Write vtu = %s\n  set Overwrite = true"
                  r"\n  set Measure cost ratios = true"
                  % ("true" if vtu else "false"), text)
    if method:
        text = set_entry(text, "Method", method)
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("%s with %s failed:\n%s" % (scene, entries, result.stderr))
    with open(os.path.join(folder, "output", "time_series.csv")) as f:
        return list(csv.DictReader(f)), result.stdout


def column(executable, k):
    """The times, tensions P and bondings of the column's steps (with t = 0)."""
    with tempfile.TemporaryDirectory() as folder:
        rows, _ = run(executable, "adhesion_column.prm",
                      {"Time step": k, "Profile times": ""}, folder)
    t = [0.0] + [float(r["time"]) for r in rows]
    P = [0.0] + [-float(r["total_contact_force"]) for r in rows]
    return t, P, [bonding_of_force(s, p) for s, p in zip(t, P)]


def order(executable, check):
    times, betas, forces = reference()
    peak, t_half = max(forces), debonding_time(times, betas)
    print("Peak force %.6f, debonding time (beta = 1/2) %.6f." % (peak, t_half))
    print("| k | largest error of P / peak | order | error of the debonding time | order |")
    print("| --- | --- | --- | --- | --- |")
    force_errors, time_errors = [], []
    for k in [1 / 16, 1 / 32, 1 / 64, 1 / 128, 1 / 256]:
        t, P, beta = column(executable, k)
        force_errors.append(max(abs(p - interpolate(times, forces, s))
                                for s, p in zip(t, P)) / peak)
        time_errors.append(abs(debonding_time(t, beta) - t_half))
        rates = ["%.2f" % (math.log(e[-2] / e[-1]) / math.log(2)) if len(e) > 1
                 else "-" for e in (force_errors, time_errors)]
        print("| 1/%d | %.3e | %s | %.3e | %s |" % (round(1 / k), force_errors[-1],
                                                   rates[0], time_errors[-1], rates[1]))
    if check:
        for name, errors, observed in (("force", force_errors, OBSERVED_FORCE_ERROR),
                                       ("debonding time", time_errors,
                                        OBSERVED_TIME_ERROR)):
            last_order = math.log(errors[-2] / errors[-1]) / math.log(2)
            if not 0.9 <= last_order <= 1.1:
                sys.exit("%s: observed order %.2f, expected within [0.9, 1.1]"
                         % (name, last_order))
            if errors[-1] > 1.5 * observed:
                sys.exit("%s: error %.3e at k = 1/256, bound 1.5 x %.2e"
                         % (name, errors[-1], observed))
            print("%s: order %.2f in [0.9, 1.1], error %.2e within 1.5 x %.2e"
                  % (name, last_order, errors[-1], observed))


def profiles(folder):
    """The bonding along the strip, {time: (x, beta)}, from the profiles."""
    result = {}
    for name in sorted(glob.glob(os.path.join(folder, "output",
                                              "contact_profile_*.csv"))):
        with open(name) as f:
            rows = list(csv.DictReader(f))
        if "z" in rows[0]:  # 3D: the middle of the width
            middle = sorted(set(float(r["z"]) for r in rows))
            middle = middle[len(middle) // 2]
            rows = [r for r in rows if float(r["z"]) == middle]
        rows.sort(key=lambda r: float(r["x"]))
        result[float(rows[0]["time"])] = ([float(r["x"]) for r in rows],
                                          [float(r["bonding"]) for r in rows])
    return result


def figure(executable):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figures = os.path.join(TOP, "doc", "figures")
    times, betas, forces = reference(40000)
    fig, (force_axis, bond_axis) = plt.subplots(1, 2, figsize=(10, 4))
    force_axis.plot([separation(b, t) for t, b in zip(times, betas)], forces,
                    "k-", label="ODE")
    bond_axis.plot(times, betas, "k-", label="ODE")
    for k, marker in ((1 / 16, "o"), (1 / 64, "s")):
        t, P, beta = column(executable, k)
        force_axis.plot([V * s - p / K for s, p in zip(t, P)], P, marker,
                        markersize=3, label="program, k = 1/%d" % round(1 / k))
        bond_axis.plot(t, beta, marker, markersize=3,
                       label="program, k = 1/%d" % round(1 / k))
    force_axis.set_xlabel("separation s")
    force_axis.set_ylabel("tension P")
    bond_axis.set_xlabel("t")
    bond_axis.set_ylabel("bonding beta")
    for axis in (force_axis, bond_axis):
        axis.legend()
        axis.grid(True, alpha=0.3)
    fig.suptitle("Adhesion column: gamma = 1000, L = 0.01, kappa = 10, "
                 "epsilon = 0.001, pulled at V = 0.02")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "adhesion_column.png"), dpi=100)

    fig, (bond_axis, force_axis) = plt.subplots(1, 2, figsize=(10, 4))
    for scene, style in (("peeling_strip.prm", "-"), ("peeling_strip_3d.prm", "--")):
        with tempfile.TemporaryDirectory() as folder:
            rows, _ = run(executable, scene, {}, folder)
            for t, (x, beta) in profiles(folder).items():
                bond_axis.plot(x, beta, style, label="%s, t = %g"
                               % ("3D" if "3d" in scene else "2D", t))
        force_axis.plot([float(r["time"]) for r in rows],
                        [float(r["reaction_prescribed_1_y"]) for r in rows], style,
                        label="3D (per unit width)" if "3d" in scene else "2D")
    bond_axis.set_xlabel("x")
    bond_axis.set_ylabel("bonding beta")
    force_axis.set_xlabel("t")
    force_axis.set_ylabel("peel force")
    for axis in (force_axis, bond_axis):
        axis.legend(fontsize=7)
        axis.grid(True, alpha=0.3)
    fig.suptitle("Peeling strip: a viscoplastic strip glued to a rigid base, "
                 "its end lifted")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "peeling_strip.png"), dpi=100)
    print("wrote doc/figures/adhesion_column.png and peeling_strip.png")


def cost(executable, pairs):
    print("| scene | back end | dofs | time per step, static glue [ms] | "
          "debonding glue [ms] | ratio (median of %d pairs) | active-set "
          "iterations per step, static / debonding |" % pairs)
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for scene, refinements in (("peeling_strip.prm", 2), ("peeling_strip_3d.prm", 1)):
        for method in ("condensed", "full space"):
            ratios, times, iterations = [], {True: [], False: []}, {}
            for pair in range(pairs):
                for debonding in ((True, False) if pair % 2 else (False, True)):
                    with tempfile.TemporaryDirectory() as folder:
                        rows, stdout = run(executable, scene,
                                           {} if debonding else {"Debonding rate": 0},
                                           folder, method, refinements=refinements)
                        times[debonding].append(time_per_step(stdout))
                        iterations[debonding] = statistics.mean(
                            int(r["active_set_iterations"]) for r in rows)
                ratios.append(times[True][-1] / times[False][-1])
            dofs = max(int(n) for n in re.findall(r"([0-9]+) (?:displacement )?dofs",
                                                  stdout))
            print("| %s | %s | %d | %.2f | %.2f | %.3f | %.2f / %.2f |"
                  % (scene, method, dofs, 1e3 * statistics.median(times[False]),
                     1e3 * statistics.median(times[True]),
                     statistics.median(ratios), iterations[False],
                     iterations[True]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable",
                        default=os.path.join(TOP, "build", "viscoplastic_contact"))
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--order", action="store_true")
    parser.add_argument("--figure", action="store_true")
    parser.add_argument("--cost", action="store_true")
    parser.add_argument("--pairs", type=int, default=3)
    arguments = parser.parse_args()
    if arguments.check or arguments.order:
        order(arguments.executable, arguments.check)
    if arguments.figure:
        figure(arguments.executable)
    if arguments.cost:
        cost(arguments.executable, arguments.pairs)


if __name__ == "__main__":
    main()

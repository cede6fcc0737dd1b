#!/usr/bin/python3
"""A cohesive interface with damage: the cohesive column against its closed
form, and the peel of a pre-cracked strip against beam theory.

The column (parameters/cohesive_column.prm) is in uniaxial strain, its top
pulled to U = 0.03, pushed back to 0 and pulled to 0.06; K = M / H. With
the envelope T (stiffness K_c = 1000 to T_c = 10 at delta_0 = 0.01, linear
softening to 0 at delta_f = 0.04) and m(t) the largest opening before t,
the opening delta and the tension P = K (U - delta) satisfy

    K (U - delta) = T(m) delta / m   for delta <= m   (the secant),
                  = T(delta)         beyond,

one solution for every U since T softens by less than K; with
exponential softening the same holds with the polygon of the envelope
(written out here from its definition). The damage is
rate-independent, so this holds at every time: with Cohesive damage =
implicit (the envelope in the step) the program's steps are exact
(tests/run_cohesive_column.sh). With Cohesive damage = explicit a step's
opening beyond max(m, delta_0) follows a plateau at the tension reached
before it: a monotone law, with a tension that lags the envelope by one
step. --order runs the implicit update with both softenings (and checks
the area under the exponential polygon, G_c) and the explicit update with
k = 1/16 ... 1/256, and prints
the largest error of P over the steps relative to T_c, with its observed
order; --check (also run by ctest) requires the last order within
[0.9, 1.1] (observed 1.00) and the last error within 1.5 times the
observed one (1.38e-2), and the implicit update's error below 1e-9.

The peel (parameters/cohesive_peel.prm) is the half of a double
cantilever beam: an elastic strip of thickness h = 0.5 lifted at its end
by Delta, bonded beyond a pre-crack of 2. Beam theory with linear elastic
fracture mechanics (the arm clamped where the crack ends, G = P^2 a^2 /
(2 E' I), E' = E / (1 - nu^2), I = h^3 / 12) gives, while the crack runs,

    P(Delta) = ((2 E' I G_c)^(3/2) / (3 E' I Delta))^(1/2).

--peel runs the explicit update with k = 1/64 ... 1/1024 (and one global
refinement of the mesh) and prints the force at Delta = 0.5, its ratio to
beam theory and the observed order in k; the implicit update is run once
to show where it stops (the active set cycles once the crack runs: the
envelope softens far more than the slender strip carries). --figure draws
doc/figures/cohesive_column.png (the force-opening cycle, implicit and
explicit) and doc/figures/cohesive_peel.png (the lift force against beam
theory, and the damage along the strip).

--cost times the peel in 2D (two global refinements, 256 x 16 cells) and
3D (cohesive_peel_3d.prm, one, 64 x 4 x 8) with its cohesive interface
(explicit damage) and with a static glue of the same stiffness and
strength (Adhesion stiffness = K, Adhesion length = delta_0, Debonding
rate = 0: a fixed piecewise-linear law, the kind of the paper's, which the
cohesive law is for a node that has not been damaged yet), in pairs run
one after the other (the machine is shared: only ratios measured side by
side mean anything), and prints the median ratio of the time per step.

    benchmarks/run_cohesive_column.py [--executable build/viscoplastic_contact]
        [--check] [--order] [--peel] [--figure] [--cost] [--pairs 3]
"""

import argparse
import csv
import glob
import math
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, run_in_temporary_directory,
                        set_prm_entries, time_per_step)

E, NU = 1000.0, 0.3
K = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))  # plane strain, H = 1
STIFFNESS, STRENGTH, ENERGY = 1000.0, 10.0, 0.2
D0, DF = STRENGTH / STIFFNESS, 2 * ENERGY / STRENGTH
# The explicit update's observed error at k = 1/256 (the check's bound is
# 1.5 times it).
OBSERVED_ERROR = 1.38e-2


def top(t):
    return 0.03 * max(min(t, 3 - 2 * t), 0) + 0.06 * max(t - 1.5, 0)


def envelope_points(softening="linear"):
    """The envelope's points (delta_k, T_k), written out here from the
    definition (doc/model.md, section 12): linear, or the exponential tail
    T_c exp(-x / lambda), lambda = (G_c - T_c delta_0 / 2) / T_c, at 15
    equal steps down to T_c / 1000, then 0 one step on, its openings
    stretched so that the area under the polygon is G_c."""
    if softening == "linear":
        return [(0.0, 0.0), (D0, STRENGTH), (DF, 0.0)]
    tail_energy = ENERGY - STRENGTH * D0 / 2
    length = tail_energy / STRENGTH
    step = length * math.log(1000.0) / 15
    tail = [(j * step, STRENGTH * math.exp(-j * step / length)) for j in range(16)]
    tail.append((16 * step, 0.0))
    area = sum((b[0] - a[0]) * (a[1] + b[1]) / 2 for a, b in zip(tail, tail[1:]))
    return [(0.0, 0.0)] + [(D0 + x * tail_energy / area, T) for x, T in tail]


def envelope(x, points):
    for (a, Ta), (b, Tb) in zip(points, points[1:]):
        if x <= b:
            return Ta + (Tb - Ta) * (x - a) / (b - a)
    return 0.0


def exact(t, m, points):
    """(delta, P) at time t after the largest opening m: on the secant up to
    max(m, delta_0), else on the envelope's segment beyond m that holds the
    solution of K (U - delta) = T(delta) (one: every segment softens by less
    than K), else broken."""
    U = top(t)
    reached = max(m, D0)
    delta = K * U / (K + envelope(reached, points) / reached)
    if delta <= reached:
        return delta, K * (U - delta)
    for (a, Ta), (b, Tb) in zip(points, points[1:]):
        if b <= reached:
            continue
        slope = (Tb - Ta) / (b - a)
        delta = (K * U - Ta + slope * a) / (K + slope)
        if delta <= b:
            return delta, K * (U - delta)
    return U, 0.0


def reference(times, softening="linear"):
    """The exact tensions at the given times (m from a grid fine enough to
    hold every kink of the load, t = 1 and 1.5, and the given times)."""
    points = envelope_points(softening)
    grid = sorted(set([n / 4096 for n in range(4096 * 5 // 2 + 1)] + list(times)))
    m, tension = 0.0, {}
    for t in grid:
        delta, P = exact(t, m, points)
        m = max(m, delta)
        tension[t] = P
    return [tension[t] for t in times]


def scene_text(name, entries, refinements=0):
    """A shipped scene with its mesh path made absolute and the entries
    {(subsection path, entry): value} set; no VTU files."""
    with open(os.path.join(REPO_ROOT, "parameters", name)) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*set Mesh file\s*=\s*)\.\./",
                  r"\g<1>%s/" % REPO_ROOT, text)
    entries = dict(entries)
    entries[(("Output",), "Output directory")] = "output"
    entries[(("Output",), "Write vtu")] = "false"
    if refinements:
        entries[(("Geometry",), "Global refinements")] = refinements
    return set_prm_entries(text, entries)


def time_series(folder):
    with open(os.path.join(folder, "output", "time_series.csv")) as f:
        return list(csv.DictReader(f))


def column(executable, k, damage, softening="linear", method="condensed"):
    """(times, tensions) of the column's steps."""
    text = scene_text("cohesive_column.prm",
                      {(("Time",), "Time step"): k, (("Output",), "Profile times"): "",
                       (("Contact",), "Cohesive damage"): damage,
                       (("Contact",), "Cohesive softening"): softening,
                       (("Linear solver",), "Method"): method})
    with run_in_temporary_directory(executable, text) as (folder, _, _):
        rows = time_series(folder)
    return ([float(r["time"]) for r in rows],
            [-float(r["total_contact_force"]) for r in rows])


def order(executable, check):
    implicit_error = 0
    for softening, method in (("linear", "condensed"), ("exponential", "condensed"),
                              ("exponential", "full space"),
                              ("exponential", "matrix free")):
        t, P = column(executable, 1 / 16, "implicit", softening, method)
        error = max(abs(p - q) for p, q in zip(P, reference(t, softening))) / STRENGTH
        print("Implicit damage, %s softening, %s, k = 1/16: largest error of P / "
              "T_c %.2e." % (softening, method, error))
        implicit_error = max(implicit_error, error)
    points = envelope_points("exponential")
    area = sum((b[0] - a[0]) * (a[1] + b[1]) / 2 for a, b in zip(points, points[1:]))
    print("Exponential envelope: work of separation %.12f (G_c = %g), delta_f = %.5f."
          % (area, ENERGY, points[-1][0]))
    print("| k | largest error of P / T_c, explicit damage | order |")
    print("| --- | --- | --- |")
    errors = []
    for k in [1 / 16, 1 / 32, 1 / 64, 1 / 128, 1 / 256]:
        t, P = column(executable, k, "explicit")
        errors.append(max(abs(p - q) for p, q in zip(P, reference(t))) / STRENGTH)
        rate = ("%.2f" % (math.log(errors[-2] / errors[-1]) / math.log(2))
                if len(errors) > 1 else "-")
        print("| 1/%d | %.3e | %s |" % (round(1 / k), errors[-1], rate))
    if check:
        if abs(area - ENERGY) > 1e-12:
            sys.exit("exponential envelope: work %.15f, expected G_c" % area)
        if implicit_error > 1e-9:
            sys.exit("implicit damage: error %.2e, expected below 1e-9" % implicit_error)
        last_order = math.log(errors[-2] / errors[-1]) / math.log(2)
        if not 0.9 <= last_order <= 1.1:
            sys.exit("explicit damage: observed order %.2f, expected within [0.9, 1.1]"
                     % last_order)
        if errors[-1] > 1.5 * OBSERVED_ERROR:
            sys.exit("explicit damage: error %.3e at k = 1/256, bound 1.5 x %.2e"
                     % (errors[-1], OBSERVED_ERROR))
        print("implicit exact (%.1e); explicit: order %.2f in [0.9, 1.1], error "
              "%.2e within 1.5 x %.2e" % (implicit_error, last_order, errors[-1],
                                           OBSERVED_ERROR))


def beam_theory(delta, thickness=0.5, energy=0.02):
    EI = E / (1 - NU * NU) * thickness ** 3 / 12
    return math.sqrt((2 * EI * energy) ** 1.5 / (3 * EI * delta))


def peel(executable, k, damage="explicit", refinements=1):
    """(lifts Delta, forces, damage profiles {t: (x, damage)}) of the peel,
    or the failure's first line."""
    text = scene_text("cohesive_peel.prm",
                      {(("Time",), "Time step"): k, (("Contact",), "Cohesive damage"): damage},
                      refinements)
    try:
        with run_in_temporary_directory(executable, text) as (folder, _, _):
            rows = time_series(folder)
            profiles = {}
            for name in sorted(glob.glob(os.path.join(folder, "output",
                                                      "contact_profile_*.csv"))):
                with open(name) as f:
                    nodes = sorted(csv.DictReader(f), key=lambda r: float(r["x"]))
                profiles[float(nodes[0]["time"])] = (
                    [float(r["x"]) for r in nodes], [float(r["damage"]) for r in nodes])
    except RuntimeError as failure:
        accepted = re.search(r"last accepted state \(t = ([0-9.e+-]+)\)", str(failure))
        return ("the step after t = %s failed (the active set cycles)" % accepted.group(1)
                if accepted else str(failure)[-300:])
    return ([0.5 * float(r["time"]) for r in rows],
            [float(r["reaction_prescribed_1_y"]) for r in rows], profiles)


def peel_table(executable):
    implicit = peel(executable, 1 / 256, "implicit")
    if isinstance(implicit, str):
        print("Implicit damage, k = 1/256: %s" % implicit.strip())
    print("| k | force at Delta = 0.5 | / beam theory %.4f | order |" % beam_theory(0.5))
    print("| --- | --- | --- | --- |")
    forces = []
    for k in [1 / 64, 1 / 128, 1 / 256, 1 / 512, 1 / 1024]:
        lifts, P, _ = peel(executable, k)
        forces.append(P[-1])
        rate = ("%.2f" % (math.log((forces[-3] - forces[-2]) / (forces[-2] - forces[-1]))
                          / math.log(2)) if len(forces) > 2 else "-")
        print("| 1/%d | %.5f | %.4f | %s |" % (round(1 / k), P[-1],
                                               P[-1] / beam_theory(0.5), rate))
    limit = forces[-1] + (forces[-1] - forces[-2])  # first order: Richardson
    print("Extrapolated to k = 0 (first order): %.5f, %.4f times beam theory."
          % (limit, limit / beam_theory(0.5)))


def figure(executable):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figures = os.path.join(REPO_ROOT, "doc", "figures")
    fig, axis = plt.subplots(figsize=(6, 4))
    t = [n / 1024 for n in range(1, 1024 * 5 // 2 + 1)]
    for softening, style in (("linear", "k-"), ("exponential", "k--")):
        P = reference(t, softening)
        axis.plot([top(s) - p / K for s, p in zip(t, P)], P, style,
                  label="closed form, %s softening" % softening)
    for k, damage, softening, marker in ((1 / 16, "implicit", "linear", "o"),
                                         (1 / 16, "explicit", "linear", "s"),
                                         (1 / 64, "explicit", "linear", "^"),
                                         (1 / 16, "implicit", "exponential", "x")):
        times, forces = column(executable, k, damage, softening)
        axis.plot([top(s) - p / K for s, p in zip(times, forces)], forces, marker,
                  markersize=3, label="%s damage, %s, k = 1/%d"
                  % (damage, softening, round(1 / k)))
    axis.set_xlabel("opening delta")
    axis.set_ylabel("tension P")
    axis.legend(fontsize=7)
    axis.grid(True, alpha=0.3)
    axis.set_title("Cohesive column: pulled, pushed back, pulled off", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "cohesive_column.png"), dpi=100)

    fig, (force_axis, damage_axis) = plt.subplots(1, 2, figsize=(10, 4))
    lifts = [0.005 * n for n in range(20, 101)]
    force_axis.plot(lifts, [beam_theory(d) for d in lifts], "k-",
                    label="beam theory (crack running)")
    for k in (1 / 64, 1 / 256, 1 / 1024):
        result = peel(executable, k)
        force_axis.plot(result[0], result[1], label="explicit damage, k = 1/%d"
                        % round(1 / k))
    for t, (x, damage) in result[2].items():
        damage_axis.plot(x, damage, label="t = %g (Delta = %g)" % (t, 0.5 * t))
    force_axis.set_xlabel("lift Delta")
    force_axis.set_ylabel("lift force P")
    force_axis.set_ylim(0, 0.4)
    damage_axis.set_xlabel("x")
    damage_axis.set_ylabel("damage")
    for axis in (force_axis, damage_axis):
        axis.legend(fontsize=7)
        axis.grid(True, alpha=0.3)
    fig.suptitle("Peel of a pre-cracked strip (half a double cantilever beam), "
                 "128 x 8 cells; damage at k = 1/1024")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "cohesive_peel.png"), dpi=100)
    print("wrote doc/figures/cohesive_column.png and cohesive_peel.png")


def cost(executable, pairs):
    static_glue = {(("Contact",), "Cohesive strength"): 0,
                   (("Contact",), "Adhesion stiffness"): 10000,
                   (("Contact",), "Adhesion length"): 5e-4,
                   (("Contact",), "Debonding rate"): 0}
    print("| scene | back end | dofs | time per step, static glue [ms] | "
          "cohesive interface [ms] | ratio (median of %d pairs) | active-set "
          "iterations per step, static / cohesive |" % pairs)
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for scene, refinements in (("cohesive_peel.prm", 2), ("cohesive_peel_3d.prm", 1)):
        for method in ("condensed", "full space"):
            ratios, times, iterations = [], {True: [], False: []}, {}
            for pair in range(pairs):
                for cohesive in ((True, False) if pair % 2 else (False, True)):
                    entries = {(("Linear solver",), "Method"): method,
                               (("Output",), "Profile times"): "",
                               (("Output",), "Print timing summary"): "true",
                               (("Output",), "Measure cost ratios"): "true"}
                    if not cohesive:
                        entries.update(static_glue)
                    text = scene_text(scene, entries, refinements)
                    with run_in_temporary_directory(executable, text) as (folder, stdout, _):
                        rows = time_series(folder)
                    times[cohesive].append(time_per_step(stdout))
                    iterations[cohesive] = statistics.mean(
                        int(r["active_set_iterations"]) for r in rows)
                ratios.append(times[True][-1] / times[False][-1])
            dofs = max(int(n) for n in re.findall(r"([0-9]+) displacement dofs", stdout))
            print("| %s | %s | %d | %.2f | %.2f | %.3f | %.2f / %.2f |"
                  % (scene, method, dofs, 1e3 * statistics.median(times[False]),
                     1e3 * statistics.median(times[True]), statistics.median(ratios),
                     iterations[False], iterations[True]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_executable_argument(parser)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--order", action="store_true")
    parser.add_argument("--peel", action="store_true")
    parser.add_argument("--figure", action="store_true")
    parser.add_argument("--cost", action="store_true")
    parser.add_argument("--pairs", type=int, default=3)
    arguments = parser.parse_args()
    executable = resolve_executable(arguments.executable)
    if arguments.check or arguments.order:
        order(executable, arguments.check)
    if arguments.peel:
        peel_table(executable)
    if arguments.figure:
        figure(executable)
    if arguments.cost:
        cost(executable, arguments.pairs)


if __name__ == "__main__":
    main()

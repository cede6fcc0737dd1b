#!/usr/bin/python3
"""Normal compliance with memory: the memory column against its ODE, the
memory foundation against the same scene without memory, and what the
memory costs per step.

The column (parameters/memory_column.prm) is in uniaxial strain: with
K = M / L, S = K + c1 and the memory m = h1 + h2 of the kernel
b(t) = a1 exp(-lambda1 t) + a2,

    r = (K D - m) / S,   h' = a r - Lambda h   (a = (a1, a2),
                                                Lambda = diag(lambda1, 0)),

a linear system h' = a K D / S - A h, A = a 1^T / S + Lambda, solved in
closed form: h(t) = (I - exp(-A t)) A^{-1} a K D / S, the force
P(t) = K (D - r(t)). The scheme takes each step's memory from the
penetration of the last step (first order in k).

--order runs k = 1/16 ... 1/256 and prints the largest relative error of
P over the steps against the closed form, with its observed order;
--check (also run by ctest) requires the last order within [0.9, 1.1]
(observed 0.99) and the last error within 1.5 times the observed one
(1.34e-3). --figure draws doc/figures/memory_column.png (the force and the
memory against the closed form) and doc/figures/memory_foundation.png
(parameters/memory_foundation.prm with and without the memory: the contact
force and the nodes at the rigid limit). --cost times the memory
foundation (2D, Subdivisions 128) and its 3D version (Subdivisions 16)
with and without the memory term, in pairs run one after the other
(the machine is shared: only ratios measured side by side mean anything),
and prints the median ratio of the time per step.

    benchmarks/run_memory_column.py [--executable build/viscoplastic_contact]
        [--check] [--order] [--figure] [--cost] [--pairs 3]
"""

import argparse
import csv
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

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..")
E, NU, D, C1 = 1000.0, 0.3, 0.01, 1000.0
WEIGHTS, RATES = np.array([500.0, 100.0]), np.array([2.0, 0.0])
K = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))  # plane strain, L = 1
S = K + C1


def closed_form(t):
    """(P, m) at time t > 0 of the column's ODE."""
    A = np.outer(WEIGHTS, np.ones(2)) / S + np.diag(RATES)
    forcing = WEIGHTS * K * D / S
    values, vectors = np.linalg.eig(A)
    decay = (vectors @ np.diag(np.exp(-values * t)) @ np.linalg.inv(vectors)).real
    h = (np.eye(2) - decay) @ np.linalg.solve(A, forcing)
    m = h.sum()
    r = (K * D - m) / S
    return K * (D - r), m


def set_entry(text, entry, value):
    pattern = r"(?m)^(\s*set %s\s*=)[^#\n]*" % re.escape(entry)
    if not re.search(pattern, text):
        sys.exit("no entry %s" % entry)
    return re.sub(pattern, r"\g<1> %s " % value, text)


def run(executable, scene, entries, folder, method=None):
    """The scene with the entries set (and the back end, if given), into
    folder; returns the rows of its time series and its standard output."""
    with open(os.path.join(TOP, "parameters", scene)) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*set Mesh file\s*=\s*)\.\./",
                  r"\g<1>%s/" % os.path.abspath(TOP), text)
    for entry, value in dict({"Output directory": os.path.join(folder, "output")},
                             **entries).items():
        text = set_entry(text, entry, value)
    text = re.sub(r"(?m)^(subsection Output)$",
                  r"\g<1>\n  set Write vtu = false\n  set Overwrite = true"
                  r"\n  set Measure cost ratios = true", text)
    if method:
        text += "\nsubsection Linear solver\n  set Method = %s\nend\n" % method
    prm = os.path.join(folder, "scene.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("%s with %s failed:\n%s" % (scene, entries, result.stderr))
    with open(os.path.join(folder, "output", "time_series.csv")) as f:
        return list(csv.DictReader(f)), result.stdout


def column_errors(executable, k):
    """The largest relative error of P over the steps, and the rows."""
    with tempfile.TemporaryDirectory() as folder:
        rows, _ = run(executable, "memory_column.prm",
                      {"Time step": k, "Profile times": ""}, folder)
    worst = 0.0
    for row in rows:
        exact = closed_form(float(row["time"]))[0]
        worst = max(worst, abs(float(row["total_contact_force"]) - exact) / exact)
    return worst, rows


def order(executable, check):
    steps = [1 / 16, 1 / 32, 1 / 64, 1 / 128, 1 / 256]
    print("| k | largest relative error of P | observed order |")
    print("| --- | --- | --- |")
    errors = []
    for k in steps:
        errors.append(column_errors(executable, k)[0])
        rate = (math.log(errors[-2] / errors[-1]) / math.log(2)
                if len(errors) > 1 else None)
        print("| 1/%d | %.3e | %s |" % (round(1 / k), errors[-1],
                                        "%.2f" % rate if rate else "-"))
    last_order = math.log(errors[-2] / errors[-1]) / math.log(2)
    if check:
        if not 0.9 <= last_order <= 1.1:
            sys.exit("observed order %.2f, expected within [0.9, 1.1]" % last_order)
        if errors[-1] > 1.5 * 1.34e-3:
            sys.exit("error %.3e at k = 1/256, bound 1.5 x 1.34e-3" % errors[-1])
        print("order %.2f in [0.9, 1.1], error %.2e within 1.5 x 1.34e-3"
              % (last_order, errors[-1]))


def foundation_rows(executable, scene, memory, folder, entries=None,
                    method=None):
    entries = dict(entries or {})
    if not memory:
        entries.update({"Memory weights": "", "Memory rates": ""})
    return run(executable, scene, entries, folder, method)


def figure(executable):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figures = os.path.join(TOP, "doc", "figures")
    fig, (force_axis, memory_axis) = plt.subplots(1, 2, figsize=(10, 4))
    times = np.linspace(1e-6, 2, 400)
    exact = np.array([closed_form(t) for t in times])
    force_axis.plot(times, exact[:, 0], "k-", label="closed form")
    memory_axis.plot(times, exact[:, 1], "k-", label="closed form")
    for k, marker in ((1 / 8, "o"), (1 / 32, "s")):
        rows = column_errors(executable, k)[1]
        t = [float(r["time"]) for r in rows]
        force_axis.plot(t, [float(r["total_contact_force"]) for r in rows],
                        marker, markersize=3, label="program, k = 1/%d" % round(1 / k))
        # m_n = P_n - c1 r_n with r_n = D - P_n / K.
        memory_axis.plot(t, [float(r["total_contact_force"])
                             - C1 * (D - float(r["total_contact_force"]) / K)
                             for r in rows], marker, markersize=3,
                         label="program, k = 1/%d" % round(1 / k))
    force_axis.set_xlabel("t")
    force_axis.set_ylabel("contact force P")
    memory_axis.set_xlabel("t")
    memory_axis.set_ylabel("memory pressure m")
    for axis in (force_axis, memory_axis):
        axis.legend()
        axis.grid(True, alpha=0.3)
    fig.suptitle("Memory column: b(t) = 500 exp(-2t) + 100, D held from t = 0")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "memory_column.png"), dpi=100)

    fig, (force_axis, rigid_axis) = plt.subplots(1, 2, figsize=(10, 4))
    for memory, style in ((True, "-"), (False, "--")):
        with tempfile.TemporaryDirectory() as folder:
            rows, _ = foundation_rows(executable, "memory_foundation.prm",
                                      memory, folder)
        t = [float(r["time"]) for r in rows]
        label = "with memory" if memory else "without memory"
        force_axis.plot(t, [float(r["total_contact_force"]) for r in rows],
                        style, label=label)
        rigid_axis.plot(t, [int(r["unilateral_nodes"]) for r in rows], style,
                        label=label)
    force_axis.set_ylabel("contact force")
    rigid_axis.set_ylabel("nodes at the rigid limit")
    for axis in (force_axis, rigid_axis):
        axis.set_xlabel("t")
        axis.legend()
        axis.grid(True, alpha=0.3)
    fig.suptitle("Memory foundation: the paper's square, two load cycles, "
                 "b(t) = 400 exp(-2t)")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "memory_foundation.png"), dpi=100)
    print("wrote doc/figures/memory_column.png and memory_foundation.png")


def cost(executable, pairs):
    print("| scene | back end | dofs | time per step without memory [ms] | "
          "with memory [ms] | ratio (median of %d pairs) |" % pairs)
    print("| --- | --- | --- | --- | --- | --- |")
    for scene, entries in (("memory_foundation.prm", {"Subdivisions": 128}),
                           ("memory_foundation_3d.prm", {"Subdivisions": 16,
                                                         "End time": 1,
                                                         "Profile times": 1})):
        for method in ("condensed", "full space"):
            ratios, times = [], {True: [], False: []}
            for pair in range(pairs):
                for memory in ((True, False) if pair % 2 else (False, True)):
                    with tempfile.TemporaryDirectory() as folder:
                        _, stdout = foundation_rows(executable, scene, memory,
                                                    folder, entries, method)
                        times[memory].append(time_per_step(stdout))
                ratios.append(times[True][-1] / times[False][-1])
            # The mesh of the run (after any initial cycles): the most dofs.
            dofs = max(int(n) for n in re.findall(r"([0-9]+) (?:displacement )?dofs",
                                                  stdout))
            print("| %s | %s | %d | %.2f | %.2f | %.3f |"
                  % (scene, method, dofs, 1e3 * statistics.median(times[False]),
                     1e3 * statistics.median(times[True]),
                     statistics.median(ratios)))


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

#!/usr/bin/python3
"""Accuracy per degree of freedom with and without refinement toward Gamma_3.

The 2D benchmark (parameters/default.prm) on quadrilaterals, k = 1/64 for
every run, so that the time discretisation is the same everywhere and only
the mesh differs:

* uniform meshes with Subdivisions = 8, 16, 32, 64, 128;
* graded meshes: Subdivisions = 4, 8, 16, 32, 64 with Contact refinement
  levels = 1 and = 2 (the cells touching Gamma_3 refined once or twice more);
* the reference: a uniform mesh with Subdivisions = 256.

Errors at t = 1 against the reference, all on Gamma_3 where the contact law
acts (the reference profile is interpolated linearly in x):
* u_nu: the relative L2(Gamma_3) error of the normal displacement
  (lumped: the nodal weights of the coarse run);
* pressure: the same for the contact pressure z_i / w_i;
* force: the relative error of the total contact force.

Writes <output-dir>/graded_study.csv, graded_study.md, graded_study.png.

    benchmarks/run_graded_study.py [--executable build/viscoplastic_contact]
                                   [--output-dir doc/graded]
"""

import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, resolve_executable,  # noqa: E402
                        run_in_temporary_directory, set_prm_entries)
TIME_STEP = 1.0 / 64


def run(executable, subdivisions, levels):
    with open(os.path.join(REPO_ROOT, "parameters", "default.prm")) as f:
        text = f.read()
    text = set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Geometry",), "Cell type"): "hypercube",
        (("Geometry",), "Contact refinement levels"): str(levels),
        (("Time",), "Time step"): repr(TIME_STEP),
        (("Output",), "Output directory"): "results",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "1",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "false",
    })
    with run_in_temporary_directory(executable, text) as (workdir, out, wall):
        dofs = int(out.split(" displacement dofs")[0].split()[-1])
        results = os.path.join(workdir, "results")
        profile = [f for f in os.listdir(results) if f.startswith("contact_profile_")]
        with open(os.path.join(results, sorted(profile)[-1])) as f:
            nodes = sorted(csv.DictReader(f), key=lambda r: float(r["x"]))
        with open(os.path.join(results, "time_series.csv")) as f:
            force = float(list(csv.DictReader(f))[-1]["total_contact_force"])
    return {"subdivisions": subdivisions, "levels": levels, "dofs": dofs,
            "wall_time": wall, "force": force,
            "x": [float(r["x"]) for r in nodes],
            "u_nu": [float(r["u_nu"]) for r in nodes],
            "pressure": [float(r["contact_pressure"]) for r in nodes],
            "weight": [float(r["weight"]) for r in nodes]}


def interpolate(xs, ys, x):
    if x <= xs[0]:
        return ys[0]
    for i in range(1, len(xs)):
        if x <= xs[i]:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return (1 - t) * ys[i - 1] + t * ys[i]
    return ys[-1]


def relative_error(run, reference, key):
    num = den = 0.0
    for x, value, w in zip(run["x"], run[key], run["weight"]):
        exact = interpolate(reference["x"], reference[key], x)
        num += w * (value - exact) ** 2
        den += w * exact ** 2
    return math.sqrt(num / den)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable")
    parser.add_argument("--output-dir", default=os.path.join(REPO_ROOT, "doc", "graded"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)

    print("reference: uniform, Subdivisions = 256 ...", flush=True)
    reference = run(executable, 256, 0)
    runs = []
    for n in (8, 16, 32, 64, 128):
        runs.append(run(executable, n, 0))
    for levels in (1, 2):
        for n in (4, 8, 16, 32, 64):
            runs.append(run(executable, n, levels))
    for r in runs:
        r["error_u_nu"] = relative_error(r, reference, "u_nu")
        r["error_pressure"] = relative_error(r, reference, "pressure")
        r["error_force"] = abs(r["force"] - reference["force"]) / reference["force"]
        print("n = %3d, levels %d: %6d dofs, errors u_nu %.3e pressure %.3e force %.3e"
              % (r["subdivisions"], r["levels"], r["dofs"], r["error_u_nu"],
                 r["error_pressure"], r["error_force"]), flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    keys = ["subdivisions", "levels", "dofs", "wall_time", "force",
            "error_u_nu", "error_pressure", "error_force"]
    with open(os.path.join(args.output_dir, "graded_study.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(keys)
        for r in runs:
            writer.writerow([r[k] for k in keys])
    lines = ["# Accuracy per degree of freedom: uniform and graded meshes", "",
             "Generated by `benchmarks/run_graded_study.py`. The 2D benchmark on "
             "quadrilaterals, k = 1/64 in every run; errors at t = 1 on Gamma_3 "
             "against a uniform mesh with Subdivisions = 256 (%d dofs, the same k). "
             "*levels* = Contact refinement levels (0: uniform). h at Gamma_3 is "
             "1/(Subdivisions 2^levels)." % reference["dofs"], "",
             "| Subdivisions | levels | h at Gamma_3 | dofs | rel. L2 error u_nu | "
             "rel. L2 error pressure | rel. error total force | wall time [s] |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in runs:
        lines.append("| %d | %d | 1/%d | %d | %.3e | %.3e | %.3e | %.2f |" % (
            r["subdivisions"], r["levels"], r["subdivisions"] * 2 ** r["levels"],
            r["dofs"], r["error_u_nu"], r["error_pressure"], r["error_force"],
            r["wall_time"]))
    with open(os.path.join(args.output_dir, "graded_study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for ax, key, title in zip(axes, ["error_u_nu", "error_pressure", "error_force"],
                              ["u_nu on Gamma_3 (rel. L2)",
                               "contact pressure on Gamma_3 (rel. L2)",
                               "total contact force (rel.)"]):
        for levels, marker, label in ((0, "o", "uniform"), (1, "s", "graded, 1 level"),
                                      (2, "^", "graded, 2 levels")):
            sel = [r for r in runs if r["levels"] == levels]
            ax.loglog([r["dofs"] for r in sel], [r[key] for r in sel],
                      marker=marker, label=label)
        ax.set_xlabel("displacement dofs")
        ax.set_title(title + ", t = 1")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    axes[0].set_ylabel("error against the Subdivisions = 256 run")
    fig.tight_layout()
    fig.savefig(os.path.join(args.output_dir, "graded_study.png"), dpi=110)


if __name__ == "__main__":
    main()

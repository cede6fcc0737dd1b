#!/usr/bin/python3
"""Work and precision of fixed and adaptive time steps (doc/adaptivity.md).

The 2D benchmark (parameters/default.prm) on a fixed mesh, run with fixed
steps k = 1/8 ... 1/256 and with adaptive steps (Time step control =
adaptive) for a range of Error tolerances, against a fixed-step reference
on the same mesh: what is measured is the time-discretisation error alone.
The fixed steps converge at first order (the errors halve with k), so the
reference is the Richardson extrapolation 2 q(1/4096) - q(1/2048) of the
runs with k = 1/4096 and 1/2048 (the k = 1/4096 run alone would still be
off by about 2e-4). Every run lands on t = 0.25, 0.5, 0.75, 1 (Profile times; the
fixed steps all contain these levels), where the errors are taken:

* force: max over these four times of the relative error of the total
  contact force (time_series.csv);
* strain, stress: the relative errors of ||eps(u)||_L2 and ||sigma||_L2 at
  t = 1 (the run summary);
* error: the largest of the three.

Work: the number of steps (accepted; adaptive runs also report their
rejected steps, which cost a solve each), the wall time of the whole
process, and the wall time of the time loop (the last wall_time of
time_series.csv, output included; no VTU is written); both the minimum of
REPETITIONS runs, since the machine is shared.

Variants are rows of MESH_VARIANTS: (label, parameter overrides). Each
variant gets its own reference and its own fixed and adaptive runs, so that
mesh variants (graded or adaptive meshes) can be added as one line each.

Writes <output-dir>/work_precision_time.csv, work_precision_time.md and
work_precision_time.png.

    benchmarks/run_work_precision.py [--executable build/viscoplastic_contact]
                                     [--output-dir doc/adaptivity]
"""

import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, run_in_temporary_directory,
                        set_prm_entries)

# (label, {(subsection path, entry): value}): the meshes to compare on.
MESH_VARIANTS = [
    ("uniform h = 1/32", {(("Geometry",), "Subdivisions"): "32"}),
]
FIXED_STEPS = [1 / 8, 1 / 16, 1 / 32, 1 / 64, 1 / 128, 1 / 256]
TOLERANCES = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4]
REFERENCE_STEP = 1 / 4096
REPETITIONS = 3
COMPARISON_TIMES = [0.25, 0.5, 0.75, 1.0]


def run(executable, overrides, control, time_step, tolerance=1e-3,
        repetitions=REPETITIONS):
    """The minimum wall times of some repetitions of one run."""
    runs = [run_once(executable, overrides, control, time_step, tolerance)
            for _ in range(repetitions)]
    best = dict(runs[0])
    best["wall_time"] = min(r["wall_time"] for r in runs)
    best["loop_time"] = min(r["loop_time"] for r in runs)
    return best


def run_once(executable, overrides, control, time_step, tolerance):
    """One run; returns its measurements."""
    with open(os.path.join(REPO_ROOT, "parameters", "default.prm")) as f:
        text = f.read()
    entries = {
        (("Time",), "Time step"): repr(time_step),
        (("Time",), "Time step control"): control,
        (("Time",), "Error tolerance"): repr(tolerance),
        (("Time",), "Maximum time step"): "0.25",
        (("Output",), "Output directory"): "results",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): ", ".join(map(str, COMPARISON_TIMES)),
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "false",
    }
    entries.update(overrides)
    text = set_prm_entries(text, entries)
    with run_in_temporary_directory(executable, text) as (workdir, out, wall):
        with open(os.path.join(workdir, "results", "time_series.csv")) as f:
            rows = list(csv.DictReader(f))
    force = {}
    for row in rows:
        t = float(row["time"])
        for target in COMPARISON_TIMES:
            if abs(t - target) < 1e-12:
                force[target] = float(row["total_contact_force"])
    missing = [t for t in COMPARISON_TIMES if t not in force]
    if missing:
        raise RuntimeError("no step at t = %s" % missing)
    norms = re.search(r"\|\|eps\(u\)\|\|_L2 = ([^,]+), \|\|sigma\|\|_L2 = ([^,]+),",
                      out)
    rejected = re.search(r"adaptive time steps: \d+ accepted, (\d+) rejected",
                         out)
    return {
        "control": control,
        "time_step": time_step if control == "fixed" else float("nan"),
        "tolerance": tolerance if control == "adaptive" else float("nan"),
        "steps": len(rows),
        "rejected": int(rejected.group(1)) if rejected else 0,
        "smallest_step": min(float(r["time_step"]) for r in rows),
        "largest_step": max(float(r["time_step"]) for r in rows),
        "wall_time": wall,
        "loop_time": float(rows[-1]["wall_time"]),
        "force": force,
        "strain": float(norms.group(1)),
        "stress": float(norms.group(2)),
    }


def add_errors(r, reference):
    r["error_force"] = max(abs(r["force"][t] - reference["force"][t])
                           / abs(reference["force"][t]) for t in COMPARISON_TIMES)
    r["error_strain"] = abs(r["strain"] - reference["strain"]) / reference["strain"]
    r["error_stress"] = abs(r["stress"] - reference["stress"]) / reference["stress"]
    r["error"] = max(r["error_force"], r["error_strain"], r["error_stress"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_executable_argument(parser)
    parser.add_argument("--output-dir",
                        default=os.path.join(REPO_ROOT, "doc", "adaptivity"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)

    runs = []
    references = {}
    for label, overrides in MESH_VARIANTS:
        print("%s: reference k = 1/%d ..." % (label, round(1 / REFERENCE_STEP)),
              flush=True)
        reference = run(executable, overrides, "fixed", REFERENCE_STEP,
                        repetitions=1)
        half = run(executable, overrides, "fixed", 2 * REFERENCE_STEP,
                   repetitions=1)
        # Richardson: the first-order error of k = 1/4096 removed.
        for t in COMPARISON_TIMES:
            reference["force"][t] = 2 * reference["force"][t] - half["force"][t]
        for key in ("strain", "stress"):
            reference[key] = 2 * reference[key] - half[key]
        references[label] = reference
        for k in FIXED_STEPS:
            runs.append(dict(run(executable, overrides, "fixed", k), variant=label))
        for tolerance in TOLERANCES:
            runs.append(dict(run(executable, overrides, "adaptive", 1 / 64,
                                 tolerance), variant=label))
        for r in runs:
            if r["variant"] == label:
                add_errors(r, reference)
                print("  %-8s k %-9.4g tol %-8.3g: %4d steps (%2d rejected), "
                      "error %.3e (force %.3e, strain %.3e, stress %.3e), "
                      "%.2f s" % (r["control"], r["time_step"], r["tolerance"],
                                  r["steps"], r["rejected"], r["error"],
                                  r["error_force"], r["error_strain"],
                                  r["error_stress"], r["wall_time"]), flush=True)

    os.makedirs(args.output_dir, exist_ok=True)
    keys = ["variant", "control", "time_step", "tolerance", "steps", "rejected",
            "smallest_step", "largest_step", "wall_time", "loop_time",
            "error_force", "error_strain", "error_stress", "error"]
    with open(os.path.join(args.output_dir, "work_precision_time.csv"), "w",
              newline="") as f:
        writer = csv.writer(f)
        writer.writerow(keys)
        for r in runs:
            writer.writerow([r[k] for k in keys])

    lines = ["# Work and precision: fixed and adaptive time steps", "",
             "Generated by `benchmarks/run_work_precision.py` (Release build, "
             "one rank, the shared 2-core machine). The 2D benchmark "
             "(parameters/default.prm, explicit history update), the errors "
             "against fixed steps on the same mesh (the Richardson "
             "extrapolation of k = 1/%d and twice that): *force* the "
             "largest relative error of the total contact force at t = %s, "
             "*strain* and *stress* the relative errors of ||eps(u)||_L2 and "
             "||sigma||_L2 at t = 1, *error* the largest of the three. "
             "Adaptive runs start with k = 1/64, Maximum time step = 0.25 "
             "(the stability cap 0.9 x 0.12 s is lower); *steps* are the "
             "accepted steps, *rejected* the repeated ones (each costs a "
             "solve). *process* is the wall time of the whole run (about "
             "0.3-0.5 s of it is starting MPI and loading the libraries), "
             "*loop* that of the time loop, each the minimum of %d runs." % (
                 round(1 / REFERENCE_STEP),
                 ", ".join(map(str, COMPARISON_TIMES)), REPETITIONS), ""]
    for label, _ in MESH_VARIANTS:
        lines += ["## " + label, "",
                  "| steps | k or tolerance | steps | rejected | k range | "
                  "error | force | strain | stress | process [s] | loop [s] |",
                  "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|"]
        for r in runs:
            if r["variant"] != label:
                continue
            setting = ("k = 1/%d" % round(1 / r["time_step"])
                       if r["control"] == "fixed" else "tol = %g" % r["tolerance"])
            lines.append(
                "| %s | %s | %d | %d | %.3g ... %.3g | %.2e | %.2e | %.2e | "
                "%.2e | %.2f | %.3f |" % (
                    r["control"], setting, r["steps"], r["rejected"],
                    r["smallest_step"], r["largest_step"], r["error"],
                    r["error_force"], r["error_strain"], r["error_stress"],
                    r["wall_time"], r["loop_time"]))
        ref = references[label]
        lines += ["", "Reference: %d steps, %.2f s (and the run with half "
                  "the steps)." % (ref["steps"], ref["wall_time"]), ""]
    with open(os.path.join(args.output_dir, "work_precision_time.md"), "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for label, _ in MESH_VARIANTS:
        for control, marker in (("fixed", "o"), ("adaptive", "s")):
            sel = [r for r in runs if r["variant"] == label and r["control"] == control]
            name = "%s, %s" % (label, control)
            axes[0].loglog([r["steps"] + r["rejected"] for r in sel],
                           [r["error"] for r in sel], marker=marker, label=name)
            axes[1].loglog([r["loop_time"] for r in sel],
                           [r["error"] for r in sel], marker=marker, label=name)
            axes[2].loglog([r["steps"] + r["rejected"] for r in sel],
                           [r["error_force"] for r in sel], marker=marker,
                           label=name)
    axes[0].set_xlabel("steps (accepted + rejected)")
    axes[1].set_xlabel("wall time of the time loop [s]")
    axes[2].set_xlabel("steps (accepted + rejected)")
    axes[0].set_ylabel("error (largest of force, strain, stress)")
    axes[1].set_ylabel("error (largest of force, strain, stress)")
    axes[2].set_ylabel("contact force error (max over t)")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Time-discretisation error against the extrapolated "
                 "k = 1/%d" % round(1 / REFERENCE_STEP))
    fig.tight_layout()
    fig.savefig(os.path.join(args.output_dir, "work_precision_time.png"), dpi=110)


if __name__ == "__main__":
    main()

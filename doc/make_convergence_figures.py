#!/usr/bin/env python3
"""Regenerate the convergence results of doc/accuracy.md from the program.

Runs the convergence studies of parameters/ (convergence.prm: h = k =
1/2 ... 1/32 against 1/64; convergence_fine.prm: h = k = 1/4 ... 1/128
against 1/256; convergence_implicit.prm: as convergence.prm with the
implicit stress update), the stability sweeps
stability_lambda_{50,5,0.5}{,_implicit}.prm and soft_layer.prm, all on the
default mesh (P1 triangles, Simplex pattern = /), then writes

  doc/figures/convergence.png  error against wall time and against h + k,
  doc/figures/stability.png    error against k for three viscosities,
  doc/convergence_tables.md    the tables (errors, observed orders, dofs,
                               steps, wall time) and the active-set
                               iterations per step against the mesh size.

Usage: doc/make_convergence_figures.py [--executable PATH] [--skip-runs]
"""

import argparse
import csv
import glob
import math
import os
import subprocess
import sys

if "matplotlib" not in sys.modules and sys.executable != "/usr/bin/python3":
    try:
        import matplotlib  # noqa: F401
    except ImportError:  # Debian's matplotlib lives with /usr/bin/python3
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import REPO_ROOT, resolve_executable  # noqa: E402

STUDIES = [("convergence", "explicit scheme, h = k = 1/2 ... 1/32 against 1/64"),
           ("convergence_fine", "explicit scheme, h = k = 1/4 ... 1/128 against 1/256"),
           ("convergence_implicit", "implicit scheme, h = k = 1/2 ... 1/32 against 1/64")]
# Stability sweeps: viscosity lambda -> parameter file; h = 1/16 fixed.
VISCOSITIES = ["50", "5", "0.5"]
LARGEST_ELASTIC_EIGENVALUE = 1000 / (1 - 0.4)  # E/(1-k), plane stress
DOC_DIR = os.path.join(REPO_ROOT, "doc")


def read_rows(path):
    with open(path, newline="") as f:
        # Empty fields (a run that failed has no dofs or steps) read as NaN.
        return [{k: float(v) if v else float("nan") for k, v in row.items()}
                for row in csv.DictReader(f)]


def iterations_per_step(study):
    """Mean and largest active-set iteration count per step of every run."""
    result = []
    for series in glob.glob(os.path.join(REPO_ROOT, "output", study, "runs",
                                         "*", "time_series.csv")):
        with open(series, newline="") as f:
            rows = list(csv.DictReader(f))
        parameters = open(os.path.join(os.path.dirname(series),
                                       "parameters.prm")).read()
        # The last Geometry/Subdivisions entry is the run's (the study
        # appends the entries it changed).
        geometry = parameters.split("subsection Geometry")[-1]
        subdivisions = int(geometry.split("set Subdivisions")[1]
                           .split("=")[1].split()[0])
        iterations = [int(r["active_set_iterations"]) for r in rows]
        result.append((subdivisions, len(rows),
                       sum(iterations) / len(iterations), max(iterations)))
    return sorted(result)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable", default=None)
    parser.add_argument("--skip-runs", action="store_true")
    args = parser.parse_args()

    if not args.skip_runs:
        executable = resolve_executable(args.executable)
        names = [study for study, _ in STUDIES]
        names += [f"stability_lambda_{v}" for v in VISCOSITIES]
        names += [f"stability_lambda_{v}_implicit" for v in VISCOSITIES]
        names += ["soft_layer"]
        for study in names:
            print(f"running parameters/{study}.prm ...", flush=True)
            with open(os.path.join(REPO_ROOT, "output", f"{study}.log"), "w") as log:
                subprocess.run([executable, f"parameters/{study}.prm"],
                               cwd=REPO_ROOT, stdout=log,
                               stderr=subprocess.STDOUT, check=True)

    tables = {study: read_rows(os.path.join(REPO_ROOT, "output", study,
                                            "convergence.csv"))
              for study, _ in STUDIES}

    figure, (by_time, by_size) = plt.subplots(1, 2, figsize=(11, 4.5))
    for (study, label), marker in zip(STUDIES, ["o", "s", "^"]):
        rows = [r for r in tables[study] if math.isfinite(r["error"])]
        error = [r["error"] for r in rows]
        by_time.loglog([r["wall_time"] for r in rows], error, marker + "-",
                       label=label)
        by_size.loglog([r["h"] + r["k"] for r in rows], error, marker + "-",
                       label=label)
    rows = tables["convergence_fine"]
    x = [r["h"] + r["k"] for r in rows]
    by_size.loglog(x, [rows[0]["error"] * xi / x[0] for xi in x], "k--",
                   label="first order")
    by_time.set_xlabel("wall time of the run [s]")
    by_size.set_xlabel("h + k")
    for axes in (by_time, by_size):
        axes.set_ylabel(r"max$_n$ ($\|u_n - u_n^{ref}\|_V + "
                        r"\|\sigma_n - \sigma_n^{ref}\|_Q$)")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=8)
    by_time.set_title("Work-precision: error against run time")
    by_size.set_title("Error against h + k")
    figure.tight_layout()
    os.makedirs(os.path.join(DOC_DIR, "figures"), exist_ok=True)
    figure.savefig(os.path.join(DOC_DIR, "figures", "convergence.png"), dpi=120)

    # Stability: error against k on a fixed mesh; blow-ups drawn at the top.
    figure, axes = plt.subplots(figsize=(10, 5))
    ceiling = 1e3
    for viscosity, color in zip(VISCOSITIES, ["C0", "C1", "C2"]):
        rows = read_rows(os.path.join(REPO_ROOT, "output",
                                      f"stability_lambda_{viscosity}",
                                      "convergence.csv"))
        k = [r["k"] for r in rows]
        error = [min(r["error"], ceiling) if r["error"] == r["error"] else ceiling
                 for r in rows]
        axes.loglog(k, error, "o-", color=color,
                    label=f"explicit scheme, lambda = {viscosity}")
        bound = 4 * float(viscosity) / LARGEST_ELASTIC_EIGENVALUE
        axes.axvline(bound, color=color, linestyle=":",
                     label=f"stability limit 4 lambda/lambda_max(E) = {bound:.3g}")
        tables[f"stability_lambda_{viscosity}"] = rows
    for viscosity, color in zip(VISCOSITIES, ["C0", "C1", "C2"]):
        rows = read_rows(os.path.join(REPO_ROOT, "output",
                                      f"stability_lambda_{viscosity}_implicit",
                                      "convergence.csv"))
        tables[f"stability_lambda_{viscosity}_implicit"] = rows
        finite = [r for r in rows if math.isfinite(r["error"])]
        axes.loglog([r["k"] for r in finite], [r["error"] for r in finite],
                    "^--", color=color,
                    label=f"implicit scheme, lambda = {viscosity} (runs "
                          f"that converged)")
    axes.axhline(ceiling, color="k", linewidth=0.8)
    axes.text(0.3, ceiling * 1.3, "blow-up (error >= 1e3 drawn here)", fontsize=8)
    axes.set_xlabel("time step k  (h = 1/16 fixed, reference k = 1/1024)")
    axes.set_ylabel("time discretisation error (norm of the convergence study)")
    axes.set_ylim(top=ceiling * 3)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    axes.set_title("Stability: explicit and implicit stress update")
    figure.tight_layout()
    figure.savefig(os.path.join(DOC_DIR, "figures", "stability.png"), dpi=120)

    lines = ["# Convergence tables", "",
             "Generated by doc/make_convergence_figures.py from the "
             "convergence.csv files the program writes (P1 triangles with the "
             "default Simplex pattern = /, one MPI rank, Release build, one "
             "run of each study on the 2-core machine; wall times include "
             "set-up).", ""]
    for study, label in STUDIES:
        lines += [f"## parameters/{study}.prm: {label}", "",
                  "| h | k | dofs | steps | wall [s] | error u | order | "
                  "error sigma | order | error | order |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in tables[study]:
            if not math.isfinite(r["error"]):
                lines.append(f"| 1/{int(round(1 / r['h']))} | "
                             f"1/{int(round(1 / r['k']))} | failed: the "
                             f"step's iteration did not converge | | | | | | "
                             f"| | |")
                continue

            def order(key):
                return "-" if r[key] != r[key] else f"{r[key]:.2f}"
            lines.append(
                f"| 1/{int(round(1 / r['h']))} | 1/{int(round(1 / r['k']))} | "
                f"{int(r['dofs'])} | {int(r['steps'])} | {r['wall_time']:.3g} | "
                f"{r['error_u']:.3e} | {order('order_u')} | "
                f"{r['error_sigma']:.3e} | {order('order_sigma')} | "
                f"{r['error']:.3e} | {order('order')} |")
        lines.append("")
    for viscosity in VISCOSITIES + [f"{v}_implicit" for v in VISCOSITIES]:
        value, _, implicit = viscosity.partition("_")
        scheme = "implicit" if implicit else "explicit"
        lines += [f"## parameters/stability_lambda_{viscosity}.prm: {scheme} "
                  f"scheme, h = 1/16, lambda = {value}, against k = 1/1024 "
                  f"(same scheme)", "",
                  "| k | error u | error sigma | error | order in k |",
                  "|---|---|---|---|---|"]
        for r in tables[f"stability_lambda_{viscosity}"]:
            order = "-" if r["order"] != r["order"] else f"{r['order']:.2f}"
            if r["error"] == float("inf"):
                lines.append(f"| 1/{int(round(1 / r['k']))} | stopped (see "
                             f"doc/accuracy.md) | | | |")
                continue
            lines.append(f"| 1/{int(round(1 / r['k']))} | {r['error_u']:.3e} | "
                         f"{r['error_sigma']:.3e} | {r['error']:.3e} | {order} |")
        lines.append("")
    # The too-soft layer: what the program says and does.
    log = open(os.path.join(REPO_ROOT, "output", "soft_layer.log")).read()
    with open(os.path.join(REPO_ROOT, "output", "soft_layer", "time_series.csv"),
              newline="") as f:
        series = list(csv.DictReader(f))
    iterations = [int(r["active_set_iterations"]) for r in series]
    lines += ["## parameters/soft_layer.prm: a layer that softens too much", "",
              "Start-up report and outcome of the run (h = 1/32, k = 1/64):", "",
              "```"]
    lines += [l for l in log.splitlines()
              if l.startswith(("Uniqueness", "WARNING"))]
    lines += ["```", "",
              f"Steps completed: {len(series)}; active-set iterations: "
              f"{sum(iterations)} in total, at most {max(iterations)} in one "
              f"step; at t = 1: {series[-1]['unilateral_nodes']} nodes at the "
              f"rigid limit, {series[-1]['compliance_nodes']} in normal "
              f"compliance.", ""]
    lines += ["## Active-set iterations per time step against the mesh size", "",
              "From the runs of parameters/convergence_fine.prm (h = k), "
              "reference run included.", "",
              "| h = k | steps | mean iterations per step | largest |",
              "|---|---|---|---|"]
    for subdivisions, steps, mean, largest in iterations_per_step("convergence_fine"):
        lines.append(f"| 1/{subdivisions} | {steps} | {mean:.2f} | {largest} |")
    with open(os.path.join(DOC_DIR, "convergence_tables.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote doc/figures/convergence.png, doc/figures/stability.png and "
          "doc/convergence_tables.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Preconditioners for one elastic solve of the 3D cube: ML's smoothed
aggregation as the program configured it, ML with other settings, hypre's
BoomerAMG through PETSc, and a matrix-free geometric multigrid on the
hexahedral p4est mesh. Writes doc/performance/preconditioners.md and
preconditioners.png (read in doc/performance.md, section
"Preconditioners").

Each size is one process of benchmarks/preconditioner_comparison.cc (build
it with `make preconditioner_comparison` in a Release build directory),
which assembles K and b of the scene (parameters/cube_3d.prm on hexahedra,
parameters/cube_3d_tetrahedra.prm on tetrahedra, Subdivisions = N) once and
then solves K u = b by CG from zero to the scene's Tolerance (1e-10
relative) with every preconditioner in turn, checking that all give the
same u. Two parts:

1. the sweep: many settings of each preconditioner at one size per cell
   type (--sweep-hexahedra, --sweep-tetrahedra);
2. the scaling: the preconditioner as the program had it and the best of
   each kind, across sizes up to more than 1.2M dofs (hexahedra) and 1M
   (tetrahedra), one process per size, one after the other.

Usage:
    benchmarks/run_preconditioner_comparison.py
        [--executable BUILD/preconditioner_comparison]
        [--sweep-hexahedra 32] [--sweep-tetrahedra 32]
        [--hexahedra 16,24,32,48,64,80] [--tetrahedra 16,24,32,48,64,69]
        [--output doc/performance/preconditioners.md]
    benchmarks/run_preconditioner_comparison.py --figures-only

Times are wall times on whatever machine runs it; compare ratios within
one invocation.
"""

import argparse
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import REPO_ROOT  # noqa: E402

SCENES = {"hexahedra": "cube_3d.prm", "tetrahedra": "cube_3d_tetrahedra.prm"}

# The settings of the sweep: (label, variant of preconditioner_comparison).
# The first is the program's configuration before this comparison: deal.II's
# AdditionalData for elliptic problems (Chebyshev of degree 2, Amesos-KLU on
# the coarsest level), aggregation threshold 0.02, the rigid-body modes, and
# ML's "PDE equations" left at 1.
ML_BEFORE = "ml:pde=1,thr=0.02"
ML_CHOSEN = "ml:pde=3,thr=0"
HYPRE_BEST = "hypre:bs=3,theta=0.5,coarsen=HMIS,interp=ext+i,pmax=4"
GMG_BEST = "gmg:degree=4"
SWEEP = [
    ("ML, PDE equations 1, threshold 0.02", ML_BEFORE),
    ("ML, PDE equations 3", "ml:pde=3"),
    ("ML, PDE equations 3, threshold 0 (chosen for hexahedra)", ML_CHOSEN),
    ("ML, PDE equations 1, threshold 0", "ml:pde=1,thr=0"),
    ("ML, PDE equations 3, threshold 0.05", "ml:pde=3,thr=0.05"),
    ("ML, PDE equations 3, threshold 0.1", "ml:pde=3,thr=0.1"),
    ("ML, threshold 0, Chebyshev degree 3", "ml:pde=3,thr=0,sweeps=3"),
    ("ML, threshold 0, Chebyshev degree 4", "ml:pde=3,thr=0,sweeps=4"),
    ("ML, threshold 0, symmetric Gauss-Seidel x1",
     "ml:pde=3,thr=0,smoother=sgs,sweeps=1"),
    ("ML, threshold 0, symmetric Gauss-Seidel x2",
     "ml:pde=3,thr=0,smoother=sgs,sweeps=2"),
    ("ML, threshold 0, smoother as coarse solver",
     "ml:pde=3,thr=0,coarse=smoother"),
    ("ML, threshold 0, translations only", "ml:pde=3,thr=0,modes=0"),
    ("BoomerAMG, block size 3, theta 0.5", "hypre:bs=3,theta=0.5"),
    ("BoomerAMG, block size 3, theta 0.7", "hypre:bs=3,theta=0.7"),
    ("BoomerAMG, HMIS, ext+i, P_max 4, block size 3, theta 0.5", HYPRE_BEST),
    ("BoomerAMG, as above, l1-scaled SOR/Jacobi smoother",
     HYPRE_BEST + ",relax=l1scaled-SOR/Jacobi"),
    ("BoomerAMG, HMIS, ext+i, P_max 4, theta 0.6, aggressive coarsening 1",
     "hypre:bs=3,theta=0.6,agg=1,coarsen=HMIS,interp=ext+i,pmax=4"),
    ("BoomerAMG, HMIS, ext+i, P_max 4, theta 0.5, nodal coarsening 4",
     HYPRE_BEST + ",nodal=4"),
    ("GMG matrix-free, Chebyshev degree 4", GMG_BEST),
    ("GMG matrix-free, Chebyshev degree 3", "gmg:degree=3"),
    ("GMG matrix-free, Chebyshev degree 5", "gmg:degree=5"),
    ("GMG, CG on the assembled K", "gmg:degree=4,outer=matrix"),
]

# The scaling: the configuration before, the chosen one, and the best of
# the other kinds.
SCALING = [
    ("ML, PDE equations 1, threshold 0.02", ML_BEFORE),
    ("ML, PDE equations 3, threshold 0 (chosen for hexahedra)", ML_CHOSEN),
    ("BoomerAMG, HMIS, ext+i, P_max 4, block size 3, theta 0.5", HYPRE_BEST),
    ("GMG matrix-free, Chebyshev degree 4", GMG_BEST),
]


def applies(cells, spec):
    """The geometric multigrid needs the p4est level hierarchy."""
    return cells == "hexahedra" or not spec.startswith("gmg")


def parse_result(line, labels):
    """A RESULT line of preconditioner_comparison as a row, or None."""
    fields = line.rstrip("\n").split("\t")
    if fields[0] != "RESULT":
        return None
    return {"cells": fields[1], "N": int(fields[2]),
            "dofs": int(fields[3]), "spec": fields[4],
            "label": labels.get(fields[4], fields[4]),
            "setup": float(fields[5]), "solve": float(fields[6]),
            "iterations": int(fields[7]), "memory": float(fields[8]),
            "difference": float(fields[9]), "converged": fields[10] == "yes",
            "note": fields[11] if len(fields) > 11 else ""}


def read_log(path, n_sweep_processes):
    """The rows of a saved output of this script (its standard output):
    the first n_sweep_processes processes are the sweep, the others the
    scaling. The process peak is the program's own VmHWM line."""
    labels = {spec: label for label, spec in SWEEP + SCALING}
    blocks = []
    with open(path) as f:
        for line in f:
            if line.startswith("# ") and " dofs, " in line:
                blocks.append([])
            elif line.startswith("# peak memory of the process:"):
                for row in blocks[-1]:
                    row["peak"] = float(line.split(":")[1].split()[0])
            else:
                row = parse_result(line, labels)
                if row is not None:
                    blocks[-1].append(row)
    for block in blocks:
        for row in block:
            row.setdefault("peak", float("nan"))
    return ([r for b in blocks[:n_sweep_processes] for r in b],
            [r for b in blocks[n_sweep_processes:] for r in b])


def run(executable, cells, n, variants):
    """One process: K and b of the scene at Subdivisions = n, then every
    variant. Returns the rows and the process' peak memory (MB)."""
    specs = [spec for _, spec in variants if applies(cells, spec)]
    labels = {spec: label for label, spec in variants}
    command = [executable, os.path.join(REPO_ROOT, "parameters",
                                        SCENES[cells]), str(n)] + specs
    env = dict(os.environ, OMP_NUM_THREADS="1", DEAL_II_NUM_THREADS="1")
    start = time.time()
    process = subprocess.Popen(command, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, env=env)
    rows, output = [], []
    for line in process.stdout:
        output.append(line)
        print(line, end="", flush=True)
        row = parse_result(line, labels)
        if row is not None:
            rows.append(row)
    _, status, usage = os.wait4(process.pid, 0)
    if status != 0:
        sys.exit(f"{' '.join(command)} failed:\n{''.join(output[-20:])}")
    peak = usage.ru_maxrss / 1024
    for row in rows:
        row["peak"] = peak
    print(f"# {cells} N = {n}: {time.time() - start:.1f} s", flush=True)
    return rows


HEADER = ("| cells | N | dofs | preconditioner | set-up [s] | solve [s] | "
          "CG iterations | set-up + solve [s] | preconditioner memory [MB] | "
          "process peak [MB] | difference to first | one product with K, "
          "one cycle |\n"
          "| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: "
          "| ---: | ---: |")


def table_line(r):
    return (f"| {r['cells']} | {r['N']} | {r['dofs']} | {r['label']} "
            f"(`{r['spec']}`) | {r['setup']:.3g} | {r['solve']:.3g} | "
            f"{r['iterations']}{'' if r['converged'] else ' (not conv.)'} | "
            f"{r['setup'] + r['solve']:.3g} | {r['memory']:.0f} | "
            f"{r['peak']:.0f} | {r['difference']:.1e} | {short(r['note'])} |")


def short(note):
    """'K 12.345678 ms, cycle 45.678901 ms' as '12 ms, 46 ms'."""
    words = note.replace(",", "").split()
    try:
        return f"{float(words[1]):.3g} ms, {float(words[4]):.3g} ms"
    except (IndexError, ValueError):
        return note


def read_table(path):
    """The rows of the scaling table of a written preconditioners.md."""
    rows, in_scaling = [], False
    with open(path) as f:
        for line in f:
            if line.startswith("## "):
                in_scaling = line.startswith("## Scaling")
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not in_scaling or len(cells) != 12 or cells[0] not in SCENES:
                continue
            label, spec = cells[3].rsplit(" (`", 1)
            rows.append({"cells": cells[0], "N": int(cells[1]),
                         "dofs": int(cells[2]), "label": label,
                         "spec": spec.rstrip("`)"),
                         "setup": float(cells[4]), "solve": float(cells[5]),
                         "iterations": int(cells[6].split()[0])})
    return rows


def figures(rows, directory):
    """CG iterations and set-up + solve time against the dofs, one line per
    preconditioner and cell type, with an O(n) line."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    styles = {"hexahedra": "-", "tetrahedra": "--"}
    markers = {}
    for r in rows:
        markers.setdefault(r["spec"], "osd^v<>"[len(markers) % 7])
    for cells in SCENES:
        for spec in markers:
            series = sorted((r for r in rows
                             if r["cells"] == cells and r["spec"] == spec),
                            key=lambda r: r["dofs"])
            if not series:
                continue
            label = f"{cells}: {series[0]['label']}"
            dofs = [r["dofs"] for r in series]
            axes[0].semilogx(dofs, [r["iterations"] for r in series],
                             markers[spec] + styles[cells], label=label)
            axes[1].loglog(dofs, [r["setup"] + r["solve"] for r in series],
                           markers[spec] + styles[cells], label=label)
    if rows:
        first = min(rows, key=lambda r: r["dofs"])
        last = max(r["dofs"] for r in rows)
        t0 = min(r["setup"] + r["solve"] for r in rows
                 if r["dofs"] == first["dofs"])
        axes[1].loglog([first["dofs"], last],
                       [t0, t0 * last / first["dofs"]], "k:", label="O(n)")
    axes[0].set_ylabel("CG iterations (relative residual 1e-10)")
    axes[1].set_ylabel("set-up + solve [s]")
    for ax in axes:
        ax.set_xlabel("displacement dofs")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "preconditioners.png"), dpi=110)


INTRODUCTION = [
    "# Preconditioners for the elastic solve",
    "",
    "Written by `benchmarks/run_preconditioner_comparison.py` (one "
    "invocation); `doc/performance.md` reads it. One process per cell "
    "type and size: the cube's K and b (`cube_3d.prm`, "
    "`cube_3d_tetrahedra.prm`, Subdivisions = N), then CG from zero to "
    "a relative residual of 1e-10 with each preconditioner in turn. "
    "Set-up: building the preconditioner from the assembled K (for the "
    "geometric multigrid: the level operators, their diagonals, the "
    "transfer and the smoothers' eigenvalue estimates; it needs no "
    "assembled matrix at all). Preconditioner memory: growth of the "
    "resident set over the set-up. Process peak: the whole process, all "
    "variants (and, with BoomerAMG, a PETSc copy of K). Difference: "
    "|u - u_first| / |u_first| against the first variant of the "
    "process. Last column: one product with K and one application of the "
    "preconditioner, timed after the solve (a measure of the machine's "
    "load at that moment, too).",
    "",
]


def write_output(path, sweep_rows, scaling_rows):
    lines = list(INTRODUCTION)
    for title, rows in (("Sweep", sweep_rows), ("Scaling", scaling_rows)):
        lines += [f"## {title}", "", HEADER] + [table_line(r) for r in rows]
        lines.append("")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--executable", default=os.path.join(
        REPO_ROOT, "build", "preconditioner_comparison"))
    parser.add_argument("--sweep-hexahedra", default="32")
    parser.add_argument("--sweep-tetrahedra", default="32")
    parser.add_argument("--hexahedra", default="16,24,32,48,64,80")
    parser.add_argument("--tetrahedra", default="16,24,32,48,64,69")
    parser.add_argument("--output", default=os.path.join(
        REPO_ROOT, "doc", "performance", "preconditioners.md"))
    parser.add_argument("--figures-only", action="store_true")
    parser.add_argument("--from-log", default=None,
                        help="write the tables and the figure from a saved "
                             "standard output of this script instead of "
                             "running (e.g. of an interrupted run)")
    args = parser.parse_args()
    if args.figures_only:
        figures(read_table(args.output), os.path.dirname(args.output))
        return
    sweep_sizes = {"hexahedra": args.sweep_hexahedra,
                   "tetrahedra": args.sweep_tetrahedra}
    if args.from_log:
        n_sweep = sum(len([s for s in sizes.split(",") if s])
                      for sizes in sweep_sizes.values())
        sweep_rows, scaling_rows = read_log(args.from_log, n_sweep)
        write_output(args.output, sweep_rows, scaling_rows)
        figures(scaling_rows, os.path.dirname(args.output))
        return
    executable = os.path.abspath(args.executable)
    results = {"Sweep": [], "Scaling": []}
    for title, variants, sizes in (
            ("Sweep", SWEEP, sweep_sizes),
            ("Scaling", SCALING, {"hexahedra": args.hexahedra,
                                  "tetrahedra": args.tetrahedra})):
        for cells in SCENES:
            for n in [int(s) for s in sizes[cells].split(",") if s]:
                results[title] += run(executable, cells, n, variants)
        write_output(args.output, results["Sweep"], results["Scaling"])
    figures(results["Scaling"], os.path.dirname(args.output))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The full space back end across mesh sizes: what a time step costs in
elastic solves of the same mesh, and whether the CG iterations per solve
stay put as the mesh is refined. Writes doc/performance/full_space.md and
its figures (read in doc/performance.md).

The scene is the 3D cube (parameters/cube_3d.prm on hexahedra,
parameters/cube_3d_tetrahedra.prm on tetrahedra) with Method = full space,
Preconditioner = amg and the explicit update: the full run of the parameter
file (32 steps of k = 1/32 up to T = 1; --end-time 0.25 runs the first 8,
where the contact zone forms and the first step is a cold start), without
the uniqueness check (a Lanczos iteration at set-up, not part of a step)
and without file output. On hexahedra the first step is solved on 2
coarser meshes first (Initial cycles = 2, nested iteration, so the mesh
N is N/4 subdivisions refined twice; --initial-cycles 0 turns it off);
the fully distributed meshes of tetrahedra cannot be refined, so they
start cold. Every step after the first runs the shipped `Step cycles =
auto` (on hexahedra from 353k dofs: the step solved on the mesh coarsened
once first; none on tetrahedra). Each size is one process; the program's own "Cost
measurement" block gives, measured in that process, the average time step
(the initial cycles included) and one solve with the elastic operator from
a zero start to the same Tolerance (1e-10): their ratio is "elastic solves
per step".

Usage:
    benchmarks/run_full_space_scaling.py [--executable build/viscoplastic_contact]
        [--hexahedra 16,24,32,48] [--tetrahedra 16,24,32]
        [--end-time 1] [--initial-cycles 2] [--concurrent]
        [--baseline OTHER_BUILD/viscoplastic_contact --baseline-sizes 32]
        [--output doc/performance/full_space.md]
    benchmarks/run_full_space_scaling.py --figures-only
        (the figure again from the table in --output, without running)

Times are wall times on whatever machine runs it; compare ratios within
one invocation. --concurrent runs the hexahedra and the tetrahedra side by
side, one process and one thread each (on two cores about 21 minutes instead
of 30 for the sizes of doc/performance.md); the ratios measured within a
process hold, the absolute times share the memory bandwidth.
"""

import argparse
import concurrent.futures
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_performance import number, run, scene  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable)

SCENES = {"hexahedra": "cube_3d.prm", "tetrahedra": "cube_3d_tetrahedra.prm"}


def initial_cycles_for(cells, n, initial_cycles):
    """The initial cycles a run of N subdivisions gets: none on tetrahedra,
    and only as many as N can be halved."""
    if cells != "hexahedra":
        return 0
    cycles = 0
    while cycles < initial_cycles and n % (2 ** (cycles + 1)) == 0:
        cycles += 1
    return cycles


def cube(cells, n, end_time, cycles):
    return scene(SCENES[cells], {
        (("Geometry",), "Subdivisions"): str(n // 2 ** cycles),
        (("Geometry",), "Global refinements"): str(cycles),
        (("Mesh adaptation",), "Initial cycles"): str(cycles),
        (("Time",), "End time"): end_time,
        (("Linear solver",), "Method"): "full space",
        (("Linear solver",), "Preconditioner"): "amg",
        (("Contact",), "Check uniqueness"): "false",
    })


def measure(executable, cells, n, work, tag, end_time, initial_cycles,
            threads=None):
    cycles = initial_cycles_for(cells, n, initial_cycles)
    row = run(executable, cube(cells, n, end_time, cycles), work,
              f"{tag}_{cells}_{n}", threads=threads)
    row["cycles"] = cycles
    out = row["output"]
    step_cycles = re.search(r"^Step cycles: every step.* solved on (\d+) "
                            r"coarser mesh", out, re.M)
    row["step_cycles"] = int(step_cycles.group(1)) if step_cycles else 0
    row["solves"] = number(r"back end: (\d+) solves", out)
    row["setups"] = number(r"set up by the back end (\d+)x", out)
    row["elastic_krylov"] = number(
        r"one solve with the step operator, no contact: [0-9.e+-]+ ms "
        r"\((\d+) Krylov iterations\)", out)
    row["step_per_solve"] = row["step_ms"] / row["solve_ms"]
    row["krylov_per_solve"] = row["krylov"] / row["solves"]
    row["krylov_per_step"] = row["krylov"] / row["steps"]
    return row


def figures(results, directory):
    """Time per step, CG iterations per solve and elastic solves per step
    against the dofs, one line per cell type."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for cells, rows in results.items():
        dofs = [r["dofs"] for r in rows]
        axes[0].loglog(dofs, [r["step_ms"] / 1000 for r in rows], "o-",
                       label=f"{cells}: time step")
        axes[0].loglog(dofs, [r["solve_ms"] / 1000 for r in rows], "s--",
                       label=f"{cells}: one elastic solve")
        axes[1].semilogx(dofs, [r["krylov_per_solve"] for r in rows], "o-",
                         label=f"{cells}: per active-set solve")
        axes[1].semilogx(dofs, [r["elastic_krylov"] for r in rows], "s--",
                         label=f"{cells}: elastic solve (1e-10)")
        axes[2].semilogx(dofs, [r["step_per_solve"] for r in rows], "o-",
                         label=cells)
    all_rows = [r for rows in results.values() for r in rows]
    if all_rows:
        first = min(all_rows, key=lambda r: r["dofs"])
        xs = sorted(r["dofs"] for r in all_rows)
        axes[0].loglog([xs[0], xs[-1]],
                       [first["step_ms"] / 1000,
                        first["step_ms"] / 1000 * xs[-1] / xs[0]],
                       "k:", label="O(n)")
    axes[2].axhline(1.5, color="k", linestyle=":", label="goal 1.5")
    axes[0].set_ylabel("wall time [s]")
    axes[1].set_ylabel("CG iterations per solve")
    axes[2].set_ylabel("time step / one elastic solve")
    for ax in axes:
        ax.set_xlabel("displacement dofs")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    # Headroom above the curves for the legend.
    axes[1].set_ylim(bottom=0, top=1.5 * axes[1].get_ylim()[1])
    axes[2].set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "full_space_scaling.png"), dpi=110)


def phase_table(results):
    """Where the time of the largest run went: its TimerOutput sections
    (wall time, the share of the whole run), as the program printed them."""
    rows = [r for rs in results.values() for r in rs]
    if not rows:
        return []
    largest = max(rows, key=lambda r: r["dofs"])
    sections = re.findall(r"^\| ([A-Za-z][^|]*?)\s+\|\s+(\d+) \|"
                          r"\s+([0-9.e+-]+)s \|\s+([0-9.e+-]+)% \|",
                          largest["output"], re.M)
    cells = next(c for c, rs in results.items() if largest in rs)
    lines = ["", f"## Phases of the largest run ({cells}, "
             f"{largest['dofs']} dofs)", "",
             "The program's TimerOutput sections (one process); \"Solve: "
             "contact problem\" holds the active-set iterations with their "
             f"CG solves and the {largest['setups']:.0f} AMG set-ups of the "
             "step operator.", "",
             "| phase | calls | wall time [s] | share |",
             "| --- | ---: | ---: | ---: |"]
    for name, calls, wall, share in sections:
        lines.append(f"| {name} | {calls} | {float(wall):.3g} | {share}% |")
    return lines


def read_table(path):
    """The rows of the first table of a written full_space.md, as figures()
    needs them."""
    results = {}
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) != 17 or cells[0] not in SCENES:
                continue
            results.setdefault(cells[0], []).append({
                "dofs": int(cells[4]),
                "krylov_per_solve": float(cells[7]),
                "elastic_krylov": float(cells[9]),
                "step_ms": 1000 * float(cells[11]),
                "solve_ms": 1000 * float(cells[12]),
                "step_per_solve": float(cells[13]),
            })
    return results


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--hexahedra", default="16,24,32,48")
    parser.add_argument("--tetrahedra", default="16,24,32")
    parser.add_argument("--end-time", default="1")
    parser.add_argument("--initial-cycles", type=int, default=2)
    parser.add_argument("--baseline", default=None)
    parser.add_argument("--baseline-sizes", default="32")
    parser.add_argument("--output", default=os.path.join(
        REPO_ROOT, "doc", "performance", "full_space.md"))
    parser.add_argument("--figures-only", action="store_true")
    parser.add_argument("--concurrent", action="store_true",
                        help="the two cell types side by side, one process "
                        "and one thread each")
    args = parser.parse_args()
    if args.figures_only:
        figures(read_table(args.output), os.path.dirname(args.output))
        return
    executable = resolve_executable(args.executable)
    sizes = {"hexahedra": args.hexahedra, "tetrahedra": args.tetrahedra}

    lines = [
        "# Full space back end across mesh sizes",
        "",
        "Written by `benchmarks/run_full_space_scaling.py`; "
        "`doc/performance.md` reads it. The cube (`cube_3d.prm`, "
        "`cube_3d_tetrahedra.prm`), full space back end with AMG, explicit "
        f"steps of k = 1/32 up to T = {args.end_time}, one process each; "
        "\"initial cycles\": the coarser meshes on which the first step was "
        "solved first (nested iteration; none on tetrahedra); \"step "
        "cycles\": the coarser meshes on which every later step was solved "
        "first (the shipped `Step cycles = auto`). \"Elastic "
        "solves per step\": the average time step (initial cycles included) "
        "over one solve with the elastic operator from zero to the same "
        "Tolerance, both measured in that process."
        + (" The hexahedra and the tetrahedra ran side by side, one process "
           "and one thread each (`--concurrent`): they shared the memory "
           "bandwidth." if args.concurrent else ""),
        "",
        "| cells | N | initial cycles | step cycles | dofs | contact nodes | active-set its "
        "per step | CG its per active-set solve | CG its per step | CG its, "
        "elastic solve | AMG set-ups | time step [s] | elastic solve [s] | "
        "elastic solves per step | peak memory [MB] | bytes per dof | whole "
        "process [s] |",
        "|" + " ---: |" * 17,
    ]
    threads = 1 if args.concurrent else None

    def series(cells, work):
        rows, table_lines = [], []
        for n in [int(s) for s in sizes[cells].split(",") if s]:
            r = measure(executable, cells, n, work, "this", args.end_time,
                        args.initial_cycles, threads)
            rows.append(r)
            line = (
                f"| {cells} | {n} | {r['cycles']} | {r['step_cycles']} | "
                f"{r['dofs']} | {r['contact_nodes']} | "
                f"{r['iterations'] / r['steps']:.2f} | "
                f"{r['krylov_per_solve']:.1f} | {r['krylov_per_step']:.0f} | "
                f"{r['elastic_krylov']:.0f} | {r['setups']:.0f} | "
                f"{r['step_ms'] / 1000:.3g} | {r['solve_ms'] / 1000:.3g} | "
                f"{r['step_per_solve']:.2f} | {r['memory_mb']:.0f} | "
                f"{r['bytes_per_dof']:.0f} | {r['wall']:.1f} |")
            table_lines.append(line)
            print(line, flush=True)
        return rows, table_lines

    results = {}
    with tempfile.TemporaryDirectory() as work:
        with concurrent.futures.ThreadPoolExecutor(
                max_workers=2 if args.concurrent else 1) as pool:
            futures = {cells: pool.submit(series, cells, work)
                       for cells in ("hexahedra", "tetrahedra")}
            for cells, future in futures.items():
                results[cells], table_lines = future.result()
                lines += table_lines
        if args.baseline:
            lines += [
                "", "## Against another build",
                "",
                f"The same runs with `{args.baseline}`, each right after "
                "this build's run.", "",
                "| cells | N | elastic solves per step: this | baseline | "
                "CG its per step: this | baseline | time step: this / "
                "baseline |",
                "|" + " ---: |" * 7]
            baseline = resolve_executable(args.baseline)
            for cells in ("hexahedra",):
                for n in [int(s) for s in args.baseline_sizes.split(",") if s]:
                    this = measure(executable, cells, n, work, "pair",
                                   args.end_time, args.initial_cycles)
                    old = measure(baseline, cells, n, work, "baseline",
                                  args.end_time, args.initial_cycles)
                    line = (f"| {cells} | {n} | {this['step_per_solve']:.2f} | "
                            f"{old['step_per_solve']:.2f} | "
                            f"{this['krylov_per_step']:.0f} | "
                            f"{old['krylov_per_step']:.0f} | "
                            f"{this['step_ms'] / old['step_ms']:.2f} |")
                    lines.append(line)
                    print(line, flush=True)
    lines += phase_table(results)
    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w") as f:
        f.write("\n".join(lines) + "\n")
    figures(results, os.path.dirname(args.output))


if __name__ == "__main__":
    main()

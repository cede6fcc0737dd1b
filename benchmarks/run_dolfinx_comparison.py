#!/usr/bin/python3
"""The program against an independent dolfinx implementation, static scene.

The static scene is parameters/elastic.prm (elastic body, nonmonotone
normal compliance over a rigid foundation) with Subdivisions = N and one
step of k = 1/64 from rest: one static contact problem. For N in
--subdivisions and each rank count in --ranks the script runs, back to
back, the program with its default settings (Method = auto; VTU output,
profiles, timing summary and verbose output off, as in
run_method_choice.py) and benchmarks/dolfinx_static_scene.py (dolfinx 0.5,
PETSc SNES vinewtonrsls with the bounds u_y >= -g, LU by MUMPS; see its
docstring) once per line search of --line-searches: "basic" (full
semismooth Newton steps, the fastest set-up found) and "bt" (PETSc's
default for vinewtonrsls, what a dolfinx user gets without the option).
All solve the same discretisation: P1 on the "/" triangles, lumped nodal
contact. The runs of a row are repeated --repeat times, interleaved; the
fastest run of each counts.

Per run: the whole process's wall time (start-up, Python imports, mesh,
assembly, solve, for dolfinx also the MPI start-up of mpi4py), the peak
resident memory of the largest rank, the final contact state (unilateral /
compliance / no contact nodes) and the total contact force sum_i z_i. The
program's force is read from its time_series.csv (10 digits), dolfinx's
from its output (12 digits). Per row: dolfinx time / program time and the
relative difference of the forces, per line search; differing contact
counts are flagged.

Before the timed runs the dolfinx script runs once, untimed, at N = 8 so
that FFCx's JIT cache (~/.cache/fenics) holds the compiled forms and no
row pays the form compilation (about 0.5 s; a first-time user pays it once).

Writes <output-dir>/dolfinx_comparison.csv and dolfinx_comparison.md.

    benchmarks/run_dolfinx_comparison.py [--executable build/viscoplastic_contact]
        [--subdivisions 128,256,512] [--ranks 1,2] [--repeat 1]
        [--line-searches basic,bt] [--python /usr/bin/python3]
        [--petsc-options "-snes_max_it 100"]
        [--timeout 600] [--output-dir doc/back_ends]

Needs Debian's python3-dolfinx (apt-get install python3-dolfinx), run by
--python (default /usr/bin/python3, which sees the Debian packages). Build
the program in Release mode. Runs as root need no flag: the script sets
Open MPI's OMPI_ALLOW_RUN_AS_ROOT variables.
"""

import argparse
import csv
import datetime
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, static_scene_prm, timed_run)

DOLFINX_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                              "dolfinx_static_scene.py")
CONTACT_RE = re.compile(r"final contact: (\d+) unilateral, (\d+) compliance, "
                        r"(\d+) no contact, total force = (\S+)")


def checked_run(command, ranks, workdir, timeout):
    """timed_run(): (wall time [s], peak memory of the largest rank [MB],
    stdout); stdout None after a timeout, "failed" after a nonzero exit code
    (the end of the output is printed)."""
    wall, memory, result = timed_run(command, ranks, workdir, timeout)
    if result is None:
        return wall, memory, None
    if result.returncode != 0:
        print(f"{' '.join(command)} failed:\n" + result.stdout[-2000:]
              + result.stderr[-2000:], file=sys.stderr, flush=True)
        return float("inf"), float("nan"), "failed"
    return wall, memory, result.stdout


def run_program(executable, n, ranks, timeout):
    with tempfile.TemporaryDirectory() as workdir:
        with open(os.path.join(workdir, "run.prm"), "w") as f:
            f.write(static_scene_prm(n))
        wall, memory, out = checked_run([executable, "run.prm"], ranks, workdir,
                                      timeout)
        if out is None or out == "failed":
            return {"time": wall, "memory": memory,
                    "status": "timeout" if out is None else "failed"}
        # The force with 10 digits from the time series (stdout has 8).
        series = os.path.join(workdir, "out", "time_series.csv")
        force = None
        if os.path.exists(series):
            with open(series) as f:
                last = list(csv.DictReader(f))[-1]
            force = float(last["total_contact_force"])
    contact = CONTACT_RE.search(out)
    mesh = re.search(r"^Mesh: \d+ \w+ cells, (\d+) displacement dofs, (\d+) "
                     r"contact nodes", out, re.M)
    back_end = re.search(r"^Back end: ([a-z ]+):", out, re.M)
    # With initial cycles (Initial cycles = auto chooses them for the full
    # space back end) the program solves the step on coarser meshes first;
    # the mesh and the back end of the run are those of the last cycle.
    cycles = re.search(r"^Initial cycles done: \d+ cells, (\d+) dofs, (\d+) "
                       r"contact nodes.*back end: ([a-z ]+):", out, re.M)
    iterations = re.search(r"active-set iterations: (\d+)", out)
    cycle_iterations = re.search(r"initial cycles: (\d+) active-set iterations",
                                 out)
    return {"time": wall, "memory": memory, "status": "ok",
            "counts": tuple(int(contact.group(i)) for i in (1, 2, 3)),
            "force": force if force is not None else float(contact.group(4)),
            "dofs": (cycles or mesh).group(1), "contact_nodes": (cycles or mesh).group(2),
            "back_end": (cycles.group(3) + " (initial cycles)" if cycles else
                         back_end.group(1) if back_end else "?"),
            "iterations": iterations.group(1) if iterations else "",
            "cycle_iterations": (cycle_iterations.group(1)
                                 if cycle_iterations else "")}


def run_dolfinx(python, n, ranks, line_search, petsc_options, timeout):
    command = ([python, DOLFINX_SCRIPT, "--subdivisions", str(n),
                "-snes_linesearch_type", line_search] + petsc_options)
    with tempfile.TemporaryDirectory() as workdir:
        wall, memory, out = checked_run(command, ranks, workdir, timeout)
    if out is None or out == "failed":
        return {"time": wall, "memory": memory,
                "status": "timeout" if out is None else "failed"}
    contact = CONTACT_RE.search(out)
    iterations = re.search(r"SNES iterations: (\d+)", out)
    times = re.search(r"set-up time: (\S+) s, solve time: (\S+) s", out)
    return {"time": wall, "memory": memory, "status": "ok",
            "counts": tuple(int(contact.group(i)) for i in (1, 2, 3)),
            "force": float(contact.group(4)),
            "iterations": iterations.group(1),
            "setup": float(times.group(1)), "solve": float(times.group(2))}


def provenance(script, python):
    """The "Generated by" line of a page written by benchmarks/SCRIPT (the
    date, the machine, the command with paths inside the repository relative
    to it) and [dolfinx's version, PETSc's] as python imports them."""
    def shown(a):
        if a.startswith(REPO_ROOT + os.sep):
            a = os.path.relpath(a, REPO_ROOT)
        return shlex.quote(a)
    command = f"benchmarks/{script} " + " ".join(shown(a) for a in sys.argv[1:])
    versions = subprocess.run(
        [python, "-c", "import dolfinx; from petsc4py import PETSc; "
         "print(dolfinx.__version__, '.'.join(map(str, PETSc.Sys.getVersion())))"],
        capture_output=True, text=True).stdout.split()
    return (f"Generated by `benchmarks/{script}` on {datetime.date.today()} "
            f"({platform.node()}, {os.cpu_count()} cores); command: `{command}`.",
            versions)


def fastest(old, new):
    return new if old is None or new["time"] < old["time"] else old


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--subdivisions", default="128,256,512")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--python", default="/usr/bin/python3",
                        help="the Python that imports dolfinx")
    parser.add_argument("--line-searches", default="basic,bt",
                        help="the dolfinx set-ups: SNES line search types")
    parser.add_argument("--petsc-options", default="",
                        help="extra PETSc options for the dolfinx script")
    parser.add_argument("--timeout", type=float, default=600)
    parser.add_argument("--output-dir", default=os.path.join(REPO_ROOT, "doc",
                                                             "back_ends"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    petsc_options = shlex.split(args.petsc_options)
    searches = [ls for ls in args.line_searches.split(",") if ls]

    # Untimed: fills the FFCx JIT cache.
    run_dolfinx(args.python, 8, 1, searches[0], petsc_options, args.timeout)

    rows = []
    for n in [int(n) for n in args.subdivisions.split(",") if n]:
        for ranks in [int(r) for r in args.ranks.split(",") if r]:
            program = None
            dolfinx = {ls: None for ls in searches}
            for _ in range(args.repeat):
                program = fastest(program, run_program(executable, n, ranks,
                                                       args.timeout))
                for ls in searches:
                    dolfinx[ls] = fastest(dolfinx[ls], run_dolfinx(
                        args.python, n, ranks, ls, petsc_options, args.timeout))
            row = {"N": n, "ranks": ranks,
                   "dofs": program.get("dofs", ""),
                   "contact_nodes": program.get("contact_nodes", "")}
            runs = [("program", program)] + [(f"dolfinx_{ls}", dolfinx[ls])
                                             for ls in searches]
            for name, r in runs:
                row[f"{name}_s"] = (r["status"] if r["status"] != "ok"
                                    else f"{r['time']:.3f}")
                row[f"{name}_MB"] = f"{r['memory']:.0f}"
                row[f"{name}_iterations"] = r.get("iterations", "")
                row[f"{name}_counts"] = ("/".join(map(str, r["counts"]))
                                         if "counts" in r else "")
                row[f"{name}_force"] = (f"{r['force']:.12g}" if "force" in r
                                        else "")
            row["program_back_end"] = program.get("back_end", "")
            row["program_cycle_iterations"] = program.get("cycle_iterations", "")
            summary = []
            for ls in searches:
                d = dolfinx[ls]
                row[f"dolfinx_{ls}_setup_s"] = (f"{d['setup']:.3f}"
                                                if "setup" in d else "")
                row[f"dolfinx_{ls}_solve_s"] = (f"{d['solve']:.3f}"
                                                if "solve" in d else "")
                both = program["status"] == "ok" and d["status"] == "ok"
                row[f"time_ratio_{ls}"] = (f"{d['time'] / program['time']:.2f}"
                                           if both else "")
                row[f"memory_ratio_{ls}"] = (
                    f"{d['memory'] / program['memory']:.2f}" if both else "")
                row[f"force_rel_diff_{ls}"] = (
                    f"{abs(d['force'] - program['force']) / abs(program['force']):.1e}"
                    if both else "")
                row[f"counts_agree_{ls}"] = ("yes" if both and program["counts"]
                                             == d["counts"] else "NO" if both else "")
                summary.append(
                    f"dolfinx ({ls}) {row[f'dolfinx_{ls}_s']} s "
                    f"({row[f'dolfinx_{ls}_MB']} MB, solve "
                    f"{row[f'dolfinx_{ls}_solve_s']} s, "
                    f"{row[f'dolfinx_{ls}_iterations']} SNES iterations), ratio "
                    f"{row[f'time_ratio_{ls}']}, force rel. diff "
                    f"{row[f'force_rel_diff_{ls}']}, counts agree: "
                    f"{row[f'counts_agree_{ls}']}")
            print(f"N = {n:4d}, {ranks} rank(s): program {row['program_s']} s "
                  f"({row['program_MB']} MB, {row['program_back_end']}); "
                  + "; ".join(summary), flush=True)
            rows.append(row)

    os.makedirs(args.output_dir, exist_ok=True)
    with open(os.path.join(args.output_dir, "dolfinx_comparison.csv"), "w",
              newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    generated, versions = provenance("run_dolfinx_comparison.py", args.python)
    lines = [
        "# The program against dolfinx on the static scene", "", generated, "",
        "The static scene: parameters/elastic.prm with Subdivisions = N and one "
        "step of k = 1/64 from rest (one elastic contact problem with the "
        "nonmonotone layer and the rigid limit). *program*: viscoplastic_contact "
        "with its defaults (Method = auto). *dolfinx*: "
        "benchmarks/dolfinx_static_scene.py, an independent implementation of "
        "the same discretisation (P1, lumped nodal contact) in dolfinx "
        + (f"{versions[0]} with PETSc {versions[1]}" if len(versions) == 2 else "")
        + ": SNES vinewtonrsls (the rigid limit as the bounds u_y >= -g), LU "
        "by MUMPS in every Newton iteration"
        + (f", PETSc options `{args.petsc_options}`" if args.petsc_options else "")
        + ", with each line search: *basic* (full semismooth Newton steps, the "
        "fastest set-up found) and *bt* (backtracking, PETSc's default for "
        "vinewtonrsls). The runs of a row ran back to back, the fastest of "
        f"{args.repeat} interleaved repeat(s) counting. Times are whole "
        "processes in seconds (start-up, imports, mesh, assembly, solve; "
        "dolfinx's forms precompiled by an untimed warm-up run, so no JIT); "
        "*solve* is dolfinx's own timer of the SNES solve. Memory is the peak "
        "resident memory of the largest rank in MB. *program back end*: the "
        "one Method = auto chose; *initial cycles*: the program solved the step "
        "on a coarser mesh first and started the final mesh from its solution. "
        "*iterations*: the program's active-set iterations on the final mesh "
        "(in brackets those on the coarser meshes), dolfinx's SNES (Newton) "
        "iterations. *contact*: unilateral / compliance / no contact nodes "
        "(the same for every run of a row unless flagged). *force*: the total "
        "contact force sum_i z_i; *rel. diff*: the largest |dolfinx - program| "
        "/ |program| of the row (the program's force has 10 digits).", ""]
    header = ("| N | ranks | dofs | program [s] | "
              + " | ".join(f"dolfinx {ls} [s] | {ls} / program | {ls} solve [s]"
                           for ls in searches)
              + " | memory: program [MB] | "
              + " | ".join(f"dolfinx {ls} [MB]" for ls in searches)
              + " | program back end | iterations: program | "
              + " | ".join(f"dolfinx {ls}" for ls in searches)
              + " | contact | force: program | rel. diff |")
    lines += [header, "|" + "|".join(["---:"] * (header.count("|") - 1)) + "|"]
    for r in rows:
        counts_differ = any(r[f"counts_agree_{ls}"] == "NO" for ls in searches)
        diffs = [float(r[f"force_rel_diff_{ls}"]) for ls in searches
                 if r[f"force_rel_diff_{ls}"]]
        largest_diff = f"{max(diffs):.1e}" if diffs else ""
        lines.append(
            f"| {r['N']} | {r['ranks']} | {r['dofs']} | {r['program_s']} | "
            + " | ".join(f"{r[f'dolfinx_{ls}_s']} | {r[f'time_ratio_{ls}']} | "
                         f"{r[f'dolfinx_{ls}_solve_s']}" for ls in searches)
            + f" | {r['program_MB']} | "
            + " | ".join(r[f"dolfinx_{ls}_MB"] for ls in searches)
            + f" | {r['program_back_end']} | {r['program_iterations']}"
            f"{' (+' + r['program_cycle_iterations'] + ')' if r['program_cycle_iterations'] else ''} | "
            + " | ".join(r[f"dolfinx_{ls}_iterations"] for ls in searches)
            + f" | {r['program_counts']}{' (differ)' if counts_differ else ''} | "
            f"{r['program_force']} | {largest_diff} |")
    with open(os.path.join(args.output_dir, "dolfinx_comparison.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

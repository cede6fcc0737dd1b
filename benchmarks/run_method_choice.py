#!/usr/bin/python3
"""Is Method = auto the fastest back end? Every back end side by side.

For each case and rank count the program runs once with every Method
(condensed, full space, matrix free where the scene allows it) and once with
the default, Method = auto (also where the file names a back end), one run
at a time, the methods of a case back to back (repeated --repeat times,
interleaved; the fastest of the repeats counts). Where the default run
solved on coarser meshes (Initial cycles or Step cycles = auto chose some),
the case also runs once more with the default Method and both entries set
to 0 ("no cycles"), so that the nested iteration too is weighed against
going without it. Per run it records the whole process's wall time, the
peak resident memory of the largest rank, and the back end the program
reports; per case the best setting, auto's choice and the ratio auto /
best.

Cases:
  * shipped: every parameters/*.prm as shipped (VTU output off, nothing else
    changed but the Method of each run);
  * static N: the 2D static scene, parameters/elastic.prm with one step of
    k = 1/64 (the whole contact zone found in one cold step), triangles of
    h = 1/N, for N in --static-subdivisions; static quadrilaterals N: the
    same on squares (--static-cell-types simplex,hypercube);
  * cube N: parameters/cube_3d.prm (hexahedra, 32 steps) with N
    Subdivisions, for N in --cube-subdivisions (none by default).

Writes <output-dir>/<name>.csv and <name>.md (--name, default
method_choice). The tables in doc/back_ends come from two invocations:

    benchmarks/run_method_choice.py --scenes none --cube-subdivisions 24,32
    benchmarks/run_method_choice.py --static-subdivisions "" \
        --timeout 120 --name method_choice_shipped

    benchmarks/run_method_choice.py [--executable build/viscoplastic_contact]
        [--ranks 1,2] [--static-subdivisions 128,256,512]
        [--static-cell-types simplex,hypercube]
        [--cube-subdivisions 24,32] [--scenes all|none|a.prm,b.prm]
        [--repeat 1] [--timeout 600] [--output-dir doc/back_ends]
        [--name method_choice]

Build in Release mode. Runs as root need no flag: the script sets Open MPI's
OMPI_ALLOW_RUN_AS_ROOT variables.
"""

import argparse
import csv
import datetime
import os
import platform
import re
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries, static_scene_prm,
                        timed_run)

METHODS = ["condensed", "full space", "matrix free", "auto"]
# The defaults without nested iteration, where the default run had some.
NO_CYCLES = "no cycles"

def case_prms(args):
    """(name, parameter file text) of every case."""
    cases = []
    scenes = sorted(f for f in os.listdir(os.path.join(REPO_ROOT, "parameters"))
                    if f.endswith(".prm"))
    if args.scenes == "none":
        scenes = []
    elif args.scenes != "all":
        scenes = [s for s in args.scenes.split(",") if s]
    for scene in scenes:
        with open(os.path.join(REPO_ROOT, "parameters", scene)) as f:
            text = f.read()
        # Mesh files are named relative to the parameters folder.
        text = text.replace("../meshes/", os.path.join(REPO_ROOT, "meshes", ""))
        cases.append((scene, set_prm_entries(text, {
            (("Output",), "Write vtu"): "false"})))
    for cell_type in [c for c in args.static_cell_types.split(",") if c]:
        name = "static" + (" quadrilaterals" if cell_type == "hypercube" else "")
        for n in [int(n) for n in args.static_subdivisions.split(",") if n]:
            cases.append((f"{name} N={n}", static_scene_prm(n, cell_type)))
    with open(os.path.join(REPO_ROOT, "parameters", "cube_3d.prm")) as f:
        cube = f.read()
    for n in [int(n) for n in args.cube_subdivisions.split(",") if n]:
        cases.append((f"cube N={n}", set_prm_entries(cube, {
            (("Geometry",), "Subdivisions"): str(n),
            (("Output",), "Write vtu"): "false",
            (("Output",), "Print timing summary"): "false"})))
    return cases


def run(executable, text, method, ranks, timeout):
    """One run: wall time [s], peak memory of the largest rank [MB], the back
    end's description; None for a method the scene refuses."""
    # auto and no cycles set Method = auto also where the file names a
    # back end.
    overrides = {(("Output",), "Output directory"): "out",
                 (("Linear solver",), "Method"): "auto"}
    if method == NO_CYCLES:
        overrides[(("Mesh adaptation",), "Initial cycles")] = "0"
        overrides[(("Mesh adaptation",), "Step cycles")] = "0"
    elif method != "auto":
        overrides[(("Linear solver",), "Method")] = method
    with tempfile.TemporaryDirectory() as workdir:
        with open(os.path.join(workdir, "run.prm"), "w") as f:
            f.write(set_prm_entries(text, overrides))
        wall, memory, result = timed_run([executable, "run.prm"], ranks,
                                         workdir, timeout)
    if result is None:
        return {"time": wall, "memory": memory, "back_end": "timeout",
                "nested": False,
                "cycles": "", "dofs": "", "contact_nodes": "", "steps": ""}
    if result.returncode != 0:
        if "Invalid parameter <Method>" in result.stdout + result.stderr:
            return None
        raise RuntimeError(f"{method} on {ranks} rank(s) failed:\n"
                           + result.stdout[-2000:] + result.stderr[-2000:])
    back_end = re.search(r"^Back end: ([a-z ]+):", result.stdout, re.M)
    mesh = re.search(r"^Mesh: \d+ \w+ cells, (\d+) displacement dofs, (\d+) "
                     r"contact nodes, (\d+|adaptive) time steps", result.stdout, re.M)
    # With initial cycles the run's mesh is the last of them.
    cycles = re.search(r"^Initial cycles done: \d+ cells, (\d+) dofs, (\d+) "
                       r"contact nodes.*back end: ([a-z ]+):", result.stdout, re.M)
    step_cycles = re.search(r"^  step cycles: (\d+) active-set", result.stdout,
                            re.M)
    return {"time": wall,
            "memory": memory,
            "nested": bool(cycles or (step_cycles
                                      and int(step_cycles.group(1)) > 0)),
            "back_end": (cycles.group(3) if cycles else
                         back_end.group(1) if back_end else "?"),
            "cycles": "yes" if cycles else "no",
            "dofs": (cycles or mesh).group(1) if mesh else "",
            "contact_nodes": (cycles or mesh).group(2) if mesh else "",
            "steps": mesh.group(3) if mesh else ""}


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--static-subdivisions", default="128,256,512")
    parser.add_argument("--static-cell-types", default="simplex,hypercube")
    parser.add_argument("--cube-subdivisions", default="")
    parser.add_argument("--scenes", default="all")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=600)
    parser.add_argument("--output-dir", default=os.path.join(REPO_ROOT, "doc",
                                                             "back_ends"))
    parser.add_argument("--name", default="method_choice")
    args = parser.parse_args()
    executable = resolve_executable(args.executable)

    rows = []
    for name, text in case_prms(args):
        for ranks in [int(r) for r in args.ranks.split(",") if r]:
            results = {}
            for _ in range(args.repeat):
                for method in METHODS:
                    if method in results and results[method] is None:
                        continue
                    result = run(executable, text, method, ranks, args.timeout)
                    if method not in results or (
                            result is not None
                            and result["time"] < results[method]["time"]):
                        results[method] = result
                if results["auto"]["nested"]:
                    result = run(executable, text, NO_CYCLES, ranks, args.timeout)
                    if NO_CYCLES not in results or (
                            result["time"] < results[NO_CYCLES]["time"]):
                        results[NO_CYCLES] = result
            timed = {m: r for m, r in results.items() if r is not None and m != "auto"}
            best = min(timed, key=lambda m: timed[m]["time"])
            auto = results["auto"]
            row = {"case": name, "ranks": ranks, "dofs": auto["dofs"],
                   "contact_nodes": auto["contact_nodes"], "steps": auto["steps"]}
            for method in METHODS + [NO_CYCLES]:
                result = results.get(method)
                key = method.replace(" ", "_")
                row[f"{key}_s"] = ("" if result is None else
                                   f">{args.timeout:g}"
                                   if result["back_end"] == "timeout" else
                                   f"{result['time']:.3f}")
                row[f"{key}_MB"] = "" if result is None else f"{result['memory']:.0f}"
            row.update({"auto_chose": auto["back_end"], "best": best,
                        "auto_over_best": f"{auto['time'] / timed[best]['time']:.3f}"})
            print(f"{name:36s} {ranks} rank(s): " + ", ".join(
                f"{m} {row[m.replace(' ', '_') + '_s'] or '-'} s"
                for m in METHODS + [NO_CYCLES])
                + f"; auto chose {row['auto_chose']}, {row['auto_over_best']} x best ({best})",
                flush=True)
            rows.append(row)

    os.makedirs(args.output_dir, exist_ok=True)
    with open(os.path.join(args.output_dir, args.name + ".csv"), "w",
              newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    command = "benchmarks/run_method_choice.py " + " ".join(
        '""' if not a else a if not a.startswith("/")
        else os.path.relpath(a, REPO_ROOT) for a in sys.argv[1:])
    ratios = [float(r["auto_over_best"]) for r in rows]
    within = sum(1 for r in ratios if r <= 1.2)
    lines = [
        "# Method = auto against every back end", "",
        f"Generated by `benchmarks/run_method_choice.py` on "
        f"{datetime.date.today()} ({platform.node()}, {os.cpu_count()} cores); "
        f"command: `{command}`.", "",
        "Each row runs the case with every Method and with the default "
        "(auto, also where the file names a back end), back to back, the "
        "fastest of "
        f"{args.repeat} repeat(s) counting. Times are whole processes "
        "(start-up, mesh, set-up, every step, no VTU output) in seconds; "
        "memory is the peak resident memory of the largest rank in MB. "
        "*no cycles*: the defaults with Initial cycles = 0 and Step cycles = "
        "0, run only where the default run solved on coarser meshes. "
        "*auto / best*: auto's time over the fastest other setting's, "
        "measured in the same invocation (at these sizes two runs of one "
        "method differ by up to 0.35 s). *>T*: stopped at the timeout of T s, "
        "counted as T. *auto chose*: the back end of the run's mesh (a "
        "convergence study chooses per run).", "",
        f"Auto within 1.2 times the best: **{within} of {len(rows)}** rows; "
        f"largest ratio {max(ratios):.2f}.", "",
        "| case | ranks | dofs | contact nodes | steps | condensed | full space "
        "| matrix free | auto | no cycles | auto chose | best | auto / best "
        "| memory: condensed | full space | matrix free |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(
            f"| {r['case']} | {r['ranks']} | {r['dofs']} | {r['contact_nodes']} | "
            f"{r['steps']} | {r['condensed_s'] or '-'} | {r['full_space_s'] or '-'} | "
            f"{r['matrix_free_s'] or '-'} | {r['auto_s']} | "
            f"{r['no_cycles_s'] or '-'} | {r['auto_chose']} | "
            f"{r['best']} | {r['auto_over_best']} | {r['condensed_MB'] or '-'} | "
            f"{r['full_space_MB'] or '-'} | {r['matrix_free_MB'] or '-'} |")
    with open(os.path.join(args.output_dir, args.name + ".md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

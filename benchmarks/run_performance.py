#!/usr/bin/env python3
"""Performance of the condensed back end and of the stress update; writes
doc/performance/tables.md (read in doc/performance.md).

Three groups of runs, each a separate process, one after the other:

1. The 2D static scene: parameters/elastic.prm (the benchmark without
   plasticity) with one time step of k = 1/64 at h = 1/N: a cold start, the
   whole contact zone found in one step problem. Per N the condensed back end
   runs twice, with the contact boundary and without it: the second run's
   "Setup: back end for K" is the sparse factorisation alone (and its
   analysis), the figure the set-up of the compliance is measured against.
   The full space back end runs the same scene up to --full-space-limit.
   The condensed case at the largest N then runs --pairs more times, with
   and without the contact boundary (set-up / factorisation), and with
   --baseline the baseline build after each: the spread of the ratios over
   the pairs is the noise of a shared machine.
2. The 2D benchmark (parameters/default.prm) at h = k = 1/N, no file output,
   with DEAL_II_NUM_THREADS = 1 and 2: what the threads of the stress update
   save, in one invocation.
3. The 3D cube (parameters/cube_3d.prm, hexahedra), condensed: the first
   8 steps of k = 1/32 (the contact zone forms) and the whole run of 32
   steps (--cube-steps), and the first 8 without contact (as in 1.). The
   first solves after the factorisation are slower than later ones (the
   factor enters the cache), which weighs more in 8 steps than in 32.

For each run: the whole process' wall time and peak resident memory (of that
child, from os.wait4), the program's TimerOutput sections, its "Cost
measurement" block (average time step, one solve, one stress update) and the
active-set iterations. With --baseline EXECUTABLE every run of groups 1 and 2
is repeated with another build (e.g. an earlier commit), right after the run
of the current one, and the table gets the ratio of the whole-process times.
The baseline runs with OPENBLAS_NUM_THREADS=1: builds before the threaded
factorisation were measured with the serial OpenBLAS their install script
chose, and a threaded OpenBLAS would otherwise run every one of their BLAS
calls on all cores (the current program sets its BLAS threads itself, so the
variable does not change it).

Usage:
    benchmarks/run_performance.py [--executable build/viscoplastic_contact]
        [--baseline OTHER_BUILD/viscoplastic_contact]
        [--static-sizes 128,256,512] [--full-space-limit 256]
        [--benchmark-sizes 256] [--cube-sizes 16,24,32] [--cube-steps 8,32]
        [--pairs 5]
        [--output doc/performance/tables.md]

Times are wall times on whatever machine runs it; compare the ratios within
one invocation, not absolute times across invocations.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries)


def scene(base, overrides):
    with open(os.path.join(REPO_ROOT, "parameters", base)) as f:
        return set_prm_entries(f.read(), overrides)


def number(pattern, text):
    match = re.search(pattern, text)
    return float(match.group(1)) if match else float("nan")


def last_number(pattern, text):
    """The last match, for lines printed once per mesh (the initial cycles
    print the coarser meshes first)."""
    matches = re.findall(pattern, text)
    if not matches:
        return float("nan")
    last = matches[-1]
    # A pattern with alternative groups gives a tuple: the one that matched.
    return float(last if isinstance(last, str) else next(g for g in last if g))


def section(name, text):
    """Wall time [s] of a TimerOutput section (nan if absent)."""
    return number(re.escape(name) + r"\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", text)


def run(executable, prm_text, work, name, threads=None, blas_threads=None):
    """Runs one parameter file; returns the parsed measurements."""
    directory = os.path.join(work, name)
    prm_text = set_prm_entries(prm_text, {
        (("Output",), "Output directory"): directory,
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "true",
        (("Output",), "Measure cost ratios"): "true",
    })
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(prm_text)
    env = dict(os.environ)
    if threads is not None:
        env["DEAL_II_NUM_THREADS"] = str(threads)
    if blas_threads is not None:
        env["OPENBLAS_NUM_THREADS"] = str(blas_threads)
    start = time.perf_counter()
    child = subprocess.Popen([executable, prm], stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True, env=env)
    out = child.stdout.read()
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        print(out[-3000:])
        sys.exit(f"error: run {name} failed")
    # The mesh of the run: after the initial cycles, if any, the last one.
    dofs = last_number(r"(?:Mesh: \d+ \w+ cells, (\d+) displacement dofs"
                       r"|Initial cycles done: \d+ cells, (\d+) dofs)", out)
    return {
        "dofs": int(dofs),
        "contact_nodes": int(last_number(
            r"(?:displacement dofs|\d+ dofs), (\d+) contact nodes", out)),
        "wall": wall,
        "memory_mb": usage.ru_maxrss / 1024.,
        "bytes_per_dof": usage.ru_maxrss * 1024. / dofs,
        "mesh": section("Setup: mesh", out),
        "back_end": section("Setup: back end for K", out),
        "contact_solve": section("Solve: contact problem", out),
        "stress_update_total": section("Stress update", out),
        "step_ms": number(r"average time step \(without output\): ([0-9.e+-]+) ms", out),
        "solve_ms": number(r"one solve with the step operator, no contact: ([0-9.e+-]+) ms", out),
        "solve_iterations": number(r"one solve with the step operator, no contact: "
                                   r"[0-9.e+-]+ ms \((\d+) Krylov iterations\)", out),
        "operator_ms": number(r"one operator application: ([0-9.e+-]+) ms", out),
        "stress_ms": number(r"one stress update with the history load: ([0-9.e+-]+) ms", out),
        "iterations": number(r"active-set iterations: (\d+) in", out),
        "steps": number(r"active-set iterations: \d+ in (\d+) steps", out),
        "krylov": number(r"back end: \d+ solves, (\d+) Krylov iterations", out),
        "final": re.search(r"Final displacement: .*", out).group(0),
        "output": out,
    }


def table(title, description, header, baseline):
    """A section's title, its description and the header and alignment lines
    of its table (with the baseline's columns if there is a baseline)."""
    if baseline:
        header += " baseline whole process [s] | this / baseline |"
    return [f"## {title}", "", description, "", header,
            "|" + " ---: |" * (header.count("|") - 1)]


def add_row(lines, cells, row, run_baseline):
    """Appends a table row (and prints it); with run_baseline, first runs the
    same case with the baseline build and adds its time and the ratio."""
    if run_baseline:
        old = run_baseline()
        cells += f" {old['wall']:.2f} | {row['wall'] / old['wall']:.2f} |"
    lines.append(cells)
    print(cells, flush=True)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--baseline", default=None,
                        help="another build to run on the same 2D cases")
    parser.add_argument("--static-sizes", default="128,256,512")
    parser.add_argument("--full-space-limit", type=int, default=256)
    parser.add_argument("--benchmark-sizes", default="256")
    parser.add_argument("--cube-sizes", default="16,24,32")
    parser.add_argument("--cube-steps", default="8,32",
                        help="time steps of k = 1/32 per cube run")
    parser.add_argument("--pairs", type=int, default=5,
                        help="paired runs of the largest static scene, with "
                             "and without contact (and the baseline; 0: none)")
    parser.add_argument("--output", default=os.path.join(REPO_ROOT, "doc", "performance", "tables.md"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    baseline = os.path.abspath(args.baseline) if args.baseline else None
    work = tempfile.mkdtemp(prefix="vc_performance_")
    sizes = lambda text: [int(n) for n in text.split(",") if n]  # noqa: E731

    lines = ["# Performance", "",
             "Written by `benchmarks/run_performance.py` (" +
             " ".join("PATH" if a.startswith("/") else a for a in sys.argv[1:]) +
             "): Release build, one process at a time on a shared 2-core "
             "machine. Compare the ratios within a table: they were measured "
             "in one invocation; absolute times vary from run to run.", ""]

    # 1. The static scene.
    lines += table("2D static scene: one step from rest (cold start)",
              "`elastic.prm` (no plasticity), one step of k = 1/64 at h = 1/N. "
              "*factorisation* is the set-up of the back end for the same mesh "
              "without a contact boundary (analysis and factorisation only); "
              "*set-up* is that of the run with contact (factorisation with the "
              "contact dofs eliminated last, and the compliance read off its "
              "last block). *step* is the program's own average time step, "
              "*solve* one solve with the factorised operator.",
                   ("| N | dofs | contact nodes | method | whole process [s] | mesh [s] "
              "| factorisation [s] | set-up [s] | set-up / factorisation "
              "| step [ms] | solve [ms] | active-set it. | Krylov it. "
              "| peak memory [MB] | bytes per dof |"),
                   baseline)
    for n in sizes(args.static_sizes):
        for method in ["condensed", "full space"]:
            if method == "full space" and n > args.full_space_limit:
                continue
            overrides = {(("Geometry",), "Subdivisions"): str(n),
                         (("Time",), "End time"): repr(1. / 64),
                         (("Linear solver",), "Method"): method}
            text = scene("elastic.prm", overrides)
            row = run(executable, text, work, f"static_{n}_{method[0]}")
            if method == "condensed":
                no_contact = run(executable, set_prm_entries(text, {
                    (("Boundary",), "Contact boundary ids"): ""}), work,
                    f"static_{n}_nocontact")
                factorisation = no_contact["back_end"]
                ratio = f"{row['back_end'] / factorisation:.2f}"
            else:
                factorisation, ratio = float("nan"), ""
            cells = (f"| {n} | {row['dofs']} | {row['contact_nodes']} | {method} "
                     f"| {row['wall']:.2f} | {row['mesh']:.2f} | {factorisation:.2f} "
                     f"| {row['back_end']:.2f} | {ratio} | {row['step_ms']:.4g} "
                     f"| {row['solve_ms']:.4g} | {row['iterations']:.0f} "
                     f"| {row['krylov']:.0f} | {row['memory_mb']:.0f} "
                     f"| {row['bytes_per_dof']:.0f} |")
            add_row(lines, cells, row, baseline and (
                lambda: run(baseline, text, work, f"static_{n}_{method[0]}_baseline",
                            blas_threads=1)))
    lines.append("")

    # 1b. Paired runs of the largest static scene, condensed, with and
    # without contact (and the baseline): one pair is one sample of a shared
    # machine's noise.
    static_sizes = sizes(args.static_sizes)
    if args.pairs > 0 and static_sizes:
        n = static_sizes[-1]
        text = scene("elastic.prm", {(("Geometry",), "Subdivisions"): str(n),
                                     (("Time",), "End time"): repr(1. / 64),
                                     (("Linear solver",), "Method"): "condensed"})
        lines += [f"## 2D static scene at N = {n}: paired runs", "",
                  f"The condensed case of table 1, run {args.pairs} more times, "
                  "each time this build with and without the contact boundary "
                  "(factorisation and set-up as in table 1)"
                  + (" and then the baseline (with `OPENBLAS_NUM_THREADS=1`, "
                     "as above)" if baseline else "")
                  + "; the last row is the median of each column.", "",
                  "| pair | whole process [s] | factorisation [s] | set-up [s] "
                  "| set-up / factorisation |"
                  + (" baseline whole process [s] | this / baseline |"
                     if baseline else ""),
                  "| ---: | ---: | ---: | ---: | ---: |"
                  + (" ---: | ---: |" if baseline else "")]
        samples = []
        for pair in range(1, args.pairs + 1):
            this = run(executable, text, work, f"static_{n}_pair_{pair}")
            no_contact = run(executable, set_prm_entries(text, {
                (("Boundary",), "Contact boundary ids"): ""}), work,
                f"static_{n}_pair_{pair}_nocontact")
            samples.append((this["wall"], no_contact["back_end"],
                            this["back_end"],
                            this["back_end"] / no_contact["back_end"]))
            if baseline:
                old = run(baseline, text, work,
                          f"static_{n}_pair_{pair}_baseline", blas_threads=1)
                samples[-1] += (old["wall"], this["wall"] / old["wall"])
            cells = (f"| {pair} | " + " | ".join(
                f"{value:.3f}" if k in (3, 5) else f"{value:.2f}"
                for k, value in enumerate(samples[-1])) + " |")
            lines.append(cells)
            print(cells, flush=True)
        medians = [statistics.median(column) for column in zip(*samples)]
        lines += ["| median | " + " | ".join(
            f"{value:.3f}" if k in (3, 5) else f"{value:.2f}"
            for k, value in enumerate(medians)) + " |", ""]

    # 2. The benchmark with one and two threads.
    lines += table("2D benchmark: the stress update on one and two threads",
              "`default.prm` at h = k = 1/N, without file output. The same "
              "build with `DEAL_II_NUM_THREADS` = 1 and 2 (one MPI rank); "
              "*step / (solve + stress update)* is the cost of a time step "
              "relative to its two unavoidable parts.",
                   ("| N | dofs | threads | whole process [s] | time loop [s] "
              "| step [ms] | solve [ms] | stress update [ms] "
              "| step / (solve + stress update) | active-set it. per step "
              "| peak memory [MB] |"),
                   baseline)
    for n in sizes(args.benchmark_sizes):
        text = scene("default.prm", {(("Geometry",), "Subdivisions"): str(n),
                                     (("Time",), "Time step"): repr(1. / n)})
        for threads in [1, 2]:
            row = run(executable, text, work, f"benchmark_{n}_{threads}", threads)
            cells = (f"| {n} | {row['dofs']} | {threads} | {row['wall']:.2f} "
                     f"| {row['steps'] * row['step_ms'] / 1000:.2f} "
                     f"| {row['step_ms']:.4g} | {row['solve_ms']:.4g} "
                     f"| {row['stress_ms']:.4g} "
                     f"| {row['step_ms'] / (row['solve_ms'] + row['stress_ms']):.2f} "
                     f"| {row['iterations'] / row['steps']:.2f} | {row['memory_mb']:.0f} |")
            add_row(lines, cells, row, baseline and (
                lambda: run(baseline, text, work, f"benchmark_{n}_{threads}_baseline",
                            threads, blas_threads=1)))
    lines.append("")

    # 3. The cube.
    lines += table("3D cube, hexahedra, condensed back end",
              "`cube_3d.prm` on hexahedra at h = 1/N, the first 8 steps of "
              "k = 1/32 (the contact zone forms) and the whole run (32 steps); "
              "factorisation and set-up as in the static scene (without "
              "contact: 8 steps).",
                   ("| N | steps | dofs | contact nodes | whole process [s] | factorisation [s] "
              "| set-up [s] | set-up / factorisation | step [ms] | solve [ms] "
              "| stress update [ms] | step / (solve + stress update) "
              "| active-set it. per step | peak memory [MB] | bytes per dof |"),
                   None)
    for n in sizes(args.cube_sizes):
        def cube(steps):
            return scene("cube_3d.prm", {
                (("Geometry",), "Subdivisions"): str(n),
                (("Geometry",), "Cell type"): "hypercube",
                (("Time",), "End time"): repr(steps / 32.),
                (("Linear solver",), "Method"): "condensed"})
        no_contact = run(executable, set_prm_entries(cube(8), {
            (("Boundary",), "Contact boundary ids"): ""}), work, f"cube_{n}_nocontact")
        for steps in sizes(args.cube_steps):
            row = run(executable, cube(steps), work, f"cube_{n}_{steps}")
            cells = (f"| {n} | {steps} | {row['dofs']} | {row['contact_nodes']} "
                     f"| {row['wall']:.2f} "
                     f"| {no_contact['back_end']:.2f} | {row['back_end']:.2f} "
                     f"| {row['back_end'] / no_contact['back_end']:.2f} "
                     f"| {row['step_ms']:.4g} | {row['solve_ms']:.4g} | {row['stress_ms']:.4g} "
                     f"| {row['step_ms'] / (row['solve_ms'] + row['stress_ms']):.2f} "
                     f"| {row['iterations'] / row['steps']:.2f} | {row['memory_mb']:.0f} "
                     f"| {row['bytes_per_dof']:.0f} |")
            add_row(lines, cells, row, None)
    lines.append("")

    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w") as f:
        f.write("\n".join(lines))
    print("wrote", args.output)


if __name__ == "__main__":
    main()

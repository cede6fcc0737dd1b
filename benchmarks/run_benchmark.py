#!/usr/bin/env python3
"""Cost benchmark of viscoplastic_contact on the reference scene.

Runs parameters/default.prm (the benchmark of doc/model.md, section 1) with
file output switched off at h = k = 1/N for a list of N (default 32, 64, 128,
256), one run per size, one after the other, and records per size:

* mesh size (cells, displacement dofs, contact nodes) and the number of steps,
  and the back end the program chose (its "Back end:" line),
* the wall time of the whole process (time.perf_counter around the child),
  its user/system CPU time and its peak resident memory (os.wait4 rusage of
  that very child, so the numbers of different sizes do not mix),
* the program's own "Cost measurement" block: the average time step, the
  reference costs (one solve with the step operator and no contact; one
  stress update with the history load), the ratios step / solve (the figure
  of merit) and step / (solve + stress update), the time per dof and step,
  the time loop and the peak memory,
* the active-set iterations (total and per step), the back end's solves and
  Krylov iterations,
* every section of the deal.II TimerOutput table (wall time and calls).

It writes <output-dir>/benchmark.csv and <output-dir>/benchmark.md (and
prints the markdown). Only the Python standard library is used.

Usage (from anywhere; relative default paths are taken from the repo root):

    benchmarks/run_benchmark.py [--executable build/viscoplastic_contact]
                                [--sizes 32,64,128,256]
                                [--output-dir benchmarks/results]

The executable can also be given by the environment variable VC_EXECUTABLE.
Build it in Release mode; a Debug build measures something else.
"""

import argparse
import csv
import datetime
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import add_executable_argument, resolve_executable, set_prm_entries  # noqa: E402

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE_PRM = os.path.join(REPO_ROOT, "parameters", "default.prm")

FLOAT = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
UNIT_TO_SECONDS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9,
                   "min": 60.0, "h": 3600.0}


# --------------------------------------------------------------------------
# Parameter files
# --------------------------------------------------------------------------
def benchmark_prm(n, output_directory):
    """Parameter file text of the benchmark scene at h = k = 1/n."""
    with open(BASE_PRM) as f:
        text = f.read()
    return set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(n),
        (("Time",), "Time step"): repr(1.0 / n),   # shortest exact repr
        (("Output",), "Output directory"): output_directory,
        (("Output",), "Write vtu"): "false",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "true",
        (("Output",), "Measure cost ratios"): "true",
        (("Output",), "Profile times"): "",
    })


# --------------------------------------------------------------------------
# Running
# --------------------------------------------------------------------------
def run_measured(cmd, cwd, stdout_path, stderr_path):
    """Run ``cmd``, return (exit code, wall seconds, rusage of that child).

    The child is reaped with os.wait4 so that ru_maxrss etc. belong to this
    process alone (RUSAGE_CHILDREN would be a maximum over all children).
    """
    with open(stdout_path, "w") as out, open(stderr_path, "w") as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, wall, usage


# --------------------------------------------------------------------------
# Parsing the program's output
# --------------------------------------------------------------------------
def _seconds(value, unit):
    return float(value) * UNIT_TO_SECONDS.get(unit, 1.0)


def parse_stdout(text):
    """Extract the numbers of interest from the program's stdout.

    Returns a dict; keys are absent when the corresponding line is missing.
    The TimerOutput table is parsed generically into ``timers``: a list of
    (section name, calls, wall seconds) in table order.
    """
    res = {}

    def grab(pattern, conv=float, group=1):
        m = re.search(pattern, text)
        return conv(m.group(group)) if m else None

    for key, pattern in [
            ("cells", r"Mesh:\s*(\d+)\s+\S+\s+cells"),
            ("dofs", r"(\d+)\s+displacement dofs"),
            ("contact_nodes", r"(\d+)\s+contact nodes"),
            ("steps", r"(\d+)\s+time steps")]:
        v = grab(pattern, int)
        if v is not None:
            res[key] = v

    m = re.search(r"active-set iterations:\s*(\d+)\s+in\s+(\d+)\s+steps", text)
    if m:
        res["active_set_iterations"] = int(m.group(1))
        res["summary_steps"] = int(m.group(2))
    m = re.search(r"^Back end:\s*([^:\n]+)", text, re.M)
    if m:
        res["back_end"] = m.group(1).strip()
    m = re.search(r"back end:\s*(\d+)\s+solves,\s*(\d+)\s+Krylov iterations", text)
    if m:
        res["solves"] = int(m.group(1))
        res["krylov_iterations"] = int(m.group(2))
    m = re.search(r"operator:\s*assembled\s*(\d+)x,\s*set up by the back end\s*(\d+)x",
                  text)
    if m:
        res["operator_assembled"] = int(m.group(1))
        res["operator_setups"] = int(m.group(2))

    # The "Cost measurement" block.
    unit = r"\s*(ms|us|µs|ns|s|min|h)\b"
    for key, label in [
            ("avg_step_s", r"average time step \(without output\):"),
            ("solve_s", r"one solve with the step operator, no contact:"),
            ("stress_update_s", r"one stress update with the history load:"),
            ("per_dof_step_s", r"per dof and step:"),
            ("time_loop_s", r"time loop \(without output\):")]:
        m = re.search(label + r"\s*(" + FLOAT + ")" + unit, text)
        if m:
            res[key] = _seconds(m.group(1), m.group(2))
    v = grab(r"one solve with the step operator, no contact:.*?\((\d+) Krylov iterations\)",
             int)
    if v is not None:
        res["solve_krylov_iterations"] = v
    v = grab(r"ratio step / solve:\s*(" + FLOAT + ")")
    if v is not None:
        res["ratio_step_to_solve"] = v
    v = grab(r"ratio step / \(solve \+ stress update\):\s*(" + FLOAT + ")")
    if v is not None:
        res["ratio_step_to_solve_and_update"] = v
    v = grab(r"peak memory over the run \[MB\]: sum over ranks (" + FLOAT + r")")
    if v is not None:
        res["peak_memory_mb"] = v

    m = re.search(r"Total wallclock time elapsed since start\s*\|\s*(" + FLOAT
                  + r")\s*(ms|us|s|min|h)?", text)
    if m:
        res["timer_total_s"] = _seconds(m.group(1), m.group(2) or "s")
    res["timers"] = parse_timer_table(text)
    return res


def parse_timer_table(text):
    """Parse deal.II TimerOutput tables: list of (section, calls, wall s).

    Looks for a header row containing "no. calls"; the wall time column is
    the one whose header mentions "wall" (else the column after the calls).
    Every following row ``| name | calls | time | ...`` up to the closing
    rule is a section. Times may carry a unit suffix (s, ms, ...).
    """
    timers = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        cols = [c.strip() for c in lines[i].strip().strip("|").split("|")]
        if len(cols) >= 3 and any("no. calls" in c for c in cols):
            calls_col = next(j for j, c in enumerate(cols) if "no. calls" in c)
            wall_cols = [j for j, c in enumerate(cols) if "wall" in c.lower()]
            wall_col = wall_cols[0] if wall_cols else calls_col + 1
            i += 1
            while i < len(lines):
                row = lines[i].strip()
                if row.startswith("+"):
                    # A rule: either the one under the header (rows follow)
                    # or the closing one.
                    i += 1
                    if i < len(lines) and lines[i].strip().startswith("|"):
                        continue
                    break
                if not row.startswith("|"):
                    break
                cells = [c.strip() for c in row.strip("|").split("|")]
                if len(cells) > max(calls_col, wall_col):
                    m = re.match(r"(" + FLOAT + r")\s*(ms|us|s|min|h)?$",
                                 cells[wall_col])
                    if m and cells[calls_col].isdigit():
                        timers.append((cells[0], int(cells[calls_col]),
                                       _seconds(m.group(1), m.group(2) or "s")))
                i += 1
        i += 1
    return timers


def time_series_stats(path):
    """Number of steps and mean active-set iterations from time_series.csv."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError:
        return {}
    if not rows:
        return {}
    its = [float(r["active_set_iterations"]) for r in rows
           if r.get("active_set_iterations")]
    return {"ts_steps": len(rows),
            "ts_mean_iterations": sum(its) / len(its) if its else None}


# --------------------------------------------------------------------------
# Machine description
# --------------------------------------------------------------------------
def machine_description():
    """Short description: nproc, CPU model, memory, OS."""
    try:
        nproc = len(os.sched_getaffinity(0))
    except AttributeError:
        nproc = os.cpu_count()
    model = platform.processor() or "unknown CPU"
    mem = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    mem = f", {int(line.split()[1]) / 1024**2:.1f} GiB RAM"
                    break
    except OSError:
        pass
    return f"nproc = {nproc}, CPU: {model}{mem}, {platform.system()} {platform.release()}"


def build_type_of(executable):
    """CMAKE_BUILD_TYPE from a CMakeCache.txt next to the executable, if any."""
    cache = os.path.join(os.path.dirname(os.path.abspath(executable)),
                         "CMakeCache.txt")
    try:
        with open(cache) as f:
            for line in f:
                if line.startswith("CMAKE_BUILD_TYPE:"):
                    return line.split("=", 1)[1].strip() or "unknown"
    except OSError:
        pass
    return "unknown (no CMakeCache.txt next to the executable)"


# --------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------
SUMMARY_COLUMNS = [
    # (csv key, markdown header, formatter)
    ("N", "h = k", lambda v: f"1/{v}"),
    ("cells", "cells", str),
    ("dofs", "dofs", str),
    ("contact_nodes", "contact nodes", str),
    ("steps", "steps", str),
    ("process_wall_s", "process wall [s]", lambda v: f"{v:.3g}"),
    ("time_loop_s", "time loop [s]", lambda v: f"{v:.3g}"),
    ("time_per_step_ms", "per step [ms]", lambda v: f"{v:.3g}"),
    ("solve_ms", "one solve [ms]", lambda v: f"{v:.3g}"),
    ("ratio_step_to_solve", "step / solve (figure of merit)", lambda v: f"{v:.3g}"),
    ("stress_update_ms", "one stress update [ms]", lambda v: f"{v:.3g}"),
    ("ratio_step_to_solve_and_update", "step / (solve + stress update)",
     lambda v: f"{v:.3g}"),
    ("us_per_dof_step", "per dof and step [us]", lambda v: f"{v:.3g}"),
    ("active_set_iterations_per_step", "active-set it. / step", lambda v: f"{v:.3g}"),
    ("back_end", "back end", str),
    ("peak_rss_mb", "peak RSS [MB]", lambda v: f"{v:.0f}"),
    ("cpu_user_s", "user CPU [s]", lambda v: f"{v:.3g}"),
]


def summarise(n, rc, wall, usage, parsed, ts):
    """Flatten one run into a dict of CSV columns."""
    steps = parsed.get("steps") or parsed.get("summary_steps") or ts.get("ts_steps")
    row = {
        "N": n,
        "h": repr(1.0 / n),
        "k": repr(1.0 / n),
        "exit_code": rc,
        "cells": parsed.get("cells"),
        "dofs": parsed.get("dofs", 2 * (n + 1) ** 2),
        "contact_nodes": parsed.get("contact_nodes"),
        "steps": steps,
        "process_wall_s": wall,
        "cpu_user_s": usage.ru_utime,
        "cpu_sys_s": usage.ru_stime,
        "peak_rss_mb": usage.ru_maxrss / 1024.0,  # ru_maxrss is in KiB on Linux
        "time_loop_s": parsed.get("time_loop_s"),
        "avg_step_ms_program": (parsed["avg_step_s"] * 1e3
                                if "avg_step_s" in parsed else None),
        "solve_ms": parsed["solve_s"] * 1e3 if "solve_s" in parsed else None,
        "solve_krylov_iterations": parsed.get("solve_krylov_iterations"),
        "stress_update_ms": (parsed["stress_update_s"] * 1e3
                             if "stress_update_s" in parsed else None),
        "ratio_step_to_solve": parsed.get("ratio_step_to_solve"),
        "ratio_step_to_solve_and_update": parsed.get("ratio_step_to_solve_and_update"),
        "us_per_dof_step": (parsed["per_dof_step_s"] * 1e6
                            if "per_dof_step_s" in parsed else None),
        "peak_memory_program_mb": parsed.get("peak_memory_mb"),
        "back_end": parsed.get("back_end"),
        "active_set_iterations": parsed.get("active_set_iterations"),
        "solves": parsed.get("solves"),
        "krylov_iterations": parsed.get("krylov_iterations"),
        "operator_assembled": parsed.get("operator_assembled"),
        "operator_setups": parsed.get("operator_setups"),
        "timer_total_s": parsed.get("timer_total_s"),
    }
    if row["time_loop_s"] is not None and steps:
        row["time_per_step_ms"] = row["time_loop_s"] / steps * 1e3
    else:
        row["time_per_step_ms"] = row["avg_step_ms_program"]
    if row["active_set_iterations"] is not None and steps:
        row["active_set_iterations_per_step"] = row["active_set_iterations"] / steps
    else:
        row["active_set_iterations_per_step"] = ts.get("ts_mean_iterations")
    for name, calls, secs in parsed.get("timers", []):
        row[f"wall_s[{name}]"] = secs
        row[f"calls[{name}]"] = calls
    return row


def write_csv(path, rows):
    """Write all runs to CSV; timer columns are the union over the runs."""
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in keys})


def markdown_report(rows, header_lines):
    """Markdown text: header, summary table, TimerOutput phase table."""
    md = list(header_lines) + [""]
    md.append("| " + " | ".join(h for _, h, _ in SUMMARY_COLUMNS) + " |")
    md.append("|" + "---|" * len(SUMMARY_COLUMNS))
    for r in rows:
        cells = []
        for key, _, fmt in SUMMARY_COLUMNS:
            v = r.get(key)
            cells.append("n/a" if v is None else fmt(v))
        md.append("| " + " | ".join(cells) + " |")
    failed = [r for r in rows if r.get("exit_code") != 0]
    if failed:
        md.append("")
        md.append("**Failed runs:** " + ", ".join(
            f"N = {r['N']} (exit code {r['exit_code']})" for r in failed))

    sections = []
    for r in rows:
        for k in r:
            if k.startswith("wall_s[") and k[7:-1] not in sections:
                sections.append(k[7:-1])
    md += ["", "TimerOutput sections (wall time, number of calls in parentheses):", ""]
    md.append("| section | " + " | ".join(f"h = k = 1/{r['N']}" for r in rows) + " |")
    md.append("|---|" + "---|" * len(rows))
    for s in sections:
        cells = []
        for r in rows:
            secs = r.get(f"wall_s[{s}]")
            cells.append("–" if secs is None
                         else f"{secs:.3g} s ({r.get(f'calls[{s}]')})")
        md.append(f"| {s} | " + " | ".join(cells) + " |")
    md.append("| *total (TimerOutput)* | " + " | ".join(
        "–" if r.get("timer_total_s") is None else f"{r['timer_total_s']:.3g} s"
        for r in rows) + " |")
    md += ["", "Columns: *process wall* = wall time of the whole process measured "
           "by the script (setup included); *time loop* (without output), "
           "*one solve*, *one stress update*, the two ratios and *per dof and "
           "step* come from the program's \"Cost measurement\" block, measured "
           "inside the same run after the time loop (wall time, maximum over "
           "the ranks): *one solve* = one solve with the step operator and no "
           "contact (the back end's solve of K u = f); *one stress update* = "
           "the history update at every stress point with the assembly of the "
           "history load; *step / solve* (the figure of merit) = average time "
           "step / one solve; *step / (solve + stress update)* = average time "
           "step / (one solve + one stress update), i.e. against a step "
           "without contact; *per step* = time loop / steps; *back end* = the "
           "program's \"Back end:\" line (Method = auto chooses); *peak RSS* = "
           "ru_maxrss of the child process."]
    return "\n".join(md) + "\n"


# --------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------
def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_executable_argument(parser)
    parser.add_argument("--sizes", default="32,64,128,256",
                        help="comma separated N, h = k = 1/N (default %(default)s)")
    parser.add_argument("--output-dir", default=None,
                        help="where benchmark.csv/.md go "
                             "(default: benchmarks/results in the repo root)")
    args = parser.parse_args(argv)

    executable = resolve_executable(args.executable)
    if not os.access(executable, os.X_OK):
        sys.exit(f"error: executable not found or not executable: {executable}")
    sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    out_dir = (os.path.abspath(args.output_dir) if args.output_dir
               else os.path.join(REPO_ROOT, "benchmarks", "results"))
    os.makedirs(out_dir, exist_ok=True)
    csv_path = os.path.join(out_dir, "benchmark.csv")
    md_path = os.path.join(out_dir, "benchmark.md")

    started = datetime.datetime.now().astimezone()
    header = [
        "# viscoplastic_contact: cost benchmark",
        "",
        f"Date: {started.strftime('%Y-%m-%d %H:%M %Z')}. Machine: {machine_description()}.",
        f"Executable: `{executable}` (build type: {build_type_of(executable)}).",
        "Scene: parameters/default.prm (unit square, P1 triangles with the "
        "default Simplex pattern /, T = 1) with h = k = 1/N, VTU output, "
        "profiles and per-step printing off; one MPI rank.",
        "All numbers come from one invocation of benchmarks/run_benchmark.py "
        "(one run per size, run sequentially).",
        "Load average (1, 5, 15 min) when the script started: "
        + ", ".join(f"{x:.2f}" for x in os.getloadavg())
        + " (other processes on the machine disturb the timings).",
    ]

    rows = []
    failures = 0
    work = tempfile.mkdtemp(prefix="vc_benchmark_")
    try:
        for n in sizes:
            run_dir = os.path.join(work, f"N{n}")
            os.makedirs(run_dir)
            prm = os.path.join(run_dir, "benchmark.prm")
            with open(prm, "w") as f:
                f.write(benchmark_prm(n, os.path.join(run_dir, "output")))
            stdout_path = os.path.join(run_dir, "stdout.txt")
            stderr_path = os.path.join(run_dir, "stderr.txt")
            print(f"running N = {n} ...", file=sys.stderr, flush=True)
            rc, wall, usage = run_measured([executable, prm], REPO_ROOT,
                                           stdout_path, stderr_path)
            with open(stdout_path, errors="replace") as f:
                parsed = parse_stdout(f.read())
            ts = time_series_stats(os.path.join(run_dir, "output", "time_series.csv"))
            row = summarise(n, rc, wall, usage, parsed, ts)
            rows.append(row)
            print(f"  N = {n}: exit code {rc}, {wall:.2f} s, "
                  f"peak RSS {row['peak_rss_mb']:.0f} MB", file=sys.stderr, flush=True)
            if rc != 0:
                failures += 1
                with open(stderr_path, errors="replace") as f:
                    tail = f.read()[-2000:]
                print(f"  run failed; end of stderr:\n{tail}", file=sys.stderr)
            if not parsed.get("timers"):
                print("  warning: no TimerOutput table found in stdout",
                      file=sys.stderr)
            # Rewrite the reports after every size so partial results survive.
            write_csv(csv_path, rows)
            with open(md_path, "w") as f:
                f.write(markdown_report(rows, header))
            shutil.rmtree(run_dir, ignore_errors=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    with open(md_path) as f:
        print(f.read())
    print(f"wrote {csv_path} and {md_path}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

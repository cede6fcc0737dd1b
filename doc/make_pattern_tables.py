#!/usr/bin/env python3
"""Regenerate doc/pattern_tables.md: what the simplex pattern of the 2D mesh
changes.

For each 2D `Simplex pattern` of subsection Geometry (/, backslash, union
jack, crossed) it runs

* the paper's convergence study, parameters/convergence.prm (h = k = 1/2 ...
  1/32 against h = k = 1/64, every run and the reference on the same
  pattern), into output/patterns/<name>;
* the benchmark, parameters/default.prm at h = 1/32, k = 1/64 with
  Write vtu = false and Profile times = 1, into
  output/patterns/<name>_benchmark;

and writes doc/pattern_tables.md with (a) per pattern the convergence table
(h, k, dofs, errors, observed orders) read from convergence.csv and (b) one
table of the benchmark at t = 1 per pattern: cells, dofs, contact nodes,
total contact force, the contact-node counts by status, the largest von Mises
stress, the uniqueness eigenvalue printed at start-up, and the relative
difference of the total contact force and of the contact pressure profile
against the pattern /. The directory names are slash, backslash, union_jack
and crossed.

Usage (from anywhere):

    doc/make_pattern_tables.py [--executable build/viscoplastic_contact]
                               [--skip-runs]

The executable may also be given by the environment variable VC_EXECUTABLE.
Only the Python standard library is used.
"""

import argparse
import csv
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import add_executable_argument, REPO_ROOT, resolve_executable, set_prm_entries  # noqa: E402

DOC_DIR = os.path.join(REPO_ROOT, "doc")
OUTPUT_ROOT = os.path.join(REPO_ROOT, "output", "patterns")
TABLES_MD = os.path.join(DOC_DIR, "pattern_tables.md")

# Simplex pattern (value of the parameter) -> directory name.
PATTERNS = [("/", "slash"), ("backslash", "backslash"),
            ("union jack", "union_jack"), ("crossed", "crossed")]
DESCRIPTIONS = {
    "/": "each square split by the diagonal from (x_i,y_j) to (x_i+1,y_j+1) "
         "(the published benchmark; the default)",
    "backslash": "each square split by the other diagonal, from "
                 "(x_i+1,y_j) to (x_i,y_j+1)",
    "union jack": "alternating diagonals that meet at every second vertex",
    "crossed": "both diagonals around a new vertex at the centre of each "
               "square (4 triangles per square)",
}
REFERENCE_PATTERN = "/"
BENCHMARK_SUBDIVISIONS = 32
BENCHMARK_TIME_STEP = 1.0 / 64


# --------------------------------------------------------------------------
# Runs
# --------------------------------------------------------------------------
def convergence_prm(pattern, output_directory):
    with open(os.path.join(REPO_ROOT, "parameters", "convergence.prm")) as f:
        text = f.read()
    return set_prm_entries(text, {
        (("Geometry",), "Simplex pattern"): pattern,
        (("Output",), "Output directory"): output_directory,
    })


def benchmark_prm(pattern, output_directory):
    with open(os.path.join(REPO_ROOT, "parameters", "default.prm")) as f:
        text = f.read()
    return set_prm_entries(text, {
        (("Geometry",), "Simplex pattern"): pattern,
        (("Geometry",), "Subdivisions"): str(BENCHMARK_SUBDIVISIONS),
        (("Time",), "Time step"): repr(BENCHMARK_TIME_STEP),
        (("Output",), "Output directory"): output_directory,
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "1",
        (("Output",), "Verbose"): "false",
        (("Output",), "Print timing summary"): "false",
    })


def run(executable, prm_text, out_dir, tmpdir, label):
    """Run one parameter file into out_dir (wiped first); the terminal output
    goes to out_dir/run.log. Returns the wall time in seconds."""
    if os.path.isdir(out_dir):
        shutil.rmtree(out_dir)
    prm = os.path.join(tmpdir, os.path.basename(out_dir) + ".prm")
    with open(prm, "w") as f:
        f.write(prm_text)
    print(f"running {label} ...", flush=True)
    start = time.perf_counter()
    proc = subprocess.run([executable, prm], cwd=REPO_ROOT,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    wall = time.perf_counter() - start
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "run.log"), "w") as f:
        f.write(proc.stdout)
    if proc.returncode != 0:
        sys.exit(f"error: {label} failed with exit code {proc.returncode}; see "
                 f"{os.path.relpath(os.path.join(out_dir, 'run.log'), REPO_ROOT)}"
                 f"\n{proc.stdout[-2000:]}")
    print(f"  {wall:.1f} s", flush=True)
    return wall


# --------------------------------------------------------------------------
# Reading the output
# --------------------------------------------------------------------------
def read_convergence(out_dir):
    """convergence.csv -> list of dicts of floats (empty field: NaN)."""
    with open(os.path.join(out_dir, "convergence.csv"), newline="") as f:
        return [{k: float(v) if v else float("nan") for k, v in row.items()}
                for row in csv.DictReader(f)]


def read_benchmark(out_dir):
    """The numbers of table (b) from one benchmark run."""
    with open(os.path.join(out_dir, "run.log")) as f:
        log = f.read()
    m = re.search(r"^Mesh: (\d+) \S+ cells, (\d+) displacement dofs, "
                  r"(\d+) contact nodes, (\d+) time steps", log, re.M)
    if not m:
        sys.exit(f"error: no 'Mesh:' line in {out_dir}/run.log")
    result = {"cells": int(m.group(1)), "dofs": int(m.group(2)),
              "contact_nodes": int(m.group(3)), "steps": int(m.group(4))}
    m = re.search(r"^Uniqueness: smallest eigenvalue of \(stiffness, lumped "
                  r"normal boundary mass\) = ([-+\d.eE]+)", log, re.M)
    result["uniqueness"] = float(m.group(1)) if m else float("nan")
    with open(os.path.join(out_dir, "parameters.prm")) as f:
        m = re.search(r"set\s+Layer thickness\s*=\s*([^\s#]+)", f.read())
    result["g"] = float(m.group(1))
    with open(os.path.join(out_dir, "time_series.csv"), newline="") as f:
        last = list(csv.DictReader(f))[-1]
    result["time"] = float(last["time"])
    result["series_force"] = float(last["total_contact_force"])
    result["max_von_mises"] = float(last["max_von_mises"])
    profiles = sorted(glob.glob(os.path.join(out_dir, "contact_profile_*.csv")))
    if not profiles:
        sys.exit(f"error: no contact profile in {out_dir}")
    with open(profiles[-1], newline="") as f:
        nodes = sorted(csv.DictReader(f), key=lambda r: float(r["x"]))
    result["x"] = [float(r["x"]) for r in nodes]
    result["pressure"] = [float(r["contact_pressure"]) for r in nodes]
    result["u_nu"] = [float(r["u_nu"]) for r in nodes]
    result["weight"] = [float(r["weight"]) for r in nodes]
    result["status"] = [int(float(r["status"])) for r in nodes]
    result["force"] = sum(float(r["nodal_force"]) for r in nodes)
    status = [int(float(r["status"])) for r in nodes]
    result["counts"] = {s: status.count(s) for s in (0, 1, 2)}
    result["profile_time"] = float(nodes[0]["time"])
    return result


# --------------------------------------------------------------------------
# Formatting
# --------------------------------------------------------------------------
def fraction(value):
    return f"1/{int(round(1 / value))}"


def order(value):
    return "-" if not math.isfinite(value) else f"{value:.2f}"


def percent(value):
    return f"{100 * value:.2g}%" if value >= 1e-4 else f"{100 * value:.1e}%"


def write_tables(studies, benchmarks, walls):
    reference = benchmarks[REFERENCE_PATTERN]
    lines = [
        "# The simplex pattern of the 2D mesh",
        "",
        "Generated by `doc/make_pattern_tables.py` (Release build, one MPI "
        "rank, one run at a time on the 2-core machine):",
        "",
        "```sh",
        "/usr/bin/python3 doc/make_pattern_tables.py [--executable PATH] [--skip-runs]",
        "```",
        "",
        "`Simplex pattern` (subsection Geometry) says how the generated box is "
        "cut into triangles. For each 2D pattern the script runs",
        "",
        "* the paper's convergence study, `parameters/convergence.prm` "
        "(h = k = 1/2 ... 1/32 against the reference h = k = 1/64 on the same "
        "pattern) with `set Simplex pattern = <pattern>`, into "
        "`output/patterns/<name>`;",
        f"* the benchmark, `parameters/default.prm` at h = 1/"
        f"{BENCHMARK_SUBDIVISIONS}, k = {fraction(BENCHMARK_TIME_STEP)} with "
        "`Write vtu = false`, `Profile times = 1`, into "
        "`output/patterns/<name>_benchmark`.",
        "",
        "| pattern | name | triangles |",
        "|---|---|---|",
    ]
    for pattern, name in PATTERNS:
        lines.append(f"| `{pattern}` | {name} | {DESCRIPTIONS[pattern]} |")
    lines += ["", "Each convergence study compares its runs with its own "
              "reference (same pattern at h = k = 1/64); the patterns give "
              "nested meshes, so the transfer of the coarse solutions to the "
              "reference mesh is exact (doc/accuracy.md, *How the runs are "
              "compared*).", ""]

    # (a) convergence tables
    lines += ["## Convergence studies", "",
              "error = max_n (||u_n - u_n^ref||_V + ||sigma_n - sigma_n^ref||_Q); "
              "err_u and err_sigma are the two parts, each maximised over n on "
              "its own; the orders are observed in h + k between consecutive "
              "rows.", ""]
    for pattern, name in PATTERNS:
        rows = studies[pattern]
        lines += [f"### Simplex pattern = {pattern}", "",
                  f"Run time of the study (all runs and the reference): "
                  f"{walls.get(name, float('nan')):.1f} s.", "",
                  "| h | k | dofs | err_u | order | err_sigma | order | error "
                  "| order |",
                  "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rows:
            if not math.isfinite(r["error"]):
                lines.append(f"| {fraction(r['h'])} | {fraction(r['k'])} | "
                             "failed | | | | | | |")
                continue
            lines.append(
                f"| {fraction(r['h'])} | {fraction(r['k'])} | {int(r['dofs'])} | "
                f"{r['error_u']:.3e} | {order(r['order_u'])} | "
                f"{r['error_sigma']:.3e} | {order(r['order_sigma'])} | "
                f"{r['error']:.3e} | {order(r['order'])} |")
        lines.append("")

    # Side by side: total error and its order per pattern.
    hs = [r["h"] for r in studies[REFERENCE_PATTERN]]
    lines += ["### Side by side", "",
              "Total error (observed order in parentheses) per pattern, and "
              "its ratio to the error of `/` at the same h = k:", "",
              "| h = k | " + " | ".join(f"`{p}`" for p, _ in PATTERNS) + " | "
              + " | ".join(f"`{p}` / `/`" for p, _ in PATTERNS
                           if p != REFERENCE_PATTERN) + " |",
              "|---|" + "---:|" * (2 * len(PATTERNS) - 1)]
    for i, h in enumerate(hs):
        cells = []
        ratios = []
        base = studies[REFERENCE_PATTERN][i]["error"]
        for pattern, _ in PATTERNS:
            r = studies[pattern][i]
            cells.append(f"{r['error']:.3e} ({order(r['order'])})")
            if pattern != REFERENCE_PATTERN:
                ratios.append(f"{r['error'] / base:.2f}")
        lines.append(f"| {fraction(h)} | " + " | ".join(cells) + " | "
                     + " | ".join(ratios) + " |")
    lines.append("")

    # (b) the benchmark at h = 1/32, k = 1/64, t = 1
    lines += [f"## The benchmark at h = 1/{BENCHMARK_SUBDIVISIONS}, "
              f"k = {fraction(BENCHMARK_TIME_STEP)}, t = "
              f"{reference['profile_time']:g}", "",
              "Cells, dofs and contact nodes from the program's `Mesh:` line; "
              "the uniqueness eigenvalue from its start-up line (smallest "
              "generalised eigenvalue of stiffness against the lumped normal "
              "boundary mass, doc/model.md, section 4); the counts and the "
              "total contact force (sum of the nodal forces) from "
              "contact_profile_0064.csv, the largest von Mises stress from the "
              "last row of time_series.csv. The differences against `/` are "
              "taken at the contact nodes, which are the same points x_i for "
              "every pattern: *force diff.* = |F - F(/)| / F(/); *pressure "
              "diff. (max)* = max_i |p_i - p_i(/)| / max_i p_i(/), with the node "
              "x_i where it is largest; *pressure diff. (L2)* = "
              "(sum_i w_i (p_i - p_i(/))^2 / sum_i w_i p_i(/)^2)^(1/2) with the "
              "nodal weights w_i; *u_nu diff.* = max_i |u_nu,i - u_nu,i(/)| / g.",
              "",
              "| pattern | cells | dofs | contact nodes | total contact force "
              "[N/m] | rigid limit (2) | compliance (1) | no contact (0) | "
              "max von Mises | uniqueness eigenvalue | force diff. vs `/` | "
              "pressure diff. (max) vs `/` | pressure diff. (L2) vs `/` | "
              "u_nu diff. vs `/` |",
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    pmax = max(abs(p) for p in reference["pressure"])
    diffs = {}
    for pattern, name in PATTERNS:
        b = benchmarks[pattern]
        if len(b["x"]) != len(reference["x"]) or any(
                abs(x - y) > 1e-12 for x, y in zip(b["x"], reference["x"])):
            sys.exit(f"error: the contact nodes of {pattern} are not those of "
                     f"{REFERENCE_PATTERN}")
        if not math.isclose(b["force"], b["series_force"], rel_tol=1e-6):
            print(f"warning: {pattern}: sum of the nodal forces {b['force']} != "
                  f"time_series.csv {b['series_force']}")
        force_diff = abs(b["force"] - reference["force"]) / reference["force"]
        jumps = [abs(p - q) for p, q in zip(b["pressure"], reference["pressure"])]
        where = b["x"][jumps.index(max(jumps))]
        pressure_diff = max(jumps) / pmax
        pressure_l2 = math.sqrt(
            sum(w * d ** 2 for w, d in zip(reference["weight"], jumps))
            / sum(w * p ** 2 for w, p in zip(reference["weight"],
                                             reference["pressure"])))
        u_diff = max(abs(u - v) for u, v in zip(b["u_nu"], reference["u_nu"])) \
            / reference["g"]
        diffs[pattern] = (force_diff, pressure_diff, where, pressure_l2, u_diff)
        c = b["counts"]
        same = pattern == REFERENCE_PATTERN
        lines.append(
            f"| `{pattern}` | {b['cells']} | {b['dofs']} | {b['contact_nodes']} | "
            f"{b['force']:.6g} | {c[2]} | {c[1]} | {c[0]} | "
            f"{b['max_von_mises']:.4g} | {b['uniqueness']:.6g} | "
            f"{'-' if same else percent(force_diff)} | "
            f"{'-' if same else f'{percent(pressure_diff)} (x = {where:g})'} | "
            f"{'-' if same else percent(pressure_l2)} | "
            f"{'-' if same else percent(u_diff)} |")
    lines.append("")
    walls_b = [walls.get(f"{name}_benchmark") for _, name in PATTERNS]
    if all(w is not None for w in walls_b):
        lines += ["Run time of the benchmark runs (whole process): "
                  + ", ".join(f"`{p}` {w:.2f} s" for (p, _), w in
                              zip(PATTERNS, walls_b)) + ".", ""]

    # What the numbers show (computed, so that it stays true on a rerun).
    others = [p for p, _ in PATTERNS if p != REFERENCE_PATTERN]
    finest = {p: studies[p][-1] for p, _ in PATTERNS}
    orders = {p: [r["order"] for r in studies[p] if math.isfinite(r["order"])]
              for p, _ in PATTERNS}
    stress_share = [r["error_sigma"] / r["error_u"] for p, _ in PATTERNS
                    for r in studies[p] if math.isfinite(r["error"])]
    largest_from = None  # first level from which / has the largest error
    for i in range(len(hs)):
        if all(studies[REFERENCE_PATTERN][j]["error"]
               >= max(studies[p][j]["error"] for p in others)
               for j in range(i, len(hs))):
            largest_from = i
            break
    worst_force = max(others, key=lambda p: diffs[p][0])
    worst_pressure = max(others, key=lambda p: diffs[p][1])
    worst_l2 = max(others, key=lambda p: diffs[p][3])
    worst_u = max(others, key=lambda p: diffs[p][4])
    counts_equal = all(benchmarks[p]["counts"] == reference["counts"] for p in others)
    crossed = benchmarks.get("crossed")
    u_orders = [finest[p]["order_u"] for p, _ in PATTERNS]
    rigid_x = [x for x, st in zip(reference["x"], reference["status"]) if st == 2]
    spacing = reference["x"][1] - reference["x"][0]
    at_zone_edge = bool(rigid_x) and \
        abs(diffs[worst_pressure][2] - min(rigid_x)) <= 1.5 * spacing
    lines += [
        "## What the numbers show", "",
        "* **Convergence.** At the finest pair (h = k = "
        f"{fraction(hs[-1])} against 1/64) the observed orders of the total "
        "error are "
        + ", ".join(f"{order(finest[p]['order'])} (`{p}`)" for p, _ in PATTERNS)
        + f" (over all levels between {min(min(v) for v in orders.values()):.2f} "
        f"and {max(max(v) for v in orders.values()):.2f}). The last order of each "
        "study is inflated, as in doc/accuracy.md: its reference is only twice "
        "as fine. The displacement part has "
        + ("nearly the same orders on every pattern ("
           if max(u_orders) - min(u_orders) < 0.1 else "the orders ")
        + ", ".join(f"{order(finest[p]['order_u'])}" for p, _ in PATTERNS)
        + (")" if max(u_orders) - min(u_orders) < 0.1 else "")
        + " at the finest pair; the stress part is "
        f"{min(stress_share):.0f} to {max(stress_share):.0f} times the "
        "displacement part and decides the total.",
        "* **Size of the errors.** At h = k = "
        f"{fraction(hs[-1])} the errors of "
        + ", ".join(f"`{p}`" for p in others) + " are "
        + ", ".join(f"{finest[p]['error'] / finest[REFERENCE_PATTERN]['error']:.2f}"
                    for p in others)
        + " times that of `/`"
        + (f"; from h = k = {fraction(hs[largest_from])} on, `/` has the largest "
           "error of the four" if largest_from is not None else "")
        + "."
        + (f" `crossed` has {crossed['dofs'] / reference['dofs']:.2f} times "
           "the dofs of the others at the same h (the centre vertices)."
           if crossed else ""),
        "* **The benchmark at t = 1.** "
        + ("The contact state is the same on every pattern ("
           f"{reference['counts'][2]} nodes at the rigid limit, "
           f"{reference['counts'][1]} in compliance, {reference['counts'][0]} "
           "out of contact). " if counts_equal else
           "The contact state depends on the pattern (nodes at the rigid limit: "
           + ", ".join(f"{benchmarks[p]['counts'][2]} (`{p}`)" for p, _ in PATTERNS)
           + "). ")
        + f"The total contact force differs from that of `/` by at most "
        f"{percent(diffs[worst_force][0])} (`{worst_force}`) and u_nu by at "
        f"most {percent(diffs[worst_u][4])} of g (`{worst_u}`). The contact "
        f"pressure differs by at most {percent(diffs[worst_pressure][1])} of "
        f"its largest value (`{worst_pressure}`, at x = "
        f"{diffs[worst_pressure][2]:g})"
        + (", i.e. at the left end of the zone at the rigid limit, where the "
           "foundation's part of the pressure jumps"
           if at_zone_edge else "")
        + f"; in the weighted L2 sense by at most {percent(diffs[worst_l2][3])}. The "
        "largest von Mises stress (at a corner singularity) is "
        + ", ".join(f"{benchmarks[p]['max_von_mises']:.3g} (`{p}`)"
                    for p, _ in PATTERNS) + ".",
        "* **Uniqueness margin.** "
        + ", ".join(f"{benchmarks[p]['uniqueness']:.4g} (`{p}`)"
                    for p, _ in PATTERNS)
        + ", against the steepest softening |c2| = 100: the pattern changes it "
        "by less than "
        + percent(max(abs(benchmarks[p]["uniqueness"] / reference["uniqueness"] - 1)
                      for p in others) * 1.0001)
        + ".",
    ]
    with open(TABLES_MD, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {os.path.relpath(TABLES_MD, REPO_ROOT)}")


# --------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------
def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_executable_argument(parser)
    parser.add_argument("--skip-runs", action="store_true",
                        help="reuse the existing output in output/patterns/")
    args = parser.parse_args(argv)

    walls_path = os.path.join(OUTPUT_ROOT, "run_times.csv")
    walls = {}
    if not args.skip_runs:
        executable = resolve_executable(args.executable)
        if not os.access(executable, os.X_OK):
            sys.exit(f"error: executable not found or not executable: {executable}")
        os.makedirs(OUTPUT_ROOT, exist_ok=True)
        with tempfile.TemporaryDirectory(prefix="vc_patterns_") as tmp:
            for pattern, name in PATTERNS:
                out = os.path.join(OUTPUT_ROOT, name)
                walls[name] = run(executable, convergence_prm(pattern, out), out,
                                  tmp, f"convergence study, Simplex pattern = {pattern}")
                out = os.path.join(OUTPUT_ROOT, f"{name}_benchmark")
                walls[f"{name}_benchmark"] = run(
                    executable, benchmark_prm(pattern, out), out, tmp,
                    f"benchmark h = 1/{BENCHMARK_SUBDIVISIONS}, Simplex pattern = {pattern}")
        with open(walls_path, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["run", "wall_time"])
            for key, value in walls.items():
                writer.writerow([key, repr(value)])
    elif os.path.exists(walls_path):
        with open(walls_path, newline="") as f:
            walls = {r["run"]: float(r["wall_time"]) for r in csv.DictReader(f)}

    studies = {p: read_convergence(os.path.join(OUTPUT_ROOT, name))
               for p, name in PATTERNS}
    benchmarks = {p: read_benchmark(os.path.join(OUTPUT_ROOT, f"{name}_benchmark"))
                  for p, name in PATTERNS}
    write_tables(studies, benchmarks, walls)
    return 0


if __name__ == "__main__":
    sys.exit(main())

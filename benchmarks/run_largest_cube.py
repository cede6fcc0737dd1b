#!/usr/bin/python3
"""The largest cube this machine runs with the shipped defaults.

Runs parameters/cube_3d.prm as shipped (Method = auto, Initial cycles =
auto, VTU output on) with only these entries changed: Subdivisions = N
(--subdivisions, 3 (N+1)^3 dofs: 152 gives 10.7M), the first --steps time
steps (Checkpoint / Stop after step), a checkpoint and a VTU file after
every step, the output in a folder of --workdir. Records what the program
prints (the back end and why, the initial cycles, the active-set iterations
of each step, the peak memory over the run, the
TimerOutput table, the cost measurement) and the sizes of the files it
wrote, and writes them to --output as a Markdown page.

    benchmarks/run_largest_cube.py [--executable build/viscoplastic_contact]
        [--subdivisions 152] [--ranks 2] [--steps 2] [--workdir /tmp]
        [--resume-ranks R] [--keep] [--output doc/back_ends/largest_cube.md]

With --resume-ranks R the run's last checkpoint is then resumed on R ranks
for one more step (Resume = true, Stop after step = steps + 1), and an
uninterrupted run of steps + 1 steps on --ranks ranks (no VTU output) is
the reference: every row of the two time series must agree in all columns
but the wall time and the Krylov iterations to the accuracy of the linear
solves, |difference| <= 1e-6 |value| + 1e-9 (the iteration and node counts
exactly), and the final norms the program prints to a relative 1e-6 (8
digits); the page gets a section on the comparison, and the script exits
with status 1 if they differ.

The run needs about 1.7 kB per dof (18 GB at N = 152) and writes about
2.5 GB of VTU files and a 7 GB checkpoint at N = 152 (the resume and the
reference run another 7 GB each); the folders are removed afterwards
unless --keep. Build in Release mode.
"""

import argparse
import datetime
import glob
import os
import platform
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries, timed_run)


def scene(subdivisions, steps):
    with open(os.path.join(REPO_ROOT, "parameters", "cube_3d.prm")) as f:
        text = f.read()
    text = set_prm_entries(text, {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Output",), "Output directory"): "results",
        (("Output",), "Output interval"): "1",
        (("Output",), "Measure cost ratios"): "true"})
    return text + ("\nsubsection Checkpoint\n"
                   "  set Checkpoint interval = 1\n"
                   f"  set Stop after step     = {steps}\n"
                   "end\n")


# The time series of a resumed run agree with the uninterrupted run's to
# the accuracy of the linear solves: they stop at Tolerance, and on another
# number of ranks the Krylov method takes another path to it, which moves a
# single node's value (the peak pressure) more than the sums.
RELATIVE = 1e-6
ABSOLUTE = 1e-9


def relative_difference(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def compare_runs(reference_dir, resumed_dir, reference_out, resumed_out):
    """The largest relative difference per column of the two time series
    (all but the wall time and the Krylov iterations) and of the final
    norms; returns (Markdown lines, whether they agree)."""
    def series(directory):
        with open(os.path.join(directory, "results", "time_series.csv")) as f:
            rows = [line.strip().split(",") for line in f if line.strip()]
        return rows[0], [[float(x) for x in row] for row in rows[1:]]

    header, reference = series(reference_dir)
    _, resumed = series(resumed_dir)
    skipped = {"wall_time", "krylov_iterations"}
    counts = {"step", "active_set_iterations", "unilateral_nodes",
              "compliance_nodes", "no_contact_nodes"}
    agree = len(reference) == len(resumed)
    worst = {}  # column: (largest |difference|, largest relative difference)
    for a, b in zip(reference, resumed):
        for name, x, y in zip(header, a, b):
            if name in skipped:
                continue
            absolute, relative = worst.get(name, (0., 0.))
            worst[name] = (max(absolute, abs(x - y)),
                           max(relative, relative_difference(x, y)))
            agree = agree and (x == y if name in counts else
                               abs(x - y) <= RELATIVE * max(abs(x), abs(y))
                               + ABSOLUTE)

    def finals(out):
        return [float(x) for line in out.splitlines()
                if line.startswith(("  final state:", "  final contact:",
                                    "Final displacement:"))
                for x in re.findall(r"(?<![\w.])[-+]?\d+(?:\.\d+)?"
                                    r"(?:e[-+]?\d+)?",
                                    line.split(":", 1)[1])]
    final_reference, final_resumed = finals(reference_out), finals(resumed_out)
    final_worst = max((relative_difference(x, y) for x, y in
                       zip(final_reference, final_resumed)), default=0.)
    agree = (agree and len(final_reference) == len(final_resumed) > 0
             and final_worst <= 1e-6)
    lines = ["| quantity | largest difference | largest relative "
             "difference |", "|---|---:|---:|"]
    lines += [f"| {name} (time series, steps 1 to {len(resumed)}) "
              f"| {absolute:.1e} | {relative:.1e} |"
              for name, (absolute, relative) in worst.items()]
    lines += [f"| final norms and contact counts ({len(final_resumed)} "
              f"numbers, 8 digits printed) | | {final_worst:.1e} |"]
    return lines, agree


def megabytes(paths):
    return sum(os.path.getsize(p) for p in paths) / 1e6


def report(stdout, wall, peak_rank_mb, results, args):
    """The Markdown page of one run."""
    def find(pattern, default=""):
        match = re.search(pattern, stdout, re.M)
        return match.group(1) if match else default

    final_mesh = re.search(r"^Initial cycles done: (\d+) cells, (\d+) dofs, "
                           r"(\d+) contact nodes", stdout, re.M) or re.search(
        r"^Mesh: (\d+) \w+ cells, (\d+) displacement dofs, (\d+) contact",
        stdout, re.M)
    cells, dofs, contact_nodes = (int(g) for g in final_mesh.groups())
    back_end = find(r"^Initial cycles done: .*?back end: (.*)$") or find(
        r"^Back end: (.*)$")
    peak = float(find(r"peak memory over the run \[MB\]: sum over ranks "
                      r"([\d.]+)", "nan"))
    largest = float(find(r"peak memory over the run \[MB\]: sum over ranks "
                         r"[\d.]+, largest rank ([\d.]+)", "nan"))
    steps = re.findall(r"^Step\s+(\d+)\s+t =\s+(\S+)\s+active-set iterations"
                       r"\s+(\d+).*contact force (\S+)", stdout, re.M)
    timer = "\n".join(line for line in stdout.splitlines()
                      if line.startswith(("+", "|")))
    cost = "\n".join(line for line in stdout.split(
        "Cost measurement", 1)[-1].splitlines()[1:] if line.startswith("  "))
    vtu = sorted(glob.glob(os.path.join(results, "solution_*.vtu")))
    last = sorted({re.sub(r"\.\d+\.vtu$", "", v) for v in vtu})[-1]
    checkpoint = glob.glob(os.path.join(results, "checkpoint", "step_*.bin"))

    lines = [
        "# The largest cube on this machine, with the shipped defaults", "",
        f"Generated by `benchmarks/run_largest_cube.py` on "
        f"{datetime.date.today()} ({platform.node()}, {os.cpu_count()} cores); "
        f"command: `benchmarks/run_largest_cube.py "
        f"{' '.join(a for a in sys.argv[1:] if not a.startswith('/'))}`.", "",
        f"`parameters/cube_3d.prm` as shipped (`Method = auto`, `Initial "
        f"cycles = auto`, VTU output), with `Subdivisions = "
        f"{args.subdivisions}`, the first {args.steps} time steps (`Stop "
        f"after step`), a checkpoint and a VTU file after every step; "
        f"{args.ranks} MPI rank(s). All numbers are the program's own output "
        f"but the wall time of the whole process and the file sizes.", "",
        "| quantity | value |", "|---|---:|",
        f"| cells, dofs, contact nodes | {cells}, {dofs}, {contact_nodes} |",
        f"| peak memory over the run, sum over the ranks | {peak:.0f} MB |",
        f"| peak memory of the largest rank | {largest:.0f} MB |",
        f"| bytes per dof (the sum over the ranks, libraries included) | "
        f"{peak * 1e6 / dofs:.0f} |",
        f"| wall time of the whole process | {wall:.0f} s |",
        f"| VTU files of the last step written ({os.path.basename(last)}) | "
        f"{megabytes(glob.glob(last + '.*.vtu')):.0f} MB |",
        f"| checkpoint ({', '.join(os.path.basename(c) for c in checkpoint)}) "
        f"| {megabytes(checkpoint):.0f} MB |", "",
        f"**Back end:** {back_end}", "",
        "**Initial cycles** (the first step on coarser meshes first):", ""]
    lines += ["    " + line for line in stdout.splitlines()
              if line.startswith("Initial cycle")]
    lines += ["", "**Steps:**", "", "| step | t | active-set iterations "
              "| contact force |", "|---:|---:|---:|---:|"]
    lines += [f"| {s} | {t} | {i} | {f} |" for s, t, i, f in steps]
    lines += ["", "**Where the time goes** (the program's TimerOutput table "
              "and cost measurement):", ""]
    lines += ["    " + line for line in (timer + "\n" + cost).splitlines()]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--subdivisions", type=int, default=152)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--steps", type=int, default=2)
    parser.add_argument("--workdir", default=tempfile.gettempdir())
    parser.add_argument("--keep", action="store_true")
    parser.add_argument("--resume-ranks", type=int, default=0,
                        help="resume the last checkpoint on this many ranks "
                        "for one more step and compare it with an "
                        "uninterrupted run")
    parser.add_argument("--timeout", type=float, default=6 * 3600)
    parser.add_argument("--output", default=os.path.join(
        REPO_ROOT, "doc", "back_ends", "largest_cube.md"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)

    workdir = tempfile.mkdtemp(prefix="largest_cube_", dir=args.workdir)
    try:
        with open(os.path.join(workdir, "cube.prm"), "w") as f:
            f.write(scene(args.subdivisions, args.steps))
        wall, peak_rank_mb, result = checked_run(
            executable, args.ranks, workdir, args.timeout, "run",
            "output.txt")
        page = report(result.stdout, wall, peak_rank_mb,
                      os.path.join(workdir, "results"), args)
        agree = True
        if args.resume_ranks:
            section, agree = resume_check(executable, workdir, args)
            page += "\n" + "\n".join(section) + "\n"
        with open(args.output, "w") as f:
            f.write(page)
        print(page)
        if not agree:
            sys.exit("the resumed run differs from the uninterrupted one")
    finally:
        for directory in (workdir, workdir + "_reference"):
            if not os.path.isdir(directory):
                continue
            if args.keep:
                print("kept", directory)
            else:
                shutil.rmtree(directory, ignore_errors=True)


def checked_run(executable, ranks, directory, timeout, what, output_name):
    """Runs directory/cube.prm on ranks ranks, stops the script if the run
    fails or times out, and keeps its terminal output in output_name;
    returns timed_run's (wall time, peak memory of a rank, result)."""
    wall, peak_mb, result = timed_run([executable, "cube.prm"], ranks,
                                      directory, timeout)
    if result is None or result.returncode != 0:
        sys.exit(f"the {what} failed or timed out:\n"
                 + ("" if result is None else
                    result.stdout[-3000:] + result.stderr[-3000:]))
    with open(os.path.join(directory, output_name), "w") as f:
        f.write(result.stdout)
    return wall, peak_mb, result


def resume_check(executable, workdir, args):
    """Resumes the run of workdir on --resume-ranks ranks for one more step
    and runs the reference, steps + 1 steps uninterrupted, in
    workdir + "_reference"; returns the page's section and whether the two
    agree."""
    steps = args.steps + 1
    prm = os.path.join(workdir, "cube.prm")
    with open(prm) as f:
        text = f.read()
    with open(prm, "w") as f:
        f.write(set_prm_entries(text, {
            (("Checkpoint",), "Stop after step"): str(steps),
            (("Checkpoint",), "Resume"): "true"}))
    wall, peak_mb, resumed = checked_run(executable, args.resume_ranks,
                                         workdir, args.timeout,
                                         "resumed run", "resume_output.txt")
    if not args.keep:
        # The run's files are no longer needed: room for the reference.
        for name in glob.glob(os.path.join(workdir, "results", "*.vtu")) \
                + glob.glob(os.path.join(workdir, "results", "checkpoint",
                                         "*.bin")):
            os.remove(name)

    reference_dir = workdir + "_reference"
    os.mkdir(reference_dir)
    with open(os.path.join(reference_dir, "cube.prm"), "w") as f:
        f.write(set_prm_entries(scene(args.subdivisions, steps), {
            (("Output",), "Write vtu"): "false"}))
    _, _, reference = checked_run(executable, args.ranks, reference_dir,
                                  args.timeout, "reference run", "output.txt")
    lines, agree = compare_runs(reference_dir, workdir, reference.stdout,
                                resumed.stdout)
    step_line = re.search(r"^Step\s+%d\s.*$" % steps, resumed.stdout, re.M)
    section = [
        f"## Resumed on {args.resume_ranks} rank(s)", "",
        f"The checkpoint of step {args.steps} (written on {args.ranks} "
        f"rank(s)) resumed on {args.resume_ranks} rank(s) for step {steps}: "
        f"{wall:.0f} s for the whole process, peak memory of the largest "
        f"rank {peak_mb:.0f} MB. The reference is an uninterrupted run of "
        f"{steps} steps on {args.ranks} rank(s). "
        + ("**They agree**" if agree else "**They differ**")
        + f" (time series: |difference| <= {RELATIVE:g} |value| + "
        f"{ABSOLUTE:g}, iteration and node counts exactly; final norms: "
        "relative 1e-6).", "",
        "    " + (step_line.group(0) if step_line else "(no step line)"), ""]
    return section + lines, agree


if __name__ == "__main__":
    main()

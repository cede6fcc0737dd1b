#!/usr/bin/python3
"""Every measurement behind doc/performance.md, in one run: each benchmark
script of this directory that writes a file read there, in turn, with the
same executables, each writing its tables and figures to their places under
doc/.

    benchmarks/run_performance_suite.py --build BUILD [--baseline OTHER/viscoplastic_contact]
        [--only tables,full_space,...] [--list]

BUILD is a Release build directory (with `make preconditioner_comparison`
done for the preconditioner part). --baseline is a build of an earlier
version for the scripts that compare with one (the tables). The whole suite
takes about five hours on two cores, most of it the full space scaling up
to 1.2M dofs and the preconditioner comparison; --only runs a part. The
parts run one after another, never side by side: their times are only
comparable on an otherwise quiet machine.
"""

import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# (name, script, arguments, what it writes, minutes on two cores). The
# placeholders {program}, {comparison} and {baseline} are filled in below.
PARTS = [
    ("tables", "run_performance.py", ["--executable", "{program}"],
     "doc/performance/tables.md", 10),
    ("full_space", "run_full_space_scaling.py",
     ["--executable", "{program}", "--hexahedra", "16,24,32,48,64,72",
      "--tetrahedra", "16,24,32,48,69", "--concurrent"],
     "doc/performance/full_space.md", 25),
    ("two_ranks", "run_cube_benchmark.py",
     ["--executable", "{program}", "--subdivisions", "8,16,32,56",
      "--cell-types", "hypercube", "--steps", "4",
      "--output-dir", "{repo}/doc/performance/two_ranks"],
     "doc/performance/two_ranks/cube_benchmark.md", 25),
    ("preconditioners", "run_preconditioner_comparison.py",
     ["--executable", "{comparison}"],
     "doc/performance/preconditioners.md", 45),
    ("step42", "run_step42_comparison.py", ["--executable", "{program}"],
     "doc/performance/step42.md", 6),
    ("step37", "run_step37_comparison.py", ["--executable", "{program}"],
     "doc/performance/step37.md", 3),
    ("start_up", "run_start_up.py", ["--executable", "{program}"],
     "doc/performance/start_up.md", 1),
    ("cold_start", "run_cold_start.py", ["--executable", "{program}"],
     "doc/performance/cold_start.md", 15),
    ("active_set_growth", "run_active_set_growth.py",
     ["--executable", "{program}", "--hexahedra", "16,32,48,64"],
     "doc/performance/active_set_growth.md", 22),
    ("matrix_free", "run_matrix_free.py",
     ["--executable", "{program}", "--subdivisions", "16,32,72",
      "--output-dir", "{repo}/doc/back_ends"],
     "doc/back_ends/matrix_free.md", 15),
    ("method_choice", "run_method_choice.py",
     ["--executable", "{program}", "--scenes", "none",
      "--cube-subdivisions", "24", "--timeout", "60"],
     "doc/back_ends/method_choice.md", 15),
    ("method_choice_shipped", "run_method_choice.py",
     ["--executable", "{program}", "--static-subdivisions", "",
      "--timeout", "120", "--name", "method_choice_shipped"],
     "doc/back_ends/method_choice_shipped.md", 40),
    ("benchmark", "run_benchmark.py",
     ["--executable", "{program}", "--output-dir", "{repo}/doc/benchmark"],
     "doc/benchmark/benchmark.md", 1),
    ("back_ends", "run_back_end_comparison.py", ["--executable", "{program}"],
     "doc/back_ends/back_ends.md", 3),
    ("cube_benchmark", "run_cube_benchmark.py",
     ["--executable", "{program}", "--steps", "2",
      "--subdivisions", "8,16,32,48,72", "--tet-subdivisions", "8,16,32,48"],
     "doc/benchmark_3d/cube_benchmark.md", 9),
    ("largest_cube", "run_largest_cube.py",
     ["--executable", "{program}", "--subdivisions", "152", "--ranks", "2"],
     "doc/back_ends/largest_cube.md", 10),
]


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", help="Release build directory")
    parser.add_argument("--baseline", default=None,
                        help="an earlier build's viscoplastic_contact, for "
                             "the tables' ratios")
    parser.add_argument("--only", default=None,
                        help="comma-separated part names (see --list)")
    parser.add_argument("--list", action="store_true",
                        help="print the parts and stop")
    args = parser.parse_args()
    if args.list:
        for name, script, _, output, minutes in PARTS:
            print(f"{name:16s} {script:36s} -> {output} (~{minutes} min)")
        return
    if not args.build:
        parser.error("--build is required (a Release build directory)")
    names = [p[0] for p in PARTS]
    chosen = args.only.split(",") if args.only else names
    unknown = [c for c in chosen if c not in names]
    if unknown:
        parser.error(f"unknown part(s) {', '.join(unknown)}; accepted: "
                     f"{', '.join(names)}")
    values = {
        "program": os.path.join(args.build, "viscoplastic_contact"),
        "comparison": os.path.join(args.build, "preconditioner_comparison"),
        "repo": os.path.dirname(HERE),
    }
    for name, script, arguments, output, minutes in PARTS:
        if name not in chosen:
            continue
        command = [sys.executable, os.path.join(HERE, script)] + [
            a.format(**values) for a in arguments]
        if name == "tables" and args.baseline:
            command += ["--baseline", args.baseline]
        print(f"== {name}: {' '.join(command)} (about {minutes} min)",
              flush=True)
        start = time.perf_counter()
        result = subprocess.run(command)
        if result.returncode != 0:
            sys.exit(f"error: part {name} failed with exit status "
                     f"{result.returncode}; {output} is left as it was")
        print(f"== {name}: wrote {output} in "
              f"{(time.perf_counter() - start) / 60:.1f} min", flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""What a process pays before it solves: the start-up floor of every run.

Times whole processes, each the median of --repeat runs (one at a time,
with the test suite's Open MPI settings: no helper process for one rank,
shared-memory transports), of

  * /bin/true: starting and ending a process on this machine;
  * MPI_Init and MPI_Finalize alone (a C program linked to MPI only), also
    with Open MPI's default transports (UCX);
  * a program that loads deal.II's library, and with it everything Debian's
    deal.II is linked to (Trilinos, PETSc, SLEPc, p4est, OpenCASCADE, ...),
    and does nothing;
  * the same calling deal.II's Utilities::MPI::MPI_InitFinalize (MPI, PETSc,
    SLEPc, p4est, Zoltan), as every deal.II program does;
  * the program's --help, and the program on the static scene with N = 8
    (parameters/elastic.prm, 1 step, 162 dofs, no output but the time
    series), also with UCX.

The differences give the parts: loading the libraries, MPI, the rest of
deal.II's initialisation, the program's own start-up, a small solve. The
three small programs are built with deal.II's CMake set-up in --work.
Writes doc/performance/start_up.md (--output).

    benchmarks/run_start_up.py [--executable build/viscoplastic_contact]
        [--repeat 15] [--work /tmp/vc_start_up]
"""

import argparse
import datetime
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import (REPO_ROOT, add_executable_argument,  # noqa: E402
                        resolve_executable, set_prm_entries,
                        static_scene_prm)

SOURCES = {
    "load_only.cc": """#include <deal.II/base/utilities.h>
// Loads deal.II's library (a call that is never made, but that the linker
// must resolve) and returns.
int main(int argc, char **argv)
{
  if (argc > 99)
    return dealii::Utilities::string_to_int(argv[1]);
  return 0;
}
""",
    "init_finalize.cc": """#include <deal.II/base/mpi.h>
int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return 0;
}
""",
    "CMakeLists.txt": """cmake_minimum_required(VERSION 3.13.4)
find_package(deal.II 9.4 REQUIRED HINTS ${DEAL_II_DIR})
deal_ii_initialize_cached_variables()
project(start_up CXX)
foreach(name load_only init_finalize)
  add_executable(${name} ${name}.cc)
  deal_ii_setup_target(${name})
endforeach()
""",
    "mpi_only.c": """#include <mpi.h>
int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  MPI_Finalize();
  return 0;
}
"""}

# The test suite's settings (tests/CMakeLists.txt) and Open MPI's defaults.
SUITE_MPI = {"OMPI_MCA_ess_singleton_isolated": "1", "OMPI_MCA_pml": "ob1",
             "OMPI_MCA_btl": "self,vader",
             "OMPI_MCA_btl_vader_single_copy_mechanism": "none"}
DEFAULT_MPI = {"OMPI_MCA_ess_singleton_isolated": "1"}


def build(work):
    """The three small programs, built once in work."""
    for name, text in SOURCES.items():
        with open(os.path.join(work, name), "w") as f:
            f.write(text)
    build_dir = os.path.join(work, "build")
    os.makedirs(build_dir, exist_ok=True)
    subprocess.run(["cmake", "-DCMAKE_BUILD_TYPE=Release", work],
                   cwd=build_dir, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["make", "-j2"], cwd=build_dir, check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["mpicc", "-O2", "mpi_only.c", "-o",
                    os.path.join(build_dir, "mpi_only")], cwd=work,
                   check=True)
    return {name: os.path.join(build_dir, name)
            for name in ["load_only", "init_finalize", "mpi_only"]}


def median_time(command, environment, repeat, cwd):
    """Median, smallest and largest wall time of repeat runs; a run that
    fails stops the script."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    for key in list(env):
        if key.startswith("OMPI_MCA_"):
            del env[key]
    env.update(environment)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(command, cwd=cwd, env=env, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), max(times)


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--work", default=os.path.join(
        tempfile.gettempdir(), "vc_start_up"))
    parser.add_argument("--output", default=os.path.join(
        REPO_ROOT, "doc", "performance", "start_up.md"))
    args = parser.parse_args()
    executable = resolve_executable(args.executable)
    os.makedirs(args.work, exist_ok=True)
    programs = build(args.work)
    scene = os.path.join(args.work, "scene.prm")
    with open(scene, "w") as f:
        # Every run replaces the files of the one before.
        f.write(set_prm_entries(static_scene_prm(8),
                                {(("Output",), "Overwrite"): "true"}))

    cases = [
        ("/bin/true", ["/bin/true"], SUITE_MPI),
        ("MPI_Init and MPI_Finalize (MPI only)", [programs["mpi_only"]],
         SUITE_MPI),
        ("the same, Open MPI's default transports (UCX)",
         [programs["mpi_only"]], DEFAULT_MPI),
        ("deal.II's libraries loaded, nothing run", [programs["load_only"]],
         SUITE_MPI),
        ("deal.II's MPI_InitFinalize", [programs["init_finalize"]],
         SUITE_MPI),
        ("the program: --help", [executable, "--help"], SUITE_MPI),
        ("the program: static scene, N = 8, one step", [executable, scene],
         SUITE_MPI),
        ("the same, Open MPI's default transports (UCX)",
         [executable, scene], DEFAULT_MPI),
    ]
    results = []
    for label, command, environment in cases:
        result = median_time(command, environment, args.repeat, args.work)
        results.append((label, result))
        print(f"{label:50s} {result[0]:.3f} s ({result[1]:.3f} to "
              f"{result[2]:.3f})", flush=True)
    median = [r[1][0] for r in results]
    true, mpi, mpi_ucx, load, init, help_, scene_run, scene_ucx = median
    parts = [
        ("starting and ending a process", true),
        ("loading deal.II's libraries", load - true),
        ("MPI_Init and MPI_Finalize", mpi - true),
        ("deal.II's initialisation beyond MPI (PETSc, SLEPc, p4est, Zoltan)",
         init - load - (mpi - true)),
        ("the program's own start-up (--help)", help_ - init),
        ("reading the scene, mesh, solve, time series (N = 8)",
         scene_run - help_),
        ("UCX instead of shared memory (the scene)", scene_ucx - scene_run),
    ]

    command = "benchmarks/run_start_up.py " + " ".join(
        a if " " not in a else f'"{a}"' for a in sys.argv[1:])
    lines = [
        "# What a process pays before it solves",
        "",
        f"Generated by `benchmarks/run_start_up.py` on "
        f"{datetime.date.today()} ({platform.node()}, {os.cpu_count()} "
        f"cores); command: `{command.strip()}`.",
        "",
        f"Whole processes, one at a time, the median of {args.repeat} runs "
        "each (smallest and largest in brackets), with the test suite's "
        "Open MPI settings (no helper process for one rank, shared-memory "
        "transports) unless the row says otherwise. The small programs are "
        "built by the script against Debian's deal.II with deal.II's CMake "
        "set-up.",
        "",
        "| process | median [s] | range [s] |",
        "| --- | ---: | ---: |"]
    for label, (med, low, high) in results:
        lines.append(f"| {label} | {med:.3f} | {low:.3f} to {high:.3f} |")
    lines += ["", "The parts, as differences of the medians:", "",
              "| part | [s] |", "| --- | ---: |"]
    for label, value in parts:
        lines.append(f"| {label} | {value:.3f} |")
    lines.append("")
    with open(args.output, "w") as f:
        f.write("\n".join(lines))
    print(f"Wrote {args.output}")


if __name__ == "__main__":
    main()

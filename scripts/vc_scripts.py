"""Helpers shared by the project's scripts (benchmarks/run_benchmark.py,
doc/make_figures.py): editing a deal.II parameter file and finding the
program."""

import contextlib
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_EXECUTABLE = os.path.join("build", "viscoplastic_contact")


def set_prm_entries(text, overrides):
    """Return a copy of a deal.II parameter file with some entries replaced.

    ``overrides`` maps (subsection path, entry name) to the new value, where
    the subsection path is a tuple such as ("Output",) (empty tuple for the
    top level). Existing ``set ENTRY = value`` lines are rewritten (their
    trailing comment is dropped since it may no longer be true); entries not
    present are inserted just before the ``end`` of their subsection (the
    subsection is appended if it does not exist). Everything else is kept.
    """
    remaining = dict(overrides)
    out = []
    stack = []
    set_re = re.compile(r"^(\s*)set\s+(.+?)\s*=(.*)$")
    for line in text.splitlines():
        stripped = line.split("#", 1)[0].strip()
        m_sub = re.match(r"^subsection\s+(.+)$", stripped)
        if m_sub:
            stack.append(m_sub.group(1).strip())
            out.append(line)
            continue
        if stripped == "end" and stack:
            path = tuple(stack)
            indent = "  " * len(stack)
            for (sub, name), value in list(remaining.items()):
                if sub == path:
                    out.append(f"{indent}set {name} = {value}")
                    del remaining[(sub, name)]
            stack.pop()
            out.append(line)
            continue
        m_set = set_re.match(line.split("#", 1)[0])
        if m_set:
            key = (tuple(stack), m_set.group(2).strip())
            if key in remaining:
                out.append(f"{m_set.group(1)}set {key[1]} = {remaining.pop(key)}")
                continue
        out.append(line)
    # Entries of subsections that do not exist at all (or top level ones).
    for (sub, name), value in remaining.items():
        for depth, s in enumerate(sub):
            out.append("  " * depth + f"subsection {s}")
        out.append("  " * len(sub) + f"set {name} = {value}")
        for depth in reversed(range(len(sub))):
            out.append("  " * depth + "end")
    return "\n".join(out) + "\n"


def resolve_executable(arg):
    """Path of the program: --executable, else $VC_EXECUTABLE, else the default
    build/viscoplastic_contact relative to the repo root."""
    if arg:
        return os.path.abspath(arg)
    env = os.environ.get("VC_EXECUTABLE")
    if env:
        return os.path.abspath(env)
    return os.path.join(REPO_ROOT, DEFAULT_EXECUTABLE)


def add_executable_argument(parser):
    """The --executable option every script has (see resolve_executable)."""
    parser.add_argument("--executable", default=None,
                        help="program to run (default: $VC_EXECUTABLE or "
                             "build/viscoplastic_contact in the repo root)")


def time_per_step(stdout):
    """The program's own time loop (without output) over its steps, from a
    run's standard output (its Cost measurement block: the run must set
    Measure cost ratios = true)."""
    found = re.search(r"time loop \(without output\): ([0-9.e+-]+) s", stdout)
    if found is None:
        raise RuntimeError("The run printed no time loop: set Measure cost "
                           "ratios = true in subsection Output.")
    loop = float(found.group(1))
    steps = [line for line in stdout.splitlines() if line.startswith("Step ")]
    return loop / int(steps[-1].split()[1])


@contextlib.contextmanager
def run_in_temporary_directory(executable, prm_text):
    """Runs the program on a parameter file in a fresh temporary directory
    (relative output directories land there) and yields (directory, standard
    output, wall time in seconds) while the directory still exists; a failed
    run raises RuntimeError with the end of its output."""
    with tempfile.TemporaryDirectory() as workdir:
        prm = os.path.join(workdir, "run.prm")
        with open(prm, "w") as f:
            f.write(prm_text)
        start = time.perf_counter()
        result = subprocess.run([executable, prm], cwd=workdir,
                                capture_output=True, text=True)
        wall = time.perf_counter() - start
        if result.returncode != 0:
            raise RuntimeError(result.stdout[-2000:] + result.stderr[-2000:])
        yield workdir, result.stdout, wall


# Runs the command and prints the largest resident set of its descendants
# (kB): the largest rank's peak under mpirun.
PEAK_WRAPPER = ("import resource, subprocess, sys; "
                "code = subprocess.run(sys.argv[1:]).returncode; "
                "print('peak-rss-kB', resource.getrusage("
                "resource.RUSAGE_CHILDREN).ru_maxrss, file=sys.stderr); "
                "sys.exit(code)")


def timed_run(command, ranks, workdir, timeout):
    """Runs command (under mpirun for ranks > 1, as root too) in workdir and
    returns (wall time [s], peak resident memory of the largest process [MB],
    subprocess.CompletedProcess). The run has a session of its own: past the
    timeout all its processes (mpirun and the ranks) are stopped, which would
    otherwise go on and slow the next runs down, and the result is
    (inf, nan, None)."""
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks)] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, "-c", PEAK_WRAPPER] + command,
                               cwd=workdir, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env=env,
                               start_new_session=True)
    try:
        stdout, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        # SIGTERM first: mpirun passes it on to the ranks, which it starts in
        # a session of their own.
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
        return float("inf"), float("nan"), None
    wall = time.perf_counter() - start
    peak = re.search(r"peak-rss-kB (\d+)", stderr)
    return (wall, int(peak.group(1)) / 1024 if peak else float("nan"),
            subprocess.CompletedProcess(command, process.returncode, stdout,
                                        stderr))


def static_scene_prm(subdivisions, cell_type="simplex"):
    """The static scene of the benchmarks: parameters/elastic.prm (elastic
    body, nonmonotone layer, rigid limit) with N Subdivisions of the given
    Cell type and one step of k = 1/64 from rest, so that the whole contact
    zone forms in one cold step; no files but the time series, output
    folder "out"."""
    with open(os.path.join(REPO_ROOT, "parameters", "elastic.prm")) as f:
        elastic = f.read()
    return set_prm_entries(elastic, {
        (("Geometry",), "Subdivisions"): str(subdivisions),
        (("Geometry",), "Cell type"): cell_type,
        (("Time",), "End time"): "0.015625",
        (("Output",), "Write vtu"): "false",
        (("Output",), "Profile times"): "",
        (("Output",), "Print timing summary"): "false",
        (("Output",), "Verbose"): "false",
        (("Output",), "Output directory"): "out"})

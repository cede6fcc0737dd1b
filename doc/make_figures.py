#!/usr/bin/env python3
"""Regenerate the documentation figures and the contact-count table.

The figures reproduce those of the reference benchmark (doc/model.md,
section 1) from the program's own output:

* fig3_plasticity.png  with / without plasticity, g = 0.01, at t = 1;
* fig4_gap.png         g = 0.006 (= u1, monotone), 0.008, 0.01, at t = 1;
* fig5_evolution.png   the default case at t = 1/64, 1/2, 1.

Each figure has one column per (case, time): on top the deformed mesh
(displacement magnified, coloured by the von Mises stress, undeformed outline
dashed, the foundation layer drawn below the body), below the contact
pressure along Gamma_3 (compliance part, rigid-foundation part, total) with
the status of every contact node marked.

doc/contact_counts.md lists, for every (case, time) shown, how many contact
nodes are at the rigid limit (status 2), in normal compliance (status 1) and
out of contact (status 0), and the total contact force (sum of the nodal
forces), all computed from the contact_profile_NNNN.csv files, and checks them
against the same step of time_series.csv (a warning is printed on mismatch).

All cases use h = 1/32, k = 1/64 on the default mesh (Simplex pattern = /,
each square split by its diagonal from (x_i,y_j) to (x_i+1,y_j+1)) and are
derived from parameters/default.prm by overriding single entries (the same
differences as parameters/elastic.prm, monotone.prm and gap_0.008.prm). Runs
go to output/doc/<case>. The VTU output of a step N is read from its parallel
record solution_NNNN.pvtu (found through solution.pvd) and the piece files it
lists (solution_NNNN.0.vtu on one MPI rank).

Usage (from anywhere):

    doc/make_figures.py [--executable build/viscoplastic_contact]
                        [--skip-runs] [--magnification 10]

The executable may also be given by the environment variable VC_EXECUTABLE;
relative default paths are taken from the repo root. Needs matplotlib, numpy
and meshio (Debian: python3-matplotlib python3-numpy python3-meshio).
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
import xml.etree.ElementTree as ET
from fractions import Fraction

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import add_executable_argument, resolve_executable, set_prm_entries  # noqa: E402

try:
    import matplotlib
except ImportError:
    # "python3" on PATH may be another interpreter than the Debian one that
    # has python3-matplotlib etc.; retry with /usr/bin/python3 if it exists.
    if os.path.exists("/usr/bin/python3") and \
            os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("error: matplotlib, numpy and meshio are needed "
             "(Debian: apt-get install python3-matplotlib python3-numpy python3-meshio)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

DOC_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_ROOT = os.path.dirname(DOC_DIR)
BASE_PRM = os.path.join(REPO_ROOT, "parameters", "default.prm")
OUTPUT_ROOT = os.path.join(REPO_ROOT, "output", "doc")
FIGURE_DIR = os.path.join(DOC_DIR, "figures")
COUNTS_MD = os.path.join(DOC_DIR, "contact_counts.md")

SUBDIVISIONS = 32            # h = 1/32
TIME_STEP = 1.0 / 64         # k = 1/64
PROFILE_TIMES = (1.0 / 64, 0.5, 1.0)

# name -> (title, overrides of default.prm as {(subsection path, entry): value})
CASES = {
    "default": ("with plasticity, g = 0.01", {}),
    "elastic": ("without plasticity, g = 0.01",
                {(("Material",), "Plasticity"): "false"}),
    "monotone": ("g = 0.006 = u1 (monotone)",
                 {(("Contact",), "Layer thickness"): "0.006"}),
    "gap_0.008": ("g = 0.008",
                  {(("Contact",), "Layer thickness"): "0.008"}),
}

# figure file -> (suptitle, [(case, time), ...])
FIGURES = {
    "fig3_plasticity.png": ("Influence of plasticity (t = 1)",
                            [("default", 1.0), ("elastic", 1.0)]),
    "fig4_gap.png": ("Influence of the layer thickness g (with plasticity, t = 1)",
                     [("monotone", 1.0), ("gap_0.008", 1.0), ("default", 1.0)]),
    "fig5_evolution.png": ("Evolution of the default case (with plasticity, g = 0.01)",
                           [("default", 1.0 / 64), ("default", 0.5), ("default", 1.0)]),
}

STATUS_STYLE = {  # status -> (label, marker, face colour)
    0: ("no contact (0)", "o", "white"),
    1: ("normal compliance (1)", "o", "tab:blue"),
    2: ("rigid limit u_nu = g (2)", "s", "tab:red"),
}


# --------------------------------------------------------------------------
# Parameter files and runs
# --------------------------------------------------------------------------
def case_prm(case, output_directory):
    """Parameter file text for one case (h = 1/32, k = 1/64, VTU every step)."""
    with open(BASE_PRM) as f:
        text = f.read()
    overrides = {
        (("Geometry",), "Subdivisions"): str(SUBDIVISIONS),
        (("Time",), "Time step"): repr(TIME_STEP),
        (("Output",), "Output directory"): output_directory,
        (("Output",), "Write vtu"): "true",
        # Steps 1, 32 and 64 are needed, so every step is written.
        (("Output",), "Output interval"): "1",
        (("Output",), "Profile times"): ", ".join(repr(t) for t in PROFILE_TIMES),
        (("Output",), "Verbose"): "false",
        # The default case (the reference benchmark as a user runs it, VTU
        # output included) also reports its timings for doc/default_run_timing.md.
        (("Output",), "Print timing summary"): "true" if case == "default" else "false",
        (("Output",), "Measure cost ratios"): "true" if case == "default" else "false",
    }
    overrides.update(CASES[case][1])
    return set_prm_entries(text, overrides)


def run_case(executable, case, tmpdir):
    """Run the program for one case into output/doc/<case> (wiped first)."""
    out_dir = os.path.join(OUTPUT_ROOT, case)
    if os.path.isdir(out_dir):
        shutil.rmtree(out_dir)
    prm = os.path.join(tmpdir, f"{case}.prm")
    with open(prm, "w") as f:
        f.write(case_prm(case, out_dir))
    print(f"running {case} ...", flush=True)
    proc = subprocess.run([executable, prm], cwd=REPO_ROOT,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "run.log"), "w") as f:
        f.write(proc.stdout)
    if proc.returncode != 0:
        sys.exit(f"error: {case} failed with exit code {proc.returncode}; "
                 f"see {os.path.join(out_dir, 'run.log')}\n{proc.stdout[-2000:]}")


# --------------------------------------------------------------------------
# Reading the output
# --------------------------------------------------------------------------
def read_csv_columns(path):
    """CSV file -> dict column name -> numpy float array."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path} has no data rows")
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def find_profile(case_dir, time):
    """(step, columns) of the contact profile whose time is closest to ``time``."""
    best = None
    for path in glob.glob(os.path.join(case_dir, "contact_profile_*.csv")):
        step = int(re.search(r"contact_profile_(\d+)\.csv$", path).group(1))
        cols = read_csv_columns(path)
        # Sorted along Gamma_3 (the program sorts on one rank only).
        order = np.argsort(cols["x"], kind="stable")
        cols = {k: v[order] for k, v in cols.items()}
        dt = abs(cols["time"][0] - time)
        if best is None or dt < best[0]:
            best = (dt, step, cols)
    if best is None:
        sys.exit(f"error: no contact_profile_*.csv in {case_dir} (run without --skip-runs?)")
    if best[0] > 0.5 * TIME_STEP:
        print(f"warning: {case_dir}: no profile near t = {time} "
              f"(closest is off by {best[0]:g})")
    return best[1], best[2]


def find_pvtu(case_dir, time):
    """(time, path) of the .pvtu record in solution.pvd closest to ``time``."""
    pvd = os.path.join(case_dir, "solution.pvd")
    entries = [(float(ds.get("timestep")), os.path.join(case_dir, ds.get("file")))
               for ds in ET.parse(pvd).getroot().iter("DataSet")]
    t, path = min(entries, key=lambda e: abs(e[0] - time))
    if abs(t - time) > 0.5 * TIME_STEP:
        print(f"warning: {pvd}: no VTU output near t = {time} (closest t = {t:g})")
    return t, path


def pvtu_for_step(case_dir, step):
    """Path of the parallel record solution_NNNN.pvtu of one step."""
    return os.path.join(case_dir, f"solution_{step:04d}.pvtu")


def read_pvtu(path):
    """Read a parallel VTU record: the pieces it lists (solution_NNNN.0.vtu on
    one MPI rank; .0, .1, ... on several), merged into one meshio.Mesh.

    The program writes every cell with its own copies of the vertices, so the
    pieces are simply concatenated (point indices of later pieces shifted).
    """
    directory = os.path.dirname(path)
    pieces = [os.path.join(directory, piece.get("Source"))
              for piece in ET.parse(path).getroot().iter("Piece")]
    if not pieces:
        sys.exit(f"error: {path} lists no piece files")
    meshes = [meshio.read(piece) for piece in pieces]
    if len(meshes) == 1:
        return meshes[0]
    offsets = np.cumsum([0] + [len(m.points) for m in meshes[:-1]])
    cell_types = []
    for m in meshes:
        for block in m.cells:
            if block.type not in cell_types:
                cell_types.append(block.type)
    cells = []
    for cell_type in cell_types:
        blocks = [block.data + offset for m, offset in zip(meshes, offsets)
                  for block in m.cells if block.type == cell_type]
        cells.append((cell_type, np.concatenate(blocks)))
    point_data = {name: np.concatenate([m.point_data[name] for m in meshes])
                  for name in meshes[0].point_data}
    return meshio.Mesh(np.concatenate([m.points for m in meshes]), cells,
                       point_data=point_data)


def read_time_series(case_dir):
    """time_series.csv -> dict step -> row (dict of strings)."""
    with open(os.path.join(case_dir, "time_series.csv"), newline="") as f:
        return {int(r["step"]): r for r in csv.DictReader(f)}


def layer_thickness(case_dir):
    """g as actually used by the run (from its parameters.prm)."""
    with open(os.path.join(case_dir, "parameters.prm")) as f:
        m = re.search(r"set\s+Layer thickness\s*=\s*([^\s#]+)", f.read())
    return float(m.group(1))


def simplex_pattern(case_dir):
    """Simplex pattern as actually used by the run (from its parameters.prm)."""
    with open(os.path.join(case_dir, "parameters.prm")) as f:
        m = re.search(r"set\s+Simplex pattern\s*=\s*([^#\n]*)", f.read())
    return m.group(1).strip() if m else "?"


class Snapshot:
    """Everything plotted/tabulated for one (case, time)."""

    def __init__(self, case, time):
        self.case = case
        self.case_dir = os.path.join(OUTPUT_ROOT, case)
        self.title = CASES[case][0]
        self.g = layer_thickness(self.case_dir)
        self.step, self.profile = find_profile(self.case_dir, time)
        self.time = float(self.profile["time"][0])
        vtu_time, vtu_path = find_pvtu(self.case_dir, time)
        if abs(vtu_time - self.time) > 1e-12:
            print(f"warning: {self.case}: VTU time {vtu_time} != profile time {self.time}")
        if os.path.abspath(vtu_path) != os.path.abspath(
                pvtu_for_step(self.case_dir, self.step)):
            print(f"warning: {self.case}: solution.pvd lists {vtu_path} for "
                  f"t = {vtu_time:g}, expected solution_{self.step:04d}.pvtu")
        self.mesh = read_pvtu(vtu_path)
        self.series_row = read_time_series(self.case_dir).get(self.step)
        status = self.profile["status"].astype(int)
        self.counts = {s: int(np.sum(status == s)) for s in (0, 1, 2)}
        self.total_force = float(np.sum(self.profile["nodal_force"]))

    # ---------------------------------------------------------------- checks
    def check(self):
        """Compare with time_series.csv and the VTU; return list of problems."""
        problems = []
        row = self.series_row
        if row is None:
            problems.append(f"step {self.step} missing in time_series.csv")
        else:
            for s, col in ((2, "unilateral_nodes"), (1, "compliance_nodes"),
                           (0, "no_contact_nodes")):
                if int(row[col]) != self.counts[s]:
                    problems.append(f"{col} = {row[col]} in time_series.csv but "
                                    f"{self.counts[s]} nodes of status {s} in the profile")
            ts_force = float(row["total_contact_force"])
            if not math.isclose(ts_force, self.total_force, rel_tol=1e-6, abs_tol=1e-9):
                problems.append(f"total_contact_force = {ts_force} in time_series.csv "
                                f"but sum(nodal_force) = {self.total_force}")
        # status versus u_nu and g
        u, st = self.profile["u_nu"], self.profile["status"].astype(int)
        tol = 1e-9 + 1e-7 * self.g
        bad2 = np.sum((st == 2) & (np.abs(u - self.g) > tol))
        bad_pen = np.sum(u > self.g + tol)
        bad0 = np.sum((st == 0) & (u > tol))
        if bad2:
            problems.append(f"{bad2} nodes of status 2 with u_nu != g")
        if bad_pen:
            problems.append(f"{bad_pen} nodes with u_nu > g (penetration of the rigid body)")
        if bad0:
            problems.append(f"{bad0} nodes of status 0 with u_nu > 0")
        total = self.profile["compliance_pressure"] + self.profile["foundation_pressure"]
        if not np.allclose(total, self.profile["contact_pressure"], rtol=1e-8, atol=1e-10):
            problems.append("contact_pressure != compliance_pressure + foundation_pressure")
        if np.any(self.profile["foundation_pressure"] < -1e-10):
            problems.append("negative foundation pressure")
        # VTU displacement on Gamma_3 versus the profile's u_nu (normal (0,-1))
        pts, disp = self.mesh.points, self.mesh.point_data["displacement"]
        for x, un in zip(self.profile["x"], u):
            sel = (np.abs(pts[:, 1]) < 1e-9) & (np.abs(pts[:, 0] - x) < 1e-9)
            if not np.any(sel):
                problems.append(f"no VTU point at ({x:g}, 0)")
                break
            if np.max(np.abs(-disp[sel, 1] - un)) > 1e-6 * max(1.0, abs(un)) + 1e-7:
                problems.append(f"VTU displacement at x = {x:g} differs from "
                                f"profile u_nu = {un:g}")
                break
        return problems


# --------------------------------------------------------------------------
# Plotting
# --------------------------------------------------------------------------
def time_label(t):
    """'1/64' style label for simple fractions, else '%g'."""
    fr = Fraction(t).limit_denominator(1024)
    if abs(float(fr) - t) < 1e-12 and fr.denominator != 1:
        return f"{fr.numerator}/{fr.denominator}"
    return f"{t:g}"


def cell_values(mesh, name):
    """Per-triangle value of a piecewise constant field written as point data."""
    tri = mesh.cells_dict["triangle"]
    return mesh.point_data[name][tri].mean(axis=1)


def plot_deformed(ax, snap, magnification, norm, cmap):
    """Deformed mesh coloured by von Mises stress, undeformed outline dashed."""
    mesh = snap.mesh
    tri = mesh.cells_dict["triangle"]
    xy = mesh.points[:, :2] + magnification * mesh.point_data["displacement"][:, :2]
    triang = mtri.Triangulation(xy[:, 0], xy[:, 1], tri)
    pc = ax.tripcolor(triang, facecolors=cell_values(mesh, "von_mises_stress"),
                      cmap=cmap, norm=norm, edgecolors="none", zorder=2)
    ax.triplot(triang, color="k", lw=0.15, alpha=0.35, zorder=3)
    x0, y0 = mesh.points[:, 0].min(), mesh.points[:, 1].min()
    x1, y1 = mesh.points[:, 0].max(), mesh.points[:, 1].max()
    ax.plot([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], "k--", lw=1.0,
            label="undeformed", zorder=4)
    # The foundation: layer of thickness g (magnified) over the rigid body.
    yg = y0 - magnification * snap.g
    ax.fill_between([x0 - 0.1, x1 + 0.3], yg, y0, color="tan", alpha=0.45, lw=0,
                    label=f"layer, g = {snap.g:g} (x{magnification:g})", zorder=0)
    ax.fill_between([x0 - 0.1, x1 + 0.3], yg - 0.06, yg, color="0.55", lw=0,
                    label="rigid foundation", zorder=0)
    ax.plot([x0 - 0.1, x1 + 0.3], [yg, yg], color="0.3", lw=1.0, zorder=1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{snap.title}, t = {time_label(snap.time)}\n"
                 f"deformed mesh, displacement x{magnification:g}", fontsize=10)
    return pc


def plot_pressure(ax, snap):
    """Contact pressure along Gamma_3 with node status markers."""
    p = snap.profile
    x = p["x"]
    ax.plot(x, p["compliance_pressure"], "-", color="tab:blue", lw=1.2,
            label="normal compliance p(u_nu)")
    ax.plot(x, p["foundation_pressure"], "-", color="tab:orange", lw=1.2,
            label="rigid foundation")
    ax.plot(x, p["contact_pressure"], "-", color="k", lw=1.8, label="total")
    st = p["status"].astype(int)
    for s, (label, marker, face) in STATUS_STYLE.items():
        sel = st == s
        ax.plot(x[sel], p["contact_pressure"][sel], linestyle="none", marker=marker,
                markersize=4.5, markerfacecolor=face, markeredgecolor="k",
                markeredgewidth=0.6)
    ax.set_xlabel("x on $\\Gamma_3$ (y = 0) [m]")
    ax.set_ylabel("contact pressure $-\\sigma_\\nu$ [N/m$^2$]")
    c = snap.counts
    ax.set_title(f"{snap.title}, t = {time_label(snap.time)}\n"
                 f"nodes: {c[2]} rigid limit, {c[1]} compliance, {c[0]} no contact",
                 fontsize=10)
    ax.grid(True, alpha=0.3)


def make_figure(path, suptitle, snaps, magnification):
    """One figure: deformed meshes on top, contact pressures below."""
    ncols = len(snaps)
    fig, axes = plt.subplots(2, ncols, figsize=(4.6 * ncols + 1.0, 8.6),
                             squeeze=False, layout="constrained",
                             gridspec_kw={"height_ratios": [1.25, 1.0]})
    # Common colour scale, clipped at the 99th percentile of the cell values
    # so that the stress singularities at the corners do not wash it out.
    vm_all = np.concatenate([cell_values(s.mesh, "von_mises_stress") for s in snaps])
    vmax = float(np.percentile(vm_all, 99.0))
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=vmax)
    cmap = plt.get_cmap("viridis")
    pc = None
    for j, snap in enumerate(snaps):
        pc = plot_deformed(axes[0, j], snap, magnification, norm, cmap)
        plot_pressure(axes[1, j], snap)
    # Common axis ranges so that the columns compare directly.
    xmax = max(ax.dataLim.x1 for ax in axes[0]) + 0.03
    ymin = min(ax.dataLim.y0 for ax in axes[0])
    for ax in axes[0]:
        ax.set_xlim(-0.05, xmax)
        ax.set_ylim(ymin, 1.05)
    pmax = max(float(np.max(s.profile["contact_pressure"])) for s in snaps)
    for ax in axes[1]:
        ax.set_xlim(0.0, 1.0)
        ax.set_ylim(-0.05 * pmax, 1.08 * pmax)
    fig.colorbar(pc, ax=list(axes[0]), extend="max", shrink=0.85,
                 label="von Mises stress [N/m$^2$]\n(scale clipped at the 99th "
                       f"percentile; max {float(np.max(vm_all)):.3g})")
    axes[0, 0].legend(loc="upper right", fontsize=7, framealpha=0.85)
    handles = [Line2D([], [], color="tab:blue", lw=1.2, label="normal compliance p(u_nu)"),
               Line2D([], [], color="tab:orange", lw=1.2, label="rigid foundation"),
               Line2D([], [], color="k", lw=1.8, label="total")]
    handles += [Line2D([], [], linestyle="none", marker=m, markerfacecolor=f,
                       markeredgecolor="k", label=lab)
                for lab, m, f in STATUS_STYLE.values()]
    axes[1, -1].legend(handles=handles, loc="upper left", fontsize=7, framealpha=0.85)
    patterns = ", ".join(sorted({simplex_pattern(s.case_dir) for s in snaps}))
    fig.suptitle(f"{suptitle} - h = 1/{SUBDIVISIONS} (triangles, pattern {patterns}), "
                 f"k = 1/{round(1 / TIME_STEP)}; "
                 f"displacements magnified {magnification:g}x", fontsize=12)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"wrote {os.path.relpath(path, REPO_ROOT)}")


# --------------------------------------------------------------------------
# Contact counts table
# --------------------------------------------------------------------------
def write_counts(path, snaps):
    """Markdown table of the contact node counts per (case, time)."""
    lines = [
        "# Contact node counts of the documentation figures",
        "",
        f"Generated by doc/make_figures.py from the program's contact profiles "
        f"(h = 1/{SUBDIVISIONS}, Simplex pattern = "
        f"{simplex_pattern(snaps[0].case_dir)}, k = 1/{round(1 / TIME_STEP)}, "
        f"{len(snaps[0].profile['x'])} contact nodes on Gamma_3). The total contact "
        "force is the sum of the nodal forces. *time_series.csv* says whether "
        "these numbers equal the same step of the run's time_series.csv.",
        "",
        "| case | g | t | step | rigid limit (2) | normal compliance (1) | "
        "no contact (0) | total contact force [N/m] | time_series.csv |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for s in snaps:
        ok = "agrees" if not s.problems_with_series else "**differs**"
        lines.append(f"| {s.title} | {s.g:g} | {time_label(s.time)} | {s.step} | "
                     f"{s.counts[2]} | {s.counts[1]} | {s.counts[0]} | "
                     f"{s.total_force:.6g} | {ok} |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {os.path.relpath(path, REPO_ROOT)}")


# --------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------
def write_default_timing(path):
    """Copy the run summary, TimerOutput table and cost block of the default
    case's run.log into a markdown page."""
    log = os.path.join(OUTPUT_ROOT, "default", "run.log")
    with open(log) as f:
        text = f.read()
    start = text.find("Run summary")
    with open(path, "w") as f:
        f.write("# Timings of the default run\n\n"
                "Generated by doc/make_figures.py: the reference benchmark "
                "(parameters/default.prm: h = 1/32, k = 1/64, T = 1, VTU output "
                "every step), Release build, one run on the 2-core machine; "
                "verbatim end of the program's terminal output.\n\n```\n")
        f.write(text[start:].strip() + "\n```\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_executable_argument(parser)
    parser.add_argument("--skip-runs", action="store_true",
                        help="reuse the existing output in output/doc/<case>")
    parser.add_argument("--magnification", type=float, default=10.0,
                        help="displacement magnification of the deformed meshes "
                             "(default %(default)s)")
    args = parser.parse_args(argv)

    if not args.skip_runs:
        executable = resolve_executable(args.executable)
        if not os.access(executable, os.X_OK):
            sys.exit(f"error: executable not found or not executable: {executable}")
        with tempfile.TemporaryDirectory(prefix="vc_doc_") as tmp:
            for case in CASES:
                run_case(executable, case, tmp)

    os.makedirs(FIGURE_DIR, exist_ok=True)
    snapshots = {}
    for _, panels in FIGURES.values():
        for case, t in panels:
            if (case, t) not in snapshots:
                snapshots[(case, t)] = Snapshot(case, t)

    n_problems = 0
    for snap in snapshots.values():
        problems = snap.check()
        snap.problems_with_series = [p for p in problems if "time_series" in p]
        for p in problems:
            print(f"WARNING: {snap.case}, t = {time_label(snap.time)}: {p}")
        n_problems += len(problems)

    for name, (suptitle, panels) in FIGURES.items():
        make_figure(os.path.join(FIGURE_DIR, name), suptitle,
                    [snapshots[p] for p in panels], args.magnification)

    order = [("default", 1.0 / 64), ("default", 0.5), ("default", 1.0),
             ("elastic", 1.0), ("monotone", 1.0), ("gap_0.008", 1.0)]
    order += [k for k in snapshots if k not in order]
    write_counts(COUNTS_MD, [snapshots[k] for k in order if k in snapshots])
    write_default_timing(os.path.join(DOC_DIR, "default_run_timing.md"))
    if n_problems:
        print(f"{n_problems} consistency warning(s), see above")
    return 0


if __name__ == "__main__":
    sys.exit(main())

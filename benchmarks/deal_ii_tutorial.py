"""deal.II 9.4 tutorial programs built from their sources, as the peers of
the benchmark scripts (run_step42_comparison.py, run_step37_comparison.py).

The sources come from /usr/share/doc/libdeal.ii-doc/examples/step-N if
Debian's libdeal.ii-doc is installed; otherwise the package is downloaded
with `apt-get download` (about 260 MB, the tutorial sources and the
manual) and only step-N is unpacked. The program is built in Release
against the installed library, after an optional edit of its source (a
function from the text of step-N.cc to the text to build).
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "scripts"))
from vc_scripts import REPO_ROOT, add_executable_argument  # noqa: E402

INSTALLED_EXAMPLES = "/usr/share/doc/libdeal.ii-doc/examples"


def tutorial_sources(name, work):
    """The directory with the sources of the tutorial program name
    ("step-42"), installed or unpacked into work/src-name."""
    installed = os.path.join(INSTALLED_EXAMPLES, name)
    if os.path.isfile(os.path.join(installed, name + ".cc")):
        return installed
    source = os.path.join(work, "src-" + name)
    if os.path.isfile(os.path.join(source, name + ".cc")):
        return source
    download = os.path.join(work, "download")
    os.makedirs(download, exist_ok=True)
    print(f"Downloading Debian's libdeal.ii-doc for the {name} sources ...",
          flush=True)
    subprocess.run(["apt-get", "download", "libdeal.ii-doc"], cwd=download,
                   check=True)
    package = glob.glob(os.path.join(download, "libdeal.ii-doc_*.deb"))[0]
    member = f"./usr/share/doc/libdeal.ii-doc/examples/{name}/"
    tar = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", package],
                           stdout=subprocess.PIPE)
    subprocess.run(["tar", "-x", "-C", download, member], stdin=tar.stdout,
                   check=True)
    tar.wait()
    shutil.copytree(os.path.join(download, member), source)
    shutil.rmtree(download)
    return source


def build_tutorial(name, work, edit=None):
    """Configures and builds the tutorial program name in Release under
    work/build-name, its source edited by edit if given; returns the
    executable. A build that exists is taken as it is."""
    build = os.path.join(work, "build-" + name)
    executable = os.path.join(build, name)
    if os.path.isfile(executable):
        return executable
    source = tutorial_sources(name, work)
    if edit is not None:
        edited = os.path.join(work, "edited-" + name)
        shutil.rmtree(edited, ignore_errors=True)
        shutil.copytree(source, edited)
        path = os.path.join(edited, name + ".cc")
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write(edit(text))
        source = edited
    os.makedirs(build, exist_ok=True)
    subprocess.run(["cmake", "-DCMAKE_BUILD_TYPE=Release", source],
                   cwd=build, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["make", "release"], cwd=build, check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["make", name], cwd=build, check=True,
                   stdout=subprocess.DEVNULL)
    return executable


def comparison_arguments(description, name, refinements, refinements_help,
                         page):
    """The command line of a comparison with the tutorial program name:
    --executable, --refinements (default refinements), --work-dir (where
    it is built, default build-name in the repository) and --output
    (default doc/performance/page)."""
    parser = argparse.ArgumentParser(
        description=description,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_executable_argument(parser)
    parser.add_argument("--refinements", default=refinements,
                        help=refinements_help)
    parser.add_argument("--work-dir",
                        default=os.path.join(REPO_ROOT, "build-" + name),
                        help=f"where {name} is downloaded and built")
    parser.add_argument("--output", default=os.path.join(
        REPO_ROOT, "doc", "performance", page))
    return parser.parse_args()


def write_page(path, lines):
    """Writes the lines of a comparison's page to path."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines))
    print(f"wrote {path}")

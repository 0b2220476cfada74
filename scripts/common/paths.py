"""Where things are: the tree the scripts belong to and the disco binary.

ROOT is the folder holding scripts/ and configs/: the source tree, or PREFIX/share/disco in an
installed layout (`cmake --install`: the scripts in PREFIX/share/disco/scripts, the binary in
PREFIX/bin/disco).
"""
import os
import shutil
import sys

SCRIPTS = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
ROOT = os.path.dirname(SCRIPTS)


def disco_candidates(root=ROOT):
    """The places find_disco() looks, in order: the build tree (scripts/build), the installed
    layout (ROOT = PREFIX/share/disco, so ROOT/../../bin/disco), then `disco` on PATH."""
    places = [os.path.join(root, "build", "mpi", "disco"),
              os.path.normpath(os.path.join(root, "..", "..", "bin", "disco"))]
    on_path = shutil.which("disco")
    if on_path:
        places.append(on_path)
    return places


def find_disco(explicit=None, root=ROOT):
    """The disco binary to run: `explicit` (a script's --disco) when given, else the first
    executable of disco_candidates(). Exits with a message naming every place tried when
    there is none."""
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            sys.exit(f"--disco {explicit}: not an executable file")
        return explicit
    places = disco_candidates(root)
    for p in places:
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    sys.exit("no disco binary: none of " + ", ".join(places[:2]) + " exists and there is "
             "none on PATH; build it (scripts/build) or give --disco PATH")


def scene_file(name, root=ROOT):
    """A scene given as a file path or by name: NAME.yaml in configs/scenarios,
    configs/scenarios/paper or configs/stress. Exits naming the folders when not found."""
    if os.path.isfile(name):
        return name
    folders = [os.path.join(root, "configs", d) for d in ("scenarios", "scenarios/paper", "stress")]
    for d in folders:
        path = os.path.join(d, name + ".yaml")
        if os.path.isfile(path):
            return path
    sys.exit(f"scene '{name}': no such file, and no {name}.yaml in " + ", ".join(folders))


def scene_name(path):
    """The file name of a scene without folder and .yaml."""
    return os.path.splitext(os.path.basename(path))[0]


def shown(path, root=ROOT):
    """`path` relative to ROOT when inside it (for command lines in results), else as given."""
    full = os.path.abspath(path)
    if full == root or full.startswith(root + os.sep):
        return os.path.relpath(full, root)
    return path

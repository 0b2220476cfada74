#!/usr/bin/env python3
"""The install (run by CTest as install.tree, install.package and install.solve; see
tests/CMakeLists.txt).

  install_tests.py tree    BUILD PREFIX SOURCE CMAKE [instrumented]
  install_tests.py package PREFIX SOURCE CMAKE [CMAKE_ARG ...]
  install_tests.py solve   PREFIX SOURCE

tree: `CMAKE --install BUILD --prefix PREFIX` into an emptied PREFIX; the layout (bin/disco,
share/disco/configs/disco.yaml, the scenes, the scripts, the headers, the libraries, the CMake
package); and no installed file names the source tree or the build tree (the only absolute
paths under SOURCE allowed are PREFIX's own). `instrumented` (a DISCO_SANITIZE build): the
executables and libraries are not searched, since ASan's and UBSan's instrumentation records
each source file's absolute path whatever -ffile-prefix-map says; the text files still are.
package: copies the outside project tests/install to a scratch directory (outside the
source tree), configures it with CMAKE against
PREFIX alone (find_package(disco), disco::core), builds it and runs it: it states MacMPEC's
gauvin, solves it with the installed settings and compares with a reference it computes
itself. Its build names nothing of the source tree.
solve: the installed disco, run in a scratch directory outside the source tree, solves
PREFIX/share/disco/configs/scenarios/one_robot_axis.yaml (25 steps) with its default settings
file, which lies under PREFIX (solution.json's provenance, --help); a copy of the binary
without share/disco beside it refuses to run, naming the path it looked at and --settings.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

from script_checks import check, finish

MODE = sys.argv[1]
ENV = dict(os.environ, OMP_NUM_THREADS="1")
SETTINGS = os.path.join("share", "disco", "configs", "disco.yaml")


def run(args, **kw):
    return subprocess.run(args, env=ENV, capture_output=True, text=True, **kw)


def check_that(cond, what, detail):
    """check(), with `detail` (a command's output) shown only when the check fails."""
    check(cond, what if cond else f"{what}:\n{detail}")


def foreign_paths(root, source, prefix, skip_binaries=False):
    """Files under `root` whose bytes name `source` other than as the start of `prefix`;
    skip_binaries: ELF files and static libraries are not searched."""
    needle, allowed = source.encode(), prefix.encode()
    bad = []
    for d, _, files in os.walk(root):
        for name in files:
            path = os.path.join(d, name)
            if os.path.islink(path):
                continue
            data = open(path, "rb").read()
            if skip_binaries and data.startswith((b"\x7fELF", b"!<arch>\n")):
                continue
            start = data.find(needle)
            while start >= 0:
                if not data.startswith(allowed, start):
                    bad.append(os.path.relpath(path, root))
                    break
                start = data.find(needle, start + 1)
    return bad


if MODE == "tree":
    build, prefix, source = map(os.path.realpath, sys.argv[2:5])
    shutil.rmtree(prefix, ignore_errors=True)
    r = run([sys.argv[5], "--install", build, "--prefix", prefix])
    check_that(r.returncode == 0, f"cmake --install {build} --prefix {prefix}", r.stderr.strip()[-1500:])
    for rel in ["bin/disco", SETTINGS, "share/disco/configs/scenarios/one_robot_axis.yaml",
                "share/disco/configs/scenarios/paper/A3.yaml", "share/disco/configs/benchmarks/smoke.yaml",
                "share/disco/configs/stress/overflow.yaml", "share/disco/scripts/bench_starts",
                "share/disco/scripts/report", "share/disco/scripts/viz/snapshots.py",
                "include/disco/core/nlp/mpcc.h", "include/disco/core/elastic/elastic_solver.h",
                "include/disco/search/objective_reduction.h"]:
        check(os.path.isfile(os.path.join(prefix, rel)), f"installed: {rel}")
    check(os.access(os.path.join(prefix, "share/disco/scripts/bench_starts"), os.X_OK),
          "the scripts stay executable")
    check(not os.path.exists(os.path.join(prefix, "share/disco/scripts/build")),
          "not installed: scripts/build (it builds the source tree)")
    # lib/ or lib/MULTIARCH/ (GNUInstallDirs).
    cmake_dir = next((d for d, _, fs in os.walk(os.path.join(prefix, "lib")) if "discoConfig.cmake" in fs), None)
    check(cmake_dir is not None and os.path.basename(cmake_dir) == "disco" and
          all(os.path.isfile(os.path.join(cmake_dir, f)) for f in
              ["discoConfigVersion.cmake", "discoTargets.cmake"]),
          f"the CMake package: {cmake_dir}")
    libs = [f for d, _, fs in os.walk(os.path.join(prefix, "lib")) for f in fs if f.endswith(".a")]
    check(sorted(libs) == ["libdisco_core.a", "libdisco_search.a"], f"the static libraries ({libs})")
    # The BLAS pin of the top CMakeLists.txt (a DT_RPATH) survives the install.
    if os.path.isfile("/usr/lib/x86_64-linux-gnu/blas/libblas.so.3"):
        r = run(["readelf", "-d", os.path.join(prefix, "bin", "disco")])
        rpath = [line for line in r.stdout.splitlines() if "(RPATH)" in line]
        check(len(rpath) == 1 and "/usr/lib/x86_64-linux-gnu/blas:" in rpath[0],
              f"the installed disco keeps the BLAS RPATH ({rpath})")
    instrumented = sys.argv[6:] == ["instrumented"]
    bad = foreign_paths(prefix, source, prefix, skip_binaries=instrumented)
    check(not bad, f"no installed {'text ' if instrumented else ''}file names the source tree {source} ({bad})")
    if not build.startswith(source + os.sep):
        bad = foreign_paths(prefix, build, prefix, skip_binaries=instrumented)
        check(not bad, f"no installed file names the build tree {build} ({bad})")
    finish("install.tree")

if MODE == "package":
    prefix, source = map(os.path.realpath, sys.argv[2:4])
    cmake, cmake_args = sys.argv[4], sys.argv[5:]
    with tempfile.TemporaryDirectory(prefix="disco_outside_") as work:
        src, bld = os.path.join(work, "src"), os.path.join(work, "build")
        shutil.copytree(os.path.join(source, "tests", "install"), src)
        r = run([cmake, "-S", src, "-B", bld, f"-DCMAKE_PREFIX_PATH={prefix}",
                 "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON", *cmake_args])
        check_that(r.returncode == 0, "configure the outside project", (r.stdout + r.stderr).strip()[-1500:])
        cache = os.path.join(bld, "CMakeCache.txt")
        disco_dir = next((line.split("=", 1)[1] for line in
                          (open(cache).read().splitlines() if os.path.isfile(cache) else [])
                          if line.startswith("disco_DIR:")), "")
        check(disco_dir.startswith(prefix + os.sep), f"find_package(disco) found the install ({disco_dir})")
        r = run([cmake, "--build", bld])
        check_that(r.returncode == 0, "build the outside project", (r.stdout + r.stderr).strip()[-1500:])
        # Linked with an instrumented disco (CMAKE_ARGs with -fsanitize), its executable holds
        # the paths the instrumentation recorded (see `instrumented` above).
        bad = foreign_paths(bld, source, prefix, skip_binaries=any("-fsanitize" in a for a in cmake_args))
        check(not bad, f"its build (compile and link lines) names nothing of the source tree ({bad})")
        exe = os.path.join(bld, "gauvin")
        r = run([exe]) if os.path.isfile(exe) else None
        out = (r.stdout + r.stderr).strip() if r else "not built"
        check(r is not None and r.returncode == 0 and out.endswith("\nmatch"),
              f"the outside program solves gauvin to the reference optimum:\n{out}")
    finish("install.package")

if MODE == "solve":
    prefix, source = map(os.path.realpath, sys.argv[2:4])
    disco = os.path.join(prefix, "bin", "disco")
    settings = os.path.join(prefix, SETTINGS)
    scene = os.path.join(prefix, "share", "disco", "configs", "scenarios", "one_robot_axis.yaml")
    with tempfile.TemporaryDirectory(prefix="disco_install_") as cwd:
        check(not os.path.realpath(cwd).startswith(source + os.sep), f"working directory {cwd}")
        r = run([disco, "solve", "--help"], cwd=cwd)
        check(r.returncode == 0 and f"--settings TEXT={settings}" in r.stdout,
              f"solve --help shows the default settings file under the prefix ({settings})")
        r = run([disco, "solve", scene, "--set", "scene.steps=25", "--out", "out"], cwd=cwd)
        check_that(r.returncode == 0, "disco solve one_robot_axis from the install",
                   f"exit {r.returncode}: {r.stderr.strip()[-1500:]}")
        path = os.path.join(cwd, "out", "solution.json")
        doc = json.load(open(path)) if os.path.isfile(path) else {}
        p = doc.get("provenance", {})
        check(doc.get("status") == "solved", f"solution.json: status {doc.get('status')}")
        check(p.get("settings_file") == settings and p.get("settings_file", "").startswith(prefix + os.sep),
              f"provenance.settings_file lies under the prefix ({p.get('settings_file')})")
        check(p.get("scene_file") == scene, f"provenance.scene_file ({p.get('scene_file')})")

        # Without share/disco beside its prefix, the binary names where it looked.
        bare = os.path.join(cwd, "bare")
        os.makedirs(os.path.join(bare, "bin"))
        shutil.copy2(disco, os.path.join(bare, "bin", "disco"))
        looked = os.path.join(bare, SETTINGS)
        r = run([os.path.join(bare, "bin", "disco"), "solve", scene, "--model-only"], cwd=cwd)
        check(r.returncode == 2 and f"{looked}: no settings file here" in r.stderr and
              "--settings FILE" in r.stderr,
              f"a binary without its settings names the path and --settings ({r.stderr.strip()!r})")
        r = run([os.path.join(bare, "bin", "disco"), "solve", scene, "--model-only",
                 "--settings", settings], cwd=cwd)
        check_that(r.returncode == 0, "... and runs with --settings", r.stderr.strip()[-1500:])
    finish("install.solve")

sys.exit(f"unknown mode {MODE}")

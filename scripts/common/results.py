"""The results file of a benchmark script: scripts/results/NAME.md (NAME the script's file
name), written by running the script and never edited by hand.

The file holds one section per configuration label, each the latest run of that
configuration:

    # Results: scripts/NAME
    (what the file is)
    <!-- section: LABEL -->
    ## LABEL
    - Command: `scripts/NAME ...` (exactly as run)
    - Date: YYYY-MM-DD HH:MM UTC (the start)
    - disco: `VERSION (git COMMIT)` (what `disco --version` prints), the binary's path
    - Machine: nproc, CPU model, memory; load average at the start and at the end
    - Wall time: of the whole run
    (the script's tables and the conclusions it computes)
    <!-- end section: LABEL -->

Labels. A run's label is --label when given. Else it is the script's configuration (e.g. its
--set KEY=VALUE list: "reduction.minimize=branch") or "default". A run that measures less than
the script's full run (one of the script's `partial` options changed from its default, e.g.
--scenes A3) and has no --label is labelled "CONFIG (partial: --scenes A3)", so that it never
replaces the full run's section. A run replaces only the section of its own label; a full run
(no partial option changed, or an explicit --label) also removes the partial sections of its
configuration, which it supersedes.

Options (add_options): --results FILE (default: scripts/results/NAME.md in a source tree;
in an installed copy, which has no CMakeLists.txt at ROOT, NAME.md in the run's output
folder), --no-results (write none), --label TEXT.
"""
import datetime
import os
import re
import shlex
import sys
import time

from common.paths import ROOT, SCRIPTS, shown
from common.solve import disco_version

BEGIN = re.compile(r"^<!-- section: (.*) -->$")
END = "<!-- end section: {} -->"


def add_options(ap):
    g = ap.add_argument_group("results file (scripts/results/NAME.md; see common/results.py)")
    g.add_argument("--results", metavar="FILE",
                   help="the results file to update (default scripts/results/NAME.md)")
    g.add_argument("--no-results", action="store_true", help="write no results file")
    g.add_argument("--label", help="the section to replace (default: the configuration, e.g. "
                                   "the --set list, or 'default'; partial runs get their own)")


def option_text(dest, value, argv):
    """The option as typed in argv ("--name value", "--name" for a flag), or from its value."""
    flag = "--" + dest.replace("_", "-")
    for i, word in enumerate(argv):
        if word.startswith(flag + "="):
            return f"{flag} {word[len(flag) + 1:]}"
        if word == flag:
            return flag if value is True or i + 1 == len(argv) else f"{flag} {argv[i + 1]}"
    if value is True:
        return flag
    if isinstance(value, (list, tuple)):
        value = ",".join(str(v) for v in value)
    return f"{flag} {value}"


def partial_options(ap, args, dests, argv=None):
    """The options among `dests` whose values differ from the defaults, as "--name value"."""
    defaults = vars(ap.parse_args([]))
    argv = sys.argv[1:] if argv is None else argv
    return [option_text(d, getattr(args, d), argv) for d in dests if getattr(args, d) != defaults[d]]


def machine():
    cpus = len(os.sched_getaffinity(0))
    model = mem = None
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f
                          if line.startswith("model name")), None)
        with open("/proc/meminfo") as f:
            kb = next(int(line.split()[1]) for line in f if line.startswith("MemTotal:"))
            mem = f"{kb / 2**20:.1f} GiB memory"
    except (OSError, StopIteration, ValueError):
        pass
    return ", ".join(x for x in (f"{cpus} CPUs (nproc)", model, mem) if x)


def split_sections(text):
    """[(label, text of the section with its markers)] of a results file."""
    sections, label, lines = [], None, []
    for line in text.splitlines():
        m = BEGIN.match(line)
        if m and label is None:
            label, lines = m.group(1), [line]
        elif label is not None:
            lines.append(line)
            if line == END.format(label):
                sections.append((label, "\n".join(lines)))
                label = None
    return sections


def merge(old_text, label, section, supersedes):
    """The sections of old_text with `label`'s replaced by `section` (in place, or appended),
    and those labelled "<supersedes> (partial: ..." dropped when supersedes is given."""
    out, placed = [], False
    for lab, text in split_sections(old_text):
        if lab == label:
            out.append(section)
            placed = True
        elif not (supersedes is not None and lab.startswith(supersedes + " (partial: ")):
            out.append(text)
    if not placed:
        out.append(section)
    return out


class Results:
    """Start it right after parsing the arguments (its clock and load average start then);
    write(body, binaries) at the end."""

    def __init__(self, ap, args, config=(), partial=(), out_dir=None):
        """config: the strings that name the configuration (e.g. the --set list); partial: the
        argparse dests whose change makes a run partial; out_dir: where an installed copy
        writes its results file."""
        self.name = os.path.basename(sys.argv[0])
        self.title = " ".join((ap.description or "").strip().split("\n\n")[0].split())
        self.enabled = not args.no_results
        self.t0, self.start = time.monotonic(), datetime.datetime.now(datetime.timezone.utc)
        self.load0 = os.getloadavg()[0]
        self.command = shlex.join([shown(os.path.realpath(sys.argv[0]))] + sys.argv[1:])
        configuration = ", ".join(config) or "default"
        cut = partial_options(ap, args, partial)
        if args.label:
            if "-->" in args.label or "\n" in args.label:
                sys.exit("--label: must not hold '-->' or a line break")
            self.label, self.supersedes = args.label, args.label
        elif cut:
            self.label, self.supersedes = f"{configuration} (partial: {' '.join(cut)})", None
        else:
            self.label, self.supersedes = configuration, configuration
        if args.results:
            self.path = args.results
        elif os.path.isfile(os.path.join(ROOT, "CMakeLists.txt")):
            self.path = os.path.join(SCRIPTS, "results", self.name + ".md")
        else:
            self.path = os.path.join(out_dir or ".", self.name + ".md")

    def header(self, binaries):
        lines = [f"- Command: `{self.command}`",
                 f"- Date: {self.start:%Y-%m-%d %H:%M} UTC"]
        for role, path in binaries:
            lines.append(f"- {role}: `{disco_version(path)}` ({shown(path)})")
        lines += [f"- Machine: {machine()}; load average (1 min) {self.load0:.2f} at the start, "
                  f"{os.getloadavg()[0]:.2f} at the end",
                  f"- Wall time: {time.monotonic() - self.t0:.0f} s"]
        return lines

    def write(self, body, binaries=()):
        """Replaces this run's section of the results file with the header and `body` (the
        script's Markdown); binaries: [(role, path)] of the disco binaries run, each shown
        with its --version. Returns the path written, or None with --no-results."""
        if not self.enabled:
            return None
        section = "\n".join([f"<!-- section: {self.label} -->", f"## {self.label}", ""]
                            + self.header(binaries) + ["", body.strip("\n"), "",
                                                        END.format(self.label)])
        old = ""
        if os.path.isfile(self.path):
            with open(self.path) as f:
                old = f.read()
        sections = merge(old, self.label, section, self.supersedes)
        preamble = [f"# Results: scripts/{self.name}", ""]
        if self.title:
            preamble += [self.title, ""]
        preamble += [f"Generated by `scripts/{self.name}`: do not edit by hand. Each section is the "
                     "latest run of one configuration, named by its label; a run replaces only "
                     f"its own section (`scripts/{self.name} --help`, options --label, --results, "
                     "--no-results).", ""]
        os.makedirs(os.path.dirname(os.path.abspath(self.path)), exist_ok=True)
        tmp = self.path + ".tmp"
        with open(tmp, "w") as f:
            f.write("\n".join(preamble) + "\n" + "\n\n".join(sections) + "\n")
        os.replace(tmp, self.path)
        print(f"{self.name}: results in {self.path}, section '{self.label}'", file=sys.stderr)
        return self.path

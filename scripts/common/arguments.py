"""Command-line argument types shared by the scripts (argparse `type=`), and the options every
benchmark shares."""
import argparse


def _integers(ok, message):
    """A parser of integers v with ok(v); argparse's error message(text) for anything else."""
    def parse(text):
        try:
            v = int(text)
        except ValueError:
            v = None
        if v is None or not ok(v):
            raise argparse.ArgumentTypeError(message(text))
        return v
    return parse


def int_at_least(low):
    """A parser of integers >= low."""
    return _integers(lambda v: v >= low, lambda t: f"'{t}' is not an integer >= {low}")


def int_in_range(low, high, what):
    """A parser of integers in [low, high]; the error says '<text>' is not <what>, low..high."""
    return _integers(lambda v: low <= v <= high, lambda t: f"'{t}' is not {what}, {low}..{high}")


def comma_list(item=str):
    """A parser of a comma-separated list (empty items dropped), each item parsed by `item`."""
    def parse(text):
        try:
            values = [item(v) for v in text.split(",") if v]
        except ValueError:
            values = []
        if not values:
            raise argparse.ArgumentTypeError(f"'{text}' is not a comma-separated list")
        return values
    return parse


def add_disco_option(ap, flag="--disco", help_extra=""):
    """--disco PATH: the binary to run (default: common.paths.find_disco())."""
    ap.add_argument(flag, metavar="PATH",
                    help="the disco binary (default: build/mpi/disco, else PREFIX/bin/disco of "
                         "an installed copy, else disco on PATH)" + help_extra)

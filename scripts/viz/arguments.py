"""Command-line argument types shared by the scripts (argparse `type=`)."""
import argparse


def int_at_least(low):
    """A parser of integers >= low, with argparse's error for anything else."""
    def parse(text):
        try:
            v = int(text)
        except ValueError:
            v = low - 1
        if v < low:
            raise argparse.ArgumentTypeError(f"'{text}' is not an integer >= {low}")
        return v
    return parse

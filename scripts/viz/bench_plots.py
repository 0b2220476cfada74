"""What the benchmark scripts' figures share (bench_budget, bench_error, bench_formulations,
bench_scaling): a figure on the Agg backend, log-log axes, a fitted power law, saving."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402


def figure(rows, cols, size):
    """(fig, axes) of a rows x cols grid, `size` (width, height) in inches."""
    return plt.subplots(rows, cols, figsize=size)


def log_log(ax, xlabel, ylabel):
    """Log scales on both axes (minor ticks unlabelled), labels, grid and legend."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def power_law(ax, xs, fit, colour, label):
    """The line y = exp(c) x^p of fit = (p, c) (common.tables.loglog_fit) over [min xs, max xs]."""
    if not fit or not xs:
        return
    lo, hi = min(xs), max(xs)
    gx = [lo * (hi / lo) ** (k / 50) for k in range(51)]
    ax.plot(gx, [math.exp(fit[1]) * x ** fit[0] for x in gx], "-", color=colour, label=label)


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)

"""Numbers into tables: fmt, Markdown tables, CSV files, the log-log fit the benchmarks
state their growth rates with, and the sign test they judge a split of starts with."""
import csv
import math
import os


def fmt(v, spec, missing=""):
    """format(v, spec), or `missing` for None."""
    return missing if v is None else format(v, spec)


def markdown_table(head, rows):
    """The lines of a Markdown table: `head` a list of column titles, `rows` lists of cells."""
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines


def write_csv(path, rows):
    """`rows` (dicts with the same keys) as a CSV file with a header line."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else [])
        w.writeheader()
        w.writerows(rows)


def write_text(path, text):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def loglog_fit(xs, ys):
    """Least-squares line through (log x, log y) for the pairs with x, y > 0: (p, c) with
    y = exp(c) x^p, or None with fewer than two distinct x."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys)
           if x is not None and y is not None and x > 0 and y > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if not sxx:
        return None
    p = sum((a - mx) * (b - my) for a, b in pts) / sxx
    return p, my - p * mx


def sign_test(worse, better):
    """Two-sided exact sign test: the probability that `worse` + `better` fair coin flips split
    at least as unevenly as worse : better (1 when they are even or there are none). Starts that
    end elsewhere only through roundoff (a chaotic path) split like such coins."""
    n, k = worse + better, max(worse, better)
    if n == 0 or 2 * k == n:
        return 1.0
    tail = sum(math.comb(n, i) for i in range(k, n + 1)) / 2 ** n
    return min(1.0, 2 * tail)

#!/usr/bin/python3
"""The settings tables of configs/README.md against configs/disco.yaml (CTest docs.settings):
every key the settings file holds has a row, every row names a key the file holds, and a row's
value column holds the file's value (as a number, a word, or a boolean).

  docs_tests.py CONFIGS_DIR

The tables are the sections "### `SECTION:`..." of "## The settings file". A row's first cell
names one key or several (`a`, `b`, or `stall.after`, `.window`: a name that starts with a dot
keeps the previous name's prefix); a name whose first part is not a section of the file is
relative to the heading's section. The value cell lists the values in the same order, comma
separated (one value for several keys: all the same).
"""
import os
import re
import sys

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish  # noqa: E402


def leaves(node, prefix=""):
    """Every scalar of the settings file by its dotted key."""
    out = {}
    for key, value in node.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(leaves(value, name + "."))
        else:
            out[name] = value
    return out


def table_rows(readme, sections):
    """(full keys, value cell, line number) of every row of the settings tables."""
    rows = []
    lines = readme.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("## The settings file"))
    heading_sections = []
    for number, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("## "):
            break
        if line.startswith("### "):
            heading_sections = re.findall(r"`(\w+):`", line)
            continue
        if not line.startswith("| `") or not heading_sections:
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        keys, last = [], ""
        for name in re.findall(r"`([^`]+)`", cells[0]):
            if name.startswith("."):
                name = last.rsplit(".", 1)[0] + name
            last = name
            full = name if name.split(".")[0] in sections else f"{heading_sections[0]}.{name}"
            keys.append(full)
        rows.append((keys, cells[1], number))
    return rows


def same_value(cell_value, value):
    """Whether a table's value (text) is the settings file's value."""
    text = cell_value.strip().strip("`").strip('"')
    text = re.sub(r"\s*\(.*\)$", "", text)  # "0 (off)", "2 (AMF)"
    if isinstance(value, bool):
        return text.lower() == ("true" if value else "false")
    try:  # numbers, also those YAML 1.1 reads as text ("1.0e6": no sign in the exponent)
        return float(text) == float(value)
    except (TypeError, ValueError):
        return text == str(value)


def main():
    configs = sys.argv[1]
    settings = yaml.safe_load(open(os.path.join(configs, "disco.yaml")))
    readme = open(os.path.join(configs, "README.md")).read()
    keys = leaves(settings)
    sections = set(settings)
    rows = table_rows(readme, sections)
    check(len(rows) > 20, f"configs/README.md has the settings tables ({len(rows)} rows)")
    documented = {}
    for row_keys, value_cell, number in rows:
        values = [v.strip() for v in value_cell.split(",")]
        for k, key in enumerate(row_keys):
            documented[key] = number
            check(key in keys, f"configs/README.md:{number}: `{key}` is a key of disco.yaml")
            if key not in keys:
                continue
            value = values[k] if len(values) == len(row_keys) else values[0]
            check(same_value(value, keys[key]),
                  f"configs/README.md:{number}: `{key}` is {value!r} in the table, "
                  f"{keys[key]!r} in disco.yaml")
    for key in sorted(keys):
        check(key in documented, f"disco.yaml's `{key}` has a row in configs/README.md")
    finish("docs_tests")


if __name__ == "__main__":
    main()

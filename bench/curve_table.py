"""How the bench scripts read a curve table as `rupture run` writes it (docs/formats.md): '#' comment lines
and blank lines skipped, a byte-order mark allowed, a header of NAME[unit] columns, then rows of
numbers; every failure one line naming the file, the place and the fix. Standard library only."""
import csv
import sys
from typing import NamedTuple


class Table(NamedTuple):
    comments: list  # the '#' lines, as written
    names: list  # the header's column names, units included ("strain[%]")
    rows: list  # the rows as lists of floats


def read_table(path, what="a curves.csv of rupture run"):
    try:
        f = open(path, newline="", encoding="utf-8-sig")
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name {what}")
    with f:
        lines = f.read().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    table = list(csv.reader(line for line in lines if line.strip() and not line.startswith("#")))
    if not table:
        sys.exit(f"{path}: no header line; name {what}")
    names, rows = table[0], []
    for number, row in enumerate(table[1:], start=2):
        if len(row) != len(names):
            sys.exit(f"{path}: data row {number - 1} has {len(row)} fields where the header has {len(names)}; "
                     f"name {what}")
        try:
            rows.append([float(v) for v in row])
        except ValueError:
            sys.exit(f"{path}: data row {number - 1} holds a field that is not a number; name {what}")
    return Table(comments, names, rows)


def column_index(table, path, name):
    """The index of the column called `name` (its unit aside), or a one-line exit naming the columns."""
    bare = [n.split("[")[0].strip() for n in table.names]
    if name not in bare:
        sys.exit(f"{path}: no column '{name}' (the header has {', '.join(bare)}); name another column or file")
    return bare.index(name)


def read_columns(path, names, what="a curves.csv of rupture run"):
    """The columns called `names` (e.g. "strain", "force_top"), as rows of floats."""
    table = read_table(path, what)
    indices = [column_index(table, path, name) for name in names]
    return [[row[i] for i in indices] for row in table.rows]

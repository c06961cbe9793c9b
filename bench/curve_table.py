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
    """Every field must be a number, as in a run's curves.csv (a scan's results.csv, with text columns
    and empty fields, is not such a table)."""
    try:
        f = open(path, newline="", encoding="utf-8-sig")
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name {what}")
    with f:
        lines = f.read().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    numbered = [(number, row) for number, line in enumerate(lines, start=1)
                if line.strip() and not line.startswith("#") for row in csv.reader([line])]
    if not numbered:
        sys.exit(f"{path}: no header line; name {what}")
    names, rows = numbered[0][1], []
    for number, row in numbered[1:]:
        if len(row) != len(names):
            sys.exit(f"{path}: line {number} has {len(row)} fields where the header has {len(names)}; "
                     f"name {what}")
        try:
            rows.append([float(v) for v in row])
        except ValueError:
            column, value = next((n, v) for n, v in zip(names, row) if not is_number(v))
            sys.exit(f"{path}: line {number}, column '{column}': '{value}' is not a number; name {what}")
    return Table(comments, names, rows)


def is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


def column_index(table, path, name, fix="name another column or file"):
    """The index of the column called `name` (its unit aside), or a one-line exit naming the columns
    and `fix`."""
    bare = [n.split("[")[0].strip() for n in table.names]
    if name not in bare:
        sys.exit(f"{path}: no column '{name}' (the header has {', '.join(bare)}); {fix}")
    return bare.index(name)


def read_columns(path, names, what="a curves.csv of rupture run", fix="name another column or file"):
    """The columns called `names` (e.g. "strain", "force_top"), as rows of floats."""
    table = read_table(path, what)
    indices = [column_index(table, path, name, fix) for name in names]
    return [[row[i] for i in indices] for row in table.rows]

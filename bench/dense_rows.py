"""What the dense-run bench scripts share beyond reading the table (bench/curve_table.py): the means of a
run's rows over a sliding window, each window summed on its own, and the force's top among them.
Standard library only."""
import sys


def window_means(rows, width):
    """Per window of `width` consecutive rows (first rows[0:width], then one row on), each column's mean."""
    return [[sum(r[k] for r in rows[i:i + width]) / width for k in range(len(rows[0]))]
            for i in range(len(rows) - width + 1)]


def force_top(means, low=0.3, high=0.5):
    """The index of the window whose mean top force (column 1) is largest where its mean strain
    (column 0) lies in (low, high) %, or None: a DEM tissue's force peak, away from the ramp's start
    and the fragments (0.3-0.5 % holds the default study's; other runs name their own range)."""
    inside = [i for i, m in enumerate(means) if low < m[0] < high]
    return max(inside, key=lambda i: means[i][1]) if inside else None


def found_force_top(means, low, high, path):
    """force_top, or a one-line exit naming the file and the fix where no window lies in the range."""
    top = force_top(means, low, high)
    if top is None:
        sys.exit(f"{path}: no rows between {low} and {high} % strain; name a curves.csv of a run pulled past "
                 "its peak or give its --top-range")
    return top


def take_top_range(args):
    """--top-range LOW,HIGH taken from args (default 0.3,0.5 %, the default study's)."""
    return parse_range(take_option(args, "--top-range", "0.3,0.5"))


def parse_range(text, option="--top-range"):
    """'LOW,HIGH' (strain, %) as two floats with LOW < HIGH, or a one-line exit saying what to give."""
    try:
        low, high = (float(v) for v in text.split(","))
    except ValueError:
        sys.exit(f"{option} {text}: give two strains in %, LOW,HIGH (e.g. 0.3,0.5)")
    if not low < high:
        sys.exit(f"{option} {text}: LOW must lie below HIGH")
    return low, high


def take_option(args, name, default):
    """Removes `name VALUE` from the list args and returns VALUE, or default where it is not there."""
    if name not in args:
        return default
    at = args.index(name)
    if at + 1 == len(args):
        sys.exit(f"{name} needs a value")
    value = args[at + 1]
    del args[at:at + 2]
    return value


def parse_rows(text, option):
    """A count of rows (at least 2), or a one-line exit."""
    if not text.isdigit() or int(text) < 2:
        sys.exit(f"{option} {text}: give a whole number of rows, at least 2")
    return int(text)


def no_other_options(args, known):
    """A one-line exit where args still hold an option (--name) that the script does not take."""
    stray = [a for a in args if a.startswith("--")]
    if stray:
        sys.exit(f"{stray[0]}: not an option here; the options are {', '.join(known)}")

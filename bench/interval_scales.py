#!/usr/bin/env python3
"""Learns the per-level scales of δ_x's intervals (or x_c's, x_p's) and checks them (docs/analysis.md,
"Calibration").

Usage: interval_scales.py LEARN.csv [LEARN.csv ...] [--quantity delta_x|x_c|x_p] [--use KIND=S68,S95 ...]
                          [--skip-shape NAME ...] [--kind-column COLUMN] [--quiet-below SHARE]
                          [--white-by-level] [--white-from SHARE] [--level-from-both]
                          [--collapse-closeness EDGE] [--pool-groups-below N] [--pool-checks]
                          [--only COLUMN=VALUE] [--check CHECK.csv ...]

The files are the per-curve output of bench/analysis_calibration. For every accepted curve and each
level L (68 %, 95 %) the score is how far the interval's half-width on the side of the truth must be
stretched about the estimate to reach the truth. The scale of level L is the split-conformal
quantile of the learning curves' scores, the ceil((n + 1) L)-th smallest of n, rounded up to four
digits, taken separately for each kind of noise the analysis tells apart (the `noise` column: white,
random walk), as src/analysis/analysis.hpp ships and applies them (the check scores what ships). The
check files are then scored with those scales and never used to choose them, each file on its own, or
with `--pool-checks` all of them as one set (a held-out set whose groups were run into several files).
`--use "random walk=1,0.6119"` scores with given factors for one kind instead of the learned ones (what
src/analysis/analysis.hpp applies where a learned factor failed its check).
`--skip-shape "uniform [0.3,0.8]"` leaves that shape's curves out of learning and checking alike (a
case outside the calibration's domain, documented on its own). As in the analysis, the 95 % interval
is never inside the 68 % one: a curve counts as covered at
95 % when either scaled interval reaches the truth.
`--kind-column noise_read` takes each curve's kind from that column instead of `noise` (from held-out
24 on the files write both: `noise` is the kind whose factors the analysis applies, `noise_read` the
whole record's reading). `--quiet-below 5e-4` scores as a random walk every accepted curve whose
white noise in the bootstrap window is below that share of both peaks (`force_white_share`,
`energy_white_share`): the analysis's quiet reading (quiet_white_noise_share), applied to files
written before it.
`--white-by-level` learns the white kind's scales per white group ("white 1 %": anchored at a share
of 0.01) and applies them to each curve through its measured white noise in E_e
(`energy_white_share`): interpolated linearly in the log of that share between the anchors, held at
the end anchors beyond them. `--white-from 0.0017` gives factor 1 below that share instead, as
src/analysis/analysis.hpp's precursor_white_scales does for x_p (below its checked range); a curve
without a measured share (no E_max) gets factor 1 either way.
`--use "white@0.002=0.6213,0.8308"` gives one such anchor (several make the model).
`--level-from-both` takes as each curve's level the larger of its white noise in F and in E_e
(`force_white_share`, `energy_white_share`), as src/analysis/analysis.hpp's delay_noise_level does for
δ_x (either curve's noise can set its spread).
`--collapse-closeness 0.1` learns and scores only the curves cut by a sharp collapse (a
`collapse_onset`), each kind split by how close the collapse comes to the force peak, the estimated
onset over x_c minus 1: "near" below EDGE, "far" from it on (src/analysis/analysis.hpp's
collapse_delta_scales and the strain ones; docs/analysis.md, "Intervals of a curve cut by a collapse,
by how close it comes").
`--pool-groups-below 20` scores, in the rule's check of each kind, that kind's groups of fewer than 20
accepted curves together as one group (a group of 3 fails at 95 % with a single miss, a chance of 14 %
at exactly nominal coverage); without it every group counts alone, as in the checks up to held-out 36.
`--only force_walk_read_as_zero=1` learns and scores only the curves whose column has that value, in
the learning files and the check files alike (e.g. the curves whose F walk was taken from E_e's where
its fit read none; that column is written from held-out 39 on); given more than once, every one holds
(`--only collapse_onset=` keeps the curves without a collapse found).
`--quantity x_c` (or x_p) scores that strain's intervals instead, ± sd (68 %) and ± 1.96 sd (95 %)
about the estimate, from the x_c and x_c_sd columns: the scale multiplies the half-width as for δ_x
(src/analysis/analysis.hpp, critical_strain_scales and precursor_strain_scales).
Standard library only, so it runs wherever the bench does.
"""
import csv
import math
import sys
from collections import OrderedDict

LEVELS = (("68", 0.6826894921370859), ("95", 0.95))


QUANTITY = "delta_x"  # set by --quantity
KIND_COLUMN = "noise"  # set by --kind-column
QUIET_BELOW = None  # set by --quiet-below
WHITE_BY_LEVEL = False  # set by --white-by-level
WHITE_FROM = None  # set by --white-from
LEVEL_FROM_BOTH = False  # set by --level-from-both
COLLAPSE_EDGE = None  # set by --collapse-closeness
POOL_GROUPS_BELOW = 0  # set by --pool-groups-below
ONLY = []  # (column, value) pairs, set by --only
HALF_WIDTH_IN_SD = {"68": 1.0, "95": 1.96}


def score(row, level):
    if QUANTITY != "delta_x":
        gap = abs(float(row[QUANTITY]) - float(row[QUANTITY + "_true"]))
        reach = HALF_WIDTH_IN_SD[level] * float(row[QUANTITY + "_sd"])
        if gap == 0.0:
            return 0.0
        return gap / reach if reach > 0.0 else math.inf
    truth, estimate = float(row["delta_x_true"]), float(row["delta_x"])
    low, high = float(row[f"ci{level}_low"]), float(row[f"ci{level}_high"])
    reach = high - estimate if truth >= estimate else estimate - low
    gap = abs(truth - estimate)
    if gap == 0.0:
        return 0.0
    return gap / reach if reach > 0.0 else math.inf


COLUMNS = ("group", "noise", "accepted", "delta_x_true", "delta_x", "ci68_low", "ci68_high", "ci95_low",
           "ci95_high")


def read(paths, skipped=()):
    rows = []
    for path in paths:
        try:
            with open(path, newline="", encoding="utf-8") as f:
                table = csv.DictReader(f)
                missing = [c for c in COLUMNS if c not in (table.fieldnames or [])]
                if missing:
                    sys.exit(f"{path}: no column {', '.join(missing)}; give the per-curve file that "
                             "bench/analysis_calibration writes as its third argument")
                if KIND_COLUMN not in (table.fieldnames or []):
                    sys.exit(f"{path}: no column {KIND_COLUMN}; --kind-column names a column the file has "
                             "(noise_read is written from held-out 24 on)")
                kept = [r for r in table if r.get("shape") not in skipped]
                if COLLAPSE_EDGE is not None:
                    if "collapse_onset" not in (table.fieldnames or []):
                        sys.exit(f"{path}: no column collapse_onset; --collapse-closeness needs files from "
                                 "held-out-27-brittle on")
                    kept = [r for r in kept if collapse_closeness(r) is not None]
                for column, value in ONLY:
                    if column not in (table.fieldnames or []):
                        sys.exit(f"{path}: no column {column}; --only names a column the file has")
                    kept = [r for r in kept if r[column] == value]
                    if not kept:
                        sys.exit(f"{path}: no curve with {column} = '{value}'; --only keeps the curves with "
                                 "that value")
                rows += [dict(r, source=path, noise=kind_of(r)) for r in kept]
        except OSError as e:
            sys.exit(f"{path}: cannot read it ({e.strerror}); name an existing per-curve file")
    return rows


def collapse_closeness(row):
    """How close a curve's collapse comes to its force peak: the estimated onset over x_c minus 1, or
    None without an onset or an x_c (a rejected curve may have neither)."""
    try:
        onset, x_c = float(row["collapse_onset"]), float(row["x_c"])
    except ValueError:
        return None
    return onset / x_c - 1.0 if math.isfinite(onset) and x_c > 0.0 else None


def kind_of(row):
    """The kind a curve is scored as: its KIND_COLUMN, or a random walk where --quiet-below finds it
    quiet (a missing share, as for a curve without E_max, is not quiet); with --collapse-closeness,
    followed by how close its collapse comes ("white, collapse near")."""
    kind = row[KIND_COLUMN]
    if QUIET_BELOW is not None and row.get("accepted") == "1":
        try:
            shares = [float(row["force_white_share"]), float(row["energy_white_share"])]
        except (KeyError, ValueError):
            shares = None
        if shares is not None and max(shares) < QUIET_BELOW:
            kind = "random walk"
    if COLLAPSE_EDGE is not None:
        kind += ", collapse " + ("near" if collapse_closeness(row) < COLLAPSE_EDGE else "far")
    return kind


def parse_use(text):
    """KIND=S68,S95 as (kind, None, {level: factor}); KIND@SHARE=S68,S95 as (kind, share, {level: factor}),
    one anchor of a kind whose factors follow the measured noise level."""
    kind, _, factors = text.partition("=")
    kind, at, share = kind.partition("@")
    try:
        s68, s95 = (float(f) for f in factors.split(","))
        anchor = float(share) if at else None
    except ValueError:
        sys.exit(f"interval_scales.py: --use '{text}': give KIND=S68,S95 or KIND@SHARE=S68,S95, e.g. "
                 "--use \"random walk=1,0.6119\" or --use \"white@0.002=0.6213,0.8308\"")
    if anchor is not None and not anchor > 0.0:
        sys.exit(f"interval_scales.py: --use '{text}': the share after @ must be positive, e.g. white@0.002")
    return kind, anchor, {"68": s68, "95": s95}


def white_level(group):
    """The share of each peak a "white X %" group's noise has, or None for another group."""
    name, _, rest = group.partition(" ")
    if name != "white" or not rest.endswith(" %"):
        return None
    try:
        return float(rest[:-2]) / 100.0
    except ValueError:
        return None


def factor(row, level, scales):
    """A kind's factor for one curve: a number, or, for anchors {share: {level: factor}}, the anchors'
    factors interpolated linearly in the log of the curve's measured white noise in E_e."""
    if level in scales:
        return scales[level]
    shares = sorted(scales)
    if not shares:
        sys.exit(f"{row['source']}: no white group to anchor level-following factors on; learn on files with "
                 "\"white X %\" groups or give anchors with --use \"white@SHARE=S68,S95\"")
    for column in ("energy_white_share",) + (("force_white_share",) if LEVEL_FROM_BOTH else ()):
        if column not in row:
            sys.exit(f"{row['source']}: no {column} for a curve scored with level-following factors; "
                     "give files from held-out-22-edge on")
    try:
        share = float(row["energy_white_share"])
        if LEVEL_FROM_BOTH:
            share = max(share, float(row["force_white_share"]))
    except ValueError:
        return 1.0  # not measured (no E_max): the analysis keeps the bootstrap's own sd
    if not math.isfinite(share) or (WHITE_FROM is not None and not share >= WHITE_FROM):
        return 1.0
    if share <= shares[0]:
        return scales[shares[0]][level]
    for low, high in zip(shares, shares[1:]):
        if share <= high:
            t = (math.log(share) - math.log(low)) / (math.log(high) - math.log(low))
            return (1.0 - t) * scales[low][level] + t * scales[high][level]
    return scales[shares[-1]][level]


def conformal_scale(scores, level):
    ordered = sorted(scores)
    rank = min(len(ordered), math.ceil((len(ordered) + 1) * level))
    return ordered[rank - 1]


def rounded_up(scale):
    """A learned scale as it ships: up to the next 1e-4 (widening, never narrowing, the interval). The
    product is rounded to 1e-9 first so that a scale already on the grid (0.69) stays there."""
    return math.ceil(round(scale * 1e4, 9)) / 1e4


def learn_scales(rows):
    """{noise kind: {level: scale}} from the accepted rows of each kind; with --white-by-level the white
    kind's are {share: {level: scale}}, one anchor per white group."""
    scales = {}
    for kind in sorted({r["noise"] for r in rows}):
        accepted = [r for r in rows if r["noise"] == kind and r["accepted"] == "1"]
        if WHITE_BY_LEVEL and kind == "white":
            anchors = {}
            for r in accepted:
                if white_level(r["group"]) is not None:
                    anchors.setdefault(white_level(r["group"]), []).append(r)
            scales[kind] = {share: {lvl: rounded_up(conformal_scale([score(r, lvl) for r in members], p))
                                    for lvl, p in LEVELS} for share, members in anchors.items()}
        elif accepted:
            scales[kind] = {lvl: rounded_up(conformal_scale([score(r, lvl) for r in accepted], p))
                            for lvl, p in LEVELS}
    return scales


def describe(by_level):
    """A kind's scales in words: one pair, or one pair per anchor."""
    if "68" in by_level:
        return f"scale 68 % = {by_level['68']:.4f}, scale 95 % = {by_level['95']:.4f}"
    return "; ".join(f"at {100 * share:g} %: {by_level[share]['68']:.4f}, {by_level[share]['95']:.4f}"
                     for share in sorted(by_level))


def is_covered(row, level, by_level):
    """Whether the scaled interval of `level` reaches the truth (the 95 % one holds the 68 % one)."""
    reached = score(row, level) <= factor(row, level, by_level)
    return reached or (level == "95" and score(row, "68") <= factor(row, "68", by_level))


def table(title, rows, scales):
    groups = OrderedDict()
    for row in rows:
        groups.setdefault(row["group"], []).append(row)
    print(f"\n{title}\n")
    q = "δ_x" if QUANTITY == "delta_x" else QUANTITY
    print(f"| group | curves | read as random walk | accepted | {q} 68 % (scaled) | {q} 95 % (scaled) | "
          f"{q} 68 % (unscaled) | {q} 95 % (unscaled) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, members in list(groups.items()) + [("all", rows)]:
        accepted = [r for r in members if r["accepted"] == "1"]
        n = max(1, len(accepted))
        for r in accepted:
            if r["noise"] not in scales:
                sys.exit(f"{r['source']}: no scale for {r['noise']} noise; learn on curves of that kind "
                         "or give it with --use")
        covered = {lvl: sum(is_covered(r, lvl, scales[r["noise"]]) for r in accepted) for lvl, _ in LEVELS}
        raw = {lvl: sum(score(r, lvl) <= 1.0 for r in accepted) for lvl, _ in LEVELS}
        walks = sum(r["noise"].startswith("random walk") for r in members)
        print(f"| {name} | {len(members)} | {walks} | {len(accepted)} | {100 * covered['68'] / n:.1f} % | "
              f"{100 * covered['95'] / n:.1f} % | {100 * raw['68'] / n:.1f} % | {100 * raw['95'] / n:.1f} % |")


def rule_groups(accepted):
    """{group name: curves} as the rule counts them: each group alone, but those of fewer than
    POOL_GROUPS_BELOW curves together as one."""
    groups = OrderedDict()
    for r in accepted:
        groups.setdefault(r["group"], []).append(r)
    small = [name for name, members in groups.items() if len(members) < POOL_GROUPS_BELOW]
    if small:
        pooled = [r for name in small for r in groups.pop(name)]
        groups[f"groups under {POOL_GROUPS_BELOW} curves ({len(small)})"] = pooled
    return groups


def verdict(rows, scales):
    """Each noise kind against the shipping rule (docs/analysis.md, "Calibration"): coverage within
    63-73 % at 68 % and 93-97 % at 95 %, and no group (rule_groups) more than 2 binomial sd below
    nominal."""
    print("\n| noise | accepted | 68 % | 95 % | lowest group, 68 % / 95 % | verdict |")
    print("|---|---|---|---|---|---|")
    bounds = {"68": (63.0, 73.0), "95": (93.0, 97.0)}
    for kind in sorted({r["noise"] for r in rows if r["accepted"] == "1"}):
        accepted = [r for r in rows if r["noise"] == kind and r["accepted"] == "1"]
        coverage = {lvl: 100 * sum(is_covered(r, lvl, scales[kind]) for r in accepted) / len(accepted)
                    for lvl, _ in LEVELS}
        failures = [f"{coverage[lvl]:.1f} % at {lvl} % is outside {low:g}-{high:g} %"
                    for lvl, (low, high) in bounds.items() if not low <= coverage[lvl] <= high]
        lowest = {}
        groups = rule_groups(accepted)
        for lvl, nominal in LEVELS:
            for group in sorted(groups):
                members = groups[group]
                covered = sum(is_covered(r, lvl, scales[kind]) for r in members)
                share = 100 * covered / len(members)
                if lvl not in lowest or share < lowest[lvl][0]:
                    lowest[lvl] = (share, group)
                floor = nominal - 2 * math.sqrt(nominal * (1 - nominal) / len(members))
                if covered < floor * len(members):
                    failures.append(f"{group}: {covered} of {len(members)} at {lvl} %, "
                                    f"{math.ceil(floor * len(members))} needed")
        low68, low95 = lowest["68"], lowest["95"]
        print(f"| {kind} | {len(accepted)} | {coverage['68']:.1f} % | {coverage['95']:.1f} % | "
              f"{low68[0]:.1f} % ({low68[1]}) / {low95[0]:.1f} % ({low95[1]}) | "
              f"{'passes' if not failures else 'fails: ' + '; '.join(failures)} |")


def share_argument(args, option, of_what, example):
    """The share an option names, or the exit that says how to give it."""
    try:
        return float(next(args, ""))
    except ValueError:
        sys.exit(f"interval_scales.py: {option} needs a share {of_what}, e.g. {option} {example}")


def main(argv):
    global QUANTITY, KIND_COLUMN, QUIET_BELOW, WHITE_BY_LEVEL, WHITE_FROM, LEVEL_FROM_BOTH, COLLAPSE_EDGE
    global POOL_GROUPS_BELOW
    if "--check" in argv:
        cut = argv.index("--check")
        argv, check = argv[:cut], argv[cut + 1:]
    else:
        check = []
    learn, given, skipped, pool_checks = [], {}, set(), False
    args = iter(argv)
    for arg in args:
        if arg == "--quantity":
            QUANTITY = next(args, "")
            if QUANTITY not in ("delta_x", "x_c", "x_p"):
                sys.exit(f"interval_scales.py: --quantity '{QUANTITY}': name delta_x, x_c or x_p")
        elif arg == "--kind-column":
            KIND_COLUMN = next(args, "")
            if not KIND_COLUMN:
                sys.exit("interval_scales.py: --kind-column needs a column name, e.g. --kind-column noise_read")
        elif arg == "--quiet-below":
            QUIET_BELOW = share_argument(args, arg, "of the peaks", "5e-4")
        elif arg == "--white-by-level":
            WHITE_BY_LEVEL = True
        elif arg == "--level-from-both":
            LEVEL_FROM_BOTH = True
        elif arg == "--white-from":
            WHITE_FROM = share_argument(args, arg, "of E_max", "0.0017")
        elif arg == "--collapse-closeness":
            COLLAPSE_EDGE = share_argument(args, arg, "of x_c between near and far collapses", "0.1")
        elif arg == "--pool-groups-below":
            try:
                POOL_GROUPS_BELOW = int(next(args, ""))
            except ValueError:
                POOL_GROUPS_BELOW = 0
            if POOL_GROUPS_BELOW < 1:
                sys.exit("interval_scales.py: --pool-groups-below needs a positive whole number of curves, "
                         "e.g. --pool-groups-below 20")
        elif arg == "--only":
            column, equals, value = next(args, "").partition("=")
            if not column or not equals:
                sys.exit("interval_scales.py: --only needs COLUMN=VALUE, e.g. --only force_walk_read_as_zero=1")
            ONLY.append((column, value))
        elif arg == "--pool-checks":
            pool_checks = True
        elif arg == "--use":
            kind, share, by_level = parse_use(next(args, ""))
            if share is None:
                if kind in given:
                    sys.exit(f"interval_scales.py: --use: {kind} is given twice or with anchors; give it once")
                given[kind] = by_level
            else:
                anchors = given.setdefault(kind, {})
                if "68" in anchors:
                    sys.exit(f"interval_scales.py: --use: {kind} has both one factor and anchors; give one or "
                             "the other")
                anchors[share] = by_level
        elif arg == "--skip-shape":
            name = next(args, "")
            if not name:
                sys.exit("interval_scales.py: --skip-shape needs a shape name as the files write it, "
                         "e.g. --skip-shape \"uniform [0.3,0.8]\"")
            skipped.add(name)
        else:
            learn.append(arg)
    if not learn:
        sys.exit("interval_scales.py: name at least one per-curve file to learn from")
    if COLLAPSE_EDGE is not None and WHITE_BY_LEVEL:
        sys.exit("interval_scales.py: --white-by-level learns white groups of curves without a collapse; "
                 "give it or --collapse-closeness, not both")
    learning = read(learn, skipped)
    present = {r.get("shape") for r in read(learn + check)}
    for name in sorted(skipped - present):
        sys.exit(f"interval_scales.py: --skip-shape '{name}': no curve of that shape in the files; "
                 "give the name as their `shape` column writes it")
    scales = learn_scales(learning)
    print(f"{QUANTITY}'s scales learned on {', '.join(learn)}:")
    for kind, by_level in scales.items():
        n = sum(r["noise"] == kind and r["accepted"] == "1" for r in learning)
        print(f"  {kind} noise ({n} accepted curves): {describe(by_level)}")
    for kind in given:
        if kind not in {r["noise"] for r in read(learn + check)}:
            sys.exit(f"interval_scales.py: --use '{kind}=...': no curve of that kind of noise; the `noise` "
                     "column names them (white, random walk)")
    for kind, by_level in given.items():
        print(f"  scored with {kind} noise: {describe(by_level)}")
        scales[kind] = by_level
    table("Learning set", learning, scales)
    for paths in ([check] if pool_checks and check else [[path] for path in check]):
        checked = read(paths, skipped)
        table(f"Check: {', '.join(paths)}", checked, scales)
        verdict(checked, scales)


if __name__ == "__main__":
    main(sys.argv[1:])

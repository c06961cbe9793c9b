"""bench/interval_scales.py: the conformal scales it learns, the shipping rule it applies to a
check file, and the inputs it refuses (docs/analysis.md, "Calibration")."""
import csv
import subprocess
import sys

import bench_scripts

SCRIPT = bench_scripts.path("interval_scales")
COLUMNS = ["set", "group", "shape", "noise", "accepted", "delta_x_true", "delta_x", "ci68_low", "ci68_high",
           "ci95_low", "ci95_high"]


def load():
    return bench_scripts.load("interval_scales")


def rows_with_scores(scores68, scores95, noise="random walk", group="bundle N=1e4"):
    """Curves whose 68 % and 95 % intervals must be stretched by the given factors to reach the truth:
    estimate 1, truth 1 + s68 (so the half-widths are 1 and s68 / s95)."""
    rows = []
    for s68, s95 in zip(scores68, scores95):
        gap = s68
        rows.append({"set": "t", "group": group, "shape": "weibull k=2", "noise": noise, "accepted": "1",
                     "delta_x_true": str(1.0 + gap), "delta_x": "1.0", "ci68_low": "0.0", "ci68_high": "2.0",
                     "ci95_low": str(1.0 - gap / s95), "ci95_high": str(1.0 + gap / s95)})
    return rows


def write(path, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        table = csv.DictWriter(f, fieldnames=COLUMNS)
        table.writeheader()
        table.writerows(rows)
    return str(path)


def run(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, check=False)


def test_the_learned_scale_is_the_split_conformal_quantile():
    module = load()
    scores = [0.01 * (i + 1) for i in range(100)]  # 0.01 .. 1.00
    rows = rows_with_scores(scores, scores)
    scales = module.learn_scales(rows)["random walk"]
    # ceil((n + 1) L)-th smallest of n = 100: the 69th (0.69) at 68.27 %, the 96th (0.96) at 95 %.
    assert abs(scales["68"] - 0.69) < 1e-12
    assert abs(scales["95"] - 0.96) < 1e-12
    # Off the 1e-4 grid the scale is rounded up, as it ships (src/analysis/analysis.hpp): never narrower.
    off_grid = module.learn_scales(rows_with_scores([0.12341] * 10, [0.12341] * 10))["random walk"]
    assert off_grid["68"] == 0.1235 and off_grid["95"] == 0.1235


def test_the_rule_passes_nominal_coverage_and_names_what_fails(tmp_path, capsys):
    module = load()
    scores = [0.01 * (i + 1) for i in range(200)]  # needed stretch 0.01 .. 2.00, so scale 1 covers half
    half = rows_with_scores(scores, scores)
    module.verdict(half, {"random walk": {"68": 1.0, "95": 1.0}})
    failed = capsys.readouterr().out
    assert "fails" in failed and "50.0 % at 68 % is outside 63-73 %" in failed
    assert "bundle N=1e4: 100 of 200 at 68 %, 124 needed" in failed

    module.verdict(half, {"random walk": {"68": 1.365, "95": 1.905}})  # covers 136 and 190 of 200
    passed = capsys.readouterr().out
    assert "| random walk | 200 | 68.0 % | 95.0 % |" in passed and passed.rstrip().endswith("passes |")


def test_small_groups_are_scored_together_only_when_asked(capsys):
    module = load()
    # 200 curves covered at 68 % / 95 % with factors 1.365 / 1.905 (nominal, as above), beside two groups
    # of 3 whose curves each need 1.5 at 95 %: one miss in 3 fails a group alone.
    scores = [0.01 * (i + 1) for i in range(200)]
    rows = rows_with_scores(scores, scores)
    for group in ("run-like a", "run-like b"):
        rows += rows_with_scores([0.1, 0.1, 2.0], [0.1, 0.1, 2.0], group=group)
    factors = {"random walk": {"68": 1.365, "95": 1.905}}
    module.verdict(rows, factors)
    alone = capsys.readouterr().out
    assert "run-like a: 2 of 3 at 95 %, 3 needed" in alone and "fails" in alone
    try:
        module.POOL_GROUPS_BELOW = 20
        module.verdict(rows, factors)
    finally:
        module.POOL_GROUPS_BELOW = 0
    pooled = capsys.readouterr().out
    # Together the six are 4 of 6 at 95 %, below 95 % - 2 sd (77.2 % of 6: 5 needed), so the pooled group
    # fails too, but as one group under its own name.
    assert "run-like a:" not in pooled
    assert "groups under 20 curves (2): 4 of 6 at 95 %, 5 needed" in pooled


def test_pooled_checks_score_several_files_as_one_set(tmp_path):
    scores = [0.01 * (i + 1) for i in range(200)]
    learn = write(tmp_path / "learn.csv", rows_with_scores(scores, scores))
    first = write(tmp_path / "a.csv", rows_with_scores(scores[:100], scores[:100], group="a"))
    second = write(tmp_path / "b.csv", rows_with_scores(scores[100:], scores[100:], group="b"))
    apart = run(learn, "--check", first, second)
    together = run(learn, "--pool-checks", "--check", first, second)
    assert apart.returncode == 0 and together.returncode == 0
    assert apart.stdout.count("| noise | accepted |") == 2
    assert together.stdout.count("| noise | accepted |") == 1
    assert f"Check: {first}, {second}" in together.stdout
    # Apart, the low half is all covered and the high half mostly missed; together they are the learning
    # set itself, covered as learned (the 137th and 191st smallest of 200 scores).
    assert "b: 38 of 100 at 68 %, 59 needed" in apart.stdout
    assert "| random walk | 200 | 69.0 % | 95.0 % |" in together.stdout
    assert run(learn, "--pool-groups-below", "0").returncode != 0
    assert "positive whole number of curves" in run(learn, "--pool-groups-below", "x").stderr


def test_a_factor_for_a_kind_of_noise_the_files_do_not_have_is_refused(tmp_path):
    learn = write(tmp_path / "learn.csv", rows_with_scores([0.5] * 10, [0.5] * 10))
    result = run(learn, "--use", "white noise=1,1")
    assert result.returncode != 0
    assert "--use 'white noise=...': no curve of that kind of noise" in result.stderr
    assert run(learn, "--use", "random walk=1,1").returncode == 0


def test_quiet_curves_and_another_kind_column_choose_the_kind_scored(tmp_path):
    """--quiet-below scores curves with white noise below the share of both peaks as a random walk
    (not those with a missing share); --kind-column reads the kind from another column."""
    rows = rows_with_scores([0.5] * 6, [0.5] * 6, noise="white")
    for row, (force, energy) in zip(rows, [("1e-5", "2e-5")] * 3 + [("1e-5", "")] + [("3e-3", "1e-5")] * 2):
        row.update(force_white_share=force, energy_white_share=energy, noise_read="random walk")
    path = tmp_path / "shares.csv"
    with open(path, "w", newline="", encoding="utf-8") as f:
        table = csv.DictWriter(f, fieldnames=COLUMNS + ["force_white_share", "energy_white_share", "noise_read"])
        table.writeheader()
        table.writerows(rows)
    quiet = run(str(path), "--quiet-below", "5e-4")
    assert quiet.returncode == 0, quiet.stderr
    assert "random walk noise (3 accepted curves)" in quiet.stdout
    assert "white noise (3 accepted curves)" in quiet.stdout
    read = run(str(path), "--kind-column", "noise_read")
    assert "random walk noise (6 accepted curves)" in read.stdout and "white noise" not in read.stdout
    missing = run(str(path), "--kind-column", "no_such_column")
    assert missing.returncode != 0 and "no column no_such_column" in missing.stderr


def test_white_factors_by_level_are_learned_per_group_and_follow_the_measured_share(tmp_path):
    """--white-by-level learns one anchor per "white X %" group; each curve is scored by its
    energy_white_share, linear in log share between anchors and held at the ends, or with
    --white-from given, 1 below that share (as white_level_scales in src/analysis/analysis.hpp);
    1 where the share is not measured."""
    module = load()
    low = rows_with_scores([0.01 * (i + 1) for i in range(100)], [0.5] * 100, noise="white", group="white 0.2 %")
    high = rows_with_scores([0.02 * (i + 1) for i in range(100)], [0.5] * 100, noise="white", group="white 3 %")
    module.WHITE_BY_LEVEL = True
    try:
        scales = module.learn_scales(low + high)["white"]
    finally:
        module.WHITE_BY_LEVEL = False
    assert sorted(scales) == [0.002, 0.03]
    assert abs(scales[0.002]["68"] - 0.69) < 1e-12 and abs(scales[0.03]["68"] - 1.38) < 1e-12
    between = {"energy_white_share": str((0.002 * 0.03) ** 0.5), "source": "t"}
    assert abs(module.factor(between, "68", scales) - 0.5 * (0.69 + 1.38)) < 1e-12
    assert module.factor({"energy_white_share": "1e-4", "source": "t"}, "68", scales) == scales[0.002]["68"]
    assert module.factor({"energy_white_share": "0.5", "source": "t"}, "68", scales) == scales[0.03]["68"]
    assert module.factor({"energy_white_share": "", "source": "t"}, "68", scales) == 1.0
    assert module.factor({"energy_white_share": "nan", "source": "t"}, "95", scales) == 1.0
    module.WHITE_FROM = 0.0017
    try:
        assert module.factor({"energy_white_share": "1e-4", "source": "t"}, "68", scales) == 1.0
        assert module.factor({"energy_white_share": "0.0018", "source": "t"}, "68", scales) == scales[0.002]["68"]
    finally:
        module.WHITE_FROM = None
    # --level-from-both: the larger of F's and E_e's shares (δ_x's level), so a curve whose F carries
    # 3 % takes the 3 % anchor whatever E_e's noise.
    loud_force = {"energy_white_share": "1e-4", "force_white_share": "0.03", "source": "t"}
    assert module.factor(loud_force, "68", scales) == scales[0.002]["68"]
    module.LEVEL_FROM_BOTH = True
    try:
        assert module.factor(loud_force, "68", scales) == scales[0.03]["68"]
    finally:
        module.LEVEL_FROM_BOTH = False


def test_anchors_given_with_use_score_each_curve_at_its_level(tmp_path):
    """--use KIND@SHARE=S68,S95 builds the level model from the command line; a curve without a
    measured share, a nonpositive share or a kind given both ways is refused with the fix."""
    rows = rows_with_scores([0.5] * 4, [0.5] * 4, noise="white", group="white 1 %")
    for row, share in zip(rows, ["0.002", "0.002", "0.03", "0.03"]):
        row["energy_white_share"] = share
    path = tmp_path / "levels.csv"
    with open(path, "w", newline="", encoding="utf-8") as f:
        table = csv.DictWriter(f, fieldnames=COLUMNS + ["energy_white_share"])
        table.writeheader()
        table.writerows(rows)
    # Needed stretch 0.5 everywhere: covered at 68 % where the anchor's factor is 0.6, not where it is 0.4.
    result = run(str(path), "--use", "white@0.002=0.6,1", "--use", "white@0.03=0.4,1", "--check", str(path))
    assert result.returncode == 0, result.stderr
    assert "at 0.2 %: 0.6000, 1.0000; at 3 %: 0.4000, 1.0000" in result.stdout
    assert "| white 1 % | 4 | 0 | 4 | 50.0 % |" in result.stdout
    bad = run(str(path), "--use", "white@0=0.6,1")
    assert bad.returncode != 0 and "the share after @ must be positive" in bad.stderr
    both = run(str(path), "--use", "white@0.002=0.6,1", "--use", "white=1,1")
    assert both.returncode != 0 and "give it once" in both.stderr
    no_share = write(tmp_path / "no-share.csv", rows_with_scores([0.5] * 2, [0.5] * 2, noise="white"))
    missing = run(no_share, "--use", "white@0.002=0.6,1")
    assert missing.returncode != 0 and "no energy_white_share" in missing.stderr
    no_force = run(str(path), "--level-from-both", "--use", "white@0.002=0.6,1", "--check", str(path))
    assert no_force.returncode != 0 and "no force_white_share" in no_force.stderr, no_force.stderr


def test_a_share_option_without_a_number_is_refused_with_an_example(tmp_path):
    learn = write(tmp_path / "learn.csv", rows_with_scores([0.5] * 4, [0.5] * 4))
    for option, example in (("--white-from", "--white-from 0.0017"), ("--quiet-below", "--quiet-below 5e-4")):
        result = run(learn, option, "low")
        assert result.returncode != 0 and f"e.g. {example}" in result.stderr, result.stderr


def test_collapse_closeness_keeps_curves_cut_by_a_collapse_and_splits_each_kind_near_and_far(tmp_path):
    """--collapse-closeness 0.1 drops curves without a collapse onset (or x_c) and scores the others
    as "KIND, collapse near" below onset / x_c - 1 = 0.1, "KIND, collapse far" from it on."""
    rows = rows_with_scores([0.5, 0.6, 0.7, 0.8], [0.5, 0.6, 0.7, 0.8], noise="white")
    for row, (onset, x_c) in zip(rows, [("1.05", "1.0"), ("1.2", "1.0"), ("", "1.0"), ("1.3", "")]):
        row.update(collapse_onset=onset, x_c=x_c)
    path = tmp_path / "cut.csv"
    with open(path, "w", newline="", encoding="utf-8") as f:
        table = csv.DictWriter(f, fieldnames=COLUMNS + ["collapse_onset", "x_c"])
        table.writeheader()
        table.writerows(rows)
    module = load()
    module.COLLAPSE_EDGE = 0.1
    read = module.read([str(path)])
    assert [r["noise"] for r in read] == ["white, collapse near", "white, collapse far"]
    assert set(module.learn_scales(read)) == {"white, collapse near", "white, collapse far"}
    assert "white, collapse far noise (1 accepted curves)" in run(str(path), "--collapse-closeness", "0.1").stdout
    refused = run(write(tmp_path / "uncut.csv", rows_with_scores([0.5], [0.5])), "--collapse-closeness", "0.1")
    assert refused.returncode != 0 and "no column collapse_onset" in refused.stderr

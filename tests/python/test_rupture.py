"""Tests of the Python package (src/python): the same numbers as the command line, numpy views that
are the sample's own memory, runs that match `rupture run` byte for byte, Ctrl-C, errors, the readers
of run and scan folders, and the examples under examples/python."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import rupture

BINARY = os.environ["RUPTURE_BINARY"]
EXAMPLES = Path(os.environ["RUPTURE_EXAMPLES_DIR"]).resolve()
BLOCK = EXAMPLES / "block.toml"


def cli(*args, cwd=None):
    done = subprocess.run([BINARY, *map(str, args)], cwd=cwd, capture_output=True, text=True)
    assert done.returncode in (0, 4), done.stderr
    return done


def data_rows(path):
    """A CSV's lines without its '#' comments (which name the command that wrote it)."""
    return [line for line in Path(path).read_text().splitlines() if not line.startswith("#")]


# ---- fbm --------------------------------------------------------------------------------------

def test_fbm_theory_of_the_uniform_law_is_exact():
    # Uniform thresholds on [0, 1]: F = x (1 - x), E_e = x^2 (1 - x) / 2: x_p = 1/3, x_c = 1/2, x_m = 2/3.
    t = rupture.fbm.theory("uniform")
    assert t["x_p"] == pytest.approx(1 / 3, abs=1e-9)
    assert t["x_c"] == pytest.approx(1 / 2, abs=1e-9)
    assert t["x_m"] == pytest.approx(2 / 3, abs=1e-9)
    assert t["A_r"] == pytest.approx(4 / 3, abs=1e-8)
    from_cli = json.loads(cli("fbm", "theory", "--dist", "uniform", "--json").stdout)
    assert all(from_cli[key] == value for key, value in t.items())  # the command line's numbers, bit for bit


def test_fbm_curves_at_chosen_strains_follow_the_closed_form():
    x = np.linspace(0.0, 1.0, 101)
    c = rupture.fbm.curves("uniform", x=x)
    np.testing.assert_allclose(c["strain"], x)
    np.testing.assert_allclose(c["force"], x * (1 - x), atol=1e-12)
    np.testing.assert_allclose(c["elastic_energy"], x * x * (1 - x) / 2, atol=1e-12)
    np.testing.assert_allclose(c["energy_rate"], x - 1.5 * x * x, atol=1e-9)
    assert c.attrs["units"]["force"] == "1"


def test_fbm_simulate_is_reproducible_and_near_the_theory():
    a_curve, a = rupture.fbm.simulate("uniform", 100000, seed=3)
    b_curve, b = rupture.fbm.simulate("uniform", 100000, seed=3)
    assert a == b
    assert a_curve.equals(b_curve)
    assert a["x_c"] == pytest.approx(0.5, abs=0.01)  # N = 1e5: fluctuations ~ N^-1/2
    _, load = rupture.fbm.simulate("uniform", 100000, seed=3, control="load")
    assert sum(load["bursts"].values()) > 0 and load["final_burst"] > 0
    with pytest.raises(rupture.InputError, match="load control only"):
        rupture.fbm.simulate("uniform", 10, control="strain", sharing="lls")


# ---- samples ------------------------------------------------------------------------------------

def test_sample_arrays_are_views_of_the_sample_and_keep_it_alive():
    s = rupture.sample.generate("tissue-small", seed=1)
    stats = s.stats()
    assert (len(s), len(s.bonds)) == (stats["particles"], stats["bonds"])
    positions = s.positions
    assert positions.shape == (len(s), 3) and positions.dtype == np.float64
    assert np.shares_memory(positions, s.positions)  # no copy: two reads see one buffer
    bonds, rest = s.bonds, s.rest_lengths
    i, j = bonds[:, 0], bonds[:, 1]
    assert np.all(i < j)
    np.testing.assert_allclose(rest, np.linalg.norm(positions[j] - positions[i], axis=1), rtol=1e-12)
    del s  # the arrays hold the sample
    assert np.isfinite(positions).all() and rest.min() > 0


def test_sample_save_load_round_trip(tmp_path):
    s = rupture.sample.generate("tissue-small", seed=2)
    rupture.sample.save(s, tmp_path / "t.rsample")
    back = rupture.sample.load(tmp_path / "t.rsample")
    for name in ("positions", "radii", "ids", "groups", "bonds", "rest_lengths"):
        np.testing.assert_array_equal(getattr(back, name), getattr(s, name), err_msg=name)
    assert back.density == s.density


def test_sample_from_arrays_bonds_touching_particles_and_glues_the_faces():
    # A column of 5 touching spheres of radius 0.5 mm along y: 4 bonds of 1 mm, the ends glued.
    positions = [[0.5, 0.5 + k, 0.5] for k in range(5)]
    s = rupture.sample.from_arrays(positions, [0.5] * 5)
    np.testing.assert_array_equal(s.bonds, [[0, 1], [1, 2], [2, 3], [3, 4]])
    np.testing.assert_allclose(s.rest_lengths, 1.0)
    np.testing.assert_array_equal(s.groups, [1, 0, 0, 0, 2])
    with pytest.raises(ValueError, match="positions"):
        rupture.sample.from_arrays([[0, 0]], [0.5])
    with pytest.raises(ValueError, match="bonds row 0"):
        rupture.sample.from_arrays(positions, [0.5] * 5, bonds=[[0, 7]])


# ---- runs ---------------------------------------------------------------------------------------

def test_run_writes_what_the_command_line_writes(tmp_path):
    rows = []
    run = rupture.run(BLOCK, out=tmp_path / "py", progress=rows.append)
    cli("run", BLOCK, "-o", tmp_path / "cli")
    assert run.summary["status"] == "finished"
    for name in ("curves.csv", "breaks.csv"):  # no comment lines naming the command: the same bytes
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert len(rows) == len(run.curves)  # one progress call per curve row
    assert rows[-1]["steps"] == run.curves["step[1]"].iloc[-1]
    assert run.curves.attrs["units"]["strain[%]"] == "%"
    assert run.record["command"].startswith("python: rupture.run(")


def test_run_tables_load_in_pandas_and_numpy_without_options(tmp_path):
    import pandas as pd
    cli("run", BLOCK, "-o", tmp_path / "r")
    curves = pd.read_csv(tmp_path / "r" / "curves.csv")
    assert list(curves.columns[:3]) == ["time[s]", "step[1]", "strain[%]"]
    assert curves["strain[%]"].is_monotonic_increasing and curves["force_top[N]"].max() > 0
    table = np.genfromtxt(tmp_path / "r" / "curves.csv", delimiter=",", names=True)
    assert len(table) == len(curves)  # numpy drops the brackets from the names; pandas' parser may differ in the last bit
    assert np.allclose(table["strain"], curves["strain[%]"].to_numpy(), rtol=1e-12, atol=0)
    breaks = pd.read_csv(tmp_path / "r" / "breaks.csv")
    assert len(breaks) > 0 and list(breaks.columns[:2]) == ["step[1]", "time[s]"]
    record = json.loads((tmp_path / "r" / "run.json").read_text())
    assert "initial plate separation" in record["columns"]["strain"]


def test_run_from_a_dict_with_a_sample_object(tmp_path):
    block = rupture.sample.from_arrays([[0.5 + x, 0.5 + y, 0.5] for x in range(3) for y in range(6)], [0.5] * 18)
    config = {"bonds": {"stiffness": 1e3, "break_distance": 0.002}, "loading": {"speed": 500.0, "ramp_steps": 500},
              "stop": {"extra_strain": 0.5, "max_strain": 20.0}, "output": {"interval": 50}}
    run = rupture.run(config, out=tmp_path / "r", sample=block)
    assert run.summary["status"] == "finished" and run.summary["stop_reason"] == "separated"
    assert run.record["sample"]["particles"] == 18
    assert Path(run.record["config"]["sample"]["file"]) == (tmp_path / "r.rsample").resolve()
    assert rupture.sample.load(tmp_path / "r.rsample").positions.shape == (18, 3)


def test_ctrl_c_writes_a_checkpoint_that_python_resumes_to_the_same_curves(tmp_path):
    # A child Python runs a long pull; SIGINT reaches it mid-run. It must stop with a checkpoint and
    # raise KeyboardInterrupt; rupture.resume then ends the run exactly as one without a stop.
    script = textwrap.dedent(f"""
        import rupture
        try:
            rupture.run({str(BLOCK)!r}, out={str(tmp_path / 'stopped')!r},
                        set=["loading.speed=5", "stop.max_strain=2", "output.interval=20"],
                        progress=lambda p: print("row", flush=True))
        except KeyboardInterrupt:
            print("interrupted", flush=True)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "row"  # the run has started
    time.sleep(0.2)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=120)
    assert "interrupted" in out
    record = json.loads((tmp_path / "stopped" / "run.json").read_text())
    assert record["status"] == "interrupted"
    resumed = rupture.resume(tmp_path / "stopped")
    assert resumed.summary["status"] == "finished"
    cli("run", BLOCK, "-o", tmp_path / "whole", "--set", "loading.speed=5", "--set", "stop.max_strain=2",
        "--set", "output.interval=20")
    assert data_rows(tmp_path / "stopped" / "curves.csv") == data_rows(tmp_path / "whole" / "curves.csv")


def test_bad_config_is_a_value_error_naming_the_key(tmp_path):
    with pytest.raises(rupture.InputError, match="bonds.stiffness"):
        rupture.run({"sample": {"preset": "tissue-small"}, "bonds": {"stiffness": -1.0}}, out=tmp_path / "r")
    with pytest.raises(ValueError, match="unknown key"):
        rupture.run(BLOCK, out=tmp_path / "r", set=["bonds.stifness=1"])
    assert not (tmp_path / "r").exists()


# ---- analysis and folders -----------------------------------------------------------------------

def test_analyze_gives_the_numbers_of_rupture_analyze(tmp_path):
    study = tmp_path / "study"
    cli("study", "--out", study, "--no-scan")
    expected = json.loads((study / "run" / "analysis.json").read_text())
    run = rupture.read_run(study / "run")
    for a in (rupture.analyze(run.curves), rupture.analyze(study / "run" / "curves.csv"),
              rupture.analyze(run.curves["strain_mean[%]"], run.curves["force_top_mean[N]"],
                              run.curves["elastic_energy_mean[mJ]"], rows="interval-means")):
        assert a.document["resample"]["rows"] == "interval-means"
        for key in ("x_p", "x_c", "x_m", "A_r"):
            assert getattr(a, key).value == pytest.approx(expected[key]["value"], rel=1e-12), key
            assert getattr(a, key).unit == expected[key]["unit"]
        assert a.delta_x.value == pytest.approx(expected["delta_x"]["mean"], rel=1e-12)
        assert a.delta_x_ci95 == pytest.approx(tuple(expected["delta_x"]["ci95"]), rel=1e-12)
        assert a.accepted
        assert a.units == {"strain": "%", "force": "N", "energy": "mJ"}
        delta, density = a.posterior
        assert delta.shape == density.shape and np.all(density >= 0)
    # Three arrays are instants unless said otherwise; a word that names no kind of row is refused.
    means = [run.curves[c] for c in ("strain_mean[%]", "force_top_mean[N]", "elastic_energy_mean[mJ]")]
    assert rupture.analyze(*means).document["resample"]["rows"] == "instants"
    with pytest.raises(rupture.InputError, match="'means' is not what a row holds"):
        rupture.analyze(*means, rows="means")
    # Only the file carries the breaks, so only it classifies as the CLI does.
    assert rupture.analyze(study / "run" / "curves.csv").mechanism == expected["mechanism"]["class"]


def test_a_dataframe_is_read_by_the_columns_rupture_analyze_picks():
    # rupture analyze's choice (find_curve_columns): a run's means as a set, else strain/force/energy.
    header = ["time[s]", "strain[%]", "force_top[N]", "elastic_energy[mJ]", "strain_mean[%]",
              "force_top_mean[N]", "elastic_energy_mean[mJ]"]
    import pandas as pd
    assert rupture._rupture.columns_read(header) == (4, 5, 6, "interval-means")
    assert rupture._rupture.columns_read(header[:5]) == (1, 2, 3, "instants")
    with pytest.raises(rupture.InputError, match="no column 'strain'.*from Python: name the DataFrame's columns"):
        rupture.analyze(pd.DataFrame({"force": [0.0, 1.0], "elastic_energy": [0.0, 1.0]}))


def test_analyze_force_peak_form_matches_the_command_line(tmp_path):
    # A force that rises at 0.5 to a corner at x = 0.4, sags at 1.5 to a collapse at 0.41 and falls, under
    # white noise: the corner form puts x_c on the corner (the cubic: 0.383), as --force-peak-form corner does.
    rng = np.random.default_rng(5)
    strain = np.linspace(0.0, 0.5, 1001)
    force = np.where(strain < 0.4, 1.0 - 0.5 * (0.4 - strain), 1.0 - 1.5 * (strain - 0.4))
    force = np.where(strain < 0.41, force, force[np.searchsorted(strain, 0.41)] * np.exp(-(strain - 0.41) / 0.0015))
    force = force * strain / (strain + 0.02)
    energy = 0.5 * strain * force
    curve = tmp_path / "corner.csv"
    np.savetxt(curve, np.column_stack([strain, force + 0.002 * rng.standard_normal(strain.size), energy]),
               delimiter=",", header="strain[1],force[1],elastic_energy[1]", comments="")
    for form, fit in (("smooth", "cubic"), ("corner", "corner")):
        out = tmp_path / f"analysis-{form}.json"
        cli("analyze", curve, "--force-peak-form", form, "-o", out)
        expected = json.loads(out.read_text())
        a = rupture.analyze(curve, force_peak_form=form)
        assert a.document["inputs"]["force_peak_form"] == form
        assert a.document["peak_fits"]["force"]["form"] == expected["peak_fits"]["force"]["form"] == fit
        assert a.x_c.value == expected["x_c"]["value"]
    assert abs(a.x_c.value - 0.4) < 0.002
    with pytest.raises(rupture.InputError, match="force_peak_form.*use \"smooth\" or \"corner\""):
        rupture.analyze(curve, force_peak_form="sharp")


def test_analyze_smoothing_floor_matches_the_command_line(tmp_path):
    # The power law α = 3 (F = x(1 - x⁴)) under 0.2 % white noise, 2,000 rows: the floor strengthens the
    # filter and brings x_p towards its exact 0.50813; 0 leaves the filter to the noise, as --smoothing-floor 0.
    rng = np.random.default_rng(9)
    strain = np.linspace(0.0, 1.2, 2000)
    force = strain * (1.0 - np.clip(strain, 0.0, 1.0) ** 4)
    energy = 0.5 * strain * force
    curve = tmp_path / "white.csv"
    np.savetxt(curve, np.column_stack([strain, force + 0.002 * force.max() * rng.standard_normal(strain.size),
                                       energy + 0.002 * energy.max() * rng.standard_normal(strain.size)]),
               delimiter=",", header="strain[1],force[1],elastic_energy[1]", comments="")
    x_p = {}
    for share, applied in ((0.25, True), (0.0, False)):
        out = tmp_path / f"analysis-{share}.json"
        cli("analyze", curve, "--smoothing-floor", str(share), "-o", out)
        expected = json.loads(out.read_text())
        a = rupture.analyze(curve, smoothing_floor=share)
        assert a.document["inputs"]["smoothing_floor_share"] == share
        assert a.document["filter"]["smoothing_floor_applied"] == expected["filter"]["smoothing_floor_applied"] == applied
        assert a.x_p.value == expected["x_p"]["value"]
        # the factors were learned without the floor: its intervals say they are not calibrated
        assert a.document["delta_x"]["interval_scales"]["calibrated"] == (not applied)
        assert any("smoothing floor" in w for w in a.document["warnings"]) == applied
        x_p[share] = a.x_p.value
    assert abs(x_p[0.25] - 0.50813) < 0.5 * abs(x_p[0.0] - 0.50813)
    with pytest.raises(rupture.InputError, match="smoothing_floor.*give a value in \\[0, 1\\]"):
        rupture.analyze(curve, smoothing_floor=2.0)
    with pytest.raises(rupture.InputError, match="replicates.*give 0 \\(the default 200\\) or 20 to 100000"):
        rupture.analyze(curve, replicates=-5)
    with pytest.raises(rupture.InputError, match="seed.*give a seed >= 0"):
        rupture.analyze(curve, seed=-1)
    with pytest.raises(rupture.InputError, match="'fitted' is not a method.*use \"fitted-maxima\" or \"shift-l1\""):
        rupture.analyze(curve, delay_method="fitted")
    with pytest.raises(rupture.InputError,
                       match="'round' is not a form of the force's peak.*use \"smooth\" or \"corner\""):
        rupture.analyze(curve, force_peak_form="round")
    # the core takes the options by keyword and refuses one it does not know (package and core out of step)
    with pytest.raises(rupture.InputError, match="'smoothing' is not an option.*use delay_method, force_peak_form, "
                       "replicates, rows, seed, smoothing_floor or walk_profile"):
        rupture._rupture.analyze_file(str(curve), smoothing=0.25)


def test_analyze_walk_profile_switch_matches_the_command_line(tmp_path):
    curve = tmp_path / "bundle.csv"
    cli("fbm", "simulate", "--dist", "uniform", "--fibers", "100000", "--seed", "7", "--out", curve)
    for walk_profile, switches in ((True, []), (False, ["--no-walk-profile"])):
        out = tmp_path / f"analysis-{walk_profile}.json"
        cli("analyze", curve, *switches, "-o", out)
        expected = json.loads(out.read_text())
        a = rupture.analyze(curve, walk_profile=walk_profile)
        assert a.document["inputs"]["walk_profile"] is walk_profile
        assert a.document["delta_x"]["interval_scales"]["noise"] == "random walk"
        assert a.delta_x.error == expected["delta_x"]["error"]
        assert a.delta_x_ci95 == tuple(expected["delta_x"]["ci95"])
        # On a random walk the three intervals' factors passed their last held-out check (held-out 35),
        # with the walk's step profile only.
        assert a.intervals_calibrated == {"x_c": walk_profile, "x_p": walk_profile, "delta_x": walk_profile}
        for key in ("x_c", "x_p"):
            assert getattr(a, f"{key}_ci95") == tuple(expected[key]["ci95"])
            assert getattr(a, f"{key}_ci68") == tuple(expected[key]["ci68"])
            low, high = getattr(a, f"{key}_ci95")
            assert low < getattr(a, key).value < high
    # The switch reaches the bootstrap: the two sds differ.
    assert (rupture.analyze(curve).delta_x.error
            != rupture.analyze(curve, walk_profile=False).delta_x.error)


def test_read_scan_and_the_examples(tmp_path):
    cli("scan", EXAMPLES / "scan-block.toml", "-o", tmp_path / "scan")
    scan = rupture.read_scan(tmp_path / "scan")
    assert len(scan) == 6
    assert scan.attrs["units"]["k_n[N/mm]"] == "N/mm"
    assert scan.attrs["scan"]["tool"] == "rupture scan"
    assert set(scan["status"]) <= {"ok", "no_separation", "unstable", "error"}
    env = dict(os.environ)
    folder = EXAMPLES / "python"
    out = subprocess.run([sys.executable, folder / "figure3.py", tmp_path / "f3.png"], env=env, cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "x_p = 0.3333, x_c = 0.5000, x_m = 0.6667" in out.stdout
    assert (tmp_path / "f3.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    out = subprocess.run([sys.executable, folder / "run_and_analyze.py", tmp_path / "b"], env=env, cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("finished separated") and "Analysis(x_p=" in out.stdout
    out = subprocess.run([sys.executable, folder / "scan_table.py", tmp_path / "scan"], env=env, cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("6 points,")

"""bench/curve_table.py and bench/dense_rows.py: a curves.csv read as rupture writes it (comments, a
byte-order mark, units in the header), each malformed table refused in one line naming the file and the
row, and the dense rows' window means and force top."""
import pytest

import bench_scripts


def write(tmp_path, text, name="curves.csv", encoding="utf-8"):
    path = tmp_path / name
    path.write_text(text, encoding=encoding)
    return path


def refusal(call):
    with pytest.raises(SystemExit) as stop:
        call()
    return str(stop.value.code)


def test_a_run_s_table_reads_with_its_comments_and_units(tmp_path):
    table_module = bench_scripts.load("curve_table")
    path = write(tmp_path, "# rupture 0.1.0 run\nstrain[%],force_top[N],elastic_energy[mJ]\n0,0,0\n\n0.5,2.5,1e-3\n",
                 encoding="utf-8-sig")
    table = table_module.read_table(path)
    assert table.comments == ["# rupture 0.1.0 run"]
    assert table.names == ["strain[%]", "force_top[N]", "elastic_energy[mJ]"]
    assert table.rows == [[0.0, 0.0, 0.0], [0.5, 2.5, 1e-3]]
    assert table_module.read_columns(path, ("elastic_energy", "strain")) == [[0.0, 0.0], [1e-3, 0.5]]


def test_malformed_tables_are_refused_naming_the_file_and_the_row(tmp_path):
    table_module = bench_scripts.load("curve_table")
    short = write(tmp_path, "strain[%],force_top[N]\n0,1\n0.1\n", "short.csv")
    assert refusal(lambda: table_module.read_table(short)) == (
        f"{short}: line 3 has 1 fields where the header has 2; name a curves.csv of rupture run")
    word = write(tmp_path, "strain[%],force_top[N]\n0,1\n0.1,x\n", "word.csv")
    assert refusal(lambda: table_module.read_table(word)).startswith(f"{word}: line 3, column 'force_top[N]': 'x' is not")
    assert "no header line" in refusal(lambda: table_module.read_table(write(tmp_path, "# only\n", "empty.csv")))
    assert "cannot read it" in refusal(lambda: table_module.read_table(tmp_path / "missing.csv"))
    good = write(tmp_path, "strain[%],force_top[N]\n0,1\n", "good.csv")
    assert refusal(lambda: table_module.read_columns(good, ("force",))).endswith(
        "no column 'force' (the header has strain, force_top); name another column or file")


def test_the_force_top_is_the_largest_window_mean_within_the_range():
    rows_module = bench_scripts.load("dense_rows")
    # A force rising to 1 at 0.4 % and a larger spike of fragments at 0.9 %, outside the range.
    rows = [[0.01 * i, 1.0 - abs(0.01 * i - 0.4), 0.0] for i in range(60)] + [[0.9, 5.0, 0.0]]
    means = rows_module.window_means(rows, 2)
    assert means[0] == pytest.approx([0.005, 0.605, 0.0])
    top = rows_module.force_top(means)
    assert means[top][0] == pytest.approx(0.395) or means[top][0] == pytest.approx(0.405)
    assert means[rows_module.force_top(means, 0.3, 1.0)][1] > 2.0
    assert rows_module.force_top(means, 1.0, 2.0) is None
    assert rows_module.parse_range("0.1,0.7") == (0.1, 0.7)
    assert "LOW must lie below HIGH" in refusal(lambda: rows_module.parse_range("0.7,0.1"))
    args = ["--width", "12", "a.csv"]
    assert rows_module.take_option(args, "--width", "40") == "12" and args == ["a.csv"]
    assert rows_module.take_option(args, "--width", "40") == "40"
    assert "at least 2" in refusal(lambda: rows_module.parse_rows("1", "--width"))

"""The scripts of bench/ as the tests beside this file load them: by path, since bench/ is no package
(bench/ goes on the module path, as it is for a script run from there, so that the scripts' shared
modules, curve_table and dense_rows, import)."""
import importlib.util
import pathlib
import sys

BENCH = pathlib.Path(__file__).resolve().parents[2] / "bench"
if str(BENCH) not in sys.path:
    sys.path.insert(0, str(BENCH))


def path(name):
    """bench/NAME.py."""
    return BENCH / f"{name}.py"


def load(name):
    """bench/NAME.py as a module, its main() not run."""
    spec = importlib.util.spec_from_file_location(name, path(name))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module

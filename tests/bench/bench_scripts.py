"""The scripts of bench/ as the tests beside this file load them: by path, since bench/ is no package."""
import importlib.util
import pathlib

BENCH = pathlib.Path(__file__).resolve().parents[2] / "bench"


def path(name):
    """bench/NAME.py."""
    return BENCH / f"{name}.py"


def load(name):
    """bench/NAME.py as a module, its main() not run."""
    spec = importlib.util.spec_from_file_location(name, path(name))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module

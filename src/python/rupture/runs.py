"""Tension tests from Python: `run(config)` with a dict or a TOML file, `--set`-style overrides, a
progress callback; Ctrl-C stops the run with a checkpoint and raises KeyboardInterrupt; `resume(folder)`
(or `rupture run --resume`) continues it.
"""
import json
import math
from pathlib import Path

from . import _rupture
from .folders import read_run


def config_reference():
    """Every run-config key with its unit, default and meaning (`rupture run --help-config`)."""
    return _rupture.config_reference()


def _toml_value(value, where):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise _rupture.InputError(f"config {where}: {value} is not a finite number; give a finite value")
        return repr(value)
    if isinstance(value, (str, Path)):
        return json.dumps(str(value))  # a TOML basic string: JSON's escapes are TOML's
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    raise _rupture.InputError(f"config {where}: a {type(value).__name__} is not a config value; "
                              "give a number, string, bool or list")


def _toml_text(config):
    lines = []
    for section, keys in config.items():
        if not isinstance(keys, dict):
            raise _rupture.InputError(f"config {section}: keys belong to sections, e.g. "
                                      "{'bonds': {'stiffness': 1e3}}")
        lines.append(f"[{section}]")
        lines += [f"{key} = {_toml_value(value, f'{section}.{key}')}" for key, value in keys.items()]
    return "\n".join(lines) + "\n"


def run(config, out=None, set=(), progress=None, overwrite=False, sample=None):
    """Runs a tension test and returns its Run (curves, breaks, run.json; `summary` is what the run
    said at the end).

    config: a dict of sections ({"sample": {"preset": "tissue-small"}, "bonds": {"stiffness": 1e3}})
      or the path of a TOML run config; every key: `config_reference()`.
    out: the run folder (else the config's output.folder).
    set: overrides "section.key=value", as `rupture run --set`.
    progress: called after each curve row with {"steps", "strain_percent", "force_N", "broken_bonds"}.
    overwrite: replace a run that ended in that folder (else it is refused, and kept).
    sample: a rupture.sample.Sample to run instead of the config's; saved beside the folder as
      OUT.rsample, so run.json names the file it ran.
    """
    overrides = [str(s) for s in set]
    if out is not None:
        overrides.append(f"output.folder={json.dumps(str(out))}")
    if isinstance(config, dict):
        config_file, text = "", _toml_text(config)
    else:
        config_file, text = str(config), ""
    if sample is not None:
        if out is None:
            raise _rupture.InputError("run: a sample object needs out=FOLDER (it is saved as FOLDER.rsample)")
        sample_file = Path(str(out).rstrip("/") + ".rsample").resolve()
        _rupture.sample_save(sample, str(sample_file))
        overrides += ['sample.preset=""', 'sample.lattice=""', f"sample.file={json.dumps(str(sample_file))}"]
    command = "python: rupture.run(" + (repr(config_file) if config_file else "{...}") + \
        "".join(f", set {o}" for o in overrides) + ")"
    summary = _rupture.run(config_file, text, overrides, command, bool(overwrite), progress)
    result = read_run(summary["folder"])
    result.summary = summary
    return result


def resume(folder, progress=None):
    """Continues an interrupted run (Ctrl-C, a kill, a full disk) from its newest checkpoint, as
    `rupture run --resume FOLDER`: the outputs come out byte-identical to an uninterrupted run.
    Returns its Run; `progress` and Ctrl-C work as in run()."""
    summary = _rupture.resume(str(folder), f"python: rupture.resume({str(folder)!r})", progress)
    result = read_run(summary["folder"])
    result.summary = summary
    return result

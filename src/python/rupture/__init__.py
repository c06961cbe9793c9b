"""rupture from Python: fiber bundle theory, bonded-particle tension tests and the precursor of failure.

    import rupture
    rupture.fbm.theory("weibull:k=2")               # the ELS maxima of a fiber bundle, as a dict
    s = rupture.sample.generate("tissue-small", seed=1)
    r = rupture.run({"sample": {"preset": "tissue-small"}}, out="run")
    a = rupture.analyze(r.curves)                    # x_p, x_c, delta_x with uncertainties and units
    rupture.read_scan("scan")                        # a scan's results.csv as a DataFrame

The numbers are those of the `rupture` command line, computed by the same C++ code; errors carry
its one-line messages (InputError is a ValueError, RunError a RuntimeError).
"""
from ._rupture import InputError, RunError, version as __version__
from . import fbm, sample
from .analysis import Analysis, Measured, analyze
from .folders import Run, read_curves, read_run, read_scan
from .runs import config_reference, resume, run

__all__ = ["Analysis", "InputError", "Measured", "Run", "RunError", "analyze", "config_reference", "fbm",
           "read_curves", "read_run", "read_scan", "resume", "run", "sample"]

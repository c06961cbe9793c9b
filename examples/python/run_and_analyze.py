"""A tension test and its precursor analysis in a dozen lines.  python3 run_and_analyze.py [FOLDER]"""
import sys

import rupture

folder = sys.argv[1] if len(sys.argv) > 1 else "block-run"
config = {"sample": {"lattice": "block", "lattice_cells": [4, 8, 2], "lattice_radius": 0.5},
          "bonds": {"stiffness": 1e3, "break_distance": 0.002},
          "loading": {"speed": 500.0, "ramp_steps": 500},
          "stop": {"extra_strain": 0.5, "max_strain": 20.0},
          "output": {"interval": 10}}
run = rupture.run(config, out=folder, overwrite=True)
analysis = rupture.analyze(run.curves)
print(run.summary["status"], run.summary["stop_reason"], f"{len(run.curves)} rows,",
      f"{run.summary['broken_bonds']} bonds broken")
print(analysis)

"""Bonded-particle samples: generate, load, save, or build one from your own arrays.

A Sample's arrays are numpy views into the sample itself (no copy): positions (n, 3) and radii in mm,
ids, groups (0 free, 1 glued to the bottom plate, 2 to the top one), bonds (m, 2) particle indices
i < j and rest_lengths in mm. x is across the width, y the loading direction, z the depth.
"""
import numpy as np

from . import _rupture

Sample = _rupture.Sample


def generate(preset="tissue-small", seed=1):
    """A generator preset ("tissue", "tissue-small", ...: `rupture sample generate --help`)."""
    return _rupture.sample_generate(preset, int(seed))


def load(path):
    """A sample file in any format rupture reads (.rsample, LAMMPS data, ESyS .geo, ...)."""
    return _rupture.sample_load(str(path))


def save(sample, path):
    """Writes the sample; the format follows the file name (.rsample, .data, .geo, .vtp)."""
    _rupture.sample_save(sample, str(path))


def from_arrays(positions, radii, groups=None, bonds=None, bond_tolerance=0.7, density=2.5e-4):
    """A sample from arrays: positions (n, 3) and radii (n,) in mm; bonds (m, 2) particle indices (rest
    lengths = the initial distances), or None to bond every pair whose gap is below bond_tolerance x
    their mean radius, as the generator does; groups (n,) 0/1/2, or None for the glue rule (particles
    within one smallest radius of the bottom or top face). density in g/mm^3."""
    return _rupture.sample_from_arrays(np.asarray(positions, dtype=float), np.asarray(radii, dtype=float),
                                       None if groups is None else np.asarray(groups, dtype=np.uint8),
                                       None if bonds is None else np.asarray(bonds, dtype=np.int64),
                                       float(bond_tolerance), float(density))

#!/usr/bin/env python3
"""Turns a LAMMPS data file written by `rupture sample convert` into the input of pull.in.

Usage: bin_bonds.py DATA_IN DATA_OUT COEFFS_OUT --types N --stiffness K --break-distance B

LAMMPS before its BPM package (Debian 12 ships the January 2022 release) has no per-bond rest
length: harmonic bonds take r0 from their bond type. With --types 0 every bond gets a type of its
own, so the rest lengths are exactly rupture's (the atoms' initial distances); but `fix bond/break`
takes one bond type per fix, so a run that breaks bonds needs few types: with --types N the rest
lengths are binned into N types of equal width, each with the mean rest length of its bonds, and
the sample starts slightly pre-stressed; the script prints by how much, against the break distance. It also rescales the density column from rupture's g/mm^3 to t/mm^3,
the mass unit of the deck's unit system (mm, t, s: forces in N, energies in mJ), and writes, for
each type, its `bond_coeff` (LAMMPS's harmonic K is k/2) and a `fix bond/break` at r0 + B
(rupture's absolute rule), into COEFFS_OUT and COEFFS_OUT's `.break` sibling.
Standard library only.
"""
import argparse
import math
import sys


def sections(lines):
    """The data file as (header lines, {section name: body lines})."""
    names = {"Atoms", "Bonds", "Velocities", "Masses"}
    header, body, current = [], {}, None
    for line in lines:
        word = line.split("#")[0].strip()
        if word in names:
            current = word
            body[current] = []
            continue
        if current is None:
            header.append(line)
        elif line.strip():
            body[current].append(line)
    return header, body


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data_in")
    parser.add_argument("data_out")
    parser.add_argument("coeffs_out")
    parser.add_argument("--types", type=int, required=True, help="bond types (rest-length bins); 0: one per bond, exact rest lengths")
    parser.add_argument("--stiffness", type=float, required=True, help="bond stiffness k (N/mm)")
    parser.add_argument("--break-distance", type=float, required=True, help="b_d (mm), absolute rule")
    args = parser.parse_args()
    with open(args.data_in) as f:
        lines = f.read().splitlines()
    header, body = sections(lines)
    if not lines[0].startswith("LAMMPS data file: rupture sample") or "Atoms" not in body or "Bonds" not in body:
        sys.exit(f"{args.data_in}: not a data file written by `rupture sample convert` (with bonds)")

    position, atoms = {}, []
    for line in body["Atoms"]:
        f = line.split()  # atom-ID atom-type x y z diameter density molecule-ID (hybrid sphere bond)
        position[f[0]] = tuple(float(v) for v in f[2:5])
        f[6] = repr(float(f[6]) * 1e-6)  # g/mm^3 -> t/mm^3
        atoms.append(" ".join(f))
    bonds = [line.split() for line in body["Bonds"]]
    rest = [math.dist(position[b[2]], position[b[3]]) for b in bonds]
    low, high = min(rest), max(rest)
    if args.types == 0:
        args.types = len(bonds)
        kind = list(range(len(bonds)))
        width = 0.0
    else:
        width = (high - low) / args.types or 1.0
        kind = [min(args.types - 1, int((r - low) / width)) for r in rest]
    sums, counts = [0.0] * args.types, [0] * args.types
    for r, t in zip(rest, kind):
        sums[t] += r
        counts[t] += 1
    r0 = [s / c if c else low + (t + 0.5) * width for t, (s, c) in enumerate(zip(sums, counts))]
    error = [abs(r - r0[t]) for r, t in zip(rest, kind)]

    out = []
    for line in header:
        out.append(f"{args.types} bond types" if line.strip().endswith("bond types") else line)
    out += ["Atoms # hybrid sphere bond", ""] + atoms + ["", "Bonds", ""]
    out += [f"{b[0]} {t + 1} {b[2]} {b[3]}" for b, t in zip(bonds, kind)]
    with open(args.data_out, "w") as f:
        f.write("\n".join(out) + "\n")
    with open(args.coeffs_out, "w") as f:
        for t in range(args.types):
            f.write(f"bond_coeff {t + 1} {args.stiffness / 2!r} {r0[t]!r}\n")
    with open(args.coeffs_out + ".break", "w") as f:
        for t in range(args.types):
            f.write(f"fix break{t + 1} all bond/break 1 {t + 1} {r0[t] + args.break_distance!r}\n")
    rms = math.sqrt(sum(e * e for e in error) / len(error))
    if width == 0.0:
        print(f"{len(bonds)} bonds, rest lengths {low:.4f}-{high:.4f} mm, one type per bond: exact rest lengths")
    else:
        print(f"{len(bonds)} bonds, rest lengths {low:.4f}-{high:.4f} mm in {args.types} types of "
              f"{width:.2e} mm: initial stretch error max {max(error):.2e} mm, rms {rms:.2e} mm "
              f"({100 * max(error) / args.break_distance:.1f} % and {100 * rms / args.break_distance:.1f} % "
              f"of the break distance)")


if __name__ == "__main__":
    main()

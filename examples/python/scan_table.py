"""A small scan read into pandas: delta_x against x_c of the accepted points.
python3 scan_table.py [SCAN_FOLDER]   (e.g. after `rupture scan examples/scan-block.toml`)"""
import sys

import rupture

scan = rupture.read_scan(sys.argv[1] if len(sys.argv) > 1 else "scan-block")
accepted = scan[(scan["status"] == "ok") & (scan["accepted[1]"] == 1)]
print(f"{len(scan)} points, {len(accepted)} accepted; units: x_c in {scan.attrs['units']['x_c[%]']}")
print(accepted[["k_n[N/mm]", "b_d[mm]", "x_c[%]", "delta_x[%]", "class"]].to_string(index=False))

#!/usr/bin/env python3
"""Writes a flat mmCIF of COPIES side-by-side copies of a PDB file's first biological assembly.

The 10 M-atom input of issue 15's memory measurement (docs/PERFORMANCE.md, "Ten million
atoms"): `bench/large_mmcif.py data/3J6R.pdb 10 /tmp/3j6r-x10.cif` writes the 60-operator
3J6R capsid ten times (10,328,400 atoms, about 0.9 GB). It is generated, never checked in.
Every copy of every operator gets its own chain (auth_asym_id = label_asym_id), so the file
reads as one flat model, as a deposited assembly file does.

Needs numpy (Debian's python3-numpy); formats rows in blocks so it writes ~10 M rows a minute.
"""
import sys

import numpy as np


def read_pdb(path):
    atoms, ops = [], {}
    with open(path) as f:
        for line in f:
            rec = line[:6]
            if rec in ("ATOM  ", "HETATM"):
                atoms.append((rec.strip(), line[12:16].strip(), line[17:20].strip(), line[21],
                              int(line[22:26]), float(line[30:38]), float(line[38:46]),
                              float(line[46:54]), line[76:78].strip() or line[12:14].strip()))
            elif line.startswith("REMARK 350   BIOMT"):
                row, num = int(line[18]) - 1, int(line[19:23])
                vals = [float(v) for v in line[23:].split()]
                ops.setdefault(num, np.zeros((3, 4)))[row] = vals
            elif rec == "ENDMDL":
                break
    return atoms, [ops[k] for k in sorted(ops)] or [np.hstack([np.eye(3), np.zeros((3, 1))])]


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: large_mmcif.py IN.pdb COPIES OUT.cif")
    atoms, ops = read_pdb(sys.argv[1])
    copies = int(sys.argv[2])
    xyz = np.array([a[5:8] for a in atoms])
    span = np.ptp(xyz, axis=0).max() * 1.1 + 20.0
    text = [f"{a[0]} {a[8]} {a[1]} {a[2]} " for a in atoms]  # group, element, atom, residue
    seq = [a[4] for a in atoms]
    with open(sys.argv[3], "w") as out:
        out.write("data_LARGE\n_struct.title 'generated: %d copies of %s'\nloop_\n"
                  % (copies, sys.argv[1]))
        for tag in ("group_PDB", "type_symbol", "label_atom_id", "label_comp_id", "id",
                    "label_alt_id", "label_asym_id", "auth_asym_id", "auth_seq_id",
                    "pdbx_PDB_ins_code", "Cartn_x", "Cartn_y", "Cartn_z", "occupancy",
                    "B_iso_or_equiv", "pdbx_PDB_model_num"):
            out.write(f"_atom_site.{tag}\n")
        serial = 1
        for c in range(copies):
            for k, op in enumerate(ops):
                p = xyz @ op[:, :3].T + op[:, 3] + np.array([c * span, 0.0, 0.0])
                rows = []
                for i, a in enumerate(atoms):
                    chain = f"{a[3]}{c * len(ops) + k}"
                    rows.append(f"{text[i]}{serial + i} . {chain} {chain} {seq[i]} ? "
                                f"{p[i, 0]:.3f} {p[i, 1]:.3f} {p[i, 2]:.3f} 1.00 0.00 1\n")
                out.write("".join(rows))
                serial += len(atoms)
    print(f"{sys.argv[3]}: {serial - 1} atoms")


if __name__ == "__main__":
    main()

// io/bonds.h — distance-based covalent bonds. Two atoms are bonded when their distance is
// below the sum of their covalent radii (io/elements.h) plus a tolerance. Found with a uniform
// grid in O(n), in parallel (oneTBB), with the same bonds in the same order for any thread
// count. Record bonds (CONECT / struct_conn) already in the Molecule are kept.
#pragma once

#include <cstddef>

#include "io/molecule.h"

namespace softmol::io {

struct BondOptions {
  float tolerance = 0.45f;  // Å added to the sum of the covalent radii
};

// Pairs that are never bonded by distance:
//  * atoms of different models, and pairs closer than 0.4 Å (overlapping duplicates);
//  * hydrogen to hydrogen;
//  * ions (kIon): metal coordination is not drawn as a covalent bond unless a record says so;
//  * a water atom with anything outside its own residue (waters bond only O-H inside).
// Alternate locations never meet: the reader keeps the first one only.
// Adds the new bonds (BondSource::kDistance) to mol, leaves bondA/bondB sorted by (A, B) and
// unique (a pair that is already there, from a record, keeps its source); returns how many
// bonds were added.
size_t ComputeDistanceBonds(Molecule& mol, const BondOptions& options = {});

}  // namespace softmol::io

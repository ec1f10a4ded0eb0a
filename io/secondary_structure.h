// io/secondary_structure.h — per-residue secondary structure (Residue::ss): from the file's
// records (PDB HELIX/SHEET, mmCIF struct_conf/struct_sheet_range, as ranges of residues), or,
// when the file has none, assigned from the CA trace alone with P-SEA (Labesse et al. 1997,
// "P-SEA: a new efficient assignment of secondary structure from Cα trace of proteins",
// CABIOS 13:291-295), the CA-only rule that also serves structures with no backbone N/O.
// The readers (io/structure_reader.h) call this; Molecule::secondaryStructureFromFile says
// which of the two set it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/molecule.h"

namespace softmol::io {

// One record: residues firstSeq/firstIcode .. lastSeq/lastIcode (inclusive, in file order) of
// the chain with author id `chain`, in every model. Insertion code ' ' = none.
struct SecondaryStructureRange {
  SecondaryStructure ss = SecondaryStructure::kCoil;
  std::string chain;
  int32_t firstSeq = 0, lastSeq = 0;
  char firstIcode = ' ', lastIcode = ' ';
};

// Sets Residue::ss of every residue a range covers (helices win over strands where records
// overlap). A range whose first or last residue is not in the molecule (unobserved residues,
// a broken record) marks nothing. Returns the number of residues marked.
size_t ApplySecondaryStructureRanges(const std::vector<SecondaryStructureRange>& ranges,
                                     Molecule& mol);

// P-SEA on the CA atoms of every amino-acid chain (broken where consecutive CA are more
// than kMaxCaGap apart, so no window spans a gap); every other residue is coil. Overwrites
// Residue::ss of all residues.
void AssignSecondaryStructureFromGeometry(Molecule& mol);

// Records if there are any (Molecule::secondaryStructureFromFile = true), else the geometric
// rule. What the readers call once the residues are built.
void SetSecondaryStructure(const std::vector<SecondaryStructureRange>& ranges, Molecule& mol);

// Consecutive CA of one chain farther apart than this are a chain break: the trans peptide
// CA-CA distance is 3.80 Å (cis 2.9 Å); 4.2 Å leaves room for poorly refined models.
inline constexpr double kMaxCaGap = 4.2;

// The atom named CA (element carbon, so a calcium ion named CA is not one) of an amino-acid
// residue (AtomFlags kPolymer), or UINT32_MAX.
uint32_t AlphaCarbon(const Molecule& mol, const Residue& residue);

}  // namespace softmol::io

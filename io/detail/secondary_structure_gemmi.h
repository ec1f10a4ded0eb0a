// io/detail/secondary_structure_gemmi.h — internal to io/: the helices and strands gemmi
// parsed (PDB HELIX/SHEET, mmCIF struct_conf/struct_sheet_range) as residue ranges
// (io/secondary_structure.h), for the readers.
#pragma once

#include <vector>

#include <gemmi/model.hpp>

#include "io/secondary_structure.h"

namespace softmol::io::detail {

std::vector<SecondaryStructureRange> SecondaryStructureRanges(const gemmi::Structure& structure);

}  // namespace softmol::io::detail

// io/structure_reader.h — reads a molecule from a PDB or mmCIF file (plain or gzipped) into
// the structure-of-arrays Molecule (io/molecule.h), through gemmi: atoms with element, name,
// residue, chain, flags, occupancy, B-factor and ANISOU; the first alternate location only;
// the first model (or all); record bonds (CONECT, LINK/SSBOND, struct_conn); and, on request,
// a biological assembly built from BIOMT / _pdbx_struct_assembly_gen. Distance bonds are
// separate (io/bonds.h). Every bad input throws InputError naming the file and, where known,
// the line.
#pragma once

#include <string>
#include <string_view>

#include "io/molecule.h"

namespace softmol::io {

struct ReadOptions {
  std::string assembly;    // "" = asymmetric unit; else an id of Molecule::assemblyIds
  bool allModels = false;  // default: first model only (modelCount still counts them all)
};

enum class StructureFormat { kAuto, kPdb, kMmcif };

// Reads `path`. The format comes from the extension (.pdb/.ent/.cif/.mmcif, each optionally
// .gz), else from the content. Throws InputError for a missing, unreadable, empty, binary,
// truncated or malformed file, non-finite coordinates, a file with no atoms, or an unknown
// assembly id (the message lists the ids the file defines). Unknown elements are not an
// error: they get Element(0) and one warning line on stderr.
Molecule ReadMolecule(const std::string& path, const ReadOptions& options = {});

// Same as ReadMolecule, from bytes already in memory (uncompressed); `name` is the file name
// used in messages and in Molecule::sourcePath. Used by the fuzzers and tests.
Molecule ReadMoleculeFromMemory(std::string_view bytes, const std::string& name,
                                StructureFormat format = StructureFormat::kAuto,
                                const ReadOptions& options = {});

}  // namespace softmol::io

// io/molecule.h — the in-memory molecule: atoms as structure-of-arrays (no per-atom
// allocation, room for 10 million atoms), with residue and chain tables and a bond list.
// Built by ReadMolecule (io/structure_reader.h) from PDB or mmCIF; positions of later frames
// come from io/trajectory.h. Units are Ångström; positions are double so that a structure far
// from the origin keeps its precision until the camera makes it relative (DESIGN.md).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace softmol::io {

// Per-atom flags (Molecule::flags).
enum AtomFlags : uint8_t {
  kHetatm = 1 << 0,      // HETATM record (or group_PDB HETATM)
  kWater = 1 << 1,       // residue is water (HOH, WAT, DOD, SOL, TIP3, ...)
  kIon = 1 << 2,         // single-atom residue of a metal or halide ion (NA, CL, MG, ZN, ...)
  kHydrogen = 1 << 3,    // element H or D
  kHasAnisou = 1 << 4,   // Molecule::anisou holds this atom's tensor
  kPolymer = 1 << 5,     // standard amino-acid or nucleotide residue
};

// Secondary structure of a residue: from the file's HELIX/SHEET records (mmCIF struct_conf /
// struct_sheet_range), else assigned from the CA trace (io/secondary_structure.h).
enum class SecondaryStructure : uint8_t { kCoil = 0, kHelix = 1, kSheet = 2 };

// A residue: consecutive atoms of one chain with the same number and insertion code.
struct Residue {
  std::array<char, 8> name{};  // NUL-padded residue name, e.g. "ALA", "HOH", "ATP"
  int32_t seqNum = 0;          // author residue number
  char insertionCode = ' ';
  uint32_t chainIndex = 0;     // into Molecule::chains
  uint32_t firstAtom = 0;      // atoms [firstAtom, firstAtom + atomCount)
  uint32_t atomCount = 0;
  SecondaryStructure ss = SecondaryStructure::kCoil;
};

struct Chain {
  std::string name;        // author chain id ("A"; assembly copies get "A-2", ...)
  uint32_t modelIndex = 0;
};

// The coordinate range softmol accepts, in Å. A coordinate beyond ±1e6 Å is a placeholder
// or a corrupt file (the largest assemblies span ~1e4 Å; floats relative to the camera keep
// 0.06 Å there): readers refuse it as bad input, naming the file and the line (PDB) or the atom
// (mmCIF, assemblies, trajectory frames), instead of rendering an empty image.
constexpr double kMaxCoordinate = 1e6;

enum class BondSource : uint8_t { kRecord = 0, kDistance = 1 };

struct Molecule {
  std::string sourcePath;  // the file it was read from
  std::string title;

  // ---- atoms, structure of arrays; every vector has atomCount() entries ----
  std::vector<double> x, y, z;                  // Å
  std::vector<float> vdwRadius;                 // Å, from the element table (io/elements.h)
  std::vector<uint32_t> color;                  // sRGB 0xRRGGBB from the element table
  std::vector<uint8_t> element;                 // atomic number, 0 = unknown
  std::vector<uint8_t> flags;                   // AtomFlags
  std::vector<std::array<char, 4>> atomName;    // NUL-padded, e.g. "CA", "OXT"
  std::vector<float> occupancy, bFactor;
  std::vector<uint32_t> residueIndex;           // into residues
  std::vector<uint16_t> modelIndex;             // 0-based model the atom comes from
  std::vector<uint32_t> serial;                 // atom serial number of the file (for CONECT)
  // ANISOU U tensor (Å²) in PDB order U11 U22 U33 U12 U13 U23; empty when no atom has one,
  // else atomCount() entries (zeros where the atom has none, see kHasAnisou).
  std::vector<std::array<float, 6>> anisou;

  std::vector<Residue> residues;
  std::vector<Chain> chains;
  uint32_t modelCount = 1;  // models in the file (frames of a multi-model trajectory)
  // Where Residue::ss comes from: the file's records, or the CA-geometry rule (P-SEA) because
  // the file has none.
  bool secondaryStructureFromFile = false;

  // ---- bonds, structure of arrays ----
  std::vector<uint32_t> bondA, bondB;   // atom indices, bondA < bondB, sorted, unique
  std::vector<BondSource> bondSource;

  // Biological assemblies the file defines (ids usable with the assembly option).
  std::vector<std::string> assemblyIds;

  size_t atomCount() const { return x.size(); }
  size_t bondCount() const { return bondA.size(); }
};

}  // namespace softmol::io

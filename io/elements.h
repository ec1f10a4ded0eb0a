// io/elements.h — the periodic table softmol draws with: for every element 1..118 its symbol,
// van der Waals radius (what spacefill draws), covalent radius (what distance bonds use) and
// CPK/Jmol color. Also the PDB rules that infer an element from an atom name when a file
// leaves the element column blank. Sources of every number are in io/elements.cpp.
#pragma once

#include <cstdint>
#include <string_view>

namespace softmol::io {

struct ElementInfo {
  const char* symbol;    // "C", "Fe"; "X" for unknown
  float vdwRadius;       // Å
  float covalentRadius;  // Å (single bond)
  uint32_t color;        // sRGB 0xRRGGBB
};

// Atomic number of the highest element in the table.
inline constexpr uint8_t kMaxElement = 118;

// Element(0) and any number above kMaxElement is the unknown element: a carbon-sized
// sphere (vdW 1.70 Å, covalent 0.77 Å) in neutral grey 0x808080, symbol "X".
const ElementInfo& Element(uint8_t atomicNumber);

// Atomic number of a symbol, case-insensitive ("C", "FE", "fe", "Fe"); surrounding spaces
// are ignored; "D" (deuterium) and "T" (tritium) give 1. Unknown or empty: 0.
uint8_t ElementFromSymbol(std::string_view symbol);

// Element from an atom name, following the PDB format's atom-name convention
// (wwPDB format v3.3, ATOM record, columns 13-16). `atomName` is either the raw 4-column
// field with its padding (" CA ", "CA  ", "1HB ", "HG21") or a trimmed name ("CA").
//  1. a single-atom residue whose name is an element (ions: "ZN", "CL", "NA") is that element;
//  2. a leading digit ("1HB ", "2HG1") means the element is the next letter (old H naming);
//  3. in a padded name, column 13 blank means a one-letter element in column 14 (" CA " = C),
//     column 13 set means a two-letter element in 13-14 ("CA  " = Ca, "FE  " = Fe),
//     except 4-character names starting with H, which are hydrogens ("HG21");
//  4. a trimmed name gives the one-letter element of its first letter ("CA" = C), since the
//     alignment that told Ca from C-alpha is lost.
// Returns 0 when nothing matches.
uint8_t InferElement(std::string_view atomName, std::string_view residueName);

}  // namespace softmol::io

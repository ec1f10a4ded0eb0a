// io/selection.h — a small selection language in the spirit of PyMOL's, used by --highlight
// and per-selection styles. ParseSelection turns text into a Selection (an AST); Evaluate
// marks the atoms of a Molecule it selects.
//
//   all  none  hetatm  protein  nucleic  water  ion  ligand  hydrogen  polymer
//   chain A[+B...]     resn ATP[+ADP...]      name CA[+CB...]     elem C[+N...]
//   resi 10-20 | resi 5 | resi 5+7+10-12     (author residue numbers; "-3--1" is a range)
//   within 5 of <selection>                 (atoms within 5 Å of it, same model, itself too)
//   not X    X and Y    X or Y    ( X )
// Precedence: `not` and `within D of` (prefix) > `and` > `or`; so
// `within 5 of resn ATP and chain A` is `(within 5 of resn ATP) and chain A`.
// Keywords, residue, atom and element names are case-insensitive; chain names are not.
// `ligand` is a HETATM atom that is not water or an ion; `protein` an amino-acid residue.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/error.h"
#include "io/molecule.h"

namespace softmol::io {

struct Selection {
  enum class Kind : uint8_t {
    kAll, kNone, kHetatm, kProtein, kNucleic, kWater, kIon, kLigand, kHydrogen, kPolymer,
    kChain, kResn, kName, kElem, kResi, kWithin, kNot, kAnd, kOr
  };
  struct Node {
    Kind kind = Kind::kAll;
    int lhs = -1, rhs = -1;                          // child nodes (kNot/kWithin: lhs only)
    std::vector<std::string> words;                  // kChain/kResn/kName (upper-cased but chain)
    std::vector<uint8_t> elements;                   // kElem: atomic numbers
    std::vector<std::pair<int32_t, int32_t>> ranges; // kResi: inclusive
    double distance = 0;                             // kWithin, Å
  };
  std::string text;         // the source text
  std::vector<Node> nodes;  // children precede parents
  int root = -1;
};

// Throws InputError with file "selection", line 1 and the column of the offending word, e.g.
// "selection:1:6: expected a number after 'resi', found 'x'".
Selection ParseSelection(std::string_view text);
// The same for a selection given as an option value or scene key: errors name `where` (the
// flag or the file and key) and the column inside the selection.
Selection ParseSelection(std::string_view text, const SourceLocation& where);

// 1 for every selected atom, 0 otherwise; atomCount() entries. Parallel (oneTBB), with the
// same result for any thread count.
std::vector<uint8_t> Evaluate(const Selection& selection, const Molecule& mol);

}  // namespace softmol::io

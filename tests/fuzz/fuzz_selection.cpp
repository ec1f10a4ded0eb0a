// tests/fuzz/fuzz_selection.cpp — libFuzzer target for the selection language
// (io/selection.h): any text parses or throws InputError with a column inside the text (or
// one past its end); what parses evaluates on a small built-in molecule without crashing.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "io/error.h"
#include "io/selection.h"
#include "io/structure_reader.h"

namespace {

const softmol::io::Molecule& Small() {
  static const softmol::io::Molecule mol = softmol::io::ReadMoleculeFromMemory(
      "ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00  0.00           N\n"
      "ATOM      2  CA  ALA A   1       1.450   0.000   0.000  1.00  0.00           C\n"
      "ATOM      3  C   ALA A   1       2.000   1.400   0.000  1.00  0.00           C\n"
      "ATOM      4  N   GLY B  -2       3.300   1.600   0.000  1.00  0.00           N\n"
      "HETATM    5  O   HOH W 100       5.000   5.000   5.000  1.00  0.00           O\n"
      "HETATM    6 ZN    ZN Z 200      -4.000   0.000   0.000  1.00  0.00          ZN\n"
      "HETATM    7  C1  ATP L 300       1.000   2.000   3.000  1.00  0.00           C\n",
      "small.pdb");
  return mol;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace softmol::io;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const Selection selection = ParseSelection(text);
    const auto mask = Evaluate(selection, Small());
    if (mask.size() != Small().atomCount()) std::abort();
  } catch (const InputError& e) {
    if (e.where().column < 1 || size_t(e.where().column) > size + 1) std::abort();
  }
  return 0;
}

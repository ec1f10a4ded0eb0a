// io/structure_reader_cif.h — internal to io/structure_reader.cpp: mmCIF text -> gemmi
// structures, with the atoms streamed in chunks. In its own translation unit because
// gemmi/cif.hpp does not compile as C++20 with clang 14 + libstdc++ 12 (std::vector of the
// incomplete gemmi::cif::Item), so the clang builds (fuzz preset) compile this one file as
// C++17 (io/CMakeLists.txt). Everything else, gemmi's PDB reader included, stays C++20, where
// left shifts of negative residue numbers in gemmi's hashes are defined behaviour.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gemmi/model.hpp>

namespace softmol::io::detail {

// Receives the atoms of the file a chunk at a time, in file order: a structure with models,
// chains and residues but no file-level records. A chunk ends where a residue does, so no
// residue is split between two chunks; a chain can be.
using AtomChunkSink = std::function<void(const gemmi::Structure& chunk)>;

// Everything of the first data block but its atoms.
struct MmcifContent {
  gemmi::Structure records;  // title, assemblies, connections, helices, sheets; no models
  // _atom_site_anisotrop: (atom serial, U11 U22 U33 U12 U13 U23 in Å²), in no particular order.
  std::vector<std::pair<int, std::array<float, 6>>> anisou;
};

// Parses mmCIF `text` with gemmi's grammar and gemmi's actions, except that the first block's
// _atom_site rows go to `onAtoms` in chunks of about 65 k rows instead of into the document.
// gemmi's document holds every value as a std::string (~32 bytes each, ~20 per atom), so
// parsing a 10 M-atom file whole would hold ~7 GB; chunked, it holds one chunk. Throws
// InputError (naming `name`, with the line where gemmi gives one) for any syntax or content
// error.
MmcifContent ParseMmcif(std::string_view text, const std::string& name,
                        const AtomChunkSink& onAtoms);

}  // namespace softmol::io::detail

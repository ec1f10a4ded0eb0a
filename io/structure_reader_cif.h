// io/structure_reader_cif.h — internal to io/structure_reader.cpp: mmCIF text -> gemmi
// Structure. In its own translation unit because gemmi/cif.hpp does not compile as C++20
// with clang 14 + libstdc++ 12 (std::vector of the incomplete gemmi::cif::Item), so the
// clang builds (fuzz preset) compile this one file as C++17 (io/CMakeLists.txt). Everything
// else, gemmi's PDB reader included, stays C++20, where left shifts of negative residue
// numbers in gemmi's hashes are defined behaviour.
#pragma once

#include <string>
#include <string_view>

#include <gemmi/model.hpp>

namespace softmol::io::detail {

// Parses mmCIF `text` and builds the structure from its first block. Throws InputError
// (naming `name`, with the line where gemmi gives one) for any syntax or content error.
gemmi::Structure ParseMmcif(std::string_view text, const std::string& name);

}  // namespace softmol::io::detail

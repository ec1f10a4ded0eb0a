// io/structure_reader_cif.cpp — mmCIF parsing through gemmi (see structure_reader_cif.h for
// why it is a file of its own). Keep it C++17-clean.
#include "io/structure_reader_cif.h"

#include <cstdlib>
#include <exception>

#include <gemmi/cif.hpp>
#include <gemmi/mmcif.hpp>

#include "io/error.h"

namespace softmol::io::detail {
namespace {

// gemmi's CIF messages start with "name:line:column: "; keep the line, drop the prefix so
// the file is not named twice.
InputError FromGemmi(const std::string& name, const std::string& message) {
  std::string rest = message;
  if (!name.empty() && rest.rfind(name, 0) == 0) {
    rest.erase(0, name.size());
    while (!rest.empty() && (rest[0] == ':' || rest[0] == ' ')) rest.erase(0, 1);
  }
  long line = 0;
  char* end = nullptr;
  const long parsed = std::strtol(rest.c_str(), &end, 10);
  if (end != rest.c_str() && *end == ':' && parsed > 0) {
    line = parsed;
    rest.erase(0, size_t(end - rest.c_str()) + 1);
    // drop the column too ("19: unterminated ..."), it is not always right for CIF values
    const long column = std::strtol(rest.c_str(), &end, 10);
    if (end != rest.c_str() && *end == ':' && column >= 0) rest.erase(0, size_t(end - rest.c_str()) + 1);
    while (!rest.empty() && rest[0] == ' ') rest.erase(0, 1);
  }
  return InputError(SourceLocation(name, line), rest);
}

}  // namespace

gemmi::Structure ParseMmcif(std::string_view text, const std::string& name) {
  try {
    const gemmi::cif::Document doc = gemmi::cif::read_memory(text.data(), text.size(),
                                                             name.c_str());
    if (doc.blocks.empty()) throw InputError(SourceLocation(name), "no data block: not an mmCIF file");
    gemmi::Structure st = gemmi::make_structure(doc);
    // gemmi skips an _atom_site table that lacks a column it needs; say which ones.
    if (st.models.empty() && doc.blocks[0].has_tag("_atom_site.Cartn_x"))
      throw InputError(SourceLocation(name),
                       "_atom_site lacks a required column (id, type_symbol, label_alt_id, "
                       "label_asym_id, Cartn_x, Cartn_y, Cartn_z, occupancy, "
                       "B_iso_or_equiv, auth_seq_id)");
    return st;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw FromGemmi(name, e.what());
  }
}

}  // namespace softmol::io::detail

// io/structure_reader_cif.cpp — mmCIF parsing through gemmi, the atoms streamed in chunks (see
// structure_reader_cif.h for why, and for why it is a file of its own). Keep it C++17-clean.
#include "io/structure_reader_cif.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iterator>

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


// ---------------------------------------------------------------------------------------
// Streaming the _atom_site loop.

namespace cif = gemmi::cif;
namespace pegtl = tao::pegtl;

constexpr size_t kRowsPerChunk = size_t(1) << 16;

bool StartsWithNoCase(const std::string& s, const char* prefix) {
  const size_t n = std::strlen(prefix);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

int FindColumn(const cif::Loop& loop, const char* tag) {  // tag in lower case
  for (size_t i = 0; i < loop.tags.size(); ++i)
    if (loop.tags[i].size() == std::strlen(tag) && StartsWithNoCase(loop.tags[i], tag))
      return int(i);
  return -1;
}

// The columns that tell gemmi's make_structure a new residue begins: model, chain (auth, else
// label), author residue number and insertion code. Empty when the loop lacks the chain or the
// number: gemmi refuses such a table, and the loop is then parsed whole (the error is the same).
std::vector<int> ResidueKeyColumns(const cif::Loop& loop) {
  int chain = FindColumn(loop, "_atom_site.auth_asym_id");
  if (chain < 0) chain = FindColumn(loop, "_atom_site.label_asym_id");
  const int number = FindColumn(loop, "_atom_site.auth_seq_id");
  if (chain < 0 || number < 0) return {};
  std::vector<int> key{chain, number};
  for (const char* tag : {"_atom_site.pdbx_pdb_model_num", "_atom_site.pdbx_pdb_ins_code"})
    if (const int c = FindColumn(loop, tag); c >= 0) key.push_back(c);
  return key;
}

// gemmi's Document, plus the state of the _atom_site loop being streamed.
struct StreamingDocument : cif::Document {
  const AtomChunkSink* onAtoms = nullptr;
  const std::string* name = nullptr;
  cif::Loop* atoms = nullptr;   // the first block's _atom_site loop while it is parsed
  std::vector<int> residueKey;  // ResidueKeyColumns(*atoms)
  bool streamed = false;        // some chunk went to onAtoms
};

InputError MissingAtomColumn(const std::string& name) {
  // gemmi skips an _atom_site table that lacks a column it needs; say which ones.
  return InputError(SourceLocation(name),
                    "_atom_site lacks a required column (id, type_symbol, label_alt_id, "
                    "label_asym_id, Cartn_x, Cartn_y, Cartn_z, occupancy, "
                    "B_iso_or_equiv, auth_seq_id)");
}

// Moves the first `rows` rows of the streamed loop into a one-loop block, builds them with
// gemmi's make_structure and hands them on.
void FlushRows(StreamingDocument& doc, size_t rows) {
  cif::Loop& loop = *doc.atoms;
  const auto end = loop.values.begin() + std::ptrdiff_t(rows * loop.tags.size());
  cif::Block chunk("atoms");
  chunk.items.emplace_back(cif::LoopArg{});
  cif::Loop& out = chunk.items.back().loop;
  out.tags = loop.tags;
  out.values.assign(std::make_move_iterator(loop.values.begin()), std::make_move_iterator(end));
  loop.values.erase(loop.values.begin(), end);
  const gemmi::Structure st = gemmi::make_structure_from_block(chunk);
  if (st.models.empty()) throw MissingAtomColumn(*doc.name);
  doc.streamed = true;
  (*doc.onAtoms)(st);
}

bool SameResidue(const cif::Loop& loop, const std::vector<int>& key, size_t rowA, size_t rowB) {
  const size_t width = loop.tags.size();
  for (const int c : key)
    if (loop.values[rowA * width + size_t(c)] != loop.values[rowB * width + size_t(c)])
      return false;
  return true;
}

// gemmi's actions for every rule; two of them also drive the streaming.
template <typename Rule>
struct StreamAction : cif::Action<Rule> {};

template <>
struct StreamAction<cif::rules::loop_value> {
  template <typename Input>
  static void apply(const Input& in, StreamingDocument& doc) {
    cif::Action<cif::rules::loop_value>::apply(in, doc);
    cif::Loop& loop = doc.items_->back().loop;
    if (loop.values.size() == 1 && doc.blocks.size() == 1 && doc.items_ == &doc.blocks[0].items &&
        StartsWithNoCase(loop.tags[0], "_atom_site.")) {
      doc.residueKey = ResidueKeyColumns(loop);
      doc.atoms = doc.residueKey.empty() ? nullptr : &loop;
    }
    if (doc.atoms != &loop || loop.values.size() % loop.tags.size() != 0) return;
    // A full row just ended. Past a chunk's worth, cut before it if it starts a residue.
    const size_t rows = loop.values.size() / loop.tags.size();
    if (rows > kRowsPerChunk && !SameResidue(loop, doc.residueKey, rows - 2, rows - 1))
      FlushRows(doc, rows - 1);
  }
};

template <>
struct StreamAction<cif::rules::loop> {
  template <typename Input>
  static void apply(const Input& in, StreamingDocument& doc) {
    cif::Action<cif::rules::loop>::apply(in, doc);  // checks the loop's value count
    cif::Loop& loop = doc.items_->back().loop;
    if (doc.atoms != &loop) return;
    FlushRows(doc, loop.values.size() / loop.tags.size());
    doc.atoms = nullptr;
  }
};

MmcifContent Parse(std::string_view text, const std::string& name, const AtomChunkSink& onAtoms) {
  StreamingDocument doc;
  doc.source = name;
  doc.onAtoms = &onAtoms;
  doc.name = &name;
  pegtl::memory_input<> in(text.data(), text.size(), name.c_str());
  pegtl::parse<cif::rules::file, StreamAction, cif::Errors>(in, doc);
  cif::check_for_missing_values(doc);
  cif::check_for_duplicates(doc);
  if (doc.blocks.empty()) throw InputError(SourceLocation(name), "no data block: not an mmCIF file");

  MmcifContent content;
  content.records = gemmi::make_structure_from_block(doc.blocks[0]);
  // Atoms left in the block: an _atom_site written as pairs (one atom) or a loop that could not
  // be streamed.
  if (!content.records.models.empty()) {
    onAtoms(content.records);
    content.records.models.clear();
  } else if (!doc.streamed && doc.blocks[0].has_tag("_atom_site.Cartn_x")) {
    throw MissingAtomColumn(name);
  }
  for (const auto& [id, u] : gemmi::impl::get_anisotropic_u(doc.blocks[0]))
    content.anisou.emplace_back(gemmi::string_to_int(id, false), u.elements_pdb());
  return content;
}

}  // namespace

MmcifContent ParseMmcif(std::string_view text, const std::string& name,
                        const AtomChunkSink& onAtoms) {
  try {
    return Parse(text, name, onAtoms);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw FromGemmi(name, e.what());
  }
}

}  // namespace softmol::io::detail

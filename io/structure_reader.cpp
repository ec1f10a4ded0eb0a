// io/structure_reader.cpp — PDB / mmCIF -> Molecule through gemmi.
//
// gemmi parses; this file adds what gemmi 0.5.7 does not do for us:
//  * gzip is inflated here with zlib (not gemmi::MaybeGzipped), because gzread accepts a
//    truncated stream silently and we must report it;
//  * PDB coordinates are validated here before gemmi sees them: gemmi's fixed-column number
//    reader turns "abc" or "nan" into some number without complaint, so a pre-scan checks that
//    columns 31-54 of every ATOM/HETATM record hold finite numbers and names the line;
//  * CONECT records are read here (gemmi's PDB reader skips them);
//  * assemblies are built here straight into the structure of arrays: gemmi::make_assembly
//    would copy 1 M gemmi::Atom objects (each with a std::string) for 3J6R, where copying
//    the SoA columns with a transform is bound by first-touch of the new memory (~0.2 s).
#include "io/structure_reader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <zlib.h>

#include <gemmi/pdb.hpp>
#include <gemmi/resinfo.hpp>

#include "io/detail/secondary_structure_gemmi.h"
#include "io/elements.h"
#include "io/error.h"
#include "io/structure_reader_cif.h"

namespace softmol::io {
namespace {

// ---------------------------------------------------------------------------------------
// Bytes in: plain or gzip, from disk or memory.

bool IsGzip(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// Inflates every gzip member of `bytes`. A stream that ends before its trailer is an error:
// that is what a truncated download looks like.
constexpr size_t kMaxInflated = size_t(4) << 30;  // a PDB/mmCIF text beyond this is not real
// A gzip bomb is refused as it inflates, not after: PDB and mmCIF text deflates 3-10× (even a
// file of near-identical records stays far below 100×), gzip itself tops out at 1032×. Past
// kBombCheckFrom bytes of output, more than kMaxRatio output bytes per input byte consumed so
// far is a bomb: refused with at most ~kBombCheckFrom bytes held (5.8 MB → 6 GB: 16 MiB, 0.1 s).
constexpr size_t kMaxRatio = 256;
constexpr size_t kBombCheckFrom = size_t(16) << 20;

std::string Gunzip(std::string_view bytes, const std::string& name) {
  std::string out;
  z_stream zs{};
  // 15 + 16: gzip wrapper only (we only come here after seeing the gzip magic bytes).
  if (inflateInit2(&zs, 15 + 16) != Z_OK)
    throw InputError(SourceLocation(name), "cannot initialise the gzip decoder");
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  zs.avail_in = static_cast<uInt>(bytes.size());
  std::vector<char> chunk(1 << 16);
  int rc = Z_OK;
  for (;;) {
    zs.next_out = reinterpret_cast<Bytef*>(chunk.data());
    zs.avail_out = static_cast<uInt>(chunk.size());
    rc = inflate(&zs, Z_NO_FLUSH);
    out.append(chunk.data(), chunk.size() - zs.avail_out);
    if (out.size() > kMaxInflated) {
      inflateEnd(&zs);
      throw InputError(SourceLocation(name), "gzip data inflates to more than 4 GiB");
    }
    const size_t consumed = size_t(zs.next_in - reinterpret_cast<const Bytef*>(bytes.data()));
    if (out.size() > kBombCheckFrom && out.size() > kMaxRatio * std::max<size_t>(consumed, 1)) {
      inflateEnd(&zs);
      throw InputError(SourceLocation(name),
                       "gzip data inflates more than " + std::to_string(kMaxRatio) + "× (" +
                           std::to_string(consumed) + " bytes to " + std::to_string(out.size()) +
                           " so far): not a molecule file (a gzip bomb?)");
    }
    if (rc == Z_STREAM_END) {
      if (zs.avail_in == 0) break;
      // Another gzip member follows (concatenated .gz files are valid gzip).
      if (!IsGzip(std::string_view(reinterpret_cast<const char*>(zs.next_in), zs.avail_in)))
        break;  // trailing garbage after a complete member: ignored, as gzip(1) does
      inflateReset(&zs);
      continue;
    }
    if (rc != Z_OK) break;
    if (zs.avail_in == 0 && zs.avail_out != 0) break;  // input exhausted mid-stream
  }
  const std::string message = zs.msg ? zs.msg : "";
  inflateEnd(&zs);
  if (rc != Z_STREAM_END) {
    if (rc == Z_OK || rc == Z_BUF_ERROR)
      throw InputError(SourceLocation(name), "gzip data is truncated (the file ends before the "
                               "compressed stream does)");
    throw InputError(SourceLocation(name), "gzip data is corrupt" + (message.empty() ? "" : ": " + message));
  }
  return out;
}

std::string ReadFileBytes(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw InputError(SourceLocation(path), "cannot open file: no such file or directory");
  if (fs::is_directory(status))
    throw InputError(SourceLocation(path), "is a directory, not a PDB or mmCIF file");
  // A FIFO or a device (/dev/zero) could block or never end: only regular files are read.
  if (!fs::is_regular_file(status))
    throw InputError(SourceLocation(path), "is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation(path), std::string("cannot open file: ") + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(SourceLocation(path), "read error");
  return bytes;
}

// ---------------------------------------------------------------------------------------
// Text checks shared by both formats.

std::string_view TrimView(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// PDB and mmCIF are text: a NUL or a control character other than tab/CR/LF/FF/VT means the
// file is something else (an image, a compressed file under the wrong name, a DCD...).
void CheckIsText(std::string_view text, const std::string& name) {
  if (TrimView(text).empty()) throw InputError(SourceLocation(name), "file is empty");
  long line = 1;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') {
      ++line;
    } else if (c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", c);
      throw InputError(SourceLocation(name, line), std::string("binary data (byte ") + hex +
                                         "): not a PDB or mmCIF text file");
    }
  }
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(),
                                                suffix) == 0;
}

StructureFormat DetectFormat(const std::string& name, std::string_view text) {
  std::string lower = Lower(name);
  if (EndsWith(lower, ".gz")) lower.resize(lower.size() - 3);
  if (EndsWith(lower, ".pdb") || EndsWith(lower, ".ent") || EndsWith(lower, ".pdb1"))
    return StructureFormat::kPdb;
  if (EndsWith(lower, ".cif") || EndsWith(lower, ".mmcif")) return StructureFormat::kMmcif;
  // By content: an mmCIF file starts (after comments) with a data_ block header.
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = TrimView(text.substr(pos, end - pos));
    if (!line.empty() && line[0] != '#')
      return Lower(std::string(line.substr(0, 5))) == "data_" ? StructureFormat::kMmcif
                                                              : StructureFormat::kPdb;
    pos = end + 1;
  }
  return StructureFormat::kPdb;
}

// gemmi's PDB messages may start with "Problem in line 12: "; that line goes into the
// location (where it reads "file.pdb:12: ...") instead of staying in the text.
InputError FromGemmiPdb(const std::string& name, const std::string& message) {
  static const std::string kPrefix = "Problem in line ";
  if (message.rfind(kPrefix, 0) == 0) {
    char* end = nullptr;
    const long line = std::strtol(message.c_str() + kPrefix.size(), &end, 10);
    if (line > 0 && end[0] == ':') {
      const char* rest = end + 1;
      while (*rest == ' ') ++rest;
      return InputError(SourceLocation(name, line), rest);
    }
  }
  return InputError(SourceLocation(name), message);
}

// ---------------------------------------------------------------------------------------
// PDB pre-scan: coordinates and CONECT.

struct PdbScan {
  std::vector<std::pair<uint32_t, uint32_t>> conect;  // serial pairs
  std::vector<long> conectLine;                       // the line of each pair
};

bool RecordIs(std::string_view line, const char* record4) {
  if (line.size() < 4) return false;
  for (int i = 0; i < 4; ++i)
    if (std::toupper(static_cast<unsigned char>(line[i])) != record4[i]) return false;
  return true;
}

void ParseCoordinate(std::string_view line, size_t begin, const char* axis,
                     const std::string& name, long lineNumber) {
  const std::string_view field = line.substr(begin, 8);
  size_t lead = 0;
  while (lead < field.size() && field[lead] == ' ') ++lead;
  const std::string text(TrimView(field));
  const int column = static_cast<int>(begin + lead + 1);
  if (text.empty())
    throw InputError(SourceLocation(name, lineNumber, static_cast<int>(begin + 1)),
                     std::string(axis) + " coordinate is missing (columns " +
                         std::to_string(begin + 1) + "-" + std::to_string(begin + 8) + ")");
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size())
    throw InputError(SourceLocation(name, lineNumber, column),
                     std::string(axis) + " coordinate is not a number: '" + text + "'");
  if (!std::isfinite(value))
    throw InputError(SourceLocation(name, lineNumber, column),
                     std::string(axis) + " coordinate is not finite: '" + text + "'");
  if (std::fabs(value) > kMaxCoordinate)
    throw InputError(SourceLocation(name, lineNumber, column),
                     std::string(axis) + " coordinate " + text + " is beyond ±1e6 Å");
}

PdbScan ScanPdb(std::string_view text, const std::string& name) {
  PdbScan scan;
  size_t pos = 0;
  long lineNumber = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.size() > 120) line = line.substr(0, 120);  // gemmi reads at most 120 columns
    if (RecordIs(line, "ATOM") || RecordIs(line, "HETA")) {
      if (line.size() < 54)
        throw InputError(SourceLocation(name, lineNumber),
                         "ATOM/HETATM record is too short (" + std::to_string(line.size()) +
                             " columns; the coordinates are in columns 31-54): truncated?");
      ParseCoordinate(line, 30, "x", name, lineNumber);
      ParseCoordinate(line, 38, "y", name, lineNumber);
      ParseCoordinate(line, 46, "z", name, lineNumber);
    } else if (RecordIs(line, "ANIS")) {
      if (line.size() < 70)
        throw InputError(SourceLocation(name, lineNumber),
                         "ANISOU record is too short (" + std::to_string(line.size()) +
                             " columns; the tensor is in columns 29-70): truncated?");
    } else if (RecordIs(line, "CONE")) {
      // CONECT: serial in 7-11, bonded serials in 12-16, 17-21, 22-26, 27-31.
      uint32_t from = 0;
      for (int field = 0; field < 5; ++field) {
        const size_t begin = 6 + 5 * static_cast<size_t>(field);
        if (begin >= line.size()) break;
        const std::string value(TrimView(line.substr(begin, 5)));
        if (value.empty()) continue;
        char* endp = nullptr;
        const long serial = std::strtol(value.c_str(), &endp, 10);
        if (endp != value.c_str() + value.size() || serial <= 0)
          throw InputError(SourceLocation(name, lineNumber, static_cast<int>(begin + 1)),
                           "CONECT atom serial is not a positive number: '" + value + "'");
        if (field == 0)
          from = static_cast<uint32_t>(serial);
        else if (from != 0) {
          scan.conect.emplace_back(from, static_cast<uint32_t>(serial));
          scan.conectLine.push_back(lineNumber);
        }
      }
    } else if (line.size() >= 3 && std::toupper(static_cast<unsigned char>(line[0])) == 'E' &&
               std::toupper(static_cast<unsigned char>(line[1])) == 'N' &&
               std::toupper(static_cast<unsigned char>(line[2])) == 'D' &&
               (line.size() == 3 || line[3] == ' ' || line[3] == '\t')) {
      break;  // gemmi stops at END too
    }
  }
  return scan;
}

// ---------------------------------------------------------------------------------------
// gemmi::Structure -> Molecule.

bool IsWaterName(const std::string& n) {
  static const char* const kNames[] = {"HOH", "WAT", "DOD", "H2O", "SOL", "TIP",  "TIP3",
                                       "TIP4", "TIP5", "SPC", "SPCE", "T3P", "T4P", "T5P"};
  for (const char* w : kNames)
    if (n == w) return true;
  return false;
}

bool IsIonElement(uint8_t z) {
  if (z == 9 || z == 17 || z == 35 || z == 53) return true;  // halides
  return z != 0 && z != 1 && gemmi::is_metal(static_cast<gemmi::El>(z));
}

// What the reader keeps beside the Molecule until assemblies are built.
struct ReadState {
  std::vector<std::string> residueSubchain;  // mmCIF label_asym_id per residue
  bool anyAnisou = false;                    // Molecule::anisou is in use
};

bool SameSeqId(const gemmi::SeqId& a, const gemmi::SeqId& b) {
  return a.num == b.num && (a.icode == b.icode || ((a.icode == ' ' || a.icode == '\0') &&
                                                    (b.icode == ' ' || b.icode == '\0')));
}

char FirstAltloc(const gemmi::Residue& res) {
  for (const gemmi::Atom& a : res.atoms)
    if (a.altloc != '\0') return a.altloc;
  return '\0';
}

struct UnknownElements {
  size_t count = 0;
  std::string firstAtom, firstResidue;
};

// Chains of one model are merged by name (into Molecule::chains); `chainByName` persists
// across calls, so a chain that continues in the next mmCIF chunk stays one Chain.
void AppendModel(const gemmi::Model& model, uint16_t modelIndex,
                 std::unordered_map<std::string, uint32_t>& chainByName, Molecule& mol,
                 ReadState& state, UnknownElements& unknown) {
  for (const gemmi::Chain& chain : model.chains) {
    auto [it, inserted] = chainByName.emplace(chain.name, uint32_t(mol.chains.size()));
    if (inserted) mol.chains.push_back(Chain{chain.name, modelIndex});
    const uint32_t chainIndex = it->second;
    // gemmi splits a residue number into several gemmi residues when the residue name
    // changes. Two cases: microheterogeneity (two residue types at one position, told apart
    // by alternate locations): keep the first; and files that simply rename part of a
    // residue (md.pdb's waters: OW, HW1 in SOL 359, HW2 in WAT 359): one Residue, as
    // io/molecule.h defines it (consecutive atoms with the same number and insertion code).
    const gemmi::Residue* previous = nullptr;
    const size_t firstResidueOfChain = mol.residues.size();
    for (const gemmi::Residue& res : chain.residues) {
      const bool sameNumber = previous && SameSeqId(previous->seqid, res.seqid) &&
                              mol.residues.size() > firstResidueOfChain;
      if (sameNumber && FirstAltloc(res) != '\0' && FirstAltloc(*previous) != '\0' &&
          FirstAltloc(res) != FirstAltloc(*previous))
        continue;  // a later conformer of a microheterogeneous position
      previous = &res;
      Residue out;
      std::snprintf(out.name.data(), out.name.size(), "%s", res.name.c_str());
      out.seqNum = res.seqid.num.has_value() ? res.seqid.num.value : 0;
      out.insertionCode = res.seqid.icode == ' ' || res.seqid.icode == '\0' ? ' '
                                                                             : res.seqid.icode;
      out.chainIndex = chainIndex;
      out.firstAtom = static_cast<uint32_t>(mol.x.size());
      const bool merge = sameNumber && mol.residues.back().chainIndex == chainIndex &&
                         mol.residues.back().firstAtom + mol.residues.back().atomCount ==
                             out.firstAtom;
      const uint32_t residueIndex = static_cast<uint32_t>(mol.residues.size()) - (merge ? 1 : 0);
      const bool water = IsWaterName(res.name);
      const gemmi::ResidueInfo info = gemmi::find_tabulated_residue(res.name);
      const bool polymer = info.is_amino_acid() || info.is_nucleic_acid();
      const bool het = res.het_flag == 'H';
      // Alternate locations: keep atoms with none, and those of the first one the residue
      // names (whatever order the conformers come in).
      const char keepAltloc = FirstAltloc(res);
      for (const gemmi::Atom& atom : res.atoms) {
        if (atom.altloc != '\0' && atom.altloc != keepAltloc) continue;
        uint8_t z = atom.element.elem == gemmi::El::D
                        ? uint8_t{1}
                        : static_cast<uint8_t>(atom.element.elem);
        if (z == 0 || z > kMaxElement) z = InferElement(atom.name, res.name);
        if (z == 0) {
          if (unknown.count++ == 0) {
            unknown.firstAtom = atom.name;
            unknown.firstResidue = res.name;
          }
        }
        mol.x.push_back(atom.pos.x);
        mol.y.push_back(atom.pos.y);
        mol.z.push_back(atom.pos.z);
        mol.element.push_back(z);
        uint8_t flags = 0;
        if (het) flags |= kHetatm;
        if (water) flags |= kWater;
        if (z == 1) flags |= kHydrogen;
        if (polymer) flags |= kPolymer;
        const bool hasAniso = atom.aniso.u11 != 0.f || atom.aniso.u22 != 0.f ||
                              atom.aniso.u33 != 0.f;
        if (hasAniso) {
          flags |= kHasAnisou;
          if (!state.anyAnisou) mol.anisou.resize(mol.x.size() - 1);  // zeros so far
          state.anyAnisou = true;
        }
        if (state.anyAnisou) {
          const std::array<float, 6> u = atom.aniso.elements_pdb();
          mol.anisou.push_back(hasAniso ? u : std::array<float, 6>{});
        }
        mol.flags.push_back(flags);
        std::array<char, 4> name{};
        std::memcpy(name.data(), atom.name.data(), std::min<size_t>(4, atom.name.size()));
        mol.atomName.push_back(name);
        mol.occupancy.push_back(atom.occ);
        mol.bFactor.push_back(atom.b_iso);
        mol.residueIndex.push_back(residueIndex);
        mol.modelIndex.push_back(modelIndex);
        mol.serial.push_back(static_cast<uint32_t>(std::max(atom.serial, 0)));
      }
      out.atomCount = static_cast<uint32_t>(mol.x.size()) - out.firstAtom;
      if (out.atomCount == 0) continue;
      if (merge) {
        mol.residues.back().atomCount += out.atomCount;
        continue;
      }
      mol.residues.push_back(out);
      state.residueSubchain.push_back(res.subchain);
    }
  }
}

// Takes models as they come (a whole PDB structure, or mmCIF chunks in file order): numbers
// them by first appearance of their name, keeps only the first unless all are asked for.
struct ModelAppender {
  bool allModels = false;
  std::string fileName;
  std::unordered_map<std::string, uint16_t> indexOfModel;
  std::vector<std::unordered_map<std::string, uint32_t>> chainsOfModel;  // per model index

  void Append(const gemmi::Structure& st, Molecule& mol, ReadState& state,
              UnknownElements& unknown) {
    for (const gemmi::Model& model : st.models) {
      auto [it, inserted] = indexOfModel.emplace(model.name, uint16_t(chainsOfModel.size()));
      if (inserted) {
        if (chainsOfModel.size() == 65536)
          throw InputError(SourceLocation(fileName), "too many models (at most 65536)");
        chainsOfModel.emplace_back();
      }
      if (it->second == 0 || allModels)
        AppendModel(model, it->second, chainsOfModel[it->second], mol, state, unknown);
    }
  }
  uint32_t modelCount() const { return uint32_t(chainsOfModel.size()); }
};

// _atom_site_anisotrop rows, matched to atoms by serial (_atom_site.id) as gemmi matches them.
void SetAnisou(const std::vector<std::pair<int, std::array<float, 6>>>& rows, Molecule& mol) {
  if (rows.empty()) return;
  std::unordered_map<uint32_t, std::array<float, 6>> bySerial;
  for (const auto& [serial, u] : rows)
    if (serial >= 0 && (u[0] != 0.f || u[1] != 0.f || u[2] != 0.f)) bySerial.emplace(serial, u);
  if (bySerial.empty()) return;
  mol.anisou.assign(mol.atomCount(), std::array<float, 6>{});
  for (size_t i = 0; i < mol.atomCount(); ++i)
    if (const auto it = bySerial.find(mol.serial[i]); it != bySerial.end()) {
      mol.anisou[i] = it->second;
      mol.flags[i] |= kHasAnisou;
    }
}

// Every atom row of an mmCIF file is one line of at least ~20 bytes (ten required values): that
// bounds the atoms, so the columns are allocated once instead of growing (a growing vector
// holds up to twice its size, and both copies while it moves).
void ReserveAtoms(std::string_view text, Molecule& mol) {
  const size_t lines = std::min(size_t(std::count(text.begin(), text.end(), '\n')) + 1,
                                text.size() / 20 + 1);
  for (auto* v : {&mol.x, &mol.y, &mol.z}) v->reserve(lines);
  mol.element.reserve(lines), mol.flags.reserve(lines), mol.atomName.reserve(lines);
  mol.occupancy.reserve(lines), mol.bFactor.reserve(lines), mol.residueIndex.reserve(lines);
  mol.modelIndex.reserve(lines), mol.serial.reserve(lines);
}

// An ion: a single-atom residue of a metal or halide that is not water.
void FlagIons(Molecule& mol) {
  for (const Residue& r : mol.residues)
    if (r.atomCount == 1 && !(mol.flags[r.firstAtom] & kWater) &&
        IsIonElement(mol.element[r.firstAtom]))
      mol.flags[r.firstAtom] |= kIon;
}

std::string Describe(const Molecule& mol, size_t atom) {
  const Residue& r = mol.residues[mol.residueIndex[atom]];
  const std::string atomName(mol.atomName[atom].data(),
                             strnlen(mol.atomName[atom].data(), mol.atomName[atom].size()));
  return "atom " + std::to_string(mol.serial[atom]) + " (" + atomName + " of " +
         std::string(r.name.data()) + " " + std::to_string(r.seqNum) + " chain " +
         mol.chains[r.chainIndex].name + ")";
}

// Finite and within ±kMaxCoordinate (io/molecule.h): a 1e30 placeholder would otherwise give
// an empty image and grids sized by it.
void CheckCoordinates(const Molecule& mol, const std::string& name, const char* what = "") {
  for (size_t i = 0; i < mol.atomCount(); ++i) {
    if (!std::isfinite(mol.x[i]) || !std::isfinite(mol.y[i]) || !std::isfinite(mol.z[i]))
      throw InputError(SourceLocation(name, 0, 0, Describe(mol, i)),
                       "coordinate is not a finite number (not a number, NaN or Inf)");
    const double m = std::max({std::fabs(mol.x[i]), std::fabs(mol.y[i]), std::fabs(mol.z[i])});
    if (m > kMaxCoordinate) {
      char xyz[128];
      std::snprintf(xyz, sizeof xyz, "(%g, %g, %g)", mol.x[i], mol.y[i], mol.z[i]);
      throw InputError(SourceLocation(name, 0, 0, Describe(mol, i)),
                       std::string("coordinate ") + xyz + what + " is beyond ±1e6 Å");
    }
  }
}

void SetBonds(Molecule& mol, std::vector<std::pair<uint32_t, uint32_t>> pairs) {
  for (auto& p : pairs)
    if (p.first > p.second) std::swap(p.first, p.second);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  mol.bondA.clear();
  mol.bondB.clear();
  mol.bondSource.clear();
  for (const auto& [a, b] : pairs) {
    if (a == b) continue;  // an atom "bonded" to itself in a broken CONECT
    mol.bondA.push_back(a);
    mol.bondB.push_back(b);
    mol.bondSource.push_back(BondSource::kRecord);
  }
}

// Record bonds: CONECT serial pairs (PDB) and gemmi's connections (mmCIF struct_conn, PDB
// LINK/SSBOND) of covalent, disulfide and metal-coordination type. Hydrogen bonds are not
// drawn as bonds. Both apply inside every model that was read.
void AddRecordBonds(const gemmi::Structure& st, const PdbScan& scan, Molecule& mol) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  size_t skipped = 0;  // CONECT pairs of the first model naming an atom that was not read
  size_t firstSkipped = 0;
  if (!scan.conect.empty()) {
    std::unordered_map<uint64_t, uint32_t> bySerial;  // (model << 32 | serial) -> atom
    bySerial.reserve(mol.atomCount());
    for (size_t i = 0; i < mol.atomCount(); ++i)
      bySerial.emplace(uint64_t(mol.modelIndex[i]) << 32 | mol.serial[i], uint32_t(i));
    const uint32_t models = mol.atomCount() ? mol.modelIndex.back() + 1u : 0u;
    for (uint32_t m = 0; m < models; ++m)
      for (size_t k = 0; k < scan.conect.size(); ++k) {
        const auto [sa, sb] = scan.conect[k];
        const auto a = bySerial.find(uint64_t(m) << 32 | sa);
        const auto b = bySerial.find(uint64_t(m) << 32 | sb);
        // CONECT may name atoms of a dropped alternate location, or a broken serial: skip,
        // and say so once (below).
        if (a != bySerial.end() && b != bySerial.end()) {
          pairs.emplace_back(a->second, b->second);
        } else if (m == 0 && skipped++ == 0) {
          firstSkipped = k;
        }
      }
    if (skipped > 0) {
      const auto [sa, sb] = scan.conect[firstSkipped];
      const uint32_t missing = bySerial.count(sa) ? sb : sa;  // model 0: key = serial
      std::fprintf(stderr,
                   "softmol: warning: %s:%ld: CONECT names atom serial %u, which was not read (no such "
                   "atom, or an alternate location that was dropped); %zu CONECT bond(s) skipped\n",
                   mol.sourcePath.c_str(), scan.conectLine[firstSkipped], missing, skipped);
    }
  }
  bool anyConnection = false;
  for (const gemmi::Connection& c : st.connections)
    anyConnection |= c.type != gemmi::Connection::Hydrog;
  if (anyConnection) {
    auto key = [](uint16_t model, const std::string& chain, int seq, char icode,
                  const std::string& atom) {
      return std::to_string(model) + '\x1f' + chain + '\x1f' + std::to_string(seq) +
             (icode == '\0' ? ' ' : icode) + '\x1f' + atom;
    };
    std::unordered_map<std::string, uint32_t> byAddress;
    byAddress.reserve(mol.atomCount());
    for (size_t i = 0; i < mol.atomCount(); ++i) {
      const Residue& r = mol.residues[mol.residueIndex[i]];
      const std::string atom(mol.atomName[i].data(),
                             strnlen(mol.atomName[i].data(), mol.atomName[i].size()));
      byAddress.emplace(key(mol.modelIndex[i], mol.chains[r.chainIndex].name, r.seqNum,
                            r.insertionCode, atom),
                        uint32_t(i));
    }
    const uint32_t models = mol.atomCount() ? mol.modelIndex.back() + 1u : 0u;
    for (uint32_t m = 0; m < models; ++m)
      for (const gemmi::Connection& c : st.connections) {
        if (c.type == gemmi::Connection::Hydrog) continue;
        auto find = [&](const gemmi::AtomAddress& p) {
          const int seq = p.res_id.seqid.num.has_value() ? p.res_id.seqid.num.value : 0;
          return byAddress.find(key(uint16_t(m), p.chain_name, seq, p.res_id.seqid.icode == ' ' ? '\0' : p.res_id.seqid.icode, p.atom_name));
        };
        const auto a = find(c.partner1);
        const auto b = find(c.partner2);
        if (a != byAddress.end() && b != byAddress.end()) pairs.emplace_back(a->second, b->second);
      }
  }
  SetBonds(mol, std::move(pairs));
}

void FillElementColumns(Molecule& mol) {
  mol.vdwRadius.resize(mol.atomCount());
  mol.color.resize(mol.atomCount());
  for (size_t i = 0; i < mol.atomCount(); ++i) {
    const ElementInfo& e = Element(mol.element[i]);
    mol.vdwRadius[i] = e.vdwRadius;
    mol.color[i] = e.color;
  }
}

// ---------------------------------------------------------------------------------------
// Assemblies.

bool Contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// U' = R U Rᵀ for an ANISOU tensor stored as U11 U22 U33 U12 U13 U23.
std::array<float, 6> RotateTensor(const gemmi::Mat33& r, const std::array<float, 6>& u6) {
  const double u[3][3] = {{u6[0], u6[3], u6[4]}, {u6[3], u6[1], u6[5]}, {u6[4], u6[5], u6[2]}};
  double ru[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) ru[i][j] += r.a[i][k] * u[k][j];
  double out[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) out[i][j] += ru[i][k] * r.a[j][k];
  return {float(out[0][0]), float(out[1][1]), float(out[2][2]),
          float(out[0][1]), float(out[0][2]), float(out[1][2])};
}

Molecule BuildAssembly(const Molecule& au, const ReadState& state,
                       const gemmi::Assembly& assembly, const std::string& name) {
  // Which residues each generator takes: PDB BIOMT lists author chains, mmCIF lists label
  // asym ids (subchains).
  std::vector<std::vector<uint8_t>> takes(assembly.generators.size());
  size_t total = 0;
  for (size_t g = 0; g < assembly.generators.size(); ++g) {
    const gemmi::Assembly::Gen& gen = assembly.generators[g];
    const bool all = !gen.chains.empty() && gen.chains[0] == "(all)";
    takes[g].resize(au.residues.size());
    size_t atoms = 0;
    for (size_t r = 0; r < au.residues.size(); ++r) {
      const bool take = all || Contains(gen.chains, au.chains[au.residues[r].chainIndex].name) ||
                        Contains(gen.subchains, state.residueSubchain[r]);
      takes[g][r] = take;
      if (take) atoms += au.residues[r].atomCount;
    }
    total += atoms * gen.operators.size();
  }
  // Atom indices are uint32 (io/molecule.h); a file asking for more copies than that fits
  // (thousands of operators on a large unit) is refused rather than exhausting memory.
  constexpr size_t kMaxAtoms = size_t(1) << 31;
  if (total >= kMaxAtoms)
    throw InputError(SourceLocation(name), "assembly '" + assembly.name + "' would have " +
                                    std::to_string(total) + " atoms, more than " +
                                    std::to_string(kMaxAtoms));
  if (total == 0)
    throw InputError(SourceLocation(name), "assembly '" + assembly.name + "' selects no atoms (its chains "
                                                             "are not in the file)");

  Molecule out;
  out.sourcePath = au.sourcePath;
  out.title = au.title;
  out.modelCount = au.modelCount;
  out.secondaryStructureFromFile = au.secondaryStructureFromFile;
  out.assemblyIds = au.assemblyIds;
  auto reserve = [total](auto& v) { v.reserve(total); };
  reserve(out.x), reserve(out.y), reserve(out.z), reserve(out.element), reserve(out.flags);
  reserve(out.atomName), reserve(out.occupancy), reserve(out.bFactor);
  reserve(out.residueIndex), reserve(out.modelIndex), reserve(out.serial);
  if (!au.anisou.empty()) out.anisou.reserve(total);

  std::map<std::string, int> copiesOfChain;           // how many times a name was emitted
  std::vector<uint32_t> newIndex(au.atomCount(), UINT32_MAX);  // AU atom -> copy atom
  std::vector<std::pair<uint32_t, uint32_t>> bonds;
  bonds.reserve(au.bondCount() * (total / std::max<size_t>(au.atomCount(), 1) + 1));

  for (size_t g = 0; g < assembly.generators.size(); ++g) {
    for (const gemmi::Assembly::Operator& op : assembly.generators[g].operators) {
      const gemmi::Mat33& m = op.transform.mat;
      const gemmi::Vec3& v = op.transform.vec;
      std::vector<uint32_t> chainMap(au.chains.size(), UINT32_MAX);
      std::fill(newIndex.begin(), newIndex.end(), UINT32_MAX);
      for (size_t r = 0; r < au.residues.size(); ++r) {
        if (!takes[g][r]) continue;
        const Residue& res = au.residues[r];
        uint32_t& chain = chainMap[res.chainIndex];
        if (chain == UINT32_MAX) {
          const Chain& src = au.chains[res.chainIndex];
          // Counted per model, so every model's chains are named A, A-2, ... alike.
          const int n = ++copiesOfChain[src.name + '\x1f' + std::to_string(src.modelIndex)];
          chain = static_cast<uint32_t>(out.chains.size());
          out.chains.push_back(
              Chain{n == 1 ? src.name : src.name + "-" + std::to_string(n), src.modelIndex});
        }
        Residue copy = res;
        copy.chainIndex = chain;
        copy.firstAtom = static_cast<uint32_t>(out.x.size());
        const uint32_t residueIndex = static_cast<uint32_t>(out.residues.size());
        out.residues.push_back(copy);
        for (uint32_t i = res.firstAtom; i < res.firstAtom + res.atomCount; ++i) {
          newIndex[i] = static_cast<uint32_t>(out.x.size());
          const double x = au.x[i], y = au.y[i], z = au.z[i];
          out.x.push_back(m.a[0][0] * x + m.a[0][1] * y + m.a[0][2] * z + v.x);
          out.y.push_back(m.a[1][0] * x + m.a[1][1] * y + m.a[1][2] * z + v.y);
          out.z.push_back(m.a[2][0] * x + m.a[2][1] * y + m.a[2][2] * z + v.z);
          out.element.push_back(au.element[i]);
          out.flags.push_back(au.flags[i]);
          out.atomName.push_back(au.atomName[i]);
          out.occupancy.push_back(au.occupancy[i]);
          out.bFactor.push_back(au.bFactor[i]);
          out.residueIndex.push_back(residueIndex);
          out.modelIndex.push_back(au.modelIndex[i]);
          out.serial.push_back(au.serial[i]);
          if (!au.anisou.empty())
            out.anisou.push_back((au.flags[i] & kHasAnisou) ? RotateTensor(m, au.anisou[i])
                                                            : au.anisou[i]);
        }
      }
      for (size_t b = 0; b < au.bondCount(); ++b) {
        const uint32_t a = newIndex[au.bondA[b]], c = newIndex[au.bondB[b]];
        if (a != UINT32_MAX && c != UINT32_MAX) bonds.emplace_back(a, c);
      }
    }
  }
  SetBonds(out, std::move(bonds));
  return out;
}

std::string ListIds(const std::vector<std::string>& ids) {
  std::string s;
  for (const std::string& id : ids) s += (s.empty() ? "" : ", ") + id;
  return s;
}

}  // namespace

Molecule ReadMoleculeFromMemory(std::string_view bytes, const std::string& name,
                                StructureFormat format, const ReadOptions& options) {
  std::string inflated;
  if (IsGzip(bytes)) {
    inflated = Gunzip(bytes, name);
    bytes = inflated;
  }
  CheckIsText(bytes, name);
  if (format == StructureFormat::kAuto) format = DetectFormat(name, bytes);

  Molecule mol;
  mol.sourcePath = name;
  ReadState state;
  UnknownElements unknown;
  ModelAppender models{options.allModels, name, {}, {}};
  // The file's records (title, assemblies, connections, secondary structure); its models are
  // appended to `mol` and dropped as they come.
  gemmi::Structure st;
  PdbScan scan;
  if (format == StructureFormat::kPdb) {
    scan = ScanPdb(bytes, name);
    try {
      st = gemmi::read_pdb_from_memory(bytes.data(), bytes.size(), name);
    } catch (const std::exception& e) {
      throw FromGemmiPdb(name, e.what());
    }
    models.Append(st, mol, state, unknown);
    st.models.clear();
  } else {
    ReserveAtoms(bytes, mol);
    detail::MmcifContent cif = detail::ParseMmcif(bytes, name, [&](const gemmi::Structure& chunk) {
      models.Append(chunk, mol, state, unknown);
    });
    st = std::move(cif.records);
    SetAnisou(cif.anisou, mol);
  }
  mol.title = st.get_info("_struct.title");
  mol.modelCount = models.modelCount();
  for (const gemmi::Assembly& a : st.assemblies) mol.assemblyIds.push_back(a.name);
  FlagIons(mol);
  if (mol.atomCount() == 0)
    throw InputError(SourceLocation(name), "no atoms: the file has no ATOM/HETATM records (or _atom_site "
                             "rows)");
  if (mol.atomCount() >= UINT32_MAX / 2)
    throw InputError(SourceLocation(name), "too many atoms (" + std::to_string(mol.atomCount()) + ")");
  CheckCoordinates(mol, name);
  SetSecondaryStructure(detail::SecondaryStructureRanges(st), mol);
  if (unknown.count > 0)
    std::fprintf(stderr,
                 "softmol: warning: %s: %zu atom(s) of unknown element (first: '%s' in '%s'); "
                 "drawn as grey %.2f A spheres\n",
                 name.c_str(), unknown.count, unknown.firstAtom.c_str(),
                 unknown.firstResidue.c_str(), double(Element(0).vdwRadius));
  AddRecordBonds(st, scan, mol);

  if (!options.assembly.empty()) {
    const gemmi::Assembly* found = nullptr;
    for (const gemmi::Assembly& a : st.assemblies)
      if (a.name == options.assembly) found = &a;
    if (!found)
      throw InputError(SourceLocation(name), "unknown assembly '" + options.assembly + "'; " +
                                   (mol.assemblyIds.empty()
                                        ? std::string("the file defines no assemblies")
                                        : "available: " + ListIds(mol.assemblyIds)));
    mol = BuildAssembly(mol, state, *found, name);
    CheckCoordinates(mol, name, (" after the operators of assembly " + options.assembly).c_str());
  }
  FillElementColumns(mol);
  return mol;
}

Molecule ReadMolecule(const std::string& path, const ReadOptions& options) {
  const std::string bytes = ReadFileBytes(path);
  return ReadMoleculeFromMemory(bytes, path, StructureFormat::kAuto, options);
}

}  // namespace softmol::io

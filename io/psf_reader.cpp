// io/psf_reader.cpp — PSF topology reader. A PSF is a series of sections, each headed by a
// count and a "!NAME" tag ("42 !NATOM", "41 !NBOND: bonds"). An atom line holds
//   id segid resid resname name type charge mass [imove ...]
// in fixed columns that differ between the standard, EXT and X-PLOR flavours, so fields are read
// as whitespace-separated words (as VMD does). Bonds are 2*NBOND atom ids, 8 to a line.
#include "io/psf_reader.h"

#include <gemmi/elem.hpp>
#include <gemmi/resinfo.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "io/detail/trajectory_formats.h"
#include "io/elements.h"

namespace softmol::io {
namespace {

using detail::FileLoc;

std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

template <typename T>
bool ParseNumber(std::string_view w, T& out) {
  auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), out);
  return ec == std::errc() && end == w.data() + w.size();
}

// A section header "<count> !TAG..."; returns false when the line is not one.
bool SectionHeader(std::string_view line, long& count, std::string_view& tag) {
  size_t bang = line.find('!');
  if (bang == std::string_view::npos) return false;
  auto words = Words(line.substr(0, bang));
  if (words.empty() || !ParseNumber(words[0], count)) return false;
  tag = line.substr(bang + 1);
  size_t end = tag.find_first_of(": \r");
  if (end != std::string_view::npos) tag = tag.substr(0, end);
  return true;
}

// The element whose standard atomic weight is within 0.1 u of `mass`, if exactly one is.
uint8_t ElementFromMass(double mass) {
  if (!(mass > 0.5)) return 0;  // massless sites (lone pairs, TIP4P's M) and garbage
  uint8_t best = 0;
  int matches = 0;
  for (int z = 1; z <= 118; ++z) {
    if (std::abs(gemmi::molecular_weight(static_cast<gemmi::El>(z)) - mass) < 0.1) {
      best = static_cast<uint8_t>(z);
      ++matches;
    }
  }
  return matches == 1 ? best : 0;
}

bool IsWaterResidue(std::string_view n) {
  static const char* const kNames[] = {"HOH", "WAT", "DOD", "H2O", "SOL", "TIP", "TIP3", "TIP4",
                                       "TIP5", "SPC", "SPCE", "T3P", "T4P", "T5P", "TIP3P"};
  for (const char* w : kNames)
    if (n == w) return true;
  return false;
}

bool IsPolymerResidue(const std::string& n) {
  // CHARMM/AMBER names for protonation states and nucleic acids that the PDB table lacks.
  static const char* const kForceField[] = {"HSD", "HSE", "HSP", "HID", "HIE", "HIP", "CYX", "ASH",
                                            "GLH", "LYN", "ADE", "CYT", "GUA", "THY", "URA"};
  for (const char* w : kForceField)
    if (n == w) return true;
  gemmi::ResidueInfo info = gemmi::find_tabulated_residue(n);
  return info.is_amino_acid() || info.is_nucleic_acid();
}

bool IsIonElement(uint8_t z) {
  if (z == 9 || z == 17 || z == 35 || z == 53) return true;  // halides
  return z > 1 && gemmi::is_metal(static_cast<gemmi::El>(z));
}

// "12" -> (12, ' '), "12A" -> (12, 'A'); false when it does not start with an integer.
bool ParseResid(std::string_view w, int32_t& num, char& icode) {
  size_t digits = (!w.empty() && w[0] == '-') ? 1 : 0;
  while (digits < w.size() && w[digits] >= '0' && w[digits] <= '9') ++digits;
  if (digits == 0 || w.size() - digits > 1) return false;
  if (!ParseNumber(w.substr(0, digits), num)) return false;
  icode = digits < w.size() ? w[digits] : ' ';
  return true;
}

}  // namespace

Molecule ReadPsfTopology(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(FileLoc(path), "cannot open PSF: no such file");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(FileLoc(path), "cannot open PSF: is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(FileLoc(path), "cannot open PSF");
  const uintmax_t fileSize = std::filesystem::file_size(path, ec);
  if (ec || fileSize == 0) throw InputError(FileLoc(path), "PSF file is empty");

  std::string line;
  long lineNo = 0;
  auto next = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++lineNo;
    return true;
  };
  if (!next() || line.compare(0, 3, "PSF") != 0)
    throw InputError(FileLoc(path, {}, 1), "not a PSF file (the first line must start with \"PSF\")");

  Molecule mol;
  mol.sourcePath = path;
  long natom = -1;
  long nbond = -1;
  std::vector<uint32_t> bondIds;
  while (next()) {
    long count = 0;
    std::string_view tag;
    if (!SectionHeader(line, count, tag)) continue;
    if (count < 0) throw InputError(FileLoc(path, {}, lineNo), "negative section count");
    if (tag == "NTITLE") {
      for (long i = 0; i < count; ++i) {
        if (!next()) throw InputError(FileLoc(path, {}, lineNo), "truncated: file ends inside the title");
        if (mol.title.empty()) {
          std::string_view t = line;
          while (!t.empty() && (t.front() == '*' || t.front() == ' ')) t.remove_prefix(1);
          while (!t.empty() && (t.back() == ' ' || t.back() == '\r')) t.remove_suffix(1);
          mol.title = t;
        }
      }
    } else if (tag == "NATOM") {
      if (natom >= 0) throw InputError(FileLoc(path, {}, lineNo), "a second !NATOM section");
      // Every atom line takes at least 16 bytes: a count larger than the file allows is corrupt,
      // and checking it first keeps a forged count from driving a huge allocation.
      if (static_cast<uintmax_t>(count) > fileSize / 16)
        throw InputError(FileLoc(path, {}, lineNo),
                         "!NATOM says " + std::to_string(count) + " atoms, more than the file can hold");
      natom = count;
      const size_t n = static_cast<size_t>(count);
      mol.x.assign(n, 0.0);
      mol.y.assign(n, 0.0);
      mol.z.assign(n, 0.0);
      mol.element.resize(n);
      mol.flags.resize(n);
      mol.atomName.resize(n);
      mol.occupancy.assign(n, 1.0f);
      mol.bFactor.assign(n, 0.0f);
      mol.residueIndex.resize(n);
      mol.modelIndex.assign(n, 0);
      mol.serial.resize(n);
      mol.vdwRadius.resize(n);
      mol.color.resize(n);
      std::string prevSeg, prevResid, prevResname;
      for (size_t a = 0; a < n; ++a) {
        if (!next())
          throw InputError(FileLoc(path, {}, lineNo), "truncated: !NATOM announces " + std::to_string(n) +
                                                         " atoms but the file ends after " + std::to_string(a));
        auto w = Words(line);
        if (w.size() < 8)
          throw InputError(FileLoc(path, {}, lineNo),
                           "atom line has " + std::to_string(w.size()) +
                               " fields, expected at least 8 (id segid resid resname name type charge mass)");
        uint32_t id = 0;
        int32_t resnum = 0;
        char icode = ' ';
        double charge = 0, mass = 0;
        if (!ParseNumber(w[0], id)) throw InputError(FileLoc(path, {}, lineNo), "atom id is not a number: '" + std::string(w[0]) + "'");
        if (!ParseResid(w[2], resnum, icode))
          throw InputError(FileLoc(path, {}, lineNo), "residue number is not a number: '" + std::string(w[2]) + "'");
        if (!ParseNumber(w[6], charge) || !ParseNumber(w[7], mass) || !std::isfinite(mass))
          throw InputError(FileLoc(path, {}, lineNo), "charge or mass is not a number");
        const std::string_view seg = w[1], resid = w[2], resname = w[3], name = w[4];
        if (a == 0 || seg != prevSeg) mol.chains.push_back(Chain{std::string(seg), 0});
        if (a == 0 || seg != prevSeg || resid != prevResid || resname != prevResname) {
          Residue r;
          std::copy_n(resname.data(), std::min<size_t>(resname.size(), r.name.size() - 1), r.name.begin());
          r.seqNum = resnum;
          r.insertionCode = icode;
          r.chainIndex = static_cast<uint32_t>(mol.chains.size() - 1);
          r.firstAtom = static_cast<uint32_t>(a);
          mol.residues.push_back(r);
        }
        prevSeg = seg, prevResid = resid, prevResname = resname;
        mol.residues.back().atomCount++;
        mol.residueIndex[a] = static_cast<uint32_t>(mol.residues.size() - 1);
        mol.serial[a] = id;
        std::array<char, 4> nm{};
        std::copy_n(name.data(), std::min<size_t>(name.size(), nm.size()), nm.begin());
        mol.atomName[a] = nm;
        uint8_t z = ElementFromMass(mass);
        if (z == 0) z = InferElement(name, resname);
        mol.element[a] = z;
        const ElementInfo& e = Element(z);
        mol.vdwRadius[a] = e.vdwRadius;
        mol.color[a] = e.color;
      }
    } else if (tag == "NBOND") {
      if (natom < 0) throw InputError(FileLoc(path, {}, lineNo), "!NBOND before !NATOM");
      nbond = count;
      // Same guard as for atoms: 2 ids of at least 2 bytes each per bond.
      if (static_cast<uintmax_t>(count) > fileSize / 4)
        throw InputError(FileLoc(path, {}, lineNo), "!NBOND count is larger than the file can hold");
      const size_t want = 2 * static_cast<size_t>(count);
      while (bondIds.size() < want) {
        if (!next())
          throw InputError(FileLoc(path, {}, lineNo), "truncated: !NBOND announces " + std::to_string(count) +
                                                         " bonds but the file ends after " +
                                                         std::to_string(bondIds.size() / 2));
        for (std::string_view w : Words(line)) {
          uint32_t id = 0;
          if (!ParseNumber(w, id) || id < 1 || id > static_cast<uint64_t>(natom))
            throw InputError(FileLoc(path, {}, lineNo),
                             "bond atom '" + std::string(w) + "' is not an atom number 1.." + std::to_string(natom));
          if (bondIds.size() == want)
            throw InputError(FileLoc(path, {}, lineNo), "more bond entries than !NBOND announces");
          bondIds.push_back(id - 1);
        }
      }
      break;  // nothing after the bonds is needed
    }
  }
  if (natom < 0) throw InputError(FileLoc(path), "no !NATOM section: not a PSF topology");
  if (natom == 0) throw InputError(FileLoc(path), "the PSF has no atoms");
  (void)nbond;

  // Flags need whole residues (ions are single-atom residues).
  for (const Residue& r : mol.residues) {
    std::string name(r.name.data());
    const bool water = IsWaterResidue(name);
    const bool polymer = !water && IsPolymerResidue(name);
    for (uint32_t a = r.firstAtom; a < r.firstAtom + r.atomCount; ++a) {
      uint8_t f = 0;
      if (mol.element[a] == 1) f |= kHydrogen;
      if (water) f |= kWater;
      if (polymer) f |= kPolymer;
      if (r.atomCount == 1 && !water && IsIonElement(mol.element[a])) f |= kIon;
      // PSF has no HETATM notion; mark what a PDB would: non-polymer residues.
      if (!polymer) f |= kHetatm;
      mol.flags[a] = f;
    }
  }

  std::vector<std::pair<uint32_t, uint32_t>> bonds;
  bonds.reserve(bondIds.size() / 2);
  for (size_t i = 0; i + 1 < bondIds.size(); i += 2) {
    uint32_t a = bondIds[i], b = bondIds[i + 1];
    if (a == b) throw InputError(FileLoc(path), "bond " + std::to_string(i / 2 + 1) + " joins atom " + std::to_string(a + 1) + " to itself");
    bonds.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(bonds.begin(), bonds.end());
  bonds.erase(std::unique(bonds.begin(), bonds.end()), bonds.end());
  for (auto [a, b] : bonds) {
    mol.bondA.push_back(a);
    mol.bondB.push_back(b);
    mol.bondSource.push_back(BondSource::kRecord);
  }
  return mol;
}

}  // namespace softmol::io

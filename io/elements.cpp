// io/elements.cpp — the element table (data) and the PDB element-inference rules.
//
// Sources:
//  * van der Waals radii: Bondi 1964 (J. Phys. Chem. 68, 441) where Bondi gives one;
//    Mantina et al. 2009 (J. Phys. Chem. A 113, 5806) for the other main-group elements;
//    Alvarez 2013 (Dalton Trans. 42, 8617) for the transition metals, lanthanides and
//    actinides Bondi lacks. Pm has no published value (mean of Nd and Sm); 100-118 have none
//    (2.00 Å, marked below). The letter after each value says which: B, M, A, or - (none).
//  * covalent radii: Cordero et al. 2008 (Dalton Trans. 2832), taken from gemmi's table
//    (gemmi::covalent_radius), which covers every element 1..118.
//  * colors: Jmol's CPK colors (jmol.sourceforge.net/jscolors) for 1..109; 110-118 have no
//    Jmol color and reuse Mt's.
#include "io/elements.h"

#include <array>
#include <cctype>
#include <string>

#include <gemmi/elem.hpp>

namespace softmol::io {
namespace {

struct Row {
  const char* symbol;
  float vdw;
  uint32_t color;
};

// Index = atomic number; row 0 is the unknown element.
constexpr Row kRows[kMaxElement + 1] = {
    {"X", 1.70f, 0x808080},                                    // unknown: documented default
    {"H", 1.20f, 0xFFFFFF},   {"He", 1.40f, 0xD9FFFF},         // B B
    {"Li", 1.82f, 0xCC80FF},  {"Be", 1.53f, 0xC2FF00},         // B M
    {"B", 1.92f, 0xFFB5B5},   {"C", 1.70f, 0x909090},          // M B
    {"N", 1.55f, 0x3050F8},   {"O", 1.52f, 0xFF0D0D},          // B B
    {"F", 1.47f, 0x90E050},   {"Ne", 1.54f, 0xB3E3F5},         // B B
    {"Na", 2.27f, 0xAB5CF2},  {"Mg", 1.73f, 0x8AFF00},         // B B
    {"Al", 1.84f, 0xBFA6A6},  {"Si", 2.10f, 0xF0C8A0},         // M B
    {"P", 1.80f, 0xFF8000},   {"S", 1.80f, 0xFFFF30},          // B B
    {"Cl", 1.75f, 0x1FF01F},  {"Ar", 1.88f, 0x80D1E3},         // B B
    {"K", 2.75f, 0x8F40D4},   {"Ca", 2.31f, 0x3DFF00},         // B M
    {"Sc", 2.58f, 0xE6E6E6},  {"Ti", 2.46f, 0xBFC2C7},         // A A
    {"V", 2.42f, 0xA6A6AB},   {"Cr", 2.45f, 0x8A99C7},         // A A
    {"Mn", 2.45f, 0x9C7AC7},  {"Fe", 2.44f, 0xE06633},         // A A
    {"Co", 2.40f, 0xF090A0},  {"Ni", 1.63f, 0x50D050},         // A B
    {"Cu", 1.40f, 0xC88033},  {"Zn", 1.39f, 0x7D80B0},         // B B
    {"Ga", 1.87f, 0xC28F8F},  {"Ge", 2.11f, 0x668F8F},         // B M
    {"As", 1.85f, 0xBD80E3},  {"Se", 1.90f, 0xFFA100},         // B B
    {"Br", 1.85f, 0xA62929},  {"Kr", 2.02f, 0x5CB8D1},         // B B
    {"Rb", 3.03f, 0x702EB0},  {"Sr", 2.49f, 0x00FF00},         // M M
    {"Y", 2.75f, 0x94FFFF},   {"Zr", 2.52f, 0x94E0E0},         // A A
    {"Nb", 2.56f, 0x73C2C9},  {"Mo", 2.45f, 0x54B5B5},         // A A
    {"Tc", 2.44f, 0x3B9E9E},  {"Ru", 2.46f, 0x248F8F},         // A A
    {"Rh", 2.44f, 0x0A7D8C},  {"Pd", 1.63f, 0x006985},         // A B
    {"Ag", 1.72f, 0xC0C0C0},  {"Cd", 1.58f, 0xFFD98F},         // B B
    {"In", 1.93f, 0xA67573},  {"Sn", 2.17f, 0x668080},         // B B
    {"Sb", 2.06f, 0x9E63B5},  {"Te", 2.06f, 0xD47A00},         // M B
    {"I", 1.98f, 0x940094},   {"Xe", 2.16f, 0x429EB0},         // B B
    {"Cs", 3.43f, 0x57178F},  {"Ba", 2.68f, 0x00C900},         // M M
    {"La", 2.98f, 0x70D4FF},  {"Ce", 2.88f, 0xFFFFC7},         // A A
    {"Pr", 2.92f, 0xD9FFC7},  {"Nd", 2.95f, 0xC7FFC7},         // A A
    {"Pm", 2.92f, 0xA3FFC7},  {"Sm", 2.90f, 0x8FFFC7},         // - A
    {"Eu", 2.87f, 0x61FFC7},  {"Gd", 2.83f, 0x45FFC7},         // A A
    {"Tb", 2.79f, 0x30FFC7},  {"Dy", 2.87f, 0x1FFFC7},         // A A
    {"Ho", 2.81f, 0x00FF9C},  {"Er", 2.83f, 0x00E675},         // A A
    {"Tm", 2.79f, 0x00D452},  {"Yb", 2.80f, 0x00BF38},         // A A
    {"Lu", 2.74f, 0x00AB24},  {"Hf", 2.63f, 0x4DC2FF},         // A A
    {"Ta", 2.53f, 0x4DA6FF},  {"W", 2.57f, 0x2194D6},          // A A
    {"Re", 2.49f, 0x267DAB},  {"Os", 2.48f, 0x266696},         // A A
    {"Ir", 2.41f, 0x175487},  {"Pt", 1.72f, 0xD0D0E0},         // A B
    {"Au", 1.66f, 0xFFD123},  {"Hg", 1.55f, 0xB8B8D0},         // B B
    {"Tl", 1.96f, 0xA6544D},  {"Pb", 2.02f, 0x575961},         // B B
    {"Bi", 2.07f, 0x9E4FB5},  {"Po", 1.97f, 0xAB5C00},         // M M
    {"At", 2.02f, 0x754F45},  {"Rn", 2.20f, 0x428296},         // M M
    {"Fr", 3.48f, 0x420066},  {"Ra", 2.83f, 0x007D00},         // M M
    {"Ac", 2.80f, 0x70ABFA},  {"Th", 2.93f, 0x00BAFF},         // A A
    {"Pa", 2.88f, 0x00A1FF},  {"U", 1.86f, 0x008FFF},          // A B
    {"Np", 2.82f, 0x0080FF},  {"Pu", 2.81f, 0x006BFF},         // A A
    {"Am", 2.83f, 0x545CF2},  {"Cm", 3.05f, 0x785CE3},         // A A
    {"Bk", 3.40f, 0x8A4FE3},  {"Cf", 3.05f, 0xA136D4},         // A A
    {"Es", 2.70f, 0xB31FD4},  {"Fm", 2.00f, 0xB31FBA},         // A -
    {"Md", 2.00f, 0xB30DA6},  {"No", 2.00f, 0xBD0D87},         // - -
    {"Lr", 2.00f, 0xC70066},  {"Rf", 2.00f, 0xCC0059},         // - -
    {"Db", 2.00f, 0xD1004F},  {"Sg", 2.00f, 0xD90045},         // - -
    {"Bh", 2.00f, 0xE00038},  {"Hs", 2.00f, 0xE6002E},         // - -
    {"Mt", 2.00f, 0xEB0026},  {"Ds", 2.00f, 0xEB0026},         // - -
    {"Rg", 2.00f, 0xEB0026},  {"Cn", 2.00f, 0xEB0026},         // - -
    {"Nh", 2.00f, 0xEB0026},  {"Fl", 2.00f, 0xEB0026},         // - -
    {"Mc", 2.00f, 0xEB0026},  {"Lv", 2.00f, 0xEB0026},         // - -
    {"Ts", 2.00f, 0xEB0026},  {"Og", 2.00f, 0xEB0026},         // - -
};
static_assert(sizeof(kRows) / sizeof(kRows[0]) == kMaxElement + 1);

// Covalent radius of the unknown element: a carbon-like 0.77 Å, so an unidentified atom in
// a chain still bonds to its neighbours.
constexpr float kUnknownCovalentRadius = 0.77f;

const std::array<ElementInfo, kMaxElement + 1>& Table() {
  static const std::array<ElementInfo, kMaxElement + 1> table = [] {
    std::array<ElementInfo, kMaxElement + 1> t{};
    for (int z = 0; z <= kMaxElement; ++z) {
      const float covalent = z == 0 ? kUnknownCovalentRadius
                                    : gemmi::covalent_radius(static_cast<gemmi::El>(z));
      t[z] = ElementInfo{kRows[z].symbol, kRows[z].vdw, covalent, kRows[z].color};
    }
    return t;
  }();
  return table;
}

char Upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsAlpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' ||
                        s.back() == '\n'))
    s.remove_suffix(1);
  return s;
}

// One-letter elements that occur in atom names of biomolecules; a lone letter outside this
// set (e.g. "A" or "Q") is not taken as an element.
uint8_t OneLetter(char c) {
  switch (Upper(c)) {
    case 'H': case 'D': case 'T': return 1;
    case 'B': return 5;
    case 'C': return 6;
    case 'N': return 7;
    case 'O': return 8;
    case 'F': return 9;
    case 'P': return 15;
    case 'S': return 16;
    case 'K': return 19;
    case 'V': return 23;
    case 'Y': return 39;
    case 'I': return 53;
    case 'W': return 74;
    case 'U': return 92;
    default: return 0;
  }
}

}  // namespace

const ElementInfo& Element(uint8_t atomicNumber) {
  return Table()[atomicNumber <= kMaxElement ? atomicNumber : 0];
}

uint8_t ElementFromSymbol(std::string_view symbol) {
  symbol = Trim(symbol);
  if (symbol.empty() || symbol.size() > 2) return 0;
  const char a = Upper(symbol[0]);
  const char b = symbol.size() == 2 ? Upper(symbol[1]) : '\0';
  if (b == '\0' && (a == 'D' || a == 'T')) return 1;  // deuterium, tritium
  for (int z = 1; z <= kMaxElement; ++z) {
    const char* s = kRows[z].symbol;
    if (Upper(s[0]) == a && Upper(s[1]) == b) return static_cast<uint8_t>(z);
  }
  return 0;
}

uint8_t InferElement(std::string_view atomName, std::string_view residueName) {
  const std::string_view trimmed = Trim(atomName);
  if (trimmed.empty()) return 0;
  // Rule 1: ions are single-atom residues named after their element ("ZN" in "ZN").
  const std::string_view res = Trim(residueName);
  if (trimmed.size() <= 2 && res.size() == trimmed.size()) {
    bool same = true;
    for (size_t i = 0; i < res.size(); ++i) same = same && Upper(res[i]) == Upper(trimmed[i]);
    if (same)
      if (const uint8_t z = ElementFromSymbol(trimmed)) return z;
  }
  // Rule 2: "1HB", "2HG1": old hydrogen names; the element is the letter after the digit.
  if (IsDigit(trimmed[0])) return trimmed.size() > 1 ? OneLetter(trimmed[1]) : 0;

  if (atomName.size() == 4) {
    // Rule 3: the padded 4-column field keeps the alignment of columns 13-14.
    if (atomName[0] == ' ') return OneLetter(atomName[1]);
    if (Upper(atomName[0]) == 'H' && atomName[3] != ' ') return 1;  // "HG21", "HD11"
    if (IsAlpha(atomName[1]))
      if (const uint8_t z = ElementFromSymbol(atomName.substr(0, 2))) return z;
    return OneLetter(atomName[0]);
  }
  // Rule 4: a trimmed name has lost the alignment; take its first letter.
  return OneLetter(trimmed[0]);
}

}  // namespace softmol::io

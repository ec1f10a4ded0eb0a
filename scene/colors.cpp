// scene/colors.cpp — the colour schemes.
#include "scene/colors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "io/elements.h"
#include "io/params.h"
#include "io/selection.h"

namespace softmol::scene {
namespace {

using namespace palette;
constexpr uint8_t kCarbon = 6;

// Okabe & Ito's colour-blind-safe qualitative palette without its black, ordered so that
// neighbouring chains contrast (the loud yellow last).
constexpr std::array<uint32_t, 7> kChainPalette = {0x56B4E9, 0xE69F00, 0x009E73, 0xD55E00,
                                                   0x0072B2, 0xCC79A7, 0xF0E442};


uint32_t Mix(uint32_t rgb, uint32_t toward, double t) {
  uint32_t out = 0;
  for (int shift = 16; shift >= 0; shift -= 8) {
    const double a = (rgb >> shift) & 0xFF, b = (toward >> shift) & 0xFF;
    out |= uint32_t(std::lround(a + (b - a) * t)) << shift;
  }
  return out;
}

struct SchemeName {
  std::string_view name;
  ColorScheme scheme;
};
constexpr SchemeName kSchemes[] = {
    {"auto", ColorScheme::kAuto},       {"element", ColorScheme::kElement}, {"cpk", ColorScheme::kCpk},
    {"chain", ColorScheme::kChain},
    {"residue", ColorScheme::kResidue}, {"ss", ColorScheme::kSecondaryStructure},
    {"bfactor", ColorScheme::kBFactor}, {"uniform", ColorScheme::kUniform},
};

// "SCHEME[:ARG[:ARG]]" or "COLOR" (no selection part).
ColorRule ParseScheme(std::string_view text, const io::SourceLocation& where) {
  ColorRule rule;
  if (const std::optional<uint32_t> rgb = io::ColorFromText(text)) {
    rule.scheme = ColorScheme::kUniform, rule.rgb = *rgb, rule.hasRgb = true;
    return rule;
  }
  const size_t colon = text.find(':');
  const std::string_view name = io::TrimBlanks(text.substr(0, colon));
  const std::string_view arg = colon == std::string_view::npos ? std::string_view() : text.substr(colon + 1);
  const auto it = std::find_if(std::begin(kSchemes), std::end(kSchemes), [&](const SchemeName& s) { return s.name == name; });
  if (it == std::end(kSchemes))
    throw io::InputError(where, "unknown colour " + io::Quoted(text) +
                                    " (a scheme: auto, element[:COLOR], cpk[:COLOR], chain, residue, ss, bfactor[:LO:HI], "
                                    "uniform:COLOR; a colour: RRGGBB or a CSS name; or SELECTION=one of these)");
  rule.scheme = it->scheme;
  const bool elementScheme = rule.scheme == ColorScheme::kElement || rule.scheme == ColorScheme::kCpk;
  if (rule.scheme == ColorScheme::kUniform || (elementScheme && !arg.empty())) {
    if (arg.empty()) throw io::InputError(where, "uniform needs a colour: uniform:COLOR");
    rule.rgb = io::ParseColorValue(arg, where), rule.hasRgb = true;
  } else if (rule.scheme == ColorScheme::kBFactor && colon != std::string_view::npos) {
    const size_t second = arg.find(':');
    if (second == std::string_view::npos) throw io::InputError(where, "expected bfactor:LO:HI, got " + io::Quoted(text));
    rule.lo = io::ParseRealValue(arg.substr(0, second), {-1e9, 1e9}, "", where);
    rule.hi = io::ParseRealValue(arg.substr(second + 1), {-1e9, 1e9}, "", where);
    if (!(rule.hi > rule.lo)) throw io::InputError(where, "bfactor:LO:HI needs LO < HI, got " + io::Quoted(text));
    rule.hasRange = true;
  } else if (colon != std::string_view::npos) {
    throw io::InputError(where, "the scheme '" + std::string(name) + "' takes no argument, got " + io::Quoted(text));
  }
  return rule;
}

// The chain palette's ordinal of every chain: chains sharing a name (the same chain in several
// models) share a colour.
std::vector<size_t> ChainOrdinals(const io::Molecule& mol) {
  std::map<std::string, size_t> byName;
  std::vector<size_t> ordinal(mol.chains.size());
  for (size_t c = 0; c < mol.chains.size(); ++c)
    ordinal[c] = byName.emplace(mol.chains[c].name, byName.size()).first->second;
  return ordinal;
}

uint32_t AminoAcidClass(std::string_view resn) {
  static const std::map<std::string_view, uint32_t> kClasses = {
      {"ALA", kHydrophobic}, {"VAL", kHydrophobic}, {"LEU", kHydrophobic}, {"ILE", kHydrophobic},
      {"MET", kHydrophobic}, {"PHE", kHydrophobic}, {"TRP", kHydrophobic}, {"PRO", kHydrophobic},
      {"GLY", kHydrophobic}, {"CYS", kHydrophobic}, {"SER", kPolar},       {"THR", kPolar},
      {"ASN", kPolar},       {"GLN", kPolar},       {"TYR", kPolar},       {"ASP", kAcidic},
      {"GLU", kAcidic},      {"LYS", kBasic},       {"ARG", kBasic},       {"HIS", kBasic}};
  const auto it = kClasses.find(resn);
  return it == kClasses.end() ? 0 : it->second;
}

std::string_view ResidueName(const io::Residue& r) {
  return std::string_view(r.name.data(), std::find(r.name.begin(), r.name.end(), '\0') - r.name.begin());
}

// B-factor range of the selected atoms (0..1 when none is selected).
void SelectedRange(const io::Molecule& mol, const std::vector<uint8_t>& selected, double& lo, double& hi) {
  lo = 1e300, hi = -1e300;
  for (size_t i = 0; i < mol.atomCount(); ++i)
    if (selected[i]) lo = std::min(lo, double(mol.bFactor[i])), hi = std::max(hi, double(mol.bFactor[i]));
  if (lo > hi) lo = 0.0, hi = 1.0;
  if (hi == lo) hi = lo + 1.0;  // one B-factor: the low end of the map, not 0/0
}

}  // namespace

uint32_t SoftElementColor(uint8_t atomicNumber, uint32_t cpk) {
  // Hand-picked for the elements of biomolecules (CPK hues at about 70% saturation, lighter, so
  // AO and lines read on them); every other element: its CPK colour a quarter of the way to white.
  switch (atomicNumber) {
    case 1: return 0xE8E8E8;   // H
    case 6: return kCarbonGrey;
    case 7: return 0x7B93E8;   // N
    case 8: return 0xE8695E;   // O
    case 9: case 17: return 0x9ED67A;  // F, Cl
    case 15: return 0xF0A860;  // P
    case 16: return 0xEDD26A;  // S
    case 35: return 0xC0806C;  // Br
    case 53: return 0xA47FC0;  // I
    default: return Mix(cpk, 0xFFFFFF, 0.25);
  }
}

uint32_t ChainColor(size_t ordinal) {
  // Beyond the palette: a lighter round, a darker one, lighter still, darker still, then again.
  constexpr double kShade[] = {0.0, 0.4, -0.35, 0.65, -0.55};
  const uint32_t base = kChainPalette[ordinal % kChainPalette.size()];
  const double shade = kShade[(ordinal / kChainPalette.size()) % std::size(kShade)];
  return shade >= 0 ? Mix(base, 0xFFFFFF, shade) : Mix(base, 0x000000, -shade);
}

uint32_t Viridis(double t) {
  // viridisLite's 9-step viridis; linear between steps (sRGB).
  constexpr uint32_t kSteps[] = {0x440154, 0x472D7B, 0x3B528B, 0x2C728E, 0x21908C,
                                 0x27AD81, 0x5DC863, 0xAADC32, 0xFDE725};
  constexpr size_t n = std::size(kSteps);
  if (!(t > 0.0)) return kSteps[0];  // also NaN
  if (t >= 1.0) return kSteps[n - 1];
  const double x = t * double(n - 1);
  const size_t k = size_t(x);
  return Mix(kSteps[k], kSteps[k + 1], x - double(k));
}

ColorRule ParseColorRule(std::string_view text, const io::SourceLocation& where) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) return ParseScheme(io::TrimBlanks(text), where);
  const std::string_view selection = io::TrimBlanks(text.substr(0, eq));
  if (selection.empty()) throw io::InputError(where, "expected SELECTION=COLOR, got " + io::Quoted(text));
  ColorRule rule = ParseScheme(io::TrimBlanks(text.substr(eq + 1)), where);
  (void)io::ParseSelection(selection, where);
  rule.selection = std::string(selection);
  return rule;
}

std::string FormatColorRule(const ColorRule& rule) {
  std::string s = rule.selection.empty() ? "" : rule.selection + "=";
  if (rule.scheme == ColorScheme::kUniform) return s + io::FormatColor(rule.rgb);
  for (const SchemeName& n : kSchemes)
    if (n.scheme == rule.scheme) s += n.name;
  if ((rule.scheme == ColorScheme::kElement || rule.scheme == ColorScheme::kCpk) && rule.hasRgb)
    s += ":" + io::FormatColor(rule.rgb);
  if (rule.scheme == ColorScheme::kBFactor && rule.hasRange)
    s += ":" + io::FormatReal(rule.lo) + ":" + io::FormatReal(rule.hi);
  return s;
}

void ApplyColorRule(const io::Molecule& mol, const ColorRule& rule, const std::vector<uint8_t>& selected,
                    std::vector<uint32_t>& colors) {
  const size_t n = mol.atomCount();
  const std::vector<size_t> chainOrdinal = ChainOrdinals(mol);
  const auto chainOf = [&](size_t i) { return chainOrdinal[mol.residues[mol.residueIndex[i]].chainIndex]; };
  std::vector<uint8_t> nucleic;
  if (rule.scheme == ColorScheme::kResidue) nucleic = io::Evaluate(io::ParseSelection("nucleic"), mol);
  double lo = rule.lo, hi = rule.hi;
  if (rule.scheme == ColorScheme::kBFactor && !rule.hasRange) SelectedRange(mol, selected, lo, hi);
  for (size_t i = 0; i < n; ++i) {
    if (!selected[i]) continue;
    const bool carbon = mol.element[i] == kCarbon;
    const io::Residue& residue = mol.residues[mol.residueIndex[i]];
    switch (rule.scheme) {
      case ColorScheme::kAuto:
        colors[i] = !carbon                       ? SoftElementColor(mol.element[i], mol.color[i])
                    : (mol.flags[i] & io::kPolymer) ? ChainColor(chainOf(i))
                                                    : kCarbonGrey;
        break;
      case ColorScheme::kElement:
        colors[i] = carbon && rule.hasRgb ? rule.rgb : SoftElementColor(mol.element[i], mol.color[i]);
        break;
      case ColorScheme::kCpk: colors[i] = carbon && rule.hasRgb ? rule.rgb : mol.color[i]; break;
      case ColorScheme::kChain: colors[i] = ChainColor(chainOf(i)); break;
      case ColorScheme::kResidue:
        if (nucleic[i]) colors[i] = kNucleic;
        else if (const uint32_t c = AminoAcidClass(ResidueName(residue))) colors[i] = c;
        break;
      case ColorScheme::kSecondaryStructure:  // polymers only: a ligand has no secondary structure
        if (!(mol.flags[i] & io::kPolymer)) break;
        colors[i] = residue.ss == io::SecondaryStructure::kHelix   ? kHelix
                    : residue.ss == io::SecondaryStructure::kSheet ? kSheet
                                                                   : kCoil;
        break;
      case ColorScheme::kBFactor: colors[i] = Viridis((double(mol.bFactor[i]) - lo) / (hi - lo)); break;
      case ColorScheme::kUniform: colors[i] = rule.rgb; break;
    }
  }
}

std::vector<uint32_t> AtomColors(const io::Molecule& mol, const std::vector<ColorRule>& rules) {
  std::vector<uint32_t> colors(mol.atomCount(), 0);
  const std::vector<uint8_t> all(mol.atomCount(), 1);
  ApplyColorRule(mol, ColorRule{}, all, colors);
  for (const ColorRule& rule : rules)
    ApplyColorRule(mol, rule, rule.selection.empty() ? all : io::Evaluate(io::ParseSelection(rule.selection), mol), colors);
  return colors;
}

}  // namespace softmol::scene

// scene/colors.h — what colour each atom is drawn in: colour schemes and per-selection colours,
// applied in order (the last rule that reaches an atom wins).
//
//   auto              the default: element colours, with the carbons of polymer residues in
//                     their chain's colour (as PyMOL's and Mol*'s defaults), other carbons grey
//   element[:COLOR]   softened element colours (QuteMol's pastel look: CPK hues, lighter and
//                     less saturated); COLOR replaces the carbons' grey
//   cpk[:COLOR]       the saturated CPK/Jmol element colours
//   chain             a colour-blind-safe qualitative palette (Okabe & Ito 2008), one colour per
//                     chain name in order of first appearance, cycling in lighter and darker
//                     shades for more than seven chains
//   residue           hydrophobic / polar / acidic / basic amino acids and nucleotides (other
//                     residues keep the colour they had)
//   ss                secondary structure of polymer residues: helix, sheet, coil (io::Residue::ss)
//   bfactor[:LO:HI]   viridis over the B-factors, LO..HI or the selected atoms' range
//   uniform:COLOR, COLOR   one colour (hex or a CSS name)
//   SEL=SCHEME|COLOR  any of the above over a selection only ("ligand=orange", "chain B=ss")
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/error.h"
#include "io/molecule.h"

namespace softmol::scene {

enum class ColorScheme : uint8_t { kAuto, kElement, kCpk, kChain, kResidue, kSecondaryStructure, kBFactor, kUniform };

struct ColorRule {
  std::string selection;  // io/selection.h text; "" = every atom
  ColorScheme scheme = ColorScheme::kAuto;
  uint32_t rgb = 0;          // kUniform: the colour; kElement with hasRgb: the carbons' colour
  bool hasRgb = false;
  bool hasRange = false;     // kBFactor: lo..hi given (else the selection's range)
  double lo = 0.0, hi = 0.0;
};

// Parses the forms above; throws io::InputError at `where` (selection errors give the column).
ColorRule ParseColorRule(std::string_view text, const io::SourceLocation& where);
// The text ParseColorRule reads back as the same rule.
std::string FormatColorRule(const ColorRule& rule);

// Per-atom sRGB colours: `auto` over every atom, then each rule over its selection.
std::vector<uint32_t> AtomColors(const io::Molecule& molecule, const std::vector<ColorRule>& rules);
// Applies one rule to the atoms where selected[i] != 0.
void ApplyColorRule(const io::Molecule& molecule, const ColorRule& rule, const std::vector<uint8_t>& selected,
                    std::vector<uint32_t>& colors);

// The fixed colours of the schemes (sRGB).
namespace palette {
constexpr uint32_t kCarbonGrey = 0xB0B0B0;  // `auto` and `element` for carbons outside polymers
constexpr uint32_t kHydrophobic = 0xE8D8A8, kPolar = 0x66CCEE, kAcidic = 0xEE6677, kBasic = 0x4477AA,
                   kNucleic = 0xAA3377;                       // residue
constexpr uint32_t kHelix = 0xE8575A, kSheet = 0xF2C14E, kCoil = 0xD0D0D0;  // ss
}  // namespace palette

// The softened colour of an element (`element`, `auto`) whose CPK/Jmol colour is `cpk`.
uint32_t SoftElementColor(uint8_t atomicNumber, uint32_t cpk);

// The chain palette's colour for the chain name that appeared `ordinal`-th (0-based).
uint32_t ChainColor(size_t ordinal);
// Viridis (van der Walt & Smith 2015) at t in [0, 1], sRGB; clamped outside.
uint32_t Viridis(double t);

}  // namespace softmol::scene

// tests/io/elements_test.cpp — the element table is complete and sane, symbols round-trip,
// and atom names give the element the PDB format's naming rules say they do.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "io/elements.h"

namespace softmol::io {
namespace {

TEST(Elements, EveryElementHasPlausibleData) {
  std::set<std::string> symbols;
  for (int z = 1; z <= kMaxElement; ++z) {
    const ElementInfo& e = Element(uint8_t(z));
    ASSERT_NE(e.symbol, nullptr);
    EXPECT_TRUE(symbols.insert(e.symbol).second) << "duplicate symbol " << e.symbol;
    // vdW radii of the tables used lie in 1.2 (H) .. 3.5 (Fr) Å; covalent in 0.28 .. 2.6 Å.
    EXPECT_GE(e.vdwRadius, 1.2f) << e.symbol;
    EXPECT_LE(e.vdwRadius, 3.5f) << e.symbol;
    EXPECT_GE(e.covalentRadius, 0.28f) << e.symbol;
    EXPECT_LE(e.covalentRadius, 2.6f) << e.symbol;
    EXPECT_LE(e.color, 0xFFFFFFu) << e.symbol;
    EXPECT_EQ(ElementFromSymbol(e.symbol), z) << e.symbol;
  }
  EXPECT_EQ(symbols.size(), size_t(kMaxElement));
}

TEST(Elements, KnownValues) {
  // Bondi 1964 vdW radii and Jmol colors of the biological elements.
  EXPECT_FLOAT_EQ(Element(1).vdwRadius, 1.20f);
  EXPECT_FLOAT_EQ(Element(6).vdwRadius, 1.70f);
  EXPECT_FLOAT_EQ(Element(7).vdwRadius, 1.55f);
  EXPECT_FLOAT_EQ(Element(8).vdwRadius, 1.52f);
  EXPECT_FLOAT_EQ(Element(16).vdwRadius, 1.80f);
  EXPECT_FLOAT_EQ(Element(26).vdwRadius, 2.44f);  // Fe: Alvarez 2013
  EXPECT_EQ(Element(6).color, 0x909090u);
  EXPECT_EQ(Element(7).color, 0x3050F8u);
  EXPECT_EQ(Element(8).color, 0xFF0D0Du);
  EXPECT_EQ(Element(16).color, 0xFFFF30u);
  // Cordero 2008 covalent radii (sp3 C is 0.76; gemmi's table uses 0.73 for sp2 C).
  EXPECT_NEAR(Element(6).covalentRadius, 0.75f, 0.03f);
  EXPECT_NEAR(Element(1).covalentRadius, 0.31f, 1e-6f);
  EXPECT_STREQ(Element(26).symbol, "Fe");
  EXPECT_STREQ(Element(118).symbol, "Og");
}

TEST(Elements, UnknownIsGreyDefault) {
  EXPECT_STREQ(Element(0).symbol, "X");
  EXPECT_EQ(Element(0).color, 0x808080u);
  EXPECT_FLOAT_EQ(Element(0).vdwRadius, 1.70f);
  EXPECT_STREQ(Element(119).symbol, "X");
  EXPECT_STREQ(Element(255).symbol, "X");
}

TEST(Elements, SymbolParsing) {
  EXPECT_EQ(ElementFromSymbol("C"), 6);
  EXPECT_EQ(ElementFromSymbol("FE"), 26);
  EXPECT_EQ(ElementFromSymbol("fe"), 26);
  EXPECT_EQ(ElementFromSymbol(" Zn "), 30);
  EXPECT_EQ(ElementFromSymbol("D"), 1);
  EXPECT_EQ(ElementFromSymbol(""), 0);
  EXPECT_EQ(ElementFromSymbol("Xx"), 0);
  EXPECT_EQ(ElementFromSymbol("Q"), 0);
  EXPECT_EQ(ElementFromSymbol("CAL"), 0);
}

TEST(Elements, InferFromPaddedPdbName) {
  EXPECT_EQ(InferElement(" CA ", "ALA"), 6);   // C-alpha: column 13 blank
  EXPECT_EQ(InferElement("CA  ", "CA"), 20);   // calcium ion
  EXPECT_EQ(InferElement("CA  ", "XYZ"), 20);  // aligned to column 13: two-letter element
  EXPECT_EQ(InferElement(" N  ", "GLY"), 7);
  EXPECT_EQ(InferElement(" OXT", "GLY"), 8);
  EXPECT_EQ(InferElement("FE  ", "HEM"), 26);
  EXPECT_EQ(InferElement("HG21", "THR"), 1);   // four-character hydrogen name
  EXPECT_EQ(InferElement("HG  ", "HG"), 80);   // mercury ion
  EXPECT_EQ(InferElement("1HB ", "ALA"), 1);   // old hydrogen naming
  EXPECT_EQ(InferElement(" SD ", "MET"), 16);
  EXPECT_EQ(InferElement("C210", "LIG"), 6);   // digits after the letter
}

TEST(Elements, InferFromTrimmedName) {
  EXPECT_EQ(InferElement("CA", "ALA"), 6);     // alignment lost: first letter
  EXPECT_EQ(InferElement("CA", "CA"), 20);     // unless the residue is that ion
  EXPECT_EQ(InferElement("ZN", "ZN"), 30);
  EXPECT_EQ(InferElement("CL", "CL"), 17);
  EXPECT_EQ(InferElement("OW", "SOL"), 8);
  EXPECT_EQ(InferElement("HW1", "SOL"), 1);
  EXPECT_EQ(InferElement("1HG1", "VAL"), 1);
  EXPECT_EQ(InferElement("", "ALA"), 0);
  EXPECT_EQ(InferElement("QQ", "UNK"), 0);     // nothing matches: unknown
}

}  // namespace
}  // namespace softmol::io

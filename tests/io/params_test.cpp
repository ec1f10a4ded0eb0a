// tests/io/params_test.cpp — parameter declarations (io/params.h): each kind parses what it
// should, refuses the rest with one message naming where the text came from, and prints its
// value in a form it reads back (defaults, presets and round trips rely on that).
#include <gtest/gtest.h>

#include "io/params.h"

namespace softmol::io {
namespace {

struct Knobs {
  int samples = 64;
  float radius = 0.6f;
  double trail = 0.0;
  bool on = false;
  std::string mode = "b";
  uint32_t outputs = 0;
  std::string path;
  struct Inner {
    int depth = 3;
  } inner;
};

ParamTable<Knobs> Table() {
  return {
      IntParam<Knobs>("samples", [](auto& k) -> auto& { return k.samples; }, 1, 256, "taps", "PCF taps", "shadows"),
      RealParam<Knobs>("radius", [](auto& k) -> auto& { return k.radius; }, {0.0, 100.0, /*loOpen=*/true}, "Å",
                       "radius", "shadows"),
      RealParam<Knobs>("trail", [](auto& k) -> auto& { return k.trail; }, {0.0, 10.0}, "ps", "trail", "halos"),
      SwitchParam<Knobs>("on", [](auto& k) -> auto& { return k.on; }, "switch", "frame"),
      ChoiceParam<Knobs>("mode", [](auto& k) -> auto& { return k.mode; },
                         std::vector<std::pair<std::string, std::string>>{{"a", "a"}, {"b", "b"}}, "mode", "frame"),
      BitSetParam<Knobs>("outputs", [](auto& k) -> auto& { return k.outputs; }, {{"depth", 1}, {"id", 4}}, "AOVs",
                         "aovs"),
      TextParam<Knobs>("path", [](auto& k) -> auto& { return k.path; }, "FILE", "a file", "job",
                       [](std::string_view text, const SourceLocation& where) {
                         if (text.empty()) throw InputError(where, "must not be empty");
                       }),
  };
}

const Param<Knobs>& Find(const ParamTable<Knobs>& t, const std::string& name) {
  for (const auto& p : t)
    if (p.name == name) return p;
  throw std::logic_error(name);
}

std::string ErrorOf(const Param<Knobs>& p, const std::string& text, const SourceLocation& where) {
  Knobs k;
  try {
    p.set(k, text, where);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Params, EachKindParsesItsValues) {
  const ParamTable<Knobs> t = Table();
  Knobs k;
  Find(t, "samples").set(k, "16", FlagLocation("samples"));
  Find(t, "radius").set(k, " 2.5 ", FlagLocation("radius"));
  Find(t, "trail").set(k, "10", FlagLocation("trail"));
  Find(t, "on").set(k, "true", FlagLocation("on"));
  Find(t, "mode").set(k, "a", FlagLocation("mode"));
  Find(t, "outputs").set(k, "id, depth", FlagLocation("outputs"));
  EXPECT_EQ(k.samples, 16);
  EXPECT_EQ(k.radius, 2.5f);
  EXPECT_EQ(k.trail, 10.0);
  EXPECT_TRUE(k.on);
  EXPECT_EQ(k.mode, "a");
  EXPECT_EQ(k.outputs, 5u);
  EXPECT_EQ(Find(t, "outputs").get(k), "depth,id");
}

TEST(Params, BadValuesNameTheirOrigin) {
  const ParamTable<Knobs> t = Table();
  EXPECT_EQ(ErrorOf(Find(t, "samples"), "300", FlagLocation("samples")), "--samples: must be in 1..256 taps, got 300");
  EXPECT_EQ(ErrorOf(Find(t, "samples"), "1.5", FlagLocation("samples")),
            "--samples: expected a whole number, got '1.5'");
  EXPECT_EQ(ErrorOf(Find(t, "radius"), "0", SceneKeyLocation("s.json", "radius")),
            "s.json: key 'radius': must be in (0, 100] Å, got 0");
  EXPECT_EQ(ErrorOf(Find(t, "radius"), "nan", FlagLocation("radius")), "--radius: expected a finite number, got 'nan'");
  EXPECT_EQ(ErrorOf(Find(t, "radius"), "1e400", FlagLocation("radius")),
            "--radius: expected a finite number, got '1e400'");
  EXPECT_NE(ErrorOf(Find(t, "trail"), "10.000001", FlagLocation("trail")), "");
  EXPECT_EQ(ErrorOf(Find(t, "mode"), "c", FlagLocation("mode")), "--mode: unknown value 'c' (a, b)");
  EXPECT_EQ(ErrorOf(Find(t, "outputs"), "depth,colour", FlagLocation("outputs")),
            "--outputs: unknown value 'colour' (depth, id)");
  EXPECT_EQ(ErrorOf(Find(t, "on"), "yes", FlagLocation("on")), "--on: expected true or false, got 'yes'");
  EXPECT_EQ(ErrorOf(Find(t, "path"), "", FlagLocation("path")), "--path: must not be empty");
}

TEST(Params, EveryDefaultReadsBackUnchanged) {
  // Defaults live in the struct; their text must parse back to the same value.
  const ParamTable<Knobs> t = Table();
  const Knobs defaults;
  for (const Param<Knobs>& p : t) {
    if (p.name == "path") continue;  // empty by default, refused by its check
    Knobs k;
    p.set(k, p.get(defaults), FlagLocation(p.name));
    EXPECT_EQ(p.get(k), p.get(defaults)) << p.name;
  }
  EXPECT_EQ(Find(t, "radius").get(defaults), "0.6");  // the float's shortest form, not 0.60000002
  EXPECT_EQ(Find(t, "samples").hint, "1..256 taps");
  EXPECT_EQ(Find(t, "radius").hint, "(0, 100] Å");
  EXPECT_EQ(Find(t, "mode").hint, "a|b");
}

TEST(Params, LiftedParamsReachTheNestedStruct) {
  ParamTable<Knobs::Inner> inner = {IntParam<Knobs::Inner>("depth", [](auto& i) -> auto& { return i.depth; }, 0, 9, "",
                                                           "depth", "inner")};
  inner[0].implicitValue = "5";
  const ParamTable<Knobs> lifted = Lift<Knobs>(inner, [](auto& k) -> auto& { return k.inner; });
  ASSERT_EQ(lifted.size(), 1u);
  EXPECT_EQ(lifted[0].implicitValue, "5");
  Knobs k;
  lifted[0].set(k, "7", FlagLocation("depth"));
  EXPECT_EQ(k.inner.depth, 7);
  EXPECT_EQ(lifted[0].get(k), "7");
}

TEST(Params, ColoursAndReals) {
  EXPECT_EQ(ParseColorValue("#FFcc00", FlagLocation("c")), 0xFFCC00u);
  EXPECT_EQ(ParseColorValue("red", FlagLocation("c")), 0xFF0000u);  // a CSS name
  EXPECT_THROW(ParseColorValue("reddish", FlagLocation("c")), InputError);
  EXPECT_THROW(ParseColorValue("12345", FlagLocation("c")), InputError);
  EXPECT_EQ(FormatColor(0x0a0b0c), "0a0b0c");
  EXPECT_EQ(FormatReal(30.0), "30");
  EXPECT_EQ(FormatReal(0.6f), "0.6");
  EXPECT_EQ(FormatReal(1e9), "1e+09");
}

}  // namespace
}  // namespace softmol::io

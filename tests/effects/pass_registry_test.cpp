// tests/effects/pass_registry_test.cpp — the passes as data agree with themselves: one unit per
// PassId in run order, every buffer bit named once, every parameter declared once with a
// default that reads back unchanged, and every pass that its option switches on appears in the
// plan under that option.
#include <set>

#include <gtest/gtest.h>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"

namespace softmol::effects {
namespace {

TEST(PassRegistry, OneUnitPerPassInRunOrder) {
  const auto units = PassRegistry();
  ASSERT_EQ(units.size(), size_t(PassId::kCount));
  std::set<std::string> names;
  for (size_t i = 0; i < units.size(); ++i) {
    EXPECT_EQ(units[i]->id, PassId(i)) << units[i]->name;
    EXPECT_EQ(&Pass(PassId(i)), units[i]);
    EXPECT_TRUE(names.insert(units[i]->name).second) << "two passes named " << units[i]->name;
    EXPECT_NE(units[i]->run, nullptr);
    EXPECT_NE(units[i]->writes, 0u) << units[i]->name << " writes nothing";
  }
}

TEST(PassRegistry, EveryBufferHasOneName) {
  std::set<std::string> names;
  for (int bit = 0; bit < kFrameBufferCount; ++bit) {
    const std::string name = BufferNames(uint64_t(1) << bit);
    EXPECT_FALSE(name.empty()) << bit;
    EXPECT_EQ(name.find(','), std::string::npos) << name;
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  EXPECT_EQ(BufferNames(uint64_t(1) << kFrameBufferCount), "");
}

TEST(PassRegistry, EveryParameterIsDeclaredOnceAndReadsBackItsDefault) {
  const io::ParamTable<RenderOptions> params = RenderParams();
  std::set<std::string> names;
  const RenderOptions defaults;
  for (const io::Param<RenderOptions>& p : params) {
    EXPECT_TRUE(names.insert(p.name).second) << "declared twice: " << p.name;
    EXPECT_FALSE(p.help.empty()) << p.name;
    EXPECT_FALSE(p.group.empty()) << p.name;
    RenderOptions o;
    const std::string text = p.get(defaults);
    p.set(o, text, io::FlagLocation(p.name));
    EXPECT_EQ(p.get(o), text) << p.name;
    if (!p.implicitValue.empty()) {
      EXPECT_NO_THROW(p.set(o, p.implicitValue, io::FlagLocation(p.name))) << p.name;
    }
  }
  EXPECT_GE(params.size(), 25u);
}

// The option each pass names as its switch turns it on: its parameter sets a RenderOptions in
// which that pass is planned.
TEST(PassRegistry, EachPassIsSwitchedOnByTheOptionItNames) {
  const io::ParamTable<RenderOptions> params = RenderParams();
  for (const PassUnit* unit : PassRegistry()) {
    const std::string enabledBy = unit->enabledBy;
    if (enabledBy.empty() || enabledBy == "--highlight") continue;  // always planned / a selection
    const size_t space = enabledBy.find(' ');
    const std::string flag = enabledBy.substr(2, space == std::string::npos ? std::string::npos : space - 2);
    RenderOptions o;
    o.aovs = kAovAo;  // so that AO passes have a reader even without shading
    bool found = false;
    for (const auto& p : params) {
      if (p.name != flag) continue;
      found = true;
      // "--ao baked": that value; "--shadows": a switch; "--aov": a list, its first entry.
      const std::string value = space != std::string::npos ? enabledBy.substr(space + 1)
                                : p.isSwitch                ? "true"
                                                            : p.hint.substr(0, p.hint.find(','));
      p.set(o, value, io::FlagLocation(p.name));
    }
    ASSERT_TRUE(found) << unit->name << " names " << enabledBy << ", which is not a parameter";
    bool planned = false;
    for (const PlannedPass& pp : PlanPasses(o)) planned |= pp.id == unit->id;
    EXPECT_TRUE(planned) << enabledBy << " does not plan '" << unit->name << "'";
  }
}

TEST(PassRegistry, CrossParameterRulesNameTheFlag) {
  RenderOptions o;
  o.shadow.pcfSamples = 16;
  o.shadow.pretestSamples = 32;
  try {
    CheckRenderOptions(o);
    FAIL() << "accepted a pre-test larger than the PCF";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--pcf-pretest"), std::string::npos) << e.what();
  }
  o.shadow.pretestSamples = 16;
  EXPECT_NO_THROW(CheckRenderOptions(o));
}

}  // namespace
}  // namespace softmol::effects

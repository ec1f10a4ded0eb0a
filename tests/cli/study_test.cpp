// tests/cli/study_test.cpp — `softmol study`'s plumbing (cli/study.h): the sweep points, the
// statistics and the Pareto front on hand-made tables, and a whole study of every method on a
// tiny molecule and image: every point runs, every error is finite, each knob's most accurate
// setting beats its least accurate, and the CSV holds the columns scripts/study_plot.py reads
// (which is run when matplotlib is there). The numbers themselves are benchmarks, not tests.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "cli/load_molecule.h"
#include "cli/study.h"
#include "io/error.h"
#include "raster/representation.h"
#include "scene/layers.h"

namespace softmol::cli::study {
namespace {

TEST(StudyStats, ParetoFrontOfAHandMadeTable) {
  //                         on     on     off    on     on (equal to #1)  off
  const std::vector<double> cost = {1, 2, 3, 4, 2, 5};
  const std::vector<double> error = {5, 3, 4, 1, 3, 1};
  EXPECT_EQ(ParetoFront(cost, error), (std::vector<bool>{true, true, false, true, true, false}));
  EXPECT_EQ(ParetoFront(std::vector<double>{}, std::vector<double>{}), std::vector<bool>{});
}

TEST(StudyStats, MedianAndNearestRankPercentile) {
  EXPECT_EQ(Median({3, 1, 2}), 2);
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(Median({})));
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) hundred.push_back(i);
  EXPECT_EQ(Percentile(hundred, 0.95), 95);
  EXPECT_EQ(Percentile(hundred, 0.0), 1);
  EXPECT_EQ(Percentile(hundred, 1.0), 100);
  const ErrorStats s = AbsErrorStats(std::vector<float>{0.5f, 1.0f, 0.0f}, std::vector<float>{0.25f, 0.0f, 0.0f},
                                     std::vector<uint8_t>{1, 0, 1});
  EXPECT_EQ(s.count, 2u);
  EXPECT_DOUBLE_EQ(s.mean, 0.125);
  EXPECT_DOUBLE_EQ(s.p95, 0.25);
  // A(1−A)/n at A = 0.5 and n = 100: 0.0025, standard error 0.05; open pixels add none.
  EXPECT_DOUBLE_EQ(BinomialStdError(std::vector<float>{0.5f, 1.0f}, std::vector<uint8_t>{1, 0}, 100), 0.05);
}

TEST(StudySweep, DefaultFirstThenOneAtATimeThenTheProduct) {
  const MethodPlan plan{Method::kShadows, "shadows",
                        {{"pcf-samples", {"8", "64"}}, {"pcf-pretest", {"8", "0"}}, {"shadow-map", {"512"}}}, 0, 1, 1};
  const std::vector<std::string> defaults = Defaults(plan);
  EXPECT_EQ(defaults, (std::vector<std::string>{"64", "8", "2048"}));
  const std::vector<SweepPoint> points = SweepPoints(plan, defaults);
  std::vector<std::string> labels;
  for (const SweepPoint& p : points) labels.push_back(Label(plan, defaults, p));
  EXPECT_EQ(labels, (std::vector<std::string>{"default", "pcf-samples=8", "pcf-pretest=0", "shadow-map=512",
                                              "pcf-samples=8 pcf-pretest=0"}));
  EXPECT_TRUE(points[0].isDefault);
  for (size_t i = 1; i < points.size(); ++i) EXPECT_FALSE(points[i].isDefault);
}

TEST(StudySweep, ProductStrideKeepsBothEnds) {
  const MethodPlan plan{Method::kConeAo, "cone-ao", {{"cones", {"3", "5", "9"}}, {"ao-grid", {"32", "64", "128", "256"}}}, 0,
                  1, 2};
  // The default (9, 64); cones 3, 5; grid 32, 128, 256; then the product cones {3, 9} × grid
  // {32, 128, 256} adds (3, 32), (3, 128) and (3, 256): (9, ·) are already there.
  const std::vector<std::string> defaults = Defaults(plan);
  std::vector<std::string> labels;
  for (const SweepPoint& p : SweepPoints(plan, defaults)) labels.push_back(Label(plan, defaults, p));
  EXPECT_EQ(labels, (std::vector<std::string>{"default", "cones=3", "cones=5", "ao-grid=32", "ao-grid=128", "ao-grid=256",
                                              "cones=3 ao-grid=32", "cones=3 ao-grid=128", "cones=3 ao-grid=256"}));
}

TEST(StudySweep, KnobSelectionAndUnknownKnobs) {
  const std::vector<MethodPlan> plans = SelectKnobs(DefaultPlans(), {"cones", "ssaa"}, {"--knobs"});
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[0].name, "cone-ao");
  EXPECT_EQ(plans[0].knobs.size(), 1u);
  EXPECT_EQ(plans[0].productA, -1);  // the product needs both knobs
  EXPECT_EQ(plans[1].name, "antialiasing");
  try {
    (void)SelectKnobs(DefaultPlans(), {"ao-directions", "nope"}, {"--knobs"});
    FAIL() << "an unknown knob was accepted";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--knobs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos) << e.what();
  }
}

// Every default plan's knobs are render options whose values parse (the plans are data that
// could drift from the declarations).
TEST(StudySweep, EveryPlannedValueIsAValidRenderOption) {
  const io::ParamTable<RenderArgs> table = RenderParams();
  for (const MethodPlan& plan : DefaultPlans())
    for (const Knob& k : plan.knobs) {
      const auto p = std::find_if(table.begin(), table.end(), [&](const auto& q) { return q.name == k.name; });
      ASSERT_NE(p, table.end()) << k.name;
      for (const std::string& v : k.values) {
        RenderArgs a;
        EXPECT_NO_THROW(p->set(a, v, io::FlagLocation(k.name))) << k.name << "=" << v;
      }
    }
}

// The names in scripts/study_plot.py's COLUMNS tuple.
std::vector<std::string> PlotScriptColumns() {
  std::ifstream in(std::string(SOFTMOL_TESTS_DIR) + "/../../scripts/study_plot.py");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("COLUMNS = (", 0) == 0) {
      std::vector<std::string> names;
      const std::regex quoted("\"([^\"]+)\"");
      for (auto it = std::sregex_iterator(line.begin(), line.end(), quoted); it != std::sregex_iterator(); ++it)
        names.push_back((*it)[1]);
      return names;
    }
  return {};
}

TEST(StudyCsv, ThePlotScriptReadsTheColumnsTheStudyWrites) {
  EXPECT_EQ(PlotScriptColumns(), std::vector<std::string>(std::begin(kPlotColumns), std::end(kPlotColumns)));
}

// Small lists with cheap ends, so the whole study of every method stays about a second.
std::vector<MethodPlan> TinyPlans() {
  return {{Method::kBakedAo, "baked-ao",
           {{"ao-directions", {"16", "128"}}, {"ao-patch", {"4", "32"}}, {"ao-map", {"256", "1024"}}}, 1, 2, 1},
          {Method::kConeAo, "cone-ao", {{"cones", {"3", "9"}}, {"ao-grid", {"32", "128"}}}, 0, 1, 1},
          {Method::kAntialiasing, "antialiasing", {{"ssaa", {"1", "4"}}}},
          {Method::kShadows, "shadows",
           {{"pcf-samples", {"8", "64"}}, {"pcf-pretest", {"8", "0"}}, {"shadow-map", {"512", "2048"}}}, 0, 1, 1},
          {Method::kSetupPrecision, "setup-precision", {{"setup-precision", {"float", "double"}}}}};
}

bool Sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return false;
#endif
}

// The row whose knob k is `value` and every other knob at its default.
const Row* RowWith(const MethodResult& r, size_t k, const std::string& value) {
  for (const Row& row : r.rows) {
    bool match = row.point.values[k] == value;
    for (size_t j = 0; j < row.point.values.size(); ++j) match &= j == k || row.point.values[j] == r.defaults[j];
    if (match) return &row;
  }
  return nullptr;
}

void ExpectEveryPointRan(const MethodPlan& plan, const MethodResult& r) {
  EXPECT_EQ(r.rows.size(), SweepPoints(plan, Defaults(plan)).size()) << r.plan.name;
  bool anyFront = false;
  for (const Row& row : r.rows) {
    SCOPED_TRACE(r.plan.name + " " + row.label);
    EXPECT_GT(row.error.count, 0u);
    EXPECT_TRUE(std::isfinite(row.error.mean) && row.error.mean >= 0);
    EXPECT_TRUE(std::isfinite(row.errorP95) && row.errorP95 >= 0);
    EXPECT_TRUE(std::isfinite(row.frameMs) && row.frameMs >= 0 && row.setupMs >= 0);
    EXPECT_FALSE(row.passMs.empty());
    anyFront |= row.front;
  }
  EXPECT_TRUE(anyFront) << r.plan.name;
  EXPECT_FALSE(r.reference.empty()) << r.plan.name;
}

// Each knob's last value (the most accurate) against its first, the others at their defaults.
// The PCF pre-test only may tie: it decides a sample only where its 8 taps agree, and on a tiny
// image all of them may agree with the full filter too.
void ExpectMostAccurateBeatsLeast(const MethodResult& r) {
  for (size_t k = 0; k < r.plan.knobs.size(); ++k) {
    const Knob& knob = r.plan.knobs[k];
    const Row* least = RowWith(r, k, knob.values.front());
    const Row* most = RowWith(r, k, knob.values.back());
    ASSERT_TRUE(least && most) << knob.name;
    SCOPED_TRACE(knob.name + "=" + knob.values.back() + " against " + knob.values.front());
    if (knob.name == "pcf-pretest") EXPECT_LE(most->error.mean, least->error.mean);
    else EXPECT_LT(most->error.mean, least->error.mean);
  }
}

void ExpectCsvColumns(const MethodResult& r) {
  std::istringstream csv(CsvText(r));
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> columns;
  std::stringstream hs(header);
  for (std::string c; std::getline(hs, c, ',');) columns.push_back(c);
  for (const char* c : kPlotColumns) EXPECT_NE(std::find(columns.begin(), columns.end(), c), columns.end()) << c;
  size_t lines = 0;
  while (std::getline(csv, line)) {
    ++lines;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), std::count(header.begin(), header.end(), ',')) << line;
  }
  EXPECT_EQ(lines, r.rows.size());
}

// One study (ctest runs each TEST in its own process, so one TEST renders it once).
TEST(StudyRun, TinyStudyOfEveryMethod) {
  if (Sanitized()) GTEST_SKIP() << "renders every method's sweep: the release stage runs it";
  const scene::SceneLayers layers;
  const LoadedMolecule m = LoadMolecule(std::string(SOFTMOL_DATA_DIR) + "/pept.pdb", "", "", false);
  const raster::Representation drawn =
      raster::BuildRepresentation(m.molecule, scene::ResolveLooks(m.molecule, layers).looks, {});
  raster::Camera cam = raster::OrientedCamera(drawn.scene, 24, 18);
  raster::FitNearFar(cam, drawn.scene);
  StudyOptions o;
  o.repeats = 1;
  o.maxReferenceRays = 1024;
  const std::vector<MethodPlan> plans = TinyPlans();
  const std::vector<MethodResult> results = RunStudy(plans, {&drawn.scene, {cam}}, o);
  ASSERT_EQ(results.size(), plans.size());
  for (size_t i = 0; i < plans.size(); ++i) {
    ExpectEveryPointRan(plans[i], results[i]);
    ExpectMostAccurateBeatsLeast(results[i]);
    ExpectCsvColumns(results[i]);
  }
  // pept's automatic patch is 32 texels (ao/patch_atlas.h ChooseAtlas): the default and
  // ao-patch=32 are one bake, measured once, so they carry the same time and error.
  const Row* automatic = RowWith(results[0], 1, "0");
  const Row* patch32 = RowWith(results[0], 1, "32");
  ASSERT_TRUE(automatic && patch32);
  EXPECT_EQ(automatic->setupMs, patch32->setupMs);
  EXPECT_EQ(automatic->error.mean, patch32->error.mean);
}

// A hand-made result: the plot script needs no render.
MethodResult HandMadeResult(const std::string& name) {
  MethodResult r;
  r.plan = {Method::kConeAo, name, {{"cones", {"3", "9"}}}};
  r.defaults = {"9"};
  r.errorName = "mean |AO - reference| over visible pixels";
  r.p95Name = "p95";
  const double cost[] = {1.0, 4.0, 2.0}, error[] = {0.09, 0.03, 0.05};  // all three on the front
  for (int i = 0; i < 3; ++i) {
    Row row;
    row.point = {{i == 1 ? "9" : "3"}, i == 1};
    row.label = i == 1 ? "default" : "cones=3";
    row.frameMs = cost[i];
    row.error.mean = error[i];
    row.error.count = 10;
    row.front = true;  // (2, 0.05) lies between the other two
    r.rows.push_back(row);
  }
  return r;
}

TEST(StudyPlot, ThePlotScriptDrawsEveryCsv) {
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  if (std::system((python + " -c 'import matplotlib' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "no matplotlib for " << python << " (apt-get install python3-matplotlib)";
  const auto dir = std::filesystem::temp_directory_path() / ("softmol_study_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const char* name : {"one", "two"}) std::ofstream(dir / (std::string(name) + ".csv")) << CsvText(HandMadeResult(name));
  const std::string script = std::string(SOFTMOL_TESTS_DIR) + "/../../scripts/study_plot.py";
  EXPECT_EQ(std::system((python + " '" + script + "' '" + dir.string() + "'").c_str()), 0);
  for (const char* name : {"one", "two"}) {
    const auto png = dir / (std::string(name) + ".png");
    EXPECT_TRUE(std::filesystem::exists(png) && std::filesystem::file_size(png) > 1000) << png;
  }
  // A CSV without a column the script reads is refused, not half drawn.
  std::ofstream(dir / "bad.csv") << "method,label\ncone-ao,default\n";
  EXPECT_NE(std::system((python + " '" + script + "' '" + dir.string() + "' 2>/dev/null").c_str()), 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace softmol::cli::study

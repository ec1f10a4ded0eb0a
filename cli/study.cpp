// cli/study.cpp — the study's plans, sweep points, statistics and CSV (cli/study.h); the
// renders themselves are in cli/study_run.cpp.
#include "cli/study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/check.h"
#include "io/error.h"

namespace softmol::cli::study {

std::vector<MethodPlan> DefaultPlans() {
  // Baked AO: patch size and shadow-map size are both spatial resolutions of the same lookup (a
  // fine patch only pays when the map resolves it), so they are the pair swept together.
  MethodPlan baked{Method::kBakedAo, "baked-ao",
                   {{"ao-directions", {"16", "32", "64", "128", "256", "512", "1024"}},
                    {"ao-patch", {"4", "8", "16", "32", "64"}},
                    {"ao-map", {"256", "512", "1024", "2048", "4096"}},
                    {"ao-sphere-map", {"octahedral", "cube"}}},
                   1, 2, 2};
  MethodPlan cone{Method::kConeAo, "cone-ao", {{"cones", {"3", "5", "9"}}, {"ao-grid", {"32", "64", "128", "256"}}},
                  0, 1, 1};
  MethodPlan aa{Method::kAntialiasing, "antialiasing", {{"ssaa", {"1", "2", "3", "4"}}}};
  // The pre-test skips taps, so "on" (8 taps) is the less accurate end of its list.
  MethodPlan shadows{Method::kShadows, "shadows",
                     {{"pcf-samples", {"8", "16", "32", "64"}},
                      {"pcf-pretest", {"8", "0"}},
                      {"shadow-map", {"512", "1024", "2048", "4096", "8192"}}},
                     0, 1, 1};
  // Float setup is the less accurate end (raster/frame.h SetupPrecision).
  MethodPlan setup{Method::kSetupPrecision, "setup-precision", {{"setup-precision", {"float", "double"}}}};
  return {baked, cone, aa, shadows, setup};
}

std::vector<std::string> KnobNames(const std::vector<MethodPlan>& plans) {
  std::vector<std::string> names;
  for (const MethodPlan& p : plans)
    for (const Knob& k : p.knobs) names.push_back(k.name);
  return names;
}

std::vector<MethodPlan> SelectKnobs(const std::vector<MethodPlan>& plans, const std::vector<std::string>& names,
                                    const io::SourceLocation& where) {
  const std::vector<std::string> known = KnobNames(plans);
  for (const std::string& n : names)
    if (std::find(known.begin(), known.end(), n) == known.end())
      throw io::InputError(where, "unknown knob " + io::Quoted(n) + " (known: " + io::JoinChoices(known, ",") + ")");
  std::vector<MethodPlan> kept;
  for (const MethodPlan& p : plans) {
    MethodPlan q = p;
    q.knobs.clear();
    q.productA = q.productB = -1;
    for (size_t i = 0; i < p.knobs.size(); ++i) {
      if (std::find(names.begin(), names.end(), p.knobs[i].name) == names.end()) continue;
      if (int(i) == p.productA) q.productA = int(q.knobs.size());
      if (int(i) == p.productB) q.productB = int(q.knobs.size());
      q.knobs.push_back(p.knobs[i]);
    }
    if (q.productA < 0 || q.productB < 0) q.productA = q.productB = -1;  // a product needs both
    if (!q.knobs.empty()) kept.push_back(std::move(q));
  }
  return kept;
}

std::vector<std::string> Defaults(const MethodPlan& plan) {
  const io::ParamTable<RenderArgs> table = RenderParams();
  const RenderArgs shipped;
  std::vector<std::string> defaults;
  for (const Knob& k : plan.knobs) {
    const auto p = std::find_if(table.begin(), table.end(), [&](const auto& q) { return q.name == k.name; });
    SOFTMOL_CHECK(p != table.end());  // the plans name render options only
    defaults.push_back(p->get(shipped));
  }
  return defaults;
}

namespace {

// Every stride-th value of a list, the last one always.
std::vector<std::string> Strided(const std::vector<std::string>& values, int stride) {
  std::vector<std::string> kept;
  for (size_t i = 0; i < values.size(); i += size_t(stride)) kept.push_back(values[i]);
  if (!values.empty() && kept.back() != values.back()) kept.push_back(values.back());
  return kept;
}

void AddPoint(std::vector<SweepPoint>& points, std::vector<std::string> values, const std::vector<std::string>& defaults) {
  for (const SweepPoint& p : points)
    if (p.values == values) return;
  const bool isDefault = values == defaults;
  points.push_back({std::move(values), isDefault});
}

}  // namespace

std::vector<SweepPoint> SweepPoints(const MethodPlan& plan, const std::vector<std::string>& defaults) {
  std::vector<SweepPoint> points;
  AddPoint(points, defaults, defaults);
  for (size_t k = 0; k < plan.knobs.size(); ++k)
    for (const std::string& v : plan.knobs[k].values) {
      std::vector<std::string> values = defaults;
      values[k] = v;
      AddPoint(points, values, defaults);
    }
  if (plan.productA < 0) return points;
  for (const std::string& a : Strided(plan.knobs[size_t(plan.productA)].values, plan.productStride))
    for (const std::string& b : Strided(plan.knobs[size_t(plan.productB)].values, plan.productStride)) {
      std::vector<std::string> values = defaults;
      values[size_t(plan.productA)] = a;
      values[size_t(plan.productB)] = b;
      AddPoint(points, values, defaults);
    }
  return points;
}

std::string Label(const MethodPlan& plan, const std::vector<std::string>& defaults, const SweepPoint& point) {
  std::string label;
  for (size_t k = 0; k < plan.knobs.size(); ++k)
    if (point.values[k] != defaults[k]) label += (label.empty() ? "" : " ") + plan.knobs[k].name + "=" + point.values[k];
  return label.empty() ? "default" : label;
}

double Median(std::vector<double> samples) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  return n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
}

double Percentile(std::vector<double> samples, double q) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(samples.begin(), samples.end());
  const double rank = std::ceil(q * double(samples.size()));
  const size_t i = rank < 1.0 ? 0 : std::min(samples.size() - 1, size_t(rank) - 1);
  return samples[i];
}

std::vector<bool> ParetoFront(std::span<const double> cost, std::span<const double> error) {
  SOFTMOL_CHECK(cost.size() == error.size());
  std::vector<bool> front(cost.size(), true);
  for (size_t i = 0; i < cost.size(); ++i)
    for (size_t j = 0; j < cost.size() && front[i]; ++j) {
      const bool noWorse = cost[j] <= cost[i] && error[j] <= error[i];
      const bool better = cost[j] < cost[i] || error[j] < error[i];
      if (noWorse && better) front[i] = false;
    }
  return front;
}

ErrorStats AbsErrorStats(std::span<const float> a, std::span<const float> b, std::span<const uint8_t> mask) {
  SOFTMOL_CHECK(a.size() == b.size() && a.size() == mask.size());
  std::vector<double> diff;
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (mask[i]) {
      diff.push_back(std::fabs(double(a[i]) - double(b[i])));
      sum += diff.back();
    }
  ErrorStats s;
  s.count = diff.size();
  s.mean = diff.empty() ? 0.0 : sum / double(diff.size());
  s.p95 = diff.empty() ? 0.0 : Percentile(std::move(diff), 0.95);
  return s;
}

double BinomialStdError(std::span<const float> reference, std::span<const uint8_t> mask, int rays) {
  SOFTMOL_CHECK(reference.size() == mask.size() && rays > 0);
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < reference.size(); ++i)
    if (mask[i]) {
      const double a = reference[i];
      sum += a * (1.0 - a) / double(rays);
      ++n;
    }
  return n == 0 ? 0.0 : std::sqrt(sum / double(n));
}

namespace {

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

std::string CsvText(const MethodResult& r) {
  std::string csv = "method,label";
  for (const Knob& k : r.plan.knobs) csv += "," + k.name;
  csv += ",setup_ms,frame_ms,cost_ms,error,error_p95,error_name,p95_name,pixels,default,front,passes\n";
  for (const Row& row : r.rows) {
    csv += r.plan.name + "," + row.label;
    for (const std::string& v : row.point.values) csv += "," + v;
    csv += "," + Number(row.setupMs) + "," + Number(row.frameMs) + "," + Number(row.setupMs + row.frameMs) + "," +
           Number(row.error.mean) + "," + Number(row.errorP95) + "," + r.errorName + "," + r.p95Name + "," +
           std::to_string(row.error.count) + "," + (row.point.isDefault ? "1" : "0") + "," + (row.front ? "1" : "0") + ",";
    for (size_t i = 0; i < row.passMs.size(); ++i)
      csv += (i ? ";" : "") + row.passMs[i].first + "=" + Number(row.passMs[i].second);
    csv += "\n";
  }
  return csv;
}

}  // namespace softmol::cli::study

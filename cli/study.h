// cli/study.h — `softmol study`'s sweep and its statistics (DESIGN.md rule 1: every accuracy
// knob priced in milliseconds and in error). A method (baked AO, cone AO, anti-aliasing, soft
// shadows) owns some knobs, each a `softmol render` option swept over a list of values; its
// sweep points are the defaults, each knob one at a time around them, and the product of the
// two knobs that interact most. Each point is rendered (times from the frame's own per-pass
// profile, the median of several repetitions) and compared with a ground truth of the same
// frame. The Pareto front (time against error) is computed here and drawn by
// scripts/study_plot.py from the CSV this writes.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.h"
#include "raster/camera.h"
#include "raster/primitives.h"

namespace softmol::cli::study {

// A `softmol render` option (its declaration in RenderParams() parses the values and gives the
// shipped default) and the values swept, from the least to the most accurate.
struct Knob {
  std::string name;  // "ao-directions"
  std::vector<std::string> values;
};

enum class Method { kBakedAo, kConeAo, kAntialiasing, kShadows, kSetupPrecision };

struct MethodPlan {
  Method method;
  std::string name;  // "baked-ao": the CSV's and the plot's name
  std::vector<Knob> knobs;
  // Two knob indices also swept together (-1: none): every `productStride`-th value of each
  // list (the first and the last always), so that a costly product stays a few points.
  int productA = -1, productB = -1;
  int productStride = 1;
};

// Every method with the knobs and values the study sweeps by default.
std::vector<MethodPlan> DefaultPlans();
// Every knob name of the plans, in order ("ao-directions,ao-patch,...").
std::vector<std::string> KnobNames(const std::vector<MethodPlan>& plans);
// The plans keeping only the knobs named (the others stay at their defaults); a method left with
// no knob drops out. An unknown name is an io::InputError at `where`, listing the known ones.
std::vector<MethodPlan> SelectKnobs(const std::vector<MethodPlan>& plans, const std::vector<std::string>& names,
                                    const io::SourceLocation& where);

// One setting of every knob of a method.
struct SweepPoint {
  std::vector<std::string> values;  // one per knob of the plan, in the plan's order
  bool isDefault = false;           // every knob at its shipped default
};
// The shipped default of each knob of `plan`, as its declaration writes it.
std::vector<std::string> Defaults(const MethodPlan& plan);
// The default point first, then each knob's other values one at a time, then the product's
// points not already there; no point twice.
std::vector<SweepPoint> SweepPoints(const MethodPlan& plan, const std::vector<std::string>& defaults);
// "ao-map=4096 ao-patch=8", the knobs away from their defaults ("default" when none is).
std::string Label(const MethodPlan& plan, const std::vector<std::string>& defaults, const SweepPoint& point);

// Statistics. Each takes its samples by value (it sorts them); an empty set gives NaN.
double Median(std::vector<double> samples);
// The nearest-rank percentile, q in [0,1] (0.95: the smallest value ≥ 95% of the samples).
double Percentile(std::vector<double> samples, double q);
// Whether each point lies on the Pareto front of (cost, error), both minimised: no other point
// is at most as costly and at most as wrong, and better in one of the two. Equal points are
// both on it.
std::vector<bool> ParetoFront(std::span<const double> cost, std::span<const double> error);

struct ErrorStats {
  double mean = 0, p95 = 0;
  size_t count = 0;  // pixels compared
};
// |a − b| over the pixels where mask is non-zero.
ErrorStats AbsErrorStats(std::span<const float> a, std::span<const float> b, std::span<const uint8_t> mask);
// The reference AO's own standard error per pixel, from the binomial variance A(1−A)/rays of a
// fraction of escaping rays (an upper bound: its rays are stratified), as the root mean square
// over the masked pixels.
double BinomialStdError(std::span<const float> reference, std::span<const uint8_t> mask, int rays);

// What a sweep point measured.
struct Row {
  SweepPoint point;
  std::string label;
  double setupMs = 0;  // paid once per structure (the AO bake); 0 for the others
  double frameMs = 0;  // paid every frame by the method's own passes (the whole frame for SSAA)
  std::vector<std::pair<std::string, double>> passMs;  // every pass that ran, median ms
  ErrorStats error;    // the method's error measure (ErrorName)
  double errorP95 = 0;
  bool front = false;  // on the Pareto front of (setupMs + frameMs, error)
};

struct MethodResult {
  MethodPlan plan;
  std::vector<std::string> defaults;
  std::vector<Row> rows;
  std::string errorName, p95Name;  // what `error` and `errorP95` measure, for the CSV and plots
  std::string reference;           // the ground truth, in words (rays, its standard error, ...)
  std::string detail;              // Markdown for the summary beyond the table (per-case errors), or empty
  bool referenceReached = true;    // the ground truth is as precise as the study asked
};

// What the errors are measured on: the drawn scene and one camera per view (output size).
struct StudyInput {
  const raster::PrimitiveScene* scene = nullptr;
  std::vector<raster::Camera> views;
};

struct StudyOptions {
  RenderArgs base;        // every other option of the renders (their defaults)
  int repeats = 3;        // renders per point and view; times are their median
  int minReferenceRays = 256;
  int maxReferenceRays = 8192;  // the reference AO stops here even if not precise enough
  // Called before each render of a sweep point: (points done, points in all, method, label).
  std::function<void(size_t, size_t, const std::string&, const std::string&)> progress;
};

// Sweeps every plan on `input`. Knob values are set through RenderParams()'s declarations.
std::vector<MethodResult> RunStudy(const std::vector<MethodPlan>& plans, const StudyInput& input,
                                   const StudyOptions& options);

// The CSV of one method: a header, then one line per point. The columns the plot script reads
// are kPlotColumns (scripts/study_plot.py lists the same names).
inline constexpr const char* kPlotColumns[] = {"method", "label", "cost_ms", "error", "error_name", "default", "front"};
std::string CsvText(const MethodResult& result);

}  // namespace softmol::cli::study

// cli/study_run.cpp — the study's renders (cli/study.h RunStudy): every sweep point of every
// method through effects::RenderFrame, its per-pass times, and its error against the method's
// ground truth of the same frames:
//   AO (baked, cone): the ray-traced reference AO (ao/reference_ao.h), with rays added until its
//     standard error is a tenth of the smallest error measured, or the cap;
//   anti-aliasing: the frame rendered at 16× the size, each 16×16 block averaged (256 samples
//     a pixel, the box filter the SSAA resolve uses), on the pixels more than one surface covers;
//   shadows: the PCF shadow factor per pixel (the renderer's own buffer, kept in
//     FrameResources::shadow: it is no AOV) against 256 taps with no pre-test on an 8192² map.
//   setup precision: the visible primitive and its depth per pixel against the double-precision
//     reference ray caster (raster/reference_raycaster.h), on the views as given and with the
//     molecule and camera moved far from the origin, where float positions lose their digits.
#include <algorithm>
#include <cmath>
#include <glm/vec3.hpp>
#include <iterator>
#include <limits>

#include "cli/study.h"
#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "raster/gbuffer.h"
#include "raster/reference_raycaster.h"

namespace softmol::cli::study {
namespace {

constexpr int kAaReferenceScale = 16;      // samples per axis of the anti-aliasing reference
constexpr int kShadowReferenceTaps = 256;  // the most --pcf-samples takes
constexpr int kShadowReferenceMap = 8192;  // the largest --shadow-map
constexpr double kShadowThreshold = 1.0 / 255.0;

// What one render of a point keeps for the error: the AO AOV, the resolved colour or the
// shadow factors, per view; and the coverage it is measured on.
struct Output {
  std::vector<float> values;
  std::vector<uint8_t> mask;
  std::vector<uint32_t> id;  // the setup-precision method's visible primitives
};

RenderArgs PointArgs(const StudyOptions& o, const MethodPlan& plan, const SweepPoint& p) {
  static const io::ParamTable<RenderArgs> table = RenderParams();
  RenderArgs a = o.base;
  for (size_t k = 0; k < plan.knobs.size(); ++k) {
    const auto param = std::find_if(table.begin(), table.end(), [&](const auto& q) { return q.name == plan.knobs[k].name; });
    SOFTMOL_CHECK(param != table.end());
    param->set(a, p.values[k], io::FlagLocation(plan.knobs[k].name));
  }
  effects::CheckRenderOptions(a.options);
  return a;
}

// The passes a method renders: only what its error is measured on, plus what that needs.
effects::RenderOptions MethodOptions(Method m, const RenderArgs& a, const raster::PrimitiveScene& scene) {
  effects::RenderOptions o = a.options;
  o.shadows = false;
  o.ao = effects::AoMode::kNone;
  if (m == Method::kBakedAo || m == Method::kConeAo) {
    o.ao = m == Method::kBakedAo ? effects::AoMode::kBaked : effects::AoMode::kCone;
    if (m == Method::kBakedAo) o.bake = MakeBakeOptions(a.bake, scene);
    o.color = false;
    o.aovs = effects::kAovAo | effects::kAovId;
  }
  if (m == Method::kShadows) o.shadows = true;
  if (m == Method::kSetupPrecision) {
    o.color = false;
    o.aovs = effects::kAovDepth | effects::kAovId;
  }
  return o;
}

std::vector<uint8_t> VisibleMask(const std::vector<uint32_t>& id) {
  std::vector<uint8_t> mask(id.size());
  for (size_t i = 0; i < id.size(); ++i) mask[i] = id[i] != raster::kNoPrimitive;
  return mask;
}

std::vector<uint8_t> CoveredMask(const raster::GBuffer& g) {
  std::vector<uint8_t> mask(g.depth.size());
  for (size_t i = 0; i < g.depth.size(); ++i) mask[i] = std::isfinite(g.depth[i]);
  return mask;
}

Output Keep(Method m, const effects::RenderedFrame& f, const effects::FrameResources& res) {
  if (m == Method::kShadows) return {res.shadow, CoveredMask(res.gbuffer)};
  if (m == Method::kAntialiasing) return {std::vector<float>(f.rgba.begin(), f.rgba.end()), {}};
  if (m == Method::kSetupPrecision) return {f.depth, VisibleMask(f.id), f.id};
  return {f.ao, VisibleMask(f.id)};
}

// The passes whose time the method's frame pays (SSAA changes every pass: the whole frame; the
// setup precision only the G-buffer's setup stage).
double FrameMs(Method m, const effects::RenderedFrame& f) {
  if (m == Method::kAntialiasing) return f.totalMs;
  if (m == Method::kSetupPrecision) return f.rasterStats.setupMs;
  double ms = 0;
  for (const effects::PassTiming& p : f.passes) {
    const bool own = m == Method::kBakedAo  ? p.name == "baked ao lookup"
                     : m == Method::kConeAo ? p.name == "occupancy pyramid" || p.name == "cone ao"
                                            : p.name == "shadow map" || p.name == "shadows";
    if (own) ms += p.durationMs;
  }
  return ms;
}

struct Measured {
  std::vector<Output> views;  // from the first repetition
  Row row;
};

// Renders one point `repeats` times over every view. Each repetition bakes once (for every
// view: the bake does not depend on the camera); the cone pyramid is rebuilt every frame, as
// it is for a moving structure.
Measured MeasurePoint(Method m, const StudyInput& in, const effects::RenderOptions& o, int repeats) {
  Measured out;
  std::vector<std::pair<std::string, std::vector<double>>> passes;
  std::vector<double> setup, frame;
  effects::FrameResources res;
  res.keepGBuffer = m == Method::kShadows;  // Keep reads its coverage
  effects::RenderedFrame f;
  for (int r = 0; r < repeats; ++r)
    for (size_t v = 0; v < in.views.size(); ++v) {
      if (v == 0) res.atlasBaked = false;
      res.pyramid = ao::OccupancyPyramid();
      effects::RenderFrame(*in.scene, in.views[v], o, f, &res);
      for (const effects::PassTiming& p : f.passes) {
        auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& q) { return q.first == p.name; });
        if (it == passes.end()) it = passes.insert(passes.end(), {p.name, {}});
        it->second.push_back(p.durationMs);
        if (p.name == "ao bake") setup.push_back(p.durationMs);
      }
      frame.push_back(FrameMs(m, f));
      if (r == 0) out.views.push_back(Keep(m, f, res));
    }
  out.row.setupMs = setup.empty() ? 0.0 : Median(setup);
  out.row.frameMs = Median(frame);
  for (auto& [name, ms] : passes) out.row.passMs.emplace_back(name, Median(ms));
  return out;
}

// The values and masks of every view, end to end.
Output Concatenate(const std::vector<Output>& views) {
  Output all;
  for (const Output& v : views) {
    all.values.insert(all.values.end(), v.values.begin(), v.values.end());
    all.mask.insert(all.mask.end(), v.mask.begin(), v.mask.end());
    all.id.insert(all.id.end(), v.id.begin(), v.id.end());
  }
  return all;
}

// --- AO: the ray-traced reference --------------------------------------------------------

// The reference with `rays` rays a pixel, as the mean of two independent halves (seeds 1 and
// 2): their difference measures its standard error (`measuredSe`, RMS over the visible pixels)
// at no extra cost, beside the binomial bound.
Output ReferenceAo(const StudyInput& in, const StudyOptions& so, int rays, double& measuredSe) {
  effects::RenderOptions o = so.base.options;
  o.ao = effects::AoMode::kReference;
  o.reference.rays = std::max(1, rays / 2);
  o.color = false;
  o.aovs = effects::kAovAo | effects::kAovId;
  o.ssaa = 1;
  Output mean;
  double sum = 0;  // Σ (r1 − r2)² over the visible pixels
  size_t n = 0;
  for (const raster::Camera& cam : in.views) {
    o.reference.seed = 1;
    const effects::RenderedFrame f = effects::RenderFrame(*in.scene, cam, o);
    o.reference.seed = 2;
    const effects::RenderedFrame g = effects::RenderFrame(*in.scene, cam, o);
    for (size_t i = 0; i < f.ao.size(); ++i) {
      const bool visible = f.id[i] != raster::kNoPrimitive;
      mean.values.push_back(0.5f * (f.ao[i] + g.ao[i]));
      mean.mask.push_back(visible);
      if (visible) {
        const double d = double(f.ao[i]) - double(g.ao[i]);
        sum += d * d, ++n;
      }
    }
  }
  // Var(r1) = E[(r1 − r2)²] / 2 and the mean of two halves has half that.
  measuredSe = n ? std::sqrt(sum / double(n)) / 2.0 : 0.0;
  return mean;
}

double SmallestError(const std::vector<MethodResult*>& results) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const MethodResult* r : results)
    for (const Row& row : r->rows) smallest = std::min(smallest, row.error.mean);
  return smallest;
}

// Errors of the AO methods against one reference; outputs[m][i]: method m's point i, its views
// end to end.
void ScoreAo(const std::vector<MethodResult*>& results, const std::vector<std::vector<Output>>& outputs,
             const Output& ref) {
  for (size_t m = 0; m < results.size(); ++m)
    for (size_t i = 0; i < results[m]->rows.size(); ++i) {
      Row& row = results[m]->rows[i];
      row.error = AbsErrorStats(outputs[m][i].values, ref.values, ref.mask);
      row.errorP95 = row.error.p95;
    }
}

// The reference AO with enough rays that its standard error is under a tenth of the smallest
// error measured: one render at the minimum, then (if needed) one at the number of rays the
// binomial variance says is enough, within the cap.
void ScoreAgainstReferenceAo(const std::vector<MethodResult*>& results,
                             const std::vector<std::vector<Output>>& outputs, const StudyInput& in,
                             const StudyOptions& so) {
  int rays = std::min(so.minReferenceRays, so.maxReferenceRays);
  double measured = 0;
  Output ref = ReferenceAo(in, so, rays, measured);
  ScoreAo(results, outputs, ref);
  double se = BinomialStdError(ref.values, ref.mask, rays);
  double target = SmallestError(results) / 10.0;
  if (se > target && rays < so.maxReferenceRays) {
    const double needed = double(rays) * (se / std::max(target, 1e-12)) * (se / std::max(target, 1e-12));
    int next = rays;
    while (next < so.maxReferenceRays && double(next) < needed) next *= 2;
    rays = std::min(next, so.maxReferenceRays);
    ref = ReferenceAo(in, so, rays, measured);
    ScoreAo(results, outputs, ref);
    se = BinomialStdError(ref.values, ref.mask, rays);
    target = SmallestError(results) / 10.0;
  }
  char text[400];
  std::snprintf(text, sizeof text,
                "ray-traced reference AO, %d stratified rays a pixel (two seeded halves); its standard error per "
                "pixel (RMS over visible pixels) %.4g by the binomial bound, %.4g measured from the two halves; "
                "the bound is %s a tenth of the smallest mean error measured (%.4g)",
                rays, se, measured, se <= target ? "under" : "NOT under (the ray cap was reached)", target);
  for (MethodResult* r : results) {
    r->reference = text;
    r->referenceReached = se <= target;
    r->errorName = "mean |AO - reference| over visible pixels";
    r->p95Name = "p95 |AO - reference|";
  }
}

// --- anti-aliasing: 16×16 samples a pixel ----------------------------------------------------

// The colour of each pixel of `cam` averaged over its s×s samples in `f` (rendered at s× the
// size), and the silhouette mask: pixels whose samples see more than one primitive (or a
// primitive and the background).
Output BoxDownsample(const effects::RenderedFrame& f, const raster::Camera& cam, int s) {
  Output v;
  v.values.assign(size_t(cam.width) * cam.height * 4, 0.0f);
  v.mask.assign(size_t(cam.width) * cam.height, 0);
  const size_t bigWidth = size_t(cam.width) * size_t(s);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      double sum[4] = {0, 0, 0, 0};
      const uint32_t first = f.id[size_t(y * s) * bigWidth + size_t(x * s)];
      bool edge = false;
      for (int sy = 0; sy < s; ++sy)
        for (int sx = 0; sx < s; ++sx) {
          const size_t i = size_t(y * s + sy) * bigWidth + size_t(x * s + sx);
          for (int c = 0; c < 4; ++c) sum[c] += f.rgba[4 * i + size_t(c)];
          edge |= f.id[i] != first;
        }
      const size_t pixel = size_t(y) * cam.width + size_t(x);
      for (int c = 0; c < 4; ++c) v.values[4 * pixel + size_t(c)] = float(sum[c] / double(s * s));
      v.mask[pixel] = edge;
    }
  return v;
}

// The anti-aliasing ground truth of every view: kAaReferenceScale² samples a pixel.
Output AaReference(const StudyInput& in, const StudyOptions& so) {
  effects::RenderOptions o = MethodOptions(Method::kAntialiasing, so.base, *in.scene);
  o.ssaa = 1;
  o.aovs = effects::kAovId;
  std::vector<Output> views;
  for (const raster::Camera& cam : in.views) {
    raster::Camera big = cam;
    big.width *= kAaReferenceScale;
    big.height *= kAaReferenceScale;
    views.push_back(BoxDownsample(effects::RenderFrame(*in.scene, big, o), cam, kAaReferenceScale));
  }
  return Concatenate(views);
}

// Per silhouette pixel: the mean over R, G, B of |colour − reference| (linear, premultiplied).
void ScoreAa(MethodResult& result, const std::vector<std::vector<Output>>& outputs, const Output& ref) {
  for (size_t i = 0; i < result.rows.size(); ++i) {
    const Output all = Concatenate(outputs[i]);
    std::vector<float> a, b;
    std::vector<uint8_t> mask;
    for (size_t p = 0; p < ref.mask.size(); ++p) {
      double d = 0;
      for (int c = 0; c < 3; ++c) d += std::fabs(double(all.values[4 * p + size_t(c)]) - ref.values[4 * p + size_t(c)]);
      a.push_back(float(d / 3.0));
      b.push_back(0.0f);
      mask.push_back(ref.mask[p]);
    }
    result.rows[i].error = AbsErrorStats(a, b, mask);
    result.rows[i].errorP95 = result.rows[i].error.p95;
  }
  result.errorName = "mean colour error on silhouette pixels (linear RGB; |d| averaged over R G B)";
  result.p95Name = "p95 colour error on silhouette pixels";
  result.reference = "the same frame at 16x the size with each 16x16 block averaged (256 samples a pixel); "
                     "silhouette pixels: those whose samples see more than one surface";
}

// --- shadows: the shadow factor --------------------------------------------------------------

void ScoreShadows(MethodResult& result, const std::vector<std::vector<Output>>& outputs, const StudyInput& in,
                  const StudyOptions& so) {
  RenderArgs a = so.base;
  a.options.shadow.pcfSamples = kShadowReferenceTaps;
  a.options.shadow.pretestSamples = 0;
  a.options.shadow.mapSize = kShadowReferenceMap;
  const effects::RenderOptions o = MethodOptions(Method::kShadows, a, *in.scene);
  const Output ref = Concatenate(MeasurePoint(Method::kShadows, in, o, 1).views);
  for (size_t i = 0; i < result.rows.size(); ++i) {
    const Output all = Concatenate(outputs[i]);
    std::vector<float> diff(all.values.size());
    size_t over = 0;
    for (size_t p = 0; p < diff.size(); ++p) {
      diff[p] = std::fabs(all.values[p] - ref.values[p]);
      over += ref.mask[p] && diff[p] > kShadowThreshold;
    }
    const std::vector<float> zero(diff.size(), 0.0f);
    const ErrorStats s = AbsErrorStats(diff, zero, ref.mask);
    result.rows[i].error.count = s.count;
    result.rows[i].error.mean = s.count ? double(over) / double(s.count) : 0.0;
    result.rows[i].error.p95 = s.p95;
    result.rows[i].errorP95 = s.p95;
  }
  result.errorName = "fraction of covered pixels whose shadow factor differs by more than 1/255";
  result.p95Name = "p95 |shadow factor - reference|";
  result.reference = "PCF with 256 taps and no pre-test on an 8192^2 map (the shadow factor read from the "
                     "renderer's per-sample shadow buffer)";
}

// --- setup precision: the double-precision reference ray caster --------------------------------

// Where the molecule is moved (Å along (1, −1, 1)): as given, the PDB format's largest
// coordinates, and a capsid's world (tests/support/scenes.h has a shell there too).
constexpr double kSetupOffsets[] = {0.0, 1e4, 1e5};

// The study's scene and views moved by `offset`, or (offset 0) the study's own.
struct SetupCase {
  double offset = 0;
  const raster::PrimitiveScene* given = nullptr;
  raster::PrimitiveScene moved;  // offset != 0
  std::vector<raster::Camera> views;
  const raster::PrimitiveScene& Scene() const { return offset == 0.0 ? *given : moved; }
};

void Translate(std::vector<double>& x, std::vector<double>& y, std::vector<double>& z, const glm::dvec3& d) {
  for (size_t i = 0; i < x.size(); ++i) x[i] += d.x, y[i] += d.y, z[i] += d.z;
}

std::vector<SetupCase> SetupCases(const StudyInput& in) {
  std::vector<SetupCase> cases(std::size(kSetupOffsets));
  for (size_t c = 0; c < cases.size(); ++c) {
    SetupCase& k = cases[c];
    k.offset = kSetupOffsets[c];
    k.views = in.views;
    k.given = in.scene;
    if (k.offset == 0.0) continue;
    const glm::dvec3 d = k.offset * glm::dvec3(1.0, -1.0, 1.0);
    k.moved = *in.scene;
    Translate(k.moved.spheres.x, k.moved.spheres.y, k.moved.spheres.z, d);
    Translate(k.moved.cylinders.x0, k.moved.cylinders.y0, k.moved.cylinders.z0, d);
    Translate(k.moved.cylinders.x1, k.moved.cylinders.y1, k.moved.cylinders.z1, d);
    Translate(k.moved.ellipsoids.x, k.moved.ellipsoids.y, k.moved.ellipsoids.z, d);
    for (raster::Camera& cam : k.views) cam.eye += d, cam.target += d;
  }
  return cases;
}

// Every case's views end to end; the times are the unmoved case's (the same work).
Measured MeasureSetupPoint(const std::vector<SetupCase>& cases, const effects::RenderOptions& o, int repeats) {
  Measured out;
  for (size_t c = 0; c < cases.size(); ++c) {
    Measured m = MeasurePoint(Method::kSetupPrecision, {&cases[c].Scene(), cases[c].views}, o, c == 0 ? repeats : 1);
    if (c == 0) out.row = std::move(m.row);
    for (Output& v : m.views) out.views.push_back(std::move(v));
  }
  return out;
}

// One case's disagreement with the reference: pixels covered by either, pixels whose visible
// primitive differs, and |depth − reference| where both see the same primitive.
struct SetupError {
  size_t covered = 0, differ = 0;
  std::vector<double> depthError;
  void Add(const Output& view, const raster::ReferenceImage& ref) {
    for (int row = 0; row < ref.height; ++row)
      for (int x = 0; x < ref.width; ++x) {
        const size_t i = size_t(row) * size_t(ref.width) + size_t(x);
        const size_t r = ref.Index(x, ref.height - 1 - row);  // the AOVs' rows top-down, the reference's bottom-up
        if (view.id[i] == raster::kNoPrimitive && ref.id[r] == raster::kNoPrimitive) continue;
        ++covered;
        if (view.id[i] != ref.id[r]) ++differ;
        else depthError.push_back(std::fabs(double(view.values[i]) - ref.depth[r]));
      }
  }
  double Fraction() const { return covered ? double(differ) / double(covered) : 0.0; }
  double MeanDepth() const {
    double sum = 0;
    for (double e : depthError) sum += e;
    return depthError.empty() ? 0.0 : sum / double(depthError.size());
  }
};

void ScoreSetup(MethodResult& result, const std::vector<std::vector<Output>>& outputs,
                const std::vector<SetupCase>& cases) {
  std::vector<raster::ReferenceImage> refs;  // case-major, as MeasureSetupPoint keeps the views
  for (const SetupCase& c : cases)
    for (const raster::Camera& cam : c.views) refs.push_back(raster::RayCastReference(c.Scene(), cam));
  std::string table = "Per case (the molecule and camera moved along (1, -1, 1) by the offset):\n\n"
                      "| point | offset Å | coverage error | mean depth error Å | p95 depth error Å |\n"
                      "|---|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < result.rows.size(); ++i) {
    SetupError all;
    for (size_t c = 0, v = 0; c < cases.size(); ++c) {
      SetupError one;
      for (size_t k = 0; k < cases[c].views.size(); ++k, ++v) one.Add(outputs[i][v], refs[v]);
      char line[200];
      std::snprintf(line, sizeof line, "| %s | %.0e | %.6f | %.3g | %.3g |\n", result.rows[i].label.c_str(),
                    cases[c].offset, one.Fraction(), one.MeanDepth(), Percentile(one.depthError, 0.95));
      table += line;
      all.covered += one.covered, all.differ += one.differ;
      all.depthError.insert(all.depthError.end(), one.depthError.begin(), one.depthError.end());
    }
    Row& row = result.rows[i];
    row.error.count = all.covered;
    row.error.mean = all.Fraction();
    row.error.p95 = row.errorP95 = Percentile(all.depthError, 0.95);
  }
  result.detail = table;
  result.errorName = "fraction of covered pixels whose visible primitive differs from the reference";
  result.p95Name = "p95 |depth - reference| (Å) where both see the same primitive";
  result.reference = "the double-precision reference ray caster (each pixel's ray against the primitives in "
                     "double, no setup and no kernels), on the views as given and with the molecule and camera "
                     "moved 1e4 and 1e5 Å from the origin; the cost is the G-buffer's setup stage";
}

// Every method's errors against its ground truth; the AO methods share one reference.
void ScoreAll(const std::vector<MethodPlan>& plans, std::vector<MethodResult>& results,
              std::vector<std::vector<std::vector<Output>>>& outputs, const StudyInput& in, const StudyOptions& so,
              const std::vector<SetupCase>& setupCases) {
  std::vector<MethodResult*> aoResults;
  std::vector<std::vector<Output>> aoOutputs;  // per AO method and point: its views end to end
  for (size_t m = 0; m < plans.size(); ++m) {
    if (plans[m].method == Method::kAntialiasing) ScoreAa(results[m], outputs[m], AaReference(in, so));
    if (plans[m].method == Method::kShadows) ScoreShadows(results[m], outputs[m], in, so);
    if (plans[m].method == Method::kSetupPrecision) ScoreSetup(results[m], outputs[m], setupCases);
    if (plans[m].method != Method::kBakedAo && plans[m].method != Method::kConeAo) continue;
    aoResults.push_back(&results[m]);
    std::vector<Output> points;
    for (const std::vector<Output>& views : outputs[m]) points.push_back(Concatenate(views));
    aoOutputs.push_back(std::move(points));
    outputs[m].clear();
  }
  if (!aoResults.empty()) ScoreAgainstReferenceAo(aoResults, aoOutputs, in, so);
}

void MarkFront(MethodResult& r) {
  std::vector<double> cost, error;
  for (const Row& row : r.rows) cost.push_back(row.setupMs + row.frameMs), error.push_back(row.error.mean);
  const std::vector<bool> front = ParetoFront(cost, error);
  for (size_t i = 0; i < r.rows.size(); ++i) r.rows[i].front = front[i];
}

// Two points of the baked method whose automatic choices resolve to the same bake (the default's
// automatic patch is one of the swept sizes) are one render: measured once, so that the same
// work gets the same time. Empty: never the same (the other methods choose nothing themselves).
std::string SameRenderKey(Method m, const effects::RenderOptions& o) {
  if (m != Method::kBakedAo) return "";
  const ao::BakeOptions& b = o.bake;
  char key[160];
  std::snprintf(key, sizeof key, "%d %d %.9g %d %d %d %d", b.directions, b.shadowMapSize, double(b.depthBias),
                b.atlas.textureSide, b.atlas.patchSize, int(b.atlas.sphereMap), b.atlas.cylindersPerPatch);
  return key;
}

}  // namespace

std::vector<MethodResult> RunStudy(const std::vector<MethodPlan>& plans, const StudyInput& in,
                                   const StudyOptions& so) {
  SOFTMOL_CHECK(in.scene && !in.views.empty() && so.repeats >= 1);
  std::vector<MethodResult> results(plans.size());
  std::vector<std::vector<std::vector<Output>>> outputs(plans.size());  // method, point, view
  size_t total = 0, done = 0;
  for (const MethodPlan& p : plans) total += SweepPoints(p, Defaults(p)).size();
  const bool setup = std::any_of(plans.begin(), plans.end(), [](const auto& p) { return p.method == Method::kSetupPrecision; });
  const std::vector<SetupCase> setupCases = setup ? SetupCases(in) : std::vector<SetupCase>();
  for (size_t m = 0; m < plans.size(); ++m) {
    MethodResult& r = results[m];
    r.plan = plans[m];
    r.defaults = Defaults(plans[m]);
    auto options = [&](const SweepPoint& point) {
      return MethodOptions(plans[m].method, PointArgs(so, plans[m], point), *in.scene);
    };
    auto measure = [&](const effects::RenderOptions& o, int repeats) {
      return plans[m].method == Method::kSetupPrecision ? MeasureSetupPoint(setupCases, o, repeats)
                                                       : MeasurePoint(plans[m].method, in, o, repeats);
    };
    const std::vector<SweepPoint> points = SweepPoints(plans[m], r.defaults);
    // One untimed render first: the method's first frame touches its buffers fresh (page faults,
    // allocation) and would make whichever point comes first, the default, look dearer than the
    // same work done later.
    (void)measure(options(points.front()), 1);
    std::vector<std::string> resolved;  // per point measured: SameRender's key
    for (const SweepPoint& point : points) {
      const std::string label = Label(plans[m], r.defaults, point);
      if (so.progress) so.progress(done++, total, plans[m].name, label);
      const effects::RenderOptions o = options(point);
      resolved.push_back(SameRenderKey(plans[m].method, o));
      const auto same = std::find(resolved.begin(), resolved.end() - 1, resolved.back());
      Measured measured;
      if (!resolved.back().empty() && same != resolved.end() - 1) {  // measured already
        const size_t k = size_t(same - resolved.begin());
        measured.row = r.rows[k];
        measured.views = outputs[m][k];
      } else {
        measured = measure(o, so.repeats);
      }
      measured.row.point = point;
      measured.row.label = label;
      r.rows.push_back(std::move(measured.row));
      outputs[m].push_back(std::move(measured.views));
    }
  }
  if (so.progress) so.progress(done, total, "reference", "ground truth");
  ScoreAll(plans, results, outputs, in, so, setupCases);
  for (MethodResult& r : results) MarkFront(r);
  return results;
}

}  // namespace softmol::cli::study

// effects/depth_halos.cpp — the depth-aware halo pass (Tarini et al. 2006 §5.2): per-atom disc
// setup in double, binning of the discs into bands of rows (common/binning.h), one TBB task per
// band (disjoint outputs), the Highway kernel of effects/depth_halos-inl.h dispatched once per
// band, and the scalar twin built from effects/shared/depth_halo.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/depth_halos.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/depth_halos-inl.h"

#if HWY_ONCE
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/binning.h"
#include "common/check.h"
#include "effects/depth_halos.h"
#include "effects/shared/prelude.h"
#include "raster/detail/setup.h"

namespace softmol::effects {
HWY_EXPORT(DepthHaloBandImpl);

namespace {

using detail::HaloBand;
using detail::HaloDisc;
using detail::HaloFrame;

// Rows per band: one TBB task each. 16 rows of 1920 samples keep a band's depth copy and
// accumulators (2 × 126 KB) in L2, and give 68 tasks at 1080p for load balance.
constexpr int kBandRows = 16;
// Discs farther than this from the eye (or larger) are dropped: their squares (≤ 1e30) and the
// products with |d|² (tan-space, < 1e5 for any field of view below 179°) stay far below
// FLT_MAX, so no kernel value can overflow to inf.
constexpr double kMaxExtent = 1e15;

bool Finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Pixels whose centres (p + 0.5) lie in [lo, hi] (ray units), widened by one pixel: the box only
// has to be conservative, the kernel decides coverage per sample.
bool PixelRange(double lo, double hi, double invScale, double half, int size, int32_t& p0,
                int32_t& p1) {
  const auto clampBig = [](double x) { return x < -1e9 ? -1e9 : (x > 1e9 ? 1e9 : x); };
  const double a = std::ceil(clampBig(lo * invScale + half - 0.5) - 1.0);
  const double b = std::floor(clampBig(hi * invScale + half - 0.5) + 1.0);
  if (!(a <= b) || b < 0.0 || a > double(size - 1)) return false;
  p0 = int32_t(std::max(a, 0.0));
  p1 = int32_t(std::min(b, double(size - 1)));
  return true;
}

// The disc of sphere i, or false when it is not drawn (degenerate, non-finite, clipped by the
// near or far plane, or off screen).
bool SetupDisc(const raster::SphereSet& spheres, size_t i, const raster::detail::ViewSetup& view,
               double size, HaloDisc& disc) {
  const double r = spheres.radius[i];
  if (!(r > 0.0) || !std::isfinite(r)) return false;
  const glm::dvec3 c = view.ToEye(spheres.x[i], spheres.y[i], spheres.z[i]);
  if (!Finite(c)) return false;
  const double discDepth = -c.z;
  // A GPU clips the flat disc against the near and far planes: drawn only between them.
  if (!(discDepth >= view.nearPlane && discDepth <= view.farPlane)) return false;
  const double haloR = r + size;
  if (!(std::abs(c.x) < kMaxExtent && std::abs(c.y) < kMaxExtent &&
        std::abs(c.z) < kMaxExtent && haloR < kMaxExtent))
    return false;
  // The disc covers the silhouette of the sphere of radius haloR (depth_halo.inc), whose tight
  // bounds are the rasterizer's own (Sigg et al. eq. 5 with S = haloR²·I).
  const double S[3][3] = {{haloR * haloR, 0, 0}, {0, haloR * haloR, 0}, {0, 0, haloR * haloR}};
  double lo[2], hi[2];
  const bool bounded = raster::detail::TangentBounds(view.ortho, c, S, 0, lo[0], hi[0]) &&
                       raster::detail::TangentBounds(view.ortho, c, S, 1, lo[1], hi[1]);
  if (bounded) {
    if (!PixelRange(lo[0], hi[0], view.invPixelScale, view.halfWidth, view.width, disc.x0,
                    disc.x1) ||
        !PixelRange(lo[1], hi[1], view.invPixelScale, view.halfHeight, view.height, disc.y0,
                    disc.y1))
      return false;
  } else {  // the disc reaches the eye plane: its projection is no ellipse, take the screen
    disc.x0 = 0, disc.y0 = 0, disc.x1 = view.width - 1, disc.y1 = view.height - 1;
  }
  disc.cx = float(c.x), disc.cy = float(c.y), disc.cz = float(c.z);
  disc.rr = float(r * r);
  disc.haloR = float(haloR);
  disc.haloRR = float(haloR * haloR);
  disc.discDepth = float(discDepth);
  return true;
}

// Scalar twin of DepthHaloBandImpl: effects/shared/depth_halo.inc, sample by sample.
void DepthHaloBandScalar(const HaloFrame& f, const HaloDisc* discs, const uint32_t* list,
                         size_t count, const HaloBand& band) {
  for (size_t k = 0; k < count; ++k) {
    const HaloDisc& s = discs[list[k]];
    const int y0 = std::max(s.y0, band.y0), y1 = std::min(s.y1, band.y1 - 1);
    for (int y = y0; y <= y1; ++y) {
      const float v = raster::shared::PixelToRay(float(y), f.halfHeight, f.pixelScale);
      const shared::DepthHaloRow row = shared::DepthHaloRowSetup(f.ortho, v, s.cx, s.cy, s.cz);
      const size_t offset = size_t(y - band.y0) * size_t(band.stride);
      for (int x = s.x0; x <= s.x1; ++x) {
        const float u = raster::shared::PixelToRay(float(x), f.halfWidth, f.pixelScale);
        const float opacity = shared::DepthHaloOpacity(
            f.ortho, u, row, s.cx, s.cy, s.cz, s.rr, s.haloR, s.haloRR, s.discDepth,
            band.depth[offset + size_t(x)], f.invSize, f.maxGap, f.invMaxGap, f.strength);
        uint32_t& acc = band.acc[offset + size_t(x)];
        const uint32_t sum = acc + uint32_t(shared::DepthHaloQuantize(opacity));
        acc = sum < detail::kDepthHaloOne ? sum : detail::kDepthHaloOne;
      }
    }
  }
}

// The SIMD kernel, dispatched once per band (never per row or pixel).
void DepthHaloBand(const HaloFrame& f, const HaloDisc* discs, const uint32_t* list, size_t count,
                   const HaloBand& band) {
  HWY_DYNAMIC_DISPATCH(DepthHaloBandImpl)(f, discs, list, count, band);
}

using BandFn = void (*)(const HaloFrame&, const HaloDisc*, const uint32_t*, size_t,
                        const HaloBand&);

}  // namespace

namespace detail {

DepthHaloSetup PrepareDepthHalos(const raster::PrimitiveScene& scene, const raster::Camera& cam,
                                 const DepthHaloOptions& o) {
  const raster::detail::ViewSetup view = raster::detail::MakeViewSetup(cam, scene);
  const raster::detail::FrameConstants fc = raster::detail::MakeFrameConstants(view, 0);
  DepthHaloSetup s;
  HaloFrame& f = s.frame;
  f.halfWidth = fc.halfWidth, f.halfHeight = fc.halfHeight, f.pixelScale = fc.pixelScale;
  f.ortho = fc.ortho;
  f.invSize = 1.0f / o.size;
  f.maxGap = o.maxGap;
  f.invMaxGap = 1.0f / o.maxGap;
  f.strength = o.strength;
  // Each sphere writes only its own slot.
  const raster::SphereSet& spheres = scene.spheres;
  const size_t n = spheres.size();
  s.discs.resize(n);
  s.drawn.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 2048), [&](const auto& range) {
    for (size_t i = range.begin(); i != range.end(); ++i)
      s.drawn[i] = SetupDisc(spheres, i, view, double(o.size), s.discs[i]) ? 1 : 0;
  });
  return s;
}

}  // namespace detail

namespace {

void RunDepthHalos(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                   const raster::GBuffer& g, const DepthHaloOptions& o, std::span<float> halo,
                   bool scalar) {
  SOFTMOL_CHECK(ValidDepthHaloOptions(o));
  const int width = g.width, height = g.height;
  SOFTMOL_CHECK(width >= 0 && height >= 0);
  SOFTMOL_CHECK(halo.size() == size_t(width) * size_t(height));
  SOFTMOL_CHECK(g.depth.size() == halo.size());
  if (halo.empty()) return;

  raster::Camera cam = camera;
  cam.width = width, cam.height = height;
  const detail::DepthHaloSetup setup = detail::PrepareDepthHalos(scene, cam, o);
  const HaloFrame& f = setup.frame;
  const std::vector<HaloDisc>& discs = setup.discs;
  const std::vector<uint8_t>& drawn = setup.drawn;
  const size_t n = discs.size();

  // Each band's discs, in sphere order (common/binning.h). The sum is exact, so the order
  // within a band does not change the result; a fixed order still keeps every run identical.
  const int bands = (height + kBandRows - 1) / kBandRows;
  Bins bins;
  std::vector<uint32_t> list;
  BinItems(
      n, size_t(bands),
      [&](size_t i, auto&& f) {
        if (drawn[i])
          for (int b = discs[i].y0 / kBandRows; b <= discs[i].y1 / kBandRows; ++b) f(size_t(b));
      },
      [](size_t i) { return uint32_t(i); }, bins, list);

  const BandFn draw = scalar ? &DepthHaloBandScalar : &DepthHaloBand;
  const int stride = width + detail::kDepthHaloRowPad;
  tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const auto& range) {
    std::vector<float> depth(size_t(kBandRows) * size_t(stride));
    std::vector<uint32_t> acc(depth.size());
    for (int b = range.begin(); b != range.end(); ++b) {
      HaloBand band;
      band.y0 = b * kBandRows;
      band.y1 = std::min(height, band.y0 + kBandRows);
      band.stride = stride;
      band.depth = depth.data();
      band.acc = acc.data();
      const size_t count = bins.Size(size_t(b));
      if (count == 0) {
        std::fill(halo.begin() + ptrdiff_t(size_t(band.y0) * size_t(width)),
                  halo.begin() + ptrdiff_t(size_t(band.y1) * size_t(width)), 0.0f);
        continue;
      }
      // The band's depth rows, padded with 0 (never read as a sample: masked off).
      std::fill(depth.begin(), depth.end(), 0.0f);
      std::fill(acc.begin(), acc.end(), 0u);
      for (int y = band.y0; y < band.y1; ++y)
        std::copy_n(g.depth.data() + g.Index(0, y), width,
                    depth.data() + size_t(y - band.y0) * size_t(stride));
      draw(f, discs.data(), list.data() + bins.Begin(size_t(b)), count, band);
      // Fixed point to float: an exact scaling by 2^-16, at most 1.
      for (int y = band.y0; y < band.y1; ++y) {
        const uint32_t* in = acc.data() + size_t(y - band.y0) * size_t(stride);
        float* out = halo.data() + size_t(y) * size_t(width);
        for (int x = 0; x < width; ++x)
          out[x] = float(in[x]) * (1.0f / float(detail::kDepthHaloOne));
      }
    }
  });
}

}  // namespace

bool DepthHaloCamera(const raster::PrimitiveScene& scene, const raster::Camera& samples, float nearClip,
                     raster::Camera& view) {
  view = samples;
  if (nearClip > 0) {
    if (view.nearPlane <= 0 || view.farPlane <= 0) raster::FitNearFar(view, scene);
    view.nearPlane = std::max(view.nearPlane, double(nearClip));
  }
  return view.nearPlane < view.farPlane || view.nearPlane <= 0;
}

bool ValidDepthHaloOptions(const DepthHaloOptions& o) {
  return std::isfinite(o.size) && o.size > 0.0f && o.size <= 1000.0f && std::isfinite(o.strength) &&
         o.strength > 0.0f && o.strength <= 1.0f && std::isfinite(o.maxGap) && o.maxGap > 0.0f && o.maxGap <= 1e6f;
}

void ComputeDepthHalos(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                       const raster::GBuffer& gbuffer, const DepthHaloOptions& options,
                       std::span<float> halo) {
  RunDepthHalos(scene, camera, gbuffer, options, halo, /*scalar=*/false);
}

void ComputeDepthHalosScalar(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                             const raster::GBuffer& gbuffer, const DepthHaloOptions& options,
                             std::span<float> halo) {
  RunDepthHalos(scene, camera, gbuffer, options, halo, /*scalar=*/true);
}

}  // namespace softmol::effects
#endif  // HWY_ONCE

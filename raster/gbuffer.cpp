// raster/gbuffer.cpp — G-buffer allocation.
#include "raster/gbuffer.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace softmol::raster {
namespace {

// Samples per task of the parallel clear: a few pages, so first-touch faults spread over the
// threads.
constexpr size_t kClearGrain = 1 << 16;

template <class T>
void SizePlane(Plane<T>& v, bool want, size_t n, bool clear) {
  if (!want) {
    Plane<T>().swap(v);
    return;
  }
  const size_t kept = std::min(v.size(), n);
  v.resize(n);  // new elements uninitialised (UninitAllocator)
  if (!clear) return;
  tbb::parallel_for(tbb::blocked_range<size_t>(kept, n, kClearGrain), [&](const tbb::blocked_range<size_t>& r) {
    std::fill(v.begin() + std::ptrdiff_t(r.begin()), v.begin() + std::ptrdiff_t(r.end()), T(0));
  });
}

}  // namespace

void GBuffer::Resize(int w, int h, uint32_t ch, bool clear) {
  width = w;
  height = h;
  channels = ch | kDepth;
  const size_t n = size_t(w) * size_t(h);
  SizePlane(depth, true, n, clear);
  SizePlane(normalX, channels & kNormal, n, clear);
  SizePlane(normalY, channels & kNormal, n, clear);
  SizePlane(normalZ, channels & kNormal, n, clear);
  SizePlane(baseColor, channels & kBaseColor, n, clear);
  SizePlane(primitiveId, channels & kPrimitiveId, n, clear);
  SizePlane(surfaceU, channels & kSurfaceCoord, n, clear);
  SizePlane(surfaceV, channels & kSurfaceCoord, n, clear);
  SizePlane(surfaceW, channels & kSurfaceCoord, n, clear);
  SizePlane(line, channels & kLine, n, clear);
  SizePlane(capped, channels & kCapped, n, clear);
}

}  // namespace softmol::raster

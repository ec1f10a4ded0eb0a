// raster/gbuffer.cpp — G-buffer allocation.
#include "raster/gbuffer.h"

#include <algorithm>
#include <span>

#include "common/first_touch.h"

namespace softmol::raster {
namespace {

template <class T>
void SizePlane(Plane<T>& v, bool want, size_t n, bool clear) {
  if (!want) {
    Plane<T>().swap(v);
    return;
  }
  const size_t kept = std::min(v.size(), n);
  v.resize(n);  // new elements uninitialised (UninitAllocator)
  if (clear) FillInParallel(std::span(v).subspan(kept), T(0));  // first-touch faults on every thread
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

// raster/gbuffer.cpp — G-buffer allocation.
#include "raster/gbuffer.h"

namespace softmol::raster {
namespace {
template <class T>
void Plane(std::vector<T>& v, bool want, size_t n) {
  if (want) {
    v.resize(n);
  } else {
    std::vector<T>().swap(v);
  }
}
}  // namespace

void GBuffer::Resize(int w, int h, uint32_t ch) {
  width = w;
  height = h;
  channels = ch | kDepth;
  const size_t n = size_t(w) * size_t(h);
  Plane(depth, true, n);
  Plane(normalX, channels & kNormal, n);
  Plane(normalY, channels & kNormal, n);
  Plane(normalZ, channels & kNormal, n);
  Plane(baseColor, channels & kBaseColor, n);
  Plane(primitiveId, channels & kPrimitiveId, n);
  Plane(surfaceU, channels & kSurfaceCoord, n);
  Plane(surfaceV, channels & kSurfaceCoord, n);
  Plane(surfaceW, channels & kSurfaceCoord, n);
  Plane(line, channels & kLine, n);
  Plane(capped, channels & kCapped, n);
}

}  // namespace softmol::raster

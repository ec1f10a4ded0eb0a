// raster/gbuffer.cpp — G-buffer allocation.
#include "raster/gbuffer.h"

namespace softmol::raster {
namespace {
template <class T>
void SizePlane(Plane<T>& v, bool want, size_t n) {
  if (want) {
    v.resize(n);
  } else {
    Plane<T>().swap(v);
  }
}
}  // namespace

void GBuffer::Resize(int w, int h, uint32_t ch) {
  width = w;
  height = h;
  channels = ch | kDepth;
  const size_t n = size_t(w) * size_t(h);
  SizePlane(depth, true, n);
  SizePlane(normalX, channels & kNormal, n);
  SizePlane(normalY, channels & kNormal, n);
  SizePlane(normalZ, channels & kNormal, n);
  SizePlane(baseColor, channels & kBaseColor, n);
  SizePlane(primitiveId, channels & kPrimitiveId, n);
  SizePlane(surfaceU, channels & kSurfaceCoord, n);
  SizePlane(surfaceV, channels & kSurfaceCoord, n);
  SizePlane(surfaceW, channels & kSurfaceCoord, n);
  SizePlane(line, channels & kLine, n);
  SizePlane(capped, channels & kCapped, n);
}

}  // namespace softmol::raster

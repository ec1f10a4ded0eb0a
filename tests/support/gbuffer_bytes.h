// tests/support/gbuffer_bytes.h — every plane of a G-buffer as one byte string, in a fixed
// order (absent channels add nothing): the tests' bit-for-bit comparison of two renders.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "raster/gbuffer.h"

namespace softmol::test {

inline std::vector<uint8_t> GBufferBytes(const raster::GBuffer& g) {
  std::vector<uint8_t> b;
  auto add = [&](const auto& v) {
    const size_t n = v.size() * sizeof(v[0]);
    const size_t o = b.size();
    b.resize(o + n);
    if (n) std::memcpy(b.data() + o, v.data(), n);
  };
  add(g.depth), add(g.normalX), add(g.normalY), add(g.normalZ), add(g.baseColor);
  add(g.primitiveId), add(g.surfaceU), add(g.surfaceV), add(g.surfaceW);
  add(g.line), add(g.capped);
  return b;
}

}  // namespace softmol::test

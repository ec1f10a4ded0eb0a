// effects/color.h — colour encodings: sRGB 8-bit <-> linear light. Shading happens in linear
// light (DESIGN.md); PNG output is sRGB-encoded. Both directions are table-driven, so the bits
// never depend on a libm call inside a kernel: decoding is a 256-entry table and encoding
// is a search in a table of the 255 decision thresholds between neighbouring 8-bit codes.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace softmol::effects {

// Linear value of an sRGB-encoded 8-bit code (IEC 61966-2-1), exact to float rounding.
float SrgbToLinear(uint8_t code);

// The 8-bit sRGB code nearest to a linear value (clamped to [0,1]; NaN maps to 0).
uint8_t LinearToSrgb8(float linear);

// n pixels of premultiplied linear RGBA (4 floats each) to 8-bit sRGB: RGB (3 bytes a pixel),
// or with straight alpha RGBA (4 bytes; alpha rounded, colour un-premultiplied first). Each
// colour channel is exactly LinearToSrgb8.
void EncodeSrgb8Pixels(const float* rgba, size_t n, bool withAlpha, uint8_t* out);
// The same from four planes (channel c of pixel i at c[i]): EncodeSrgb8Pixels' bytes for the
// pixels those planes interleave to, without interleaving them first.
void EncodeSrgb8Planes(const float* r, const float* g, const float* b, const float* a, size_t n, bool withAlpha,
                       uint8_t* out);

// The 256-entry decode table itself (SrgbToLinear(k) == SrgbDecodeTable()[k]), for loops
// that want to look it up without a call per channel.
const float* SrgbDecodeTable();

// Linear RGB of a packed sRGB colour 0xRRGGBB.
struct LinearRgb {
  float r, g, b;
};
LinearRgb UnpackSrgb(uint32_t rgb);
inline glm::vec3 LinearFromSrgb(uint32_t rgb) {
  const LinearRgb c = UnpackSrgb(rgb);
  return glm::vec3(c.r, c.g, c.b);
}

}  // namespace softmol::effects

// io/image_io.h — writes rendered images through OpenImageIO: PNG (8-bit sRGB, RGB or RGBA)
// and OpenEXR (linear float colour plus AOV channels: Z, N.x N.y N.z, AO as float32, id as
// uint32). Files are written to a temporary name and renamed at the end, so a failure never
// leaves a half-written image. Images here are stored top row first (file order).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softmol::io {

// One named channel: float32 (`values`) or uint32 (`ids`, then `values` is empty).
struct ImageChannel {
  std::string name;              // "R", "G", "B", "A", "Z", "N.x", "id", "AO", ...
  std::vector<float> values;     // width*height, top row first
  std::vector<uint32_t> ids;     // width*height, top row first (uint32 channels only)
};

struct ImageFile {
  int width = 0, height = 0;
  std::vector<ImageChannel> channels;
};

// PNG: 8-bit, `channels` is 3 (RGB) or 4 (RGBA), pixels interleaved, top row first.
void WritePng(const std::string& path, int width, int height, int channels,
              const std::vector<uint8_t>& pixels);

// OpenEXR with every channel of `image` (mixed float32 / uint32), zip-compressed.
void WriteExr(const std::string& path, const ImageFile& image);

// Reads any image OpenImageIO knows as 8-bit interleaved pixels (for tests and `diff`).
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};
Image8 ReadImage8(const std::string& path);

// Reads an EXR (or other float image) as float channels with their names; uint32 channels are
// returned in ImageChannel::ids.
ImageFile ReadExr(const std::string& path);

}  // namespace softmol::io

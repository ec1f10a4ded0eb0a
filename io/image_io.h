// io/image_io.h — writes and reads rendered images: PNG (8-bit sRGB, RGB or RGBA) through
// softmol's parallel encoder (io/png_encoder.h) and libpng's reader; OpenEXR (linear float
// colour plus AOV channels: Z, N.x N.y N.z, AO as float32, id as uint32) and every other format
// through OpenImageIO, in a module (softmol_oiio.so) that only a process needing it loads.
// Images here are stored top row first (file order).
//
// Every write goes through io::TemporaryFile (io/atomic_file.h): a unique temporary beside the
// output, every call checked, rename() as the only step that makes the output appear; nothing is
// left under either name on failure or on SIGINT/SIGTERM/SIGHUP. Errors (io::InputError) name
// the output as given. An output that is a symlink is written through, as `cp` does: the file
// the link points to is replaced and the link stays. An output that is a directory, a device or
// a FIFO, or in a folder that does not exist, is refused with a message saying so.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
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
              std::span<const uint8_t> pixels);

// OpenEXR with every channel of `image` (mixed float32 / uint32), zip-compressed.
void WriteExr(const std::string& path, const ImageFile& image);

// The same file written by bands of rows from the top, so that an image too large to hold (a
// poster) is never whole in memory: the first band names the channels, every band has them and
// the image's width, and Finish() is the whole image (its bytes are WriteExr's for the whole).
// Destroyed unfinished (a failed render), it leaves nothing under either name.
class ExrStreamWriter {
 public:
  ExrStreamWriter(const std::string& path, int width, int height);
  ~ExrStreamWriter();
  ExrStreamWriter(const ExrStreamWriter&) = delete;
  ExrStreamWriter& operator=(const ExrStreamWriter&) = delete;

  void AddRows(const ImageFile& band);
  void Finish();

 private:
  struct Output;
  std::unique_ptr<Output> out_;
};

// Reads an image as 8-bit interleaved pixels (for tests and `diff`): a PNG through libpng, with
// its own channel count and straight alpha; any other format through the OpenImageIO module.
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};
Image8 ReadImage8(const std::string& path);

// Reads an EXR (or other float image) as float channels with their names; uint32 channels are
// returned in ImageChannel::ids.
ImageFile ReadExr(const std::string& path);

}  // namespace softmol::io

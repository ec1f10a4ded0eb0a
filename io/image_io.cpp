// io/image_io.cpp — PNG through softmol's encoder and libpng's reader; EXR and other formats
// through the OpenImageIO module, loaded on first use; every write through TemporaryFile.
#include "io/image_io.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "io/atomic_file.h"
#include "io/detail/oiio_loader.h"
#include "io/error.h"
#include "io/png_encoder.h"

namespace softmol::io {
namespace {

// ---- libpng reading ---------------------------------------------------------------------------
// libpng reports errors by longjmp, so the two functions that call it hold no C++ object that
// needs destroying; the caller owns everything.
struct PngError {
  char message[256] = "";
};

void OnPngError(png_structp png, png_const_charp msg) {
  auto* e = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(e->message, sizeof e->message, "%s", msg);
  png_longjmp(png, 1);
}
void OnPngWarning(png_structp, png_const_charp) {}

// Reads the header and sets the transforms to 8-bit gray/GA/RGB/RGBA; 0 on error.
int PngHeader(png_structp png, png_infop info, FILE* f, int* width, int* height, int* channels, int* passes) {
  if (setjmp(png_jmpbuf(png))) return 0;
  png_init_io(png, f);
  png_read_info(png, info);
  png_set_expand(png);  // palette -> RGB, gray < 8 bits -> 8, tRNS -> alpha
  png_set_strip_16(png);
  *passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  *width = int(png_get_image_width(png, info));
  *height = int(png_get_image_height(png, info));
  *channels = int(png_get_channels(png, info));
  return 1;
}

int PngRows(png_structp png, png_infop info, uint8_t* out, size_t rowBytes, int height, int passes) {
  if (setjmp(png_jmpbuf(png))) return 0;
  for (int pass = 0; pass < passes; ++pass)
    for (int y = 0; y < height; ++y) png_read_row(png, out + size_t(y) * rowBytes, nullptr);
  png_read_end(png, nullptr);
  (void)info;
  return 1;
}

struct PngReader {
  PngError error;
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReader() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

Image8 ReadPng(const std::string& path, FILE* f) {
  PngReader r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.error, OnPngError, OnPngWarning);
  if (r.png) r.info = png_create_info_struct(r.png);
  if (!r.png || !r.info) throw std::bad_alloc();
  Image8 img;
  int passes = 1;
  if (!PngHeader(r.png, r.info, f, &img.width, &img.height, &img.channels, &passes))
    throw InputError({path}, std::string("cannot read the PNG: ") + r.error.message);
  const size_t rowBytes = size_t(img.width) * size_t(img.channels);
  img.pixels.resize(rowBytes * size_t(img.height));
  if (!PngRows(r.png, r.info, img.pixels.data(), rowBytes, img.height, passes))
    throw InputError({path}, std::string("cannot read the PNG: ") + r.error.message);
  return img;
}

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};

// ---- The OpenImageIO module -------------------------------------------------------------------
struct ModuleImage {
  const SoftmolOiioApi* api;
  void* image;
  ~ModuleImage() { api->close(image); }
};

ModuleImage OpenWithModule(const std::string& path) {
  const SoftmolOiioApi& api = detail::OiioModule(path);
  char err[512] = "";
  void* image = api.open(path.c_str(), err, sizeof err);
  if (image == nullptr) throw InputError({path}, std::string("cannot read the image: ") + err);
  return ModuleImage{&api, image};
}

void ReadChannels(const ModuleImage& m, const std::string& path, int begin, int end, int type, void* out) {
  char err[512] = "";
  if (!m.api->read(m.image, begin, end, type, out, err, sizeof err))
    throw InputError({path}, std::string("cannot read the image: ") + err);
}

}  // namespace

void WritePng(const std::string& path, int width, int height, int channels,
              const std::vector<uint8_t>& pixels) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) ||
      pixels.size() != size_t(width) * size_t(height) * size_t(channels))
    throw InputError({path}, "internal error: inconsistent PNG image size");
  TemporaryFile file(path);  // first, so a bad output path is reported before the encoding
  const std::vector<uint8_t> bytes = EncodePng(width, height, channels, pixels.data());
  file.Write(bytes.data(), bytes.size());
  file.Commit();
}

void WriteExr(const std::string& path, const ImageFile& image) {
  const size_t n = size_t(image.width) * size_t(image.height);
  if (image.width <= 0 || image.height <= 0 || image.channels.empty())
    throw InputError({path}, "internal error: empty EXR image");
  const int nc = int(image.channels.size());
  std::vector<const char*> names;
  std::vector<unsigned char> isU32;
  int alpha = -1, z = -1;
  for (int c = 0; c < nc; ++c) {
    const ImageChannel& ch = image.channels[size_t(c)];
    if ((!ch.ids.empty() ? ch.ids.size() : ch.values.size()) != n)
      throw InputError({path}, "internal error: channel " + ch.name + " has the wrong size");
    names.push_back(ch.name.c_str());
    isU32.push_back(ch.ids.empty() ? 0 : 1);
    if (ch.name == "A") alpha = c;
    if (ch.name == "Z") z = c;
  }
  // OpenEXR's writer stamps the current time (capDate) unless DateTime is set; an empty one
  // leaves it out, so the same render gives the same bytes (DESIGN.md, determinism).
  const char* attrNames[] = {"compression", "oiio:ColorSpace", "DateTime"};
  const char* attrValues[] = {"zip", "Linear", ""};
  // Every channel is 4 bytes, so the native (per-channel format) layout is 4·nc bytes a pixel.
  std::vector<uint32_t> native(n * size_t(nc));
  for (int c = 0; c < nc; ++c) {
    const ImageChannel& ch = image.channels[size_t(c)];
    for (size_t i = 0; i < n; ++i) {
      uint32_t bits;
      if (!ch.ids.empty()) bits = ch.ids[i];
      else std::memcpy(&bits, &ch.values[i], 4);
      native[i * size_t(nc) + size_t(c)] = bits;
    }
  }
  const SoftmolOiioApi& api = detail::OiioModule(path);
  TemporaryFile file(path);
  file.CloseForExternalWriter();  // OpenImageIO opens the temporary by name
  const SoftmolOiioWrite w{path.c_str(), file.temporaryPath().c_str(), image.width, image.height, nc,
                           names.data(), isU32.data(), alpha, z, attrNames, attrValues, 3, native.data()};
  char err[512] = "";
  if (!api.write(&w, err, sizeof err)) throw InputError({path}, std::string("cannot write the image: ") + err);
  file.Commit();
}

Image8 ReadImage8(const std::string& path) {
  std::unique_ptr<FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) throw InputError({path}, std::string("cannot read the image: ") + std::strerror(errno));
  unsigned char sig[8] = {};
  if (std::fread(sig, 1, 8, f.get()) == 8 && png_sig_cmp(sig, 0, 8) == 0) {
    std::rewind(f.get());
    return ReadPng(path, f.get());
  }
  f.reset();
  const ModuleImage m = OpenWithModule(path);
  Image8 img;
  m.api->info(m.image, &img.width, &img.height, &img.channels);
  img.pixels.resize(size_t(img.width) * size_t(img.height) * size_t(img.channels));
  ReadChannels(m, path, 0, img.channels, kSoftmolOiioU8, img.pixels.data());
  return img;
}

ImageFile ReadExr(const std::string& path) {
  const ModuleImage m = OpenWithModule(path);
  ImageFile img;
  int nchannels = 0;
  m.api->info(m.image, &img.width, &img.height, &nchannels);
  const size_t n = size_t(img.width) * size_t(img.height);
  for (int c = 0; c < nchannels; ++c) {
    ImageChannel ch;
    ch.name = m.api->channelName(m.image, c);
    if (m.api->channelIsU32(m.image, c)) {
      ch.ids.resize(n);
      ReadChannels(m, path, c, c + 1, kSoftmolOiioU32, ch.ids.data());
    } else {
      ch.values.resize(n);
      ReadChannels(m, path, c, c + 1, kSoftmolOiioF32, ch.values.data());
    }
    img.channels.push_back(std::move(ch));
  }
  return img;
}

}  // namespace softmol::io

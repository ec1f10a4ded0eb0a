// io/image_io.cpp — PNG through softmol's encoder and libpng's reader; EXR and other formats
// through the OpenImageIO module, loaded on first use; every write through TemporaryFile.
#include "io/image_io.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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
              std::span<const uint8_t> pixels) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) ||
      pixels.size() != size_t(width) * size_t(height) * size_t(channels))
    throw InputError({path}, "internal error: inconsistent PNG image size");
  TemporaryFile file(path);  // first, so a bad output path is reported before the encoding
  const std::vector<uint8_t> bytes = EncodePng(width, height, channels, pixels.data());
  file.Write(bytes.data(), bytes.size());
  file.Commit();
}

// The open output: the temporary the module writes by name, and where the rows have got to.
struct ExrStreamWriter::Output {
  const SoftmolOiioApi& api;
  TemporaryFile file;
  std::string path;
  int width, height;
  std::vector<std::string> names;  // the first band's channels
  std::vector<unsigned char> isU32;
  void* image = nullptr;  // the module's output, from the first band on
  int rowsDone = 0;
  Output(const std::string& p, int w, int h) : api(detail::OiioModule(p)), file(p), path(p), width(w), height(h) {
    file.CloseForExternalWriter();  // OpenImageIO opens the temporary by name
  }
  [[noreturn]] void Fail(const char* what, const char* err) const {
    throw InputError({path}, std::string(what) + err);
  }
  void Open(const ImageFile& band);
  void Check(const ImageFile& band) const;
};

void ExrStreamWriter::Output::Open(const ImageFile& band) {
  std::vector<const char*> cnames;
  int alpha = -1, z = -1;
  for (const ImageChannel& ch : band.channels) {
    if (ch.name == "A") alpha = int(names.size());
    if (ch.name == "Z") z = int(names.size());
    names.push_back(ch.name);
    isU32.push_back(ch.ids.empty() ? 0 : 1);
  }
  for (const std::string& n : names) cnames.push_back(n.c_str());
  // OpenEXR's writer stamps the current time (capDate) unless DateTime is set; an empty one
  // leaves it out, so the same render gives the same bytes (DESIGN.md, determinism).
  const char* attrNames[] = {"compression", "oiio:ColorSpace", "DateTime"};
  const char* attrValues[] = {"zip", "Linear", ""};
  const SoftmolOiioWrite w{path.c_str(), file.temporaryPath().c_str(), width, height, int(names.size()),
                           cnames.data(), isU32.data(), alpha, z, attrNames, attrValues, 3};
  char err[512] = "";
  image = api.create(&w, err, sizeof err);
  if (image == nullptr) Fail("cannot write the image: ", err);
}

void ExrStreamWriter::Output::Check(const ImageFile& band) const {
  auto internal = [&](const std::string& why) { throw InputError({path}, "internal error: " + why); };
  if (band.width != width || band.height <= 0 || band.height > height - rowsDone || band.channels.empty())
    internal("an EXR band of " + std::to_string(band.width) + "x" + std::to_string(band.height) + " after " +
             std::to_string(rowsDone) + " of " + std::to_string(height) + " rows");
  if (image != nullptr && band.channels.size() != names.size()) internal("an EXR band with other channels");
  const size_t n = size_t(band.width) * size_t(band.height);
  for (size_t c = 0; c < band.channels.size(); ++c) {
    const ImageChannel& ch = band.channels[c];
    if ((!ch.ids.empty() ? ch.ids.size() : ch.values.size()) != n)
      internal("channel " + ch.name + " has the wrong size");
    if (image != nullptr && (ch.name != names[c] || (ch.ids.empty() ? 0 : 1) != isU32[c]))
      internal("an EXR band with other channels");
  }
}

ExrStreamWriter::ExrStreamWriter(const std::string& path, int width, int height) {
  if (width <= 0 || height <= 0) throw InputError({path}, "internal error: empty EXR image");
  out_ = std::make_unique<Output>(path, width, height);
}

ExrStreamWriter::~ExrStreamWriter() {
  if (out_ && out_->image != nullptr) {  // abandoned: close it, then the temporary goes
    char err[512];
    out_->api.finish(out_->image, err, sizeof err);
  }
}

void ExrStreamWriter::AddRows(const ImageFile& band) {
  Output& o = *out_;
  o.Check(band);
  if (o.image == nullptr) o.Open(band);
  // Every channel is 4 bytes, so the native (per-channel format) layout is 4·nc bytes a pixel.
  const size_t n = size_t(band.width) * size_t(band.height), nc = band.channels.size();
  std::vector<uint32_t> native(n * nc);
  for (size_t c = 0; c < nc; ++c) {
    const ImageChannel& ch = band.channels[c];
    for (size_t i = 0; i < n; ++i) {
      uint32_t bits;
      if (!ch.ids.empty()) bits = ch.ids[i];
      else std::memcpy(&bits, &ch.values[i], 4);
      native[i * nc + c] = bits;
    }
  }
  char err[512] = "";
  if (!o.api.writeRows(o.image, o.rowsDone, o.rowsDone + band.height, native.data(), err, sizeof err))
    o.Fail("cannot write the image: ", err);
  o.rowsDone += band.height;
}

void ExrStreamWriter::Finish() {
  Output& o = *out_;
  if (o.image == nullptr || o.rowsDone != o.height)
    throw InputError({o.path}, "internal error: an EXR finished after " + std::to_string(o.rowsDone) + " of " +
                                   std::to_string(o.height) + " rows");
  char err[512] = "";
  void* image = std::exchange(o.image, nullptr);
  if (!o.api.finish(image, err, sizeof err)) o.Fail("cannot write the image: ", err);
  o.file.Commit();
}

void WriteExr(const std::string& path, const ImageFile& image) {
  ExrStreamWriter exr(path, image.width, image.height);
  exr.AddRows(image);
  exr.Finish();
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

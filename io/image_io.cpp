// io/image_io.cpp — OpenImageIO writers and readers, with temp-then-rename.
#include "io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "io/error.h"

namespace softmol::io {
namespace {

namespace fs = std::filesystem;

// The temporary sits beside the target (same file system, so rename is atomic) and keeps the
// extension, because OpenImageIO picks the format from it.
std::string TemporaryPath(const std::string& path) {
  fs::path p(path);
  std::string name = ".";  // appended piece by piece: GCC 12 misreports "." + std::string (-Wrestrict)
  name += p.stem().string();
  name += ".tmp";
  name += p.extension().string();
  return (p.parent_path() / name).string();
}

void Commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError({path}, "cannot write the output file: " + ec.message());
  }
}

void WriteWithSpec(const std::string& path, const OIIO::ImageSpec& spec, const void* data) {
  const std::string tmp = TemporaryPath(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError({path}, "unsupported image format: " + OIIO::geterror());
  bool ok = out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::UNKNOWN, data);
  ok = out->close() && ok;
  if (!ok) {
    const std::string why = out->geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError({path}, "cannot write the image: " + why);
  }
  Commit(tmp, path);
}

}  // namespace

void WritePng(const std::string& path, int width, int height, int channels,
              const std::vector<uint8_t>& pixels) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) ||
      pixels.size() != size_t(width) * size_t(height) * size_t(channels))
    throw InputError({path}, "internal error: inconsistent PNG image size");
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  // The pixels already hold straight (unassociated) alpha: OpenImageIO must not divide again.
  if (channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
  WriteWithSpec(path, spec, pixels.data());
}

void WriteExr(const std::string& path, const ImageFile& image) {
  const size_t n = size_t(image.width) * size_t(image.height);
  if (image.width <= 0 || image.height <= 0 || image.channels.empty())
    throw InputError({path}, "internal error: empty EXR image");
  const int nc = int(image.channels.size());
  OIIO::ImageSpec spec(image.width, image.height, nc, OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  spec.channelformats.clear();
  spec.alpha_channel = -1;
  spec.z_channel = -1;
  for (int c = 0; c < nc; ++c) {
    const ImageChannel& ch = image.channels[size_t(c)];
    const bool isUint = !ch.ids.empty();
    if ((isUint ? ch.ids.size() : ch.values.size()) != n)
      throw InputError({path}, "internal error: channel " + ch.name + " has the wrong size");
    spec.channelnames.push_back(ch.name);
    spec.channelformats.push_back(isUint ? OIIO::TypeDesc::UINT32 : OIIO::TypeDesc::FLOAT);
    if (ch.name == "A") spec.alpha_channel = c;
    if (ch.name == "Z") spec.z_channel = c;
  }
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  // OpenEXR's writer stamps the current time (capDate) unless DateTime is set; an empty one
  // leaves it out, so the same render gives the same bytes (DESIGN.md, determinism).
  spec.attribute("DateTime", "");
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
  WriteWithSpec(path, spec, native.data());
}

Image8 ReadImage8(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path}, "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image8 img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, img.pixels.data()))
    throw InputError({path}, "cannot read the image: " + in->geterror());
  return img;
}

ImageFile ReadExr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path}, "cannot read the image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  ImageFile img;
  img.width = spec.width;
  img.height = spec.height;
  const size_t n = size_t(spec.width) * size_t(spec.height);
  for (int c = 0; c < spec.nchannels; ++c) {
    ImageChannel ch;
    ch.name = spec.channelnames[size_t(c)];
    const bool isUint = spec.channelformat(c) == OIIO::TypeDesc::UINT32;
    bool ok;
    if (isUint) {
      ch.ids.resize(n);
      ok = in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::UINT32, ch.ids.data());
    } else {
      ch.values.resize(n);
      ok = in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, ch.values.data());
    }
    if (!ok) throw InputError({path}, "cannot read channel " + ch.name + ": " + in->geterror());
    img.channels.push_back(std::move(ch));
  }
  return img;
}

}  // namespace softmol::io

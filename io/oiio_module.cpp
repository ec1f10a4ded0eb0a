// io/oiio_module.cpp — softmol_oiio.so: the only code that links OpenImageIO. Built as a CMake
// MODULE beside the softmol binary and opened on first use (io/oiio_loader.cpp); exports one
// C function returning the table of io/detail/oiio_module_api.h. Exceptions stop here.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "io/detail/oiio_module_api.h"

namespace {

void SetError(char* err, size_t size, const std::string& why) {
  if (size > 0) std::snprintf(err, size, "%s", why.empty() ? "unknown OpenImageIO error" : why.c_str());
}

OIIO::TypeDesc ToType(int type) {
  if (type == kSoftmolOiioU8) return OIIO::TypeDesc::UINT8;
  if (type == kSoftmolOiioU32) return OIIO::TypeDesc::UINT32;
  return OIIO::TypeDesc::FLOAT;
}

OIIO::ImageSpec SpecOf(const SoftmolOiioWrite& w) {
  OIIO::ImageSpec spec(w.width, w.height, w.nchannels, OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  spec.channelformats.clear();
  for (int c = 0; c < w.nchannels; ++c) {
    spec.channelnames.push_back(w.channelNames[c]);
    spec.channelformats.push_back(w.channelIsU32[c] ? OIIO::TypeDesc::UINT32 : OIIO::TypeDesc::FLOAT);
  }
  spec.alpha_channel = w.alphaChannel;
  spec.z_channel = w.zChannel;
  for (int i = 0; i < w.nattributes; ++i) spec.attribute(w.attributeNames[i], w.attributeValues[i]);
  return spec;
}

void* Create(const SoftmolOiioWrite* w, char* err, size_t errSize) {
  try {
    auto out = OIIO::ImageOutput::create(w->formatPath);
    if (!out) {
      SetError(err, errSize, "unsupported image format: " + OIIO::geterror());
      return nullptr;
    }
    if (!out->open(w->filePath, SpecOf(*w))) {
      SetError(err, errSize, out->geterror());
      return nullptr;
    }
    return out.release();
  } catch (const std::exception& e) {
    SetError(err, errSize, e.what());
    return nullptr;
  }
}

OIIO::ImageOutput* Out(void* output) { return static_cast<OIIO::ImageOutput*>(output); }

int WriteRows(void* output, int ybegin, int yend, const void* pixels, char* err, size_t errSize) {
  try {
    if (Out(output)->write_scanlines(ybegin, yend, 0, OIIO::TypeDesc::UNKNOWN, pixels)) return 1;
    SetError(err, errSize, Out(output)->geterror());
  } catch (const std::exception& e) {
    SetError(err, errSize, e.what());
  }
  return 0;
}

int Finish(void* output, char* err, size_t errSize) {
  std::unique_ptr<OIIO::ImageOutput> out(Out(output));
  try {
    if (out->close()) return 1;  // close() flushes: its failure is a failed write too
    SetError(err, errSize, out->geterror());
  } catch (const std::exception& e) {
    SetError(err, errSize, e.what());
  }
  return 0;
}

void* Open(const char* path, char* err, size_t errSize) {
  try {
    auto in = OIIO::ImageInput::open(path);
    if (!in) SetError(err, errSize, OIIO::geterror());
    return in.release();
  } catch (const std::exception& e) {
    SetError(err, errSize, e.what());
    return nullptr;
  }
}

OIIO::ImageInput* In(void* image) { return static_cast<OIIO::ImageInput*>(image); }

void Info(void* image, int* width, int* height, int* nchannels) {
  const OIIO::ImageSpec& s = In(image)->spec();
  *width = s.width, *height = s.height, *nchannels = s.nchannels;
}

const char* ChannelName(void* image, int c) { return In(image)->spec().channelnames[size_t(c)].c_str(); }

int ChannelIsU32(void* image, int c) { return In(image)->spec().channelformat(c) == OIIO::TypeDesc::UINT32; }

int Read(void* image, int begin, int end, int type, void* out, char* err, size_t errSize) {
  try {
    if (In(image)->read_image(0, 0, begin, end, ToType(type), out)) return 1;
    SetError(err, errSize, In(image)->geterror());
  } catch (const std::exception& e) {
    SetError(err, errSize, e.what());
  }
  return 0;
}

void Close(void* image) {
  std::unique_ptr<OIIO::ImageInput> in(In(image));  // ImageInput::destroy via unique_ptr's deleter
}

const SoftmolOiioApi kApi = {SOFTMOL_OIIO_ABI, Create, WriteRows, Finish, Open, Info, ChannelName, ChannelIsU32, Read, Close};

}  // namespace

extern "C" __attribute__((visibility("default"))) const SoftmolOiioApi* softmol_oiio_api(void) { return &kApi; }

// io/detail/oiio_module_api.h — the C function table between softmol and its OpenImageIO
// module (softmol_oiio.so, io/oiio_module.cpp). OpenImageIO pulls in ~260 shared libraries
// (0.24 s, 128 MB per process), so only a process that writes EXR or reads a non-PNG image
// opens the module (io/oiio_loader.cpp). Plain C types only: no C++ object or exception crosses
// the boundary; every function reports failure by its return value and a message in `err`.
#pragma once

#include <cstddef>

extern "C" {

#define SOFTMOL_OIIO_ABI 2  // bump when the table changes

enum SoftmolOiioType { kSoftmolOiioU8 = 0, kSoftmolOiioF32 = 1, kSoftmolOiioU32 = 2 };

struct SoftmolOiioWrite {
  const char* formatPath;  // the user's output name: its extension picks the format
  const char* filePath;    // where the bytes go (the temporary)
  int width, height, nchannels;
  const char* const* channelNames;
  const unsigned char* channelIsU32;  // per channel: 1 uint32, 0 float32
  int alphaChannel, zChannel;         // -1 for none
  const char* const* attributeNames;  // string attributes ("compression" = "zip", ...)
  const char* const* attributeValues;
  int nattributes;
};

struct SoftmolOiioApi {
  int abi;  // SOFTMOL_OIIO_ABI
  // A written image, by rows from the top: an open output, or null with a message.
  void* (*create)(const SoftmolOiioWrite* w, char* err, size_t errSize);
  // Rows [ybegin, yend), the next ones, interleaved, 4 bytes per channel value; 1 on success.
  int (*writeRows)(void* output, int ybegin, int yend, const void* pixels, char* err, size_t errSize);
  // Closes (flushes) and frees the output; 1 when every byte was written. Also the way to
  // abandon a half-written one.
  int (*finish)(void* output, char* err, size_t errSize);
  // An open image, or null with a message.
  void* (*open)(const char* path, char* err, size_t errSize);
  void (*info)(void* image, int* width, int* height, int* nchannels);
  // The channel's name (valid until close) and whether it is uint32.
  const char* (*channelName)(void* image, int c);
  int (*channelIsU32)(void* image, int c);
  // Reads channels [begin, end) of every pixel as `type` into `out`; 1 on success.
  int (*read)(void* image, int begin, int end, int type, void* out, char* err, size_t errSize);
  void (*close)(void* image);
};

// The module's one exported symbol.
typedef const SoftmolOiioApi* (*SoftmolOiioEntry)(void);
const SoftmolOiioApi* softmol_oiio_api(void);

}  // extern "C"

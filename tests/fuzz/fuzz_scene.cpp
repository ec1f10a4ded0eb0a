// tests/fuzz/fuzz_scene.cpp — libFuzzer target for scene files (io/scene_file.h): any bytes
// parse into settings with a key and at least one value each, or throw InputError naming the
// source (with a line and column inside the text for malformed JSON).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/error.h"
#include "io/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace softmol::io;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    for (const SceneSetting& s : ParseSceneFile(text, "scene.json"))
      if (s.values.empty()) std::abort();
  } catch (const InputError& e) {
    if (e.where().file != "scene.json") std::abort();
    if (e.where().line < 0 || e.where().column < 0) std::abort();
  }
  return 0;
}

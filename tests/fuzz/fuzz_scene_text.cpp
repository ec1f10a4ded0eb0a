// tests/fuzz/fuzz_scene_text.cpp — libFuzzer target for the scene model's option texts
// (scene/): a layer (--show), a colour rule (--color) and a view (--view, PyMOL's get_view).
// Any text parses or throws InputError; what parses formats to text that parses back to the
// same text, resolves on a small built-in molecule, and (views) gives a finite camera.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/error.h"
#include "io/structure_reader.h"
#include "scene/colors.h"
#include "scene/layers.h"
#include "scene/view.h"

namespace {

using namespace softmol;

const io::Molecule& Small() {
  static const io::Molecule mol = io::ReadMoleculeFromMemory(
      "ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00 10.00           N\n"
      "ATOM      2  CA  ALA A   1       1.450   0.000   0.000  1.00 20.00           C\n"
      "ATOM      3  C   ALA A   1       2.000   1.400   0.000  1.00  5.00           C\n"
      "HETATM    4  O   HOH W 100       5.000   5.000   5.000  1.00  0.00           O\n"
      "HETATM    5  C1  ATP L 300       1.000   2.000   3.000  1.00  0.00           C\n",
      "small.pdb");
  return mol;
}

template <class Parse>
bool Parses(Parse parse) {
  try {
    parse();
    return true;
  } catch (const io::InputError&) {
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const io::SourceLocation where{"--fuzz"};
  scene::SceneLayers layers;
  Parses([&] {
    const scene::Layer layer = scene::ParseLayer(text, where);
    const std::string again = scene::FormatLayer(layer);
    if (scene::FormatLayer(scene::ParseLayer(again, where)) != again) std::abort();
    layers.layers.push_back(layer);
  });
  Parses([&] {
    const scene::ColorRule rule = scene::ParseColorRule(text, where);
    const std::string again = scene::FormatColorRule(rule);
    if (scene::FormatColorRule(scene::ParseColorRule(again, where)) != again) std::abort();
    layers.colors.push_back(rule);
  });
  const scene::ResolvedLooks looks = scene::ResolveLooks(Small(), layers);
  if (looks.looks.style.size() != Small().atomCount()) std::abort();
  Parses([&] {
    const scene::View v = scene::ParseView(text, where);
    const raster::Camera c = scene::CameraOf(scene::ParseView(scene::FormatView(v), where), 64, 48);
    if (!std::isfinite(c.eye.x + c.eye.y + c.eye.z + c.target.x + c.up.y + c.fovYDegrees)) std::abort();
  });
  return 0;
}

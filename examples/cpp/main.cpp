// examples/cpp/main.cpp — softmol from C++: load a molecule, render it with the command's
// options into memory (colour and the depth AOV), render it again turned (the AO bake is kept),
// write a PNG, and show that a bad option value is reported by name.
#include <softmol/softmol.h>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s MOLECULE OUT.png\n", argv[0]);
    return 2;
  }
  try {
    const softmol::Molecule molecule = softmol::Molecule::Load(argv[1]);
    softmol::Renderer renderer;
    softmol::Options options{{"size", "320x240"}, {"style", "balls"}, {"ao", "baked"}, {"aov", "depth"}};
    const softmol::Image front = renderer.Render(molecule, options);
    size_t covered = 0;
    for (float d : front.depth) covered += std::isfinite(d) ? 1 : 0;
    std::printf("%s: %zu atoms, %dx%d, %zu pixels covered, baked: %s\n", argv[1], molecule.AtomCount(), front.width,
                front.height, covered, renderer.LastRenderBaked() ? "yes" : "no");

    options.Set("rotate", "0,90,0");
    const softmol::Image side = renderer.Render(molecule, options);  // same atoms: the bake is reused
    std::printf("turned: baked again: %s\n", renderer.LastRenderBaked() ? "yes" : "no");
    side.SavePng(argv[2]);

    try {
      renderer.Render(molecule, {{"size", "0x0"}});
    } catch (const softmol::Error& e) {
      std::printf("bad option: %s\n", e.what());
    }
  } catch (const softmol::Error& e) {
    std::fprintf(stderr, "softmol: %s\n", e.what());
    return 2;
  }
  return 0;
}

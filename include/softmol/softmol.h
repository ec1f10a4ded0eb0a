// softmol/softmol.h — softmol from a program: load a molecule (a file, through the readers the
// `softmol` command uses, or arrays of positions and elements), render it with the command's
// own options into pixels in memory (RGBA8 and, on request, the depth, normal, AO and id AOVs)
// or into a file, and keep the per-structure work (the AO bake) from one render to the next.
// Options are `softmol render`'s flags without their dashes ({"size", "1280x960"},
// {"ao", "baked"}, {"show", {"ligand=balls", "water=hidden"}}), checked by the same
// declarations, so a bad value throws softmol::Error with the command's message ("--size: ...").
// The RGBA bytes of a render are the pixels of the PNG the command writes for the same options.
// Only standard types appear here; link softmol::softmol (CMake) or `pkg-config softmol`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

// What libsoftmol.so exports (it is built with hidden visibility); the same in users' code, so
// that softmol::Error's type is one type on both sides of the library, whatever their flags.
#define SOFTMOL_API __attribute__((visibility("default")))

namespace softmol {

// Bad input: an option, a file, an array. what() names it as the command does
// ("--ao-directions: ...", "1abc.pdb:12:31: ...", "positions: ...").
class SOFTMOL_API Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "0.1.0"
SOFTMOL_API std::string Version();

// One option's value(s): text, a number or a switch (true/false), or a list for a repeatable
// option (show, hide, color), applied in order.
class SOFTMOL_API OptionValue {
 public:
  OptionValue(const char* text) : values_{text} {}
  OptionValue(std::string text) : values_{std::move(text)} {}
  OptionValue(std::string_view text) : values_{std::string(text)} {}
  OptionValue(std::initializer_list<std::string> list) : values_(list) {}
  OptionValue(std::vector<std::string> list) : values_(std::move(list)) {}
  template <class T>
    requires std::is_arithmetic_v<T>
  OptionValue(T number) : values_{FormatNumber(number)} {}
  const std::vector<std::string>& values() const { return values_; }

 private:
  template <class T>
  static std::string FormatNumber(T v) {
    if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
    else if constexpr (std::is_integral_v<T>) return std::to_string(v);
    else return FormatReal(double(v));
  }
  static std::string FormatReal(double v);  // shortest text that reads back as v
  std::vector<std::string> values_;
};

// `softmol render`'s options by name, in the order given. Setting a name again replaces it.
class SOFTMOL_API Options {
 public:
  Options() = default;
  Options(std::initializer_list<std::pair<std::string, OptionValue>> entries);
  Options& Set(std::string name, OptionValue value);
  // Appends to a repeatable option's values (Add("show", "ligand=balls")).
  Options& Add(std::string name, std::string value);
  const std::vector<std::pair<std::string, std::vector<std::string>>>& entries() const { return entries_; }

 private:
  std::vector<std::pair<std::string, std::vector<std::string>>> entries_;
};

// A molecule: atoms (positions, elements, radii), residues, chains and bonds. Positions can be
// replaced frame by frame (a trajectory); the topology stays. Movable, not copyable.
class SOFTMOL_API Molecule {
 public:
  // PDB or mmCIF (plain or .gz), as `softmol render FILE [--assembly ID]` reads it.
  static Molecule Load(const std::string& path, const std::string& assembly = "");
  // `xyz`: 3 numbers per atom (Å); `elements`: a symbol per atom ("C", "Fe"); `radii`: Å per
  // atom, or empty for the van der Waals radii; `bonds`: pairs of atom indices (2 per bond), or
  // empty to compute them from distances as the command does. One chain "A", one residue "MOL".
  static Molecule FromArrays(std::span<const double> xyz, const std::vector<std::string>& elements,
                             std::span<const float> radii = {}, std::span<const uint32_t> bonds = {});
  Molecule(Molecule&&) noexcept;
  Molecule& operator=(Molecule&&) noexcept;
  ~Molecule();

  size_t AtomCount() const;
  size_t BondCount() const;  // the file's or the given bonds (distance bonds are added per render)
  const std::string& Path() const;  // the file it was read from ("" for arrays)
  std::vector<double> Positions() const;  // 3 per atom, the current frame
  // New positions for every atom (3 per atom, Å), e.g. a trajectory frame. From then on the
  // molecule counts as moving: the automatic AO is cone AO (as for `--trajectory`), and a
  // renderer keeps the camera that framed the loaded positions, as the command does for frames.
  void SetPositions(std::span<const double> xyz);
  void SetPositions(std::span<const float> xyz);

  struct Impl;

 private:
  friend class Renderer;
  explicit Molecule(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// A rendered frame, top row first.
struct SOFTMOL_API Image {
  int width = 0, height = 0;
  bool transparent = false;    // the background has alpha 0 (option transparent)
  std::vector<uint8_t> rgba;   // 4 bytes a pixel: sRGB, straight alpha (255 unless transparent)
  // AOVs, filled when option "aov" asks for them (DESIGN.md defines each); else empty.
  std::vector<float> depth;    // eye-space Å along the view axis, +inf on the background
  std::vector<float> normal;   // 3 floats a pixel (x, y, z), eye space, 0 on the background
  std::vector<float> ao;       // accessibility in [0, 1], 1 on the background
  std::vector<uint32_t> id;    // primitive id, 0xFFFFFFFF on the background
  // The PNG the command writes (RGB, or RGBA when transparent), as bytes or into a file.
  std::vector<uint8_t> EncodePng() const;
  void SavePng(const std::string& path) const;  // written whole or not at all
};

// Renders molecules; keeps one structure's work (the AO bake, the framing camera) while the
// molecule's topology and the options stay the same. Not thread-safe: one renderer per thread.
class SOFTMOL_API Renderer {
 public:
  Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  Image Render(const Molecule& molecule, const Options& options = {});
  // The same frame written by the command's writers: .png (plus NAME.aov.exr when AOVs are
  // asked for) or .exr; bytes equal `softmol render FILE -o path` with the same options.
  void RenderToFile(const Molecule& molecule, const std::string& path, const Options& options = {});
  // The passes of the last render and their milliseconds.
  std::vector<std::pair<std::string, double>> LastPasses() const;
  // Whether the last render baked AO (false: it reused the bake, or used none).
  bool LastRenderBaked() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace softmol

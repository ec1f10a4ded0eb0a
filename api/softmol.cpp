// api/softmol.cpp — the library behind include/softmol/softmol.h. It runs the command's own
// steps (cli/render_steps.h): the options go through `softmol render`'s CLI11 command and
// parameter tables (so presets, scene files, checks and messages are the command's), a
// structure is prepared once per molecule and options, and frames go through the run's one
// renderer and writers (cli/frame_sink.h). io::InputError becomes softmol::Error here, the
// library's one boundary.
#include "softmol/softmol.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "cli/commands.h"
#include "cli/frame_sink.h"
#include "cli/load_molecule.h"
#include "cli/render_steps.h"
#include "effects/frame_renderer.h"
#include "io/bonds.h"
#include "io/elements.h"
#include "io/error.h"
#include "io/image_io.h"
#include "io/molecule.h"
#include "io/png_encoder.h"
#include "io/trajectory.h"
#include "raster/representation.h"
#include "scene/layers.h"

namespace softmol {

struct Molecule::Impl {
  uint64_t id = 0;             // tells molecules apart in a renderer's cache
  io::Molecule topology;       // as loaded; its positions frame the camera
  bool bondsGiven = false;     // arrays with bonds: no distance bonds are added
  bool moved = false;          // SetPositions was called: a trajectory
  std::vector<double> x, y, z; // the current frame, when moved
};

namespace {

std::atomic<uint64_t> nextMoleculeId{1};

// The command's options the library does not take, and what takes their place.
constexpr std::pair<const char*, const char*> kJobOptions[] = {
    {"output", "write files with Renderer::RenderToFile or Image::SavePng"},
    {"assembly", "give it to Molecule::Load"},
    {"trajectory", "set the molecule's positions for each frame"},
    {"frames", "set the molecule's positions for each frame"},
    {"frame-numbers", "set the molecule's positions for each frame"},
    {"turntable", "render once per angle with \"rotate\""},
    {"shard", "a job option of the command"},
    {"profile", "a job option of the command (see Renderer::LastPasses)"},
    {"repeat", "a job option of the command"},
    {"band-rows", "a job option of the command (the library renders whole images)"},
    {"list-presets", "a job option of the command"},
    {"print-view", "a job option of the command"},
};

// The options as `softmol render` arguments, parsed by the command itself; switches set to
// false are applied after it (a flag can only turn a switch on).
cli::RenderArgs ParseOptions(const Options& options) {
  const io::ParamTable<cli::RenderArgs> table = cli::RenderParams();
  std::vector<std::string> args = {"softmol", "render"};
  std::vector<size_t> switchedOff;
  for (const auto& [name, values] : options.entries()) {
    const std::string flag = "--" + name;
    if (name == "scene") {
      for (const std::string& v : values) args.push_back(flag + "=" + v);
      continue;
    }
    for (const auto& [job, instead] : kJobOptions)
      if (name == job) throw Error(flag + ": not a library option (" + instead + ")");
    const auto it = std::find_if(table.begin(), table.end(), [&](const auto& p) { return p.name == name; });
    if (it == table.end()) throw Error(flag + ": unknown option (see softmol render --help)");
    if (!it->repeatable && values.size() != 1)
      throw Error(flag + ": takes one value, got " + std::to_string(values.size()));
    for (const std::string& v : values) {
      if (!it->isSwitch) args.push_back(flag + "=" + v);
      else if (io::ParseBoolValue(v, io::FlagLocation(name))) args.push_back(flag);
      else switchedOff.push_back(size_t(it - table.begin()));
    }
  }
  CLI::App app;
  cli::RenderCommand command(app);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    throw Error(e.what());
  }
  cli::RenderArgs a = command.Args();
  for (size_t i : switchedOff) table[i].set(a, "false", io::FlagLocation(table[i].name));
  a.molecules = {"molecule"};  // the plan wants an input; the molecule comes as an object
  return a;
}

// The options as one text: equal options, equal keys.
std::string OptionsKey(const Options& options) {
  std::string key;
  for (const auto& [name, values] : options.entries()) {
    key += name;
    for (const std::string& v : values) key += '\0' + v;
    key += '\1';
  }
  return key;
}

Image ToImage(const effects::RenderedFrame& f, bool transparent) {
  Image img;
  img.width = f.width, img.height = f.height, img.transparent = transparent;
  const size_t n = size_t(f.width) * size_t(f.height);
  if (!f.rgba.empty() || !f.srgb8.empty()) {
    std::vector<uint8_t> px = effects::EncodeSrgb8(f, transparent);
    if (transparent) {
      img.rgba = std::move(px);
    } else {
      img.rgba.assign(4 * n, 255);
      for (size_t i = 0; i < n; ++i) std::copy_n(&px[3 * i], 3, &img.rgba[4 * i]);
    }
  }
  img.depth = f.depth, img.ao = f.ao, img.id = f.id;
  if (!f.normalX.empty()) {
    img.normal.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
      img.normal[3 * i] = f.normalX[i], img.normal[3 * i + 1] = f.normalY[i], img.normal[3 * i + 2] = f.normalZ[i];
  }
  return img;
}

// The PNG's pixels: RGB unless transparent.
std::vector<uint8_t> PngPixels(const Image& img) {
  if (img.transparent) return img.rgba;
  const size_t n = size_t(img.width) * size_t(img.height);
  std::vector<uint8_t> rgb(3 * n);
  for (size_t i = 0; i < n; ++i) std::copy_n(&img.rgba[4 * i], 3, &rgb[3 * i]);
  return rgb;
}

void CheckCoordinates(std::span<const double> xyz, size_t atoms) {
  if (xyz.size() != 3 * atoms)
    throw Error("positions: " + std::to_string(xyz.size()) + " numbers for " + std::to_string(atoms) +
                " atoms (3 per atom)");
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]) || std::abs(xyz[i]) > io::kMaxCoordinate)
      throw Error("positions: atom " + std::to_string(i / 3) + " has a coordinate that is not finite or beyond ±1e6 Å");
}

// Atoms of one chain "A" and one residue "MOL", flagged as a PDB reader would flag HETATMs.
io::Molecule MoleculeOfArrays(std::span<const double> xyz, const std::vector<std::string>& elements,
                              std::span<const float> radii) {
  const size_t n = elements.size();
  if (n == 0) throw Error("elements: a molecule needs at least one atom");
  CheckCoordinates(xyz, n);
  if (!radii.empty() && radii.size() != n)
    throw Error("radii: " + std::to_string(radii.size()) + " radii for " + std::to_string(n) + " atoms");
  io::Molecule m;
  m.chains.push_back({"A", 0});
  io::Residue r;
  std::copy_n("MOL", 3, r.name.begin());
  r.seqNum = 1;
  r.atomCount = uint32_t(n);
  m.residues.push_back(r);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t z = io::ElementFromSymbol(elements[i]);
    if (z == 0) throw Error("elements: atom " + std::to_string(i) + ": unknown element '" + elements[i] + "'");
    const io::ElementInfo& e = io::Element(z);
    const float radius = radii.empty() ? e.vdwRadius : radii[i];
    if (!(radius > 0.0f) || !std::isfinite(radius))
      throw Error("radii: atom " + std::to_string(i) + ": a radius must be a positive number of Å");
    m.x.push_back(xyz[3 * i]), m.y.push_back(xyz[3 * i + 1]), m.z.push_back(xyz[3 * i + 2]);
    m.vdwRadius.push_back(radius);
    m.color.push_back(e.color);
    m.element.push_back(z);
    m.flags.push_back(uint8_t(io::kHetatm | (z == 1 ? io::kHydrogen : 0)));
    std::array<char, 4> name{};
    std::copy_n(e.symbol, std::min<size_t>(std::char_traits<char>::length(e.symbol), 4), name.begin());
    m.atomName.push_back(name);
    m.occupancy.push_back(1.0f), m.bFactor.push_back(0.0f);
    m.residueIndex.push_back(0), m.modelIndex.push_back(0), m.serial.push_back(uint32_t(i + 1));
  }
  return m;
}

// Bonds as given: pairs of atom indices, sorted and unique like a reader's record bonds.
void SetBonds(io::Molecule& m, std::span<const uint32_t> bonds) {
  if (bonds.size() % 2 != 0) throw Error("bonds: 2 atom indices per bond, got " + std::to_string(bonds.size()));
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t i = 0; i < bonds.size(); i += 2) {
    const uint32_t a = bonds[i], b = bonds[i + 1];
    if (a >= m.atomCount() || b >= m.atomCount() || a == b)
      throw Error("bonds: bond " + std::to_string(i / 2) + " (" + std::to_string(a) + ", " + std::to_string(b) +
                  ") does not join two different atoms of " + std::to_string(m.atomCount()));
    pairs.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [a, b] : pairs) {
    m.bondA.push_back(a), m.bondB.push_back(b);
    m.bondSource.push_back(io::BondSource::kRecord);
  }
}

}  // namespace

std::string Version() { return SOFTMOL_VERSION; }

std::string OptionValue::FormatReal(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

Options::Options(std::initializer_list<std::pair<std::string, OptionValue>> entries) {
  for (const auto& [name, value] : entries) Set(name, value);
}

Options& Options::Set(std::string name, OptionValue value) {
  for (auto& e : entries_)
    if (e.first == name) return e.second = value.values(), *this;
  entries_.emplace_back(std::move(name), value.values());
  return *this;
}

Options& Options::Add(std::string name, std::string value) {
  for (auto& e : entries_)
    if (e.first == name) return e.second.push_back(std::move(value)), *this;
  entries_.emplace_back(std::move(name), std::vector<std::string>{std::move(value)});
  return *this;
}

// ---- Molecule ----

Molecule::Molecule(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) { impl_->id = nextMoleculeId++; }
Molecule::Molecule(Molecule&&) noexcept = default;
Molecule& Molecule::operator=(Molecule&&) noexcept = default;
Molecule::~Molecule() = default;

Molecule Molecule::Load(const std::string& path, const std::string& assembly) {
  auto impl = std::make_unique<Impl>();
  try {
    impl->topology = cli::LoadMolecule(path, assembly, /*trajectory=*/"", /*withBonds=*/false).molecule;
  } catch (const io::InputError& e) {
    throw Error(e.what());
  }
  return Molecule(std::move(impl));
}

Molecule Molecule::FromArrays(std::span<const double> xyz, const std::vector<std::string>& elements,
                              std::span<const float> radii, std::span<const uint32_t> bonds) {
  auto impl = std::make_unique<Impl>();
  impl->topology = MoleculeOfArrays(xyz, elements, radii);
  impl->bondsGiven = !bonds.empty();
  SetBonds(impl->topology, bonds);
  return Molecule(std::move(impl));
}

size_t Molecule::AtomCount() const { return impl_->topology.atomCount(); }
size_t Molecule::BondCount() const { return impl_->topology.bondCount(); }
const std::string& Molecule::Path() const { return impl_->topology.sourcePath; }

std::vector<double> Molecule::Positions() const {
  const Impl& m = *impl_;
  const size_t n = m.topology.atomCount();
  const std::vector<double>&x = m.moved ? m.x : m.topology.x, &y = m.moved ? m.y : m.topology.y,
                          &z = m.moved ? m.z : m.topology.z;
  std::vector<double> xyz(3 * n);
  for (size_t i = 0; i < n; ++i) xyz[3 * i] = x[i], xyz[3 * i + 1] = y[i], xyz[3 * i + 2] = z[i];
  return xyz;
}

void Molecule::SetPositions(std::span<const double> xyz) {
  Impl& m = *impl_;
  const size_t n = m.topology.atomCount();
  CheckCoordinates(xyz, n);
  m.x.resize(n), m.y.resize(n), m.z.resize(n);
  for (size_t i = 0; i < n; ++i) m.x[i] = xyz[3 * i], m.y[i] = xyz[3 * i + 1], m.z[i] = xyz[3 * i + 2];
  m.moved = true;
}

void Molecule::SetPositions(std::span<const float> xyz) {
  const std::vector<double> wide(xyz.begin(), xyz.end());  // exact: every float is a double
  SetPositions(std::span<const double>(wide));
}

// ---- Image ----

std::vector<uint8_t> Image::EncodePng() const {
  if (rgba.empty()) throw Error("image: no colour to encode (option color is false)");
  return io::EncodePng(width, height, transparent ? 4 : 3, PngPixels(*this).data());
}

void Image::SavePng(const std::string& path) const {
  if (rgba.empty()) throw Error("image: no colour to write (option color is false)");
  try {
    io::WritePng(path, width, height, transparent ? 4 : 3, PngPixels(*this));
  } catch (const io::InputError& e) {
    throw Error(e.what());
  }
}

// ---- Renderer ----

struct Renderer::Impl {
  std::unique_ptr<cli::FrameSink> sink;
  std::string backend;
  // The options last parsed and their plan.
  std::string optionsKey;
  cli::RenderArgs args;
  std::optional<cli::RunPlan> plan;
  // The structure prepared for them: which molecule, and whether it was moving.
  uint64_t sceneMolecule = 0;
  bool sceneMoving = false;
  std::optional<cli::InputScene> scene;
  effects::FrameResources resources;  // the bake and the pyramid, kept from frame to frame

  void Render(const Molecule::Impl& m, const Options& options, bool srgb8);
  void Prepare(const Molecule::Impl& m, const Options& options);
};

void Renderer::Impl::Prepare(const Molecule::Impl& m, const Options& options) {
  const std::string key = OptionsKey(options);
  if (!plan || key != optionsKey) {
    scene.reset(), plan.reset();
    args = ParseOptions(options);
    args.toFiles = false;  // in memory: whole images only
    plan = cli::PlanRun(args);
    optionsKey = key;
  }
  if (!sink || backend != args.backend) {
    sink = std::make_unique<cli::FrameSink>(args.backend, args.threads, /*trace=*/false);
    backend = args.backend;
  }
  if (scene && sceneMolecule == m.id && sceneMoving == m.moved) return;
  if (sceneMolecule != m.id) resources = {};  // another structure: free the last one's buffers
  scene.reset();
  cli::LoadedMolecule loaded;
  loaded.molecule = m.topology;
  // As the command: the file's bonds, plus distance bonds when a style draws bonds.
  if (!m.bondsGiven && scene::NeedsBonds(args.layers)) io::ComputeDistanceBonds(loaded.molecule);
  const std::string name = m.topology.sourcePath.empty() ? "molecule" : m.topology.sourcePath;
  scene = cli::PrepareInput(args, *plan, std::move(loaded), name, m.moved, *sink);
  sceneMolecule = m.id, sceneMoving = m.moved;
}

// A moved molecule renders as a trajectory frame does: the camera that framed the loaded
// positions, near/far fitted to the frame.
// `srgb8`: the caller takes 8-bit pixels (an Image, a PNG), which the frame may then make in its
// tiles instead of linear floats (effects::RenderOptions::srgb8).
void Renderer::Impl::Render(const Molecule::Impl& m, const Options& options, bool srgb8) {
  Prepare(m, options);
  std::unique_ptr<tbb::global_control> threads;
  if (args.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(args.threads));
  cli::InputScene& s = *scene;
  effects::RenderOptions o = s.options;
  o.srgb8 = srgb8;
  if (!m.moved) return sink->Render(s.drawn.scene, s.camera, o, resources);
  s.loaded.molecule.x = m.x, s.loaded.molecule.y = m.y, s.loaded.molecule.z = m.z;
  const raster::PrimitiveScene frame = raster::BuildRepresentation(s.loaded.molecule, s.looks.looks, s.rep).scene;
  raster::Camera camera = s.camera;
  cli::FitDepthRange(args, plan->view, frame, camera);
  sink->Render(frame, camera, o, resources);
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Image Renderer::Render(const Molecule& molecule, const Options& options) {
  try {
    impl_->Render(*molecule.impl_, options, /*srgb8=*/true);
    return ToImage(impl_->sink->frame(), impl_->scene->options.transparent);
  } catch (const io::InputError& e) {
    throw Error(e.what());
  }
}

void Renderer::RenderToFile(const Molecule& molecule, const std::string& path, const Options& options) {
  try {
    const cli::OutputKind kind = cli::OutputKindOf(path, {path});
    impl_->Render(*molecule.impl_, options, /*srgb8=*/kind == cli::OutputKind::kPng);
    impl_->sink->Write(path, kind, impl_->scene->options);
  } catch (const io::InputError& e) {
    throw Error(e.what());
  }
}

std::vector<std::pair<std::string, double>> Renderer::LastPasses() const {
  std::vector<std::pair<std::string, double>> passes;
  if (impl_->sink)
    for (const effects::PassTiming& p : impl_->sink->frame().passes) passes.emplace_back(p.name, p.durationMs);
  return passes;
}

bool Renderer::LastRenderBaked() const {
  if (!impl_->sink) return false;
  const auto& passes = impl_->sink->frame().passes;
  return std::any_of(passes.begin(), passes.end(), [](const effects::PassTiming& p) { return p.name == "ao bake"; });
}

}  // namespace softmol

// python/softmol_module.cpp — `import softmol`: the library (include/softmol/softmol.h) for
// Python. Keyword arguments of render() are `softmol render`'s options (ao_directions= is
// --ao-directions); the pixels come back as NumPy views of the image's own buffers (no copy);
// softmol.Error (a ValueError) carries the command's message, naming the option. Renders keep
// the GIL: a molecule's renderer is not thread-safe, and the work runs on oneTBB's threads anyway.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "softmol/softmol.h"

namespace py = pybind11;

namespace {

// A molecule with the renderer that keeps its AO bake from one render() to the next.
struct PyMolecule {
  softmol::Molecule molecule;
  softmol::Renderer renderer;
};

// A NumPy array over one of the image's vectors; `owner` (the Python Image) keeps it alive.
template <class T>
py::object View(const std::vector<T>& data, const softmol::Image& img, size_t channels, py::handle owner) {
  if (data.empty()) return py::none();
  std::vector<py::ssize_t> shape = {img.height, img.width}, strides = {py::ssize_t(sizeof(T) * channels * img.width),
                                                                        py::ssize_t(sizeof(T) * channels)};
  if (channels > 1) shape.push_back(py::ssize_t(channels)), strides.push_back(sizeof(T));
  return py::array_t<T>(shape, strides, data.data(), owner);
}

// A keyword's value as option text: True/False, a number, a string, or a sequence: numbers
// joined by commas, as --camera and --rotate take them (size=(W, H) as WxH), AOV names too (as
// --aov takes them), other strings as the repeated values of show=, hide=, color=.
softmol::OptionValue OptionText(const std::string& name, py::handle value) {
  if (py::isinstance<py::bool_>(value)) return softmol::OptionValue(value.cast<bool>());
  if (py::isinstance<py::str>(value)) return softmol::OptionValue(value.cast<std::string>());
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return softmol::OptionValue(py::str(value).cast<std::string>());
  if (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value)) {
    std::vector<std::string> items;
    bool numbers = true;
    for (py::handle item : value) {
      numbers &= !py::isinstance<py::str>(item);
      items.push_back(py::str(item).cast<std::string>());
    }
    if (!numbers && name != "aov") return softmol::OptionValue(items);  // show=[...]: one value each
    std::string joined;
    for (const std::string& s : items) joined += (joined.empty() ? "" : ",") + s;
    if (name == "size" && items.size() == 2) joined = items[0] + "x" + items[1];  // (1280, 960)
    return softmol::OptionValue(joined);
  }
  throw softmol::Error("--" + name + ": cannot use a value of type " + py::str(value.get_type()).cast<std::string>());
}

// A str or any os.PathLike (pathlib.Path) as a file name.
std::string PathOf(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

softmol::Options OptionsOf(const py::kwargs& kwargs) {
  softmol::Options options;
  for (const auto& [key, value] : kwargs) {
    std::string name = key.cast<std::string>();
    for (char& c : name)
      if (c == '_') c = '-';
    if (name == "aovs") name = "aov";
    options.Set(name, OptionText(name, value));
  }
  return options;
}

void SetPositions(softmol::Molecule& m, const py::array_t<double, py::array::c_style | py::array::forcecast>& xyz) {
  if (xyz.ndim() != 2 || xyz.shape(1) != 3) throw softmol::Error("positions: expected an array of shape (atoms, 3)");
  m.SetPositions(std::span<const double>(xyz.data(), size_t(xyz.size())));
}

std::shared_ptr<softmol::Image> Render(PyMolecule& self, py::object positions, const py::kwargs& kwargs) {
  if (!positions.is_none()) SetPositions(self.molecule, positions);
  const softmol::Options options = OptionsOf(kwargs);
  return std::make_shared<softmol::Image>(self.renderer.Render(self.molecule, options));
}

PyMolecule FromArrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& xyz, py::iterable elements,
                      py::object radii, py::object bonds) {
  if (xyz.ndim() != 2 || xyz.shape(1) != 3) throw softmol::Error("xyz: expected an array of shape (atoms, 3)");
  std::vector<std::string> symbols;
  for (py::handle e : elements) symbols.push_back(py::str(e).cast<std::string>());
  std::vector<float> r;
  if (!radii.is_none()) r = py::cast<std::vector<float>>(py::array_t<float, py::array::forcecast>(radii).attr("ravel")());
  std::vector<uint32_t> b;
  if (!bonds.is_none()) {
    const auto pairs = py::array_t<int64_t, py::array::c_style | py::array::forcecast>(bonds);
    if (pairs.size() > 0 && (pairs.ndim() != 2 || pairs.shape(1) != 2))
      throw softmol::Error("bonds: expected an array of shape (bonds, 2)");
    for (py::ssize_t i = 0; i < pairs.size(); ++i) {
      const int64_t v = pairs.data()[i];
      if (v < 0 || v > int64_t(UINT32_MAX)) throw softmol::Error("bonds: atom index " + std::to_string(v) + " is out of range");
      b.push_back(uint32_t(v));
    }
    if (b.empty()) throw softmol::Error("bonds: empty; pass None to compute bonds from distances");
  }
  return PyMolecule{softmol::Molecule::FromArrays(std::span<const double>(xyz.data(), size_t(xyz.size())), symbols, r, b),
                    softmol::Renderer()};
}

}  // namespace

PYBIND11_MODULE(softmol, m) {
  m.doc() = "softmol: CPU renderer of molecules (quadric impostors, baked and cone-traced AO)";
  m.attr("__version__") = softmol::Version();
  py::register_exception<softmol::Error>(m, "Error", PyExc_ValueError);

  py::class_<softmol::Image, std::shared_ptr<softmol::Image>>(m, "Image", "A rendered frame, top row first")
      .def_property_readonly("width", [](const softmol::Image& i) { return i.width; })
      .def_property_readonly("height", [](const softmol::Image& i) { return i.height; })
      .def_property_readonly("rgba", [](py::object self) {
        const auto& i = self.cast<const softmol::Image&>();
        return View(i.rgba, i, 4, self);
      }, "uint8 (height, width, 4): sRGB, straight alpha; a view of the image's buffer")
      .def_property_readonly("depth", [](py::object self) {
        const auto& i = self.cast<const softmol::Image&>();
        return View(i.depth, i, 1, self);
      }, "float32 (height, width): eye-space Å along the view axis, inf on the background; None unless asked")
      .def_property_readonly("normal", [](py::object self) {
        const auto& i = self.cast<const softmol::Image&>();
        return View(i.normal, i, 3, self);
      }, "float32 (height, width, 3): eye-space normals; None unless asked")
      .def_property_readonly("ao", [](py::object self) {
        const auto& i = self.cast<const softmol::Image&>();
        return View(i.ao, i, 1, self);
      }, "float32 (height, width): accessibility in [0, 1]; None unless asked")
      .def_property_readonly("id", [](py::object self) {
        const auto& i = self.cast<const softmol::Image&>();
        return View(i.id, i, 1, self);
      }, "uint32 (height, width): primitive id, 0xFFFFFFFF on the background; None unless asked")
      .def("save", [](const softmol::Image& i, const py::object& file) {
        const std::string path = PathOf(file);
        if (path.size() < 4 || path.substr(path.size() - 4) != ".png")
          throw softmol::Error(path + ": Image.save writes PNG; for EXR use Molecule.render_file");
        i.SavePng(path);
      }, py::arg("path"), "Writes the PNG softmol render writes (RGB, or RGBA when transparent)")
      .def("_repr_png_", [](const softmol::Image& i) {
        const std::vector<uint8_t> png = i.EncodePng();
        return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
      })
      .def("__repr__", [](const softmol::Image& i) {
        return "<softmol.Image " + std::to_string(i.width) + "x" + std::to_string(i.height) + ">";
      });

  py::class_<PyMolecule>(m, "Molecule", "A molecule and the renderer that keeps its AO bake")
      .def_static("from_arrays", &FromArrays, py::arg("xyz"), py::arg("elements"), py::arg("radii") = py::none(),
                  py::arg("bonds") = py::none(),
                  "Atoms from arrays: xyz (atoms, 3) Å, element symbols, optional radii (Å) and bonds (pairs of "
                  "atom indices; None: computed from distances as the command does)")
      .def_property_readonly("atom_count", [](const PyMolecule& p) { return p.molecule.AtomCount(); })
      .def("__len__", [](const PyMolecule& p) { return p.molecule.AtomCount(); })
      .def_property_readonly("path", [](const PyMolecule& p) { return p.molecule.Path(); })
      .def_property("positions",
                    [](const PyMolecule& p) {
                      std::vector<double> xyz = p.molecule.Positions();
                      py::array_t<double> a({py::ssize_t(xyz.size() / 3), py::ssize_t(3)});
                      std::copy(xyz.begin(), xyz.end(), a.mutable_data());
                      return a;
                    },
                    [](PyMolecule& p, const py::array_t<double, py::array::c_style | py::array::forcecast>& xyz) {
                      SetPositions(p.molecule, xyz);
                    },
                    "(atoms, 3) float64 Å; setting it renders the molecule as a trajectory frame")
      .def("render", &Render, py::arg("positions") = py::none(),
           "Renders with softmol render's options as keywords (size=(1280, 960), ao='baked', style='balls', "
           "color='chain', show=['ligand=balls'], aovs=('depth', 'ao'), ao_directions=64, ...); positions= moves "
           "the atoms first (a trajectory frame)")
      .def("render_file", [](PyMolecule& self, const py::object& path, const py::kwargs& kwargs) {
        const softmol::Options options = OptionsOf(kwargs);
        self.renderer.RenderToFile(self.molecule, PathOf(path), options);
      }, py::arg("path"), "Writes the frame as softmol render -o PATH does (.png, with NAME.aov.exr for AOVs, or .exr)");

  m.def("load", [](const py::object& path, const std::string& assembly) {
    return PyMolecule{softmol::Molecule::Load(PathOf(path), assembly), softmol::Renderer()};
  }, py::arg("path"), py::arg("assembly") = "", "Reads a PDB or mmCIF file (plain or .gz), as softmol render does");
}

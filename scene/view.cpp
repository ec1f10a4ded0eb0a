// scene/view.cpp — view text and PyMOL's get_view.
#include "scene/view.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "io/params.h"

namespace softmol::scene {
namespace {

std::vector<std::string_view> Words(std::string_view text) {
  std::vector<std::string_view> words;
  for (size_t i = 0; i < text.size();) {
    const size_t a = text.find_first_not_of(" \t\r\n", i);
    if (a == std::string_view::npos) break;
    const size_t b = std::min(text.find_first_of(" \t\r\n", a), text.size());
    words.push_back(text.substr(a, b - a));
    i = b;
  }
  return words;
}

glm::dvec3 ParseVector(std::string_view key, std::string_view text, const io::SourceLocation& where) {
  glm::dvec3 v(0.0);
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t comma = k < 2 ? text.find(',', start) : text.size();
    if (comma == std::string_view::npos)
      throw io::InputError(where, std::string(key) + " needs X,Y,Z, got " + io::Quoted(text));
    v[k] = io::ParseRealValue(text.substr(start, comma - start), {-1e9, 1e9}, "Å", where);
    start = comma + 1;
  }
  if (start <= text.size()) throw io::InputError(where, std::string(key) + " needs X,Y,Z, got " + io::Quoted(text));
  return v;
}

std::string FormatVector(glm::dvec3 v) {
  return io::FormatReal(v.x) + "," + io::FormatReal(v.y) + "," + io::FormatReal(v.z);
}

// Every number in PyMOL's `set_view (\ 0.53, ..., -20.0 )`; the words around them are skipped.
bool PyMolNumbers(std::string_view text, std::vector<double>& out) {
  std::string cleaned(text);
  for (char& c : cleaned)
    if (c == ',' || c == '(' || c == ')' || c == '\\') c = ' ';
  std::vector<std::string_view> words = Words(cleaned);
  if (!words.empty() && (words.front() == "set_view" || words.front() == "cmd.set_view")) words.erase(words.begin());
  out.clear();
  for (std::string_view w : words) {
    double v = 0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v)) return false;
    out.push_back(v);
  }
  return out.size() == 18;
}

// Camera = R·(model − origin) + pos, R column-major in v[0..8] (PyMOL's SceneGetView).
View ViewOfPyMol(const std::vector<double>& v) {
  const auto row = [&](int i) { return glm::dvec3(v[i], v[3 + i], v[6 + i]); };  // R's row i
  const glm::dvec3 pos(v[9], v[10], v[11]), origin(v[12], v[13], v[14]);
  View view;
  // model = Rᵀ·(camera − pos) + origin, and Rᵀ·c = Σ c_i · row_i.
  view.eye = origin - (pos.x * row(0) + pos.y * row(1) + pos.z * row(2));
  const glm::dvec3 forward = -row(2);
  view.target = view.eye + forward * std::max(std::abs(pos.z), 1e-3);
  view.up = row(1);
  const double fov = std::abs(v[17]);
  view.fovYDegrees = fov > 0 ? fov : 20.0;  // PyMOL's default field_of_view
  if (v[17] > 0) view.orthoHeight = 2.0 * std::abs(pos.z) * std::tan(0.5 * view.fovYDegrees * std::numbers::pi / 180.0);
  if (v[15] > 0 && v[16] > v[15]) view.nearPlane = v[15], view.farPlane = v[16];
  return view;
}

bool Bounded(glm::dvec3 v) { return std::abs(v.x) <= 1e9 && std::abs(v.y) <= 1e9 && std::abs(v.z) <= 1e9; }

void CheckCamera(const View& v, const io::SourceLocation& where) {
  // (The PyMOL form computes eye and target: they may overflow what the key=value form allows.)
  if (!Bounded(v.eye) || !Bounded(v.target) || !Bounded(v.up) || !(v.farPlane <= 1e9) || !(v.orthoHeight <= 1e9))
    throw io::InputError(where, "the camera is beyond ±1e9 Å");
  const glm::dvec3 f = v.target - v.eye, side = glm::cross(f, v.up);
  if (glm::dot(f, f) == 0.0 || glm::dot(side, side) == 0.0)
    throw io::InputError(where, "eye and target coincide, or up is parallel to the view direction");
  if (!(v.fovYDegrees >= 0.1 && v.fovYDegrees <= 179.0)) throw io::InputError(where, "fov must be in [0.1, 179] degrees");
  if ((v.farPlane > 0 || v.nearPlane > 0) && !(v.nearPlane > 0 && v.farPlane > v.nearPlane))
    throw io::InputError(where, "near and far go together: 0 < near < far");
}

}  // namespace

View ParseView(std::string_view text, const io::SourceLocation& where) {
  std::vector<double> pymol;
  View view;
  if (PyMolNumbers(text, pymol)) {
    view = ViewOfPyMol(pymol);
    CheckCamera(view, where);
    return view;
  }
  bool hasEye = false, hasTarget = false;
  for (std::string_view word : Words(text)) {
    const size_t eq = word.find('=');
    const std::string_view key = word.substr(0, eq), value = eq == std::string_view::npos ? "" : word.substr(eq + 1);
    if (key == "eye") view.eye = ParseVector(key, value, where), hasEye = true;
    else if (key == "target") view.target = ParseVector(key, value, where), hasTarget = true;
    else if (key == "up") view.up = ParseVector(key, value, where);
    else if (key == "fov") view.fovYDegrees = io::ParseRealValue(value, {0.1, 179.0}, "degrees", where);
    else if (key == "ortho") view.orthoHeight = io::ParseRealValue(value, {0.0, 1e9, true}, "Å", where);
    else if (key == "near") view.nearPlane = io::ParseRealValue(value, {0.0, 1e9}, "Å", where);
    else if (key == "far") view.farPlane = io::ParseRealValue(value, {0.0, 1e9}, "Å", where);
    else
      throw io::InputError(where, "expected eye=X,Y,Z target=X,Y,Z up=X,Y,Z [fov=DEG|ortho=HEIGHT] [near=N far=F], "
                                  "or PyMOL's 18-number get_view; got " + io::Quoted(word));
  }
  if (!hasEye || !hasTarget) throw io::InputError(where, "a view needs eye=X,Y,Z and target=X,Y,Z");
  CheckCamera(view, where);
  return view;
}

std::string FormatView(const View& v) {
  std::string s = "eye=" + FormatVector(v.eye) + " target=" + FormatVector(v.target) + " up=" + FormatVector(v.up);
  s += v.orthoHeight > 0 ? " ortho=" + io::FormatReal(v.orthoHeight) : " fov=" + io::FormatReal(v.fovYDegrees);
  if (v.farPlane > 0) s += " near=" + io::FormatReal(v.nearPlane) + " far=" + io::FormatReal(v.farPlane);
  return s;
}

View ViewOf(const raster::Camera& c) {
  View v;
  v.eye = c.eye, v.target = c.target, v.up = c.up, v.fovYDegrees = c.fovYDegrees;
  v.orthoHeight = c.orthographic ? c.orthoHeight : 0.0;
  v.nearPlane = c.nearPlane, v.farPlane = c.farPlane;
  return v;
}

raster::Camera CameraOf(const View& v, int width, int height) {
  raster::Camera c;
  c.width = width, c.height = height;
  c.eye = v.eye, c.target = v.target, c.up = v.up, c.fovYDegrees = v.fovYDegrees;
  c.orthographic = v.orthoHeight > 0, c.orthoHeight = v.orthoHeight;
  c.nearPlane = v.nearPlane, c.farPlane = v.farPlane;
  return c;
}

}  // namespace softmol::scene

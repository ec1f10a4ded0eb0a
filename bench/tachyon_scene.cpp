// bench/tachyon_scene.cpp — writes a Tachyon scene (.dat) of what `softmol render` draws by
// default (spacefill, water hidden: scene::ResolveLooks of the default layers; the same
// spheres, radii and colours) from the camera a `--view` gives (the one `softmol render
// --print-view` printed), for bench/peers_tachyon.py to time Tachyon on the same picture.
// Tachyon's camera is left-handed (its image is softmol's mirrored left to right), so every x
// is negated; its ZOOM is 1 / (2·tan(fov/2)) (image plane at distance 1, 1/zoom high). One
// directional light along softmol's light, shadows on (SHADER_MODE FULL), softmol's
// ambient/diffuse/specular weights, and with --ao-samples N Tachyon's own ambient occlusion
// (N sample rays) standing in for the ambient term. Colours are given as softmol's sRGB values
// (Tachyon shades them as they are; no gamma), so the images agree in framing and light, not
// in exact tone.
// Run: tachyon_scene data/1tii.pdb --view "$(softmol render ... --print-view ...)" --size 1024x768 -o 1tii.dat
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "effects/shading.h"
#include "io/atomic_file.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"
#include "scene/layers.h"
#include "scene/view.h"

namespace {

using namespace softmol;

struct Args {
  std::string molecule, view, size = "1024x768", assembly, output;
  int aoSamples = 0;
};

// Tachyon's world is softmol's mirrored in x (see the top of the file).
glm::dvec3 Mirror(glm::dvec3 v) { return {-v.x, v.y, v.z}; }

void Append(std::string& out, const char* format, auto... values) {
  char line[256];
  const int n = std::snprintf(line, sizeof line, format, values...);
  out.append(line, size_t(n));
}
void AppendVec(std::string& out, const char* keyword, glm::dvec3 v) {
  Append(out, "  %s %.9g %.9g %.9g\n", keyword, v.x, v.y, v.z);
}

// Header: resolution, shader mode (AO), camera, background, the light.
void WriteHeader(std::string& out, const raster::Camera& cam, const effects::ShadingOptions& shading,
                 int aoSamples) {
  Append(out, "BEGIN_SCENE\nRESOLUTION %d %d\nSHADER_MODE FULL\n", cam.width, cam.height);
  if (aoSamples > 0) {
    Append(out, "  AMBIENT_OCCLUSION\n    AMBIENT_COLOR %g %g %g\n    RESCALE_DIRECT 1\n    SAMPLES %d\n",
           shading.ambient, shading.ambient, shading.ambient, aoSamples);
  }
  out += "END_SHADER_MODE\nCAMERA\n  PROJECTION PERSPECTIVE\n";
  Append(out, "  ZOOM %.9g\n  ASPECTRATIO 1\n  ANTIALIASING 0\n  RAYDEPTH 4\n",
         1.0 / (2.0 * std::tan(0.5 * cam.fovYDegrees * 3.14159265358979323846 / 180.0)));
  const glm::dvec3 view = glm::normalize(cam.target - cam.eye);
  const glm::dvec3 up = glm::normalize(glm::cross(glm::cross(view, cam.up), view));
  AppendVec(out, "CENTER", Mirror(cam.eye));
  AppendVec(out, "VIEWDIR", Mirror(view));
  AppendVec(out, "UPDIR", Mirror(up));
  out += "END_CAMERA\nBACKGROUND 1 1 1\n";
  // softmol's light is an eye-space direction towards the light; Tachyon's is the world-space
  // direction the light travels.
  const glm::vec3 light = effects::LightVectors(shading).key;
  const glm::dmat3 eyeToWorld = glm::transpose(glm::dmat3(raster::ViewMatrix(cam)));
  const glm::dvec3 towards = eyeToWorld * glm::dvec3(light);
  Append(out, "DIRECTIONAL_LIGHT DIRECTION %.9g %.9g %.9g COLOR 1 1 1\n", -Mirror(towards).x,
         -Mirror(towards).y, -Mirror(towards).z);
}

// One texture per distinct colour, then one SPHERE line per drawn sphere.
void WriteSpheres(std::string& out, const raster::SphereSet& s, const effects::ShadingOptions& shading,
                  bool ao) {
  std::map<uint32_t, int> texture;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!texture.emplace(s.color[i], int(texture.size())).second) continue;
    const uint32_t c = s.color[i];
    Append(out,
           "TEXDEF c%d AMBIENT %g DIFFUSE %g SPECULAR 0 OPACITY 1 PHONG PLASTIC %g PHONG_SIZE %d "
           "COLOR %.6g %.6g %.6g TEXFUNC 0\n",
           texture[c], ao ? 0.0 : double(shading.ambient), double(shading.key), double(shading.specular),
           shading.shininess, ((c >> 16) & 0xFF) / 255.0, ((c >> 8) & 0xFF) / 255.0, (c & 0xFF) / 255.0);
  }
  for (size_t i = 0; i < s.size(); ++i) {
    if (!(s.radius[i] > 0.0f) || !std::isfinite(s.radius[i])) continue;  // softmol draws none of these
    Append(out, "SPHERE CENTER %.6f %.6f %.6f RAD %.6g c%d\n", -s.x[i], s.y[i], s.z[i], double(s.radius[i]),
           texture[s.color[i]]);
  }
  out += "END_SCENE\n";
}

int Run(const Args& a) {
  io::ReadOptions read;
  read.assembly = a.assembly;
  const io::Molecule mol = io::ReadMolecule(a.molecule, read);
  const scene::ResolvedLooks looks = scene::ResolveLooks(mol, scene::SceneLayers{});
  const raster::Representation drawn = raster::BuildRepresentation(mol, looks.looks, raster::RepresentationOptions{});
  int width = 0, height = 0;
  char x = 0;
  if (std::sscanf(a.size.c_str(), "%d%c%d", &width, &x, &height) != 3 || x != 'x' || width < 1 || height < 1)
    throw std::runtime_error("--size: expected WIDTHxHEIGHT, got '" + a.size + "'");
  const raster::Camera cam = scene::CameraOf(scene::ParseView(a.view, {"--view"}), width, height);
  if (cam.orthographic) throw std::runtime_error("--view: only perspective views are written");
  const effects::ShadingOptions shading;
  std::string out;
  out.reserve(drawn.scene.spheres.size() * 56 + 4096);
  WriteHeader(out, cam, shading, a.aoSamples);
  WriteSpheres(out, drawn.scene.spheres, shading, a.aoSamples > 0);
  io::TemporaryFile file(a.output);
  file.Write(out.data(), out.size());
  file.Commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes a Tachyon scene of softmol's default spacefill picture (bench/peers_tachyon.py)"};
  Args a;
  app.add_option("MOLECULE", a.molecule, "PDB or mmCIF file")->required();
  app.add_option("--view", a.view, "The camera, as `softmol render --print-view` prints it")->required();
  app.add_option("--size", a.size, "WIDTHxHEIGHT");
  app.add_option("--assembly", a.assembly, "Biological assembly ID");
  app.add_option("--ao-samples", a.aoSamples, "Tachyon ambient-occlusion sample rays (0: no AO)")
      ->check(CLI::Range(0, 4096));
  app.add_option("-o", a.output, "Output .dat")->required();
  try {
    app.parse(argc, argv);
    return Run(a);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tachyon_scene: %s\n", e.what());
    return 2;
  }
}

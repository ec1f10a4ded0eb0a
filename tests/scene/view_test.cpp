// tests/scene/view_test.cpp — orient and fit, and the view as text: the default camera puts the
// largest principal axis along the image's x (against a power-iteration eigen-decomposition
// written here), the projected molecule fills ≥ 90% of the limiting image side, a printed
// view reads back as the same camera bits, and PyMOL's get_view gives the camera its
// modelview matrix describes (inverted here with glm, not by the formula under test).
#include "scene/view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "effects/frame_renderer.h"
#include "io/structure_reader.h"
#include "scene/layers.h"

namespace softmol::scene {
namespace {

raster::Representation Drawn(const char* name) {
  const io::Molecule m = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/" + name);
  return raster::BuildRepresentation(m, ResolveLooks(m, SceneLayers{}).looks, raster::RepresentationOptions{});
}

// The dominant eigenvector of the centres' covariance by power iteration.
glm::dvec3 LargestAxis(const raster::SphereSet& s) {
  glm::dvec3 mean(0.0);
  for (size_t i = 0; i < s.size(); ++i) mean += glm::dvec3(s.x[i], s.y[i], s.z[i]);
  mean /= double(s.size());
  glm::dmat3 cov(0.0);
  for (size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(s.x[i], s.y[i], s.z[i]) - mean;
    cov += glm::outerProduct(d, d);
  }
  glm::dvec3 v(1.0, 0.7, 0.3);
  for (int it = 0; it < 500; ++it) v = glm::normalize(cov * v);
  return v;
}

TEST(Orient, LargestPrincipalAxisAlongXAndTheMoleculeFillsTheImage) {
  for (const char* name : {"1tii.pdb", "4YVS.cif", "3sn6.pdb"}) {
    SCOPED_TRACE(name);
    const raster::Representation d = Drawn(name);
    raster::Camera cam = raster::OrientedCamera(d.scene, 400, 300);
    raster::FitNearFar(cam, d.scene);
    const glm::dvec3 f = glm::normalize(cam.target - cam.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(f, cam.up));
    EXPECT_GT(std::abs(glm::dot(right, LargestAxis(d.scene.spheres))), 0.999);
    effects::RenderOptions ro;
    ro.aovs = effects::kAovId;
    ro.color = false;
    const effects::RenderedFrame fr = effects::RenderFrame(d.scene, cam, ro);
    int x0 = fr.width, x1 = -1, y0 = fr.height, y1 = -1;
    for (int y = 0; y < fr.height; ++y)
      for (int x = 0; x < fr.width; ++x)
        if (fr.id[size_t(y) * fr.width + x] != raster::kNoPrimitive)
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    const double fill = std::max(double(x1 - x0 + 1) / fr.width, double(y1 - y0 + 1) / fr.height);
    EXPECT_GE(fill, 0.90);
    EXPECT_GT(x0, 0);  // a margin: nothing touches the border
    EXPECT_LT(x1, fr.width - 1);
    EXPECT_GT(y0, 0);
    EXPECT_LT(y1, fr.height - 1);
  }
}

TEST(ViewText, PrintedViewsReadBackBitForBit) {
  raster::Camera cam = raster::OrientedCamera(Drawn("pept.pdb").scene, 640, 480);
  raster::FitNearFar(cam, Drawn("pept.pdb").scene);
  const View v = ParseView(FormatView(ViewOf(cam)), {"--view"});
  const raster::Camera back = CameraOf(v, 640, 480);
  EXPECT_EQ(back.eye, cam.eye);
  EXPECT_EQ(back.target, cam.target);
  EXPECT_EQ(back.up, cam.up);
  EXPECT_EQ(back.nearPlane, cam.nearPlane);
  EXPECT_EQ(back.farPlane, cam.farPlane);
  EXPECT_EQ(back.fovYDegrees, cam.fovYDegrees);
  const View o = ParseView("eye=0,0,50 target=0,0,0 up=0,1,0 ortho=40", {"--view"});
  EXPECT_EQ(o.orthoHeight, 40.0);
  EXPECT_TRUE(CameraOf(o, 10, 10).orthographic);
  for (const char* bad : {"eye=0,0,1", "eye=1,1,1 target=1,1,1", "eye=0,0,1 target=0,0,0 up=0,0,1",
                          "eye=0,0,1,2 target=0,0,0", "eye=0,0,5 target=0,0,0 near=9", "zoom=3", "1 2 3"}) {
    try {
      (void)ParseView(bad, {"--view"});
      ADD_FAILURE() << bad;
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--view: ", 0), 0u) << e.what();
    }
  }
}

// PyMOL 2.5's get_view after `orient` of data/pept.pdb with field_of_view 30, as it prints it.
constexpr const char* kPyMolView = R"(set_view (\
     0.536882818,    0.311563969,    0.784018338,\
    -0.840586722,    0.118341126,    0.528591871,\
     0.071908556,   -0.942827284,    0.325431854,\
     0.000000000,    0.000000000,  -63.190540314,\
     1.224037170,  -10.279197693,   20.545440674,\
    49.819904327,   76.561180115,  -30.000000000 ))";

TEST(ViewText, PyMolGetViewIsTheCameraOfItsModelviewMatrix) {
  const View v = ParseView(kPyMolView, {"--view"});
  // PyMOL's modelview: translate(pos) · R · translate(−origin), R column-major in v[0..8].
  const double r[9] = {0.536882818, 0.311563969, 0.784018338, -0.840586722, 0.118341126,
                       0.528591871, 0.071908556, -0.942827284, 0.325431854};
  glm::dmat4 rot(1.0);
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) rot[c][row] = r[3 * c + row];
  const glm::dmat4 modelview = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, -63.190540314)) * rot *
                               glm::translate(glm::dmat4(1.0), -glm::dvec3(1.224037170, -10.279197693, 20.545440674));
  const glm::dmat4 cameraToModel = glm::inverse(modelview);
  const glm::dvec3 eye(cameraToModel * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 ahead(cameraToModel * glm::dvec4(0, 0, -1, 1));
  const glm::dvec3 up = glm::dvec3(cameraToModel * glm::dvec4(0, 1, 0, 0));
  EXPECT_LT(glm::length(v.eye - eye), 1e-6);
  EXPECT_LT(glm::length(glm::normalize(v.target - v.eye) - glm::normalize(ahead - eye)), 1e-6);
  EXPECT_LT(glm::length(glm::normalize(v.up) - glm::normalize(up)), 1e-6);
  EXPECT_LT(glm::length(v.target - glm::dvec3(1.224037170, -10.279197693, 20.545440674)), 1e-6)
      << "the origin of rotation straight ahead";
  EXPECT_EQ(v.fovYDegrees, 30.0);
  EXPECT_EQ(v.orthoHeight, 0.0);
  EXPECT_NEAR(v.nearPlane, 49.819904327, 1e-9);
  EXPECT_NEAR(v.farPlane, 76.561180115, 1e-9);
  // The same numbers without PyMOL's punctuation, and orthoscopic (positive field of view).
  std::string plain = kPyMolView;
  for (char& c : plain)
    if (c == '\\' || c == '(' || c == ')' || c == ',') c = ' ';
  plain = plain.substr(plain.find("set_view") + 8);
  plain.replace(plain.rfind("-30.0"), 1, " ");
  const View ortho = ParseView(plain, {"--view"});
  EXPECT_GT(ortho.orthoHeight, 0.0);
  EXPECT_NEAR(ortho.orthoHeight, 2.0 * 63.190540314 * std::tan(15.0 * M_PI / 180.0), 1e-9);
}

}  // namespace
}  // namespace softmol::scene

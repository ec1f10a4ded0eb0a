// scene/view.h — a camera as text, so a render's view can be printed (--print-view) and given
// back (--view, the scene file's "view") to the same bytes:
//   eye=EX,EY,EZ target=TX,TY,TZ up=UX,UY,UZ fov=30 near=N far=F    (perspective)
//   eye=... target=... up=... ortho=HEIGHT near=N far=F             (orthographic)
// Numbers are printed shortest-exact, so they read back as the same doubles. near/far may be
// left out (fitted to the scene). Also accepted: PyMOL's 18-number `get_view` matrix, as
// PyMOL prints it (`set_view (\ ... )` pasted whole, or just the numbers):
//   0-8   model-to-camera rotation, column-major     9-11  camera-space position of the origin
//   12-14 origin of rotation (model space)          15,16 front and rear clip distances
//   17    field of view in degrees: negative for perspective, positive for orthoscopic
#pragma once

#include <string>
#include <string_view>

#include "io/error.h"
#include "raster/camera.h"

namespace softmol::scene {

struct View {
  glm::dvec3 eye{0.0}, target{0.0}, up{0.0, 1.0, 0.0};
  double fovYDegrees = 30.0;
  double orthoHeight = 0.0;  // > 0: orthographic
  double nearPlane = 0.0, farPlane = 0.0;  // 0: fitted
};

// Throws io::InputError at `where` for malformed text or a degenerate camera (eye on the
// target, up along the view direction).
View ParseView(std::string_view text, const io::SourceLocation& where);
std::string FormatView(const View& view);

View ViewOf(const raster::Camera& camera);
// The camera of `view` at this image size (near/far as the view has them).
raster::Camera CameraOf(const View& view, int width, int height);

}  // namespace softmol::scene

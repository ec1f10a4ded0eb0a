// raster/camera.h — the view: eye, target, up, and an OpenGL projection (perspective with a
// vertical field of view, or orthographic). Eye space looks down −Z, window pixel centres are
// at (x + 0.5, y + 0.5) with y up (DESIGN.md). Near/far of 0 mean "fitted to the scene".
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "raster/primitives.h"

namespace softmol::raster {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 10.0}, target{0.0}, up{0.0, 1.0, 0.0};
  double fovYDegrees = 30.0;  // perspective only
  bool orthographic = false;
  double orthoHeight = 0.0;                // view height in Å (orthographic only)
  double nearPlane = 0.0, farPlane = 0.0;  // eye-space distances along −Z; 0 = fitted
  int width = 0, height = 0;               // pixels rendered (the window's, see below)
  // A window into a larger frame (one band of a poster): the frame is frameWidth × frameHeight
  // pixels, projected as a camera of that size would project it, and this camera renders the
  // width × height of them whose lower-left pixel is (windowX, windowY), y up. Every ray is the
  // frame's own ray through that pixel, bit for bit (HalfWidth below says why), so a frame
  // rendered window by window is the frame rendered at once. 0, 0, 0, 0: the window is the frame.
  int windowX = 0, windowY = 0, frameWidth = 0, frameHeight = 0;
};

// The whole frame's size (the camera's own when it is not a window).
inline int FrameWidth(const Camera& c) { return c.frameWidth > 0 ? c.frameWidth : c.width; }
inline int FrameHeight(const Camera& c) { return c.frameHeight > 0 ? c.frameHeight : c.height; }
inline bool IsWindow(const Camera& c) {
  return c.windowX != 0 || c.windowY != 0 || FrameWidth(c) != c.width || FrameHeight(c) != c.height;
}
// The frame's centre in the window's pixel coordinates: what PixelToRay subtracts. A window's
// pixel p is the frame's pixel p + windowX, and ((p + 0.5) − (W/2 − windowX)) is computed
// exactly (in float too: both terms are multiples of ½ below 2²³), so it equals the frame's
// ((p + windowX + 0.5) − W/2) to the last bit.
inline double HalfWidth(const Camera& c) { return 0.5 * FrameWidth(c) - c.windowX; }
inline double HalfHeight(const Camera& c) { return 0.5 * FrameHeight(c) - c.windowY; }

// The pixels [x0, x0 + width) × [y0, y0 + height) (y up) of `frame`'s frame as a window camera
// (x0, y0 relative to `frame`'s own window when it is one).
Camera Window(const Camera& frame, int x0, int y0, int width, int height);
// The same view with `samples` × the pixels along each axis (supersampling): a window's
// position and its frame scale with it.
Camera Supersampled(const Camera& camera, int samples);

// DESIGN.md auto-framing: 30° vertical FOV, looking along −Z at the bounding-sphere centre,
// at the distance where the sphere fits the smaller image dimension with a 5% margin.
Camera DefaultCamera(const PrimitiveScene& scene, int width, int height);

// PyMOL's `orient`, and a tight fit: the view axes are the principal axes of the primitives'
// centres (largest extent along the image's x, the next along y, signs chosen so that each
// axis's largest component is positive), the target the centre of their projected box, and
// the eye at the distance (the view height, for orthographic views) where every primitive's
// silhouette fits the field of view with kFitMargin on the limiting side.
constexpr double kFitMargin = 0.04;  // of the half-width
Camera OrientedCamera(const PrimitiveScene& scene, int width, int height, double fovYDegrees = 30.0);

// Rotates the eye (and up) about `center` by X, then Y, then Z degrees in the camera's own
// frame (so "--rotate 0,90,0" turns the molecule to show its side).
void ApplyRotation(Camera& camera, glm::dvec3 degreesXYZ, glm::dvec3 center);
// factor > 1 brings the view closer (perspective: eye moves toward target; ortho: height / f).
void ApplyZoom(Camera& camera, double factor);
// Sets nearPlane/farPlane to enclose the scene's bounding sphere (kept ≥ 1e-4 × far).
void FitNearFar(Camera& camera, const PrimitiveScene& scene);

// OpenGL matrices (gluLookAt / gluPerspective / glOrtho) for the GL mirror and for tests; a
// window's projection is its whole frame's.
glm::dmat4 ViewMatrix(const Camera& camera);
glm::dmat4 ProjectionMatrix(const Camera& camera);  // needs nearPlane, farPlane > 0

// Ray through the pixel centre (x + 0.5, y + 0.5), eye space: perspective rays start at the
// eye with direction (u, v, −1); orthographic rays start at (u, v, 0) with direction (0,0,−1).
// pixelScale is tan-space units (perspective) or Å (orthographic) per pixel.
double PixelScale(const Camera& camera);
// A pixel centre's ray parameter along one axis, in double (the references: ao/reference_ao,
// tests/support): ((p + 0.5) − extent/2)·scale, with halfExtent = width/2 or height/2 and
// scale = PixelScale. The kernels' float twins: shared::PixelToRay (raster/shared/quadratic.inc)
// and its SIMD form in raster/pixel_ray-inl.h.
inline double PixelToRay(double pixel, double halfExtent, double scale) {
  return ((pixel + 0.5) - halfExtent) * scale;
}

}  // namespace softmol::raster

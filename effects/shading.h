// effects/shading.h — deferred shading of the G-buffer (Sigg et al. 2006, §4 "Deferred
// Shading"): each visible pixel is lit exactly once, after all overdraw is resolved.
// Ambient + Lambert + Blinn-Phong with an integer exponent (so the bits are the same on every
// machine), one white directional light, in linear light. Background pixels are left alone.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "raster/gbuffer.h"

namespace softmol::effects {

struct ShadingOptions {
  glm::vec3 lightDirection{-0.35f, 0.45f, 0.82f};  // eye space, towards the light (normalized on use)
  float ambient = 0.30f;
  float diffuse = 0.70f;
  float specular = 0.35f;
  int shininess = 32;  // integer Blinn-Phong exponent, 1..1024
};

// What the shading pass composites over.
struct Backdrop {
  glm::vec3 color{1.0f, 1.0f, 1.0f};  // linear RGB
  bool transparent = false;           // alpha 0 instead of `color`
};

// The deferred shading pass fused with the supersample resolve: shades every G-buffer sample
// (needs the normal, base-colour and id channels) and averages each ssaa×ssaa block into one
// premultiplied linear RGBA pixel of `rgba` (4 floats a pixel, g.width/ssaa × g.height/ssaa,
// top row first, as files store them). Fusing them means the shaded samples never go through
// memory. `ambientOcclusion` (one value a sample, 1 = open) scales the ambient term when given.
// Parallel over rows; the result does not depend on the thread count.
void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, std::span<const float> ambientOcclusion,
                     std::span<float> rgba);

// One pixel, the formula ShadeDeferred applies (the reference for tests and the GL mirror).
glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     glm::vec3 lightDirection, glm::vec3 halfVector, const ShadingOptions& o);

// The unit light direction and Blinn's half vector for a viewer along +Z in eye space.
// Using the constant view vector (as for a distant viewer) keeps highlights stable as the
// molecule turns; the error against the true per-pixel view vector is below the 30° FOV.
void LightVectors(const ShadingOptions& o, glm::vec3& light, glm::vec3& half);

}  // namespace softmol::effects

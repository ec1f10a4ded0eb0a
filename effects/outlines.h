// effects/outlines.h — silhouette and crease lines (Sigg et al. 2006 §4): a Sobel filter on the
// G-buffer's eye depth and normals; the gradient lengths, past a threshold, become a line
// strength in [0,1] that the shading pass blends toward the outline colour (effects/shading.h).
// SIMD (Highway, one dispatch per row) with a scalar twin built from effects/shared/sobel.inc;
// the two agree bit for bit, and the result is the same for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "raster/camera.h"
#include "raster/gbuffer.h"

namespace softmol::effects {

// Depth steps are measured on the linear eye depth in Å (not window depth, which shrinks a
// step at distance z by 1/z²), and relative to the centre sample's tangent plane: a neighbour
// one sample across is predicted at (n_x/n_z)·footprint Å deeper, footprint being the Å one
// sample spans there (z·pixelScale in perspective, pixelScale in ortho). So a tilted plane draws
// no line at any distance or tilt up to atan(slopeAllowance), and a step of h Å reads h near
// and far alike (the Sobel length is normalised so that a step h between two columns gives h).
struct OutlineOptions {
  float depthThreshold = 0.5f;   // Å: steps up to this draw no line
  float depthSoftness = 1.0f;    // Å: from the threshold to a full line
  float slopeAllowance = 4.0f;   // cap of the tangent-plane slope |n_t/n_z| (≈ 76°)
  float normalThreshold = 0.4f;  // Sobel length of the normals (≈ crease angle, radians)
  float normalSoftness = 0.4f;   // from the threshold to a full line
};

// True when every field is finite and in range (thresholds >= 0, softnesses > 0). The pass
// checks it as an invariant.
bool ValidOutlineOptions(const OutlineOptions& options);

// One line strength per G-buffer sample (index y·width + x) into `strength`; background
// samples beside a surface get the silhouette too (the background enters the filter as a
// depth step of threshold + softness, a full line). Normal differences count only between
// samples of two different primitives: a crease is where two atoms meet, while an atom's own
// curvature, however few samples it spans, never draws a line (a 3-sample sphere would be all
// "crease" otherwise). The G-buffer needs depth, normal and primitive id and must have been
// rendered with `camera`. Image borders repeat the edge samples.
void SobelOutlines(const raster::GBuffer& gbuffer, const raster::Camera& camera,
                   const OutlineOptions& options, std::span<float> strength);
// Scalar twin (effects/shared/sobel.inc only): the same bits, slowly. For tests.
void SobelOutlinesScalar(const raster::GBuffer& gbuffer, const raster::Camera& camera,
                         const OutlineOptions& options, std::span<float> strength);

namespace detail {

struct OutlineConstants {
  float pixelScale;
  bool ortho;
  float cap;  // depth steps are clamped to ±cap (a full line)
  float depthThreshold, depthInvSoftness, normalThreshold, normalInvSoftness, slopeAllowance;
  int width;
};

// Computed once per frame in C++, for both twins and the GL pass (gl/outlines.cpp).
OutlineConstants MakeOutlineConstants(const raster::Camera& camera, const OutlineOptions& options);

// The three rows around row y (index 0 below, 1 = y, 2 above; the border repeats its row) and
// their real offsets from y (0 where repeated).
struct OutlineRows {
  const float* depth[3];
  const float* nx[3];
  const float* ny[3];
  const float* nz[3];
  const uint32_t* id[3];  // primitive ids: creases are counted only between two primitives
  float dy[3];
};

// One row of strengths. Thread-safe for distinct rows.
void OutlineRow(const OutlineConstants& k, const OutlineRows& rows, float* strength) noexcept;
void OutlineRowScalar(const OutlineConstants& k, const OutlineRows& rows, float* strength) noexcept;

}  // namespace detail

}  // namespace softmol::effects

// raster/representation.h — turns a molecule into quadric primitives: spacefill (van der
// Waals spheres), balls (ball-and-stick: scaled spheres + bond cylinders coloured half and
// half), licorice (sticks with joint spheres of the same radius) and thermal ellipsoids
// (ANISOU at a given probability; atoms without one get an isotropic sphere) and the backbone
// tube (raster/tube.h). Each atom may have its own style and colour (AtomLooks: the scene's
// layers and colour rules, resolved), or be hidden: a hidden atom makes no primitive, so it
// casts no shadow and occludes no AO.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "io/molecule.h"
#include "raster/primitives.h"
#include "raster/tube.h"

namespace softmol::raster {

enum class Style { kSpacefill, kBalls, kLicorice, kEllipsoids, kTube };

struct RepresentationOptions {
  Style style = Style::kSpacefill;
  float ballScale = 0.25f;  // balls: sphere radius = ballScale × vdW (PyMOL sphere_scale 0.25)
  float bondRadius = 0.2f;  // balls and ellipsoids: bond cylinder radius, Å
  float licoriceRadius = 0.25f;       // licorice: stick and joint radius, Å (PyMOL stick_radius)
  float ellipsoidProbability = 0.5f;  // ellipsoids: probability contour (0.5 → c = 1.5382)
  TubeOptions tube;                   // tube: the backbone trace of every chain (raster/tube.h)
};

// What each atom looks like: style[i] is a Style or kHidden; color[i] sRGB 0xRRGGBB.
constexpr uint8_t kHidden = 0xFF;
struct AtomLooks {
  std::vector<uint8_t> style;
  std::vector<uint32_t> color;
};
// Every atom in one style, in the molecule's element colours.
AtomLooks UniformLooks(const io::Molecule& molecule, Style style);

// The primitives, and which atom each sphere and ellipsoid draws (tube pieces, after the
// atoms' spheres, draw residues: they have no entry) (what the id AOV's ids and
// per-atom effects such as the highlight halo map back through). Spheres and ellipsoids come
// in atom order; a bond's cylinder is drawn when both its atoms are in a style with sticks
// (balls, licorice, ellipsoids), coloured half and half.
struct Representation {
  PrimitiveScene scene;
  std::vector<uint32_t> sphereAtom, ellipsoidAtom;
};
Representation BuildRepresentation(const io::Molecule& molecule, const AtomLooks& looks,
                                   const RepresentationOptions& options);

// Every atom in options.style and its element colour.
PrimitiveScene BuildRepresentation(const io::Molecule& molecule,
                                   const RepresentationOptions& options);

// Scale c of the probability ellipsoid: P(χ²₃ ≤ c²) = p (c = 1.5382 for p = 0.5).
double EllipsoidScale(double probability);

// Eigen-decomposition of a symmetric 3×3 matrix (cyclic Jacobi, double): values ascending,
// vectors as columns (vectors[col][row]).
void SymmetricEigen3(const double m[3][3], double values[3], double vectors[3][3]);

}  // namespace softmol::raster

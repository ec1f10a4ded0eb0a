// scene/layers.h — what to draw: an ordered list of layers, each a selection with a style (or
// hidden) and optionally a colour. An atom belongs to the last layer that selects it; atoms in
// no layer, or in a hidden one, are not drawn (and so cast no shadow and occlude no AO).
// The default scene is one layer "all" in --style, then "water" hidden (solvent is shown only
// when asked for: --show-solvent, or a later layer that selects it).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/error.h"
#include "io/molecule.h"
#include "raster/representation.h"
#include "scene/colors.h"

namespace softmol::scene {

struct Layer {
  std::string selection;            // io/selection.h text
  std::optional<raster::Style> style;  // nothing: hidden
  std::optional<ColorRule> color;   // over this layer's atoms, after the scene's colour rules
};

// "SEL=STYLE" or "SEL=STYLE,COLOR" (STYLE may be "hidden"; COLOR any colour rule of
// scene/colors.h without a selection); throws io::InputError at `where`.
Layer ParseLayer(std::string_view text, const io::SourceLocation& where);
std::string FormatLayer(const Layer& layer);
// A scene-file layer object {"select": SEL, "style": STYLE, "color": COLOR} ("hide": true for a
// hidden one) as ParseLayer's text.
std::string LayerTextOfObject(const std::vector<std::pair<std::string, std::string>>& fields,
                              const io::SourceLocation& where);

// The styles a scene may use, by name (spacefill, balls, licorice, ellipsoids, tube).
const std::vector<std::pair<std::string, raster::Style>>& StyleNames();
std::string StyleName(raster::Style style);

struct SceneLayers {
  raster::Style style = raster::Style::kSpacefill;  // the first layer, "all"
  bool showSolvent = false;                         // else a second layer hides water
  std::vector<Layer> layers;                        // then these, in order
  std::vector<ColorRule> colors;                    // applied before the layers' own colours
};

// The layers in the order they apply, the defaults first.
std::vector<Layer> AllLayers(const SceneLayers& scene);
// Whether any layer draws sticks (the molecule then needs its bonds).
bool NeedsBonds(const SceneLayers& scene);

struct ResolvedLooks {
  raster::AtomLooks looks;
  std::vector<std::string> emptyLayers;  // selections of layers that selected no atom
};
// Each atom's style and colour.
ResolvedLooks ResolveLooks(const io::Molecule& molecule, const SceneLayers& scene);

}  // namespace softmol::scene

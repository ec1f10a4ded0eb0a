// scene/layers.cpp — layers → per-atom looks.
#include "scene/layers.h"

#include <algorithm>

#include "io/params.h"
#include "io/selection.h"

namespace softmol::scene {
namespace {

std::optional<raster::Style> ParseStyle(std::string_view name, const io::SourceLocation& where) {
  if (name == "hidden") return std::nullopt;
  for (const auto& [n, style] : StyleNames())
    if (n == name) return style;
  std::string all;
  for (const auto& [n, style] : StyleNames()) all += n + ", ";
  throw io::InputError(where, "unknown style " + io::Quoted(name) + " (" + all + "or hidden)");
}

}  // namespace

const std::vector<std::pair<std::string, raster::Style>>& StyleNames() {
  static const std::vector<std::pair<std::string, raster::Style>> kNames = {
      {"spacefill", raster::Style::kSpacefill},
      {"balls", raster::Style::kBalls},
      {"licorice", raster::Style::kLicorice},
      {"ellipsoids", raster::Style::kEllipsoids},
      {"tube", raster::Style::kTube}};
  return kNames;
}

std::string StyleName(raster::Style style) {
  for (const auto& [name, s] : StyleNames())
    if (s == style) return name;
  return "?";
}

Layer ParseLayer(std::string_view text, const io::SourceLocation& where) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos)
    throw io::InputError(where, "expected SELECTION=STYLE (e.g. ligand=balls), got " + io::Quoted(text));
  Layer layer;
  layer.selection = std::string(io::TrimBlanks(text.substr(0, eq)));
  if (layer.selection.empty()) throw io::InputError(where, "expected SELECTION=STYLE, got " + io::Quoted(text));
  (void)io::ParseSelection(layer.selection, where);
  std::string_view rest = text.substr(eq + 1);
  const size_t comma = rest.find(',');
  layer.style = ParseStyle(io::TrimBlanks(rest.substr(0, comma)), where);
  if (comma != std::string_view::npos) {
    const std::string_view color = io::TrimBlanks(rest.substr(comma + 1));
    if (color.find('=') != std::string_view::npos)
      throw io::InputError(where, "a layer's colour applies to its own selection: give it without SELECTION=");
    layer.color = ParseColorRule(color, where);
  }
  return layer;
}

std::string FormatLayer(const Layer& layer) {
  std::string s = layer.selection + "=" + (layer.style ? StyleName(*layer.style) : "hidden");
  if (layer.color) s += "," + FormatColorRule(*layer.color);
  return s;
}

std::string LayerTextOfObject(const std::vector<std::pair<std::string, std::string>>& fields,
                              const io::SourceLocation& where) {
  std::string select, style, color;
  bool hide = false, hasHide = false;
  for (const auto& [key, value] : fields) {
    if (key == "select") select = value;
    else if (key == "style") style = value;
    else if (key == "color") color = value;
    else if (key == "hide") hide = value == "true", hasHide = true;
    else throw io::InputError(where, "unknown field '" + key + "' (a layer has select, style, color, hide)");
  }
  if (select.empty()) throw io::InputError(where, "a layer needs \"select\"");
  if (hide && !style.empty()) throw io::InputError(where, "a layer is either hidden or has a style");
  if (!hide && style.empty())
    throw io::InputError(where, hasHide ? "a shown layer needs \"style\"" : "a layer needs \"style\" (or \"hide\": true)");
  return select + "=" + (hide ? "hidden" : style) + (color.empty() ? "" : "," + color);
}

std::vector<Layer> AllLayers(const SceneLayers& scene) {
  std::vector<Layer> all = {{"all", scene.style, std::nullopt}};
  if (!scene.showSolvent) all.push_back({"water", std::nullopt, std::nullopt});
  all.insert(all.end(), scene.layers.begin(), scene.layers.end());
  return all;
}

bool NeedsBonds(const SceneLayers& scene) {
  const std::vector<Layer> all = AllLayers(scene);
  return std::any_of(all.begin(), all.end(), [](const Layer& l) {
    return l.style && (*l.style == raster::Style::kBalls || *l.style == raster::Style::kLicorice ||
                       *l.style == raster::Style::kEllipsoids);
  });
}

ResolvedLooks ResolveLooks(const io::Molecule& mol, const SceneLayers& scene) {
  const std::vector<Layer> layers = AllLayers(scene);
  const size_t firstUserLayer = layers.size() - scene.layers.size();
  const size_t n = mol.atomCount();
  constexpr uint32_t kNoLayer = ~0u;
  std::vector<uint32_t> layerOf(n, kNoLayer);
  ResolvedLooks out;
  for (size_t l = 0; l < layers.size(); ++l) {
    const std::vector<uint8_t> selected = io::Evaluate(io::ParseSelection(layers[l].selection), mol);
    bool any = false;
    for (size_t i = 0; i < n; ++i)
      if (selected[i]) layerOf[i] = uint32_t(l), any = true;
    if (!any && l >= firstUserLayer) out.emptyLayers.push_back(layers[l].selection);
  }
  out.looks.color = AtomColors(mol, scene.colors);
  out.looks.style.assign(n, raster::kHidden);
  for (size_t i = 0; i < n; ++i)
    if (layerOf[i] != kNoLayer && layers[layerOf[i]].style) out.looks.style[i] = uint8_t(*layers[layerOf[i]].style);
  for (size_t l = 0; l < layers.size(); ++l) {
    if (!layers[l].color) continue;
    std::vector<uint8_t> mine(n, 0);
    for (size_t i = 0; i < n; ++i) mine[i] = layerOf[i] == l;
    ApplyColorRule(mol, *layers[l].color, mine, out.looks.color);
  }
  return out;
}

}  // namespace softmol::scene

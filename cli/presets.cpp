#include "cli/presets.h"

#include <algorithm>

namespace softmol::cli {
namespace {

// The light rigs, after ChimeraX's `lighting` presets. Intensities add up to a little over 1 on
// a surface facing the key light, so that AO's visibility (below 1 almost everywhere on a
// molecule's surface) leaves open surfaces at their colour. `default` is ShadingOptions' own
// defaults (effects/shading.h), listed here so --list-presets shows them.
const std::vector<OptionBundle>& LightingTable() {
  static const std::vector<OptionBundle> table = {
      {"default", "key light with highlights, a weak fill from the lower right, some ambient",
       {{"ambient", "0.35"}, {"key-light", "0.65"}, {"fill-light", "0.2"}, {"specular", "0.3"}, {"shininess", "32"}}},
      {"soft", "mostly ambient light, so the ambient occlusion carries the shape (QuteMol, ChimeraX soft)",
       {{"ambient", "0.9"}, {"key-light", "0.3"}, {"fill-light", "0"}, {"specular", "0.12"}, {"shininess", "16"}}},
      {"flat", "ambient light only: unlit colours (with AO, if on), for illustrations",
       {{"ambient", "1"}, {"key-light", "0"}, {"fill-light", "0"}, {"specular", "0"}}},
      {"full", "a strong key light casting soft shadows, plus ambient (ChimeraX full)",
       {{"ambient", "0.45"}, {"key-light", "0.75"}, {"fill-light", "0"}, {"specular", "0.3"}, {"shininess", "32"},
        {"shadows", "true"}}},
  };
  return table;
}

// The looks. Each names only what it promises; everything else stays at its default (the
// automatic AO choice among them) or at what the user gives.
const std::vector<OptionBundle>& PresetTable() {
  static const std::vector<OptionBundle> table = {
      {"plain", "direct light only: no AO, no shadows, no lines (the look of older softmol)",
       {{"ao", "none"}, {"lighting", "default"}}},
      {"qutemol", "Tarini et al.'s figures: strong baked AO as the light, depth-aware contours, halos",
       {{"ao", "baked"}, {"ao-strength", "1"}, {"lighting", "soft"}, {"contours", "0.3"},
        {"contour-depth-aware", "true"}, {"halos", "true"}}},
      {"illustrative", "flat colours by chain, thick depth-aware outlines and AO (Goodsell, Mol* illustrative)",
       {{"color", "chain"}, {"lighting", "flat"}, {"ao-strength", "0.8"}, {"contours", "0.8"},
        {"contour-depth-aware", "true"}}},
      {"shadows", "Sigg et al.'s figures: Phong light, PCF soft shadows, Sobel outlines",
       {{"ao", "none"}, {"lighting", "full"}, {"outlines", "true"}}},
      {"dynamic", "for trajectories: cone-traced AO per frame, depth cue, halos around ligands (Hermosilla et al.)",
       {{"ao", "cone"}, {"lighting", "soft"}, {"depth-cue", "0.2"}, {"highlight", "ligand"}}},
      {"publication", "the best still: baked AO, soft light, contours, 3×3 supersampling, transparent background",
       {{"ao", "baked"}, {"lighting", "soft"}, {"contours", "0.25"}, {"contour-depth-aware", "true"},
        {"ssaa", "3"}, {"transparent", "true"}}},
  };
  return table;
}

}  // namespace

std::span<const OptionBundle> LookPresets() { return PresetTable(); }
std::span<const OptionBundle> LightingPresets() { return LightingTable(); }

const OptionBundle* FindBundle(std::span<const OptionBundle> bundles, const std::string& name) {
  const auto it = std::find_if(bundles.begin(), bundles.end(), [&](const OptionBundle& b) { return name == b.name; });
  return it == bundles.end() ? nullptr : &*it;
}

std::vector<std::string> BundleNames(std::span<const OptionBundle> bundles) {
  std::vector<std::string> names;
  for (const OptionBundle& b : bundles) names.emplace_back(b.name);
  return names;
}

std::string FormatBundle(const OptionBundle& bundle) {
  std::string s;
  for (const auto& [name, value] : bundle.values) {
    s += (s.empty() ? "--" : " --") + name;
    if (value != "true") s += " " + value;
  }
  return s;
}

std::string PresetListing() {
  std::string s = "Presets (--preset NAME; any flag or scene key overrides the preset's value):\n";
  for (const OptionBundle& b : LookPresets())
    s += "  " + std::string(b.name) + ": " + b.summary + "\n      " + FormatBundle(b) + "\n";
  s += "Light rigs (--lighting NAME; --ambient, --key-light, --fill-light, --specular, --shininess override):\n";
  for (const OptionBundle& b : LightingPresets())
    s += "  " + std::string(b.name) + ": " + b.summary + "\n      " + FormatBundle(b) + "\n";
  return s;
}

}  // namespace softmol::cli

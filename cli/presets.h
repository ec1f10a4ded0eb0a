// cli/presets.h — named sets of `softmol render` option values: the looks (--preset) and the
// light rigs (--lighting). A bundle is plain data, option names and values exactly as they are
// typed on the command line, applied through the options' own parsers for every option that
// neither a flag nor the scene file gave (cli/command_params.h ParamInputs::AddBundle): flags
// and scene keys always win, and a preset's "lighting" is applied like any other value.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace softmol::cli {

struct OptionBundle {
  const char* name;
  const char* summary;  // one line for --list-presets
  std::vector<std::pair<std::string, std::string>> values;  // option (no dashes), value ("true" for a switch)
};

// --preset: plain, qutemol, illustrative, shadows, dynamic, publication.
std::span<const OptionBundle> LookPresets();
// --lighting: default, soft, flat, full.
std::span<const OptionBundle> LightingPresets();

// The bundle called `name`, or nullptr.
const OptionBundle* FindBundle(std::span<const OptionBundle> bundles, const std::string& name);
// The names, for the choice lists: {"plain", "qutemol", ...}.
std::vector<std::string> BundleNames(std::span<const OptionBundle> bundles);

// "--ao baked --lighting soft --contours 0.3 --halos": the values as command-line flags.
std::string FormatBundle(const OptionBundle& bundle);

// What `softmol render --list-presets` prints: every preset and light rig with its values.
std::string PresetListing();

}  // namespace softmol::cli

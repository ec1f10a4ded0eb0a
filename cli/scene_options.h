// cli/scene_options.h — `softmol render --scene scene.json`: applies a scene file's settings to
// the render command's options as if they had been typed, except for options the command line
// already gave (flags override the scene). Each key is checked against the options (unknown
// keys are errors) and each value by the option's own validator, so a scene accepts exactly
// what the command line accepts.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace softmol::cli {

// Throws io::InputError naming the scene file and the key. Paths under the keys "molecule" and
// "trajectory" are relative to the scene file's folder (a scene travels with its data).
void ApplySceneFile(CLI::App& render, const std::string& path);

}  // namespace softmol::cli

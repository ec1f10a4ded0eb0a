// cli/commands.h — the subcommands of `softmol`: each declares its options on a CLI11 app
// (Add*Command) and runs from the parsed values (Run*). Errors are thrown as io::InputError
// naming the file or option; main.cpp reports them.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/bake_options.h"

namespace softmol::cli {

struct InfoArgs {
  std::string molecule;
  std::string assembly;
  std::string trajectory;
  std::string select;  // a selection to count (io/selection.h)
  bool json = false;
  int threads = 0;
};
void AddInfoCommand(CLI::App& app, InfoArgs& args);
int RunInfo(const InfoArgs& args);

struct RenderArgs {
  std::string molecule;     // the argument, or the scene's "molecule"
  std::string scene;        // --scene scene.json (cli/scene_options.h); flags override it
  std::string output = "softmol.png";
  std::string size = "1024x768";
  std::string style = "spacefill";
  std::string assembly;
  std::string camera;       // EX,EY,EZ,TX,TY,TZ,UX,UY,UZ
  std::string rotate;       // X,Y,Z degrees
  std::string background = "ffffff";
  std::string aov;          // depth,normal,id
  std::string profile;      // Chrome trace-event JSON
  std::string ao = "none";       // none | baked | cone | reference
  BakeFlags bake;                 // --ao baked: --ao-directions, --ao-patch, ... (cli/bake_options.h)
  int cones = 9;                  // --ao cone: 3, 5 or 9
  int aoRays = 256;               // --ao reference: rays per pixel
  int aoGrid = 128;               // --ao cone: finest occupancy grid resolution
  std::string trajectory;         // render its frames instead of the topology's coordinates
  std::string frames;             // A:B[:STEP], 0-based, inclusive; default all
  std::string highlight;          // selection to surround with a halo (Hermosilla §6.1)
  std::string highlightColor = "ffcc00";  // RRGGBB sRGB
  double highlightStrength = 0.8;      // peak halo opacity, [0, 1]
  double highlightTrail = 0.0;         // temporal halos: trail duration, ps of simulation time
  // Edge cueing and shadows (Tarini §5, Sigg §4).
  double contours = 0.0;          // line width ξ, Å; 0 = off (--contours alone: 0.3)
  bool contourDepthAware = false;
  std::string contourColor = "000000";
  double nearClip = 0.0;          // Å from the eye; 0 = off
  bool shadows = false;
  int shadowMap = 2048;
  int pcfSamples = 64;
  int pcfPretest = 8;
  double shadowSoftness = 0.6;    // Å: PCF filter radius
  bool outlines = false;
  std::string outlineColor = "000000";
  bool halos = false;             // Tarini depth halos
  double haloSize = 1.0;          // Å beyond each atom
  double haloStrength = 0.7;
  double haloMaxGap = 4.0;        // Å of depth gap for the full halo
  std::string haloColor = "000000";
  double depthCue = 0.0;          // strength; 0 = off (--depth-cue alone: 0.5)
  std::string fogColor;           // default: the background
  std::string backend = "cpu";  // cpu | gl (the OpenGL mirror; builds with SOFTMOL_BUILD_GL)
  double fov = 30.0;
  double ortho = 0.0;
  double zoom = 1.0;
  double nearPlane = 0.0, farPlane = 0.0;
  int ssaa = 1;
  int threads = 0;
  int repeat = 1;
  int tileSize = 32;
  bool transparent = false;
  bool quiet = false;
};
// Returns the subcommand, for ApplySceneFile after parsing.
CLI::App* AddRenderCommand(CLI::App& app, RenderArgs& args);
int RunRender(const RenderArgs& args);

struct BakeArgs {
  std::string molecule;
  std::string output;               // atlas .exr (one channel "AO")
  std::string style = "spacefill";  // spacefill | balls | licorice
  std::string assembly;
  BakeFlags bake;                   // --ao-* (cli/bake_options.h)
  int threads = 0;
  bool quiet = false;
};
void AddBakeCommand(CLI::App& app, BakeArgs& args);
int RunBake(const BakeArgs& args);

}  // namespace softmol::cli

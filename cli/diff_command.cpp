// cli/diff_command.cpp — `softmol diff EXPECTED ACTUAL`: golden-image tests in any project's
// CI. Compares decoded pixels (io/image_diff.h), not file bytes: a PNG written by another zlib
// holds the same pixels in other bytes. Exit codes as cmp's: 0 same, 1 different, 2 cannot
// compare (an unreadable file, other sizes, no common channel, a bad option).
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "io/error.h"
#include "io/image_diff.h"
#include "io/image_io.h"

namespace softmol::cli {
namespace {

constexpr const char* kDiffHelp =
    "Compares decoded pixels: PNG (8-bit, channels R,G,B[,A] or Y[,A]) with PNG, or EXR (float "
    "channels R,G,B,A,Z,N.x,N.y,N.z,AO and uint32 id) with EXR. By default every channel both "
    "images hold is compared, and a channel only one holds (an RGBA PNG against an RGB one) "
    "makes them different: pass --channels R,G,B to compare the colour alone.\n"
    "A pixel differs when any compared channel differs by more than --max-abs: 8-bit levels "
    "for PNG, the channel's own units for float (Z in Å; inf against a finite value is always "
    "over); ids compare exactly. Same: at most --max-fraction of the pixels differ, and no "
    "channel is missing. The defaults (0, 0) ask for identical pixels.\n"
    "One line on stdout: pixels compared, pixels differing (count and fraction), the largest "
    "difference per channel (for ids: how many pixels differ), PSNR in dB over all non-id "
    "channels, each difference divided by its channel's peak: 255 for 8-bit, max(1, largest "
    "finite |value| of the expected channel) for float; inf when equal, -inf when a value is "
    "infinite in one image only (Z where background became geometry).\n"
    "-o diff.png: the expected image in dim grey, differing pixels from red (small) to yellow "
    "(the largest difference, each over its channel's peak), pixels different within --max-abs in blue.\n"
    "Exit codes: 0 same, 1 different, 2 cannot compare (unreadable file, other sizes, no "
    "common channel, a bad option).";

// "R,G,B" → {"R", "G", "B"}: names without blanks, none empty, none twice.
std::vector<std::string> ParseChannelList(std::string_view text, const io::SourceLocation& where) {
  std::vector<std::string> names;
  for (size_t start = 0; start <= text.size();) {
    size_t comma = text.find(',', start);
    if (comma == std::string_view::npos) comma = text.size();
    const std::string name(io::TrimBlanks(text.substr(start, comma - start)));
    if (name.empty()) throw io::InputError(where, "an empty channel name in " + io::Quoted(text) + " (e.g. R,G,B)");
    for (const std::string& n : names)
      if (n == name) throw io::InputError(where, "channel " + io::Quoted(name) + " given twice");
    names.push_back(name);
    start = comma + 1;
  }
  return names;
}

io::Param<DiffArgs> ChannelsParam() {
  io::Param<DiffArgs> p = io::Declare<DiffArgs>("channels", "NAME,NAME,...",
                                                "Channels to compare, each in both images (default: every common one)",
                                                "diff");
  p.set = [](DiffArgs& a, std::string_view text, const io::SourceLocation& where) {
    a.diff.channels = ParseChannelList(text, where);
  };
  p.get = [](const DiffArgs& a) {
    std::string s;
    for (const std::string& n : a.diff.channels) s += (s.empty() ? "" : ",") + n;
    return s;
  };
  return p;
}

void CheckPngOutput(std::string_view text, const io::SourceLocation& where) {
  std::string ext = std::filesystem::path(std::string(text)).extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != ".png") throw io::InputError(where, "the diff picture is written as .png, got " + io::Quoted(text));
}

// A typo must not overwrite a golden with its own diff picture.
void CheckNotAnInput(const DiffArgs& a) {
  namespace fs = std::filesystem;
  std::error_code outError;
  const fs::path out = fs::weakly_canonical(a.output, outError);
  for (const std::string& in : {a.expected, a.actual}) {
    std::error_code inError;
    const fs::path input = fs::weakly_canonical(in, inError);
    if (!outError && !inError && out == input)
      throw io::InputError({"-o"}, "'" + a.output + "' is one of the images compared; write the diff elsewhere");
  }
}

}  // namespace

io::ParamTable<DiffArgs> DiffParams() {
  using io::RealParam, io::TextParam;
  io::ParamTable<DiffArgs> t = {
      RealParam<DiffArgs>("max-abs", [](auto& a) -> auto& { return a.diff.maxAbs; }, {0.0, 1e30}, "",
                          "Largest difference per channel still counted as equal: 8-bit levels (PNG), channel units (EXR)", "diff"),
      RealParam<DiffArgs>("max-fraction", [](auto& a) -> auto& { return a.diff.maxFraction; }, {0.0, 1.0}, "",
                          "Largest fraction of differing pixels that still counts as the same", "diff"),
      ChannelsParam(),
      TextParam<DiffArgs>("output", [](auto& a) -> auto& { return a.output; }, "FILE.png",
                          "Write a picture of where the images differ", "diff", CheckPngOutput),
  };
  t.back().shortName = 'o';
  return t;
}

DiffCommand::DiffCommand(CLI::App& app) : params_(DiffParams()) {
  command_ = app.add_subcommand("diff", "Compare two images' pixels: exit 0 same, 1 different, 2 cannot compare");
  command_->add_option("EXPECTED", expected_, "The reference image (a golden), .png or .exr")->required();
  command_->add_option("ACTUAL", actual_, "The image to check, of the same kind and size")->required();
  command_->footer(kDiffHelp);
  params_.AddTo(*command_);
}

DiffArgs DiffCommand::Args() {
  DiffArgs a;
  params_.inputs().CollectFlags();
  a.expected = expected_;
  a.actual = actual_;
  params_.Apply(a);
  return a;
}

int RunDiff(const DiffArgs& a) {
  if (!a.output.empty()) CheckNotAnInput(a);
  const io::DiffImage expected = io::ReadDiffImage(a.expected);
  const io::DiffImage actual = io::ReadDiffImage(a.actual);
  const io::DiffResult r = io::CompareImages(expected, actual, a.diff, a.expected, a.actual);
  if (!a.output.empty()) io::WritePng(a.output, r.width, r.height, 3, io::DiffPicture(expected, r));
  std::printf("%s\n", io::DiffSummary(r).c_str());
  return r.same ? io::kExitOk : io::kExitDifferent;
}

}  // namespace softmol::cli

// cli/main.cpp — the `softmol` command. The only place that catches errors and exits:
// bad input (io::InputError) prints one line naming the file/line/option and exits 2;
// commands write outputs through temp-then-rename, so a failure leaves nothing half-written.
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "io/error.h"

int main(int argc, char** argv) {
  CLI::App app{"softmol — renders molecules on the CPU (quadric impostors, AO, edge cueing)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "softmol 0.1.0");
  softmol::cli::InfoArgs info;
  softmol::cli::AddInfoCommand(app, info);
  softmol::cli::RenderCommand render(app);
  softmol::cli::BakeCommand bake(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);  // CLI11 names the option; exit code 0 only for --help/--version
  }
  try {
    if (app.got_subcommand("info")) return softmol::cli::RunInfo(info);
    if (app.got_subcommand("render")) return softmol::cli::RunRender(render.Args());
    if (app.got_subcommand("bake")) return softmol::cli::RunBake(bake.Args());
    return 1;
  } catch (const softmol::io::InputError& e) {
    std::fprintf(stderr, "softmol: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "softmol: out of memory\n");
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softmol: error: %s\n", e.what());
    return 1;
  }
}

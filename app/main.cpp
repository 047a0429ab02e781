// fibrenet: design platform for soft fibre networks. See README.md for the commands.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "engine/core/error.h"
#include "engine/core/float_mode.h"

int main(int argc, char** argv) {
  fibrenet::FlushDenormalsToZero();  // engine/core/float_mode.h: why
  CLI::App app{"fibrenet: DEM design platform for soft fibre networks", "fibrenet"};
  app.set_version_flag("--version", std::string(FIBRENET_VERSION) + " (" FIBRENET_GIT_COMMIT ", " FIBRENET_SIMD_LEVEL ")");
  app.require_subcommand(1);
  fibrenet::cli::Context context;
  fibrenet::cli::AddValidateCommand(app, context);
  fibrenet::cli::AddBenchCommand(app, context);
  fibrenet::cli::AddRunCommand(app, context);
  fibrenet::cli::AddCampaignCommand(app, context);
  fibrenet::cli::AddDbCommand(app, context);
  fibrenet::cli::AddReportCommand(app, context);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;  // bad command line is bad input
  } catch (const fibrenet::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const fibrenet::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return context.exit_code;
}

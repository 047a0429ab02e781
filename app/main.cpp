// fibrenet: design platform for soft fibre networks. See README.md for the commands.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "app/commands.h"
#include "engine/core/error.h"

// Flush denormal results to zero and treat denormal inputs as zero. Quantities that decay
// geometrically in a quasi-static test (damped relative motion) reach the denormal range,
// where each operation takes a slow microcode path: the ZD compression of the generic tissue
// ran at half the bench's rate. Set before any thread starts; threads inherit it.
namespace {
void FlushDenormalsToZero() {
#if defined(__SSE2__)
  constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit DAZ
  _mm_setcsr(_mm_getcsr() | _MM_FLUSH_ZERO_ON | kDenormalsAreZero);
#endif
}
}  // namespace

int main(int argc, char** argv) {
  FlushDenormalsToZero();
  CLI::App app{"fibrenet: DEM design platform for soft fibre networks", "fibrenet"};
  app.set_version_flag("--version", std::string(FIBRENET_VERSION) + " (" FIBRENET_GIT_COMMIT ")");
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

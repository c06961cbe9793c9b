#include "cli/commands.hpp"

namespace rupture::cli {
void add_run_commands(CLI::App&, int&) {}
}  // namespace rupture::cli

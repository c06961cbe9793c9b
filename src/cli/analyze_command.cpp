#include "cli/commands.hpp"

namespace rupture::cli {
void add_analyze_command(CLI::App&, int&) {}
}  // namespace rupture::cli

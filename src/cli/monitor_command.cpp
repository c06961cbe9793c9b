#include "cli/commands.hpp"

namespace rupture::cli {
void add_monitor_command(CLI::App&, int&) {}
}  // namespace rupture::cli

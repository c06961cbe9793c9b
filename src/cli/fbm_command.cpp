#include "cli/commands.hpp"

namespace rupture::cli {
void add_fbm_command(CLI::App&, int&) {}
}  // namespace rupture::cli

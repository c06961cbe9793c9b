#include "cli/commands.hpp"

namespace rupture::cli {
void add_sample_command(CLI::App&, int&) {}
}  // namespace rupture::cli

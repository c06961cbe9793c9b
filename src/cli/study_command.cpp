#include "cli/commands.hpp"

namespace rupture::cli {
void add_study_command(CLI::App&, int&) {}
}  // namespace rupture::cli

#include "cli/commands.hpp"

namespace rupture::cli {
void add_bench_command(CLI::App&, int&) {}
}  // namespace rupture::cli

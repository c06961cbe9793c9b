// cli/scan_command: `rupture scan` (placeholder: the command is being written and is not registered yet).
#include "cli/commands.hpp"

namespace rupture::cli {

void add_scan_command(CLI::App& /*app*/, int& /*exit_code*/) {}

}  // namespace rupture::cli

// cli/report_command: `rupture report` (placeholder: the command is being written and is not registered yet).
#include "cli/commands.hpp"

namespace rupture::cli {

void add_report_command(CLI::App& /*app*/, int& /*exit_code*/) {}

}  // namespace rupture::cli

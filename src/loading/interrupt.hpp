// loading/interrupt: SIGINT and SIGTERM for long runs. The handlers only record which signal came
// (a sig_atomic_t); a running simulation polls it once per step, writes a checkpoint and returns
// with status "interrupted". A second signal of the same kind ends the process at once (the
// handler is reset to the default after the first). Not: what a command does afterwards
// (cli/run_command exits with interrupt_exit_code()).
#pragma once

namespace rupture::loading {

// Installs the handlers for SIGINT and SIGTERM (for commands that run simulations).
void install_interrupt_handlers();
// The signal received since the last clear_interrupt(), 0 if none.
int pending_interrupt();
void clear_interrupt();
// Exit status of a run stopped by `signal`: 128 + signal, as shells report a killed command
// (130 for SIGINT, 143 for SIGTERM).
constexpr int interrupt_exit_code(int signal) { return 128 + signal; }

}  // namespace rupture::loading

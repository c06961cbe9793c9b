#include "loading/interrupt.hpp"

#include <csignal>

namespace rupture::loading {

namespace {

volatile std::sig_atomic_t received = 0;

void record_signal(int signal) { received = signal; }

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second Ctrl-C is not caught: it ends the process
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int pending_interrupt() { return received; }

void clear_interrupt() { received = 0; }

}  // namespace rupture::loading

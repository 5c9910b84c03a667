#pragma once
// SIGINT and SIGTERM for the `vtrack` command line.
//
// The first signal sets a flag; the library's long loops poll it (core::poll_interrupt, once per
// frame, GLMB hypothesis or ranked solution), so the job stops at the next poll by throwing
// Interrupted, and the writers remove their temporary files as the exception unwinds; main()
// then prints "vtrack: interrupted" and exits with 128 + the signal number (130, 143), as a
// shell does for a process killed by it. A second signal does not wait for a poll: the handler
// removes every registered temporary file (apps::remove_temporary_files, async-signal-safe) and
// exits at once with the same status.
#include <csignal>
#include <stdexcept>

#include <unistd.h>

#include "vtrack/apps/temporary_files.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::cli {

// The job was stopped by a signal (exit status 128 + signal).
struct Interrupted : std::runtime_error {
  explicit Interrupted(int signal_number)
      : std::runtime_error("interrupted"), signal(signal_number) {}
  int signal;
};

inline volatile std::sig_atomic_t pending_signal = 0;

extern "C" inline void on_signal(int signal_number) {
  if (pending_signal != 0) {
    apps::remove_temporary_files();
    constexpr char message[] = "\nvtrack: interrupted\n";
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(128 + signal_number);
  }
  pending_signal = signal_number;
}

// Throws Interrupted once a signal has arrived (the check main() installs for the library).
inline void check_signals() {
  if (pending_signal != 0) throw Interrupted(pending_signal);
}

inline void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace vtrack::cli

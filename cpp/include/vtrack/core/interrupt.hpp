#pragma once
// Cooperative interruption of long computations (Ctrl-C in Python, SIGINT/SIGTERM in the CLI).
//
// The library never installs signal handlers or touches Python: a caller that wants its long
// calls to be interruptible installs a check for the current thread with InterruptScope, and the
// library's long loops (frames of a video, frames of a detection file, hypotheses of a GLMB step,
// Murty's ranked solutions, Gibbs sweeps, ...) call poll_interrupt() between units of work. The
// check throws to stop the work; the exception unwinds the loop like any other error, so RAII
// removes temporary files and nothing half-written is left behind.
//
//   core::InterruptScope scope([] { if (g_signal) throw Interrupted(); });
//   run_long_job();   // throws Interrupted soon after the signal arrives
#include <functional>

namespace vtrack::core {

using InterruptCheck = std::function<void()>;

// Installs `check` as the current thread's interrupt check for the scope's lifetime (scopes
// nest: the previous check is restored on destruction). An empty function keeps the outer one.
class InterruptScope {
 public:
  explicit InterruptScope(InterruptCheck check);
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  InterruptCheck check_;
  const InterruptCheck* previous_;
};

// Runs the current thread's check (which may throw); nothing when none is installed. Cheap
// enough to call once per frame, hypothesis or ranked solution (never per pixel or particle);
// a check that is expensive (Python's, which takes the GIL) rate-limits itself.
void poll_interrupt();

}  // namespace vtrack::core

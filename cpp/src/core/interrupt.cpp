#include "vtrack/core/interrupt.hpp"

#include <utility>

namespace vtrack::core {
namespace {

thread_local const InterruptCheck* current_check = nullptr;

}  // namespace

InterruptScope::InterruptScope(InterruptCheck check)
    : check_(std::move(check)), previous_(current_check) {
  current_check = check_ ? &check_ : previous_;
}

InterruptScope::~InterruptScope() { current_check = previous_; }

void poll_interrupt() {
  if (current_check) (*current_check)();
}

}  // namespace vtrack::core

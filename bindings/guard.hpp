#pragma once
// Thread safety of the bound objects. Methods that release the GIL (step, apply, detect, ...)
// would otherwise let two Python threads run one C++ object at once and corrupt it (a crash or
// wrong tracks). Every method of a stateful class holds an ObjectGuard on its object for the
// whole call: a second thread calling any guarded method of the same object waits, without the
// GIL, until the first returns, so calls on one object are serialised and calls on different
// objects still run in parallel. A thread that calls back into an object it is already using
// (from a progress callback, say) gets a RuntimeError instead of a deadlock.
#include <memory>
#include <utility>

#include "common.hpp"

namespace vtrack::bindings {

class ObjectGuard {
 public:
  // Call with the GIL held; it is released while waiting for another thread.
  explicit ObjectGuard(const void* object);
  ~ObjectGuard();
  ObjectGuard(const ObjectGuard&) = delete;
  ObjectGuard& operator=(const ObjectGuard&) = delete;

 private:
  const void* object_;
};

// A method or accessor of `Class` made to hold the object's guard. The result is copied while
// the guard is held (a reference into the object could change under another thread's call).
template <class Class, class Result, class... Args>
auto guarded(Result (Class::*method)(Args...) const) {
  return [method](const Class& self, Args... args) -> std::decay_t<Result> {
    ObjectGuard guard(&self);
    return (self.*method)(std::forward<Args>(args)...);
  };
}
template <class Class, class Result, class... Args>
auto guarded(Result (Class::*method)(Args...)) {
  return [method](Class& self, Args... args) -> std::decay_t<Result> {
    ObjectGuard guard(&self);
    return (self.*method)(std::forward<Args>(args)...);
  };
}

// The `rng` argument: a vtrack.Rng, used and advanced in place with its guard held (so threads
// sharing one Rng take turns), or an int seed in [0, 2**64 - 1] for a fresh Rng. TypeError or
// ValueError naming `rng` for anything else.
class RngArg {
 public:
  explicit RngArg(const py::handle& rng);
  core::Rng& get() { return *rng_; }

 private:
  core::Rng storage_;
  core::Rng* rng_ = &storage_;
  std::unique_ptr<ObjectGuard> guard_;
};

}  // namespace vtrack::bindings

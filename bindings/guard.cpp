#include "guard.hpp"

#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <thread>
#include <unordered_map>

namespace vtrack::bindings {
namespace {

// The objects in use and the thread using each. One table for all objects: it is held only to
// enter or leave a call, never during one.
std::mutex table_mutex;
std::condition_variable released;
std::unordered_map<const void*, std::thread::id>& in_use() {
  static auto* table = new std::unordered_map<const void*, std::thread::id>();  // never destroyed:
  return *table;  // a daemon thread may still leave a call while the interpreter exits
}

}  // namespace

ObjectGuard::ObjectGuard(const void* object) : object_(object) {
  const auto me = std::this_thread::get_id();
  {
    std::lock_guard<std::mutex> lock(table_mutex);
    const auto found = in_use().find(object);
    if (found == in_use().end()) {
      in_use().emplace(object, me);
      return;
    }
    if (found->second == me) {
      throw std::runtime_error(
          "this vtrack object is already in use by this thread (a callback called back into "
          "the object whose call it is part of)");
    }
  }
  py::gil_scoped_release release;  // let the other thread finish (it may need the GIL)
  std::unique_lock<std::mutex> lock(table_mutex);
  released.wait(lock, [&] { return in_use().count(object) == 0; });
  in_use().emplace(object, me);
}

ObjectGuard::~ObjectGuard() {
  {
    std::lock_guard<std::mutex> lock(table_mutex);
    in_use().erase(object_);
  }
  released.notify_all();
}

RngArg::RngArg(const py::handle& rng) {
  if (py::isinstance<core::Rng>(rng)) {
    rng_ = &rng.cast<core::Rng&>();
    guard_ = std::make_unique<ObjectGuard>(rng_);
    return;
  }
  if (py::isinstance<py::int_>(rng) && !py::isinstance<py::bool_>(rng)) {
    const py::int_ seed = py::reinterpret_borrow<py::int_>(rng);
    if (seed < py::int_(0) || seed > py::int_(std::numeric_limits<std::uint64_t>::max())) {
      throw py::value_error("rng seed must be in [0, 2**64 - 1], got " +
                            py::str(seed).cast<std::string>());
    }
    storage_ = core::Rng(seed.cast<std::uint64_t>());
    return;
  }
  throw py::type_error("rng must be a vtrack.Rng or an int seed, got " + type_name(rng));
}

}  // namespace vtrack::bindings

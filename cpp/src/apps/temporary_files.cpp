#include "vtrack/apps/temporary_files.hpp"

#include <atomic>
#include <cstring>
#include <string>

#include <unistd.h>

namespace vtrack::apps {
namespace {

constexpr std::size_t kMaxPath = 4096;

// A slot is free (0), being filled (1) or holds a registered path (2). Lock-free atomics keep
// the signal handler's walk async-signal-safe.
struct Slot {
  std::atomic<int> state{0};
  char path[kMaxPath];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

Slot slots[kMaxTemporaryFiles];

std::atomic<unsigned long> partial_count{0};

}  // namespace

std::filesystem::path partial_path(const std::filesystem::path& target, bool keep_extension) {
  const std::string unique = "." + std::to_string(::getpid()) + "-" +
                             std::to_string(partial_count.fetch_add(1)) + ".partial";
  if (!keep_extension) return target.string() + unique;
  return target.parent_path() / (target.stem().string() + unique + target.extension().string());
}

TemporaryFile::TemporaryFile(const std::string& path) {
  if (path.empty() || path.size() >= kMaxPath) return;
  for (int i = 0; i < kMaxTemporaryFiles; ++i) {
    int expected = 0;
    if (!slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
    slots[i].state.store(2, std::memory_order_release);
    slot_ = i;
    return;
  }
}

void TemporaryFile::release() noexcept {
  if (slot_ >= 0) slots[slot_].state.store(0, std::memory_order_release);
  slot_ = -1;
}

int remove_temporary_files() noexcept {
  int found = 0;
  for (auto& slot : slots) {
    if (slot.state.load(std::memory_order_acquire) != 2) continue;
    ::unlink(slot.path);
    ++found;
  }
  return found;
}

}  // namespace vtrack::apps

#pragma once
// Temporary output files: "tracks.txt.partial", "out.partial.mp4", "000012.partial.png", ... that
// a writer has created and not yet renamed to their final name or removed. Writers register each
// one for as long as it exists, so that a process stopped by SIGINT or SIGTERM in the middle of
// a write can remove them from its signal handler (the CLI does): remove_temporary_files() only
// uses async-signal-safe operations. Errors and ordinary interruptions need none of this: the
// writers remove their temporary files as the exception unwinds.
#include <filesystem>
#include <string>

namespace vtrack::apps {

// The temporary name a writer of `target` uses: "tracks.txt" -> "tracks.txt.<pid>-<n>.partial";
// with `keep_extension` (a video, whose container FFmpeg picks from the extension)
// "out.avi" -> "out.<pid>-<n>.partial.avi". The process id and a per-process counter make the name
// unique per write, so two writers of the same target (a task retried by Dask while a worker
// presumed dead still runs, two threads) never write into one file that one of them renames.
std::filesystem::path partial_path(const std::filesystem::path& target, bool keep_extension = false);

// At most this many temporary files are registered at once (vtrack writes at most three at a
// time); a path beyond the table or longer than 4095 bytes is simply not registered.
constexpr int kMaxTemporaryFiles = 32;

// Registers `path` for its lifetime; release() (or destruction) deregisters it. Neither creates
// nor removes the file.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& path);
  ~TemporaryFile() { release(); }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  void release() noexcept;

 private:
  int slot_ = -1;
};

// Removes (unlinks) every registered temporary file; async-signal-safe. Returns how many
// registrations it found.
int remove_temporary_files() noexcept;

}  // namespace vtrack::apps

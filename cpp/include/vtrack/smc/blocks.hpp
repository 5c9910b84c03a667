#pragma once
// Block decomposition of a particle set: the unit of parallel work and of random streams.
//
// Particles are processed in blocks of kBlockSize consecutive indices (small enough that a
// block's states, noise and log-likelihoods stay in the L1/L2 cache between the passes over it).
// Block b always covers the same indices and draws its random numbers from its own stream
// (BlockStreams), and every reduction over particles is summed per block, then over blocks in
// block order. So the result does not depend on how many threads run the blocks: bit-identical for
// any `threads`, as the issue asks.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/lane_rng.hpp"
#include "vtrack/core/random.hpp"

namespace vtrack::smc {

inline constexpr Eigen::Index kBlockSize = 1024;

inline Eigen::Index block_count(Eigen::Index n) { return (n + kBlockSize - 1) / kBlockSize; }

struct BlockRange {
  Eigen::Index begin;
  Eigen::Index end;
  Eigen::Index size() const { return end - begin; }
};

inline BlockRange block_range(Eigen::Index block, Eigen::Index n) {
  const Eigen::Index begin = block * kBlockSize;
  return {begin, begin + kBlockSize < n ? begin + kBlockSize : n};
}

// Runs body(b) once for every block b in [0, blocks): on the calling thread when threads == 1 (or
// there is one block), otherwise on OpenCV's pool (threads == 0: its default size; T > 1: T
// stripes), the `threads` convention of the image layer. Bodies must not throw: they record
// problems for the caller to report after the loop.
template <class Body>  // Body: void(Eigen::Index block)
void for_blocks(Eigen::Index blocks, int threads, const Body& body) {
  if (threads == 1 || blocks < 2) {
    for (Eigen::Index b = 0; b < blocks; ++b) body(b);
    return;
  }
  cv::parallel_for_(
      cv::Range(0, static_cast<int>(blocks)),
      [&body](const cv::Range& range) {
        for (int b = range.start; b < range.end; ++b) body(b);
      },
      threads == 0 ? -1.0 : static_cast<double>(threads));
}

// A per-thread scratch array of at least `size` elements that keeps its memory from block to block
// and step to step (a block's temporary buffers otherwise cost an allocation each, ~3 % of a SIR
// step at N = 1e5). Tag tells apart the buffers a block uses at the same time; the contents are
// undefined on return.
enum class Scratch { Noise, Normals, Gathered, LogLikelihood };
template <typename T, Scratch Tag>
T* scratch(std::size_t size) {
  thread_local std::vector<T> buffer;
  if (buffer.size() < size) buffer.resize(size);
  return buffer.data();
}

// One vectorised generator per block. Block b's generator takes lanes from consecutive jumps of
// core::Rng(seed, first_stream) (after those of blocks 0..b-1), so what block b draws depends only
// on the seed and b. Generators are created on first use and then persist, each continuing its
// stream from step to step.
class BlockStreams {
 public:
  explicit BlockStreams(std::uint64_t seed, std::uint64_t first_stream = 1)
      : source_(seed, first_stream) {}

  // Makes sure blocks [0, blocks) have generators (call before a parallel loop).
  void reserve(Eigen::Index blocks) {
    while (static_cast<Eigen::Index>(lanes_.size()) < blocks) lanes_.emplace_back(source_);
  }
  core::LaneRng& operator[](Eigen::Index block) { return lanes_[static_cast<std::size_t>(block)]; }

 private:
  core::Rng source_;
  std::vector<core::LaneRng> lanes_;
};

}  // namespace vtrack::smc

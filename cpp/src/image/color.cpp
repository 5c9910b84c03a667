#include "vtrack/image/color.hpp"

#include <array>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::image {

void bgr_to_rgi(const cv::Mat& bgr, cv::Mat& rgi) {
  if (bgr.empty()) throw InvalidArgument("frame is empty");
  if (bgr.type() != CV_8UC3) {
    throw InvalidArgument("frame must be 8-bit with 3 channels (BGR), got depth " +
                          std::to_string(bgr.depth()) + " with " +
                          std::to_string(bgr.channels()) + " channels");
  }
  rgi.create(bgr.rows, bgr.cols, CV_32FC3);
  // Reciprocal table for the 766 possible channel sums: one multiply per component instead of a
  // division, and the black pixel handled by the table entry for 0.
  static const auto reciprocal = [] {
    std::array<float, 766> table{};
    table[0] = 0.0f;
    for (int s = 1; s < 766; ++s) table[s] = 1.0f / static_cast<float>(s);
    return table;
  }();
  constexpr float kIntensityScale = 1.0f / (3.0f * 255.0f);
  constexpr float kNeutral = 1.0f / 3.0f;
  for (int row = 0; row < bgr.rows; ++row) {
    const unsigned char* in = bgr.ptr<unsigned char>(row);
    float* out = rgi.ptr<float>(row);
    for (int col = 0; col < bgr.cols; ++col) {
      const int b = in[3 * col], g = in[3 * col + 1], r = in[3 * col + 2];
      const int sum = r + g + b;
      const float inv = reciprocal[sum];
      out[3 * col] = sum ? static_cast<float>(r) * inv : kNeutral;
      out[3 * col + 1] = sum ? static_cast<float>(g) * inv : kNeutral;
      out[3 * col + 2] = static_cast<float>(sum) * kIntensityScale;
    }
  }
}

}  // namespace vtrack::image

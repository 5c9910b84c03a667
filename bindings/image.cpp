// Bindings of vtrack::image: rgI conversion, integral images, KDE background model, morphology.
#include <string>
#include <utility>

#include <limits>

#include "args.hpp"
#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "vtrack/image/color.hpp"
#include "vtrack/image/integral_image.hpp"
#include "vtrack/image/kde_background.hpp"
#include "vtrack/image/morphology.hpp"
#include "vtrack/core/limits.hpp"

namespace vtrack::bindings {
namespace {

// A new H x W float32 array and a cv::Mat header over its pixels (filled in place by the C++ call).
std::pair<py::array_t<float>, cv::Mat> new_float_image(int rows, int cols) {
  py::array_t<float> out({rows, cols});
  cv::Mat mat(rows, cols, CV_32FC1, out.mutable_data());
  return {std::move(out), mat};
}

// A rectangle's x, y, width, height: ints within int32 (Rect's fields), named in errors.
image::Rect rect_arg(const py::handle& x, const py::handle& y, const py::handle& width,
                     const py::handle& height) {
  constexpr std::int64_t lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
  return {static_cast<int>(int_arg(x, "x", lo, hi)), static_cast<int>(int_arg(y, "y", lo, hi)),
          static_cast<int>(int_arg(width, "width", lo, hi)),
          static_cast<int>(int_arg(height, "height", lo, hi))};
}

// (n, 4) rectangles of an integer dtype, each value within int32 (checked before narrowing: a
// rectangle at x = 2^32 must not wrap into the image). TypeError for a float or other dtype.
py::array_t<std::int64_t> rects_arg(const py::handle& rects) {
  py::array a = py::array::ensure(rects);
  if (!a) throw py::type_error("rects must be an (n, 4) integer array, got " + type_name(rects));
  if (a.ndim() != 2 || a.shape(1) != 4) {
    throw py::value_error("rects must be an (n, 4) integer array of x, y, width, height");
  }
  const char kind = a.dtype().kind();
  if (a.size() > 0 && kind != 'i' && kind != 'u') {
    throw py::type_error("rects must hold integers (x, y, width, height), got dtype " +
                         py::str(a.dtype()).cast<std::string>());
  }
  if (kind == 'u' && a.itemsize() == 8) {  // uint64 above INT64_MAX would wrap in the cast below
    const auto u = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    for (py::ssize_t i = 0; i < u.size(); ++i) {
      if (u.data()[i] > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
        throw py::value_error("rects[" + std::to_string(i / 4) + "] holds " +
                              std::to_string(u.data()[i]) + ", outside int32");
      }
    }
  }
  auto r = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  for (py::ssize_t i = 0; i < r.size(); ++i) {
    const std::int64_t v = r.data()[i];
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
      throw py::value_error("rects[" + std::to_string(i / 4) + "] holds " + std::to_string(v) +
                            ", outside int32");
    }
  }
  return r;
}

void bind_kde_background(py::module_& m) {
  using image::KdeBackground;
  using image::KdeBackgroundParams;
  py::class_<KdeBackground> cls(m, "KdeBackground", R"doc(
KDE background model on rgI chromaticity (mb-tbd paper, section 3.1, eqs. 6-10).

apply(frame) turns each H x W x 3 uint8 BGR frame into y, an H x W float32 image in [0, 1]
(near 1 = background): the mean over the sample stack of the product of three Gaussian kernels
(eq. 10, unnormalised). Keyword parameters (KdeBackground.default_params(); the names config
files and --set take): the stack holds up to `n_samples` (N0) frames taken every `period` (K0)
frames: frames 0, K0, ..., and from N0*K0 on the oldest is replaced every K0 frames; before it is
full, y averages over the samples taken so far (frame 0 gives y = 1). `bandwidth` is
(sigma_r, sigma_g, sigma_I), with I = (R+G+B)/765. `closing` is the side of the square used to
morphologically close y (0 = off). `threads`: 0 = OpenCV's default, 1 = single thread; the
result does not depend on it. `update_threshold` > 0 turns on the selective update (beyond the
paper): pixels of a sample frame with y below it repeat the newest sample instead, so people
leave no ghosts (0 = the paper's stack); a pixel is skipped on at most `update_max_skips`
consecutive sample frames; with `update_static`, while the stack fills, a foreground pixel
unchanged since the previous sample frame is taken (start-up ghosts of people in the first
sample; on in track_video's sir pipeline). `illumination_compensation` scales the frame's intensity by the ratio
of mean intensities before comparing it with each sample (a global light change cancels; off =
eq. 10 as printed). Not safe to share one model between threads.
)doc");
  cls.def(py::init([](const py::kwargs& kwargs) {
        return KdeBackground(params_from_kwargs<KdeBackgroundParams>(kwargs, "background"));
      }))
      .def(
          "apply",
          [](KdeBackground& model, const py::handle& frame) {
            py::array keep;
            const cv::Mat bgr = bgr_frame(frame, "frame", keep);
            auto [out, y] = new_float_image(bgr.rows, bgr.cols);
            ObjectGuard guard(&model);
            {
              py::gil_scoped_release release;
              model.apply(bgr, y);
            }
            return out;
          },
          py::arg("frame"),
          "Consume the next H x W x 3 uint8 BGR frame; return y (H x W float32, 1 = background).")
      .def("set_closing", guarded(&KdeBackground::set_closing), py::arg("size"),
           "Change the closing's side (0, 1 or odd) from the next frame on; track_video's mb "
           "pipeline sets it to MultiBernoulliTracker.closing_pixels after every frame.")
      .def("freeze", guarded(&KdeBackground::freeze), "Stop storing samples (the model stays fixed).")
      .def("resume", guarded(&KdeBackground::resume), "Store samples again on the K0 schedule.")
      .def("reset", guarded(&KdeBackground::reset),
           "Forget all samples and the frame size; the next frame is frame 0.")
      .def_property_readonly("learning", guarded(&KdeBackground::learning))
      .def_property_readonly("frame_index", guarded(&KdeBackground::frame_index),
                             "Frames consumed since construction or reset().")
      .def_property_readonly("sample_frames", guarded(&KdeBackground::sample_frames),
                             "Frame indices of the samples in the stack, oldest first.")
      .def("__repr__", [](const KdeBackground& b) {
        return "KdeBackground(" + keyword_text(params_dict(b.params())) + ")";
      });
  def_params<KdeBackgroundParams>(cls, [](const KdeBackground& b) { return b.params(); });

  m.def(
      "foreground_mask",
      [](const py::handle& y, const py::handle& threshold_arg) {
        const double threshold = real_arg(threshold_arg, "threshold");
        py::array keep;
        const cv::Mat image = gray_image(y, "y", keep);
        if (image.type() != CV_32FC1) {
          throw py::type_error("y must have dtype float32 (as KdeBackground.apply returns)");
        }
        py::array_t<std::uint8_t> out({image.rows, image.cols});
        cv::Mat mask(image.rows, image.cols, CV_8UC1, out.mutable_data());
        image::foreground_mask(image, threshold, mask);
        return out;
      },
      py::arg("y"), py::kw_only(), py::arg("threshold"),
      "Foreground mask of a background image y: uint8 H x W, 255 where y < threshold, else 0.");

  m.def(
      "close_square",
      [](const py::handle& y, const py::handle& size_arg, const py::handle& threads_arg) {
        const int size = static_cast<int>(int_arg(size_arg, "size", 0, core::kMaxImageSide));
        const int threads = static_cast<int>(int_arg(threads_arg, "threads", 0, 1024));
        py::array keep;
        const cv::Mat image = gray_image(y, "image", keep);
        if (image.type() != CV_32FC1) throw py::type_error("image must have dtype float32");
        auto [out, closed] = new_float_image(image.rows, image.cols);
        {
          py::gil_scoped_release release;
          image::close_square(image, closed, size, threads);
        }
        return out;
      },
      py::arg("image"), py::arg("size"), py::kw_only(), py::arg("threads") = 0,
      "Morphological closing (max then min filter) of an H x W float32 image with a size x size "
      "square; pixels outside the image are ignored (equals cv2.morphologyEx(MORPH_CLOSE)).");
}

}  // namespace

void bind_image(py::module_& m) {
  bind_kde_background(m);
  m.def(
      "bgr_to_rgi",
      [](const py::handle& frame) {
        py::array keep;
        const cv::Mat bgr = bgr_frame(frame, "frame", keep);
        py::array_t<float> out({bgr.rows, bgr.cols, 3});
        cv::Mat rgi(bgr.rows, bgr.cols, CV_32FC3, out.mutable_data());
        {
          py::gil_scoped_release release;
          image::bgr_to_rgi(bgr, rgi);
        }
        return out;
      },
      py::arg("frame"),
      "rgI chromaticity (mb-tbd paper eqs. 6-8) of an H x W x 3 uint8 BGR frame, as H x W x 3 "
      "float32 (r, g, I), all in [0, 1]. I = (R+G+B)/765; black pixels get r = g = 1/3.");

  py::class_<image::IntegralImage>(m, "IntegralImage", R"doc(
Summed-area table of an H x W image (uint8, float32 or float64) for O(1) rectangle sums.
Rectangles are (x, y, width, height) in pixels and are clipped to the image; a rectangle that is
empty or wholly outside sums to 0 over an area of 0.
)doc")
      .def(py::init([](const py::handle& img) {
             py::array keep;
             const cv::Mat mat = gray_image(img, "image", keep);
             py::gil_scoped_release release;
             return image::IntegralImage(mat);
           }),
           py::arg("image"))
      .def_property_readonly("shape", [](const image::IntegralImage& ii) {
        return py::make_tuple(ii.rows(), ii.cols());
      })
      .def(
          "sum",
          [](const image::IntegralImage& ii, const py::handle& x, const py::handle& y,
             const py::handle& width, const py::handle& height) {
            return ii.sum(rect_arg(x, y, width, height));
          },
          py::arg("x"), py::arg("y"), py::arg("width"), py::arg("height"))
      .def(
          "area",
          [](const image::IntegralImage& ii, const py::handle& x, const py::handle& y,
             const py::handle& width, const py::handle& height) {
            return ii.area(rect_arg(x, y, width, height));
          },
          py::arg("x"), py::arg("y"), py::arg("width"), py::arg("height"))
      .def(
          "sums",
          [](const image::IntegralImage& ii, const py::handle& rects) {
            const auto r = rects_arg(rects);
            py::array_t<double> out(r.shape(0));
            const std::int64_t* p = r.data();
            double* o = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (py::ssize_t i = 0; i < r.shape(0); ++i) {
                o[i] = ii.sum({static_cast<int>(p[4 * i]), static_cast<int>(p[4 * i + 1]),
                               static_cast<int>(p[4 * i + 2]), static_cast<int>(p[4 * i + 3])});
              }
            }
            return out;
          },
          py::arg("rects"), "Sums of many rectangles given as rows (x, y, width, height).");
}

}  // namespace vtrack::bindings

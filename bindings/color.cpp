// Bindings of vtrack::image's color histograms: HSV bins, box histograms, the Bhattacharyya
// coefficient and distance, the color likelihood (part-based paper eqs. 9-11), ColorModel.
#include <string>
#include <vector>

#include <limits>

#include "args.hpp"
#include "common.hpp"
#include "vtrack/image/color_histogram.hpp"

namespace vtrack::bindings {
namespace {

using image::ColorHistogramParams;
using image::ColorModel;
using image::HistogramMethod;

ColorHistogramParams histogram_params(const py::handle& bins, bool kernel) {
  if (!py::isinstance<py::sequence>(bins) || py::isinstance<py::str>(bins) || py::len(bins) != 3) {
    throw py::value_error("bins must be a sequence of 3 ints (H, S, V), got " +
                          std::string(py::repr(bins)));
  }
  int n[3];
  const auto seq = py::reinterpret_borrow<py::sequence>(bins);
  for (int i = 0; i < 3; ++i) {
    const py::object v = seq[static_cast<std::size_t>(i)];
    n[i] = static_cast<int>(int_arg(v, "bins", std::numeric_limits<int>::min(),
                                    std::numeric_limits<int>::max()));
  }
  ColorHistogramParams p{n[0], n[1], n[2], kernel};
  image::validate(p);
  return p;
}

py::tuple bins_tuple(const ColorHistogramParams& p) {
  return py::make_tuple(p.bins_h, p.bins_s, p.bins_v);
}

// A (bins_h, bins_s, bins_v) float64 array of the m values of `hist`.
py::array_t<double> histogram_array(const ColorHistogramParams& p, const double* hist) {
  py::array_t<double> out({p.bins_h, p.bins_s, p.bins_v});
  std::copy(hist, hist + image::bin_count(p), out.mutable_data());
  return out;
}

std::vector<double> box4(const py::handle& box, const char* name) {
  const auto b = as_vector(box, name);
  if (b.size() != 4) {
    throw py::value_error(std::string(name) + " must hold 4 numbers (x, y, w, h), got " +
                          std::to_string(b.size()));
  }
  return {b.data(), b.data() + 4};
}

py::array_t<double> boxes_n4(const py::handle& boxes) {
  auto b = as_matrix(boxes, "boxes");
  if (b.shape(1) != 4) {
    throw py::value_error("boxes must have shape (N, 4) (x, y, w, h per row), got (" +
                          std::to_string(b.shape(0)) + ", " + std::to_string(b.shape(1)) + ")");
  }
  return b;
}

// A float64 array of whatever shape `obj` has (rules of as_array).
py::array_t<double> any_shape(const py::handle& obj, const char* name) {
  const py::array a = py::array::ensure(obj);
  return as_array(obj, name, a ? static_cast<int>(a.ndim()) : 1);
}

double coefficient(const py::handle& p, const py::handle& q) {
  const auto a = any_shape(p, "p");
  const auto b = any_shape(q, "q");
  if (a.size() != b.size()) {
    throw py::value_error("p and q must have the same number of bins, got " +
                          std::to_string(a.size()) + " and " + std::to_string(b.size()));
  }
  return image::bhattacharyya_coefficient(a.data(), b.data(), static_cast<std::size_t>(a.size()));
}

HistogramMethod histogram_method(const std::string& name) {
  if (name == "direct") return HistogramMethod::direct;
  if (name == "incremental") return HistogramMethod::incremental;
  if (name == "auto") return HistogramMethod::automatic;
  throw py::value_error("method must be 'auto', 'direct' or 'incremental', got '" + name + "'");
}

py::array_t<double> coefficients(const ColorModel& model, const py::handle& frame,
                                 const py::handle& boxes, const std::string& method) {
  py::array keep;
  const cv::Mat bgr = bgr_frame(frame, "frame", keep);
  const auto b = boxes_n4(boxes);
  const auto how = histogram_method(method);
  const auto n = static_cast<std::size_t>(b.shape(0));
  py::array_t<double> rho(static_cast<py::ssize_t>(n));
  double* out = rho.mutable_data();
  {
    py::gil_scoped_release release;
    image::HsvBinImage workspace(model.params());
    model.coefficients(bgr, b.data(), n, 4, out, workspace, how);
  }
  return rho;
}

void bind_color_model(py::module_& m) {
  py::class_<ColorModel>(m, "ColorModel", R"doc(
A template color histogram q and the scoring of many boxes against it (part-based paper
section 3.1, eqs. 9-11): the color observation model of the color-histogram particle filters.

ColorModel(frame, box, bins=(16, 4, 4), kernel=False) takes q from the box (x, y, w, h) of an
H x W x 3 uint8 BGR frame; ColorModel.from_histogram(hist, kernel=False) from any non-negative
(bins_h, bins_s, bins_v) array. coefficients(frame, boxes) returns the Bhattacharyya coefficient
rho (eq. 10) of each row (x, y, w, h) of an (N, 4) array, converting the frame once (the smallest
region holding every box) and counting each box's own pixels; boxes partly outside the frame are
clipped, a box with no pixel scores 0. log_likelihood(frame, boxes, sigma) is eq. 11 on those.
With kernel=True pixels are weighted by Nummiaro et al.'s Epanechnikov profile. The GIL is
released while scoring.
)doc")
      .def(py::init([](const py::handle& frame, const py::handle& box, const py::handle& bins,
                       bool kernel) {
             py::array keep;
             const cv::Mat bgr = bgr_frame(frame, "frame", keep);
             const auto b = box4(box, "box");
             const auto p = histogram_params(bins, kernel);
             return ColorModel::from_box(bgr, b[0], b[1], b[2], b[3], p);
           }),
           py::arg("frame"), py::arg("box"), py::kw_only(),
           py::arg("bins") = py::make_tuple(16, 4, 4), py::arg("kernel") = false)
      .def_static(
          "from_histogram",
          [](const py::handle& hist, bool kernel) {
            const auto h = as_array(hist, "hist", 3);
            ColorHistogramParams p{static_cast<int>(h.shape(0)), static_cast<int>(h.shape(1)),
                                    static_cast<int>(h.shape(2)), kernel};
            image::validate(p);
            return ColorModel(p, std::vector<double>(h.data(), h.data() + h.size()));
          },
          py::arg("hist"), py::kw_only(), py::arg("kernel") = false,
          "A model whose template is `hist` (a non-negative (bins_h, bins_s, bins_v) array, "
          "normalised here).")
      .def_property_readonly(
          "reference",
          [](const ColorModel& c) { return histogram_array(c.params(), c.reference().data()); },
          "The normalised template histogram q, shape (bins_h, bins_s, bins_v).")
      .def_property_readonly("bins", [](const ColorModel& c) { return bins_tuple(c.params()); })
      .def_property_readonly("kernel", [](const ColorModel& c) { return c.params().kernel; })
      .def("coefficients", &coefficients, py::arg("frame"), py::arg("boxes"), py::kw_only(),
           py::arg("method") = "auto",
           "Bhattacharyya coefficients (eq. 10) of the (N, 4) boxes against the template, (N,) "
           "float64. `method` only changes how the counts are computed: 'direct' counts each "
           "box's pixels, 'incremental' updates a neighbouring box's counts (or weights) by "
           "the pixels that differ, 'auto' is incremental.")
      .def(
          "log_likelihood",
          [](const ColorModel& model, const py::handle& frame, const py::handle& boxes,
             double sigma) {
            auto rho = coefficients(model, frame, boxes, "auto");
            py::array_t<double> out(rho.size());
            image::color_log_likelihood(rho.data(), static_cast<std::size_t>(rho.size()), sigma,
                                         out.mutable_data());
            return out;
          },
          py::arg("frame"), py::arg("boxes"), py::kw_only(),
          py::arg("sigma") = image::kDefaultColorSigma,
          "Color log-likelihoods (eq. 11) of the (N, 4) boxes, (N,) float64.")
      .def("__repr__", [](const ColorModel& c) {
        const auto& p = c.params();
        return "ColorModel(bins=(" + std::to_string(p.bins_h) + ", " + std::to_string(p.bins_s) +
               ", " + std::to_string(p.bins_v) + "), kernel=" + (p.kernel ? "True" : "False") + ")";
      });
}

}  // namespace

void bind_color(py::module_& m) {
  bind_color_model(m);
  m.def(
      "hsv_bins",
      [](const py::handle& frame, const py::handle& bins) {
        py::array keep;
        const cv::Mat bgr = bgr_frame(frame, "frame", keep);
        image::HsvBinImage image(histogram_params(bins, false));
        py::array_t<std::uint16_t> out({bgr.rows, bgr.cols});
        {
          py::gil_scoped_release release;
          image.assign(bgr);
          for (int r = 0; r < bgr.rows; ++r) {
            std::copy(image.row_ptr(r), image.row_ptr(r) + bgr.cols,
                      out.mutable_data() + static_cast<std::size_t>(r) * bgr.cols);
          }
        }
        return out;
      },
      py::arg("frame"), py::kw_only(), py::arg("bins") = py::make_tuple(16, 4, 4),
      "Histogram bin of every pixel of an H x W x 3 uint8 BGR frame, H x W uint16: "
      "u = (h * bins_s + s) * bins_v + v with h = floor(H * bins_h / 256) of OpenCV's "
      "HSV_FULL hue H in [0, 256) (22.5 degrees per bin at 16 bins), s, v likewise from S, V.");
  m.def(
      "hsv_histogram",
      [](const py::handle& frame, const py::handle& box, const py::handle& bins, bool kernel) {
        py::array keep;
        const cv::Mat bgr = bgr_frame(frame, "frame", keep);
        const auto b = box4(box, "box");
        const auto p = histogram_params(bins, kernel);
        std::vector<double> hist(static_cast<std::size_t>(image::bin_count(p)));
        double total = 0.0;
        {
          py::gil_scoped_release release;
          image::HsvBinImage image(p);
          image.assign(bgr, image::pixel_rect(b[0], b[1], b[2], b[3]));
          total = image::box_histogram(image, b[0], b[1], b[2], b[3], kernel, hist.data());
        }
        if (total > 0) {
          for (double& v : hist) v /= total;
        }
        return histogram_array(p, hist.data());
      },
      py::arg("frame"), py::arg("box"), py::kw_only(), py::arg("bins") = py::make_tuple(16, 4, 4),
      py::arg("kernel") = false,
      "Normalised HSV histogram (section 3.1) of the box (x, y, w, h) of an H x W x 3 uint8 BGR "
      "frame, shape (bins_h, bins_s, bins_v), summing to 1 (all zeros when the box has no pixel "
      "in the frame). Box pixels: columns [round(x), round(x + w)), rows [round(y), round(y + h)). "
      "kernel=True weights pixels by Nummiaro et al.'s Epanechnikov profile.");
  m.def("bhattacharyya_coefficient", &coefficient, py::arg("p"), py::arg("q"),
        "Bhattacharyya coefficient rho = sum sqrt(p_u q_u) (eq. 10) of two non-negative "
        "histograms of the same size (any shape), each divided by its sum first.");
  m.def(
      "bhattacharyya_distance",
      [](const py::handle& p, const py::handle& q) {
        return image::bhattacharyya_distance(coefficient(p, q));
      },
      py::arg("p"), py::arg("q"),
      "Bhattacharyya distance sqrt(1 - rho) (eq. 9) of two histograms.");
  m.def(
      "color_log_likelihood",
      [](const py::handle& rho, double sigma) -> py::object {
        const auto r = any_shape(rho, "rho");
        if (r.ndim() == 0) return py::float_(image::color_log_likelihood(*r.data(), sigma));
        py::array_t<double> out(std::vector<py::ssize_t>(r.shape(), r.shape() + r.ndim()));
        image::color_log_likelihood(r.data(), static_cast<std::size_t>(r.size()), sigma,
                                     out.mutable_data());
        return std::move(out);
      },
      py::arg("rho"), py::kw_only(), py::arg("sigma") = image::kDefaultColorSigma,
      "Color log-likelihood of eq. 11, -log(sqrt(2 pi) sigma) - (1 - rho) / (2 sigma^2), of a "
      "Bhattacharyya coefficient or an array of them. sigma defaults to sqrt(0.2), the text's "
      "sigma^2 = 0.2.");
}

}  // namespace vtrack::bindings

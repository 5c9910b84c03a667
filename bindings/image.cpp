// Bindings of vtrack::image: rgI conversion, integral images.
#include "common.hpp"
#include "vtrack/image/color.hpp"
#include "vtrack/image/integral_image.hpp"

namespace vtrack::bindings {

void bind_image(py::module_& m) {
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
          [](const image::IntegralImage& ii, int x, int y, int width, int height) {
            return ii.sum({x, y, width, height});
          },
          py::arg("x"), py::arg("y"), py::arg("width"), py::arg("height"))
      .def(
          "area",
          [](const image::IntegralImage& ii, int x, int y, int width, int height) {
            return ii.area({x, y, width, height});
          },
          py::arg("x"), py::arg("y"), py::arg("width"), py::arg("height"))
      .def(
          "sums",
          [](const image::IntegralImage& ii, const py::handle& rects) {
            auto r = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(rects);
            if (!r || r.ndim() != 2 || r.shape(1) != 4) {
              throw py::value_error("rects must be an (n, 4) integer array of x, y, width, height");
            }
            py::array_t<double> out(r.shape(0));
            const int* p = r.data();
            double* o = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (py::ssize_t i = 0; i < r.shape(0); ++i) {
                o[i] = ii.sum({p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]});
              }
            }
            return out;
          },
          py::arg("rects"), "Sums of many rectangles given as rows (x, y, width, height).");
}

}  // namespace vtrack::bindings

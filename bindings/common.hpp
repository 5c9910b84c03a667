#pragma once
// Conversion and validation shared by the binding files. Bindings only convert: every check here
// is about Python types and shapes; value checks live in the C++ library.
#include <functional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/random.hpp"

namespace vtrack::bindings {
namespace py = pybind11;

enum class Nan { Allowed, Rejected };

// A 1-D float64 view of `obj` (any real floating or integer array-like), without a copy when `obj`
// is already a contiguous float64 array. TypeError for other dtypes, ValueError for other shapes
// or for NaN when rejected. The returned array owns (or references) the data; keep it alive while
// using the Map.
py::array_t<double> as_vector(const py::handle& obj, const char* name, Nan nan = Nan::Rejected);

// A 2-D C-contiguous float64 array, same rules as as_vector.
py::array_t<double> as_matrix(const py::handle& obj, const char* name, Nan nan = Nan::Rejected);

// An `ndim`-D C-contiguous float64 array, same rules as as_vector.
py::array_t<double> as_array(const py::handle& obj, const char* name, int ndim,
                             Nan nan = Nan::Rejected);

inline Eigen::Map<const Eigen::VectorXd> vector_map(const py::array_t<double>& a) {
  return {a.data(), static_cast<Eigen::Index>(a.size())};
}

// Row-major view of a 2-D C-contiguous float64 array.
using RowMatrixMap =
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
inline RowMatrixMap matrix_map(const py::array_t<double>& a) {
  return {a.data(), static_cast<Eigen::Index>(a.shape(0)), static_cast<Eigen::Index>(a.shape(1))};
}

// cv::Mat header over an H x W x 3 uint8 array (BGR), no copy for C-contiguous input.
// `keep` receives the array that owns the pixels.
cv::Mat bgr_frame(const py::handle& obj, const char* name, py::array& keep);
// cv::Mat header over an H x W array of uint8, float32 or float64 (as `image`), no copy for
// C-contiguous input.
cv::Mat gray_image(const py::handle& obj, const char* name, py::array& keep);

// A metric depth image for the depth likelihood: as gray_image, but float32 or float64 only
// (TypeError naming `name` for uint8: depth is in metres).
cv::Mat depth_image(const py::handle& obj, const char* name, py::array& keep);

// A background-subtracted image y (the filters' input): as gray_image, but float32 only
// (TypeError naming `name` otherwise; the filters read it as float without conversion).
cv::Mat float32_image(const py::handle& obj, const char* name, py::array& keep);

// `rng` may be a vtrack.Rng (used and advanced in place) or an int seed (a fresh Rng).
core::Rng& rng_from(const py::handle& rng, core::Rng& storage);

// The C++ side of a progress callback: after every frame it takes the GIL, lets Python handle a
// pending signal (Ctrl-C raises KeyboardInterrupt out of the C++ loop) and calls `callback(done,
// total)` unless it is None. Exceptions from either propagate out of the C++ job.
std::function<void(long long, long long)> progress_callback(const py::object& callback);

// The Python type name of `value`, for error messages.
std::string type_name(const py::handle& value);

void bind_core(py::module_& m);
void bind_image(py::module_& m);
void bind_color(py::module_& m);
void bind_models(py::module_& m);
void bind_filters(py::module_& m);
void bind_glmb(py::module_& m);
void bind_multi_bernoulli(py::module_& m);
void bind_reclustering_sir(py::module_& m);
void bind_apps(py::module_& m);
void bind_detections(py::module_& m);
void bind_tracks(py::module_& m);
void bind_vehicles(py::module_& m);
void bind_smc(py::module_& m);
void bind_follow(py::module_& m);

}  // namespace vtrack::bindings

#include "common.hpp"

#include <cmath>

namespace vtrack::bindings {
namespace {

std::string dtype_name(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

std::string shape_string(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    s += (i ? ", " : "") + std::to_string(a.shape(i));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array_t<double> as_float64(const py::handle& obj, const char* name, int ndim, Nan nan) {
  py::array a = py::array::ensure(obj);
  if (!a) throw py::type_error(std::string(name) + " must be a NumPy array or sequence of numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(std::string(name) + " must hold real numbers, got dtype " +
                         dtype_name(a));
  }
  if (a.ndim() != ndim) {
    throw py::value_error(std::string(name) + " must be " + std::to_string(ndim) +
                          "-D, got shape " + shape_string(a));
  }
  auto out = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (nan == Nan::Rejected) {
    const double* p = out.data();
    for (py::ssize_t i = 0; i < out.size(); ++i) {
      if (std::isnan(p[i])) {
        throw py::value_error(std::string(name) + " contains NaN (at flat index " +
                              std::to_string(i) + ")");
      }
    }
  }
  return out;
}

// The Mat is an input that the library only reads, so a read-only array (np.frombuffer, a
// frame with writeable=False) is accepted: const_cast instead of mutable_data(), which throws.
cv::Mat mat_over(const py::array& a, int cv_type) {
  return cv::Mat(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), cv_type,
                 const_cast<void*>(a.data()), static_cast<std::size_t>(a.strides(0)));
}

}  // namespace

std::string type_name(const py::handle& v) {
  return py::str(py::type::of(v).attr("__name__")).cast<std::string>();
}

py::array_t<double> as_vector(const py::handle& obj, const char* name, Nan nan) {
  return as_float64(obj, name, 1, nan);
}

py::array_t<double> as_matrix(const py::handle& obj, const char* name, Nan nan) {
  return as_float64(obj, name, 2, nan);
}

py::array_t<double> as_array(const py::handle& obj, const char* name, int ndim, Nan nan) {
  return as_float64(obj, name, ndim, nan);
}

cv::Mat bgr_frame(const py::handle& obj, const char* name, py::array& keep) {
  py::array a = py::array::ensure(obj);
  if (!a) throw py::type_error(std::string(name) + " must be a NumPy array");
  if (a.dtype().kind() != 'u' || a.itemsize() != 1) {
    throw py::type_error(std::string(name) + " must have dtype uint8, got " + dtype_name(a));
  }
  if (a.ndim() != 3 || a.shape(2) != 3) {
    throw py::value_error(std::string(name) + " must have shape (H, W, 3), got " +
                          shape_string(a));
  }
  if (a.shape(0) == 0 || a.shape(1) == 0) throw py::value_error(std::string(name) + " is empty");
  keep = py::array::ensure(a, py::array::c_style);
  return mat_over(keep, CV_8UC3);
}

cv::Mat gray_image(const py::handle& obj, const char* name, py::array& keep) {
  py::array a = py::array::ensure(obj);
  if (!a) throw py::type_error(std::string(name) + " must be a NumPy array");
  int cv_type = -1;
  if (a.dtype().is(py::dtype::of<std::uint8_t>())) cv_type = CV_8UC1;
  if (a.dtype().is(py::dtype::of<float>())) cv_type = CV_32FC1;
  if (a.dtype().is(py::dtype::of<double>())) cv_type = CV_64FC1;
  if (cv_type < 0) {
    throw py::type_error(std::string(name) + " must have dtype uint8, float32 or float64, got " +
                         dtype_name(a));
  }
  if (a.ndim() != 2) {
    throw py::value_error(std::string(name) + " must be 2-D (H, W), got " +
                          std::to_string(a.ndim()) + " dimensions");
  }
  if (a.shape(0) == 0 || a.shape(1) == 0) throw py::value_error(std::string(name) + " is empty");
  keep = py::array::ensure(a, py::array::c_style);
  return mat_over(keep, cv_type);
}

cv::Mat depth_image(const py::handle& obj, const char* name, py::array& keep) {
  cv::Mat image = gray_image(obj, name, keep);
  if (image.depth() == CV_8U) {
    throw py::type_error(std::string(name) + " must be float32 or float64 metres, got uint8");
  }
  return image;
}

cv::Mat float32_image(const py::handle& obj, const char* name, py::array& keep) {
  cv::Mat image = gray_image(obj, name, keep);
  if (image.type() != CV_32FC1) {
    throw py::type_error(std::string(name) + " must have dtype float32, got " + dtype_name(keep));
  }
  return image;
}

std::function<void(long long, long long)> progress_callback(const py::object& callback) {
  return [callback](long long done, long long total) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback.is_none()) callback(done, total);
  };
}

core::Rng& rng_from(const py::handle& rng, core::Rng& storage) {
  if (py::isinstance<core::Rng>(rng)) return rng.cast<core::Rng&>();
  if (py::isinstance<py::int_>(rng) && !py::isinstance<py::bool_>(rng)) {
    storage = core::Rng(rng.cast<std::uint64_t>());
    return storage;
  }
  throw py::type_error("rng must be a vtrack.Rng or an int seed, got " +
                       py::str(py::type::of(rng)).cast<std::string>());
}

}  // namespace vtrack::bindings

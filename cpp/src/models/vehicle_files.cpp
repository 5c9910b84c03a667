// The camera file and the vehicle models file (models/camera.hpp, models/vehicle_observation.hpp),
// read with yaml-cpp, which parses YAML and JSON alike. The only file of vtrack::models that
// reads files.
#include <algorithm>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/text_file.hpp"
#include "vtrack/models/camera.hpp"
#include "vtrack/models/vehicle_observation.hpp"

namespace vtrack::models {

namespace {

// Loads a YAML/JSON document. A file written by cv::FileStorage starts with the non-standard
// directive "%YAML:1.0", which yaml-cpp refuses: that line is dropped.
YAML::Node load_document(const std::string& path, const std::string& what) {
  // The config files' limits (apps/config.hpp): 1 MiB, flow collections 16 deep.
  std::string s = core::read_text_file(path, what, std::size_t{1} << 20, 16);
  if (s.rfind("%YAML:", 0) == 0) s = s.substr(std::min(s.size(), s.find('\n')));
  try {
    return YAML::Load(s);
  } catch (const YAML::Exception& e) {
    throw IoError(what + " " + path + ": not valid YAML or JSON: " + e.what());
  }
}

double number(const YAML::Node& node, const std::string& where) {
  if (!node.IsScalar()) throw InvalidArgument(where + " must be a number");
  try {
    return node.as<double>();
  } catch (const YAML::Exception&) {
    throw InvalidArgument(where + " must be a number, got '" + node.Scalar() + "'");
  }
}

// The numbers of a list, a list of rows (each `cols` long when cols > 0), or an OpenCV
// FileStorage matrix {rows, cols, dt, data}, row-major.
std::vector<double> numbers(const YAML::Node& node, const std::string& where, int cols) {
  if (node.IsMap() && node["data"]) return numbers(node["data"], where + ".data", 0);
  if (!node.IsSequence()) throw InvalidArgument(where + " must be a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node item = node[i];
    const std::string at = where + "[" + std::to_string(i) + "]";
    if (!item.IsSequence()) {
      out.push_back(number(item, at));
      continue;
    }
    if (cols > 0 && static_cast<int>(item.size()) != cols) {
      throw InvalidArgument(at + " must be a row of " + std::to_string(cols) + " numbers, got " +
                            std::to_string(item.size()));
    }
    for (std::size_t j = 0; j < item.size(); ++j) out.push_back(number(item[j], at + "[" + std::to_string(j) + "]"));
  }
  return out;
}

YAML::Node required(const YAML::Node& root, const char* key, const std::string& hint) {
  const YAML::Node node = root[key];
  if (!node) throw InvalidArgument(std::string("missing key '") + key + "' (" + hint + ")");
  return node;
}

template <int N>
Eigen::Matrix<double, N, 1> fixed_vector(const YAML::Node& node, const std::string& key, int cols) {
  const std::vector<double> v = numbers(node, key, cols);
  if (static_cast<int>(v.size()) != N) {
    throw InvalidArgument(key + " must have " + std::to_string(N) + " numbers, got " + std::to_string(v.size()));
  }
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(v.data());
}

Eigen::Matrix3d matrix3(const YAML::Node& node, const std::string& key) {
  const Eigen::Matrix<double, 9, 1> v = fixed_vector<9>(node, key, 3);
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
}

CameraCalibration camera_calibration(const YAML::Node& root) {
  if (!root.IsMap()) throw InvalidArgument("expected a map with the keys K, dist, R, t");
  CameraCalibration c;
  c.K = matrix3(required(root, "K", "3x3 intrinsic matrix"), "K");
  const std::vector<double> dist =
      numbers(required(root, "dist", "OpenCV distortion coefficients; [] or zeros for none"), "dist", 0);
  c.dist = Eigen::Map<const Eigen::VectorXd>(dist.data(), static_cast<Eigen::Index>(dist.size()));
  c.R = matrix3(required(root, "R", "3x3 world-to-camera rotation"), "R");
  c.t = fixed_vector<3>(required(root, "t", "translation, x_cam = R X_world + t"), "t", 0);
  if (root["road_axis_world"]) c.road_axis_world = fixed_vector<3>(root["road_axis_world"], "road_axis_world", 0);
  if (root["image_size"]) {
    const Eigen::Vector2d size = fixed_vector<2>(root["image_size"], "image_size", 0);
    if (size != size.array().round().matrix() || !(size.array() > 0).all() || !(size.array() < 1e9).all()) {
      throw InvalidArgument("image_size must be [width, height], positive integers");
    }
    c.image_width = static_cast<int>(size(0));
    c.image_height = static_cast<int>(size(1));
  }
  return c;
}

VehicleModel vehicle_class(const YAML::Node& node, const std::string& where) {
  if (!node.IsMap()) throw InvalidArgument(where + " must be a map {name, W, H, L, sigma_w, sigma_h, sigma_l}");
  static const char* known[] = {"name", "W", "H", "L", "sigma_w", "sigma_h", "sigma_l", "weight", "heavy"};
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(std::begin(known), std::end(known), key) == std::end(known)) {
      throw InvalidArgument(where + ": unknown key '" + key +
                            "' (known: name, W, H, L, sigma_w, sigma_h, sigma_l, weight, heavy)");
    }
  }
  VehicleModel c;
  const YAML::Node name = required(node, "name", "the class name");
  c.name = name.IsScalar() ? name.Scalar() : "";
  const std::string at = where + " (" + c.name + ")";
  const char* dims[] = {"W", "H", "L"};
  const char* sigmas[] = {"sigma_w", "sigma_h", "sigma_l"};
  for (int k = 0; k < 3; ++k) {
    c.mean(k) = number(required(node, dims[k], "metres"), at + ": " + dims[k]);
    c.sigma(k) = number(required(node, sigmas[k], "metres"), at + ": " + sigmas[k]);
  }
  if (node["weight"]) c.weight = number(node["weight"], at + ": weight");
  if (node["heavy"]) {
    try {
      c.heavy = node["heavy"].as<bool>();
    } catch (const YAML::Exception&) {
      throw InvalidArgument(at + ": heavy must be true or false");
    }
  }
  return c;
}

}  // namespace

Camera read_camera_file(const std::string& path) {
  const std::string what = "camera file";
  const YAML::Node root = load_document(path, what);
  try {
    return Camera(camera_calibration(root));
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(what + " " + path + ": " + e.what());
  }
}

std::vector<VehicleModel> read_vehicle_models_file(const std::string& path) {
  const std::string what = "vehicle models file";
  const YAML::Node root = load_document(path, what);
  try {
    if (!root.IsMap() || !root["models"] || !root["models"].IsSequence()) {
      throw InvalidArgument("expected a map with a list 'models'");
    }
    VehiclePriorParams params;
    params.models.clear();
    const YAML::Node models = root["models"];
    for (std::size_t i = 0; i < models.size(); ++i) {
      params.models.push_back(vehicle_class(models[i], "models[" + std::to_string(i) + "]"));
    }
    validate(params);
    return params.models;
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(what + " " + path + ": " + e.what());
  }
}

}  // namespace vtrack::models

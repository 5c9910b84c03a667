// The parameter tables (core/parameters.hpp), config files (apps/config.hpp) and the pipeline's
// routing of names to sections (apps/pipeline.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>

#include "vtrack/apps/config.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/pipeline.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/parameters.hpp"
#include "vtrack/filters/glmb_tracker.hpp"
#include "vtrack/filters/multi_bernoulli.hpp"
#include "vtrack/image/kde_background.hpp"

namespace {

using vtrack::InvalidArgument;
using vtrack::InvalidType;
using vtrack::core::ParameterValue;

// A value of the same kind as `v` but different from it.
ParameterValue changed(const ParameterValue& v, const std::vector<std::string>& choices) {
  if (const auto* d = std::get_if<double>(&v)) {
    if (!std::isfinite(*d)) return 0.25;
    const double c = *d * 0.5 + 0.125;  // 0.25 is this map's fixed point
    return c != *d ? c : *d + 1.0;
  }
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i + 1;
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return *u + 1;
  if (const auto* b = std::get_if<bool>(&v)) return !*b;
  if (const auto* r = std::get_if<std::vector<double>>(&v)) {
    std::vector<double> out = *r;
    for (double& x : out) x *= 0.5;
    return out;
  }
  const auto& s = std::get<std::string>(v);
  for (const auto& c : choices) {
    if (c != s) return c;
  }
  return s;
}

// Every entry of the table can be set by name to another value of its kind, reads back what was
// set, and leaves every other entry as it was.
template <class Params>
void expect_every_parameter_reachable() {
  const auto& table = Params::table();
  std::set<std::string> names;
  for (const auto& e : table.entries()) {
    EXPECT_TRUE(names.insert(e.name).second) << "duplicate name " << e.name;
    Params p;
    const ParameterValue before = e.get(p);
    const ParameterValue after = changed(before, e.choices);
    ASSERT_TRUE(table.set(p, e.name, after)) << e.name;
    EXPECT_EQ(e.get(p), after) << e.name;
    if (e.kind != vtrack::core::ParameterKind::choice || e.choices.size() > 1) {
      EXPECT_NE(e.get(p), before) << e.name << " did not change";
    }
    for (const auto& other : table.entries()) {
      if (other.name != e.name) EXPECT_EQ(other.get(p), other.get(Params{})) << other.name;
    }
  }
  Params p;
  EXPECT_FALSE(table.set(p, "no_such_parameter", 1.0));
}

TEST(Parameters, EveryTableReachesEveryField) {
  expect_every_parameter_reachable<vtrack::image::KdeBackgroundParams>();
  expect_every_parameter_reachable<vtrack::models::TbdLikelihoodParams>();
  expect_every_parameter_reachable<vtrack::filters::MultiBernoulliParams>();
  expect_every_parameter_reachable<vtrack::filters::TrackManagementParams>();
  expect_every_parameter_reachable<vtrack::filters::GlmbParams>();
  expect_every_parameter_reachable<vtrack::filters::ParticleParams>();
  expect_every_parameter_reachable<vtrack::filters::GlmbTrackerParams>();
  expect_every_parameter_reachable<vtrack::apps::BoxTrackerParams>();
  expect_every_parameter_reachable<vtrack::apps::HogParams>();
}

TEST(Parameters, KindsAreCheckedAndNumbersNeverNarrowSilently) {
  vtrack::filters::MultiBernoulliParams p;
  const auto& t = vtrack::filters::MultiBernoulliParams::table();
  EXPECT_THROW(t.set(p, "sigma_xy", std::string("abc")), InvalidType);
  EXPECT_THROW(t.set(p, "max_particles", 2.5), InvalidType);  // a real is never truncated
  EXPECT_THROW(t.set(p, "quarter_birth", std::int64_t{1}), InvalidType);
  EXPECT_THROW(t.set(p, "resampling", std::string("best")), InvalidArgument);
  EXPECT_THROW(t.set(p, "seed", std::int64_t{-1}), InvalidType);
  // Integers beyond int range are rejected, not wrapped.
  EXPECT_THROW(t.set(p, "max_particles", std::int64_t{99999999999}), InvalidArgument);
  // Seeds take the whole unsigned 64-bit range.
  ASSERT_TRUE(t.set(p, "seed", std::numeric_limits<std::uint64_t>::max()));
  EXPECT_EQ(p.seed, std::numeric_limits<std::uint64_t>::max());
  ASSERT_TRUE(t.set(p, "sigma_xy", std::int64_t{7}));  // an integer is a real
  EXPECT_EQ(p.sigma_xy, 7.0);
  vtrack::image::KdeBackgroundParams k;
  EXPECT_THROW(vtrack::core::set_parameters(k, {{"bandwidth", std::vector<double>{0.1, 0.2}}}, "background"),
               InvalidType);
  try {
    vtrack::core::set_parameters(k, {{"bandwith", std::vector<double>{0.1, 0.2, 0.3}}}, "background");
    FAIL();
  } catch (const InvalidType& e) {
    EXPECT_STREQ(e.what(), "unknown background parameter 'bandwith' (did you mean 'bandwidth'?)");
  }
}

TEST(Parameters, CommandLineTextParses) {
  using vtrack::core::parse_parameter_text;
  EXPECT_EQ(parse_parameter_text("true"), ParameterValue(true));
  EXPECT_EQ(parse_parameter_text("-3"), ParameterValue(std::int64_t{-3}));
  EXPECT_EQ(parse_parameter_text("18446744073709551615"),
            ParameterValue(std::numeric_limits<std::uint64_t>::max()));
  EXPECT_EQ(parse_parameter_text("2e-3"), ParameterValue(2e-3));
  EXPECT_EQ(parse_parameter_text("inf"), ParameterValue(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(parse_parameter_text("0.1,0.2,0.3"), ParameterValue(std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(parse_parameter_text("residual"), ParameterValue(std::string("residual")));
  EXPECT_EQ(parse_parameter_text("1,x"), ParameterValue(std::string("1,x")));
  EXPECT_EQ(vtrack::core::closest_name("delta_bb", {"delta_b", "delta_f", "seed"}), "delta_b");
  EXPECT_EQ(vtrack::core::closest_name("xyzzy", {"delta_b", "seed"}), "");
}

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("vtrack_params_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(Config, YamlAndJsonGiveTheSameSections) {
  const auto yaml = write_file("a.yml",
                               "seed: 18446744073709551615\n"
                               "background: {n_samples: 4, bandwidth: [0.02, 0.03, 0.07]}\n"
                               "tracker:\n  resampling: residual\n  quarter_birth: false\n");
  const auto json = write_file("a.json",
                               "{\"seed\": 18446744073709551615, \"background\": {\"n_samples\": 4, "
                               "\"bandwidth\": [0.02, 0.03, 0.07]}, \"tracker\": {\"resampling\": "
                               "\"residual\", \"quarter_birth\": false}}");
  for (const auto& path : {yaml, json}) {
    const auto c = vtrack::apps::read_config(path);
    ASSERT_TRUE(c.seed.has_value());
    EXPECT_EQ(*c.seed, std::numeric_limits<std::uint64_t>::max());
    vtrack::apps::PipelineParams p;
    vtrack::apps::apply_config(p, c);
    EXPECT_EQ(p.mb.seed, std::numeric_limits<std::uint64_t>::max());
    EXPECT_EQ(p.background.n_samples, 4);
    EXPECT_EQ(p.background.bandwidth[2], 0.07);
    EXPECT_EQ(p.mb.resampling, vtrack::core::ResamplingScheme::Residual);
    EXPECT_FALSE(p.mb.quarter_birth);
  }
}

TEST(Config, BadFilesNameTheProblem) {
  auto message = [](const std::string& text) {
    const auto path = write_file("bad.yml", text);
    try {
      vtrack::apps::PipelineParams p;
      vtrack::apps::apply_config(p, vtrack::apps::read_config(path));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("tracker: {delta_f: [1\n").find("line 2, column 1"), std::string::npos);
  EXPECT_NE(message("seed: 99999999999999999999\n").find("seed"), std::string::npos);
  EXPECT_NE(message("seed: -1\n").find("seed"), std::string::npos);
  EXPECT_NE(message("tracker: {sigma_xy: abc}\n").find("sigma_xy must be a number"), std::string::npos);
  EXPECT_NE(message("tracker: {delta_bb: 1}\n").find("did you mean 'delta_b'"), std::string::npos);
  EXPECT_NE(message("detector: {win_stride: 8}\n").find("no section 'detector'"), std::string::npos);
  EXPECT_NE(message("tracker: {sigma_xy: 1}\ntracker: {sigma_xy: 2}\n").find("line 2: 'tracker' appears twice"),
            std::string::npos);
  EXPECT_NE(message("tracker: {sigma_xy: 1, sigma_xy: 2}\n").find("appears twice"), std::string::npos);
  EXPECT_NE(message("[1, 2]\n").find("map of sections"), std::string::npos);
  EXPECT_NE(message("tracker: 5\n").find("must be a map"), std::string::npos);
  EXPECT_NE(message("a: " + std::string(50000, '[') + "\n").find("nested deeper"), std::string::npos);
  EXPECT_THROW(vtrack::apps::read_config("/no/such/file.yml"), vtrack::IoError);
  EXPECT_EQ(message(""), "no error");  // an empty file sets nothing
}

TEST(Pipeline, NamesRouteToTheOneSectionThatHasThem) {
  for (const auto& method : vtrack::apps::pipeline_methods()) {
    vtrack::apps::PipelineParams p;
    p.method = method;
    std::set<std::string> names;
    for (const auto& section : vtrack::apps::pipeline_sections(p)) {
      for (const auto& [name, value] : section.values) {
        EXPECT_TRUE(names.insert(name).second) << method << ": '" << name << "' in two sections";
        vtrack::apps::set_pipeline_parameter(p, name, value);  // every name is reachable
      }
    }
  }
  vtrack::apps::PipelineParams p;
  vtrack::apps::set_pipeline_parameter(p, "closing", std::int64_t{3});
  vtrack::apps::set_pipeline_parameter(p, "delta_f", 0.2);
  EXPECT_EQ(p.background.closing, 3);
  EXPECT_EQ(p.mb.likelihood.delta_f, 0.2);
  EXPECT_THROW(vtrack::apps::set_pipeline_parameter(p, "win_stride", std::int64_t{8}), InvalidType);
  p.method = "glmb";
  EXPECT_THROW(vtrack::apps::validate(p), InvalidArgument);  // glmb needs a detector
  p.detector = "hog";
  EXPECT_NO_THROW(vtrack::apps::validate(p));
  p.method = "sort";
  EXPECT_THROW(vtrack::apps::validate(p), InvalidArgument);
}

}  // namespace

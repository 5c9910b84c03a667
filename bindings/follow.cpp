// Bindings of the single-object colour trackers (filters/color_particle.hpp) in the shape of
// OpenCV's tracker API: init(frame, box), update(frame) -> (ok, box). Conversion only.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "guard.hpp"
#include "args.hpp"
#include "params.hpp"
#include "vtrack/apps/follow.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/filters/color_particle.hpp"

namespace vtrack::bindings {
namespace {

using filters::Box;
using filters::ColorParticleFilter;
using filters::ColorParticleParams;
using filters::PartLayout;
using filters::PartParticleFilter;
using filters::PartParticleParams;

Box box_from(const py::handle& obj) {
  const py::array_t<double> a = as_vector(obj, "box");
  if (a.size() != 4) {
    throw py::value_error("box must hold 4 numbers (x, y, w, h), got " + std::to_string(a.size()));
  }
  return Box{a.at(0), a.at(1), a.at(2), a.at(3)};
}

py::tuple box_tuple(const Box& b) { return py::make_tuple(b.x, b.y, b.w, b.h); }

// A layout from Python: `parts` a sequence of (fx, fy, fw, fh) fractions, `edges` a sequence of
// (a, b) pairs or None (every pair connected).
PartLayout layout_from(const py::handle& parts, const py::handle& edges) {
  PartLayout layout;
  const py::array_t<double> f = as_matrix(parts, "parts");
  if (f.shape(1) != 4) throw py::value_error("parts must be rows of 4 fractions (fx, fy, fw, fh)");
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    layout.parts.push_back({f.at(i, 0), f.at(i, 1), f.at(i, 2), f.at(i, 3)});
  }
  const int n = static_cast<int>(layout.parts.size());
  if (edges.is_none()) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < i; ++j) layout.edges.emplace_back(j, i);
    }
  } else {
    for (const py::handle& e : edges) {
      const auto pair = e.cast<std::vector<int>>();
      if (pair.size() != 2) throw py::value_error("edges must be pairs of part indices");
      layout.edges.emplace_back(pair[0], pair[1]);
    }
  }
  filters::validate(layout);
  return layout;
}

// Runs update() without the GIL, holding the object's guard.
template <class Tracker>
py::tuple update(Tracker& t, const py::handle& frame) {
  py::array keep;
  const cv::Mat bgr = bgr_frame(frame, "frame", keep);
  ObjectGuard guard(&t);
  bool ok;
  {
    py::gil_scoped_release release;
    ok = t.update(bgr);
  }
  return py::make_tuple(ok, box_tuple(t.box()));
}

template <class Tracker>
void init(Tracker& t, const py::handle& frame, const py::handle& box) {
  py::array keep;
  const cv::Mat bgr = bgr_frame(frame, "frame", keep);
  const Box b = box_from(box);
  ObjectGuard guard(&t);
  t.init(bgr, b);
}

const char* kColorDoc = R"doc(
The conventional colour-histogram particle filter (part-based-graphical-model-pf.txt sections
2-3.2, after Nummiaro et al.): a single-object tracker with OpenCV's tracker interface.

    t = vtrack.ColorParticleTracker(n_particles=30, seed=0)
    t.init(frame, (x, y, w, h))          # H x W x 3 uint8 BGR frame, the target's box
    ok, (x, y, w, h) = t.update(frame)   # every following frame (same size)

State (cx, cy, h, w) with the second-order auto-regressive dynamics of eq. 13 (noise
proportional to the box: `noise`, `min_scale`, `max_scale`, `min_size`), the 16 x 4 x 4 HSV
histogram of section 3.1 (bins_h, bins_s, bins_v, kernel), the likelihood of eq. 11 with `sigma`
(0.2: the reading of eq. 11 that tracks better, see benchmarks/follow.py), SIR with selective
resampling when N_eff <= ess_threshold N (eq. 7), the weighted-mean estimate (eq. 8), a template
from the init box with an optional slow update (`template_update`, off by default). ok is False
when the estimate's centre leaves the frame or the best coefficient is below
`lost_threshold` (the target left or is lost). Keyword parameters: default_params().
)doc";

const char* kPartDoc = R"doc(
The part-based particle filter on a graphical model (part-based-graphical-model-pf.txt sections
3.3-4, eqs. 14-30): each part of the object is a node with its own particles and template, and
neighbouring parts exchange message particles, so a part that is occluded is inferred from its
neighbours.

    t = vtrack.PartParticleTracker(parts=2, n_particles=15, seed=0)
    t.init(frame, (x, y, w, h))
    ok, box = t.update(frame)            # the whole object's box
    t.parts                              # (P, 4) each part's box
    t.occluded                           # (P,) bool: parts judged occluded this frame

`parts`: an int P (P horizontal stripes of the box: 2 = a person's upper and lower halves, 3 = a
face's thirds), or rows (fx, fy, fw, fh) of fractions of the box; `edges`: pairs of part indices
(default: every pair). `message_weight`: "neighbour" (eq. 26), "target" (eq. 20) or "product"
(eq. 19). A part is judged occluded when its best particle's Bhattacharyya coefficient is below
`occlusion_threshold`; it then drops its own particles and follows its neighbours' messages.
Other keyword parameters as ColorParticleTracker; default_params().
)doc";

// Each part's `of(p)` after init, for the per-part properties of PartParticleTracker.
template <class Of>
auto per_part(const PartParticleFilter& t, const char* name, const Of& of) {
  ObjectGuard guard(&t);
  if (!t.initialized()) throw InvalidArgument(std::string(name) + " before init");
  std::vector<decltype(of(0))> out;
  for (int p = 0; p < t.part_count(); ++p) out.push_back(of(p));
  return out;
}

void bind_color_tracker(py::module_& m) {
  py::class_<ColorParticleFilter> color(m, "ColorParticleTracker", kColorDoc);
  color
      .def(py::init([](const py::kwargs& kwargs) {
        return ColorParticleFilter(params_from_kwargs<ColorParticleParams>(kwargs, "tracker"));
      }))
      .def("init", &init<ColorParticleFilter>, py::arg("frame"), py::arg("box"),
           "Start on `box` (x, y, w, h) of `frame` (H x W x 3 uint8 BGR): the template.")
      .def("update", &update<ColorParticleFilter>, py::arg("frame"),
           "Track into the next frame: (ok, (x, y, w, h)).")
      .def_property_readonly("box", [](const ColorParticleFilter& t) {
        ObjectGuard guard(&t);
        return box_tuple(t.box());
      }, "The last estimate (x, y, w, h) (eq. 8).")
      .def_property_readonly("particles", guarded(&ColorParticleFilter::particle_boxes),
                             "(N, 4) the particles' boxes x, y, w, h after the last update.")
      .def_property_readonly("weights", guarded(&ColorParticleFilter::weights),
                             "(N,) their normalised weights (1/N after a resampling).")
      .def_property_readonly("coefficient", guarded(&ColorParticleFilter::coefficient),
                             "The largest Bhattacharyya coefficient (eq. 10) of the last update.")
      .def_property_readonly("occluded", guarded(&ColorParticleFilter::occluded),
                             "coefficient < occlusion_threshold.")
      .def_property_readonly("initialized", guarded(&ColorParticleFilter::initialized))
      .def("__repr__", [](const ColorParticleFilter& t) {
        return "ColorParticleTracker(" + keyword_text(params_dict(t.params())) + ")";
      });
  def_params<ColorParticleParams>(color, [](const ColorParticleFilter& t) { return t.params(); });
}

void bind_part_tracker(py::module_& m) {
  py::class_<PartParticleFilter> parts(m, "PartParticleTracker", kPartDoc);
  parts
      .def(py::init([](const py::object& edges, py::kwargs kwargs) {
        py::object layout_parts = py::none();
        if (kwargs.contains("parts") && !py::isinstance<py::int_>(kwargs["parts"])) {
          layout_parts = kwargs.attr("pop")("parts");
          if (layout_parts.is_none()) {
            throw py::type_error("parts must be an int or rows (fx, fy, fw, fh) of fractions, got None");
          }
        }
        PartParticleParams p = params_from_kwargs<PartParticleParams>(kwargs, "tracker");
        PartLayout layout;
        if (!layout_parts.is_none()) {
          layout = layout_from(layout_parts, edges);
          p.parts = static_cast<int>(layout.parts.size());
        } else if (!edges.is_none()) {
          layout = PartLayout::stripes(p.parts);
          layout = layout_from(py::cast(layout.parts), edges);
        }
        return PartParticleFilter(p, std::move(layout));
      }), py::kw_only(), py::arg("edges") = py::none())
      .def("init", &init<PartParticleFilter>, py::arg("frame"), py::arg("box"),
           "Start on `box` (x, y, w, h) of `frame` (H x W x 3 uint8 BGR): one template per part.")
      .def("update", &update<PartParticleFilter>, py::arg("frame"),
           "Track into the next frame: (ok, (x, y, w, h)) of the whole object.")
      .def_property_readonly("box", [](const PartParticleFilter& t) {
        ObjectGuard guard(&t);
        return box_tuple(t.box());
      }, "The whole object's last box (x, y, w, h).")
      .def_property_readonly("parts", [](const PartParticleFilter& t) {
        const std::vector<Box> boxes = per_part(t, "parts", [&](int p) { return t.part_box(p); });
        Eigen::MatrixXd out(boxes.size(), 4);
        for (std::size_t p = 0; p < boxes.size(); ++p) {
          out.row(static_cast<Eigen::Index>(p)) << boxes[p].x, boxes[p].y, boxes[p].w, boxes[p].h;
        }
        return out;
      }, "(P, 4) each part's box x, y, w, h (eq. 22).")
      .def_property_readonly("occluded", [](const PartParticleFilter& t) {
        return py::array_t<bool>(
            py::cast(per_part(t, "occluded", [&](int p) { return t.occluded(p); })));
      }, "(P,) bool: the parts judged occluded in the last update.")
      .def_property_readonly("coefficients", [](const PartParticleFilter& t) {
        const std::vector<double> c =
            per_part(t, "coefficients", [&](int p) { return t.coefficient(p); });
        return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(c.data(), c.size()));
      }, "(P,) each part's largest Bhattacharyya coefficient of the last update.")
      .def_property_readonly("particles", [](const PartParticleFilter& t) {
        return per_part(t, "particles", [&](int p) { return t.particle_boxes(p); });
      }, "Per part: the ((1 + degree) N, 4) predicted and message particles' boxes of Step 5.")
      .def_property_readonly("weights", [](const PartParticleFilter& t) {
        return per_part(t, "weights", [&](int p) { return t.weights(p); });
      }, "Per part: their normalised weights (eqs. 23, 30).")
      .def_property_readonly("edges", [](const PartParticleFilter& t) { return t.layout().edges; })
      .def_property_readonly("initialized", guarded(&PartParticleFilter::initialized))
      .def("__repr__", [](const PartParticleFilter& t) {
        return "PartParticleTracker(" + keyword_text(params_dict(t.params())) + ")";
      });
  def_params<PartParticleParams>(parts, [](const PartParticleFilter& t) { return t.params(); });
}

void bind_follow_video(py::module_& m) {
  m.def(
      "follow_video",
      [](const py::handle& video_arg, const py::handle& box_arg, const py::handle& method,
         const py::handle& first_arg, const py::handle& last_arg, const py::handle& render_arg,
         const py::dict& params, const py::object& progress) {
        const std::string video = path_arg(video_arg, "video");
        const Box box = box_from(box_arg);
        apps::FollowParams p;
        p.method = str_arg(method, "method");
        if (p.method == "color") {
          p.color = params_from_kwargs<ColorParticleParams>(params, "tracker");
        } else if (p.method == "parts") {
          p.parts = params_from_kwargs<PartParticleParams>(params, "tracker");
        }
        apps::validate(p);
        const long long first = int_arg(first_arg, "first", 1, std::numeric_limits<int>::max());
        const long long last =
            last_arg.is_none() ? 0 : int_arg(last_arg, "last", 1, std::numeric_limits<int>::max());
        const std::string render = render_arg.is_none() ? "" : path_arg(render_arg, "render");
        const apps::FrameProgress report = progress_callback(progress);
        std::vector<apps::FollowRow> rows;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          rows = apps::follow_video(video, box, p, first, last, render, report);
        }
        py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{5}});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < rows.size(); ++i) {
          const auto& r = rows[i];
          const auto k = static_cast<py::ssize_t>(i);
          o(k, 0) = static_cast<double>(r.frame);
          o(k, 1) = r.x;
          o(k, 2) = r.y;
          o(k, 3) = r.w;
          o(k, 4) = r.h;
        }
        return out;
      },
      py::arg("video"), py::arg("init_box"), py::arg("method"), py::arg("first"), py::arg("last"),
      py::arg("render"), py::arg("params"), py::arg("progress"),
      "The compiled half of vtrack.follow (use that): the (N, 5) rows frame, x, y, w, h.");
}

}  // namespace

void bind_follow(py::module_& m) {
  bind_color_tracker(m);
  bind_part_tracker(m);
  bind_follow_video(m);
}

}  // namespace vtrack::bindings

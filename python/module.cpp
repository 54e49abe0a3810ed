// The Python module `stereo`: the matcher registry, evaluation, the fuzzy decision and the
// co-simulation of the Verilated RTL on numpy arrays (docs/python.md). Images are uint8 arrays
// of shape (H, W) or (H, W, 3) in RGB order (the model's); results are dicts of numpy arrays
// that own the C++ buffers they came from (no copy on the way out).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/fast_engine.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/matcher.hpp"
#include "stereo/validated.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/metrics.hpp"
#include "stereo_io/output.hpp"
#include "stereo_robot/decision.hpp"
#ifdef STEREO_WITH_RTL
#include "on_demand.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_top_sim.hpp"
#endif

namespace py = pybind11;

namespace {

using stereo::Image;
using stereo::MatchConfig;
using stereo::MatcherRegistry;

const MatcherRegistry& registry() {
    static const MatcherRegistry r = [] {
        MatcherRegistry built;
        stereo::register_model_matchers(built);
        stereo::hls::register_matchers(built);
#ifdef STEREO_WITH_RTL
        stereo::sim::register_matchers(built);
#endif
        return built;
    }();
    return r;
}

// The engine of `method` when the call names none: catalogue::kDefaultEngine where the method
// has it, else the reference engine (stereo match's rule).
std::string default_engine(const std::string& method) {
    for (const auto& entry : registry().entries()) {
        if (entry.method == method && entry.engine == stereo::catalogue::kDefaultEngine) {
            return entry.engine;
        }
    }
    return std::string(stereo::catalogue::kReferenceEngine);
}

// A numpy array of shape `shape` over `values`, which it takes over (freed with the array).
template <typename T>
py::array_t<T> adopt(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
    auto owner = std::make_unique<std::vector<T>>(std::move(values));
    T* data = owner->data();
    py::capsule free_owner(owner.get(), [](void* p) {
        std::unique_ptr<std::vector<T>>(static_cast<std::vector<T>*>(p));
    });
    owner.release();  // the capsule owns it now
    return py::array_t<T>(std::move(shape), data, free_owner);
}

// The type of a Python object for an error message: "list", "NoneType", "numpy.ndarray".
std::string type_name(const py::handle& object) {
    return py::str(py::type::handle_of(object).attr("__name__"));
}

// "(480, 640, 3)": an array's shape for an error message.
std::string shape_text(const py::array& array) {
    std::string text = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d) {
        text += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
    }
    return text + (array.ndim() == 1 ? ",)" : ")");
}

// A uint8 (H, W), (H, W, 1), (H, W, 3) RGB or (H, W, 4) RGBA array as the model's Image (one
// copy: Image owns its pixels). Alpha is dropped, as the CLI drops it from an RGBA file. Anything
// else (a list, None, another dtype or shape) is one short ValueError naming the argument.
Image to_image(const py::object& object, const char* name) {
    if (!py::isinstance<py::array>(object)) {
        throw std::invalid_argument(std::string(name) +
                                    " must be a numpy uint8 array (H, W) or (H, W, 3), got " +
                                    type_name(object) + " (np.asarray(x, dtype=np.uint8))");
    }
    const auto array = py::reinterpret_borrow<py::array>(object);
    if (array.dtype().kind() != 'u' || array.dtype().itemsize() != 1) {
        throw std::invalid_argument(std::string(name) + " must have dtype uint8, got " +
                                    std::string(py::str(array.dtype())) +
                                    (array.dtype().kind() == 'f'
                                         ? " (for 0..1 floats: (x * 255).round().astype(np.uint8))"
                                         : ""));
    }
    const py::ssize_t depth = array.ndim() == 3 ? array.shape(2) : 0;
    if (!(array.ndim() == 2 || depth == 1 || depth == 3 || depth == 4)) {
        throw std::invalid_argument(std::string(name) +
                                    " must have shape (H, W), (H, W, 3) or (H, W, 4), got " +
                                    shape_text(array));
    }
    const auto u8 = py::array_t<std::uint8_t, py::array::c_style>::ensure(array);
    const int stored = array.ndim() == 2 ? 1 : static_cast<int>(depth);
    const int channels = stored == 4 ? 3 : stored;
    Image image(static_cast<int>(u8.shape(1)), static_cast<int>(u8.shape(0)), channels);
    const std::uint8_t* in = u8.data();
    for (std::size_t p = 0; p < image.pixels.size() / channels; ++p) {
        std::copy_n(in + p * stored, channels, image.pixels.begin() + p * channels);
    }
    return image;
}

// A numeric 2-D array (any real dtype, converted to float32) for evaluate(); a short ValueError
// naming the argument otherwise.
py::array_t<float, py::array::c_style | py::array::forcecast> float_array(const py::object& object,
                                                                          const char* name) {
    if (!py::isinstance<py::array>(object)) {
        throw std::invalid_argument(std::string(name) + " must be a 2-D numpy array, got " +
                                    type_name(object));
    }
    const auto array = py::reinterpret_borrow<py::array>(object);
    const char kind = array.dtype().kind();
    if (kind != 'f' && kind != 'u' && kind != 'i' && kind != 'b') {
        throw std::invalid_argument(std::string(name) + " must be a numeric array, got dtype " +
                                    std::string(py::str(array.dtype())));
    }
    return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
}

// A float32 (H, W) array as CV_32FC1 (a view: the array outlives the call).
cv::Mat float_view(const py::array_t<float, py::array::c_style | py::array::forcecast>& array,
                   const char* name) {
    if (array.ndim() != 2) {
        throw std::invalid_argument(std::string(name) + " must be a 2-D float array");
    }
    return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), CV_32FC1,
                   const_cast<float*>(array.data()));
}

cv::Mat mask_view(const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& array,
                  const char* name) {
    if (array.ndim() != 2) {
        throw std::invalid_argument(std::string(name) + " must be a 2-D uint8 array");
    }
    return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), CV_8UC1,
                   const_cast<std::uint8_t*>(array.data()));
}

py::object json_to_python(const nlohmann::json& json) {
    return py::module_::import("json").attr("loads")(json.dump());
}

struct MatchOptions {
    std::string method;
    std::string engine;
    MatchConfig config;
};

// Stage 6's outputs as arrays: fixed (int16, disparity x 16), reason, certainty, and the
// disparity in pixels (float32, NaN where invalid).
void add_validated(py::dict& out, stereo::ValidatedDisparity&& v) {
    const std::vector<py::ssize_t> shape{v.height, v.width};
    const cv::Mat pixels = stereo::io::to_float_disparity(v);
    std::vector<float> floats(pixels.begin<float>(), pixels.end<float>());
    out["disparity_px"] = adopt(std::move(floats), shape);
    out["fixed"] = adopt(std::move(v.fixed), shape);
    out["reason"] = adopt(std::move(v.reason), shape);
    out["certainty"] = adopt(std::move(v.certainty), shape);
}

py::dict run_match(const py::object& left, const py::object& right, const MatchOptions& options) {
    const Image l = to_image(left, "left");
    const Image r = to_image(right, "right");
    const auto matcher = registry().create(options.method, options.engine, options.config);
    matcher->validate(l.width, l.height);
    stereo::MatchResult result;
    {
        py::gil_scoped_release release;
        result = matcher->compute(l, r);
    }
    py::dict out;
    const int w = result.disparity.width;
    const int h = result.disparity.height;
    const std::vector<py::ssize_t> shape{h, w};
    out["disparity"] = adopt(std::move(result.disparity.disparity), shape);
    auto valid = adopt(std::move(result.disparity.valid), shape);
    out["valid"] = valid.attr("astype")("bool");
    if (!result.validated.fixed.empty()) {
        add_validated(out, std::move(result.validated));
    }
    if (!result.subpixel.empty()) {
        out["subpixel"] = adopt(std::move(result.subpixel), shape);
    }
    if (!result.vertical.empty()) {
        out["vertical"] = adopt(std::move(result.vertical), shape);
    }
    py::dict counts;
    for (const auto& [name, value] : result.counts) {
        counts[py::str(name)] = value;
    }
    out["counts"] = counts;
    return out;
}

// The keywords a call gives, applied to the defaults of `stereo match` by the CLI's rule
// (defaults::apply).
using stereo::defaults::Overrides;

MatchOptions match_options(const std::string& method, const std::string& engine, int ndisp,
                           int window, double sigma, bool ca, int min_disp,
                           const Overrides& validation, int vrange, const std::string& neighbours,
                           int log_window, double log_sigma, int edge_value, int truncation,
                           int sparse_uniqueness, int sparse_lr,
                           const std::optional<py::dict>& asw = std::nullopt) {
    MatchOptions o{method, engine, stereo::defaults::match_config(method, engine)};
    stereo::MatchParams& p = o.config.pipeline;
    p.ndisp = ndisp;
    p.window = window;
    p.sigma = sigma;
    p.use_ca = ca;
    p.min_disp = min_disp;
    stereo::defaults::apply(validation, o.config);
    o.config.vrange = vrange;
    if (neighbours == "horizontal") {
        o.config.neighbours = stereo::CaNeighbours::horizontal;
    } else if (neighbours == "both") {
        o.config.neighbours = stereo::CaNeighbours::horizontal_and_vertical;
    } else {
        throw std::invalid_argument("neighbours must be \"horizontal\" or \"both\", got \"" +
                                    neighbours + "\"");
    }
    o.config.edges.log_window = log_window;
    o.config.edges.log_sigma = log_sigma;
    o.config.edges.edge_value = edge_value;
    o.config.edges.truncation = truncation;
    o.config.sparse.uniqueness = sparse_uniqueness;
    o.config.sparse.lr_tolerance = sparse_lr;
    if (asw) {
        // method "asw": the keys of stereo::asw::Params (docs/asw.md), each optional.
        stereo::asw::Params& a = o.config.asw;
        for (const auto& [key_object, value] : *asw) {
            const auto key = key_object.cast<std::string>();
            if (key == "diameter") {
                a.diameter = value.cast<int>();
            } else if (key == "response") {
                a.response = stereo::asw::response_from_name(value.cast<std::string>());
            } else if (key == "shape") {
                a.shape = stereo::asw::shape_from_name(value.cast<std::string>());
            } else if (key == "continuity") {
                a.continuity = value.cast<bool>();
            } else if (key == "right_weights") {
                a.right_weights = value.cast<bool>();
            } else if (key == "separable") {
                a.separable = value.cast<bool>();
            } else if (key == "truncation") {
                a.truncation = value.cast<int>();
            } else if (key == "threads") {
                a.threads = value.cast<int>();
            } else {
                throw std::invalid_argument("unknown asw key \"" + key +
                                            "\" (diameter, response, shape, continuity, "
                                            "right_weights, separable, truncation, threads)");
            }
        }
    }
    return o;
}

py::dict evaluate(const py::object& disparity_object, const py::object& ground_truth_object,
                  double threshold, std::optional<py::array> nonocc, std::optional<py::array> all,
                  std::optional<py::array> disc, bool zero_is_invalid, double gt_scale,
                  bool any_gt_range) {
    using U8 = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
    if (!std::isfinite(gt_scale) || !(gt_scale > 0.0)) {
        throw std::invalid_argument("gt_scale must be a positive number, got " +
                                    std::to_string(gt_scale));
    }
    const auto disparity = float_array(disparity_object, "disparity");
    const auto ground_truth = float_array(ground_truth_object, "ground_truth");
    stereo::io::EvalInput input;
    input.disparity = {float_view(disparity, "disparity"), "disparity"};
    // ground_truth / gt_scale, as stereo eval --gt-scale reads a PNG that holds d * K.
    cv::Mat truth;
    float_view(ground_truth, "ground_truth").convertTo(truth, CV_32F, 1.0 / gt_scale);
    input.ground_truth = {truth, "ground_truth"};
    // The masks are converted once and kept alive here while evaluate() reads them.
    std::vector<U8> masks;
    const auto add_mask = [&](const std::optional<py::array>& mask, const char* name,
                              std::optional<stereo::io::NamedMat>& slot) {
        if (mask) {
            masks.push_back(U8::ensure(*mask));
            slot = stereo::io::NamedMat{mask_view(masks.back(), name), name};
        }
    };
    masks.reserve(3);
    add_mask(nonocc, "nonocc", input.nonocc);
    add_mask(all, "all", input.all);
    add_mask(disc, "disc", input.disc);
    input.threshold = threshold;
    input.zero_is_invalid = zero_is_invalid;
    if (!any_gt_range) {
        stereo::io::check_ground_truth_range(
            input,
            "if it holds d * K, pass gt_scale=K (Middlebury 2003: 4, KITTI: 256); "
            "any_gt_range=True scores anyway");
    }
    nlohmann::json json = stereo::io::evaluate(input);
    return json_to_python(json);
}

py::dict fuzzy_decision(double left, double centre, double right) {
    const stereo::robot::FisResult r = stereo::robot::evaluate_fis(left, centre, right);
    py::dict out;
    out["angle_deg"] = r.angle_deg;
    out["backwards"] = r.backwards;
    out["decision"] = stereo::robot::to_string(r.decision);
    return out;
}

#ifdef STEREO_WITH_RTL
// The defaults of the options cosim() does not expose (they do not reach the pipeline).
const stereo::edge_frontend::EdgeParams kEdges{};
const stereo::sparse::Params kSparse{};

// One frame through the smallest built stereo_top that covers it, with random input gaps and
// output stalls, compared pixel by pixel with the model (fixed, reason, certainty).
// With `core` (stereo.cosim(..., size=(W, H))): that core, Verilated on demand into `cache`
// (sim/on_demand.hpp), instead of a configuration of this build.
py::dict cosim(const py::object& left, const py::object& right, const MatchOptions& options,
               double stall, double gap, std::uint32_t seed, const std::string& trace,
               const std::optional<stereo::sim::CoreRequest>& core, const std::string& cache) {
    const Image l = to_image(left, "left");
    const Image r = to_image(right, "right");
    const stereo::MatchParams& params = options.config.pipeline;
    const auto model = registry().create("pipeline", "model", options.config);
    model->validate(l.width, l.height);
    if (l.width != r.width || l.height != r.height) {
        throw std::invalid_argument("left and right differ in size");
    }
    std::optional<stereo::sim::TopConfig> demanded;
    std::filesystem::path runner;
    if (core) {
        demanded = stereo::sim::on_demand_config(*core);
        stereo::sim::check_fits(*core, l.width, l.height, params.min_disp);
        py::gil_scoped_release release;
        runner = stereo::sim::ensure_runner(
            *core,
            cache.empty() ? stereo::sim::default_cache_folder() : std::filesystem::path(cache),
            std::cerr);
    }
    const stereo::sim::TopConfig* config =
        core ? &*demanded
             : stereo::sim::covering_config(l.width, l.height, params.ndisp, params.window,
                                            params.min_disp, params.cost);
    if (config == nullptr) {
        throw std::invalid_argument(
            "no built co-simulation configuration covers this pair and "
            "these parameters (stereo.cosim_configs())");
    }
    stereo::ValidatedDisparity expected;
    stereo::ValidatedDisparity actual;
    stereo::sim::StreamResult result;
    {
        py::gil_scoped_release release;
        expected = model->compute(l, r).validated;
        // The waveform lands atomically, once the tracer closed it (stereo_io/output.hpp).
        std::optional<stereo::io::StagedOutput> trace_file;
        if (!trace.empty()) {
            stereo::sim::check_trace_path(trace);
            trace_file.emplace(trace);
        }
        auto top = core ? stereo::sim::make_runner_sim(*config, runner)
                        : stereo::sim::make_top_sim(*config);
        if (trace_file) {
            top->trace_to(trace_file->path().string());
        }
        top->reset();
        top->set_params({l.width, l.height, params});
        const auto beats = stereo::sim::frame_beats(l, r);
        result = top->stream(beats, beats.size(), {gap, stall, seed}, 100 * beats.size() + 100000);
        top.reset();  // closes the waveform
        if (trace_file) {
            trace_file->commit();
        }
        if (!result.completed || !result.protocol_error.empty()) {
            throw std::runtime_error("the RTL did not complete the frame: " +
                                     (result.protocol_error.empty() ? std::string("it stalled")
                                                                    : result.protocol_error));
        }
        actual = stereo::sim::assemble_validated(result.outputs, 0, l.width, l.height);
    }
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < expected.fixed.size(); ++i) {
        mismatches += expected.fixed[i] != actual.fixed[i] ||
                      expected.reason[i] != actual.reason[i] ||
                      expected.certainty[i] != actual.certainty[i];
    }
    py::dict out;
    out["config"] = config->name;
    out["mismatches"] = mismatches;
    out["cycles"] = result.cycles;
    add_validated(out, std::move(actual));
    return out;
}
#endif

}  // namespace

PYBIND11_MODULE(stereo, m) {
    m.doc() = "Stereo matching with the bit-exact golden model of the FPGA stereo accelerator";
    m.attr("__version__") = STEREO_VERSION;
#ifdef STEREO_WITH_RTL
    m.attr("has_rtl") = true;
#else
    m.attr("has_rtl") = false;
#endif

    m.def(
        "matchers",
        [] {
            std::vector<std::tuple<std::string, std::string, std::string>> out;
            for (const auto& e : registry().entries()) {
                out.emplace_back(e.method, e.engine, e.description);
            }
            return out;
        },
        "Every (method, engine, description) of the matcher registry.");

    m.def(
        "load_image",
        [](const std::string& path, int downscale) {
            Image image = stereo::io::load_image(path, downscale);
            std::vector<py::ssize_t> shape{image.height, image.width};
            if (image.channels == 3) {
                shape.push_back(3);
            }
            return adopt(std::move(image.pixels), std::move(shape));
        },
        py::arg("path"), py::kw_only(), py::arg("downscale") = 1,
        "An image file as uint8 (H, W) or (H, W, 3) RGB, as the CLI reads it (alpha dropped); "
        "downscale=F area-averages it by F first, as stereo match --downscale F.");

    const auto defaults = stereo::MatchParams{};
    const auto edges = stereo::edge_frontend::EdgeParams{};
    const auto sparse = stereo::sparse::Params{};
    m.def(
        "match",
        [](const py::object& left, const py::object& right, const std::string& method,
           const std::optional<std::string>& engine, int ndisp, int window, double sigma, bool ca,
           std::optional<std::string> cost, int min_disp, bool validation,
           std::optional<int> uniqueness, std::optional<int> lr_check, std::optional<bool> subpixel,
           int vrange, const std::string& neighbours, int log_window, double log_sigma,
           int edge_value, int truncation, int sparse_uniqueness, int sparse_lr,
           const std::optional<py::dict>& asw, std::optional<int> speckle_size, int speckle_range,
           int threads) {
            const Overrides keywords{std::move(cost), validation,   uniqueness,   lr_check,
                                     subpixel,        speckle_size, speckle_range};
            MatchOptions options =
                match_options(method, engine ? *engine : default_engine(method), ndisp, window,
                              sigma, ca, min_disp, keywords, vrange, neighbours, log_window,
                              log_sigma, edge_value, truncation, sparse_uniqueness, sparse_lr, asw);
            stereo::fast::validate_threads(threads == 0 ? 1 : threads);
            options.config.threads = threads;
            return run_match(left, right, options);
        },
        py::arg("left"), py::arg("right"), py::kw_only(), py::arg("method") = "pipeline",
        py::arg("engine") = py::none(), py::arg("ndisp") = defaults.ndisp,
        py::arg("window") = defaults.window, py::arg("sigma") = defaults.sigma,
        py::arg("ca") = defaults.use_ca, py::arg("cost") = py::none(),
        py::arg("min_disp") = defaults.min_disp, py::arg("validation") = true,
        py::arg("uniqueness") = py::none(), py::arg("lr_check") = py::none(),
        py::arg("subpixel") = py::none(),
        py::arg("vrange") = stereo::hierarchical::kDefaultVerticalRange,
        py::arg("neighbours") = "horizontal", py::arg("log_window") = edges.log_window,
        py::arg("log_sigma") = edges.log_sigma, py::arg("edge_value") = edges.edge_value,
        py::arg("truncation") = edges.truncation, py::arg("sparse_uniqueness") = sparse.uniqueness,
        py::arg("sparse_lr") = sparse.lr_tolerance, py::arg("asw") = py::none(),
        py::arg("speckle_size") = py::none(),
        py::arg("speckle_range") = stereo::speckle::kDefaultRange, py::arg("threads") = 0,
        "Match a pair with (method, engine) of stereo.matchers(); engine None: fast where the "
        "method has it (the pipeline's CPU engine, bit-exact with model), else model; threads: "
        "engine fast's worker threads, 0 = every core (the GIL is released while matching). The "
        "other defaults are stereo match's (census where the method and engine have it, stage 6 "
        "with the cost's ratio and "
        "tolerance, sub-pixel, the speckle filter). Returns a dict: disparity (uint8 labels), "
        "valid (bool), and for the methods with stage 6 disparity_px (float32, NaN invalid), "
        "fixed (int16, x16), reason, certainty; subpixel (sparse), vertical (2-D methods), "
        "counts. cost: None = the method's default. validation=False: plain winners, as "
        "--no-validation. uniqueness / lr_check / subpixel / speckle_size: None = the default; a "
        "value turns that step on with it (subpixel=False, speckle_size=0: off). asw: a dict of "
        "method asw's options (diameter, response, shape, continuity, right_weights, separable, "
        "threads), defaults as stereo match --aggregation asw.");

    // Static: pybind11 keeps the pointer.
    static const std::string evaluate_doc =
        "Middlebury scores of a float disparity against ground truth / gt_scale (0 = unknown), "
        "the same dict as `stereo eval --json`; masks are uint8 with 255 = scored. A ground "
        "truth whose largest value is more than " +
        std::to_string(static_cast<int>(stereo::io::kGroundTruthRangeFactor)) +
        "x the map's is refused (ValueError: wrong gt_scale?) unless any_gt_range=True.";
    m.def("evaluate", &evaluate, py::arg("disparity"), py::arg("ground_truth"), py::kw_only(),
          py::arg("threshold") = 1.0, py::arg("nonocc") = py::none(), py::arg("all") = py::none(),
          py::arg("disc") = py::none(), py::arg("zero_is_invalid") = true,
          py::arg("gt_scale") = 1.0, py::arg("any_gt_range") = false, evaluate_doc.c_str());

    m.def("fuzzy_decision", &fuzzy_decision, py::arg("left"), py::arg("centre"), py::arg("right"),
          "The fuzzy obstacle-avoidance decision on three window occupancies in [0, 1] "
          "(stereo fis).");

#ifdef STEREO_WITH_RTL
    m.def(
        "cosim_configs",
        [] {
            std::vector<std::string> names;
            for (const stereo::sim::TopConfig* c : stereo::sim::all_top_configs()) {
                names.push_back(c->name);
            }
            return names;
        },
        "The names of every Verilated stereo_top configuration of this build, of every cost and "
        "family (small, small-lcdm, small-census, the lanes, lean and FPGA cores); cosim() runs "
        "the smallest one of the pair's cost that covers it.");
    m.def(
        "cosim",
        [](const py::object& left, const py::object& right, int ndisp, int window, double sigma,
           bool ca, std::optional<std::string> cost_name, int min_disp, bool validation,
           std::optional<int> uniqueness, std::optional<int> lr_check, std::optional<bool> subpixel,
           double stall, double gap, std::uint32_t seed, const std::string& trace,
           std::optional<std::pair<int, int>> size, int lanes, std::optional<int> max_min_disp,
           bool lean, const std::string& cache) {
            // stereo cosim's defaults: stereo match's, without the speckle filter (not in the
            // core).
            const std::string cost =
                cost_name.value_or(std::string(stereo::catalogue::default_cost("pipeline", "rtl")));
            const Overrides keywords{cost,
                                     validation,
                                     uniqueness,
                                     lr_check,
                                     subpixel,
                                     0,
                                     stereo::speckle::kDefaultRange};
            std::optional<stereo::sim::CoreRequest> core;
            if (size) {
                core.emplace();
                core->width = size->first;
                core->height = size->second;
                core->ndisp = ndisp;
                core->window = window;
                core->cost = cost;
                core->lanes = lanes;
                core->max_min_disp = max_min_disp.value_or(
                    std::max(stereo::table::kDefaultMaxMinDisp, std::abs(min_disp)));
                core->lean = lean;
                core->trace = !trace.empty();
            } else if (lanes != 0 || max_min_disp || lean || !cache.empty()) {
                throw std::invalid_argument(
                    "lanes, max_min_disp, lean and cache choose a core built on demand: give "
                    "size=(width, height) too");
            }
            return cosim(
                left, right,
                match_options("pipeline", "model", ndisp, window, sigma, ca, min_disp, keywords, 0,
                              "horizontal", kEdges.log_window, kEdges.log_sigma, kEdges.edge_value,
                              kEdges.truncation, kSparse.uniqueness, kSparse.lr_tolerance),
                stall, gap, seed, trace, core, cache);
        },
        py::arg("left"), py::arg("right"), py::kw_only(), py::arg("ndisp") = 16,
        py::arg("window") = 5, py::arg("sigma") = defaults.sigma, py::arg("ca") = true,
        py::arg("cost") = py::none(), py::arg("min_disp") = 0, py::arg("validation") = true,
        py::arg("uniqueness") = py::none(), py::arg("lr_check") = py::none(),
        py::arg("subpixel") = py::none(), py::arg("stall") = 0.0, py::arg("gap") = 0.0,
        py::arg("seed") = 1u, py::arg("trace") = "", py::arg("size") = py::none(),
        py::arg("lanes") = 0, py::arg("max_min_disp") = py::none(), py::arg("lean") = false,
        py::arg("cache") = "",
        "Stream the pair through the Verilated stereo_top (random output stalls and input gaps) "
        "and compare it with the model. Defaults as stereo cosim: stereo match's cost and stage "
        "6, 16 labels, window 5, no speckle filter (not in the core). Returns a dict with "
        "mismatches, cycles, config and the RTL's "
        "stage-6 arrays. size=(W, H) (with lanes, max_min_disp, lean, cache) co-simulates a core "
        "of that size, ndisp, window and cost Verilated on demand into the cache "
        "(~/.cache/stereo/cosim) the first time.");
#endif
}

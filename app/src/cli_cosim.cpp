// `stereo cosim LEFT RIGHT [options]`: stream a pair through the Verilated stereo_top and compare
// every output pixel with the golden model. Exit 0 when they agree, 3 when any pixel differs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_cosim_options.hpp"
#include "cli_matcher_options.hpp"
#include "cli_progress.hpp"
#include "hier_top_sim.hpp"
#include "on_demand.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"
#include "stereo_top_sim.hpp"

namespace stereo::cli {
namespace {

std::string config_text(const sim::TopConfig& config) {
    return std::to_string(config.width) + "x" + std::to_string(config.height) + ", " +
           std::to_string(config.ndisp) + " disparities, window " + std::to_string(config.window);
}

// The --diff map: 0 where RTL and model agree, kDiffOther where only the reason or the
// certainty differs, kDiffDisparity where the disparity does.
constexpr std::uint8_t kDiffOther = 128;
constexpr std::uint8_t kDiffDisparity = 255;
// The mismatching pixels (first in raster order) whose stage outputs the localisation compares.
constexpr std::size_t kWatchedPixels = 16;

cv::Mat grey_image(const std::vector<std::uint8_t>& values, int width, int height) {
    cv::Mat image(height, width, CV_8UC1);
    std::copy(values.begin(), values.end(), image.ptr<std::uint8_t>(0));
    return image;
}

// Compares the model's stage outputs with the probe build's at the watched pixels, stage by
// stage in pipeline order: the first stage that differs anywhere is where the mismatch starts.
nlohmann::json localise(const sim::CoreRequest& request, const std::filesystem::path& cache,
                        const sim::CoreParams& core, const io::ImagePair& pair,
                        const MatchParams& params, const std::vector<sim::InputBeat>& beats,
                        const std::vector<std::pair<int, int>>& watched) {
    const auto model = stage_values_at(pair.left, pair.right, params, watched);
    const auto rtl = sim::probe_stages(request, cache, core, beats, watched, std::cerr);
    const std::vector<std::string> stages = sim::probed_stages();
    for (std::size_t s = 0; s < stages.size(); ++s) {
        for (std::size_t n = 0; n < watched.size(); ++n) {
            const std::vector<std::uint16_t>& expected = s == 0   ? model[n].aggregate
                                                         : s == 1 ? model[n].rule1
                                                                  : model[n].rule2;
            if (!rtl[n].seen[s]) {
                return {{"stage", stages[s]},
                        {"x", watched[n].first},
                        {"y", watched[n].second},
                        {"problem", "the stage's output never showed the pixel"},
                        {"pixels_watched", watched.size()}};
            }
            for (std::size_t k = 0; k < expected.size(); ++k) {
                if (expected[k] != rtl[n].values[s][k]) {
                    return {{"stage", stages[s]},
                            {"x", watched[n].first},
                            {"y", watched[n].second},
                            {"label", k},
                            {"model", expected[k]},
                            {"rtl", rtl[n].values[s][k]},
                            {"pixels_watched", watched.size()}};
                }
            }
        }
    }
    return {{"stage", "after " + stages.back() + " (wta or stage 6)"},
            {"pixels_watched", watched.size()}};
}

std::string localisation_text(const nlohmann::json& localisation) {
    if (localisation.contains("unavailable")) {
        return "no stage localisation: " + localisation["unavailable"].get<std::string>();
    }
    const std::string stage = localisation["stage"].get<std::string>();
    const std::string watched =
        std::to_string(localisation["pixels_watched"].get<std::size_t>()) + " mismatching pixels";
    if (localisation.contains("label")) {
        return "the first stage that differs is " + stage + ": at (" +
               std::to_string(localisation["x"].get<int>()) + ", " +
               std::to_string(localisation["y"].get<int>()) + ") label " +
               std::to_string(localisation["label"].get<int>()) + " the model gives " +
               std::to_string(localisation["model"].get<int>()) + ", the RTL " +
               std::to_string(localisation["rtl"].get<int>()) + " (earlier stages agree at the " +
               watched + " watched)";
    }
    if (localisation.contains("problem")) {
        return "stage " + stage + ": " + localisation["problem"].get<std::string>();
    }
    return "the probed stages agree at the " + watched + " watched: the difference starts " + stage;
}

// The core --size and its companions ask for (NDISP, WINDOW and COST from the matching options).
sim::CoreRequest core_request(const CosimOptions& options, const MatchParams& params) {
    static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
    std::smatch parts;
    if (!std::regex_match(options.size, parts, pattern)) {
        throw std::invalid_argument("--size must be WIDTHxHEIGHT, got '" + options.size + "'");
    }
    sim::CoreRequest request;
    request.width = std::stoi(parts[1]);
    request.height = std::stoi(parts[2]);
    request.ndisp = params.ndisp;
    request.window = params.window;
    request.cost = params.cost;
    request.lanes = options.lanes;
    request.max_min_disp = options.max_min_disp >= 0
                               ? options.max_min_disp
                               : std::max(table::kDefaultMaxMinDisp, std::abs(params.min_disp));
    request.lean = options.lean;
    request.trace = !options.trace.empty();
    request.threads = options.sim_threads;
    return request;
}

// The checks of the options that need no image: probabilities, counts, outputs.
void check_options(const CosimOptions& options) {
    io::check_outputs_distinct({options.output, options.trace, options.diff},
                               {options.left, options.right});
    for (const std::string& output : {options.output, options.trace, options.diff}) {
        if (!output.empty()) {
            io::check_writable_location(output);
        }
    }
    // -o's format by its extension: an unknown one is refused here, before any work.
    io::output_encoding(options.output, io::DisparityEncoding::scaled);
    if (!options.trace.empty()) {
        sim::check_trace_path(options.trace);  // .fst only: refused before any work
    }
}

// The core a run streams through: a configuration of this build, or one built on demand.
struct Core {
    std::optional<sim::CoreRequest> request;  // on demand
    std::optional<sim::TopConfig> demanded;   // on demand: its configuration
    const sim::TopConfig* config = nullptr;
    std::filesystem::path runner;  // on demand: the built runner
    std::filesystem::path cache;
};

Core choose_core(const CosimOptions& options, const MatchParams& params, int width, int height) {
    const bool on_demand = !options.size.empty();
    if (!on_demand && (options.lanes != 0 || options.max_min_disp != -1 || options.lean ||
                       !options.cache.empty() || options.sim_threads != 1)) {
        throw std::invalid_argument(
            "--lanes, --max-min-disp, --lean, --cache and --sim-threads choose a core built on "
            "demand: give --size WxH too");
    }
    Core core;
    core.cache =
        options.cache.empty() ? sim::default_cache_folder() : std::filesystem::path(options.cache);
    if (on_demand) {
        core.request = core_request(options, params);
        core.demanded = sim::on_demand_config(*core.request);
        sim::check_fits(*core.request, width, height, params.min_disp);
        if (options.reset_at >= width * height) {
            throw std::invalid_argument("--reset-at must be below the frame's " +
                                        std::to_string(width * height) + " beats");
        }
        core.runner = sim::ensure_runner(*core.request, core.cache, std::cerr);
        core.config = &*core.demanded;
        return core;
    }
    core.config = sim::covering_config(width, height, params.ndisp, params.window, params.min_disp,
                                       params.cost);
    if (core.config == nullptr) {
        const sim::TopConfig& largest = sim::largest_config(params.cost);
        throw std::invalid_argument(
            "no co-simulation model covers " + std::to_string(width) + "x" +
            std::to_string(height) + " with ndisp " + std::to_string(params.ndisp) + ", window " +
            std::to_string(params.window) + " and min_disp " + std::to_string(params.min_disp) +
            "; the largest built is " + config_text(largest) +
            " (use --downscale or --crop, or --size WxH to build a core on demand)");
    }
    return core;
}

// The ASW core of this build that runs the pair (no cores on demand).
Core asw_core(const CosimOptions& options, const MatchConfig& match_config, int width, int height) {
    if (!options.size.empty() || options.lanes != 0 || options.max_min_disp != -1 || options.lean) {
        throw std::invalid_argument(
            "--method asw runs the built ASW cores: --size, --lanes, --max-min-disp and --lean "
            "are for --method pipeline");
    }
    Core core;
    core.config = &sim::asw_top_config(width, height, match_config.pipeline, match_config.asw);
    return core;
}

// The frames' pixels against the model's: the count, the first ten, and for the first frame
// with a mismatch its map (--diff) and the pixels the localisation watches.
struct Comparison {
    std::size_t mismatches = 0;
    nlohmann::json first = nlohmann::json::array();
    std::vector<std::uint8_t> diff;
    std::vector<std::pair<int, int>> watched;
    int diff_frame = -1;

    void compare(const ValidatedDisparity& rtl, const ValidatedDisparity& expected, int frame) {
        for (int y = 0; y < rtl.height; ++y) {
            for (int x = 0; x < rtl.width; ++x) {
                const auto i = rtl.index(x, y);
                if (rtl.fixed[i] == expected.fixed[i] && rtl.reason[i] == expected.reason[i] &&
                    rtl.certainty[i] == expected.certainty[i]) {
                    continue;
                }
                if (diff_frame == -1 || diff_frame == frame) {
                    diff_frame = frame;
                    diff[i] = rtl.fixed[i] != expected.fixed[i] ? kDiffDisparity : kDiffOther;
                    if (watched.size() < kWatchedPixels) {
                        watched.emplace_back(x, y);
                    }
                }
                if (mismatches++ < 10) {
                    auto fields = [i](const ValidatedDisparity& v) {
                        return nlohmann::json{{"fixed", v.fixed[i]},
                                              {"reason", v.reason[i]},
                                              {"certainty", v.certainty[i]}};
                    };
                    first.push_back({{"frame", frame},
                                     {"x", x},
                                     {"y", y},
                                     {"model", fields(expected)},
                                     {"rtl", fields(rtl)}});
                }
            }
        }
    }
};

// What streaming the frames gave.
struct Streamed {
    sim::StreamResult last;  // the last frame's
    std::uint64_t total_cycles = 0;
    double seconds = 0.0;
    std::string failure;  // a stall or a protocol error ended the run
};

// Every frame: optionally the first beats of it and a reset in the middle, then the whole frame,
// under the frame's own traffic seed; every pixel compared with the model. The last frame's
// output goes to -o.
Streamed stream_frames(const CosimOptions& options, sim::TopSim& sim,
                       const std::vector<sim::InputBeat>& beats,
                       const sim::CoreParams& frame_params, const ValidatedDisparity& expected,
                       Comparison& comparison) {
    const int width = expected.width;
    const int height = expected.height;
    const auto output_encoding = io::output_encoding(options.output, io::DisparityEncoding::scaled);
    Streamed out;
    const auto start = std::chrono::steady_clock::now();
    const ProgressBar progress("cosim", options.frames);  // stderr, only on a terminal
    for (int frame = 0; frame < options.frames; ++frame) {
        progress.update(frame, std::to_string(comparison.mismatches) + " mismatches");
        const sim::Traffic traffic{options.gap, options.stall,
                                   options.seed + static_cast<std::uint32_t>(frame)};
        if (options.reset_at >= 0) {
            const std::vector<sim::InputBeat> part(beats.begin(), beats.begin() + options.reset_at);
            // Stop once a quarter of them came out (or the cycle budget ends): the reset then
            // lands with beats still inside the pipeline. --reset-at 0: a reset before any beat.
            if (!part.empty()) {
                out.total_cycles += sim.stream(part, std::max<std::size_t>(1, part.size() / 4),
                                               traffic, 10 * part.size() + 10000)
                                        .cycles;
            }
            sim.reset();
            sim.set_params(frame_params);
        }
        out.last = sim.stream(beats, beats.size(), traffic, 100 * beats.size() + 100000);
        out.total_cycles += out.last.cycles;
        // A stall or a protocol error ends the run; the waveform up to it is still written.
        if (!out.last.completed) {
            out.failure = "the core stalled in frame " + std::to_string(frame) + ": " +
                          std::to_string(out.last.outputs.size()) + " of " +
                          std::to_string(beats.size()) + " outputs arrived";
            break;
        }
        if (!out.last.protocol_error.empty()) {
            out.failure = "AXI4-Stream protocol error: " + out.last.protocol_error;
            break;
        }
        const ValidatedDisparity rtl = sim::assemble_validated(out.last.outputs, 0, width, height);
        comparison.compare(rtl, expected, frame);
        if (frame + 1 == options.frames && !options.output.empty()) {
            // The format by the extension, as `stereo match -o` (PFM: stage 6's pixels).
            io::write_file_atomic(
                options.output, io::encode_disparity(rtl, output_encoding, frame_params.match.ndisp,
                                                     1, options.output));
        }
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

// What every --json summary reports of the run as asked (its frames, the reset, the traffic) and
// the core's sticky status bits at its end.
nlohmann::json run_json(const CosimOptions& options, unsigned status) {
    return {{"frames", options.frames}, {"reset_at", options.reset_at}, {"seed", options.seed},
            {"stall", options.stall},   {"gap", options.gap},           {"status", status}};
}

// The --json summary or the text report of a run.
struct Run {
    const MatchParams& params;
    int width;
    int height;
    std::size_t pixels;  // per frame
    const sim::TopConfig& config;
    double model_seconds;  // the golden model's time for one frame
};

void report(const CosimOptions& options, const Run& run, const Streamed& streamed,
            const Comparison& comparison, const nlohmann::json& localisation) {
    const MatchParams& params = run.params;
    const sim::StreamResult& result = streamed.last;
    const double per_pixel = static_cast<double>(result.cycles) / run.pixels;
    const double cycles_per_second = streamed.total_cycles / streamed.seconds;
    const int uniqueness = params.validation.uniqueness ? params.validation.uniqueness_ratio : -1;
    const int lr_check = params.validation.left_right ? params.validation.lr_tolerance : -1;
    if (options.json) {
        nlohmann::json summary = pipeline_json(run.width, run.height, params);
        summary.update(run_json(options, result.status));
        summary.update({
            {"mismatches", comparison.mismatches},
            {"cycles", result.cycles},
            {"total_cycles", streamed.total_cycles},
            {"pixels", run.pixels},
            {"pixels_compared", run.pixels * static_cast<std::size_t>(options.frames)},
            {"cycles_per_pixel", per_pixel},
            {"first_mismatches", comparison.first},
            {"config", run.config.name},
            {"uniqueness", uniqueness},
            {"lr_check", lr_check},
            {"sim_seconds", streamed.seconds},
            {"sim_cycles_per_second", cycles_per_second},
            // The golden model's time for one frame, and the RTL's per frame against it.
            {"model_seconds", run.model_seconds},
            {"sim_to_model_time", streamed.seconds / options.frames / run.model_seconds},
        });
        if (comparison.mismatches != 0) {
            summary["localisation"] = localisation;
        }
        std::cout << io::versioned(summary).dump() << '\n';
        return;
    }
    std::printf(
        "%dx%d ndisp %d window %d ca %s min-disp %d uniqueness %d lr-check %d subpixel %s on "
        "the '%s' model (%s), seed %u, stall %.2f, gap %.2f\n%zu mismatching pixels "
        "of %zu (fixed, reason and certainty compared); %llu cycles, %.3f cycles/pixel; "
        "simulated at "
        "%.0f cycles/s\n",
        run.width, run.height, params.ndisp, params.window, params.use_ca ? "on" : "off",
        params.min_disp, uniqueness, lr_check, params.validation.subpixel ? "on" : "off",
        run.config.name.c_str(), config_text(run.config).c_str(), options.seed, options.stall,
        options.gap, comparison.mismatches, run.pixels,
        static_cast<unsigned long long>(result.cycles), per_pixel, cycles_per_second);
    if (options.frames > 1 || options.reset_at >= 0) {
        std::printf("%d frames, reset after %d beats of each (-1 = none): %zu mismatches\n",
                    options.frames, options.reset_at, comparison.mismatches);
    }
    for (const auto& m : comparison.first) {
        std::printf(
            "  mismatch in frame %d at (%d, %d): model fixed %d reason %d certainty %d, rtl "
            "fixed %d reason %d certainty %d\n",
            m["frame"].get<int>(), m["x"].get<int>(), m["y"].get<int>(),
            m["model"]["fixed"].get<int>(), m["model"]["reason"].get<int>(),
            m["model"]["certainty"].get<int>(), m["rtl"]["fixed"].get<int>(),
            m["rtl"]["reason"].get<int>(), m["rtl"]["certainty"].get<int>());
    }
}

// Where the first mismatching frame's difference starts: the probe build of the same core.
nlohmann::json localisation_of(const Core& core, const sim::CoreParams& frame_params,
                               const io::ImagePair& pair, const MatchParams& params,
                               const std::vector<sim::InputBeat>& beats,
                               const Comparison& comparison) {
    if (comparison.mismatches == 0) {
        return {};
    }
    if (!core.request) {
        return {{"unavailable",
                 "stage localisation runs on a core built on demand: repeat with --size WxH"}};
    }
    if (core.request->lanes != 0 && core.request->lanes != core.request->ndisp) {
        return {{"unavailable", "stage localisation needs --lanes equal to --ndisp"}};
    }
    return localise(*core.request, core.cache, frame_params, pair, params, beats,
                    comparison.watched);
}

// `stereo cosim --method hierarchical`: the hierarchical search's whole core (stereo_hier_top)
// on the pair streamed as a steady rig, the host's PlaneTracker in the loop writing each next
// plane (docs/hierarchical.md "The whole core"). Every frame's beats and vertical offsets against
// the pass along that frame's setting (sim::hier_pass_expected), its statistics registers and
// setting against match_frame's with the model's own tracker.
void run_cosim_hierarchical(const CosimOptions& given) {
    CosimOptions options = given;
    options.frames = given.frames > 0 ? given.frames : kHierarchicalFrames;
    const MatchConfig match_config = options.matcher.resolved();
    const MatchParams& params = match_config.pipeline;
    if (params.min_disp != 0) {
        throw std::invalid_argument(
            "--method hierarchical: the pass searches disparities 0 .. ndisp - 1 (--min-disp 0)");
    }
    if (!options.size.empty() || !options.trace.empty() || !options.diff.empty()) {
        throw std::invalid_argument(
            "--method hierarchical runs the built stereo_hier_top: --size, --trace and --diff "
            "are for --method pipeline");
    }
    constexpr sim::HierTopLimits limits = sim::kHierTopLimits;
    hierarchical::Params search;
    search.ndisp = params.ndisp;
    search.vrange = limits.v_max - limits.v_min + 1;
    search.cost = params.cost;
    search.use_ca = params.use_ca;
    search.field_level = {params.window, params.sigma};
    search.validation = params.validation;
    sim::check_hier_top(search);  // before any file: the size comes with the pair
    check_options(options);
    const io::ImagePair pair = load_core_pair(options);
    const int width = pair.left.width;
    const int height = pair.left.height;
    const sim::HierTopLimits core = sim::check_hier_top(search, width, height);
    if (options.reset_at >= width * height) {
        throw std::invalid_argument("--reset-at must be below the frame's " +
                                    std::to_string(width * height) + " beats");
    }
    const auto start = std::chrono::steady_clock::now();
    sim::HierTopRunOptions run_options;
    run_options.frames = options.frames;
    run_options.traffic = {options.gap, options.stall, options.seed};
    run_options.reset_at = options.reset_at;
    const sim::HierTopRun run = sim::run_hier_top(pair.left, pair.right, search, run_options);
    const double sim_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto expected = sim::hier_top_expected(pair.left, pair.right, search, options.frames);

    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    const auto in_pixels = [](std::int64_t value) {
        return static_cast<double>(value) / hierarchical::kPlaneOne;
    };
    const auto plane_json = [](const hierarchical::PlaneSetting& setting) {
        return nlohmann::json{{"a", setting.plane.a},
                              {"b", setting.plane.b},
                              {"c", setting.plane.c},
                              {"tolerance", setting.tolerance}};
    };
    std::size_t mismatches = 0;
    std::size_t statistics_mismatches = 0;  // frames whose statistics or setting differ
    nlohmann::json first = nlohmann::json::array();
    nlohmann::json per_frame = nlohmann::json::array();
    std::vector<std::string> lines;
    for (std::size_t f = 0; f < run.frames.size(); ++f) {
        const sim::HierTopFrame& rtl = run.frames[f];
        const sim::HierTopExpected& model = expected[f];
        const auto differing = sim::differing_pixels(rtl.output, model.output);
        mismatches += differing.size();
        const bool statistics_equal =
            rtl.statistics == model.statistics && rtl.setting == model.setting;
        statistics_mismatches += statistics_equal ? 0 : 1;
        for (const std::size_t p : differing) {
            if (first.size() >= 10) {
                break;
            }
            const auto fields = [p](const sim::HierPassOutput& o) {
                return nlohmann::json{{"fixed", o.validated.fixed[p]},
                                      {"reason", o.validated.reason[p]},
                                      {"certainty", o.validated.certainty[p]},
                                      {"vertical", o.vertical[p]}};
            };
            first.push_back({{"frame", f},
                             {"x", p % static_cast<std::size_t>(width)},
                             {"y", p / static_cast<std::size_t>(width)},
                             {"model", fields(model.output)},
                             {"rtl", fields(rtl.output)}});
        }
        const auto valid = std::count(rtl.output.validated.reason.begin(),
                                      rtl.output.validated.reason.end(), fx::kReasonValid);
        per_frame.push_back({{"frame", f},
                             {"plane", plane_json(rtl.setting)},
                             {"mismatching_pixels", differing.size()},
                             {"statistics_equal", statistics_equal},
                             {"inliers", rtl.statistics.count},
                             {"valid_pixels", valid},
                             {"cycles", rtl.cycles}});
        char line[256];
        std::snprintf(line, sizeof line,
                      "  frame %zu: plane v = %.4f + %.5f x + %.5f y (tolerance %.1f): %zu "
                      "mismatching pixels, statistics %s (%lld inliers), %lld valid, %llu cycles",
                      f, in_pixels(rtl.setting.plane.a), in_pixels(rtl.setting.plane.b),
                      in_pixels(rtl.setting.plane.c), in_pixels(rtl.setting.tolerance),
                      differing.size(), statistics_equal ? "equal" : "DIFFER",
                      static_cast<long long>(rtl.statistics.count), static_cast<long long>(valid),
                      static_cast<unsigned long long>(rtl.cycles));
        lines.emplace_back(line);
    }
    const sim::HierTopFrame& last = run.frames.back();
    if (!options.output.empty()) {
        const auto encoding = io::output_encoding(options.output, io::DisparityEncoding::scaled);
        io::write_file_atomic(
            options.output,
            io::encode_disparity(last.output.validated, encoding, params.ndisp, 1, options.output));
    }
    const double per_pixel = static_cast<double>(last.cycles) / static_cast<double>(pixels);
    if (options.json) {
        nlohmann::json summary = pipeline_json(width, height, params);
        summary.update(run_json(options, run.status));
        summary.update({{"method", catalogue::method(catalogue::Method::hierarchical).name},
                        {"config", std::string(core.config)},
                        {"plane", plane_json(last.setting)},
                        {"mismatches", mismatches},
                        {"statistics_mismatches", statistics_mismatches},
                        {"per_frame", per_frame},
                        {"pixels", pixels},
                        {"pixels_compared", pixels * run.frames.size()},
                        {"cycles", last.cycles},
                        {"total_cycles", run.total_clocks},
                        {"cycles_per_pixel", per_pixel},
                        {"first_mismatches", first},
                        {"sim_seconds", sim_seconds}});
        std::cout << io::versioned(summary).dump() << '\n';
    } else {
        std::printf(
            "%dx%d ndisp %d window %d: the hierarchical core (stereo_hier_top, %s) on a steady "
            "rig, the host's PlaneTracker writing each next plane, seed %u, stall %.2f, gap %.2f, "
            "reset after %d beats of each frame (-1 = none)\n",
            width, height, params.ndisp, params.window, std::string(core.config).c_str(),
            options.seed, options.stall, options.gap, options.reset_at);
        for (const std::string& line : lines) {
            std::printf("%s\n", line.c_str());
        }
        std::printf(
            "%zu mismatching pixels of %zu (fixed, reason, certainty and vertical offset "
            "compared, %d frame%s), %zu frame%s whose statistics or plane differ; last frame "
            "%llu cycles, %.3f cycles/pixel; %llu clocks in all\n",
            mismatches, pixels * run.frames.size(), options.frames, options.frames == 1 ? "" : "s",
            statistics_mismatches, statistics_mismatches == 1 ? "" : "s",
            static_cast<unsigned long long>(last.cycles), per_pixel,
            static_cast<unsigned long long>(run.total_clocks));
        for (const auto& m : first) {
            std::printf("  mismatch in frame %d at (%d, %d): model %s, rtl %s\n",
                        m["frame"].get<int>(), m["x"].get<int>(), m["y"].get<int>(),
                        m["model"].dump().c_str(), m["rtl"].dump().c_str());
        }
    }
    if (mismatches != 0 || statistics_mismatches != 0) {
        throw MismatchError(std::to_string(mismatches) + " pixels and " +
                            std::to_string(statistics_mismatches) +
                            " frames' statistics differ from the golden model's hierarchical core");
    }
}

void run_cosim(const CosimOptions& given) {
    if (given.method == catalogue::method(catalogue::Method::hierarchical).name) {
        run_cosim_hierarchical(given);
        return;
    }
    CosimOptions options = given;
    options.frames = given.frames > 0 ? given.frames : kPipelineFrames;
    // --method asw: the core with adaptive support weights (stereo_top ASW = 1), the separable
    // variant whose diameter is --window, against the model's.
    const bool asw = given.method == catalogue::method(catalogue::Method::asw).name;
    MatchConfig match_config = options.matcher.resolved();
    if (asw) {
        match_config.asw.diameter = match_config.pipeline.window;
        match_config.asw.separable = true;
    }
    const MatchParams& params = match_config.pipeline;
    // The expected map: the golden model, made (and its parameters checked) before any file.
    const auto model = matchers().create(given.method, "model", match_config);
    check_options(options);
    const io::ImagePair pair = load_core_pair(options);
    const int width = pair.left.width;
    const int height = pair.left.height;
    model->validate(width, height);
    const Core core = asw ? asw_core(options, match_config, width, height)
                          : choose_core(options, params, width, height);
    if (!options.trace.empty() && !core.config->traced) {
        throw std::invalid_argument(
            "--trace: the built configuration '" + core.config->name +
            "' has no tracing compiled in (configure with -DSTEREO_TRACE_CONFIGS=all, or give "
            "--size WxH for a core built on demand)");
    }

    // Stage 6's full output: fixed disparity, reason and certainty of every pixel.
    const auto model_start = std::chrono::steady_clock::now();
    const ValidatedDisparity expected = model->compute(pair.left, pair.right).validated;
    const double model_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - model_start).count();

    // The waveform goes to a temporary file beside the destination and replaces it only once
    // the run is over and the tracer closed (io::StagedOutput): a failed or killed run leaves an
    // existing trace as it was.
    std::optional<io::StagedOutput> trace_file;
    if (!options.trace.empty()) {
        trace_file.emplace(options.trace);
    }
    auto sim = core.request ? sim::make_runner_sim(*core.config, core.runner)
                            : sim::make_top_sim(*core.config);
    if (trace_file) {
        sim->trace_to(trace_file->path().string());
    }
    const auto beats = sim::frame_beats(pair.left, pair.right);
    if (options.reset_at >= static_cast<int>(beats.size())) {
        throw std::invalid_argument("--reset-at must be below the frame's " +
                                    std::to_string(beats.size()) + " beats");
    }
    const sim::CoreParams frame_params{width, height, params};
    sim->reset();
    sim->set_params(frame_params);
    Comparison comparison;
    comparison.diff.assign(static_cast<std::size_t>(width) * height, 0);
    const Streamed streamed =
        stream_frames(options, *sim, beats, frame_params, expected, comparison);
    sim.reset();  // closes the waveform
    if (trace_file) {
        trace_file->commit();
    }
    if (!streamed.failure.empty()) {
        throw std::runtime_error(streamed.failure);
    }
    if (!options.diff.empty()) {
        io::write_file_atomic(
            options.diff, io::encode_png(grey_image(comparison.diff, width, height), options.diff));
    }
    const nlohmann::json localisation =
        localisation_of(core, frame_params, pair, params, beats, comparison);
    report(options, {params, width, height, beats.size(), *core.config, model_seconds}, streamed,
           comparison, localisation);
    if (comparison.mismatches != 0) {
        if (!options.json) {
            std::printf("%s\n", localisation_text(localisation).c_str());
        }
        throw MismatchError(std::to_string(comparison.mismatches) +
                            " pixels differ from the golden model; " +
                            localisation_text(localisation));
    }
}

}  // namespace

void add_cosim_command(CLI::App& app) {
    const auto [command, options] = add_command<CosimOptions>(
        app, "cosim",
        "Stream a pair through the Verilated RTL and compare it with the golden model.", run_cosim);
    // The configurations this binary has (-DSTEREO_COSIM_CONFIGS, docs/gtkwave.md).
    std::string built = "Verilated configurations in this build (the smallest covering one runs):";
    for (const sim::TopConfig& config : sim::built_top_configs()) {
        built += "\n  " + config.name + ": " + config_text(config) + ", cost ad";
    }
    built += "\n  " + sim::lcdm_top_config().name + ": " + config_text(sim::lcdm_top_config()) +
             ", cost lcdm\n  " + sim::census_top_config().name + ": " +
             config_text(sim::census_top_config()) + ", cost census";
    // The census builds in the lean memory architecture (RECOMPUTE_COSTS) larger than the small
    // one are chosen for pairs it does not cover (full-census-lean with
    // -DSTEREO_COSIM_CONFIGS=full_census_lean).
    for (const sim::TopConfig& config : sim::census_recompute_top_configs()) {
        if (config.width > sim::census_top_config().width) {
            built +=
                "\n  " + config.name + ": " + config_text(config) + ", cost census, lean memory";
        }
    }
    built +=
        "\nMore: -DSTEREO_COSIM_CONFIGS=full, full_census_lean or "
        "-DSTEREO_COSIM_USER=WxH:NDISP:WINDOW (docs/gtkwave.md).";
    command->footer(built);
    add_cosim_options(*command, *options);
}

}  // namespace stereo::cli

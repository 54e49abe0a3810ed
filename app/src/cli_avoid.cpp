// `stereo avoid LEFT RIGHT [options]`: the obstacle-avoidance chain of thesis Sec. 4.1 on one
// pair, or on a sequence (two folders, or one list file) with one JSON line per frame.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"
#include "stereo_robot/bands.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/decision.hpp"
#include "stereo_robot/ground.hpp"
#include "stereo_robot/overlay.hpp"

namespace stereo::cli {

namespace {

namespace fs = std::filesystem;

// The threshold method has no angle; its overlay arrow points half-way into the chosen window.
constexpr double kThresholdArrowDeg = 20.0;

struct AvoidOptions {
    std::string left;
    std::string right;  // empty: LEFT is a list file
    std::string method = "fuzzy";
    std::string calib;
    std::optional<double> focal;
    std::optional<double> baseline;
    std::optional<double> safe_distance;
    std::optional<double> threshold;
    std::string overlay;
    bool json = false;
    int downscale = 1;
    MatcherOptions matcher;  // --ndisp, --window, --sigma; config.edges: the LoG options
    robot::ThresholdParams threshold_params;
    robot::FisParams fis;
    std::string ground = "fit";  // fit | off
    int threads = 0;             // row bands matched in parallel; 0 = every core
    robot::GroundRemoval ground_params;

    static constexpr std::string_view kName = "avoid";
    static constexpr std::string_view kDescription =
        "Obstacle avoidance (thesis Sec. 4.1): direction decision on a pair or sequence.";
};

// The camera geometry when one is given (--calib, or --focal and --baseline).
std::optional<robot::StereoGeometry> geometry_of(const AvoidOptions& o) {
    if (!o.calib.empty()) {
        return robot::load_calibration(o.calib);
    }
    if (o.focal && o.baseline) {
        return robot::StereoGeometry{*o.focal, *o.baseline};
    }
    return std::nullopt;
}

// The disparity threshold in pixels of the matched (possibly downscaled) images.
double pixel_threshold(const AvoidOptions& o) {
    if (o.threshold) {
        return *o.threshold;  // checked by its option: [0, 256], the labels any matcher has
    }
    if (!o.safe_distance) {
        throw std::invalid_argument("give --safe-distance Z (with a calibration) or --threshold T");
    }
    const auto geometry = geometry_of(o);
    if (!geometry) {
        throw std::invalid_argument(
            "missing calibration: --safe-distance needs --calib FILE or --focal F --baseline B");
    }
    return robot::disparity_threshold(*geometry, *o.safe_distance, o.downscale);
}

std::vector<robot::FramePair> frames(const AvoidOptions& o, bool& sequence) {
    if (o.right.empty()) {
        sequence = true;
        return robot::pairs_from_list(o.left);
    }
    const bool left_dir = fs::is_directory(o.left);
    const bool right_dir = fs::is_directory(o.right);
    if (left_dir != right_dir) {
        throw std::invalid_argument("LEFT and RIGHT must both be images or both be folders");
    }
    sequence = left_dir;
    if (sequence) {
        return robot::pairs_from_folders(o.left, o.right);
    }
    return {{o.left, o.right}};
}

nlohmann::json occupancy_json(const std::array<robot::WindowStats, 3>& stats) {
    return {stats[0].occupancy(), stats[1].occupancy(), stats[2].occupancy()};
}

struct FrameResult {
    nlohmann::json json;
    robot::OverlayInfo overlay;
};

// Each window's free distance as a disparity (docs/avoidance.md, safety rule); null when blocked.
nlohmann::json free_disparity_json(const std::array<robot::WindowStats, 3>& stats, double rate) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& window : stats) {
        const double d = window.free_disparity(rate);
        out.push_back(std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(nullptr));
    }
    return out;
}

FrameResult decide(const AvoidOptions& o, const DisparityMap& map, double threshold,
                   const robot::GroundModel* ground) {
    FrameResult out;
    const bool want_threshold = o.method == "threshold" || o.method == "both";
    const bool want_fuzzy = o.method == "fuzzy" || o.method == "both";
    if (want_threshold) {
        const auto d = robot::decide_threshold(map, threshold, o.matcher.config.pipeline.ndisp,
                                               o.threshold_params, ground);
        const double arrow = d.direction == robot::Direction::left    ? -kThresholdArrowDeg
                             : d.direction == robot::Direction::right ? kThresholdArrowDeg
                                                                      : 0.0;
        out.json["threshold"] = {
            {"decision", robot::to_string(d.direction)},
            {"certainty", d.certainty},
            {"safety_override", d.safety_override},
            {"free_disparity", free_disparity_json(d.stats, o.threshold_params.rate)},
            {"occupancy", occupancy_json(d.stats)},
            {"mean_disparity", {d.mean[0], d.mean[1], d.mean[2]}}};
        out.overlay = {{d.stats[0].occupancy(), d.stats[1].occupancy(), d.stats[2].occupancy()},
                       d.direction,
                       arrow,
                       "threshold"};
    }
    if (want_fuzzy) {
        robot::FisParams fis = o.fis;
        fis.rate = o.threshold_params.rate;  // one safety rate for both methods
        const auto d = robot::decide_fuzzy(map, threshold, fis, o.threshold_params.border, ground);
        out.json["fuzzy"] = {{"decision", robot::to_string(d.fis.decision)},
                             {"angle_deg", d.fis.angle_deg},
                             {"backwards", d.fis.backwards},
                             {"mamdani_angle_deg", d.fis.mamdani_angle_deg},
                             {"default_rule", d.fis.default_rule},
                             {"safety_override", d.safety_override},
                             {"occupancy", occupancy_json(d.stats)}};
        char caption[64];
        std::snprintf(caption, sizeof caption, "fuzzy %+.1f deg", d.fis.angle_deg);
        out.overlay = {{d.stats[0].occupancy(), d.stats[1].occupancy(), d.stats[2].occupancy()},
                       d.fis.decision,
                       d.fis.angle_deg,
                       caption};
    }
    // The chosen method's decision at the top level (fuzzy when both are run).
    const auto& main = out.json.contains("fuzzy") ? out.json["fuzzy"] : out.json["threshold"];
    out.json["decision"] = main["decision"];
    return out;
}

void print_text(const std::string& name, const nlohmann::json& frame) {
    std::printf("%s: %s", name.c_str(), frame["decision"].get<std::string>().c_str());
    if (frame.contains("fuzzy")) {
        std::printf(" (fuzzy: angle %.2f deg, backwards %.3f)",
                    frame["fuzzy"]["angle_deg"].get<double>(),
                    frame["fuzzy"]["backwards"].get<double>());
    }
    if (frame.contains("threshold")) {
        std::printf(" (threshold: %s, certainty %.3f)",
                    frame["threshold"]["decision"].get<std::string>().c_str(),
                    frame["threshold"]["certainty"].get<double>());
    }
    std::printf(", occupancy %s, %.1f ms\n", frame["occupancy"].dump().c_str(),
                frame["ms"].get<double>());
}

void check_options(const AvoidOptions& o) {
    robot::check_fraction(o.threshold_params.rate, "--rate");
    robot::check_fraction(o.fis.backwards_threshold, "--backwards-threshold");
}

// One frame: the edge front end on row bands, the ground fit, the decision, its report line and
// overlay.
void avoid_frame(const AvoidOptions& o, const std::filesystem::path& left_path,
                 const io::ImagePair& pair, std::chrono::steady_clock::time_point start,
                 int threads, double threshold, bool sequence,
                 const std::optional<robot::StereoGeometry>& geometry,
                 std::optional<robot::SequenceWriter>& writer) {
    // The registry's edge matcher, run on row bands in parallel (bit-exact, bands.hpp).
    const MatchConfig config = o.matcher.resolved();
    MatchParams params = config.pipeline;
    params.use_ca = false;
    const DisparityMap map =
        robot::edge_match_bands(pair.left, pair.right, params, config.edges, threads);
    std::optional<robot::GroundModel> ground;
    if (geometry && o.ground == "fit") {
        ground = robot::fit_ground(
            map, o.matcher.config.pipeline.ndisp,
            robot::avoidance_camera(*geometry, o.downscale, map.width, map.height),
            o.ground_params);
    }
    const robot::GroundModel* ground_ptr = ground ? &*ground : nullptr;
    FrameResult result = decide(o, map, threshold, ground_ptr);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    nlohmann::json& frame = result.json;
    frame["frame"] = left_path.filename().string();
    frame["threshold_px"] = threshold;
    frame["occupancy"] = result.overlay.occupancy;
    frame["ms"] = elapsed.count();
    frame["ground"] = ground ? nlohmann::json{{"slope", ground->line.slope},
                                              {"intercept", ground->line.intercept}}
                             : nlohmann::json(nullptr);
    // A single pair's overlay is written before its line: a failed write prints nothing.
    if (!o.overlay.empty()) {
        result.overlay.caption = left_path.filename().string() + " " + result.overlay.caption;
        const cv::Mat picture =
            robot::draw_overlay(io::to_bgr(pair.left), map, threshold, o.threshold_params.border,
                                result.overlay, ground_ptr);
        if (writer) {
            writer->add(picture);
        } else {
            io::write_png(o.overlay, picture);
        }
    }
    if (sequence || o.json) {
        std::cout << io::versioned(frame).dump() << std::endl;
    } else {
        print_text(left_path.filename().string(), frame);
    }
    if (sequence) {
        check_stdout();  // a stream nobody receives stops at its first line
    }
}

void run_avoid(const AvoidOptions& o) {
    check_options(o);
    const auto geometry = geometry_of(o);
    const int threads = o.threads == 0 ? robot::default_threads() : o.threads;
    // The edge front end; it checks its parameters once the image size is known.
    const auto matcher = matchers().create("edges", "model", o.matcher.resolved());
    const double threshold = pixel_threshold(o);
    bool sequence = false;
    const auto pairs = frames(o, sequence);
    // Every file it reads: the list file or the two folders (all they hold), the calibration
    // and every frame (a list names frames anywhere).
    io::Inputs inputs{.files = {o.left, o.right, o.calib}};
    for (const auto& [left, right] : pairs) {
        inputs.files.push_back(left);
        inputs.files.push_back(right);
        // Every frame file before the first line is printed (docs/cli.md).
        io::check_image_file(left);
        io::check_image_file(right);
    }
    io::check_outputs({o.overlay}, inputs);
    if (!o.overlay.empty()) {
        robot::check_overlay_path(o.overlay, sequence);
        io::check_writable_location(o.overlay);
    }
    std::optional<robot::SequenceWriter> writer;
    if (sequence && !o.overlay.empty()) {
        writer.emplace(o.overlay, 10.0);
    }

    // The next pair is read and decoded on another thread while this one is matched.
    const auto load = [&](std::size_t i) {
        return io::load_pair(pairs[i].first, pairs[i].second, o.downscale);
    };
    std::future<io::ImagePair> next = std::async(std::launch::async, load, 0);
    for (std::size_t index = 0; index < pairs.size(); ++index) {
        const auto& [left_path, right_path] = pairs[index];
        const auto start = std::chrono::steady_clock::now();
        const io::ImagePair pair = next.get();
        if (index + 1 < pairs.size()) {
            next = std::async(std::launch::async, load, index + 1);
        }
        matcher->validate(pair.left.width, pair.left.height);
        avoid_frame(o, left_path, pair, start, threads, threshold, sequence, geometry, writer);
    }
    if (writer) {
        writer->finish();
    }
}

}  // namespace

void add_avoid_command(CLI::App& app) {
    const auto [command, o] = add_command<AvoidOptions>(app, run_avoid);
    command->add_option("LEFT", o->left, "Left image, folder of left images, or a list file")
        ->required();
    command->add_option("RIGHT", o->right,
                        "Right image or folder (files paired by name); omit for a list file");
    command->add_option("--method", o->method, "threshold, fuzzy, or both")
        ->check(CLI::IsMember({"threshold", "fuzzy", "both"}))
        ->capture_default_str();
    auto* calib = command->add_option("--calib", o->calib,
                                      "Calibration file with P0/P1 projection matrices (KITTI)");
    auto* focal = command->add_option("--focal", o->focal, "Focal length in pixels (full size)");
    auto* baseline = command->add_option("--baseline", o->baseline, "Baseline, metres");
    calib->excludes(focal)->excludes(baseline);
    auto* safe = command->add_option("--safe-distance", o->safe_distance,
                                     "Safety distance Z, metres: T = f B / Z");
    auto* threshold =
        command->add_option("--threshold", o->threshold, "Disparity threshold T in pixels")
            ->check(checks::real_in(0, 256));
    safe->excludes(threshold);
    command->add_option("--overlay", o->overlay,
                        "Overlay PNG; for a sequence a PNG contact sheet or an MJPG .avi");
    command->add_flag("--json", o->json, "One JSON object per frame (always for sequences)");
    add_downscale_option(*command, o->downscale);
    // The edge front end has no CA rules: no --no-ca.
    add_matcher_options(*command, o->matcher, MatcherChoice::fixed,
                        {.ndisp = true, .no_ca = false});
    edge_frontend::EdgeParams& edges = o->matcher.config.edges;
    add_number_options(
        *command,
        {{"--log-window", &edges.log_window, "Odd LoG smoothing kernel side"},
         {"--log-sigma", &edges.log_sigma, "LoG Gaussian sigma"},
         {"--edge-value", &edges.edge_value, "Intensity of superimposed edges"},
         {"--truncation", &edges.truncation, "Truncated-AD limit, of 765"},
         {"--rate", &o->threshold_params.rate,
          "Threshold method: centre fraction below which it goes straight"},
         {"--border", &o->threshold_params.border, "Excluded border, pixels"},
         {"--backwards-threshold", &o->fis.backwards_threshold,
          "Fuzzy: back off when 'move backwards' exceeds this"},
         {"--forward-band", &o->fis.forward_band, "Fuzzy: |angle| up to this (deg) is no turn"},
         {"--ground-tolerance", &o->ground_params.fit.tolerance,
          "Ground band, pixels of disparity above the v-disparity line", checks::real_in(0, 256)},
         {"--max-height", &o->ground_params.max_height,
          "Metres above the ground: higher pixels are not obstacles",
          checks::real_in(0, 1e6, checks::Bound::exclusive)}});
    command->add_option("--threads", o->threads, "Row bands matched in parallel; 0: every core")
        ->capture_default_str()
        ->check(thread_count());
    command
        ->add_option("--ground", o->ground,
                     "Ground removal: fit (v-disparity line; needs a calibration) or off")
        ->check(CLI::IsMember({"fit", "off"}))
        ->capture_default_str();
}

}  // namespace stereo::cli

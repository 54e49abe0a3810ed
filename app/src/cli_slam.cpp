// `stereo slam SEQ_DIR [options]`: stereo-vision SLAM of thesis Sec. 4.2 on a KITTI-layout or
// EuRoC-layout sequence: trajectory, occupancy map and, with ground-truth poses, its errors.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "cli_progress.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/stages.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"
#include "stereo_robot/bands.hpp"
#include "stereo_robot/slam/dataset.hpp"
#include "stereo_robot/slam/evaluation.hpp"
#include "stereo_robot/slam/pipeline.hpp"

namespace stereo::cli {

namespace {

namespace fs = std::filesystem;
namespace slam = robot::slam;

constexpr int kRpeGap = 10;  // frames: the "per 10 frames"

struct SlamOptions {
    std::string sequence;
    std::string layout = "auto";
    std::string calib;
    std::string frames;
    std::string map;
    std::string trajectory;
    std::string vdisparity;
    int vdisparity_frame = 0;
    bool json = false;
    int downscale = 1;
    int ca_passes = 1;
    double disparity_offset = 0.0;  // full-size pixels (docs/slam.md §2)
    slam::SlamParams params;
    MatcherOptions matcher;  // --ndisp, --window, --sigma of the front end (params.frontend)
    const CLI::Option* ba_window_option = nullptr;  // given: above the run's frames is an error

    static constexpr std::string_view kName = "slam";
    static constexpr std::string_view kDescription =
        "Stereo SLAM (thesis Sec. 4.2): trajectory and occupancy map of a sequence.";
};

nlohmann::json errors_json(const slam::TrajectoryErrors& e) {
    return {{"ate_rmse_m", e.ate_rmse_m},
            {"ate_percent", e.ate_percent},
            {"rpe_translation_percent", e.rpe_translation_percent},
            {"rpe_rotation_deg", e.rpe_rotation_deg},
            {"rpe_gap_frames", e.gap},
            {"rpe_pairs", e.rpe_pairs}};
}

nlohmann::json drift_json(const slam::Drift& d) {
    return {{"final_translation_m", d.final_translation_m},
            {"max_translation_m", d.max_translation_m},
            {"final_rotation_deg", d.final_rotation_deg},
            {"max_rotation_deg", d.max_rotation_deg}};
}

struct Totals {
    double load_ms = 0.0;
    slam::StageTimes stages;
    int fallbacks = 0;
    int merges_applied = 0;
    int ground_found = 0;
    double inliers = 0.0;
    double lifted = 0.0;
    double matches = 0.0;
    double valid_fraction = 0.0;
    double bundle_points = 0.0;
    double bundle_initial = 0.0;
    double bundle_final = 0.0;
    std::vector<double> offset_profile;  // least-cost disparity offsets (--ba-profile-offset)
    std::vector<double> profile_costs;   // summed over the windows, per offset
};

void add_times(slam::StageTimes& sum, const slam::StageTimes& t) {
    sum.frontend_ms += t.frontend_ms;
    sum.motion_ms += t.motion_ms;
    sum.bundle_ms += t.bundle_ms;
    sum.local_map_ms += t.local_map_ms;
    sum.global_map_ms += t.global_map_ms;
}

double fps(int frames, double ms) {
    return ms > 0.0 ? 1000.0 * frames / ms : 0.0;
}

// The sequence and the frames a run reads, after every check that reads no image.
struct Input {
    slam::Layout layout;
    slam::Sequence sequence;
    slam::FrameRange range;
    int frames;
    int width;
    int height;
};

Input checked_input(const SlamOptions& o) {
    const slam::Layout layout = slam::parse_layout(o.layout, o.sequence);
    const std::optional<fs::path> calib =
        o.calib.empty() ? std::nullopt : std::optional<fs::path>(o.calib);
    slam::Sequence sequence = slam::open_sequence(o.sequence, layout, calib);
    const int count = static_cast<int>(sequence.frames.size());
    const slam::FrameRange range = slam::parse_frames(o.frames, count);
    const int frames = range.end - range.begin;
    const int width = sequence.size.width / o.downscale;
    const int height = sequence.size.height / o.downscale;
    if (width < 1 || height < 1) {
        throw std::invalid_argument("--downscale " + std::to_string(o.downscale) +
                                    " is larger than the images");
    }
    slam::validate(o.params, width, height);
    if (o.ba_window_option->count() > 0 && o.params.bundle.window > frames) {
        throw std::invalid_argument("--ba-window " + std::to_string(o.params.bundle.window) +
                                    " is larger than the " + std::to_string(frames) +
                                    " frames of the run");
    }
    if (o.vdisparity_frame < 0 || o.vdisparity_frame >= frames) {
        throw std::invalid_argument("--vdisparity-frame must be in 0.." +
                                    std::to_string(frames - 1));
    }
    // The sequence's files (frames, poses, calibration, timestamps, wherever its links lead)
    // must survive any output path, and no output goes into the sequence folder.
    io::check_outputs({o.map, o.trajectory, o.vdisparity},
                      {.files = {o.calib}, .folders = {o.sequence}});
    for (const std::string& output : {o.map, o.trajectory, o.vdisparity}) {
        if (!output.empty()) {
            io::check_writable_location(output);
        }
    }
    return {layout, std::move(sequence), range, frames, width, height};
}

// Every frame through the SLAM system; the v-disparity picture of --vdisparity-frame.
Totals run_frames(const SlamOptions& o, const Input& in, slam::Slam& slam,
                  cv::Mat& vdisparity_picture) {
    Totals totals;
    const ProgressBar progress("slam", in.frames);
    // One frame read, decoded and through the front end, and the time the reading took.
    const auto prepare = [&](int i) {
        const auto start = std::chrono::steady_clock::now();
        const slam::StereoFrame frame =
            slam::load_frame(in.sequence, in.range.begin + i, o.downscale);
        const double load_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        return std::pair{slam.frontend(frame.left, frame.right), load_ms};
    };
    // With more than one thread the next frame is read and matched while this one's motion and
    // maps are computed (single-threaded stages that leave a core free): one frame of latency
    // more, the same results. A read error still stops the run at its frame.
    std::future<std::pair<slam::Slam::FrontendFrame, double>> next;
    for (int i = 0; i < in.frames; ++i) {
        auto [front, load_ms] = next.valid() ? next.get() : prepare(i);
        totals.load_ms += load_ms;
        if (o.params.threads > 1 && i + 1 < in.frames) {
            next = std::async(std::launch::async, prepare, i + 1);
        }
        const slam::FrameReport report = slam.integrate(std::move(front));
        add_times(totals.stages, report.ms);
        totals.valid_fraction += report.valid_fraction;
        totals.ground_found += report.ground_found ? 1 : 0;
        if (i > 0) {
            totals.fallbacks += report.motion.fallback ? 1 : 0;
            totals.merges_applied += report.merge.applied ? 1 : 0;
            totals.inliers += report.motion.inliers;
            totals.lifted += report.motion.lifted;
            totals.matches += report.motion.matches;
            totals.bundle_points += report.bundle.points;
            totals.bundle_initial += report.bundle.initial_cost;
            totals.bundle_final += report.bundle.final_cost;
            if (report.bundle.profiled) {
                totals.offset_profile.push_back(report.bundle.best_offset * o.downscale);
                totals.profile_costs.resize(report.bundle.profile_costs.size(), 0.0);
                for (std::size_t k = 0; k < report.bundle.profile_costs.size(); ++k) {
                    totals.profile_costs[k] += report.bundle.profile_costs[k];
                }
            }
        }
        if (i == o.vdisparity_frame && !o.vdisparity.empty()) {
            vdisparity_picture = slam::draw_v_disparity(slam.last_v_disparity(), report.ground,
                                                        o.params.local.tolerance, 3);
        }
        progress.update(i + 1);
    }
    return totals;
}

// The --json summary without the map: the run, its speeds, the motion and the errors.
nlohmann::json run_summary(const SlamOptions& o, const Input& in, const Totals& totals,
                           double total_ms, const slam::Slam& slam,
                           const std::optional<slam::Trajectory>& truth) {
    const int frames = in.frames;
    nlohmann::json summary;
    summary["sequence"] = o.sequence;
    summary["layout"] = in.layout == slam::Layout::kitti ? "kitti" : "euroc";
    summary["frames"] = frames;
    summary["first_frame"] = in.range.begin;
    summary["width"] = in.width;
    summary["height"] = in.height;
    summary["downscale"] = o.downscale;
    summary["merge"] = o.params.merge_enabled;
    summary["self_calibration"] = {
        {"enabled", o.params.self_calibration_enabled},
        {"calibrated_offset_px", o.disparity_offset},
        {"final_offset_px", slam.camera().disparity_offset * o.downscale},
        {"pairs", slam.self_calibration_pairs()}};
    summary["cost"] = o.params.frontend.cost;
    const double per_pair = frames > 1 ? frames - 1 : 1;
    summary["fps"] = {{"total", fps(frames, total_ms)},
                      {"load", fps(frames, totals.load_ms)},
                      {"frontend", fps(frames, totals.stages.frontend_ms)},
                      {"motion", fps(frames, totals.stages.motion_ms)},
                      {"bundle", fps(frames, totals.stages.bundle_ms)},
                      {"local_map", fps(frames, totals.stages.local_map_ms)},
                      {"global_map", fps(frames, totals.stages.global_map_ms)}};
    summary["valid_fraction"] = totals.valid_fraction / frames;
    summary["motion"] = {{"fallbacks", totals.fallbacks},
                         {"mean_matches", totals.matches / per_pair},
                         {"mean_lifted", totals.lifted / per_pair},
                         {"mean_inliers", totals.inliers / per_pair}};
    summary["bundle"] = {{"enabled", o.params.bundle_enabled},
                         {"window", o.params.bundle.window},
                         {"mean_points", totals.bundle_points / per_pair},
                         {"mean_initial_cost", totals.bundle_initial / per_pair},
                         {"mean_final_cost", totals.bundle_final / per_pair}};
    if (!totals.offset_profile.empty()) {
        std::vector<double> sorted = totals.offset_profile;
        std::sort(sorted.begin(), sorted.end());
        summary["bundle"]["offset_profile"] = {
            {"windows", sorted.size()},
            {"median_px", sorted[sorted.size() / 2]},
            {"quartiles_px", {sorted[sorted.size() / 4], sorted[3 * sorted.size() / 4]}}};
        const auto least =
            std::min_element(totals.profile_costs.begin(), totals.profile_costs.end());
        summary["bundle"]["offset_profile"]["summed_least_cost_px"] =
            (-2.0 + 0.25 * static_cast<double>(least - totals.profile_costs.begin())) * o.downscale;
        summary["bundle"]["offset_profile"]["summed_costs"] = totals.profile_costs;
    }
    summary["ground_line_frames"] = totals.ground_found;
    summary["merges_applied"] = totals.merges_applied;
    const slam::Trajectory& estimate = slam.trajectory();
    const slam::Trajectory& odometry = slam.odometry();
    const slam::Trajectory& adjusted = slam.adjusted();
    summary["drift"] = {{"odometry", drift_json(slam::drift(odometry))},
                        {"adjusted", drift_json(slam::drift(adjusted))},
                        {"merged", drift_json(slam::drift(estimate))}};
    if (truth && frames >= 3) {
        summary["poses"] = "present";
        summary["path_length_m"] = slam::trajectory_errors(odometry, *truth, kRpeGap).path_length_m;
        summary["errors"] = {
            {"odometry", errors_json(slam::trajectory_errors(odometry, *truth, kRpeGap))},
            {"adjusted", errors_json(slam::trajectory_errors(adjusted, *truth, kRpeGap))},
            {"merged", errors_json(slam::trajectory_errors(estimate, *truth, kRpeGap))}};
    } else {
        summary["poses"] = truth ? "too few frames" : "absent";
        summary["errors"] = nullptr;
    }
    return summary;
}

// The map (bounding box of the evidence and of both paths, CA-cleaned) into the summary, and the
// output files: map, v-disparity and trajectory, encoded.
std::vector<std::pair<fs::path, std::string>> map_and_files(
    const SlamOptions& o, const slam::Slam& slam, const std::optional<slam::Trajectory>& truth,
    const cv::Mat& vdisparity_picture, nlohmann::json& summary) {
    const slam::Trajectory& estimate = slam.trajectory();
    std::vector<slam::CellIndex> path_cells;
    const auto estimate_path = slam::plane_path(estimate);
    std::vector<Eigen::Vector2d> truth_path;
    if (truth) {
        truth_path = slam::plane_path(*truth);
    }
    for (const auto& path : {estimate_path, truth_path}) {
        for (const auto& p : path) {
            path_cells.push_back(slam::cell_of(p, o.params.cell_size));
        }
    }
    const slam::DenseGrid raw = slam.map().to_dense(path_cells);
    slam::DenseGrid cleaned = raw;
    for (int pass = 0; pass < o.ca_passes; ++pass) {
        cleaned = slam::ca_clean(cleaned);
    }
    summary["map"] = {{"cell_size_m", o.params.cell_size},
                      {"width_cells", raw.width},
                      {"height_cells", raw.height},
                      {"occupied", raw.count(slam::Cell::occupied)},
                      {"free", raw.count(slam::Cell::free)},
                      {"ca_passes", o.ca_passes},
                      {"occupied_after_ca", cleaned.count(slam::Cell::occupied)},
                      {"free_after_ca", cleaned.count(slam::Cell::free)}};
    std::vector<std::pair<fs::path, std::string>> files;
    if (!o.map.empty()) {
        std::vector<slam::Polyline> paths;
        if (truth) {
            paths.push_back({truth_path, cv::Scalar(0, 170, 0), "true (poses.txt)"});
        }
        paths.push_back({estimate_path, cv::Scalar(0, 0, 255), "estimate (output)"});
        files.emplace_back(
            o.map, io::encode_png(slam::render_map(cleaned, o.params.cell_size, paths), o.map));
    }
    if (!o.vdisparity.empty()) {
        files.emplace_back(o.vdisparity, io::encode_png(vdisparity_picture, o.vdisparity));
    }
    if (!o.trajectory.empty()) {
        files.emplace_back(o.trajectory, slam::format_kitti_poses(estimate));
    }
    return files;
}

void print_summary(const nlohmann::json& summary, const Input& in, const Totals& totals) {
    std::printf(
        "%d frames %dx%d: %.2f fps (front end %.2f, motion %.2f, local map %.1f, global "
        "map %.1f), %d motion fallbacks, %d merges applied\n",
        in.frames, in.width, in.height, summary["fps"]["total"].get<double>(),
        summary["fps"]["frontend"].get<double>(), summary["fps"]["motion"].get<double>(),
        summary["fps"]["local_map"].get<double>(), summary["fps"]["global_map"].get<double>(),
        totals.fallbacks, totals.merges_applied);
    if (summary["errors"].is_null()) {
        const auto& d = summary["drift"]["merged"];
        std::printf("no ground-truth poses; drift %.3f m, %.2f deg at the last frame\n",
                    d["final_translation_m"].get<double>(), d["final_rotation_deg"].get<double>());
        return;
    }
    for (const char* name : {"odometry", "adjusted", "merged"}) {
        const auto& e = summary["errors"][name];
        std::printf("%-8s ATE %.3f m (%.2f %% of %.1f m), RPE/%d frames %.2f %% %.3f deg\n", name,
                    e["ate_rmse_m"].get<double>(), e["ate_percent"].get<double>(),
                    summary["path_length_m"].get<double>(), kRpeGap,
                    e["rpe_translation_percent"].get<double>(),
                    e["rpe_rotation_deg"].get<double>());
    }
}

void run_slam(SlamOptions o) {
    const MatchParams& frontend = o.matcher.config.pipeline;
    o.params.frontend.ndisp = frontend.ndisp;
    o.params.frontend.window = frontend.window;
    o.params.frontend.sigma = frontend.sigma;
    o.params.frontend.cost = frontend.cost;
    if (o.params.threads == 0) {
        o.params.threads = robot::default_threads();
    }
    const Input in = checked_input(o);
    if (o.ba_window_option->count() == 0) {  // the default window, at most the run
        o.params.bundle.window = std::max(2, std::min(o.params.bundle.window, in.frames));
    }
    slam::Camera full_size = in.sequence.camera;
    full_size.disparity_offset = o.disparity_offset;
    // The self-calibration's pixels are those of the matched (downscaled) images.
    for (double* px : {&o.params.self_calibration.min_offset, &o.params.self_calibration.max_offset,
                       &o.params.self_calibration.step, &o.params.self_calibration.gate,
                       &o.params.self_calibration.hysteresis}) {
        *px /= o.downscale;
    }
    const slam::Camera camera = full_size.downscaled(o.downscale);
    slam::validate_camera(camera, in.width, in.height);
    slam::Slam slam(camera, o.params);
    cv::Mat vdisparity_picture;
    const auto start = std::chrono::steady_clock::now();
    const Totals totals = run_frames(o, in, slam, vdisparity_picture);
    const double total_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    std::optional<slam::Trajectory> truth;
    if (in.sequence.truth) {
        truth =
            slam::relative_to_first(slam::Trajectory(in.sequence.truth->begin() + in.range.begin,
                                                     in.sequence.truth->begin() + in.range.end));
    }
    nlohmann::json summary = run_summary(o, in, totals, total_ms, slam, truth);
    // Map, v-disparity and trajectory together, all or nothing.
    io::write_files_atomic(map_and_files(o, slam, truth, vdisparity_picture, summary));
    if (o.json) {
        std::cout << io::versioned(summary).dump() << std::endl;
        return;
    }
    print_summary(summary, in, totals);
}

}  // namespace

void add_slam_command(CLI::App& app) {
    const auto [command, o] = add_command<SlamOptions>(app, run_slam);
    auto& p = o->params;
    p.threads = 0;  // the command line's default: every core
    command->add_option("--threads", p.threads, "Front-end row bands in parallel; 0: every core")
        ->capture_default_str()
        ->check(thread_count());
    command
        ->add_option("SEQ_DIR", o->sequence,
                     "Sequence folder: image_l/ image_r/ calib.txt [poses.txt] (KITTI) or "
                     "cam0/ cam1/ (EuRoC)")
        ->required();
    command->add_option("--layout", o->layout, "auto, kitti or euroc")->capture_default_str();
    command->add_option("--calib", o->calib,
                        "Calibration (KITTI calib.txt, or the EuRoC rectification YAML)");
    command->add_option("--frames", o->frames, "Frame range A:B (0-based, half-open)");
    command->add_option("--map", o->map, "Occupancy map PNG with the trajectories")
        ->check(checks::png_output());
    command->add_option("--trajectory", o->trajectory, "Estimated poses, KITTI format");
    command->add_option("--vdisparity", o->vdisparity, "v-disparity PNG with the ground line")
        ->check(checks::png_output());
    command
        ->add_option("--vdisparity-frame", o->vdisparity_frame,
                     "Which frame of the range --vdisparity shows")
        ->capture_default_str();
    command->add_flag("--json", o->json, "Print a JSON summary");
    add_downscale_option(*command, o->downscale, "Shrink the images by integer F first");
    // The sparse front end has no CA rules: no --no-ca; its defaults are the SLAM layer's.
    MatchParams& frontend = o->matcher.config.pipeline;
    frontend.ndisp = p.frontend.ndisp;
    frontend.window = p.frontend.window;
    frontend.sigma = p.frontend.sigma;
    frontend.cost = p.frontend.cost;
    add_matcher_options(*command, o->matcher, MatcherChoice::fixed,
                        {.ndisp = true, .no_ca = false});
    command
        ->add_option("--cost", frontend.cost,
                     "Matching cost of the front end (docs/slam.md): " + catalogue::cost_help())
        ->check(CLI::IsMember(catalogue::cost_names()))
        ->capture_default_str();
    add_number_options(
        *command,
        {{"--uniqueness", &p.frontend.uniqueness,
          "Stage 6 uniqueness ratio U, percent: valid when (C2 - C1) / C1 > U / 100"},
         {"--lr-tolerance", &p.frontend.lr_tolerance, "Maximum |dL - dR|"},
         {"--features", &p.motion.features, "ORB features per image"},
         {"--max-hamming", &p.motion.max_hamming, "Worst accepted ORB match"},
         {"--max-depth", &p.motion.max_depth, "Farthest feature used, metres"},
         {"--ransac-iterations", &p.motion.ransac.iterations, "RANSAC samples"},
         {"--inlier-px", &p.motion.ransac.threshold, "Inlier residual in (u, v, d), pixels"},
         {"--min-inliers", &p.motion.ransac.min_inliers,
          "Fewer inliers: constant-velocity fallback"},
         {"--seed", &p.motion.ransac.seed, "RANSAC seed"},
         {"--disparity-offset", &o->disparity_offset,
          "Calibration: pixels added to every disparity before depth, full size (0: the "
          "calibration matches its images)"},
         {"--cell", &p.cell_size, "Grid cell size, metres"},
         {"--max-range", &p.local.max_range, "Farthest mapped point, metres"},
         {"--max-height", &p.local.max_height, "Highest obstacle point above the ground, metres"},
         {"--ground-tolerance", &p.local.tolerance,
          "Ground band either side of the v-disparity line, pixels"},
         {"--stride", &p.local.stride, "Map every stride-th pixel"}});
    command->add_flag("--ba", p.bundle_enabled,
                      "Windowed bundle adjustment of the last --ba-window key frames (off: the "
                      "frame-to-frame motion chain, docs/results-slam.md)");
    o->ba_window_option =
        command
            ->add_option("--ba-window", p.bundle.window,
                         "Key frames per bundle adjustment (the oldest held fixed), 2..frames; "
                         "the default is cut to a shorter run")
            ->capture_default_str();
    add_number_options(*command, {{"--ba-huber", &p.bundle.huber_px,
                                   "Huber threshold of the (u, v, d) reprojection error, pixels"},
                                  {"--ba-iterations", &p.bundle.iterations,
                                   "Levenberg-Marquardt iterations per adjustment"}});
    command->add_flag("--ba-profile-offset", p.bundle.profile_offset,
                      "Diagnostic: the least-cost disparity offset of every window (with --ba)");
    command->add_flag("!--no-merge", p.merge_enabled, "Place local maps with the odometry alone");
    command->add_flag("!--no-self-calibration", p.self_calibration_enabled,
                      "Keep --disparity-offset: do not measure the rig's disparity offset from "
                      "the images while moving (docs/slam.md)");
    add_number_options(
        *command,
        {{"--merge-shift", &p.merge.max_shift, "Merge search: +- cells in x and z"},
         {"--merge-angle-steps", &p.merge.angle_steps, "Merge search: +- steps"},
         {"--merge-angle-step", &p.merge.angle_step_deg, "Merge step, degrees"},
         {"--merge-min-gain", &p.merge.min_gain, "Cells a correction must gain to be applied"},
         {"--merge-significance", &p.merge.significance,
          "Gain must exceed this times sqrt(score + base score); 0: off"},
         {"--merge-min-match", &p.merge.min_match,
          "Share of the placed local map's cells that must hit occupied cells; 0: off"},
         {"--ca-passes", &o->ca_passes, "Clean-up passes over the final map",
          checks::integer_in(0, 1000)}});
}

}  // namespace stereo::cli

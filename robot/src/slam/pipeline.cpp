#include "stereo_robot/slam/pipeline.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "stereo_io/io.hpp"
#include "stereo_robot/bands.hpp"

namespace stereo::robot::slam {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Image to_grey_image(const cv::Mat& mat) {
    if (mat.type() != CV_8UC1 || mat.empty()) {
        throw std::invalid_argument("SLAM frames must be non-empty 8-bit grey images");
    }
    return io::to_image(mat, "SLAM frame");
}

Eigen::Vector2d plane(const Eigen::Vector3d& p) {
    return {p.x(), p.z()};
}

void require(bool condition, const std::string& message) {
    if (!condition) {
        throw std::invalid_argument(message);
    }
}

// One point of each camera-frame (x, z) square of side `size` (the first one met), as floats.
// The squares are marked in a bitmap over the points' box (a local map spans a few hundred
// squares a side); a box too large for it keeps every point.
std::vector<Eigen::Vector3f> thinned(const std::vector<Eigen::Vector3d>& points, double size) {
    std::vector<Eigen::Vector3f> kept;
    if (points.empty()) {
        return kept;
    }
    double low_x = points.front().x();
    double high_x = low_x;
    double low_z = points.front().z();
    double high_z = low_z;
    for (const Eigen::Vector3d& p : points) {
        low_x = std::min(low_x, p.x());
        high_x = std::max(high_x, p.x());
        low_z = std::min(low_z, p.z());
        high_z = std::max(high_z, p.z());
    }
    const double width = std::floor((high_x - low_x) / size) + 1.0;
    const double depth = std::floor((high_z - low_z) / size) + 1.0;
    if (!(width * depth <= double{1 << 24})) {
        for (const Eigen::Vector3d& p : points) {
            kept.push_back(p.cast<float>());
        }
        return kept;
    }
    const auto columns = static_cast<std::size_t>(depth);
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(width) * columns, 0);
    for (const Eigen::Vector3d& p : points) {
        const auto i = static_cast<std::size_t>((p.x() - low_x) / size);
        const auto j = static_cast<std::size_t>((p.z() - low_z) / size);
        std::uint8_t& mark = seen[i * columns + j];
        if (mark == 0) {
            mark = 1;
            kept.push_back(p.cast<float>());
        }
    }
    return kept;
}

// A camera-frame point lifted at offset `from`, lifted again at `to`: the same ray, the depth
// of its disparity under the new offset (the point itself when the offset is the same).
Eigen::Vector3d relift_point(const Eigen::Vector3f& point, const Camera& camera, double from,
                             double to) {
    if (from == to) {
        return point.cast<double>();
    }
    const double fb = camera.focal * camera.baseline;
    const double d = fb / point.z() - from;  // as matched
    return point.cast<double>() * ((fb / (d + to)) / point.z());
}

// The self-calibration looks at the points the motion uses: the same farthest depth.
SelfCalibrationParams self_calibration_params(const SlamParams& params) {
    SelfCalibrationParams calibration = params.self_calibration;
    calibration.max_depth = params.motion.max_depth;
    return calibration;
}

}  // namespace

void validate(const SlamParams& params, int width, int height) {
    const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    // Every bound keeps the work and the memory of a run finite and every value meaningful
    // (docs/reliability.md lists them): 2^31 RANSAC samples or CA passes would run for days.
    const auto within = [](double v, double low, double high) { return v >= low && v <= high; };
    require(within(params.frontend.uniqueness, 0, fx::kMaxUniqueness),
            "--uniqueness must be in 0.." + std::to_string(fx::kMaxUniqueness));
    require(within(params.frontend.lr_tolerance, 0, fx::kMaxLrTolerance),
            "--lr-tolerance must be in 0.." + std::to_string(fx::kMaxLrTolerance));
    validate_frontend(params.frontend, width, height);
    require(within(params.motion.features, 10, 100000), "--features must be in 10..100000");
    require(params.threads >= 1 && params.threads <= 256, "--threads must be in 1..256");
    require(params.motion.max_hamming >= 0 && params.motion.max_hamming <= 256,
            "--max-hamming must be in 0..256");
    require(within(params.motion.max_depth, 1e-3, 1e4), "--max-depth must be in [0.001, 10000] m");
    require(within(params.motion.ransac.iterations, 1, 100000),
            "--ransac-iterations must be in 1..100000");
    require(within(params.motion.ransac.threshold, 1e-3, 1000.0),
            "--inlier-px must be in [0.001, 1000]");
    require(within(params.motion.ransac.min_inliers, 3, 100000),
            "--min-inliers must be in 3..100000");
    // A cell from 1 cm to 100 m, and at most 10^5 cells across the mapped range: the grids stay
    // small and every cell index fits an int (a 1e-6 m cell grew the grids past 3 GB).
    require(params.cell_size >= 0.01 && params.cell_size <= 100.0,
            "--cell must be in [0.01, 100] metres");
    require(positive(params.local.max_range), "--max-range must be > 0");
    require(params.local.max_range / params.cell_size <= 1e5,
            "--max-range / --cell must be at most 100000 cells");
    require(within(params.local.max_height, 1e-3, 1000.0),
            "--max-height must be in [0.001, 1000] m");
    require(within(params.local.tolerance, 0.0, 1000.0), "--ground-tolerance must be in [0, 1000]");
    require(within(params.local.stride, 1, 10000), "--stride must be in 1..10000");
    require(params.merge.max_shift >= 0 && params.merge.max_shift <= 20,
            "--merge-shift must be in 0..20 cells");
    require(params.merge.angle_steps >= 0 && params.merge.angle_steps <= 20,
            "--merge-angle-steps must be in 0..20");
    require(within(params.merge.angle_step_deg, 1e-3, 45.0),
            "--merge-angle-step must be in [0.001, 45] degrees");
    require(within(params.merge.min_gain, 0, 1000000), "--merge-min-gain must be in 0..1000000");
    require(params.merge.significance >= 0.0 && std::isfinite(params.merge.significance),
            "--merge-significance must be >= 0");
    require(params.merge.min_match >= 0.0 && params.merge.min_match <= 1.0,
            "--merge-min-match must be in [0, 1]");
    require(positive(params.ray_bin_deg), "ray bins must be > 0 degrees");
    require(within(params.bundle.window, 2, 100000),
            "--ba-window must be at least 2 key frames (the oldest is held fixed)");
    require(within(params.bundle.huber_px, 1e-3, 1000.0), "--ba-huber must be in [0.001, 1000] px");
    require(within(params.bundle.iterations, 1, 1000), "--ba-iterations must be in 1..1000");
}

void validate_camera(const Camera& camera, int width, int height) {
    // The principal point within one image size of the image, a focal length and baseline of a
    // real rig: a calibration with cx = 1e308 sent points (and grid indices) out of range.
    const auto within = [](double v, double low, double high) {
        return std::isfinite(v) && v >= low && v <= high;
    };
    require(within(camera.focal, 1.0, 1e6), "calibration: focal length must be in [1, 1e6] px");
    require(within(camera.cx, -width, 2.0 * width),
            "calibration: cx must lie within one image width of the image");
    require(within(camera.cy, -height, 2.0 * height),
            "calibration: cy must lie within one image height of the image");
    require(within(camera.baseline, 1e-3, 1e3), "calibration: baseline must be in [1 mm, 1 km]");
    require(within(camera.disparity_offset, -width, width),
            "--disparity-offset must lie within one image width");
}

Slam::Slam(const Camera& camera, const SlamParams& params)
    : camera_(camera),
      params_(params),
      map_(params.cell_size),
      offset_estimator_(self_calibration_params(params)),
      calibrated_offset_(camera.disparity_offset) {
    params_.motion.threads = params.threads;  // the descriptor matching shares the SLAM's threads
}

FrameReport Slam::process(const cv::Mat& left, const cv::Mat& right) {
    return integrate(frontend(left, right));
}

Slam::FrontendFrame Slam::frontend(const cv::Mat& left, const cv::Mat& right) const {
    const auto start = Clock::now();
    // ORB on the left image does not depend on the disparities: with threads > 1 it runs
    // beside the front end (its time is then included in frontend_ms).
    std::future<Features> detected;
    if (params_.threads > 1) {
        detected =
            std::async(std::launch::async, [&] { return detect_features(left, params_.motion); });
    }
    FrontendFrame frame;
    frame.disparity = sparse_disparity_bands(to_grey_image(left), to_grey_image(right),
                                             params_.frontend, params_.threads);
    frame.features = detected.valid() ? detected.get() : detect_features(left, params_.motion);
    frame.ms = ms_since(start);
    return frame;
}

FrameReport Slam::integrate(FrontendFrame frame) {
    FrameReport report;
    report.valid_fraction = frame.disparity.valid_fraction();
    report.ms.frontend_ms = frame.ms;
    SparseDisparity& disparity = frame.disparity;
    Features& features = frame.features;

    auto start = Clock::now();
    bool offset_changed = false;
    if (odometry_.empty()) {
        odometry_.push_back(Eigen::Isometry3d::Identity());
        adjusted_.push_back(Eigen::Isometry3d::Identity());
        trajectory_.push_back(Eigen::Isometry3d::Identity());
        merge_corrections_.push_back(Eigen::Isometry3d::Identity());
    } else {
        // Constant velocity is the fallback: the last accepted motion again.
        report.motion = estimate_motion(features_, disparity_, features, disparity, camera_,
                                        params_.motion, last_motion_);
        if (!report.motion.fallback) {
            last_motion_ = report.motion.motion;
            const bool added = params_.self_calibration_enabled &&
                               offset_estimator_.add_pair(report.motion.matched_pairs, camera_,
                                                          report.motion.motion);
            if (added && offset_estimator_.due()) {
                offset_changed = set_disparity_offset(
                    offset_estimator_.offset_for(calibrated_offset_, camera_.disparity_offset));
            }
        }
        const Eigen::Isometry3d step = report.motion.motion.inverse();  // current -> previous
        odometry_.push_back(odometry_.back() * step);
        adjusted_.push_back(adjusted_.back() * step);
        trajectory_.push_back(trajectory_.back() * step);
        merge_corrections_.push_back(merge_corrections_.back());
        if (params_.self_calibration_enabled) {
            steps_.push_back(
                {report.motion.motion, report.motion.fallback, report.motion.inlier_pairs});
            const auto kept = static_cast<std::size_t>(params_.self_calibration.resolve_steps);
            if (steps_.size() > kept) {
                steps_.pop_front();  // too old to be solved again
                ++first_step_;
            }
        }
    }
    report.disparity_offset = camera_.disparity_offset;
    features_ = std::move(features);
    disparity_ = std::move(disparity);
    report.ms.motion_ms = ms_since(start);

    if (params_.bundle_enabled) {
        start = Clock::now();
        add_key_frame(report.motion, features_.keypoints.size());
        report.bundle = adjust_window();
        // The output is the adjusted chain under the merge corrections (all left-multiplied).
        for (const KeyFrame& key : window_) {
            const auto k = static_cast<std::size_t>(key.frame);
            trajectory_[k] = merge_corrections_[k] * adjusted_[k];
        }
        report.ms.bundle_ms = ms_since(start);
    }

    start = Clock::now();
    vdisp_ = v_disparity(disparity_, params_.frontend.ndisp);
    GroundParams ground_params = params_.ground;
    ground_params.tolerance = params_.local.tolerance;
    const auto line = fit_ground_line(vdisp_, camera_, ground_params);
    report.ground_found = line.has_value();
    if (line) {
        ground_ = line;  // else the previous frame's line is kept
    }
    report.ground = ground_;
    LocalMap local;
    if (ground_) {
        local = local_map(disparity_, *ground_, camera_, params_.local);
    }
    report.obstacle_points = static_cast<int>(local.obstacles.size());
    report.ms.local_map_ms = ms_since(start);

    start = Clock::now();
    // The local map thinned to one point per quarter cell (camera frame): the global map counts
    // cells, and the kept copy rebuilds the map exactly as it was built.
    const double quarter_cell = params_.cell_size / 4.0;
    KeptLocalMap thin{thinned(local.obstacles, quarter_cell), thinned(local.ground, quarter_cell),
                      camera_.disparity_offset};
    const auto [obstacles, ground] = relifted(thin, camera_);
    report.merge = place_local_map(trajectory_.size() - 1, obstacles, ground);
    if (params_.self_calibration_enabled) {
        keep_local_map(std::move(thin));
        if (offset_changed) {
            // Every kept motion and the map again at the new offset (docs/slam.md §2c).
            resolve_steps();
            rebuild_map();
        }
    }
    report.ms.global_map_ms = ms_since(start);
    return report;
}

MergeResult Slam::place_local_map(std::size_t frame,
                                  const std::vector<Eigen::Vector3d>& obstacles_seen,
                                  const std::vector<Eigen::Vector3d>& ground_seen) {
    MergeResult merge;
    Eigen::Isometry3d& pose = trajectory_[frame];
    std::vector<Eigen::Vector2d> obstacles;
    obstacles.reserve(obstacles_seen.size());
    for (const auto& p : obstacles_seen) {
        obstacles.push_back(plane(pose * p));
    }
    if (params_.merge_enabled && !map_.empty() && !obstacles.empty()) {
        const Eigen::Vector2d pivot = plane(pose.translation());
        merge = best_placement(map_, obstacles, pivot, params_.merge);

        const Eigen::Isometry3d correction =
            merge_correction(merge, pivot, params_.cell_size, params_.merge);
        pose = correction * pose;
        merge_corrections_[frame] = correction * merge_corrections_[frame];
        for (auto& p : obstacles) {
            p = plane(correction * Eigen::Vector3d(p.x(), 0.0, p.y()));
        }
    }
    std::vector<Eigen::Vector2d> ground;
    ground.reserve(ground_seen.size());
    for (const auto& p : ground_seen) {
        ground.push_back(plane(pose * p));
    }
    const Eigen::Vector2d origin = plane(pose.translation());
    std::vector<CellIndex> cells;
    cells.reserve(obstacles.size());
    for (const auto& p : obstacles) {
        cells.push_back(cell_of(p, params_.cell_size));
    }
    map_.add_frame(cell_of(origin, params_.cell_size), cells,
                   bearing_rays(origin, obstacles, ground, params_.cell_size, params_.ray_bin_deg));
    return merge;
}

std::pair<std::vector<Eigen::Vector3d>, std::vector<Eigen::Vector3d>> Slam::relifted(
    const KeptLocalMap& local, const Camera& camera) {
    std::pair<std::vector<Eigen::Vector3d>, std::vector<Eigen::Vector3d>> points;
    points.first.reserve(local.obstacles.size());
    points.second.reserve(local.ground.size());
    for (const auto& p : local.obstacles) {
        points.first.push_back(relift_point(p, camera, local.offset, camera.disparity_offset));
    }
    for (const auto& p : local.ground) {
        points.second.push_back(relift_point(p, camera, local.offset, camera.disparity_offset));
    }
    return points;
}

void Slam::keep_local_map(KeptLocalMap local) {
    local_maps_.push_back(std::move(local));
    if (local_maps_.size() > steps_.size() + 1) {
        local_maps_.pop_front();  // its frame's step is no longer kept either
    }
}

// The global map and the merge corrections again from the kept local maps, at the new offset
// and the solved-again motions. Only while every frame of the run is kept: older evidence could
// not be rebuilt, so a longer run keeps its map (and the motions are still solved again).
void Slam::rebuild_map() {
    if (first_step_ != 0 || local_maps_.size() != trajectory_.size()) {
        return;
    }
    map_ = EvidenceGrid(params_.cell_size);
    Eigen::Isometry3d running = Eigen::Isometry3d::Identity();
    for (std::size_t frame = 0; frame < local_maps_.size(); ++frame) {
        const auto [obstacles, ground] = relifted(local_maps_[frame], camera_);
        merge_corrections_[frame] = running;
        trajectory_[frame] = running * adjusted_[frame];
        place_local_map(frame, obstacles, ground);
        running = merge_corrections_[frame];
    }
}

bool Slam::set_disparity_offset(double offset) {
    if (offset == camera_.disparity_offset) {
        return false;
    }
    camera_.disparity_offset = offset;
    return true;
}

// The disparity offset changed: every kept step's motion again from its inliers at the new
// offset (Gauss-Newton from the old motion), and the chains rebuilt from them (the adjusted
// chain restarts from the odometry; rebuild_map() then redoes the merge corrections).
void Slam::resolve_steps() {
    for (std::size_t k = 0; k < steps_.size(); ++k) {
        Step& step = steps_[k];
        if (step.fallback || step.inliers.size() < 3) {
            continue;
        }
        std::vector<Eigen::Vector3d> src;
        std::vector<Eigen::Vector3d> observed;
        std::vector<int> all;
        for (const KeypointPair& p : step.inliers) {
            if (!(p.previous_uvd.z() + camera_.disparity_offset > 0.0) ||
                !(p.current_uvd.z() + camera_.disparity_offset > 0.0)) {
                continue;
            }
            src.push_back(camera_.lift(p.previous_uvd.x(), p.previous_uvd.y(), p.previous_uvd.z()));
            observed.push_back(p.current_uvd);
            all.push_back(static_cast<int>(all.size()));
        }
        if (all.size() >= 3) {
            step.motion = refine_reprojection(step.motion, src, observed, all, camera_,
                                              std::max(params_.motion.refine_iterations, 1));
        }
    }
    for (std::size_t k = 0; k < steps_.size(); ++k) {
        const std::size_t frame = first_step_ + k + 1;  // steps_[k] leads to this frame
        odometry_[frame] = odometry_[frame - 1] * steps_[k].motion.inverse();
        adjusted_[frame] = odometry_[frame];
        trajectory_[frame] = merge_corrections_[frame] * adjusted_[frame];
    }
    // The bundle-adjustment window's landmarks again, from their first observation at the new
    // offset and the solved-again poses (the adjustment refines them from there).
    std::unordered_set<int> placed;
    for (const KeyFrame& key : window_) {
        for (const auto& [id, uvd] : key.observations) {
            if (placed.insert(id).second) {
                landmarks_[id] = adjusted_[static_cast<std::size_t>(key.frame)] *
                                 camera_.lift(uvd.x(), uvd.y(), uvd.z());
            }
        }
    }
    if (!steps_.empty() && !steps_.back().fallback) {
        last_motion_ = steps_.back().motion;
    }
}

void Slam::add_key_frame(const MotionEstimate& motion, std::size_t keypoints) {
    KeyFrame key;
    key.frame = static_cast<int>(adjusted_.size()) - 1;
    key.linked = key.frame > 0 && !motion.fallback;
    key.landmark_of.assign(keypoints, -1);
    if (key.linked && !window_.empty()) {
        KeyFrame& previous = window_.back();
        const Eigen::Isometry3d& previous_pose =
            adjusted_[static_cast<std::size_t>(previous.frame)];
        for (const KeypointPair& pair : motion.inlier_pairs) {
            int& id = previous.landmark_of[static_cast<std::size_t>(pair.previous)];
            if (id < 0) {  // a new track: placed from the previous frame's stereo point
                id = next_landmark_++;
                const Eigen::Vector3d& uvd = pair.previous_uvd;
                landmarks_[id] = previous_pose * camera_.lift(uvd.x(), uvd.y(), uvd.z());
                previous.observations.emplace_back(id, uvd);
            }
            key.landmark_of[static_cast<std::size_t>(pair.current)] = id;
            key.observations.emplace_back(id, pair.current_uvd);
        }
    }
    window_.push_back(std::move(key));
    if (static_cast<int>(window_.size()) > params_.bundle.window) {
        window_.pop_front();
        std::unordered_map<int, Eigen::Vector3d> kept;
        for (const KeyFrame& frame : window_) {
            for (const auto& [id, uvd] : frame.observations) {
                kept.emplace(id, landmarks_.at(id));
            }
        }
        landmarks_ = std::move(kept);
    }
}

BundleReport Slam::adjust_window() {
    BundleProblem problem;
    std::unordered_map<int, int> point_index;  // landmark id -> problem index
    std::vector<int> point_id;
    // The oldest pose is the gauge; a frame without a motion estimate has no observation
    // linking it to its predecessor, so it and everything before it stay fixed too.
    std::size_t first_free = 1;
    for (std::size_t i = 1; i < window_.size(); ++i) {
        if (!window_[i].linked) {
            first_free = i + 1;
        }
    }
    for (std::size_t i = 0; i < window_.size(); ++i) {
        const KeyFrame& key = window_[i];
        problem.world_to_camera.push_back(adjusted_[static_cast<std::size_t>(key.frame)].inverse());
        problem.fixed.push_back(i < first_free);
        for (const auto& [id, uvd] : key.observations) {
            const auto [it, inserted] =
                point_index.emplace(id, static_cast<int>(problem.points.size()));
            if (inserted) {
                problem.points.push_back(landmarks_.at(id));
                point_id.push_back(id);
            }
            problem.observations.push_back({static_cast<int>(i), it->second, uvd});
        }
    }
    BundleReport profile;
    if (params_.bundle.profile_offset && first_free < window_.size()) {
        double least = std::numeric_limits<double>::infinity();
        for (int quarter = -8; quarter <= 12; ++quarter) {
            Camera shifted = camera_;
            shifted.disparity_offset = quarter / 4.0;
            BundleProblem trial = problem;
            const double cost = adjust_bundle(trial, shifted, params_.bundle).final_cost;
            profile.profile_costs.push_back(cost);
            if (cost < least) {
                least = cost;
                profile.best_offset = shifted.disparity_offset;
            }
        }
        profile.profiled = true;
    }
    BundleReport report = adjust_bundle(problem, camera_, params_.bundle);
    report.best_offset = profile.best_offset;
    report.profiled = profile.profiled;
    report.profile_costs = std::move(profile.profile_costs);
    for (std::size_t i = first_free; i < window_.size(); ++i) {
        adjusted_[static_cast<std::size_t>(window_[i].frame)] =
            problem.world_to_camera[i].inverse();
    }
    for (std::size_t p = 0; p < point_id.size(); ++p) {
        landmarks_[point_id[p]] = problem.points[p];
    }
    return report;
}

std::vector<Eigen::Vector2d> plane_path(const Trajectory& poses) {
    std::vector<Eigen::Vector2d> path;
    for (const auto& pose : poses) {
        path.push_back(plane(pose.translation()));
    }
    return path;
}

}  // namespace stereo::robot::slam

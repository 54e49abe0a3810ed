// `stereo_experiments slam-scale`: where the SLAM odometry's step length comes from on the KITTI
// clips (docs/results-slam.md, issue 50). For every pair of consecutive frames it compares the
// estimated motion with poses.txt (step length and rotation angle, each as a ratio), and it
// measures the depth scale the disparities imply under the true motion: if every depth is s
// times the truth, a point seen in both frames satisfies X_cur - M X_prev = (s - 1) t for the
// true motion M = [R | t], so (s - 1) = (X_cur - M X_prev) . t / |t|^2 for each match. The same
// is done with OpenCV's StereoSGBM disparities at the same keypoints (an independent matcher),
// and per depth band, which separates a scale error (the same s at every depth) from a disparity
// offset (s growing with depth).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo_io/io.hpp"
#include "stereo_robot/slam/dataset.hpp"
#include "stereo_robot/slam/frontend.hpp"
#include "stereo_robot/slam/maps.hpp"
#include "stereo_robot/slam/motion.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;
namespace slam = robot::slam;
using json = nlohmann::json;

struct Options : cli::ReportOptions {
    std::string clips = "kitti_sequence_1,kitti_sequence_2";
    static constexpr std::string_view kName = "slam-scale";
    static constexpr std::string_view kDescription =
        "The SLAM odometry's step lengths and rotations against poses.txt, and the depth scale "
        "of the front end's and of StereoSGBM's disparities under the true motion "
        "(docs/results-slam.md, issue 50).";
};

double median(std::vector<double> values) {
    if (values.empty()) {
        return std::nan("");
    }
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

// StereoSGBM (OpenCV's semi-global matcher, 1/16 px) with common settings for 5x5 blocks.
cv::Mat sgbm_disparity(const cv::Mat& left, const cv::Mat& right, int ndisp) {
    constexpr int kBlock = 5;
    const auto sgbm = cv::StereoSGBM::create(0, ndisp, kBlock, 8 * kBlock * kBlock,
                                             32 * kBlock * kBlock, 1, 0, 10, 100, 2);
    cv::Mat disparity;
    sgbm->compute(left, right, disparity);
    return disparity;  // CV_16S, 16 x d, negative = invalid
}

double sgbm_at(const cv::Mat& disparity, const cv::Point2f& p) {
    const int x = static_cast<int>(std::lround(p.x));
    const int y = static_cast<int>(std::lround(p.y));
    if (x < 0 || y < 0 || x >= disparity.cols || y >= disparity.rows) {
        return -1.0;
    }
    const short value = disparity.at<short>(y, x);
    return value > 0 ? value / 16.0 : -1.0;
}

double sparse_at(const slam::SparseDisparity& map, const cv::Point2f& p) {
    const int x = static_cast<int>(std::lround(p.x));
    const int y = static_cast<int>(std::lround(p.y));
    if (x < 0 || y < 0 || x >= map.width || y >= map.height) {
        return -1.0;
    }
    return map.at(x, y);
}

struct Frame {
    cv::Mat left;
    slam::SparseDisparity sparse;
    cv::Mat sgbm;
    slam::Features features;
};

constexpr std::array<double, 4> kBands = {0.0, 10.0, 20.0, 40.0};  // metres

struct ScaleSamples {
    std::array<std::vector<double>, 3> ours;  // s - 1 per depth band
    std::array<std::vector<double>, 3> sgbm;
    std::vector<double> offset;  // our disparity - SGBM's at the same keypoint, px
    std::vector<double> road;    // s - 1 of the front end's matches in the road region
    std::vector<double> rest;    // and of the others
    // Every usable match of the front end with its true motion, for the offset search.
    struct Match {
        cv::Point2f a, b;
        double da, db;
        Eigen::Isometry3d truth;
    };
    std::vector<Match> matches;
};

// The road region of road_step_over_height: the central half of the columns, from 40 px below
// the principal point down.
bool in_road_region(const cv::Point2f& p, const slam::Camera& camera, int width) {
    return p.x >= width / 4.0 && p.x < 3.0 * width / 4.0 && p.y >= camera.cy + 40.0;
}

// (s - 1) of one match under the true motion, or NaN when unusable.
double scale_excess(const slam::Camera& camera, const Eigen::Isometry3d& truth,
                    const cv::Point2f& a, double da, const cv::Point2f& b, double db) {
    const Eigen::Vector3d previous = camera.lift(a.x, a.y, da);
    const Eigen::Vector3d current = camera.lift(b.x, b.y, db);
    const Eigen::Vector3d residual = current - truth * previous;
    const Eigen::Vector3d t = truth.translation();
    // A mismatch moves the point by metres; (s - 1) t is a few decimetres.
    if (residual.norm() > 0.5 * t.norm() + 0.5) {
        return std::nan("");
    }
    return residual.dot(t) / t.squaredNorm();
}

void add_samples(const slam::Camera& camera, const Eigen::Isometry3d& truth, const Frame& previous,
                 const Frame& current, ScaleSamples& samples) {
    for (const cv::DMatch& m :
         slam::match_mutual_nearest(previous.features.descriptors, current.features.descriptors)) {
        if (m.distance > 64) {
            continue;
        }
        const cv::Point2f& a = previous.features.keypoints[m.queryIdx].pt;
        const cv::Point2f& b = current.features.keypoints[m.trainIdx].pt;
        const double da = sparse_at(previous.sparse, a);
        const double db = sparse_at(current.sparse, b);
        const double ga = sgbm_at(previous.sgbm, a);
        const double gb = sgbm_at(current.sgbm, b);
        const auto band_of = [&](double d) {
            const double z = camera.focal * camera.baseline / d;
            for (std::size_t k = 0; k + 1 < kBands.size(); ++k) {
                if (z >= kBands[k] && z < kBands[k + 1]) {
                    return static_cast<int>(k);
                }
            }
            return -1;
        };
        if (da > 0.0 && db > 0.0) {
            const double excess = scale_excess(camera, truth, a, da, b, db);
            const int band = band_of(da);
            if (std::isfinite(excess) && band >= 0) {
                samples.ours[static_cast<std::size_t>(band)].push_back(excess);
                (in_road_region(a, camera, previous.left.cols) ? samples.road : samples.rest)
                    .push_back(excess);
                samples.matches.push_back({a, b, da, db, truth});
            }
        }
        if (ga > 0.0 && gb > 0.0) {
            const double excess = scale_excess(camera, truth, a, ga, b, gb);
            const int band = band_of(ga);
            if (std::isfinite(excess) && band >= 0) {
                samples.sgbm[static_cast<std::size_t>(band)].push_back(excess);
            }
        }
        if (da > 0.0 && ga > 0.0) {
            samples.offset.push_back(da - ga);
        }
    }
}

// Camera height above the road of one frame, two ways: B / slope of the v-disparity ground line
// (independent of the focal length and of a constant disparity offset), and the distance from
// the camera of the least-squares plane through the lifted pixels of the ground band (every
// depth error enters). NaN when no line is found.
std::pair<double, double> camera_height(const slam::SparseDisparity& map,
                                        const slam::Camera& camera, int ndisp) {
    const slam::GroundParams params;
    const auto line = slam::fit_ground_line(slam::v_disparity(map, ndisp), camera, params);
    if (!line) {
        return {std::nan(""), std::nan("")};
    }
    std::vector<Eigen::Vector3d> points;
    for (int y = 0; y < map.height; ++y) {
        for (int x = map.width / 4; x < 3 * map.width / 4; ++x) {
            const double d = map.at(x, y);
            if (d > 0.0 && std::abs(d - line->disparity(y)) <= params.tolerance) {
                points.push_back(camera.lift(x, y, d));
            }
        }
    }
    if (points.size() < 100) {
        return {camera.baseline / line->slope, std::nan("")};
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : points) {
        mean += p;
    }
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const auto& p : points) {
        scatter += (p - mean) * (p - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    const Eigen::Vector3d normal = solver.eigenvectors().col(0);  // smallest eigenvalue
    return {camera.baseline / line->slope, std::abs(normal.dot(mean))};
}

// The step length from the road alone, without any disparity: the homography of the road
// pixels between two left images is K (R + t n^T / h) K^-1 for a plane at distance h, so its
// decomposition gives |t| / h, and |t| follows with h = KITTI's camera height, 1.65 m. ORB
// matches of the road region (central half of the columns, rows from 40 px below the principal
// point down); NaN when fewer than 30 matches or no near-vertical plane normal.
double road_step_over_height(const cv::Mat& previous, const cv::Mat& current,
                             const slam::Camera& camera) {
    cv::Mat mask = cv::Mat::zeros(previous.size(), CV_8U);
    const int top = static_cast<int>(camera.cy) + 40;
    mask(cv::Rect(previous.cols / 4, top, previous.cols / 2, previous.rows - top)).setTo(255);
    slam::MotionParams params;
    params.features = 1000;
    const auto orb = cv::ORB::create(params.features);
    slam::Features a;
    slam::Features b;
    orb->detectAndCompute(previous, mask, a.keypoints, a.descriptors);
    orb->detectAndCompute(current, mask, b.keypoints, b.descriptors);
    std::vector<cv::Point2f> from;
    std::vector<cv::Point2f> to;
    for (const cv::DMatch& m : slam::match_mutual_nearest(a.descriptors, b.descriptors)) {
        if (m.distance <= 64) {
            from.push_back(a.keypoints[m.queryIdx].pt);
            to.push_back(b.keypoints[m.trainIdx].pt);
        }
    }
    if (from.size() < 30) {
        return std::nan("");
    }
    const cv::Mat homography = cv::findHomography(from, to, cv::RANSAC, 2.0);
    if (homography.empty()) {
        return std::nan("");
    }
    const cv::Matx33d k(camera.focal, 0, camera.cx, 0, camera.focal, camera.cy, 0, 0, 1);
    std::vector<cv::Mat> rotations;
    std::vector<cv::Mat> translations;
    std::vector<cv::Mat> normals;
    cv::decomposeHomographyMat(homography, k, rotations, translations, normals);
    double best = 0.0;
    double step = std::nan("");
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const double vertical = std::abs(normals[i].at<double>(1));
        if (vertical > best) {
            best = vertical;
            step = cv::norm(translations[i]);
        }
    }
    return best > 0.95 ? step : std::nan("");
}

// The disparity offset delta (d + delta used for every disparity) that brings the depth scale
// under the true motion closest to 1 in all three depth bands: the largest |s - 1| of the bands,
// minimised over delta in [-3, 3] px by steps of 1/8. Returns {delta, s per band}.
std::pair<double, std::array<double, 3>> best_offset(const slam::Camera& camera,
                                                     const ScaleSamples& samples) {
    double best_delta = 0.0;
    double best_worst = std::numeric_limits<double>::infinity();
    std::array<double, 3> best_scales{};
    for (int step = -24; step <= 24; ++step) {
        const double delta = step / 8.0;
        std::array<std::vector<double>, 3> bands;
        for (const auto& m : samples.matches) {
            if (!(m.da + delta > 0.5) || !(m.db + delta > 0.5)) {
                continue;
            }
            const double excess =
                scale_excess(camera, m.truth, m.a, m.da + delta, m.b, m.db + delta);
            const double z = camera.focal * camera.baseline / (m.da + delta);
            for (std::size_t k = 0; k + 1 < kBands.size(); ++k) {
                if (std::isfinite(excess) && z >= kBands[k] && z < kBands[k + 1]) {
                    bands[k].push_back(excess);
                }
            }
        }
        double worst = 0.0;
        std::array<double, 3> scales{};
        for (std::size_t k = 0; k < 3; ++k) {
            scales[k] = 1.0 + median(bands[k]);
            worst = std::max(worst, std::abs(scales[k] - 1.0));
        }
        if (worst < best_worst) {
            best_worst = worst;
            best_delta = delta;
            best_scales = scales;
        }
    }
    return {best_delta, best_scales};
}

void run(const Options& options) {
    std::ostringstream md;
    json report;
    md << "| clip | step length est. / true (median, min-max) | rotation est. / true (median) | "
          "depth scale s, front end: < 10 / 10-20 / 20-40 m | s, StereoSGBM: < 10 / 10-20 / 20-40 "
          "m | front end - SGBM disparity (median px) | camera height, median m: B / slope / "
          "plane (frames) | road homography step (h = 1.65 m) / true, median (pairs) "
          "| s, front end: road region (matches) / elsewhere | disparity offset bringing s closest "
          "to 1 "
          "in every band: offset px: s < 10 / 10-20 / 20-40 m |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    std::stringstream list(options.clips);
    std::string clip;
    while (std::getline(list, clip, ',')) {
        const fs::path dir = fs::path(options.data_dir) / "sequence" / clip;
        const slam::Sequence sequence = slam::open_sequence(dir, slam::Layout::kitti, std::nullopt);
        if (!sequence.truth) {
            throw std::invalid_argument(clip + " has no poses.txt");
        }
        const slam::Camera& camera = sequence.camera;
        const slam::FrontendParams frontend;
        const slam::MotionParams motion;
        std::vector<double> length_ratio;
        std::vector<double> rotation_ratio;
        std::vector<double> height_slope;
        std::vector<double> height_plane;
        std::vector<double> road_ratio;  // (|t| / h) * 1.65 m over the true step
        ScaleSamples samples;
        Frame previous;
        const int count = static_cast<int>(sequence.frames.size());
        for (int i = 0; i < count; ++i) {
            const slam::StereoFrame pair = slam::load_frame(sequence, i, 1);
            Frame frame;
            frame.left = pair.left;
            frame.sparse = slam::sparse_disparity(io::to_image(pair.left, "left"),
                                                  io::to_image(pair.right, "right"), frontend);
            frame.sgbm = sgbm_disparity(pair.left, pair.right, 96);
            frame.features = slam::detect_features(pair.left, motion);
            const auto [slope_h, plane_h] = camera_height(frame.sparse, camera, frontend.ndisp);
            if (std::isfinite(slope_h)) {
                height_slope.push_back(slope_h);
            }
            if (std::isfinite(plane_h)) {
                height_plane.push_back(plane_h);
            }
            if (i > 0) {
                // previous camera -> current camera
                const Eigen::Isometry3d truth =
                    (*sequence.truth)[static_cast<std::size_t>(i)].inverse() *
                    (*sequence.truth)[static_cast<std::size_t>(i - 1)];
                const slam::MotionEstimate estimate = slam::estimate_motion(
                    previous.features, previous.sparse, frame.features, frame.sparse, camera,
                    motion, Eigen::Isometry3d::Identity());
                length_ratio.push_back(estimate.motion.translation().norm() /
                                       truth.translation().norm());
                rotation_ratio.push_back(slam::rotation_deg(estimate.motion) /
                                         slam::rotation_deg(truth));
                add_samples(camera, truth, previous, frame, samples);
                constexpr double kKittiCameraHeight = 1.65;  // metres (KITTI's setup)
                const double road = road_step_over_height(previous.left, frame.left, camera);
                if (std::isfinite(road)) {
                    road_ratio.push_back(road * kKittiCameraHeight / truth.translation().norm());
                }
            }
            previous = std::move(frame);
        }
        const auto [lo, hi] = std::minmax_element(length_ratio.begin(), length_ratio.end());
        json row = {{"clip", clip},
                    {"step_length_ratio_median", median(length_ratio)},
                    {"step_length_ratio_min", *lo},
                    {"step_length_ratio_max", *hi},
                    {"rotation_ratio_median", median(rotation_ratio)},
                    {"disparity_offset_median_px", median(samples.offset)},
                    {"camera_height_slope_median_m", median(height_slope)},
                    {"camera_height_plane_median_m", median(height_plane)},
                    {"camera_height_frames", height_plane.size()},
                    {"road_homography_step_ratio_median", median(road_ratio)},
                    {"road_homography_pairs", road_ratio.size()},
                    {"scale_frontend_road_region", 1.0 + median(samples.road)},
                    {"scale_frontend_elsewhere", 1.0 + median(samples.rest)},
                    {"matches_road_region", samples.road.size()}};
        const auto [delta, scales] = best_offset(camera, samples);
        row["best_disparity_offset_px"] = delta;
        row["scale_at_best_offset"] = scales;
        md << "| " << clip << " | " << fmt(median(length_ratio), 3) << " (" << fmt(*lo, 2) << "-"
           << fmt(*hi, 2) << ") | " << fmt(median(rotation_ratio), 3) << " | ";
        for (const auto* source : {&samples.ours, &samples.sgbm}) {
            for (std::size_t band = 0; band < 3; ++band) {
                const double s = 1.0 + median((*source)[band]);
                md << fmt(s, 3) << " (" << (*source)[band].size() << ")"
                   << (band < 2 ? " / " : " | ");
                row[source == &samples.ours ? "scale_frontend" : "scale_sgbm"].push_back(
                    {{"band_m", {kBands[band], kBands[band + 1]}},
                     {"scale", s},
                     {"matches", (*source)[band].size()}});
            }
        }
        md << fmt(median(samples.offset), 3) << " | " << fmt(median(height_slope), 3) << " / "
           << fmt(median(height_plane), 3) << " (" << height_plane.size() << ") | "
           << fmt(median(road_ratio), 3) << " (" << road_ratio.size() << ") | "
           << fmt(1.0 + median(samples.road), 3) << " (" << samples.road.size() << ") / "
           << fmt(1.0 + median(samples.rest), 3) << " | " << fmt(delta, 3) << ": "
           << fmt(scales[0], 3) << " / " << fmt(scales[1], 3) << " / " << fmt(scales[2], 3)
           << " |\n";
        report["clips"].push_back(row);
    }
    print_and_write_report({}, options.markdown, md.str(), options.json_path, report);
}

}  // namespace

void add_slam_scale_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<Options>(app, run);
    command->add_option("--clips", options->clips, "Comma-separated KITTI clips under sequence/")
        ->capture_default_str();
}

}  // namespace stereo::experiments

// Camera motion between consecutive left images (thesis Sec. 4.2.2): ORB features (SURF, which
// the thesis used, is not in Debian's OpenCV), lifted to 3-D with the validated disparities, and
// a rigid motion from RANSAC over a closed-form SVD fit.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "stereo_robot/slam/frontend.hpp"

namespace stereo::robot::slam {

// Rectified pinhole stereo camera: x right, y down, z forward (metres).
struct Camera {
    double focal = 0.0;  // pixels
    double cx = 0.0;     // principal point, pixels
    double cy = 0.0;
    double baseline = 0.0;  // metres
    // Added to every measured disparity before depth (Z = f B / (d + offset)): the principal
    // points' horizontal difference of a rig whose rectified images are not aligned with its
    // projection matrices (Middlebury's "doffs"). 0 for a calibration that matches its images.
    double disparity_offset = 0.0;

    // The camera of images shrunk by an integer factor with area averaging: pixel u' covers
    // u in [F u', F u' + F), so u = F u' + (F - 1) / 2 at its centre.
    Camera downscaled(int factor) const;
    // (u, v, d) -> (X, Y, Z) with Z = f B / (d + disparity_offset).
    Eigen::Vector3d lift(double u, double v, double d) const;
    // (X, Y, Z) -> (u, v, d), the inverse of lift.
    Eigen::Vector3d project(const Eigen::Vector3d& point) const;
};

// Closed-form least-squares rigid motion (Kabsch / Arun: SVD of the weighted cross-covariance,
// with the reflection fix): the T minimising sum_i w_i |T src_i - dst_i|^2. Weights default to
// 1. Throws std::invalid_argument for fewer than 3 pairs or sizes that differ.
Eigen::Isometry3d fit_rigid(const std::vector<Eigen::Vector3d>& src,
                            const std::vector<Eigen::Vector3d>& dst,
                            const std::vector<double>& weights = {});

struct RansacParams {
    int iterations = 300;
    double threshold = 2.0;  // residual of an inlier (units of the residual function)
    int min_inliers = 15;    // fewer: the estimate is refused
    std::uint32_t seed = 1;  // fixed, so runs are reproducible
};

struct RansacResult {
    bool ok = false;
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    std::vector<int> inliers;
};

// residual(T, i): how far pair i is from being explained by T.
using Residual = std::function<double(const Eigen::Isometry3d&, std::size_t)>;

// Minimal samples of 3 non-collinear pairs, fit_rigid on each, the largest consensus kept; then
// fit_rigid on its inliers, inliers recounted and refitted once more. ok when the final inliers
// number at least min_inliers. `weights` (optional) weigh the final fits.
RansacResult ransac_rigid(const std::vector<Eigen::Vector3d>& src,
                          const std::vector<Eigen::Vector3d>& dst, const Residual& residual,
                          const RansacParams& params, const std::vector<double>& weights = {});

// Euclidean distance |T src_i - dst_i|.
Residual euclidean_residual(const std::vector<Eigen::Vector3d>& src,
                            const std::vector<Eigen::Vector3d>& dst);

struct MotionParams {
    int features = 2000;      // ORB keypoints per image
    int max_hamming = 64;     // of 256 descriptor bits; worse matches are dropped
    double max_depth = 40.0;  // metres; farther points have too uncertain a depth
    RansacParams ransac;      // threshold in pixels of (u, v, d), see estimate_motion
    double max_step_m = 4.0;  // a larger translation between two frames is refused
    double max_step_deg = 20.0;
    int refine_iterations = 10;  // Gauss-Newton on the reprojection error; 0 = SVD fit only
    int threads = 1;             // of the descriptor matching (the same matches for any count)
};

struct Features {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
};

Features detect_features(const cv::Mat& grey, const MotionParams& params);

// Mutual nearest neighbours of two sets of binary descriptors (CV_8U rows) by Hamming distance:
// query row i and train row j match when j is i's nearest train row and i is j's nearest query
// row, ties to the lower index in both directions. One match per such query row, in query
// order, distance in bits: the same list as cv::BFMatcher(NORM_HAMMING, true).match (tested
// against it), in one pass over the pairs with 64-bit popcounts instead of OpenCV's per-pair
// calls, which took a quarter of a SLAM step. `threads` (>= 1) split the query rows; every
// thread count gives the same list.
std::vector<cv::DMatch> match_mutual_nearest(const cv::Mat& query, const cv::Mat& train,
                                             int threads = 1);

// A lifted match: keypoint indices in the previous and the current frame, and their (u, v, d).
struct KeypointPair {
    int previous = 0;
    int current = 0;
    Eigen::Vector3d previous_uvd = Eigen::Vector3d::Zero();
    Eigen::Vector3d current_uvd = Eigen::Vector3d::Zero();
};

struct MotionEstimate {
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // previous camera -> current
    bool fallback = false;  // the estimate was refused and `motion` is the fallback
    std::string reason;     // why, when fallback
    int matches = 0;        // cross-checked descriptor matches
    int lifted = 0;         // matches with a validated disparity in both frames
    int inliers = 0;
    // Every match within max_hamming, d < 0 where a frame has no validated disparity.
    std::vector<KeypointPair> matched_pairs;
    std::vector<KeypointPair> inlier_pairs;  // the final inliers (empty when refused)
};

// Matches the two frames' ORB features (brute force, Hamming, cross-check), lifts each matched
// keypoint with the disparity at its pixel (both frames must have one, and a depth below
// max_depth), and runs ransac_rigid. A pair is an inlier when the previous point moved by T and
// projected into the current frame lands within `threshold` of the observed (u, v, d) (Euclidean
// distance in pixels). The final fits weigh pairs by 1 / Z^2. Then, unless refine_iterations is
// 0, refine_reprojection on the inliers (the SVD fit treats the depth noise, which grows with Z^2,
// like the lateral one; the reprojection error does not), inliers recounted, refined once more.
// Refused (fallback returned) when RANSAC fails or the motion exceeds max_step_m / max_step_deg.
MotionEstimate estimate_motion(const Features& previous, const SparseDisparity& previous_disparity,
                               const Features& current, const SparseDisparity& current_disparity,
                               const Camera& camera, const MotionParams& params,
                               const Eigen::Isometry3d& fallback);

// Gauss-Newton on sum_i |project(T src_i) - observed_i|^2 over the listed pairs, starting from
// `start` (left-multiplied increments exp(omega, tau), numerical Jacobian).
Eigen::Isometry3d refine_reprojection(const Eigen::Isometry3d& start,
                                      const std::vector<Eigen::Vector3d>& src,
                                      const std::vector<Eigen::Vector3d>& observed,
                                      const std::vector<int>& subset, const Camera& camera,
                                      int iterations);

// A small rigid motion: rotation exp(omega) (axis-angle, the first three entries), then the
// translation tau (the last three). Left-multiplied increments of the refinements.
Eigen::Isometry3d se3_increment(const Eigen::Matrix<double, 6, 1>& delta);

// Rotation angle of T in degrees.
double rotation_deg(const Eigen::Isometry3d& transform);

}  // namespace stereo::robot::slam

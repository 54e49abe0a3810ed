// Windowed (local) bundle adjustment of the SLAM layer (issue 50): the poses of the last N key
// frames and the landmarks they observe, refined together on the stereo reprojection error
// (u, v, d) with a Huber loss; the oldest pose of the window is held fixed (the gauge: stereo
// fixes the scale, one pose fixes the other six degrees of freedom). Levenberg-Marquardt on Eigen
// with the landmarks eliminated by the Schur complement. Docs: docs/slam.md §2b.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

struct BundleParams {
    int window = 5;  // key frames adjusted together, the oldest held fixed (docs/slam.md §2b)
    // Huber threshold on the norm of a (u, v, d) residual in pixels: sqrt(7.815), the 95 %
    // chi-square bound of three coordinates with 1 px noise each (the usual stereo choice).
    double huber_px = 2.7955;
    int iterations = 10;  // Levenberg-Marquardt iterations at most
    // Diagnostic (docs/results-slam.md, issue 50): the SLAM window is also adjusted for every
    // disparity offset in [-2, 3] px by quarter pixels, and the one of least final cost is
    // reported (a profile likelihood of the offset, no ground truth involved).
    bool profile_offset = false;
};

// One stereo observation: landmark `point` seen in pose `pose` at (u, v, d) pixels.
struct StereoObservation {
    int pose = 0;
    int point = 0;
    Eigen::Vector3d uvd = Eigen::Vector3d::Zero();
};

struct BundleProblem {
    std::vector<Eigen::Isometry3d> world_to_camera;  // one per pose
    std::vector<bool> fixed;                         // one per pose; at least one must be true
    std::vector<Eigen::Vector3d> points;             // landmarks, world frame
    std::vector<StereoObservation> observations;
};

struct BundleReport {
    double initial_cost = 0.0;  // sum of the Huber losses, px^2
    double final_cost = 0.0;
    int iterations = 0;  // accepted steps
    int observations = 0;
    int points = 0;  // landmarks with at least two observations (the others are left alone)
    double best_offset = 0.0;  // with BundleParams::profile_offset: the least-cost offset, px
    bool profiled = false;
    std::vector<double> profile_costs;  // final cost per offset -2, -1.75, ..., 3 px
};

// The robust cost of one residual norm r: r^2 up to `huber`, 2 huber r - huber^2 beyond.
double huber_loss(double r, double huber);

// Sum of huber_loss over the observations (points behind a camera cost nothing).
double bundle_cost(const BundleProblem& problem, const Camera& camera, double huber);

// Refines the free poses and the landmarks with at least two observations in place. Throws
// std::invalid_argument for sizes that differ, an index out of range, or no fixed pose.
BundleReport adjust_bundle(BundleProblem& problem, const Camera& camera,
                           const BundleParams& params);

}  // namespace stereo::robot::slam

// Trajectories: the KITTI pose format, and the errors of an estimate against ground truth
// (absolute trajectory error after alignment, relative pose error over a fixed frame gap).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace stereo::robot::slam {

using Trajectory = std::vector<Eigen::Isometry3d>;  // camera-to-world pose per frame

// KITTI odometry format: one line per frame, the 3x4 matrix [R | t] row-major, 12 numbers.
// Throws std::runtime_error when unreadable and std::invalid_argument (naming the line) for a
// line that is not 12 numbers or whose R is not a rotation (to 1e-3).
Trajectory load_kitti_poses(const std::filesystem::path& path);
std::string format_kitti_poses(const Trajectory& poses);

// Every pose re-expressed relative to the first: inverse(poses[0]) * poses[i].
Trajectory relative_to_first(const Trajectory& poses);

struct TrajectoryErrors {
    double path_length_m = 0.0;  // of the ground truth, sum of frame-to-frame distances
    double ate_rmse_m = 0.0;     // RMSE of positions after the best rigid alignment (no scale)
    double ate_percent = 0.0;    // ate_rmse_m / path_length_m * 100
    double rpe_translation_percent = 0.0;  // mean over frame pairs (i, i + gap)
    double rpe_rotation_deg = 0.0;
    int rpe_pairs = 0;
    int gap = 0;
};

// ATE: fit_rigid of the estimated positions onto the true ones, then the RMSE of the
// differences. RPE for each i with i + gap < n: E = (G_i^-1 G_{i+gap})^-1 (P_i^-1 P_{i+gap});
// translation |t_E| over the true path length from i to i + gap, in %, and the angle of R_E in
// degrees, both averaged. Throws std::invalid_argument for sizes that differ or fewer than 3.
TrajectoryErrors trajectory_errors(const Trajectory& estimate, const Trajectory& truth, int gap);

// How far an estimate wanders from its start (for a camera at rest).
struct Drift {
    double final_translation_m = 0.0;
    double max_translation_m = 0.0;
    double final_rotation_deg = 0.0;
    double max_rotation_deg = 0.0;
};
Drift drift(const Trajectory& estimate);

}  // namespace stereo::robot::slam

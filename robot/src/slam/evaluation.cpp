#include "stereo_robot/slam/evaluation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "stereo_io/text_file.hpp"
#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

Trajectory load_kitti_poses(const std::filesystem::path& path) {
    std::istringstream in(io::read_text_file(path, "pose file"));
    Trajectory poses;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.find_first_not_of(" \t\r") == std::string::npos) {
            continue;
        }
        std::istringstream tokens(line);
        std::array<double, 12> v{};
        int count = 0;
        while (count < 12 && tokens >> v[count]) {
            ++count;
        }
        std::string rest;
        const auto bad = [&](const std::string& why) {
            return std::invalid_argument("pose file " + path.string() + " line " +
                                         std::to_string(number) + ": " + why);
        };
        if (count != 12 || (tokens >> rest)) {
            throw bad("expected 12 numbers (a 3x4 [R|t] matrix)");
        }
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) {
                pose.linear()(r, c) = v[4 * r + c];
            }
            pose.translation()(r) = v[4 * r + 3];
        }
        const Eigen::Matrix3d r = pose.linear();
        if (!((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-3) ||
            !(r.determinant() > 0.0)) {
            throw bad("the 3x3 part is not a rotation");
        }
        poses.push_back(pose);
    }
    return poses;
}

std::string format_kitti_poses(const Trajectory& poses) {
    std::string text;
    char number[32];
    for (const Eigen::Isometry3d& pose : poses) {
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) {
                const double value = c < 3 ? pose.linear()(r, c) : pose.translation()(r);
                std::snprintf(number, sizeof number, "%.9e", value);
                text += number;
                text += (r == 2 && c == 3) ? '\n' : ' ';
            }
        }
    }
    return text;
}

Trajectory relative_to_first(const Trajectory& poses) {
    Trajectory out;
    if (poses.empty()) {
        return out;
    }
    const Eigen::Isometry3d inverse = poses.front().inverse();
    for (const auto& pose : poses) {
        out.push_back(inverse * pose);
    }
    return out;
}

TrajectoryErrors trajectory_errors(const Trajectory& estimate, const Trajectory& truth, int gap) {
    if (estimate.size() != truth.size() || estimate.size() < 3) {
        throw std::invalid_argument(
            "trajectory_errors needs two trajectories of equal length >= 3");
    }
    if (gap < 1) {
        throw std::invalid_argument("relative pose error gap must be >= 1");
    }
    TrajectoryErrors e;
    e.gap = gap;
    const std::size_t n = truth.size();
    std::vector<double> along(n, 0.0);  // true distance travelled up to frame i
    for (std::size_t i = 1; i < n; ++i) {
        along[i] = along[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
    }
    e.path_length_m = along.back();

    std::vector<Eigen::Vector3d> est_positions;
    std::vector<Eigen::Vector3d> true_positions;
    for (std::size_t i = 0; i < n; ++i) {
        est_positions.push_back(estimate[i].translation());
        true_positions.push_back(truth[i].translation());
    }
    // A path with every position equal (camera at rest) fixes no rotation: align by translation.
    double spread = 0.0;
    for (const auto& p : est_positions) {
        spread = std::max(spread, (p - est_positions.front()).norm());
    }
    Eigen::Isometry3d alignment = Eigen::Isometry3d::Identity();
    if (spread > 1e-9) {
        alignment = fit_rigid(est_positions, true_positions);
    }
    double squared = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        squared += (alignment * est_positions[i] - true_positions[i]).squaredNorm();
    }
    e.ate_rmse_m = std::sqrt(squared / static_cast<double>(n));
    e.ate_percent = e.path_length_m > 0.0 ? 100.0 * e.ate_rmse_m / e.path_length_m : 0.0;

    double translation = 0.0;
    double rotation = 0.0;
    for (std::size_t i = 0; i + gap < n; ++i) {
        const Eigen::Isometry3d true_step = truth[i].inverse() * truth[i + gap];
        const Eigen::Isometry3d est_step = estimate[i].inverse() * estimate[i + gap];
        const Eigen::Isometry3d error = true_step.inverse() * est_step;
        const double length = along[i + gap] - along[i];
        if (length > 0.0) {
            translation += 100.0 * error.translation().norm() / length;
        }
        rotation += rotation_deg(error);
        ++e.rpe_pairs;
    }
    if (e.rpe_pairs > 0) {
        e.rpe_translation_percent = translation / e.rpe_pairs;
        e.rpe_rotation_deg = rotation / e.rpe_pairs;
    }
    return e;
}

Drift drift(const Trajectory& estimate) {
    Drift d;
    for (const auto& pose : relative_to_first(estimate)) {
        d.max_translation_m = std::max(d.max_translation_m, pose.translation().norm());
        d.max_rotation_deg = std::max(d.max_rotation_deg, rotation_deg(pose));
        d.final_translation_m = pose.translation().norm();
        d.final_rotation_deg = rotation_deg(pose);
    }
    return d;
}

}  // namespace stereo::robot::slam

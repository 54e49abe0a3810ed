#include "stereo_robot/slam/bundle.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace stereo::robot::slam {

namespace {

using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix63 = Eigen::Matrix<double, 6, 3>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

constexpr double kMinDepth = 1e-6;  // metres: a point at or behind the camera is not projected

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return m;
}

// Residual, robust weight and Jacobians of one observation at the current state.
struct Linearised {
    bool valid = false;
    Eigen::Vector3d residual;
    double weight = 0.0;  // IRLS weight of the Huber loss
    Matrix36 d_pose;      // d residual / d (omega, tau) of a left-multiplied pose increment
    Eigen::Matrix3d d_point;
};

Linearised linearise(const Eigen::Isometry3d& world_to_camera, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& uvd, const Camera& camera, double huber) {
    Linearised out;
    const Eigen::Vector3d p = world_to_camera * point;
    if (!(p.z() > kMinDepth)) {
        return out;
    }
    out.valid = true;
    out.residual = camera.project(p) - uvd;
    const double r = out.residual.norm();
    out.weight = r <= huber ? 1.0 : huber / r;
    const double inv_z = 1.0 / p.z();
    const double f = camera.focal;
    Eigen::Matrix3d d_project;
    d_project << f * inv_z, 0.0, -f * p.x() * inv_z * inv_z,  //
        0.0, f * inv_z, -f * p.y() * inv_z * inv_z,           //
        0.0, 0.0, -f * camera.baseline * inv_z * inv_z;
    out.d_pose.leftCols<3>() = -d_project * skew(p);
    out.d_pose.rightCols<3>() = d_project;
    out.d_point = d_project * world_to_camera.linear();
    return out;
}

void check(const BundleProblem& problem) {
    const std::size_t poses = problem.world_to_camera.size();
    if (problem.fixed.size() != poses) {
        throw std::invalid_argument("adjust_bundle: one fixed flag per pose");
    }
    bool any_fixed = false;
    for (const bool f : problem.fixed) {
        any_fixed = any_fixed || f;
    }
    if (!any_fixed) {
        throw std::invalid_argument("adjust_bundle: at least one pose must be fixed (the gauge)");
    }
    for (const StereoObservation& o : problem.observations) {
        if (o.pose < 0 || static_cast<std::size_t>(o.pose) >= poses || o.point < 0 ||
            static_cast<std::size_t>(o.point) >= problem.points.size()) {
            throw std::invalid_argument("adjust_bundle: observation index out of range");
        }
    }
}

}  // namespace

double huber_loss(double r, double huber) {
    return r <= huber ? r * r : 2.0 * huber * r - huber * huber;
}

double bundle_cost(const BundleProblem& problem, const Camera& camera, double huber) {
    double cost = 0.0;
    for (const StereoObservation& o : problem.observations) {
        const Eigen::Vector3d p = problem.world_to_camera[static_cast<std::size_t>(o.pose)] *
                                  problem.points[static_cast<std::size_t>(o.point)];
        if (p.z() > kMinDepth) {
            cost += huber_loss((camera.project(p) - o.uvd).norm(), huber);
        }
    }
    return cost;
}

BundleReport adjust_bundle(BundleProblem& problem, const Camera& camera,
                           const BundleParams& params) {
    check(problem);
    const std::size_t pose_count = problem.world_to_camera.size();
    std::vector<int> free_index(pose_count, -1);
    int free_count = 0;
    for (std::size_t i = 0; i < pose_count; ++i) {
        if (!problem.fixed[i]) {
            free_index[i] = free_count++;
        }
    }
    // Observations per landmark; a landmark seen once constrains nothing and is left out.
    std::vector<std::vector<int>> seen(problem.points.size());
    for (std::size_t k = 0; k < problem.observations.size(); ++k) {
        seen[static_cast<std::size_t>(problem.observations[k].point)].push_back(
            static_cast<int>(k));
    }
    BundleProblem active;
    active.world_to_camera = problem.world_to_camera;
    active.fixed = problem.fixed;
    std::vector<int> active_point;  // active index -> problem index
    for (std::size_t l = 0; l < seen.size(); ++l) {
        if (seen[l].size() < 2) {
            continue;
        }
        const int index = static_cast<int>(active.points.size());
        active.points.push_back(problem.points[l]);
        active_point.push_back(static_cast<int>(l));
        for (const int k : seen[l]) {
            StereoObservation o = problem.observations[static_cast<std::size_t>(k)];
            o.point = index;
            active.observations.push_back(o);
        }
    }
    BundleReport report;
    report.points = static_cast<int>(active.points.size());
    report.observations = static_cast<int>(active.observations.size());
    report.initial_cost = bundle_cost(active, camera, params.huber_px);
    report.final_cost = report.initial_cost;
    if (free_count == 0 || active.points.empty()) {
        return report;
    }
    std::vector<std::vector<int>> by_point(active.points.size());
    for (std::size_t k = 0; k < active.observations.size(); ++k) {
        by_point[static_cast<std::size_t>(active.observations[k].point)].push_back(
            static_cast<int>(k));
    }

    const Eigen::Index n = 6 * static_cast<Eigen::Index>(free_count);
    double lambda = 1e-4;
    double cost = report.initial_cost;
    for (int iteration = 0; iteration < params.iterations; ++iteration) {
        // Normal equations (Gauss-Newton with IRLS weights) at the current state.
        Eigen::MatrixXd h_poses = Eigen::MatrixXd::Zero(n, n);
        Eigen::VectorXd b_poses = Eigen::VectorXd::Zero(n);
        std::vector<Eigen::Matrix3d> h_points(active.points.size(), Eigen::Matrix3d::Zero());
        std::vector<Eigen::Vector3d> b_points(active.points.size(), Eigen::Vector3d::Zero());
        // Per observation: its free pose's coupling block with its landmark (zero when fixed).
        std::vector<Matrix63> coupling(active.observations.size(), Matrix63::Zero());
        for (std::size_t k = 0; k < active.observations.size(); ++k) {
            const StereoObservation& o = active.observations[k];
            const auto point = static_cast<std::size_t>(o.point);
            const Linearised lin =
                linearise(active.world_to_camera[static_cast<std::size_t>(o.pose)],
                          active.points[point], o.uvd, camera, params.huber_px);
            if (!lin.valid) {
                continue;
            }
            h_points[point] += lin.weight * lin.d_point.transpose() * lin.d_point;
            b_points[point] -= lin.weight * lin.d_point.transpose() * lin.residual;
            const int i = free_index[static_cast<std::size_t>(o.pose)];
            if (i >= 0) {
                h_poses.block<6, 6>(6 * i, 6 * i) +=
                    lin.weight * lin.d_pose.transpose() * lin.d_pose;
                b_poses.segment<6>(6 * i) -= lin.weight * lin.d_pose.transpose() * lin.residual;
                coupling[k] = lin.weight * lin.d_pose.transpose() * lin.d_point;
            }
        }
        bool accepted = false;
        while (!accepted && lambda < 1e10) {
            // Levenberg-Marquardt damping of every diagonal, then the landmarks eliminated.
            Eigen::MatrixXd reduced = h_poses;
            reduced.diagonal() += lambda * h_poses.diagonal().cwiseMax(1e-9);
            Eigen::VectorXd rhs = b_poses;
            std::vector<Eigen::Matrix3d> inverse(active.points.size());
            for (std::size_t l = 0; l < active.points.size(); ++l) {
                Eigen::Matrix3d damped = h_points[l];
                damped.diagonal() += lambda * h_points[l].diagonal().cwiseMax(1e-9);
                inverse[l] = damped.inverse();
                for (const int a : by_point[l]) {
                    const int i = free_index[static_cast<std::size_t>(
                        active.observations[static_cast<std::size_t>(a)].pose)];
                    if (i < 0) {
                        continue;
                    }
                    const Matrix63 wa = coupling[static_cast<std::size_t>(a)] * inverse[l];
                    rhs.segment<6>(6 * i) -= wa * b_points[l];
                    for (const int b : by_point[l]) {
                        const int j = free_index[static_cast<std::size_t>(
                            active.observations[static_cast<std::size_t>(b)].pose)];
                        if (j >= 0) {
                            reduced.block<6, 6>(6 * i, 6 * j) -=
                                wa * coupling[static_cast<std::size_t>(b)].transpose();
                        }
                    }
                }
            }
            const Eigen::VectorXd step = reduced.ldlt().solve(rhs);
            if (!step.allFinite()) {
                lambda *= 10.0;
                continue;
            }
            BundleProblem trial = active;
            for (std::size_t p = 0; p < pose_count; ++p) {
                const int i = free_index[p];
                if (i >= 0) {
                    trial.world_to_camera[p] =
                        se3_increment(step.segment<6>(6 * i)) * active.world_to_camera[p];
                }
            }
            for (std::size_t l = 0; l < active.points.size(); ++l) {
                Eigen::Vector3d rest = b_points[l];
                for (const int a : by_point[l]) {
                    const int i = free_index[static_cast<std::size_t>(
                        active.observations[static_cast<std::size_t>(a)].pose)];
                    if (i >= 0) {
                        rest -= coupling[static_cast<std::size_t>(a)].transpose() *
                                step.segment<6>(6 * i);
                    }
                }
                trial.points[l] += inverse[l] * rest;
            }
            const double trial_cost = bundle_cost(trial, camera, params.huber_px);
            if (trial_cost < cost) {
                accepted = true;
                const bool converged = cost - trial_cost < 1e-9 * cost;
                active = std::move(trial);
                cost = trial_cost;
                lambda = std::max(lambda / 10.0, 1e-9);
                ++report.iterations;
                if (converged) {
                    iteration = params.iterations;
                }
            } else {
                lambda *= 10.0;
            }
        }
        if (!accepted) {
            break;
        }
    }
    report.final_cost = cost;
    problem.world_to_camera = active.world_to_camera;
    for (std::size_t l = 0; l < active_point.size(); ++l) {
        problem.points[static_cast<std::size_t>(active_point[l])] = active.points[l];
    }
    return report;
}

}  // namespace stereo::robot::slam

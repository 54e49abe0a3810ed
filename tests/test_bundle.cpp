// Windowed bundle adjustment (issue 50): a synthetic stereo scene whose poses, points and
// observations are computed here (projection written out, not the library's), perturbed, and
// recovered; the gauge, the robust loss and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "stereo_io/test_support.hpp"
#include "stereo_robot/slam/bundle.hpp"

namespace stereo::robot::slam {
namespace {

constexpr double kFocal = 400.0;
constexpr double kCx = 320.0;
constexpr double kCy = 120.0;
constexpr double kBaseline = 0.5;
const Camera kCamera{kFocal, kCx, kCy, kBaseline};

// (u, v, d) of a camera-frame point, written out independently of Camera::project.
Eigen::Vector3d pixel(const Eigen::Vector3d& p) {
    return {kFocal * p.x() / p.z() + kCx, kFocal * p.y() / p.z() + kCy, kFocal * kBaseline / p.z()};
}

// A car driving forward 1 m per frame while turning 2 degrees per frame (world = frame 0).
Eigen::Isometry3d true_camera_to_world(int k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int i = 0; i < k; ++i) {
        Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
        step.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
        step.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
        pose = pose * step;
    }
    return pose;
}

struct Scene {
    BundleProblem truth;
    BundleProblem start;
};

// `poses` frames, `count` points 5-30 m ahead; every point seen by every pose that sees it in
// front within a 640 x 240 image. The start perturbs every pose but the first by about 0.3 m
// and 2 degrees and every point by about 0.3 m.
Scene make_scene(int poses, int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> lateral(-12.0, 12.0);
    std::uniform_real_distribution<double> height(-3.0, 1.5);
    std::uniform_real_distribution<double> depth(5.0, 30.0);
    std::normal_distribution<double> noise(0.0, 1.0);
    Scene scene;
    for (int k = 0; k < poses; ++k) {
        scene.truth.world_to_camera.push_back(true_camera_to_world(k).inverse());
        scene.truth.fixed.push_back(k == 0);
    }
    while (static_cast<int>(scene.truth.points.size()) < count) {
        const Eigen::Vector3d point(lateral(rng), height(rng), depth(rng) + poses);
        std::vector<StereoObservation> seen;
        for (int k = 0; k < poses; ++k) {
            const Eigen::Vector3d p =
                scene.truth.world_to_camera[static_cast<std::size_t>(k)] * point;
            const Eigen::Vector3d uvd = pixel(p);
            if (p.z() > 1.0 && uvd.x() >= 0 && uvd.x() < 640 && uvd.y() >= 0 && uvd.y() < 240) {
                seen.push_back({k, static_cast<int>(scene.truth.points.size()), uvd});
            }
        }
        if (seen.size() >= 2) {
            scene.truth.points.push_back(point);
            scene.truth.observations.insert(scene.truth.observations.end(), seen.begin(),
                                            seen.end());
        }
    }
    scene.start = scene.truth;
    for (std::size_t k = 1; k < scene.start.world_to_camera.size(); ++k) {
        Eigen::Matrix<double, 6, 1> delta;
        for (int i = 0; i < 3; ++i) {
            delta(i) = 0.02 * noise(rng);  // about 1 degree per axis
            delta(3 + i) = 0.2 * noise(rng);
        }
        scene.start.world_to_camera[k] = se3_increment(delta) * scene.start.world_to_camera[k];
    }
    for (auto& point : scene.start.points) {
        point += 0.2 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    }
    return scene;
}

double pose_error_m(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.inverse().translation() - b.inverse().translation()).norm();
}

double pose_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

TEST(BundleAdjustment, RecoversPerturbedPosesAndPointsExactly) {
    for (const std::uint32_t seed : {test::test_seed(), test::test_seed() + 1}) {
        const Scene scene = make_scene(5, 150, seed);
        BundleProblem problem = scene.start;
        BundleParams params;
        params.iterations = 50;
        const double before = bundle_cost(problem, kCamera, params.huber_px);
        const BundleReport report = adjust_bundle(problem, kCamera, params);
        EXPECT_NEAR(report.initial_cost, before, 1e-9 * before);
        EXPECT_GT(before, 1e3);  // the perturbation is visible: many pixels
        EXPECT_LT(report.final_cost, 1e-12);
        EXPECT_EQ(report.points, 150);
        for (std::size_t k = 0; k < problem.world_to_camera.size(); ++k) {
            EXPECT_LT(pose_error_m(problem.world_to_camera[k], scene.truth.world_to_camera[k]),
                      1e-7)
                << k;
            EXPECT_LT(pose_error_deg(problem.world_to_camera[k], scene.truth.world_to_camera[k]),
                      1e-6)
                << k;
        }
        for (std::size_t l = 0; l < problem.points.size(); ++l) {
            EXPECT_LT((problem.points[l] - scene.truth.points[l]).norm(), 1e-6) << l;
        }
    }
}

TEST(BundleAdjustment, TheFixedPoseIsTheGaugeAndStaysBitForBit) {
    const Scene scene = make_scene(4, 80, test::test_seed());
    BundleProblem problem = scene.start;
    problem.fixed = {true, true, false, false};
    adjust_bundle(problem, kCamera, {});
    for (int k : {0, 1}) {
        EXPECT_TRUE(problem.world_to_camera[static_cast<std::size_t>(k)].matrix() ==
                    scene.start.world_to_camera[static_cast<std::size_t>(k)].matrix());
    }
    EXPECT_GT(pose_error_m(problem.world_to_camera[2], scene.start.world_to_camera[2]), 1e-3);
}

TEST(BundleAdjustment, TheHuberLossKeepsTheSolutionUnderGrossOutliers) {
    const Scene scene = make_scene(5, 200, test::test_seed());
    BundleProblem robust = scene.start;
    // Every 10th observation is a mismatch 20-40 px away.
    std::mt19937 rng(test::test_seed());
    std::uniform_real_distribution<double> offset(20.0, 40.0);
    for (std::size_t k = 0; k < robust.observations.size(); k += 10) {
        robust.observations[k].uvd += Eigen::Vector3d(offset(rng), -offset(rng), 0.0);
    }
    BundleProblem squares = robust;
    BundleParams params;
    params.iterations = 50;
    adjust_bundle(robust, kCamera, params);
    params.huber_px = 1e3;  // no observation beyond it: plain least squares
    adjust_bundle(squares, kCamera, params);
    double robust_error = 0.0;
    double squares_error = 0.0;
    for (std::size_t k = 1; k < robust.world_to_camera.size(); ++k) {
        robust_error += pose_error_m(robust.world_to_camera[k], scene.truth.world_to_camera[k]);
        squares_error += pose_error_m(squares.world_to_camera[k], scene.truth.world_to_camera[k]);
    }
    std::printf("mean pose error over the 4 free poses: Huber %.4f m, least squares %.4f m\n",
                robust_error / 4.0, squares_error / 4.0);
    EXPECT_LT(robust_error, 0.5 * squares_error);
    // Well below the start's perturbation (0.2 m per axis, about 0.35 m per pose).
    EXPECT_LT(robust_error / 4.0, 0.1);
}

TEST(BundleAdjustment, HuberLossByHand) {
    EXPECT_DOUBLE_EQ(huber_loss(1.0, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(huber_loss(2.0, 2.0), 4.0);
    EXPECT_DOUBLE_EQ(huber_loss(5.0, 2.0), 16.0);  // 2 * 2 * 5 - 4
}

TEST(BundleAdjustment, RefusesAProblemWithoutGaugeOrWithBadIndices) {
    const Scene scene = make_scene(3, 20, test::test_seed());
    BundleProblem no_gauge = scene.start;
    no_gauge.fixed = {false, false, false};
    EXPECT_THROW(adjust_bundle(no_gauge, kCamera, {}), std::invalid_argument);
    BundleProblem bad_index = scene.start;
    bad_index.observations.push_back({3, 0, Eigen::Vector3d::Zero()});
    EXPECT_THROW(adjust_bundle(bad_index, kCamera, {}), std::invalid_argument);
    BundleProblem bad_flags = scene.start;
    bad_flags.fixed.pop_back();
    EXPECT_THROW(adjust_bundle(bad_flags, kCamera, {}), std::invalid_argument);
}

}  // namespace
}  // namespace stereo::robot::slam

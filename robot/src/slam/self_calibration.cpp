#include "stereo_robot/slam/self_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stereo::robot::slam {

namespace {

template <typename T>
double median(std::vector<T>& values) {
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace

DisparityOffsetEstimator::DisparityOffsetEstimator(const SelfCalibrationParams& params)
    : params_(params) {
    const auto finite = [](double v) { return std::isfinite(v); };
    if (!finite(params.min_offset) || !finite(params.max_offset) ||
        !(params.min_offset < params.max_offset) || !(params.step > 0.0) ||
        (params.max_offset - params.min_offset) / params.step > 1000.0) {
        throw std::invalid_argument(
            "self-calibration: the offsets need min < max and at most 1000 candidates");
    }
    if (params.min_pairs < 1 || params.window < 0 ||
        (params.window > 0 && params.window < params.min_pairs) || params.min_points < 8 ||
        !(params.min_travel > 0.0) || !(params.epipolar_px > 0.0) || !(params.max_depth > 0.0) ||
        !(params.gate >= 0.0) || !finite(params.min_travel) || !finite(params.max_depth) ||
        !finite(params.gate) || !(params.hysteresis >= 0.0) || !finite(params.hysteresis) ||
        params.every < 1 || params.resolve_steps < 0) {
        throw std::invalid_argument(
            "self-calibration: min_pairs >= 1, window 0 or >= min_pairs, min_points >= 8, "
            "positive travel, epipolar threshold and depth, gate and hysteresis >= 0, every >= "
            "1, resolve_steps >= 0");
    }
}

int DisparityOffsetEstimator::candidates() const {
    return static_cast<int>(
               std::floor((params_.max_offset - params_.min_offset) / params_.step + 1e-9)) +
           1;
}

double DisparityOffsetEstimator::offset_of(int candidate) const {
    return params_.min_offset + candidate * params_.step;
}

namespace {

// Normalised image coordinates (x - c) / f of the two views of each match.
struct Rays {
    std::vector<Eigen::Vector3d> previous;
    std::vector<Eigen::Vector3d> current;
};

// The Sampson distance of each match to the epipolar geometry E = [t]x R, in pixels, signed
// (the sign of x2^T E x1) so that it is smooth for Gauss-Newton.
std::vector<double> sampson_px(const Rays& rays, const Eigen::Matrix3d& rotation,
                               const Eigen::Vector3d& direction, double focal) {
    Eigen::Matrix3d cross;
    cross << 0, -direction.z(), direction.y(), direction.z(), 0, -direction.x(), -direction.y(),
        direction.x(), 0;
    const Eigen::Matrix3d e = cross * rotation;
    std::vector<double> distance(rays.previous.size());
    for (std::size_t i = 0; i < distance.size(); ++i) {
        const Eigen::Vector3d line = e * rays.previous[i];
        const Eigen::Vector3d back = e.transpose() * rays.current[i];
        const double algebraic = rays.current[i].dot(line);
        const double norm = line.head<2>().squaredNorm() + back.head<2>().squaredNorm();
        distance[i] = norm > 0.0 ? focal * algebraic / std::sqrt(norm)
                                 : std::numeric_limits<double>::infinity();
    }
    return distance;
}

// Rotation and translation direction refined on the Sampson distances of the matches within
// `threshold` px (Gauss-Newton, numerical Jacobian; the direction moves in the plane normal to
// it and is normalised again). The stereo motion starts it: its rotation is right, but a wrong
// disparity offset tilts its translation.
void refine_epipolar(const Rays& rays, double focal, double threshold, Eigen::Matrix3d& rotation,
                     Eigen::Vector3d& direction) {
    for (int iteration = 0; iteration < 8; ++iteration) {
        const std::vector<double> distance = sampson_px(rays, rotation, direction, focal);
        Rays inliers;
        for (std::size_t i = 0; i < distance.size(); ++i) {
            if (std::abs(distance[i]) <= threshold) {
                inliers.previous.push_back(rays.previous[i]);
                inliers.current.push_back(rays.current[i]);
            }
        }
        if (inliers.previous.size() < 8) {
            return;
        }
        // Two directions normal to t span its moves.
        const Eigen::Vector3d a = direction.unitOrthogonal();
        const Eigen::Vector3d b = direction.cross(a);
        const auto moved = [&](const Eigen::Matrix<double, 5, 1>& delta, Eigen::Matrix3d& r,
                               Eigen::Vector3d& t) {
            const Eigen::Vector3d omega = delta.head<3>();
            r = omega.norm() > 0.0
                    ? Eigen::Matrix3d(Eigen::AngleAxisd(omega.norm(), omega.normalized())) *
                          rotation
                    : rotation;
            t = (direction + delta(3) * a + delta(4) * b).normalized();
        };
        const auto residuals = [&](const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
            const std::vector<double> d = sampson_px(inliers, r, t, focal);
            return Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()))
                .eval();
        };
        const Eigen::VectorXd r0 = residuals(rotation, direction);
        constexpr double kStep = 1e-7;
        Eigen::MatrixXd jacobian(r0.size(), 5);
        for (int j = 0; j < 5; ++j) {
            Eigen::Matrix<double, 5, 1> delta = Eigen::Matrix<double, 5, 1>::Zero();
            delta(j) = kStep;
            Eigen::Matrix3d r;
            Eigen::Vector3d t;
            moved(delta, r, t);
            jacobian.col(j) = (residuals(r, t) - r0) / kStep;
        }
        const Eigen::Matrix<double, 5, 1> step =
            (jacobian.transpose() * jacobian).ldlt().solve(-jacobian.transpose() * r0);
        if (!step.allFinite()) {
            return;
        }
        Eigen::Matrix3d r;
        Eigen::Vector3d t;
        moved(step, r, t);
        if (residuals(r, t).squaredNorm() >= r0.squaredNorm()) {
            return;  // no further decrease
        }
        rotation = r;
        direction = t;
    }
}

}  // namespace

bool DisparityOffsetEstimator::add_pair(const std::vector<KeypointPair>& pairs,
                                        const Camera& camera, const Eigen::Isometry3d& motion) {
    if (static_cast<int>(pairs.size()) < params_.min_points ||
        !(motion.translation().norm() > 0.0)) {
        return false;
    }
    Rays rays;
    for (const KeypointPair& p : pairs) {
        rays.previous.emplace_back((p.previous_uvd.x() - camera.cx) / camera.focal,
                                   (p.previous_uvd.y() - camera.cy) / camera.focal, 1.0);
        rays.current.emplace_back((p.current_uvd.x() - camera.cx) / camera.focal,
                                  (p.current_uvd.y() - camera.cy) / camera.focal, 1.0);
    }
    Eigen::Matrix3d rotation = motion.rotation();
    Eigen::Vector3d direction = motion.translation().normalized();
    refine_epipolar(rays, camera.focal, 4.0 * params_.epipolar_px, rotation, direction);
    const std::vector<double> distance = sampson_px(rays, rotation, direction, camera.focal);
    std::vector<bool> inlier(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        inlier[i] = std::abs(distance[i]) <= params_.epipolar_px;
    }
    // Inliers of the essential matrix with a disparity in both frames, nearer than max_depth.
    const double min_disparity = camera.focal * camera.baseline / params_.max_depth;
    std::vector<const KeypointPair*> points;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (inlier[i] && pairs[i].previous_uvd.z() >= min_disparity &&
            pairs[i].current_uvd.z() >= min_disparity) {
            points.push_back(&pairs[i]);
        }
    }
    if (static_cast<int>(points.size()) < params_.min_points) {
        return false;
    }
    Pair kept;
    kept.candidates.resize(static_cast<std::size_t>(candidates()));
    kept.moving.resize(kept.candidates.size(), false);
    Camera lifted = camera;
    std::vector<double> travel;
    std::vector<double> depth;
    for (int c = 0; c < candidates(); ++c) {
        lifted.disparity_offset = offset_of(c);
        travel.clear();
        depth.clear();
        for (const KeypointPair* p : points) {
            const Eigen::Vector3d& a = p->previous_uvd;
            const Eigen::Vector3d& b = p->current_uvd;
            if (!(a.z() + lifted.disparity_offset > 0.5) ||
                !(b.z() + lifted.disparity_offset > 0.5)) {
                continue;
            }
            const Eigen::Vector3d previous = lifted.lift(a.x(), a.y(), a.z());
            const Eigen::Vector3d current = lifted.lift(b.x(), b.y(), b.z());
            travel.push_back((current - rotation * previous).dot(direction));
            depth.push_back(previous.z());
        }
        if (static_cast<int>(travel.size()) < params_.min_points) {
            continue;
        }
        std::vector<double> sorted = travel;
        const double typical = median(sorted);
        if (!(std::abs(typical) >= params_.min_travel)) {
            continue;
        }
        kept.moving[static_cast<std::size_t>(c)] = true;
        Bands& bands = kept.candidates[static_cast<std::size_t>(c)];
        for (std::size_t i = 0; i < travel.size(); ++i) {
            const double ratio = travel[i] / typical;
            if (!(ratio > 0.0 && ratio < 2.0)) {
                continue;  // a mismatch or a moving object
            }
            const double z = depth[i];
            const int band = z < params_.max_depth / 4 ? 0 : z < params_.max_depth / 2 ? 1 : 2;
            if (z < params_.max_depth) {
                bands[static_cast<std::size_t>(band)].push_back(static_cast<float>(ratio));
            }
        }
    }
    if (std::none_of(kept.moving.begin(), kept.moving.end(), [](bool m) { return m; })) {
        return false;  // at rest: nothing observed
    }
    pairs_.push_back(std::move(kept));
    ++seen_;
    if (params_.window > 0 && static_cast<int>(pairs_.size()) > params_.window) {
        pairs_.erase(pairs_.begin());
    }
    return true;
}

std::optional<double> DisparityOffsetEstimator::estimate() const {
    if (static_cast<int>(pairs_.size()) < params_.min_pairs) {
        return std::nullopt;
    }
    int best = -1;
    double best_spread = std::numeric_limits<double>::infinity();
    Bands pooled;
    std::vector<float> all;
    for (int c = 0; c < candidates(); ++c) {
        const auto index = static_cast<std::size_t>(c);
        int moving = 0;
        for (auto& band : pooled) {
            band.clear();
        }
        for (const Pair& pair : pairs_) {
            if (!pair.moving[index]) {
                continue;
            }
            ++moving;
            for (std::size_t b = 0; b < 3; ++b) {
                pooled[b].insert(pooled[b].end(), pair.candidates[index][b].begin(),
                                 pair.candidates[index][b].end());
            }
        }
        if (moving < params_.min_pairs ||
            std::any_of(pooled.begin(), pooled.end(), [](const auto& b) { return b.empty(); })) {
            continue;
        }
        all.clear();
        for (const auto& band : pooled) {
            all.insert(all.end(), band.begin(), band.end());
        }
        const double overall = median(all);
        double spread = 0.0;
        for (auto& band : pooled) {
            spread = std::max(spread, std::abs(median(band) / overall - 1.0));
        }
        if (spread < best_spread) {
            best_spread = spread;
            best = c;
        }
    }
    // A least spread at either end of the range is no measurement: the offset lies outside it,
    // or the travel does not tell the candidates apart.
    if (best <= 0 || best >= candidates() - 1) {
        return std::nullopt;
    }
    return offset_of(best);
}

bool DisparityOffsetEstimator::due() const {
    return seen_ >= params_.min_pairs && (seen_ - params_.min_pairs) % params_.every == 0;
}

double DisparityOffsetEstimator::offset_for(double calibrated, double applied) const {
    const std::optional<double> measured = estimate();
    const double target =
        measured && std::abs(*measured - calibrated) >= params_.gate ? *measured : calibrated;
    return std::abs(target - applied) >= params_.hysteresis ? target : applied;
}

}  // namespace stereo::robot::slam

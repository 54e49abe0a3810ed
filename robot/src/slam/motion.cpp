#include "stereo_robot/slam/motion.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <future>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include <Eigen/SVD>
#include <opencv2/features2d.hpp>

#include "stereo/target_clones.hpp"

namespace stereo::robot::slam {

Camera Camera::downscaled(int factor) const {
    const double f = factor;
    const double shift = (f - 1.0) / 2.0;
    return {focal / f, (cx - shift) / f, (cy - shift) / f, baseline, disparity_offset / f};
}

Eigen::Vector3d Camera::lift(double u, double v, double d) const {
    const double z = focal * baseline / (d + disparity_offset);
    return {(u - cx) * z / focal, (v - cy) * z / focal, z};
}

Eigen::Vector3d Camera::project(const Eigen::Vector3d& p) const {
    return {focal * p.x() / p.z() + cx, focal * p.y() / p.z() + cy,
            focal * baseline / p.z() - disparity_offset};
}

Eigen::Isometry3d fit_rigid(const std::vector<Eigen::Vector3d>& src,
                            const std::vector<Eigen::Vector3d>& dst,
                            const std::vector<double>& weights) {
    if (src.size() != dst.size() || src.size() < 3) {
        throw std::invalid_argument("fit_rigid needs at least 3 point pairs of equal count");
    }
    if (!weights.empty() && weights.size() != src.size()) {
        throw std::invalid_argument("fit_rigid: one weight per pair");
    }
    const auto weight = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };
    double total = 0.0;
    Eigen::Vector3d src_mean = Eigen::Vector3d::Zero();
    Eigen::Vector3d dst_mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < src.size(); ++i) {
        total += weight(i);
        src_mean += weight(i) * src[i];
        dst_mean += weight(i) * dst[i];
    }
    if (!(total > 0.0)) {
        throw std::invalid_argument("fit_rigid: weights must sum to a positive value");
    }
    src_mean /= total;
    dst_mean /= total;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < src.size(); ++i) {
        covariance += weight(i) * (dst[i] - dst_mean) * (src[i] - src_mean).transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    // A reflection (det -1) is the best orthogonal fit of degenerate or noisy data; flip the
    // axis of the smallest singular value to get the best proper rotation instead.
    Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
    fix(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    const Eigen::Matrix3d rotation = svd.matrixU() * fix * svd.matrixV().transpose();
    Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
    result.linear() = rotation;
    result.translation() = dst_mean - rotation * src_mean;
    return result;
}

Residual euclidean_residual(const std::vector<Eigen::Vector3d>& src,
                            const std::vector<Eigen::Vector3d>& dst) {
    return [&src, &dst](const Eigen::Isometry3d& t, std::size_t i) {
        return (t * src[i] - dst[i]).norm();
    };
}

namespace {

std::vector<int> consensus(const Eigen::Isometry3d& motion, std::size_t count,
                           const Residual& residual, double threshold) {
    std::vector<int> inliers;
    for (std::size_t i = 0; i < count; ++i) {
        if (residual(motion, i) <= threshold) {
            inliers.push_back(static_cast<int>(i));
        }
    }
    return inliers;
}

Eigen::Isometry3d fit_subset(const std::vector<Eigen::Vector3d>& src,
                             const std::vector<Eigen::Vector3d>& dst,
                             const std::vector<double>& weights, const std::vector<int>& subset) {
    std::vector<Eigen::Vector3d> a;
    std::vector<Eigen::Vector3d> b;
    std::vector<double> w;
    for (const int i : subset) {
        a.push_back(src[i]);
        b.push_back(dst[i]);
        if (!weights.empty()) {
            w.push_back(weights[i]);
        }
    }
    return fit_rigid(a, b, w);
}

}  // namespace

RansacResult ransac_rigid(const std::vector<Eigen::Vector3d>& src,
                          const std::vector<Eigen::Vector3d>& dst, const Residual& residual,
                          const RansacParams& params, const std::vector<double>& weights) {
    if (src.size() != dst.size()) {
        throw std::invalid_argument("ransac_rigid: point sets of different sizes");
    }
    RansacResult result;
    const std::size_t n = src.size();
    if (n < 3) {
        return result;
    }
    std::mt19937 rng(params.seed);
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    std::vector<int> best;
    for (int iteration = 0; iteration < params.iterations; ++iteration) {
        const std::size_t i = pick(rng);
        const std::size_t j = pick(rng);
        const std::size_t k = pick(rng);
        // Collinear (or repeated) samples do not fix a rotation.
        const double area = (src[j] - src[i]).cross(src[k] - src[i]).norm();
        if (i == j || j == k || i == k || !(area > 1e-9)) {
            continue;
        }
        const Eigen::Isometry3d candidate =
            fit_rigid({src[i], src[j], src[k]}, {dst[i], dst[j], dst[k]});
        std::vector<int> inliers = consensus(candidate, n, residual, params.threshold);
        if (inliers.size() > best.size()) {
            best = std::move(inliers);
        }
    }
    if (best.size() < 3) {
        return result;
    }
    for (int round = 0; round < 2; ++round) {
        result.motion = fit_subset(src, dst, weights, best);
        std::vector<int> inliers = consensus(result.motion, n, residual, params.threshold);
        if (inliers.size() < 3) {
            break;
        }
        best = std::move(inliers);
    }
    result.motion = fit_subset(src, dst, weights, best);
    result.inliers = best;
    result.ok = static_cast<int>(best.size()) >= params.min_inliers;
    return result;
}

Features detect_features(const cv::Mat& grey, const MotionParams& params) {
    Features features;
    const auto orb = cv::ORB::create(params.features);
    orb->detectAndCompute(grey, cv::noArray(), features.keypoints, features.descriptors);
    return features;
}

namespace {

// One descriptor row as 64-bit words, zero-padded (ORB's 32 bytes are four words).
std::vector<std::uint64_t> pack_rows(const cv::Mat& descriptors, int words) {
    std::vector<std::uint64_t> packed(static_cast<std::size_t>(descriptors.rows) * words, 0);
    for (int row = 0; row < descriptors.rows; ++row) {
        std::memcpy(&packed[static_cast<std::size_t>(row) * words], descriptors.ptr(row),
                    static_cast<std::size_t>(descriptors.cols));
    }
    return packed;
}

}  // namespace

namespace {

// The nearest rows of query rows [begin, end) (packed, `words` 64-bit words each) among all train
// rows, and each train row's nearest among those query rows. Strict comparisons: the lower index
// wins ties (i and j both ascend). Compiled per instruction set (stereo/target_clones.hpp): the
// x86-64 baseline has no popcount instruction and libgcc's took a quarter of a SLAM step.
STEREO_TARGET_CLONES
void nearest_rows(const std::uint64_t* query, const std::uint64_t* train, int words, int begin,
                  int end, int train_rows, int* query_best, int* query_best_index, int* train_best,
                  int* train_best_index) {
    for (int i = begin; i < end; ++i) {
        const std::uint64_t* a = query + static_cast<std::ptrdiff_t>(i) * words;
        int best = std::numeric_limits<int>::max();
        int best_index = -1;
        for (int j = 0; j < train_rows; ++j) {
            const std::uint64_t* b = train + static_cast<std::ptrdiff_t>(j) * words;
            int distance = 0;
            if (words == 4) {  // ORB's 256 bits: unrolled
                distance = std::popcount(a[0] ^ b[0]) + std::popcount(a[1] ^ b[1]) +
                           std::popcount(a[2] ^ b[2]) + std::popcount(a[3] ^ b[3]);
            } else {
                for (int w = 0; w < words; ++w) {
                    distance += std::popcount(a[w] ^ b[w]);
                }
            }
            if (distance < best) {
                best = distance;
                best_index = j;
            }
            if (distance < train_best[j]) {
                train_best[j] = distance;
                train_best_index[j] = i;
            }
        }
        query_best[i] = best;
        query_best_index[i] = best_index;
    }
}

}  // namespace

std::vector<cv::DMatch> match_mutual_nearest(const cv::Mat& query, const cv::Mat& train,
                                             int threads) {
    std::vector<cv::DMatch> matches;
    if (threads < 1) {
        throw std::invalid_argument("match_mutual_nearest: threads must be at least 1");
    }
    if (query.empty() || train.empty()) {
        return matches;
    }
    if (query.type() != CV_8UC1 || train.type() != CV_8UC1 || query.cols != train.cols) {
        throw std::invalid_argument("binary descriptors must be CV_8U rows of equal length");
    }
    const int words = (query.cols + 7) / 8;
    const std::vector<std::uint64_t> q = pack_rows(query, words);
    const std::vector<std::uint64_t> t = pack_rows(train, words);
    constexpr int kNone = std::numeric_limits<int>::max();
    const auto rows = static_cast<std::size_t>(query.rows);
    const auto train_rows = static_cast<std::size_t>(train.rows);
    std::vector<int> query_best(rows, kNone);
    std::vector<int> query_best_index(rows, -1);
    // Each thread takes a contiguous slice of query rows and keeps its own nearest query row per
    // train row; the slices are merged in order with a strict comparison, so the lower query
    // index still wins ties and every thread count gives the single-threaded list.
    const int slices = std::clamp(threads, 1, std::max(1, query.rows / 64));
    std::vector<int> train_best(train_rows * slices, kNone);
    std::vector<int> train_best_index(train_rows * slices, -1);
    const auto scan = [&](int slice) {
        const int begin = static_cast<int>(static_cast<std::int64_t>(query.rows) * slice / slices);
        const int end =
            static_cast<int>(static_cast<std::int64_t>(query.rows) * (slice + 1) / slices);
        nearest_rows(q.data(), t.data(), words, begin, end, train.rows, query_best.data(),
                     query_best_index.data(), &train_best[train_rows * slice],
                     &train_best_index[train_rows * slice]);
    };
    std::vector<std::future<void>> others;
    for (int slice = 1; slice < slices; ++slice) {
        others.push_back(std::async(std::launch::async, scan, slice));
    }
    scan(0);
    for (auto& other : others) {
        other.get();
    }
    for (int slice = 1; slice < slices; ++slice) {
        for (std::size_t j = 0; j < train_rows; ++j) {
            if (train_best[train_rows * slice + j] < train_best[j]) {
                train_best[j] = train_best[train_rows * slice + j];
                train_best_index[j] = train_best_index[train_rows * slice + j];
            }
        }
    }
    for (int i = 0; i < query.rows; ++i) {
        const int j = query_best_index[static_cast<std::size_t>(i)];
        if (j >= 0 && train_best_index[static_cast<std::size_t>(j)] == i) {
            matches.emplace_back(i, j, static_cast<float>(query_best[static_cast<std::size_t>(i)]));
        }
    }
    return matches;
}

double rotation_deg(const Eigen::Isometry3d& transform) {
    const Eigen::AngleAxisd angle_axis(transform.rotation());
    return std::abs(angle_axis.angle()) * 180.0 / std::numbers::pi;
}

Eigen::Isometry3d se3_increment(const Eigen::Matrix<double, 6, 1>& delta) {
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d omega = delta.head<3>();
    if (omega.norm() > 0.0) {
        step.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).matrix();
    }
    step.translation() = delta.tail<3>();
    return step;
}

Eigen::Isometry3d refine_reprojection(const Eigen::Isometry3d& start,
                                      const std::vector<Eigen::Vector3d>& src,
                                      const std::vector<Eigen::Vector3d>& observed,
                                      const std::vector<int>& subset, const Camera& camera,
                                      int iterations) {
    Eigen::Isometry3d t = start;
    const auto residuals = [&](const Eigen::Isometry3d& motion, Eigen::VectorXd& r) {
        r.resize(static_cast<Eigen::Index>(3 * subset.size()));
        for (std::size_t k = 0; k < subset.size(); ++k) {
            const Eigen::Vector3d moved = motion * src[subset[k]];
            r.segment<3>(static_cast<Eigen::Index>(3 * k)) =
                moved.z() > 0.0 ? Eigen::Vector3d(camera.project(moved) - observed[subset[k]])
                                : Eigen::Vector3d::Zero();
        }
    };
    constexpr double kStep = 1e-6;
    Eigen::VectorXd r;
    Eigen::VectorXd shifted;
    for (int iteration = 0; iteration < iterations && subset.size() >= 3; ++iteration) {
        residuals(t, r);
        Eigen::MatrixXd jacobian(r.size(), 6);
        for (int j = 0; j < 6; ++j) {
            Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
            delta(j) = kStep;
            residuals(se3_increment(delta) * t, shifted);
            jacobian.col(j) = (shifted - r) / kStep;
        }
        const Eigen::Matrix<double, 6, 1> delta =
            (jacobian.transpose() * jacobian).ldlt().solve(-jacobian.transpose() * r);
        if (!delta.allFinite()) {
            break;
        }
        t = se3_increment(delta) * t;
        if (delta.norm() < 1e-10) {
            break;
        }
    }
    return t;
}

namespace {

// The validated disparity at a keypoint's pixel, or a negative value.
double disparity_at(const SparseDisparity& map, const cv::Point2f& point) {
    const int x = static_cast<int>(std::lround(point.x));
    const int y = static_cast<int>(std::lround(point.y));
    if (x < 0 || y < 0 || x >= map.width || y >= map.height) {
        return -1.0;
    }
    return map.at(x, y);
}

}  // namespace

MotionEstimate estimate_motion(const Features& previous, const SparseDisparity& previous_disparity,
                               const Features& current, const SparseDisparity& current_disparity,
                               const Camera& camera, const MotionParams& params,
                               const Eigen::Isometry3d& fallback) {
    MotionEstimate estimate;
    const auto refuse = [&](std::string reason) {
        estimate.motion = fallback;
        estimate.fallback = true;
        estimate.reason = std::move(reason);
        return estimate;
    };
    if (previous.descriptors.empty() || current.descriptors.empty()) {
        return refuse("no features");
    }
    const std::vector<cv::DMatch> matches =
        match_mutual_nearest(previous.descriptors, current.descriptors, params.threads);
    estimate.matches = static_cast<int>(matches.size());

    const double min_disparity =
        camera.focal * camera.baseline / params.max_depth - camera.disparity_offset;
    std::vector<Eigen::Vector3d> src;
    std::vector<Eigen::Vector3d> dst;
    std::vector<Eigen::Vector3d> observed;  // (u, v, d) in the current frame
    std::vector<double> weights;
    std::vector<KeypointPair> pairs;  // keypoint indices of each lifted match
    for (const cv::DMatch& match : matches) {
        if (match.distance > params.max_hamming) {
            continue;
        }
        const cv::Point2f& a = previous.keypoints[match.queryIdx].pt;
        const cv::Point2f& b = current.keypoints[match.trainIdx].pt;
        const double da = disparity_at(previous_disparity, a);
        const double db = disparity_at(current_disparity, b);
        estimate.matched_pairs.push_back({match.queryIdx, match.trainIdx,
                                          Eigen::Vector3d(a.x, a.y, da),
                                          Eigen::Vector3d(b.x, b.y, db)});
        if (!(da >= min_disparity) || !(db >= min_disparity)) {
            continue;
        }
        src.push_back(camera.lift(a.x, a.y, da));
        dst.push_back(camera.lift(b.x, b.y, db));
        observed.emplace_back(b.x, b.y, db);
        pairs.push_back({match.queryIdx, match.trainIdx, Eigen::Vector3d(a.x, a.y, da),
                         Eigen::Vector3d(b.x, b.y, db)});
        // Depth variance grows with Z^4; 1/Z^2 still lets far points fix the rotation.
        weights.push_back(1.0 / (src.back().z() * dst.back().z()));
    }
    estimate.lifted = static_cast<int>(src.size());
    const Residual reprojection = [&](const Eigen::Isometry3d& t, std::size_t i) {
        const Eigen::Vector3d moved = t * src[i];
        if (!(moved.z() > 0.0)) {
            return std::numeric_limits<double>::infinity();
        }
        return (camera.project(moved) - observed[i]).norm();
    };
    const RansacResult ransac = ransac_rigid(src, dst, reprojection, params.ransac, weights);
    estimate.inliers = static_cast<int>(ransac.inliers.size());
    if (!ransac.ok) {
        return refuse("too few inliers (" + std::to_string(estimate.inliers) + " of " +
                      std::to_string(estimate.lifted) + ")");
    }
    Eigen::Isometry3d motion = ransac.motion;
    std::vector<int> inliers = ransac.inliers;
    if (params.refine_iterations > 0) {
        for (int round = 0; round < 2; ++round) {
            motion = refine_reprojection(motion, src, observed, inliers, camera,
                                         params.refine_iterations);
            std::vector<int> recount;
            for (std::size_t i = 0; i < src.size(); ++i) {
                if (reprojection(motion, i) <= params.ransac.threshold) {
                    recount.push_back(static_cast<int>(i));
                }
            }
            if (static_cast<int>(recount.size()) < params.ransac.min_inliers) {
                break;
            }
            inliers = std::move(recount);
        }
        estimate.inliers = static_cast<int>(inliers.size());
    }
    if (motion.translation().norm() > params.max_step_m ||
        rotation_deg(motion) > params.max_step_deg) {
        return refuse("implausible step");
    }
    estimate.motion = motion;
    for (const int i : inliers) {
        estimate.inlier_pairs.push_back(pairs[static_cast<std::size_t>(i)]);
    }
    return estimate;
}

}  // namespace stereo::robot::slam

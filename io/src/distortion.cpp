#include "stereo_io/distortion.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace stereo::io {

namespace {

cv::Point2d image_centre(int width, int height) {
    return {(width - 1) / 2.0, (height - 1) / 2.0};
}

// out(q) = image(inverse(q)) with OpenCV remap; outside the source 0.
cv::Mat remap_with(const cv::Mat& image, const std::function<cv::Point2d(cv::Point2d)>& inverse,
                   int interpolation) {
    cv::Mat map_x(image.size(), CV_32FC1);
    cv::Mat map_y(image.size(), CV_32FC1);
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) {
            const cv::Point2d source = inverse({static_cast<double>(x), static_cast<double>(y)});
            map_x.at<float>(y, x) = static_cast<float>(source.x);
            map_y.at<float>(y, x) = static_cast<float>(source.y);
        }
    }
    cv::Mat out;
    cv::remap(image, out, map_x, map_y, interpolation, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    return out;
}

}  // namespace

RadialDistortion::RadialDistortion(int width, int height, double percent)
    : centre_(image_centre(width, height)), half_diagonal_(std::hypot(width, height) / 2.0) {
    const double p = percent / 100.0;
    if (!std::isfinite(percent) || p <= -0.5 || p >= 0.5) {
        throw std::invalid_argument("distortion must be in (-50, 50) %, got " +
                                    std::to_string(percent));
    }
    lambda_ = -p / ((1.0 - p) * (1.0 - p));
}

cv::Point2d RadialDistortion::undistort(cv::Point2d distorted) const {
    const cv::Point2d offset = distorted - centre_;
    const double rho2 = offset.dot(offset) / (half_diagonal_ * half_diagonal_);
    return centre_ + offset * (1.0 / (1.0 + lambda_ * rho2));
}

cv::Point2d RadialDistortion::distort(cv::Point2d undistorted) const {
    // rho_u (1 + lambda rho_d^2) = rho_d, solved for the root that tends to rho_u as lambda -> 0:
    // rho_d = 2 rho_u / (1 + sqrt(1 - 4 lambda rho_u^2)).
    const cv::Point2d offset = undistorted - centre_;
    const double rho2 = offset.dot(offset) / (half_diagonal_ * half_diagonal_);
    const double discriminant = 1.0 - 4.0 * lambda_ * rho2;
    if (discriminant < 0) {  // pincushion far outside the image: no image point maps there
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    }
    return centre_ + offset * (2.0 / (1.0 + std::sqrt(discriminant)));
}

cv::Mat distort_image(const cv::Mat& image, const RadialDistortion& lens, int interpolation) {
    return remap_with(
        image, [&](cv::Point2d q) { return lens.undistort(q); }, interpolation);
}

PairTransform::PairTransform(int width, int height, const PairWarp& warp)
    : lens_(width, height, warp.distortion_percent),
      centre_(image_centre(width, height)),
      cos_(std::cos(warp.right_rotation_deg * std::numbers::pi / 180.0)),
      sin_(std::sin(warp.right_rotation_deg * std::numbers::pi / 180.0)),
      shift_y_(warp.right_shift_y) {
    // Beyond these the right image is empty: an error, not a black image.
    if (!(std::abs(warp.right_shift_y) < height) || !(std::abs(warp.right_rotation_deg) <= 180.0)) {
        throw std::invalid_argument("the vertical shift must be smaller than the image height (" +
                                    std::to_string(height) +
                                    " px) and the rotation within [-180, 180] degrees");
    }
}

cv::Point2d PairTransform::right(cv::Point2d p) const {
    // Counter-clockwise on screen (y points down): x' = c x + s y, y' = -s x + c y.
    const cv::Point2d o = p - centre_;
    const cv::Point2d moved =
        centre_ + cv::Point2d(cos_ * o.x + sin_ * o.y, -sin_ * o.x + cos_ * o.y + shift_y_);
    return lens_.distort(moved);
}

cv::Point2d PairTransform::right_inverse(cv::Point2d q) const {
    const cv::Point2d o = lens_.undistort(q) - centre_ - cv::Point2d(0, shift_y_);
    return centre_ + cv::Point2d(cos_ * o.x - sin_ * o.y, sin_ * o.x + cos_ * o.y);
}

cv::Mat warp_left(const cv::Mat& image, const PairTransform& transform, int interpolation) {
    return remap_with(
        image, [&](cv::Point2d q) { return transform.left_inverse(q); }, interpolation);
}

cv::Mat warp_right(const cv::Mat& image, const PairTransform& transform, int interpolation) {
    return remap_with(
        image, [&](cv::Point2d q) { return transform.right_inverse(q); }, interpolation);
}

cv::Mat warp_ground_truth(const cv::Mat& ground_truth, const PairTransform& transform) {
    return warp_left(ground_truth, transform, cv::INTER_NEAREST);
}

cv::Mat exact_ground_truth(const cv::Mat& ground_truth, const PairTransform& transform,
                           cv::Mat* vertical) {
    CV_Assert(ground_truth.type() == CV_32FC1);
    cv::Mat horizontal(ground_truth.size(), CV_32FC1, cv::Scalar(0));
    cv::Mat offsets(ground_truth.size(), CV_32FC1,
                    cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
    for (int y = 0; y < ground_truth.rows; ++y) {
        for (int x = 0; x < ground_truth.cols; ++x) {
            const cv::Point2d q(x, y);
            const cv::Point2d p = transform.left_inverse(q);
            const int px = static_cast<int>(std::lround(p.x));
            const int py = static_cast<int>(std::lround(p.y));
            if (px < 0 || py < 0 || px >= ground_truth.cols || py >= ground_truth.rows) {
                continue;
            }
            const float d = ground_truth.at<float>(py, px);
            if (d <= 0) {
                continue;  // unknown stays unknown
            }
            const cv::Point2d match = transform.right(p - cv::Point2d(d, 0));
            const double new_d = q.x - match.x;
            if (!std::isfinite(new_d) || new_d <= 0) {
                continue;
            }
            horizontal.at<float>(y, x) = static_cast<float>(new_d);
            offsets.at<float>(y, x) = static_cast<float>(match.y - q.y);
        }
    }
    if (vertical != nullptr) {
        *vertical = offsets;
    }
    return horizontal;
}

WarpedScene warp_scene(const SceneData& scene, const PairWarp& warp) {
    const int width = scene.left_bgr.cols;
    const int height = scene.left_bgr.rows;
    const PairTransform transform(width, height, warp);
    const std::string label = " (warped)";
    WarpedScene out{scene, {}, {}};
    SceneData& data = out.data;
    data.left_bgr = warp_left(scene.left_bgr, transform, cv::INTER_LINEAR);
    data.right_bgr = warp_right(scene.right_bgr, transform, cv::INTER_LINEAR);
    data.pair = {to_image(data.left_bgr, scene.scene.name + " left" + label),
                 to_image(data.right_bgr, scene.scene.name + " right" + label)};
    data.ground_truth = {warp_ground_truth(scene.ground_truth.mat, transform),
                         scene.ground_truth.name + label};
    // A scene without masks (the 2005/2006 scenes, Aloe) keeps them empty.
    const auto mask = [&](const NamedMat& m) -> NamedMat {
        return m.mat.empty()
                   ? m
                   : NamedMat{warp_left(m.mat, transform, cv::INTER_NEAREST), m.name + label};
    };
    data.nonocc = mask(scene.nonocc);
    data.all = mask(scene.all);
    data.disc = mask(scene.disc);
    out.exact_ground_truth = {
        exact_ground_truth(scene.ground_truth.mat, transform, &out.exact_vertical),
        scene.ground_truth.name + " (exact warp)"};
    return out;
}

}  // namespace stereo::io

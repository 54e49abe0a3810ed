// Synthetic decalibration of a stereo pair for the evaluation of the hierarchical search
// (docs/results-hierarchical.md): radial lens distortion of both images, and a vertical shift
// and a rotation of the right image. OpenCV remap; the model never sees this code.
//
// Coordinates are pixel centres: pixel (x, y) is the point (x, y); the image centre is
// ((W-1)/2, (H-1)/2) and the half-diagonal R = hypot(W, H) / 2 reaches the outer image corner.
#pragma once

#include <opencv2/core/mat.hpp>

#include "stereo_io/middlebury.hpp"

namespace stereo::io {

// One-parameter division model (Fitzgibbon): with radii normalised by R,
//   undistorted = centre + (distorted - centre) / (1 + lambda * rho_d^2).
// "Distortion P %": a point at the undistorted image corner (rho_u = 1) is drawn P % of the
// half-diagonal closer to the centre (rho_d = 1 - P/100): P > 0 is barrel, P < 0 pincushion.
// Hence lambda = -p / (1 - p)^2 with p = P / 100. Both directions are closed-form.
class RadialDistortion {
  public:
    RadialDistortion(int width, int height, double percent);

    double half_diagonal() const { return half_diagonal_; }
    double lambda() const { return lambda_; }
    cv::Point2d distort(cv::Point2d undistorted) const;
    cv::Point2d undistort(cv::Point2d distorted) const;

  private:
    cv::Point2d centre_;
    double half_diagonal_;
    double lambda_;
};

// out(q) = image(lens.undistort(q)), outside the source black (0).
cv::Mat distort_image(const cv::Mat& image, const RadialDistortion& lens, int interpolation);

// What is done to a pair. The right camera is first misaligned (rotated by `right_rotation_deg`
// about the image centre, counter-clockwise on screen, then moved down by `right_shift_y`
// pixels), then both images pass through the same lens.
struct PairWarp {
    double distortion_percent = 0.0;
    double right_shift_y = 0.0;
    double right_rotation_deg = 0.0;
};

// Point maps of a PairWarp: original image position -> output position, and back.
class PairTransform {
  public:
    PairTransform(int width, int height, const PairWarp& warp);
    cv::Point2d left(cv::Point2d p) const { return lens_.distort(p); }
    cv::Point2d left_inverse(cv::Point2d q) const { return lens_.undistort(q); }
    cv::Point2d right(cv::Point2d p) const;
    cv::Point2d right_inverse(cv::Point2d q) const;

  private:
    RadialDistortion lens_;
    cv::Point2d centre_;
    double cos_;
    double sin_;
    double shift_y_;
};

// A Middlebury scene after a PairWarp. `data.ground_truth` is the thesis' ground truth: the
// original disparity map distorted like the left image (values unchanged, nearest sample).
// `exact_ground_truth` follows every known pixel through the warp instead: left output q comes
// from p = left_inverse(q), its match p - (gt, 0) goes to q_r = right(p - (gt, 0)), and the
// horizontal / vertical disparities are q.x - q_r.x and q_r.y - q.y (0 / NaN where unknown).
struct WarpedScene {
    SceneData data;
    NamedMat exact_ground_truth;  // CV_32FC1, 0 = unknown
    cv::Mat exact_vertical;       // CV_32FC1, NaN = unknown
};

WarpedScene warp_scene(const SceneData& scene, const PairWarp& warp);

// The same for loose files (`stereo distort`): images bilinear, ground truth and masks nearest.
cv::Mat warp_left(const cv::Mat& image, const PairTransform& transform, int interpolation);
cv::Mat warp_right(const cv::Mat& image, const PairTransform& transform, int interpolation);
// Both ground truths of a CV_32FC1 disparity map (0 = unknown) under the warp.
cv::Mat warp_ground_truth(const cv::Mat& ground_truth, const PairTransform& transform);
cv::Mat exact_ground_truth(const cv::Mat& ground_truth, const PairTransform& transform,
                           cv::Mat* vertical = nullptr);

}  // namespace stereo::io

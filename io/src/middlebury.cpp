#include "stereo_io/middlebury.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace stereo::io {
namespace fs = std::filesystem;

const std::vector<MiddleburyScene>& middlebury2003_scenes() {
    static const std::vector<MiddleburyScene> scenes = {
        {"tsukuba", 16, 16.0}, {"venus", 20, 8.0}, {"teddy", 60, 4.0}, {"cones", 60, 4.0}};
    return scenes;
}

fs::path scene_dir(const fs::path& data_dir, const MiddleburyScene& scene) {
    return data_dir / "middlebury2003" / scene.name;
}

std::optional<SceneData> load_scene(const fs::path& data_dir, const MiddleburyScene& scene) {
    const fs::path dir = scene_dir(data_dir, scene);
    for (const char* file :
         {"left.png", "right.png", "gt.png", "nonocc.png", "all.png", "disc.png"}) {
        if (!fs::exists(dir / file)) {
            return std::nullopt;
        }
    }
    SceneData data{scene,
                   load_pair(dir / "left.png", dir / "right.png"),
                   load_bgr(dir / "left.png"),
                   load_bgr(dir / "right.png"),
                   {load_disparity(dir / "gt.png", scene.gt_scale), (dir / "gt.png").string()},
                   {load_mask(dir / "nonocc.png"), (dir / "nonocc.png").string()},
                   {load_mask(dir / "all.png"), (dir / "all.png").string()},
                   {load_mask(dir / "disc.png"), (dir / "disc.png").string()}};
    return data;
}

EvalResult evaluate_scene(const SceneData& data, const cv::Mat& disparity) {
    EvalInput input{{disparity, "disparity of " + data.scene.name}, data.ground_truth};
    input.nonocc = data.nonocc;
    input.all = data.all;
    input.disc = data.disc;
    return evaluate(input);
}

namespace {

int round_up_16(int ndisp) {
    return (ndisp + 15) / 16 * 16;
}

// OpenCV returns disparity * 16 in CV_16S, with (minDisparity - 1) * 16 where it found none.
cv::Mat from_opencv(const cv::Mat& fixed16) {
    cv::Mat out(fixed16.size(), CV_32FC1, cv::Scalar(0));
    for (int y = 0; y < fixed16.rows; ++y) {
        for (int x = 0; x < fixed16.cols; ++x) {
            const short raw = fixed16.at<short>(y, x);
            // 0 is "invalid" in our convention; a true 0 disparity has no depth anyway.
            out.at<float>(y, x) = raw > 0 ? raw / 16.0f : 0.0f;
        }
    }
    return out;
}

}  // namespace

cv::Mat run_stereo_bm(const SceneData& data, int window) {
    cv::Mat left_grey;
    cv::Mat right_grey;
    cv::cvtColor(data.left_bgr, left_grey, cv::COLOR_BGR2GRAY);
    cv::cvtColor(data.right_bgr, right_grey, cv::COLOR_BGR2GRAY);
    const auto bm = cv::StereoBM::create(round_up_16(data.scene.ndisp), window);
    cv::Mat raw;
    bm->compute(left_grey, right_grey, raw);
    return from_opencv(raw);
}

cv::Mat run_stereo_sgbm(const SceneData& data) {
    // The settings of OpenCV's own stereo_match sample for colour input, block size 5.
    constexpr int kBlock = 5;
    constexpr int kChannels = 3;
    const auto sgbm = cv::StereoSGBM::create(
        0, round_up_16(data.scene.ndisp), kBlock, 8 * kChannels * kBlock * kBlock,
        32 * kChannels * kBlock * kBlock, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM);
    cv::Mat raw;
    sgbm->compute(data.left_bgr, data.right_bgr, raw);
    return from_opencv(raw);
}

double disagreement(const DisparityMap& a, const DisparityMap& b) {
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.disparity.size(); ++i) {
        differ += (a.disparity[i] != b.disparity[i] || a.valid[i] != b.valid[i]) ? 1 : 0;
    }
    return a.disparity.empty() ? 0.0 : static_cast<double>(differ) / a.disparity.size();
}

}  // namespace stereo::io

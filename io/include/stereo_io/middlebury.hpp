// The Middlebury 2003 pairs (Tsukuba, Venus, Teddy, Cones) as evaluation scenes, and the
// OpenCV baselines we compare against. Used by `stereo middlebury` and the regression tests.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereo/pipeline.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/metrics.hpp"

namespace stereo::io {

struct MiddleburyScene {
    std::string name;  // folder under middlebury2003/
    int ndisp;         // search range from the data README (labels 0..ndisp-1)
    double gt_scale;   // gt.png holds disparity * gt_scale
};

// tsukuba 16 / 16, venus 20 / 8, teddy 60 / 4, cones 60 / 4.
const std::vector<MiddleburyScene>& middlebury2003_scenes();

struct SceneData {
    MiddleburyScene scene;
    ImagePair pair;    // RGB, as the model reads it
    cv::Mat left_bgr;  // for figures and the OpenCV baselines
    cv::Mat right_bgr;
    NamedMat ground_truth;  // CV_32FC1 disparity, 0 = unknown
    NamedMat nonocc;
    NamedMat all;
    NamedMat disc;
};

// Folder of one scene: <data_dir>/middlebury2003/<name>.
std::filesystem::path scene_dir(const std::filesystem::path& data_dir,
                                const MiddleburyScene& scene);

// nullopt when the scene's files are absent (callers skip); throws when present but broken.
std::optional<SceneData> load_scene(const std::filesystem::path& data_dir,
                                    const MiddleburyScene& scene);

EvalResult evaluate_scene(const SceneData& data, const cv::Mat& disparity);

// OpenCV baselines on the same pair, as float disparities with 0 = invalid. Parameters are
// documented in docs/results.md; numDisparities is ndisp rounded up to a multiple of 16.
cv::Mat run_stereo_bm(const SceneData& data, int window);
cv::Mat run_stereo_sgbm(const SceneData& data);

// Fraction of pixels where two maps disagree (a different disparity or validity).
double disagreement(const DisparityMap& a, const DisparityMap& b);

}  // namespace stereo::io

// The scenes with ground truth that the evaluations share (experiments.hpp).
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "experiments.hpp"
#include "stereo/defaults.hpp"
#include "stereo/speckle.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;

// A scene outside middlebury2003/: view1/view5/disp1 (2005, 2006 half size) or Aloe.
std::optional<io::SceneData> load_extra(const fs::path& left, const fs::path& right,
                                        const fs::path& gt, const io::MiddleburyScene& scene,
                                        int downscale) {
    if (!fs::exists(left) || !fs::exists(right) || !fs::exists(gt)) {
        return std::nullopt;
    }
    io::SceneData data;
    data.scene = scene;
    data.pair = io::load_pair(left, right, downscale);
    data.left_bgr = io::shrink_area(io::load_bgr(left), downscale);
    data.right_bgr = io::shrink_area(io::load_bgr(right), downscale);
    data.ground_truth = {
        io::downscale_ground_truth(io::load_disparity(gt, scene.gt_scale), downscale), gt.string()};
    return data;
}

}  // namespace

ValidatedDisparity match_as_stereo_match(const Image& left, const Image& right,
                                         MatchParams params) {
    const defaults::Validation chosen = defaults::validation_for(params.cost);
    params.validation = {true, chosen.uniqueness, true, chosen.lr_tolerance, true};
    ValidatedDisparity map = match_validated(left, right, params);
    speckle::filter(map, speckle::Params::defaults());
    return map;
}

std::string fmt(double value, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

std::vector<io::SceneData> load_2003_scenes(const fs::path& root) {
    std::vector<io::SceneData> scenes;
    for (const auto& scene : io::middlebury2003_scenes()) {
        if (auto data = io::load_scene(root, scene)) {
            scenes.push_back(std::move(*data));
        }
    }
    return scenes;
}

std::vector<io::SceneData> load_ground_truth_scenes(const fs::path& root) {
    std::vector<io::SceneData> scenes = load_2003_scenes(root);
    // The 2005/2006 README gives the range 0..128 at half size; Aloe's GT reaches 211 at full
    // size, 106 at half.
    for (const auto& [folder, name] :
         {std::pair{"middlebury2005", "Reindeer"}, std::pair{"middlebury2006", "Cloth3"},
          std::pair{"middlebury2006", "Wood2"}}) {
        const fs::path dir = root / folder / name;
        if (auto data = load_extra(dir / "view1.png", dir / "view5.png", dir / "disp1.png",
                                   {name, 128, 2.0}, 1)) {
            scenes.push_back(std::move(*data));
        }
    }
    const fs::path aloe = root / "aloe";
    if (auto data = load_extra(aloe / "aloeL.jpg", aloe / "aloeR.jpg", aloe / "aloeGT.png",
                               {"Aloe (half)", 112, 1.0}, 2)) {
        scenes.push_back(std::move(*data));
    }
    return scenes;
}

}  // namespace stereo::experiments

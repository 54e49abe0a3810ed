// libFuzzer harness: the KITTI text formats on arbitrary bytes: the calibration (robot
// load_calibration, slam::load_kitti_camera and the rig checks after them), the pose file
// (slam::load_kitti_poses) and the avoidance frame list (pairs_from_list).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/slam/dataset.hpp"
#include "stereo_robot/slam/evaluation.hpp"
#include "stereo_robot/slam/pipeline.hpp"

namespace robot = stereo::robot;
using stereo::fuzz::expect_documented_errors;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static stereo::fuzz::ScratchFile file("kitti.txt");
    const auto& path = file.write(data, size);
    expect_documented_errors("load_calibration", [&] {
        const robot::StereoGeometry geometry = robot::load_calibration(path);
        (void)robot::disparity_threshold(geometry, 5.0, 2);
    });
    expect_documented_errors("load_kitti_camera", [&] {
        const robot::slam::Camera camera = robot::slam::load_kitti_camera(path);
        robot::slam::validate_camera(camera, 1241, 376);
    });
    expect_documented_errors("load_kitti_poses", [&] {
        const robot::slam::Trajectory poses = robot::slam::load_kitti_poses(path);
        if (!poses.empty()) {
            (void)robot::slam::relative_to_first(poses);
            (void)robot::slam::drift(poses);
            (void)robot::slam::format_kitti_poses(poses);
        }
    });
    expect_documented_errors("pairs_from_list", [&] { (void)robot::pairs_from_list(path); });
    return 0;
}

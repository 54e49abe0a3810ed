// libFuzzer harness: the EuRoC rectification YAML (yaml-cpp, robot/src/slam/dataset.cpp) on
// arbitrary bytes, through slam::open_sequence on a one-frame EuRoC folder made at start-up,
// then the rig checks `stereo slam` applies (slam::validate_camera).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include <unistd.h>
#include <opencv2/core.hpp>

#include "fuzz_support.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/limits.hpp"
#include "stereo_robot/slam/dataset.hpp"
#include "stereo_robot/slam/pipeline.hpp"

namespace {

namespace fs = std::filesystem;
namespace slam = stereo::robot::slam;

// The rectification maps are allocated from the declared size: bounded like an image, here low
// enough to keep every input fast.
constexpr std::int64_t kFuzzMaxPixels = std::int64_t{1} << 16;

// SEQ/cam0/data/0.png and SEQ/cam1/data/0.png, removed at exit.
struct EurocFolder {
    fs::path root = fs::temp_directory_path() / ("stereo_fuzz_euroc_" + std::to_string(::getpid()));
    EurocFolder() {
        const cv::Mat frame(12, 16, CV_8UC1, cv::Scalar(128));
        for (const char* camera : {"cam0", "cam1"}) {
            fs::create_directories(root / camera / "data");
            stereo::io::write_png(root / camera / "data" / "0.png", frame);
        }
    }
    ~EurocFolder() {
        std::error_code ignored;
        fs::remove_all(root, ignored);
    }
    EurocFolder(const EurocFolder&) = delete;
    EurocFolder& operator=(const EurocFolder&) = delete;
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    stereo::io::set_max_image_pixels(kFuzzMaxPixels);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const EurocFolder folder;
    static stereo::fuzz::ScratchFile file("rectification.yaml");
    const auto& path = file.write(data, size);
    stereo::fuzz::expect_documented_errors("open_sequence (euroc)", [&] {
        const slam::Sequence sequence = slam::open_sequence(folder.root, slam::Layout::euroc, path);
        slam::validate_camera(sequence.camera, sequence.size.width, sequence.size.height);
    });
    return 0;
}

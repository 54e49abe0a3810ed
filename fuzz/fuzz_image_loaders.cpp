// libFuzzer harness: the image loaders of stereo_io on arbitrary bytes. The header-size check
// (io::declared_size) sees the raw bytes; load_image, load_disparity and load_mask read them from
// a file, as `stereo match`, `eval` and `avoid` do. Findings: crashes, leaks, undefined
// behaviour, undocumented exceptions, and allocations beyond libFuzzer's -rss_limit_mb.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include <opencv2/core/utils/logger.hpp>

#include "fuzz_support.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/limits.hpp"

namespace {

namespace io = stereo::io;

// 4 Mpixel: large enough for any decoder path, small enough that a legitimate image stays far
// below the fuzzer's memory limit.
constexpr std::int64_t kFuzzMaxPixels = std::int64_t{1} << 22;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    io::set_max_image_pixels(kFuzzMaxPixels);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    if (const auto declared = io::declared_size(bytes); declared) {
        if (declared->first < 0 || declared->second < 0) {
            std::abort();  // a size is never negative
        }
    }
    static stereo::fuzz::ScratchFile file("image");
    const auto& path = file.write(data, size);
    stereo::fuzz::expect_documented_errors("load_image", [&] {
        const stereo::Image image = io::load_image(path);
        if (static_cast<std::int64_t>(image.width) * image.height > kFuzzMaxPixels) {
            std::abort();  // the limit let a larger image through
        }
    });
    // The grey loaders on every other input: each decode costs as much as the first.
    if (size % 2 == 0) {
        stereo::fuzz::expect_documented_errors("load_disparity",
                                               [&] { (void)io::load_disparity(path, 4.0); });
    } else {
        stereo::fuzz::expect_documented_errors("load_mask", [&] { (void)io::load_mask(path); });
    }
    return 0;
}

// `disparity LEFT RIGHT OUT.pfm|OUT.png [NDISP [DOWNSCALE]]`: two images in (through OpenCV,
// area-averaged by DOWNSCALE), `stereo match`'s default map out (PFM in pixels, or an 8-bit PNG
// of the labels x 255 / NDISP), written atomically. The default run is the library's one
// definition of it, stereo::defaults::match_config(): the default cost (census), stage 6 with
// that cost's uniqueness ratio and left-right tolerance, sub-pixel output and the speckle filter.
// The smallest program built on the installed package (examples/consumer/CMakeLists.txt). NDISP
// must cover the pair's largest disparity at that scale: Aloe (1282x1110, up to about 211 px)
// needs 128 labels at DOWNSCALE 2.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "stereo/defaults.hpp"
#include "stereo/matcher.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: disparity LEFT RIGHT OUT.pfm|OUT.png [NDISP [DOWNSCALE]]\n");
        return 2;
    }
    try {
        const int downscale = argc > 5 ? std::stoi(argv[5]) : 1;
        const stereo::io::ImagePair pair = stereo::io::load_pair(argv[1], argv[2], downscale);
        // What `stereo match LEFT RIGHT --ndisp NDISP` runs: the default method on the model.
        stereo::MatchConfig config = stereo::defaults::match_config();
        if (argc > 4) {
            config.pipeline.ndisp = std::stoi(argv[4]);
        }
        stereo::MatcherRegistry registry;
        stereo::register_model_matchers(registry);
        const auto matcher = registry.create("pipeline", "model", config);
        const stereo::MatchResult result = matcher->compute(pair.left, pair.right);
        const std::string out = argv[3];
        if (out.ends_with(".pfm")) {
            stereo::io::write_file_atomic(
                out, stereo::io::encode_pfm(stereo::io::to_float_disparity(result.validated)));
        } else {
            stereo::io::write_png(
                out, stereo::io::disparity_to_mat(result.disparity, config.pipeline.ndisp,
                                                  std::max(1, 255 / config.pipeline.ndisp)));
        }
        int valid = 0;
        for (const auto v : result.disparity.valid) {
            valid += v;
        }
        std::printf("%dx%d, %d valid pixels\n", pair.left.width, pair.left.height, valid);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "disparity: error: %s\n", error.what());
        return 1;
    }
}

// C-simulation testbench of stereo_hls_synth_top for the vendor flow (csim_design and
// cosim_design in scripts/hls/run_vitis_hls.tcl) and for g++ (target tb_stereo_hls).
//
// Vitis' C simulation has no image library, so the pair is synthetic: a random texture and its
// copy shifted by a slanted disparity plane (4 .. 44 pixels) with noise. Two frames run back to
// back through the one static state of the top: the full 640x480 frame with 64 disparities,
// 11x11 and the CA rules, then a 200x120 frame with 32 disparities, 7x7, no CA (a smaller
// runtime configuration). Each output is compared pixel by pixel with stereo::match, the
// golden model compiled into the testbench. Exit code 0 when all are equal.
//
// Usage: tb_stereo_hls [--quick] [seed]
//   --quick  only the small frame (for C/RTL co-simulation, where the full frame is slow)
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#include "stereo/hls/host.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_hls_synth_top.hpp"

namespace {

using namespace stereo;

struct Pair {
    Image left;
    Image right;
};

Pair synthetic_pair(int width, int height, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> texture(0, 255);
    std::uniform_int_distribution<int> noise(-2, 2);
    Pair pair{Image(width, height, 3), Image(width, height, 3)};
    for (auto& p : pair.left.pixels) {
        p = static_cast<std::uint8_t>(texture(rng));
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int disparity = 4 + 40 * (x + y) / (width + height);
            const int source = std::min(x + disparity, width - 1);
            for (int c = 0; c < 3; ++c) {
                const int v = pair.left.at(source, y, c) + noise(rng);
                pair.right.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
            }
        }
    }
    return pair;
}

Image crop(const Image& image, int width, int height) {
    Image out(width, height, image.channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                out.at(x, y, c) = image.at(x, y, c);
            }
        }
    }
    return out;
}

// Runs one frame through the synthesis top and returns the number of mismatching pixels.
long run_frame(const char* name, const Image& left, const Image& right, const MatchParams& params) {
    namespace hls = stereo::hls;
    const auto cfg = hls::frame_config<hls::synth::kWindow>(params, left.width, left.height);
    hls::stream<hls::InputBeat> in("tb.in");
    hls::stream<hls::OutputBeat> out("tb.out");
    hls::push_frame(left, right, in);
    const hls::status_t status = stereo_hls_synth_top(
        in, out, static_cast<std::uint16_t>(cfg.width), static_cast<std::uint16_t>(cfg.height),
        static_cast<std::uint16_t>(cfg.ndisp), static_cast<std::uint8_t>(cfg.radius), cfg.kernel,
        cfg.use_ca, static_cast<std::int16_t>(cfg.min_disp), cfg.uniqueness,
        static_cast<std::uint8_t>(cfg.uniqueness_ratio), cfg.left_right,
        static_cast<std::uint8_t>(cfg.lr_tolerance), cfg.subpixel);
    const DisparityMap actual = hls::collect_frame(out, left.width, left.height);
    const DisparityMap expected = stereo::match(left, right, params);
    long mismatches = 0;
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            const std::size_t i = expected.index(x, y);
            if (actual.disparity[i] != expected.disparity[i] ||
                actual.valid[i] != expected.valid[i]) {
                if (++mismatches <= 10) {
                    std::printf("  %s (%d, %d): hls %d/%d model %d/%d\n", name, x, y,
                                actual.disparity[i], actual.valid[i], expected.disparity[i],
                                expected.valid[i]);
                }
            }
        }
    }
    std::printf("%s: %dx%d ndisp %d window %d ca %s: status %u, %ld of %d pixels differ\n", name,
                left.width, left.height, params.ndisp, params.window, params.use_ca ? "on" : "off",
                static_cast<unsigned>(status), mismatches, left.width * left.height);
    return mismatches + (status != 0 ? 1 : 0) + (out.empty() && in.empty() ? 0 : 1);
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    std::uint32_t seed = 2010U;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else {
            seed = static_cast<std::uint32_t>(std::strtoul(argv[i], nullptr, 10));
        }
    }
    std::printf("tb_stereo_hls: seed %u%s\n", static_cast<unsigned>(seed), quick ? ", quick" : "");
    namespace synth = stereo::hls::synth;
    const Pair pair = synthetic_pair(synth::kWidth, synth::kHeight, seed);
    long failures = 0;
    try {
        if (!quick) {
            failures +=
                run_frame("full", pair.left, pair.right,
                          MatchParams{synth::kNdisp, synth::kWindow, fx::kDefaultSigma, true});
        }
        failures += run_frame("small", crop(pair.left, 200, 120), crop(pair.right, 200, 120),
                              MatchParams{32, 7, 2.0, false});
    } catch (const std::exception& error) {
        std::printf("tb_stereo_hls: error: %s\n", error.what());
        return 2;
    }
    std::printf("tb_stereo_hls: %s\n", failures == 0 ? "PASS" : "FAIL");
    return failures == 0 ? 0 : 1;
}

// stereo_cost with COST = 1 (two stereo_lcdm_convert, one stereo_lcdm_distance per label) against
// the model's "lcdm" cost plug-in:
// every cost of every pixel and disparity, with random clock enables, odd and tiny frames, every
// colour of the RGB cube's edges and faces, constant images, a real crop, frames back to back and
// signed disparity ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <ostream>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_cost_lcdm.h"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_cost_lcdm").params.ndisp;
constexpr int kCostBits = fx::kCostBits;

struct CostStage {
    using Model = Vstereo_cost_lcdm;
    static constexpr const char* kName = "stereo_cost (COST = 1)";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_left, table::kRgbBits, rng);
        randomize_bits(model.in_right, table::kRgbBits, rng);
    }
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return port_words(model.out_data);
    }
};

using CostDriver = StageDriver<CostStage>;

// The model's LCDM cost volume over d = min_disp .. min_disp + ndisp - 1.
Dsi model_cost(const Image& left, const Image& right, int ndisp, int min_disp = 0) {
    return cost_volume(*make_cost("lcdm"), left, right, ndisp, min_disp);
}

// {R, G, B} with R in [23:16]; a grey pixel g is (g, g, g), as stereo_top feeds it.
std::uint32_t rgb(const Image& image, int x, int y) {
    if (image.channels == 1) {
        const std::uint32_t g = image.at(x, y, 0);
        return (g << 16) | (g << 8) | g;
    }
    return (std::uint32_t{image.at(x, y, 0)} << 16) | (std::uint32_t{image.at(x, y, 1)} << 8) |
           image.at(x, y, 2);
}

Dsi run_cost(CostDriver& driver, const Image& left, const Image& right, int min_disp = 0) {
    Dsi rtl(left.width, left.height, kDisparities);
    driver.model().cfg_width = static_cast<std::uint16_t>(left.width);
    driver.model().cfg_min_disp = static_cast<std::uint16_t>(static_cast<unsigned>(min_disp) &
                                                             ((1U << table::kCfgMinDispBits) - 1));
    driver.run_frame(
        left.width, left.height,
        [&](Vstereo_cost_lcdm& model, int x, int y) {
            model.in_left = rgb(left, x, y);
            model.in_right = rgb(right, x, y);
        },
        [&](const Vstereo_cost_lcdm& model, int x, int y) {
            get_column(model.out_data, rtl, x, y, kCostBits);
        });
    return rtl;
}

struct RandomCase {
    int width, height;
    bool shifted;  // right = shifted left (low costs near d = 3) or independent
    double ce_low;
};

// Test names, and the parameter as ctest and GoogleTest print it.
std::string describe(const RandomCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) +
           (c.shifted ? "_shifted" : "_independent") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

using tb::PrintTo;  // by describe()

class RandomPairs : public ::testing::TestWithParam<RandomCase> {};

TEST_P(RandomPairs, EveryCostEqualsTheModel) {
    const RandomCase c = GetParam();
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    CostDriver driver(seed, c.ce_low);
    for (int frame = 0; frame < kFramesPerCase; ++frame) {
        const Image left = test::random_image(c.width, c.height, 3, rng);
        const Image right = c.shifted ? test::shifted_copy(left, 3, 20, rng)
                                      : test::random_image(c.width, c.height, 3, rng);
        EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities),
                                run_cost(driver, left, right), kDisparities))
            << "frame " << frame;
    }
}

INSTANTIATE_TEST_SUITE_P(LcdmCost, RandomPairs,
                         ::testing::Values(RandomCase{64, 48, true, 0.0},
                                           RandomCase{64, 48, false, 0.3},
                                           RandomCase{37, 23, true, 0.2},
                                           RandomCase{13, 9, false, 0.5},  // W < NDISP
                                           RandomCase{3, 3, true, 0.3}),
                         case_name<RandomCase>);

TEST(LcdmCostExtremes, ConstantImagesGiveZeroAndTheMaximum) {
    const std::uint32_t seed = test_seed();
    CostDriver driver(seed, 0.2);
    for (const auto& [l, r, left, right] : test::constant_pairs(64, 48, 3)) {
        EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities),
                                run_cost(driver, left, right), kDisparities))
            << "left " << l << " right " << r;
    }
}

TEST(LcdmCostExtremes, EveryEdgeAndFaceColourOfTheCube) {
    // Every hue sector, every tie of the maximum, both sides of the lightness fold, the dark
    // floor and grey.
    const auto [left, right] = test::rgb_cube_pair(64, 36);
    CostDriver driver(test_seed(), 0.2);
    EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities), run_cost(driver, left, right),
                            kDisparities));
}

// Frames follow each other without reset or idle steps, with different sizes: the delay line
// holds the previous frame's flush garbage when the next frame starts.
TEST(LcdmCostFraming, BackToBackFramesOfDifferentSizes) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    CostDriver driver(seed, 0.1);
    for (const auto& [width, height] :
         {std::pair{64, 48}, std::pair{37, 23}, std::pair{5, 7}, std::pair{64, 48}}) {
        const Image left = test::random_image(width, height, 3, rng);
        const Image right = test::shifted_copy(left, 2, 30, rng);
        EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities),
                                run_cost(driver, left, right), kDisparities))
            << width << "x" << height;
    }
}

// Signed ranges: the LCDM points go through the same left delay line and right taps as the AD
// stage's pixels.
TEST(LcdmCostMinDisparity, EveryCostEqualsTheModelForEverySignedRange) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    CostDriver driver(seed, 0.2);
    constexpr int kMax = table::kDefaultMaxMinDisp;
    for (const int min_disp : {-kMax, -3, 0, 2, kMax}) {
        const Image left = test::random_image(29, 9, 3, rng);
        const Image right = test::shifted_copy(left, 2, 30, rng);
        driver.reset();  // as stereo_top clears the coordinates after a frame
        EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities, min_disp),
                                run_cost(driver, left, right, min_disp), kDisparities))
            << "min_disp " << min_disp;
    }
}

TEST(LcdmCostRealImages, TsukubaCrop) {
    const auto dir = io::data_dir() / "middlebury2003" / "tsukuba";
    if (!std::filesystem::exists(dir / "left.png") || !std::filesystem::exists(dir / "right.png")) {
        GTEST_SKIP() << "tsukuba not found in " << dir;
    }
    const auto pair = io::load_pair(dir / "left.png", dir / "right.png");
    auto crop = [](const Image& image) {
        Image out(64, 48, image.channels);
        for (int y = 0; y < out.height; ++y) {
            for (int x = 0; x < out.width; ++x) {
                for (int c = 0; c < image.channels; ++c) {
                    out.at(x, y, c) = image.at(150 + x, 100 + y, c);
                }
            }
        }
        return out;
    };
    const Image left = crop(pair.left);
    const Image right = crop(pair.right);
    CostDriver driver(test_seed(), 0.2);
    EXPECT_TRUE(same_volume(model_cost(left, right, kDisparities), run_cost(driver, left, right),
                            kDisparities));
}

}  // namespace
}  // namespace stereo::tb

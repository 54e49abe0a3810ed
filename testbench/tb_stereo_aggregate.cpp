// stereo_aggregate against stereo::aggregate: every aggregated value of every pixel and disparity
// for cost volumes of random pairs (765 where x - d < 0) and uniformly random volumes, the 5x5
// window and the runtime windows 3x3 and 1x1 (centred in the 5 taps), other sigmas, asymmetric
// kernels (tap orientation), extreme volumes (widest sums), odd and tiny frames, random clock
// enables, and frames back to back; and the constant-kernel variant (RUNTIME_KERNEL = 0) that the
// FPGA top synthesizes, against the model's default kernel whatever cfg_kernel holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_aggregate.h"
#include "Vstereo_aggregate_const.h"
#include "stereo/pipeline.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_aggregate").params.ndisp;
constexpr int kWindow = 5;  // WINDOW of Vstereo_aggregate
constexpr int kTapBits = table::kTapBits;

template <typename VerilatedModel>
struct AggregatePorts : ColumnOutputPorts<VerilatedModel> {
    using Model = VerilatedModel;
    static constexpr const char* kName = "stereo_aggregate";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_data, kDisparities * fx::kCostBits, rng);
        model.in_next_y = static_cast<std::uint16_t>(rng());  // only taken at a step
    }
    // in_next_y: the row of the step after this one (stereo_top: the cost stage's out_next_y).
    static void announce_next_row(Model& model, std::uint16_t next_y) { model.in_next_y = next_y; }
};

using AggregateDriver = StageDriver<AggregatePorts<Vstereo_aggregate>>;
using ConstantKernelDriver = StageDriver<AggregatePorts<Vstereo_aggregate_const>>;

// A kernel of `taps.size()` taps centred in the core's kWindow-tap field, zeros around it.
std::vector<std::int32_t> centred(const std::vector<std::int32_t>& taps) {
    std::vector<std::int32_t> field(kWindow, 0);
    std::copy(taps.begin(), taps.end(), field.begin() + (kWindow - std::ssize(taps)) / 2);
    return field;
}

// Runs one frame of `costs` with `kernel` (the model's taps, any odd count up to kWindow) on
// cfg_kernel.
template <typename Driver>
Dsi run_aggregate(Driver& driver, const Dsi& costs, const std::vector<std::int32_t>& kernel) {
    auto& model = driver.model();
    put_config(model.cfg,
               {{ConfigField::width, costs.width()}, {ConfigField::height, costs.height()}});
    const auto field = centred(kernel);
    for (int i = 0; i < kWindow; ++i) {
        put_bits(model.cfg_kernel, i * kTapBits, kTapBits,
                 static_cast<std::uint64_t>(field[static_cast<std::size_t>(i)]));
    }
    Dsi rtl(costs.width(), costs.height(), kDisparities);
    driver.run_frame(
        costs.width(), costs.height(),
        [&](auto& m, int x, int y) { put_column(m.in_data, costs, x, y, fx::kCostBits); },
        [&](const auto& m, int x, int y) { get_column(m.out_data, rtl, x, y, fx::kAggBits); });
    return rtl;
}

enum class Input { kPairCost, kUniform };

struct RandomCase {
    int width, height, window;
    double sigma;
    Input input;
    double ce_low;
};

// Test names, and the parameter as ctest and GoogleTest print it.
std::string describe(const RandomCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_window" +
           std::to_string(c.window) + "_sigma" + std::to_string(static_cast<int>(c.sigma * 10)) +
           (c.input == Input::kPairCost ? "_pair" : "_uniform") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

using tb::PrintTo;  // by describe()

class RandomVolumes : public ::testing::TestWithParam<RandomCase> {};

TEST_P(RandomVolumes, EveryValueEqualsTheModel) {
    const RandomCase c = GetParam();
    const auto kernel = gaussian_kernel(c.window, c.sigma);
    check_frames<AggregateDriver>(
        c.ce_low, [&](AggregateDriver& driver, std::mt19937& rng, int frame) {
            const Dsi costs =
                c.input == Input::kPairCost
                    ? pair_cost(c.width, c.height, kDisparities, 3, rng)
                    : uniform_volume(c.width, c.height, kDisparities, 0, fx::kCostMax, rng);
            EXPECT_TRUE(same_volume(aggregate(costs, kernel), run_aggregate(driver, costs, kernel),
                                    kDisparities))
                << "frame " << frame;
        });
}

INSTANTIATE_TEST_SUITE_P(
    Aggregate, RandomVolumes,
    ::testing::Values(RandomCase{64, 48, 5, 3.0, Input::kPairCost, 0.0},
                      RandomCase{64, 48, 5, 3.0, Input::kUniform, 0.3},
                      RandomCase{64, 48, 3, 3.0, Input::kPairCost, 0.2},
                      RandomCase{64, 48, 3, 3.0, Input::kUniform, 0.1},
                      RandomCase{64, 48, 1, 3.0, Input::kUniform, 0.2},
                      RandomCase{64, 48, 5, 1.0, Input::kUniform, 0.2},  // peaked taps
                      RandomCase{37, 23, 5, 3.0, Input::kUniform, 0.25},
                      RandomCase{37, 23, 3, 3.0, Input::kPairCost, 0.25},
                      RandomCase{37, 23, 1, 3.0, Input::kPairCost, 0.0},
                      RandomCase{13, 9, 5, 3.0, Input::kPairCost, 0.5},
                      RandomCase{13, 9, 3, 0.8, Input::kUniform, 0.3},
                      RandomCase{13, 9, 1, 3.0, Input::kUniform, 0.3},
                      RandomCase{3, 3, 5, 3.0, Input::kUniform, 0.3},  // window wider than frame
                      RandomCase{3, 3, 3, 3.0, Input::kPairCost, 0.3},
                      RandomCase{3, 3, 1, 3.0, Input::kUniform, 0.0}),
    case_name<RandomCase>);

// Constant and checkerboard volumes: all-765 gives the widest window sum (765 * 2^16).
TEST(AggregateExtremes, ConstantAndCheckerboardVolumes) {
    const std::uint32_t seed = test_seed();
    AggregateDriver driver(seed, 0.2);
    const auto kernel = gaussian_kernel(5, fx::kDefaultSigma);
    for (const int pattern : {0, 1, 2}) {
        Dsi costs(64, 48, kDisparities);
        for (int d = 0; d < kDisparities; ++d) {
            for (int y = 0; y < costs.height(); ++y) {
                for (int x = 0; x < costs.width(); ++x) {
                    const bool high = pattern == 1 || (pattern == 2 && (x + y + d) % 2 == 0);
                    costs.at(x, y, d) = high ? fx::kCostMax : 0;
                }
            }
        }
        EXPECT_TRUE(same_volume(aggregate(costs, kernel), run_aggregate(driver, costs, kernel),
                                kDisparities))
            << "pattern " << pattern;
    }
}

// Gaussian kernels are symmetric, so they cannot tell tap i from tap WINDOW-1-i, nor rows from
// columns being mixed up. Random kernels (any non-negative taps summing to 256 are legal) can;
// a single tap of 256 picks out one off-centre neighbour.
TEST(AggregateKernels, AsymmetricKernels) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    AggregateDriver driver(seed, 0.2);
    auto random_kernel = [&](int taps) {
        std::vector<std::int32_t> kernel(static_cast<std::size_t>(taps), 0);
        std::uniform_int_distribution<int> pick(0, taps - 1);
        for (int unit = 0; unit < fx::kKernelSum; ++unit) {
            ++kernel[static_cast<std::size_t>(pick(rng))];
        }
        return kernel;
    };
    const std::vector<std::vector<std::int32_t>> kernels = {
        {256, 0, 0, 0, 0}, {0, 0, 0, 256, 0}, {0, 256, 0},     {200, 50, 6},
        random_kernel(5),  random_kernel(5),  random_kernel(3)};
    for (const auto& kernel : kernels) {
        const Dsi costs = uniform_volume(41, 29, kDisparities, 0, fx::kCostMax, rng);
        std::string taps;
        for (const auto tap : kernel) {
            taps += std::to_string(tap) + " ";
        }
        EXPECT_TRUE(same_volume(aggregate(costs, kernel), run_aggregate(driver, costs, kernel),
                                kDisparities))
            << "kernel " << taps;
    }
}

struct Frame {
    int width, height, window;
};

void expect_frames(AggregateDriver& driver, const std::vector<Frame>& frames, bool reset_between,
                   std::mt19937& rng) {
    for (const Frame& f : frames) {
        if (reset_between) {
            driver.reset();
        }
        const Dsi costs = pair_cost(f.width, f.height, kDisparities, 4, rng);
        const auto kernel = gaussian_kernel(f.window, fx::kDefaultSigma);
        EXPECT_TRUE(same_volume(aggregate(costs, kernel), run_aggregate(driver, costs, kernel),
                                kDisparities))
            << f.width << "x" << f.height << " window " << f.window;
    }
}

// Frames follow each other without reset or idle steps: the line buffer and the column history
// hold the previous frame and its flush garbage. The kernel may change between frames.
TEST(AggregateFraming, BackToBackFramesOfOneSize) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    AggregateDriver driver(seed, 0.1);
    expect_frames(driver, {{64, 48, 5}, {64, 48, 3}, {64, 48, 1}, {64, 48, 5}}, false, rng);
    expect_frames(driver, {{13, 9, 5}, {13, 9, 3}, {13, 9, 5}}, false, rng);
}

// Frames shrinking back to back: flush coordinates (y >= H) of the previous frame stay outside.
TEST(AggregateFraming, BackToBackFramesShrinking) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    AggregateDriver driver(seed, 0.1);
    expect_frames(driver, {{64, 48, 5}, {37, 23, 5}, {13, 9, 3}, {5, 4, 5}}, false, rng);
}

// Any size after a reset, which marks every coordinate register "no pixel".
TEST(AggregateFraming, AnySizeAfterReset) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    AggregateDriver driver(seed, 0.1);
    expect_frames(driver, {{13, 9, 5}, {64, 20, 1}, {37, 23, 3}, {64, 48, 5}, {3, 3, 5}}, true,
                  rng);
}

// A taller frame straight after a shorter one needs the coordinate registers cleared between
// them (flush filler has y >= the old height, inside the new frame): stereo_top does that when a
// frame's last output leaves, and AnySizeAfterReset above covers it at this level.

// Frames narrower than the radius: the output position wraps over several rows.
TEST(AggregateSizes, WidthOne) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    AggregateDriver driver(seed, 0.0);
    expect_frames(driver, {{1, 7, 5}}, true, rng);
}

// RUNTIME_KERNEL = 0 (the FPGA build): the taps are the model's default kernel for WINDOW,
// whatever cfg_kernel says; here cfg_kernel carries other kernels, which must have no effect.
TEST(AggregateConstantKernel, DefaultKernelWhateverCfgKernelHolds) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    ConstantKernelDriver driver(seed, 0.2);
    const auto default_kernel = gaussian_kernel(kWindow, fx::kDefaultSigma);
    const std::vector<std::vector<std::int32_t>> ignored = {
        {256, 0, 0, 0, 0}, {0, 256, 0}, gaussian_kernel(3, 1.0), default_kernel};
    const std::vector<std::pair<int, int>> sizes = {{64, 48}, {37, 23}, {5, 4}, {64, 48}};
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const auto [width, height] = sizes[i];
        driver.reset();  // a taller frame follows a shorter one (see AnySizeAfterReset)
        const Dsi costs = i % 2 == 0
                              ? pair_cost(width, height, kDisparities, 3, rng)
                              : uniform_volume(width, height, kDisparities, 0, fx::kCostMax, rng);
        EXPECT_TRUE(same_volume(aggregate(costs, default_kernel),
                                run_aggregate(driver, costs, ignored[i]), kDisparities))
            << width << "x" << height << " frame " << i;
    }
}

}  // namespace
}  // namespace stereo::tb

// stereo_wta against stereo::wta: the disparity and the valid flag of every pixel, for uniformly
// random volumes, volumes full of ties (values from a tiny range: ties go to the smallest d),
// the CA output of a random pair (a true disparity near the left border's validity limit),
// cfg_ndisp < NDISP with the unused planes holding values that would win if they took part,
// every reach = cfg_radius + cfg_use_ca from 0 to 3, odd and tiny frames, random clock enables,
// and frames back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <ostream>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_wta.h"
#include "stereo/pipeline.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_wta").params.ndisp;
constexpr int kBits = fx::kAggBits;

struct WtaStage {
    using Model = Vstereo_wta;
    static constexpr const char* kName = "stereo_wta";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_data, kDisparities * kBits, rng);
    }
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return {model.out_label, model.out_border, model.out_cost, model.out_before,
                model.out_after};
    }
};

using WtaDriver = StageDriver<WtaStage>;

struct WtaConfig {
    int ndisp;
    int radius;
    bool use_ca;
};

DisparityMap run_wta(WtaDriver& driver, const Dsi& input, const WtaConfig& config) {
    auto& model = driver.model();
    put_config(model.cfg, {{ConfigField::width, input.width()},
                           {ConfigField::height, input.height()},
                           {ConfigField::ndisp, config.ndisp},
                           {ConfigField::radius, config.radius},
                           {ConfigField::use_ca, config.use_ca ? 1 : 0},
                           // stage 6's signed range: tb_stereo_top and tb_stereo_validate
                           {ConfigField::min_disp, 0}});
    DisparityMap rtl(input.width(), input.height());
    driver.run_frame(
        input.width(), input.height(),
        [&](Vstereo_wta& m, int x, int y) { put_column(m.in_data, input, x, y, kBits); },
        [&](const Vstereo_wta& m, int x, int y) {
            // The label is the winner whatever the border rule says; the map writes 0 there.
            rtl.disparity[rtl.index(x, y)] = m.out_border ? m.out_label : 0;
            rtl.valid[rtl.index(x, y)] = m.out_border;
        });
    return rtl;
}

// The model's volume has exactly the cfg_ndisp planes the core uses.
DisparityMap expected_wta(const Dsi& input, const WtaConfig& config) {
    return wta(truncated(input, config.ndisp),
               InvalidBorder{config.radius + (config.use_ca ? 1 : 0)});
}

// ---- Inputs ----------------------------------------------------------------------------------

enum class Input { kUniform, kTies, kAllEqual, kPairCa };

const char* input_name(Input input) {
    constexpr std::array kNames{"uniform", "ties", "allequal", "pair"};  // in the enum's order
    return kNames.at(static_cast<std::size_t>(input));
}

// The full NDISP planes fed to the core. Planes d >= ndisp hold 0, below every used value
// (> 0 here), so they would win wherever the core let them take part.
Dsi make_input(Input input, int width, int height, int ndisp, std::mt19937& rng) {
    Dsi volume;
    switch (input) {
        case Input::kUniform:
            volume = uniform_volume(width, height, kDisparities, 1, fx::kAggMax, rng);
            break;
        case Input::kTies:  // three values: most pixels have a tie for the minimum
            volume = uniform_volume(width, height, kDisparities, 1, 3, rng);
            break;
        case Input::kAllEqual:  // the winner must be 0 everywhere
            volume = uniform_volume(width, height, kDisparities, fx::kAggMax, fx::kAggMax, rng);
            break;
        case Input::kPairCa: {  // true disparity 5; aggregates never reach 0 here
            volume = ca_rule2(ca_rule1(aggregate(pair_cost(width, height, kDisparities, 5, rng),
                                                 gaussian_kernel(5, fx::kDefaultSigma))));
            for (auto d = 0; d < kDisparities; ++d) {
                for (auto& cell : volume.plane(d)) {
                    cell = std::max<Dsi::Value>(cell, 1);
                }
            }
            break;
        }
    }
    for (int d = ndisp; d < kDisparities; ++d) {
        for (auto& cell : volume.plane(d)) {
            cell = 0;
        }
    }
    return volume;
}

struct WtaCase {
    int width, height;
    Input input;
    WtaConfig config;
    double ce_low;
};

// Test names, and the parameter as ctest and GoogleTest print it.
std::string describe(const WtaCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_" + input_name(c.input) +
           "_ndisp" + std::to_string(c.config.ndisp) + "_radius" + std::to_string(c.config.radius) +
           (c.config.use_ca ? "_ca" : "_noca") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

using tb::PrintTo;  // by describe()

class Volumes : public ::testing::TestWithParam<WtaCase> {};

TEST_P(Volumes, EveryPixelEqualsTheModel) {
    const WtaCase c = GetParam();
    check_frames<WtaDriver>(c.ce_low, [&](WtaDriver& driver, std::mt19937& rng, int frame) {
        const Dsi input = make_input(c.input, c.width, c.height, c.config.ndisp, rng);
        EXPECT_TRUE(same_map(expected_wta(input, c.config), run_wta(driver, input, c.config)))
            << "frame " << frame;
    });
}

INSTANTIATE_TEST_SUITE_P(
    Wta, Volumes,
    ::testing::Values(WtaCase{64, 48, Input::kUniform, {16, 2, true}, 0.0},
                      WtaCase{64, 48, Input::kUniform, {16, 2, false}, 0.3},
                      WtaCase{64, 48, Input::kTies, {16, 2, true}, 0.2},
                      WtaCase{64, 48, Input::kTies, {16, 0, false}, 0.2},
                      WtaCase{64, 48, Input::kAllEqual, {16, 1, true}, 0.2},
                      WtaCase{64, 48, Input::kPairCa, {16, 2, true}, 0.1},
                      WtaCase{64, 48, Input::kPairCa, {9, 2, true}, 0.1},
                      WtaCase{37, 23, Input::kUniform, {9, 1, true}, 0.25},
                      WtaCase{37, 23, Input::kTies, {5, 2, false}, 0.25},
                      WtaCase{37, 23, Input::kUniform, {15, 0, true}, 0.0},
                      WtaCase{13, 9, Input::kUniform, {16, 2, true}, 0.5},  // ndisp > valid x
                      WtaCase{13, 9, Input::kTies, {2, 1, false}, 0.3},
                      WtaCase{13, 9, Input::kUniform, {1, 0, false}, 0.3},  // one label
                      WtaCase{3, 3, Input::kUniform, {16, 0, false}, 0.3},
                      WtaCase{3, 3, Input::kTies, {4, 0, true}, 0.0},       // only the centre valid
                      WtaCase{3, 3, Input::kUniform, {16, 2, true}, 0.2}),  // none valid
    case_name<WtaCase>);

// Frames follow each other without reset or idle steps, changing size and configuration.
TEST(WtaFraming, BackToBackFrames) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    WtaDriver driver(seed, 0.1);
    struct Frame {
        int width, height;
        WtaConfig config;
    };
    for (const Frame f : {Frame{64, 48, {16, 2, true}}, Frame{37, 23, {9, 1, false}},
                          Frame{64, 48, {12, 0, true}}, Frame{13, 9, {16, 2, false}}}) {
        const Dsi input = make_input(Input::kTies, f.width, f.height, f.config.ndisp, rng);
        EXPECT_TRUE(same_map(expected_wta(input, f.config), run_wta(driver, input, f.config)))
            << f.width << "x" << f.height;
    }
}

}  // namespace
}  // namespace stereo::tb

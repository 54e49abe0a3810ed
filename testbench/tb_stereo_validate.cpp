// stereo_validate against stage 6's arithmetic (stereo::validation, docs/fixed-point.md): for
// every pixel of random volumes (uniform, full of ties, flat), the second cost C2 (the minimum
// over labels away from the winner, kNoSecondCost when there is none) and the fixed disparity
// 16 (m + k1) + offset, offset = stereo::validation::subpixel_offset where sub-pixel refinement
// applies. The winner k1, C1 and the neighbours' costs are fed as stereo_wta computes them; the
// border flag is random and must pass through. Signed ranges, cfg_ndisp < NDISP with the unused
// lanes holding winning values, random clock enables, frames back to back.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_validate.h"
#include "stereo/stages/validate.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_validate").params.ndisp;
constexpr int kBits = fx::kAggBits;

struct ValidateStage {
    using Model = Vstereo_validate;
    static constexpr const char* kName = "stereo_validate";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_data, kDisparities * kBits, rng);
        model.in_label = static_cast<std::uint8_t>(rng());
        model.in_border = rng() & 1U;
        model.in_cost = static_cast<std::uint16_t>(rng() & ((1U << kBits) - 1));
        model.in_before = static_cast<std::uint16_t>(rng() & ((1U << kBits) - 1));
        model.in_after = static_cast<std::uint16_t>(rng() & ((1U << kBits) - 1));
    }
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return {model.out_label, model.out_border, model.out_cost, model.out_second,
                model.out_fixed};
    }
};

using ValidateDriver = StageDriver<ValidateStage>;

struct Config {
    int ndisp;
    int min_disp;
    bool subpixel;
};

// What stereo_wta hands over for one pixel, and what stereo_validate must make of it.
struct Pixel {
    int label = 0;
    int cost = 0;
    int before = 0;
    int after = 0;
    bool border = false;
    int second = fx::kNoSecondCost;
    int fixed = 0;
};

Pixel expected_pixel(const Dsi& volume, int x, int y, const Config& config, bool border) {
    Pixel p;
    p.border = border;
    for (int k = 1; k < config.ndisp; ++k) {
        if (volume.at(x, y, k) < volume.at(x, y, p.label)) {
            p.label = k;  // strict: ties keep the smaller label
        }
    }
    p.cost = volume.at(x, y, p.label);
    // stereo_wta's neighbours: 0 where the label does not exist (a don't-care then).
    p.before = p.label > 0 ? volume.at(x, y, p.label - 1) : 0;
    p.after = p.label + 1 < kDisparities ? volume.at(x, y, p.label + 1) : 0;
    for (int k = 0; k < config.ndisp; ++k) {
        if ((k < p.label - 1 || k > p.label + 1) && volume.at(x, y, k) < p.second) {
            p.second = volume.at(x, y, k);
        }
    }
    int offset = 0;
    if (config.subpixel && p.label > 0 && p.label < config.ndisp - 1) {
        offset = validation::subpixel_offset(p.before, p.cost, p.after);
    }
    p.fixed = (config.min_disp + p.label) * fx::kSubpixelScale + offset;
    return p;
}

enum class Input { kUniform, kTies, kSmooth };

Dsi make_input(Input input, int width, int height, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> any(0, fx::kAggMax);
    std::uniform_int_distribution<int> few(0, 3);
    std::uniform_int_distribution<int> centre(0, kDisparities - 1);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int minimum = centre(rng);
            const int base = any(rng) / 2;
            for (int k = 0; k < kDisparities; ++k) {
                int value = 0;
                switch (input) {
                    case Input::kUniform:
                        value = any(rng);
                        break;
                    case Input::kTies:
                        value = few(rng) * 1000;
                        break;
                    case Input::kSmooth:  // a parabola-like valley: real sub-pixel offsets
                        value = std::min(fx::kAggMax,
                                         base + 37 * (k - minimum) * (k - minimum) + few(rng));
                        break;
                }
                volume.at(x, y, k) = static_cast<Dsi::Value>(value);
            }
        }
    }
    return volume;
}

::testing::AssertionResult run_and_compare(ValidateDriver& driver, const Dsi& volume,
                                           const Config& config, std::mt19937& rng) {
    auto& model = driver.model();
    put_config(model.cfg, {{ConfigField::ndisp, config.ndisp},
                           {ConfigField::min_disp, config.min_disp},
                           {ConfigField::subpixel_en, config.subpixel ? 1 : 0}});
    const int width = volume.width();
    const int height = volume.height();
    std::vector<Pixel> want(static_cast<std::size_t>(width) * height);
    for (auto& p : want) {
        p.border = (rng() & 1U) != 0;
    }
    std::size_t mismatches = 0;
    std::string first;
    driver.run_frame(
        width, height,
        [&](Vstereo_validate& m, int x, int y) {
            Pixel& p = want[static_cast<std::size_t>(y) * width + x];
            p = expected_pixel(volume, x, y, config, p.border);
            put_column(m.in_data, volume, x, y, kBits);
            m.in_label = static_cast<std::uint8_t>(p.label);
            m.in_border = p.border ? 1 : 0;
            m.in_cost = static_cast<std::uint16_t>(p.cost);
            m.in_before = static_cast<std::uint16_t>(p.before);
            m.in_after = static_cast<std::uint16_t>(p.after);
        },
        [&](const Vstereo_validate& m, int x, int y) {
            const Pixel& p = want[static_cast<std::size_t>(y) * width + x];
            const int fixed = static_cast<std::int16_t>(m.out_fixed);
            if ((m.out_label != p.label || (m.out_border != 0) != p.border ||
                 m.out_cost != p.cost || m.out_second != p.second || fixed != p.fixed) &&
                mismatches++ < 5) {
                first += " (" + std::to_string(x) + ", " + std::to_string(y) + "): model C2 " +
                         std::to_string(p.second) + " fixed " + std::to_string(p.fixed) +
                         ", rtl C2 " + std::to_string(m.out_second) + " fixed " +
                         std::to_string(fixed) + ";";
            }
        });
    if (mismatches == 0) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << mismatches << " pixels differ:" << first;
}

struct Case {
    int width, height;
    Input input;
    Config config;
    double ce_low;
};

std::string describe(const Case& c) {
    const char* names[] = {"uniform", "ties", "smooth"};
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_" +
           names[static_cast<int>(c.input)] + "_ndisp" + std::to_string(c.config.ndisp) + "_min" +
           (c.config.min_disp < 0 ? "m" : "") + std::to_string(std::abs(c.config.min_disp)) +
           (c.config.subpixel ? "_subpixel" : "") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

using tb::PrintTo;  // by describe()

class Volumes : public ::testing::TestWithParam<Case> {};

TEST_P(Volumes, EveryPixelEqualsTheArithmetic) {
    const Case c = GetParam();
    check_frames<ValidateDriver>(
        c.ce_low, [&](ValidateDriver& driver, std::mt19937& rng, int frame) {
            const Dsi volume = make_input(c.input, c.width, c.height, rng);
            EXPECT_TRUE(run_and_compare(driver, volume, c.config, rng)) << "frame " << frame;
        });
}

INSTANTIATE_TEST_SUITE_P(
    Validate, Volumes,
    ::testing::Values(Case{32, 24, Input::kUniform, {16, 0, true}, 0.0},
                      Case{32, 24, Input::kSmooth, {16, 0, true}, 0.3},
                      Case{32, 24, Input::kSmooth, {16, -1024, true}, 0.2},
                      Case{32, 24, Input::kSmooth, {11, 1024, true}, 0.2},
                      Case{32, 24, Input::kTies, {16, -7, true}, 0.2},
                      Case{32, 24, Input::kTies, {9, 3, false}, 0.1},
                      Case{17, 9, Input::kUniform, {4, -2, true}, 0.3},
                      Case{17, 9, Input::kUniform, {3, 0, true}, 0.3},  // no second cost
                      Case{17, 9, Input::kSmooth, {2, 5, true}, 0.0},
                      Case{5, 3, Input::kUniform, {1, -1, true}, 0.3}),
    case_name<Case>);

}  // namespace
}  // namespace stereo::tb

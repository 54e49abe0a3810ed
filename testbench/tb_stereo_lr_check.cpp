// stereo_lr_check against stage 6's definition, stereo::naive::validate (every label scanned for
// the winner, the second cost and the right image's winner along the DSI diagonal): the fixed
// disparity, the reason and the certainty of every pixel of random final volumes. The module's
// inputs are what stereo_wta and stereo_validate hand over (tb_stereo_validate checks those):
// the cost vector of pixel p and the left result of pixel p - 1, in raster order, then flush
// steps. Signed ranges, every tolerance and ratio, cfg_ndisp < NDISP, random clock enables,
// frames of different sizes back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_lr_check.h"
#include "stereo/reference.hpp"
#include "stereo/stages/validate.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_lr_check").params.ndisp;
constexpr int kBits = fx::kAggBits;

struct Config {
    int ndisp;
    int min_disp;
    int reach;
    ValidationParams validation;
};

// The left result of pixel (x, y) as stereo_validate's register holds it.
struct Left {
    int label = 0;
    bool border = false;
    int cost = 0;
    int second = fx::kNoSecondCost;
    int fixed = 0;
};

Left left_result(const Dsi& volume, int x, int y, const Config& c) {
    Left r;
    for (int k = 1; k < c.ndisp; ++k) {
        if (volume.at(x, y, k) < volume.at(x, y, r.label)) {
            r.label = k;
        }
    }
    r.cost = volume.at(x, y, r.label);
    for (int k = 0; k < c.ndisp; ++k) {
        if ((k < r.label - 1 || k > r.label + 1) && volume.at(x, y, k) < r.second) {
            r.second = volume.at(x, y, k);
        }
    }
    const int d = c.min_disp + r.label;
    r.border = InvalidBorder{c.reach}.valid(x, y, d, volume.width(), volume.height());
    int offset = 0;
    if (c.validation.subpixel && r.label > 0 && r.label < c.ndisp - 1) {
        offset = validation::subpixel_offset(volume.at(x, y, r.label - 1), r.cost,
                                             volume.at(x, y, r.label + 1));
    }
    r.fixed = d * fx::kSubpixelScale + offset;
    return r;
}

class Driver {
  public:
    Driver(std::uint32_t seed, double ce_low)
        : rng_(seed),
          ce_low_(ce_low),
          harness_("stereo_lr_check", 2, static_cast<int>(seed % 0x7FFFFFFFU) + 1),
          m_(&harness_.model()) {
        if (const std::string path = trace_path(); !path.empty()) {
            harness_.trace_to(path);
        }
        m_->clk = 0;
        m_->ce = 0;
        m_->rst = 1;
        m_->rst_output = 1;
        m_->eval();
        harness_.tick();
        harness_.tick();
        m_->rst = 0;
        m_->rst_output = 0;
    }

    // Streams one frame; returns the module's output for every pixel.
    ValidatedDisparity run(const Dsi& volume, const Config& c) {
        const int width = volume.width();
        const int height = volume.height();
        put_config(m_->cfg, {{ConfigField::width, width},
                             {ConfigField::height, height},
                             {ConfigField::ndisp, c.ndisp},
                             {ConfigField::min_disp, c.min_disp},
                             {ConfigField::uniqueness_en, c.validation.uniqueness ? 1 : 0},
                             {ConfigField::uniqueness, c.validation.uniqueness_ratio},
                             {ConfigField::lr_en, c.validation.left_right ? 1 : 0},
                             {ConfigField::lr_tolerance, c.validation.lr_tolerance}});
        ValidatedDisparity out(width, height);
        std::vector<bool> seen(out.fixed.size(), false);
        std::size_t seen_count = 0;
        std::bernoulli_distribution skip(ce_low_);
        const int pixels = width * height;
        // Raster position p of the cost vector; the left result is p - 1's. Flush positions
        // continue the raster (y >= height) with garbage data, as in stereo_top.
        int p = 0;
        Left previous;
        int previous_x = 0;
        int previous_y = table::kNoPixel;
        const std::uint64_t limit = static_cast<std::uint64_t>(pixels) * 4 + 1000;
        for (std::uint64_t cycle = 0; seen_count < out.fixed.size() && cycle < limit; ++cycle) {
            if (skip(rng_)) {
                randomize_bits(m_->acc_data, kDisparities * kBits, rng_);
                m_->ce = 0;
                harness_.tick();
                continue;
            }
            const int x = p % width;
            const int y = p / width;
            if (p < pixels) {
                put_column(m_->acc_data, volume, x, y, kBits);
            } else {
                randomize_bits(m_->acc_data, kDisparities * kBits, rng_);
            }
            m_->acc_x = coordinate_port(x);
            m_->acc_y = coordinate_port(y);
            m_->in_x = coordinate_port(previous_x);
            m_->in_y = coordinate_port(previous_y);
            m_->in_label = static_cast<std::uint8_t>(previous.label);
            m_->in_border = previous.border ? 1 : 0;
            m_->in_cost = static_cast<std::uint16_t>(previous.cost);
            m_->in_second = static_cast<std::uint16_t>(previous.second);
            m_->in_fixed = static_cast<std::uint16_t>(previous.fixed);
            m_->ce = 1;
            harness_.tick();
            previous = p < pixels ? left_result(volume, x, y, c) : Left{};
            previous_x = x;
            previous_y = y;
            ++p;
            const int ox = coordinate_value(m_->out_x);
            const int oy = coordinate_value(m_->out_y);
            if (ox < 0 || ox >= width || oy < 0 || oy >= height) {
                continue;
            }
            const std::size_t i = out.index(ox, oy);
            if (seen[i]) {
                ADD_FAILURE() << "output (" << ox << ", " << oy << ") appeared twice";
                continue;
            }
            seen[i] = true;
            ++seen_count;
            const auto beat = static_cast<std::uint64_t>(m_->out_beat);
            out.fixed[i] = static_cast<std::int16_t>(static_cast<std::uint16_t>(
                get_bits(beat, table::kOutFixedLsb, fx::kFixedDisparityBits)));
            out.reason[i] =
                static_cast<std::uint8_t>(get_bits(beat, table::kOutReasonLsb, fx::kReasonBits));
            out.certainty[i] = static_cast<std::uint8_t>(
                get_bits(beat, table::kOutCertaintyLsb, table::kOutCertaintyBits));
            EXPECT_EQ(get_bits(beat, table::kOutReasonLsb + fx::kReasonBits, table::kOutPadBits),
                      0U);
        }
        EXPECT_EQ(seen_count, out.fixed.size()) << "not every pixel came out";
        // The frame's end: stereo_top clears the coordinates of everything still in flight.
        m_->rst = 1;
        m_->ce = 0;
        harness_.tick();
        m_->rst = 0;
        return out;
    }

  private:
    std::mt19937 rng_;
    double ce_low_;
    sim::VerilatedHarness<Vstereo_lr_check> harness_;
    Vstereo_lr_check* m_;
};

// The naive reference sees exactly the cfg_ndisp planes.
ValidatedDisparity expected(const Dsi& volume, const Config& c) {
    return naive::validate(truncated(volume, c.ndisp), c.min_disp, c.validation,
                           InvalidBorder{c.reach});
}

// Costs with a true disparity (a valley along the diagonal), plus noise and ties, so that the
// right-referenced winners agree on most pixels and disagree on some.
Dsi make_volume(int width, int height, int min_disp, int truth, int noise, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> jitter(0, noise);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int k = 0; k < kDisparities; ++k) {
                const int distance = std::abs(min_disp + k - truth);
                volume.at(x, y, k) =
                    static_cast<Dsi::Value>(std::min(fx::kAggMax, 300 * distance + jitter(rng)));
            }
        }
    }
    return volume;
}

struct Case {
    int width, height;
    Config config;
    int truth, noise;
    double ce_low;
};

void PrintTo(const Case& c, std::ostream* out) {
    *out << c.width << "x" << c.height << " ndisp " << c.config.ndisp << " min_disp "
         << c.config.min_disp << " reach " << c.config.reach << " uniqueness "
         << c.config.validation.uniqueness << "/" << c.config.validation.uniqueness_ratio << " lr "
         << c.config.validation.left_right << "/" << c.config.validation.lr_tolerance
         << " subpixel " << c.config.validation.subpixel << " truth " << c.truth << " noise "
         << c.noise << " ce_low " << c.ce_low;
}

// The cases are written for 16 labels; a build with fewer searches what it has (cfg_ndisp is
// clamped to NDISP in stereo_top), so the same cases run at any Verilated NDISP.
Case within_build(Case c) {
    c.config.ndisp = std::min(c.config.ndisp, kDisparities);
    return c;
}

class Volumes : public ::testing::TestWithParam<Case> {};

TEST_P(Volumes, EveryPixelEqualsTheNaiveReference) {
    const Case c = within_build(GetParam());
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Driver driver(seed, c.ce_low);
    std::size_t left_right = 0;
    for (int frame = 0; frame < kFramesPerCase; ++frame) {
        const Dsi volume = make_volume(c.width, c.height, c.config.min_disp, c.truth, c.noise, rng);
        const ValidatedDisparity model = expected(volume, c.config);
        EXPECT_TRUE(same_validated(model, driver.run(volume, c.config))) << "frame " << frame;
        for (const auto reason : model.reason) {
            left_right += reason == fx::kReasonLeftRight ? 1 : 0;
        }
    }
    if (c.config.validation.left_right && c.config.ndisp > 2 && c.noise > 300) {
        EXPECT_GT(left_right, 0U) << "the left-right check rejected nothing";
    }
}

INSTANTIATE_TEST_SUITE_P(
    LrCheck, Volumes,
    ::testing::Values(Case{32, 12, {16, 0, 2, {true, 10, true, 1, true}}, 4, 2000, 0.0},
                      Case{32, 12, {16, 0, 2, {false, 10, true, 0, false}}, 4, 900, 0.3},
                      Case{32, 12, {16, -6, 1, {true, 0, true, 1, true}}, -2, 1200, 0.2},
                      Case{32, 12, {16, 5, 0, {true, 40, true, 2, false}}, 9, 2500, 0.2},
                      Case{29, 7, {9, -3, 2, {false, 10, true, 0, true}}, 0, 1500, 0.3},
                      Case{29, 7, {16, 0, 0, {true, 255, false, 1, false}}, 3, 3000, 0.1},
                      Case{29, 7, {3, -1, 1, {true, 10, true, 0, true}}, 0, 600, 0.2},
                      Case{13, 5, {1, 2, 0, {true, 10, true, 0, true}}, 2, 500, 0.2}));

// Frames of different sizes and configurations back to back.
TEST(LrCheckFraming, BackToBackFrames) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Driver driver(seed, 0.2);
    const Case cases[] = {{32, 12, {16, -4, 2, {true, 10, true, 1, true}}, 1, 1500, 0},
                          {17, 19, {8, 3, 1, {false, 10, true, 0, false}}, 6, 1500, 0},
                          {32, 12, {16, 0, 0, {true, 5, true, 3, true}}, 7, 2000, 0},
                          {6, 4, {4, -2, 0, {true, 10, true, 0, true}}, -1, 800, 0}};
    for (const Case& written : cases) {
        const Case c = within_build(written);
        const Dsi volume = make_volume(c.width, c.height, c.config.min_disp, c.truth, c.noise, rng);
        EXPECT_TRUE(same_validated(expected(volume, c.config), driver.run(volume, c.config)))
            << ::testing::PrintToString(c);
    }
}

}  // namespace
}  // namespace stereo::tb

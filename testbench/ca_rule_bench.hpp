// The testbench of stereo_ca_plane as one rule (its Verilated configurations Vstereo_ca_rule1 and
// Vstereo_ca_rule2): the stage ports, one frame through the Verilated rule against the model's
// rule, the parameterised volume cases, frames back to back and width one. `Rule` supplies:
//   Model, kPrefix (the Verilated configuration), kName (the stage),
//   apply(const Dsi&) (the model's rule), pair(w, h, rng) (what the rule sees in the pipeline),
//   structured(w, h, rng) (inputs on which the rule fires often), and
//   kSmallLow .. kSmallHigh (small values that decide agreement at 2|n - c| == c).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <iostream>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "stereo/stage_table.hpp"
#include "tb_options.hpp"

namespace stereo::tb {

inline constexpr int kCaBits = fx::kAggBits;

// The inputs of a CA rule testbench.
enum class CaInput { kPair, kStructured, kSmallValues, kNearMaximum, kFull14Bits };

// One parameterised case: frames of `input` through the rule, the model sees cfg_ndisp planes.
struct CaCase {
    int width, height;
    CaInput input;
    int ndisp;
    bool use_ca;
    double ce_low;
};

inline const char* input_name(CaInput input) {
    // In the enum's order.
    constexpr std::array kNames{"pair", "structured", "small", "nearmax", "full14bits"};
    return kNames.at(static_cast<std::size_t>(input));
}

// Test names, and the parameter as ctest and GoogleTest print it (tb::PrintTo).
inline std::string describe(const CaCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_" + input_name(c.input) +
           "_ndisp" + std::to_string(c.ndisp) + (c.use_ca ? "_ca" : "_noca") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

// One frame of frames back to back.
struct CaFrame {
    int width, height, ndisp;
    bool use_ca;
};

template <typename Rule>
struct CaRuleBench {
    using Model = typename Rule::Model;
    using Input = CaInput;
    static constexpr int kDisparities = table::verilated(Rule::kPrefix).params.ndisp;

    static Dsi make_input(Input input, int width, int height, std::mt19937& rng) {
        switch (input) {
            case Input::kPair:
                return Rule::pair(width, height, rng);
            case Input::kStructured:
                return Rule::structured(width, height, rng);
            case Input::kSmallValues:
                return uniform_volume(width, height, kDisparities, Rule::kSmallLow,
                                      Rule::kSmallHigh, rng);
            case Input::kNearMaximum:  // the widest sums and products
                return uniform_volume(width, height, kDisparities, fx::kAggMax - 300, fx::kAggMax,
                                      rng);
            case Input::kFull14Bits:  // for the identity only: every bit must pass
                return uniform_volume(width, height, kDisparities, 0, (1 << kCaBits) - 1, rng);
        }
        return {};
    }

    struct Ports : ColumnOutputPorts<Model> {
        static constexpr const char* kName = Rule::kName;
        static void scramble(Model& model, std::mt19937& rng) {
            randomize_bits(model.in_data, kDisparities * kCaBits, rng);
        }
    };
    using Driver = StageDriver<Ports>;

    // Runs one frame of the NDISP-plane `input`; returns all NDISP output planes.
    static Dsi run(Driver& driver, const Dsi& input, int ndisp, bool use_ca) {
        auto& model = driver.model();
        put_config(model.cfg, {{ConfigField::width, input.width()},
                               {ConfigField::height, input.height()},
                               {ConfigField::ndisp, ndisp},  // rule 2 ignores it
                               {ConfigField::use_ca, use_ca ? 1 : 0}});
        Dsi rtl(input.width(), input.height(), kDisparities);
        driver.run_frame(
            input.width(), input.height(),
            [&](Model& m, int x, int y) { put_column(m.in_data, input, x, y, kCaBits); },
            [&](const Model& m, int x, int y) { get_column(m.out_data, rtl, x, y, kCaBits); });
        return rtl;
    }

    // The model sees only the cfg_ndisp planes the core uses; with CA off the stage is the
    // identity.
    static Dsi expected(const Dsi& input, int ndisp, bool use_ca) {
        const Dsi used = truncated(input, ndisp);
        return use_ca ? Rule::apply(used) : used;
    }

    using Case = CaCase;

    // kFramesPerCase frames of fresh input through one driver, each value against the model.
    static void check_case(const Case& c) {
        check_frames<Driver>(c.ce_low, [&](Driver& driver, std::mt19937& rng, int frame) {
            const Dsi input = make_input(c.input, c.width, c.height, rng);
            const Dsi want = expected(input, c.ndisp, c.use_ca);
            if (c.use_ca && frame == 0) {
                std::cout << "[fires] " << Rule::kName << " changes "
                          << 100.0 * changed_fraction(truncated(input, c.ndisp), want)
                          << " % of the cells\n";
            }
            EXPECT_TRUE(same_volume(want, run(driver, input, c.ndisp, c.use_ca), c.ndisp))
                << "frame " << frame;
        });
    }

    using Frame = CaFrame;

    // Frames follow each other without idle steps, changing size, cfg_ndisp and CA: the line
    // buffer and the column registers hold the previous frame and its flush garbage.
    static void check_back_to_back(const std::vector<Frame>& frames, Input input) {
        const std::uint32_t seed = test_seed();
        std::mt19937 rng(seed);
        Driver driver(seed, 0.1);
        int previous_height = 0;
        for (const Frame& f : frames) {
            // The contract of every stage (docs/rtl.md): a frame taller than the one before
            // needs the coordinate registers cleared between them, since the flush filler still
            // in flight (rows >= the old height) lies inside the new frame; stereo_top clears
            // them when a frame's last output leaves. Same-size and shorter frames follow
            // without a reset.
            if (f.height > previous_height) {
                driver.reset();
            }
            previous_height = f.height;
            const Dsi in = make_input(input, f.width, f.height, rng);
            EXPECT_TRUE(same_volume(expected(in, f.ndisp, f.use_ca),
                                    run(driver, in, f.ndisp, f.use_ca), f.ndisp))
                << f.width << "x" << f.height << " ndisp " << f.ndisp << " CA " << f.use_ca;
        }
    }

    // Width 1: the line buffer's read-ahead address is the word being written, which it passes
    // straight through (a read-first RAM alone would deliver every row one row late).
    static void check_width_one(Input input) {
        const std::uint32_t seed = test_seed();
        std::mt19937 rng(seed);
        Driver driver(seed, 0.0);
        const Dsi in = make_input(input, 1, 7, rng);
        EXPECT_TRUE(
            same_volume(Rule::apply(in), run(driver, in, kDisparities, true), kDisparities));
    }
};

}  // namespace stereo::tb

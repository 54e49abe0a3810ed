// One Verilated stereo_top configuration driven frame by frame, as the top-level testbenches use
// it: reset (and an FST trace with --trace-dir) on construction, then whole frames streamed under
// the given traffic, with completion, protocol and status checked.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "stereo/stage_table.hpp"
#include "stereo/validated.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "stereo_top_sim.hpp"
#include "tb_options.hpp"

namespace stereo::tb {

// The model's name (MatchParams::cost) of a configuration's COST.
inline std::string model_cost_name(int cost) {
    switch (cost) {
        case table::kCostLcdm:
            return "lcdm";
        case table::kCostCensus:
            return "census";
        default:
            return "ad";
    }
}

// A random pair through the core (true disparity 3, noise 25): its size, the matching
// parameters and the traffic (input gaps and output stalls).
struct RandomCase {
    int width, height, ndisp, window;
    bool use_ca;
    double gap, stall;
};

inline void PrintTo(const RandomCase& c, std::ostream* out) {
    *out << c.width << "x" << c.height << " ndisp " << c.ndisp << " window " << c.window
         << (c.use_ca ? " CA" : " no CA") << " gap " << c.gap << " stall " << c.stall;
}

// A test over RandomCases: the case, the test's seed, the case's pair drawn from it and the
// case's traffic.
class RandomPairTest : public ::testing::TestWithParam<RandomCase> {
  protected:
    const RandomCase c = GetParam();
    const std::uint32_t seed = test_seed();
    std::mt19937 rng{seed};
    const io::ImagePair pair = test::shifted_pair(c.width, c.height, 3, 3, 25, rng);
    const sim::Traffic traffic{c.gap, c.stall, seed};
};

class Cosim {
  public:
    explicit Cosim(const sim::TopConfig& config) : sim_(sim::make_top_sim(config)) {
        if (const std::string path = trace_path(); !path.empty()) {
            sim_->trace_to(path);
        }
        sim_->reset();
    }
    sim::TopSim& sim() { return *sim_; }

    // Streams one frame and returns the RTL's result, checking completion and protocol.
    ValidatedDisparity run(const Image& left, const Image& right, const MatchParams& params,
                           const sim::Traffic& traffic, sim::StreamResult* result_out = nullptr) {
        sim_->set_params({left.width, left.height, params});
        const auto beats = sim::frame_beats(left, right);
        sim::StreamResult result =
            sim_->stream(beats, beats.size(), traffic, 50 * beats.size() + 10000);
        EXPECT_TRUE(result.completed) << "the core stalled: " << result.outputs.size() << " of "
                                      << beats.size() << " outputs";
        EXPECT_EQ(result.protocol_error, "");
        EXPECT_EQ(result.status, 0U) << "status bits";
        ValidatedDisparity map =
            sim::assemble_validated(result.outputs, 0, left.width, left.height);
        if (result_out != nullptr) {
            *result_out = std::move(result);
        }
        return map;
    }

    // Starts a frame of (left, right), streams its first `fed` beats (taking at most `outputs`
    // outputs) and resets the core in the middle of that frame.
    void reset_mid_frame(const Image& left, const Image& right, const MatchParams& params,
                         std::size_t fed, std::size_t outputs, const sim::Traffic& traffic) {
        sim_->set_params({left.width, left.height, params});
        const auto beats = sim::frame_beats(left, right);
        const std::vector<sim::InputBeat> part(beats.begin(), beats.begin() + fed);
        EXPECT_GT(sim_->stream(part, outputs, traffic, 100000).input_beats, 0U);
        sim_->reset();
    }

  private:
    std::unique_ptr<sim::TopSim> sim_;
};

}  // namespace stereo::tb

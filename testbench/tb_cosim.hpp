// One Verilated stereo_top configuration driven frame by frame, as the top-level testbenches use
// it: reset (and an FST trace with --trace-dir) on construction, then whole frames streamed under
// the given traffic, with completion, protocol and status checked.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "stereo/validated.hpp"
#include "stereo_top_sim.hpp"
#include "tb_options.hpp"

namespace stereo::tb {

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

  private:
    std::unique_ptr<sim::TopSim> sim_;
};

}  // namespace stereo::tb

// The AXI4-Stream side of a co-simulation: streams input beats into a Verilated model with
// s_axis_* / m_axis_* ports (stereo_top and the wrappers around it) under random input gaps and
// output stalls, collects the output beats and checks the AXI4-Stream rules on the way.
// Include the Verilator runtime headers and verilated_harness.hpp before this one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "stereo_top_sim.hpp"
#include "verilated_harness.hpp"

namespace stereo::sim {

// Streams `beats` (possibly several frames back to back) and collects `expected_outputs` output
// beats, or stops after `max_cycles`. The cycle count starts at the first accepted input beat.
// Leaves the stream inputs as they were in the last cycle; `status` is not read.
// `after_edge(model)` runs after every rising edge (the co-simulation runner's stage probes).
struct NoProbe {
    template <typename Model>
    void operator()(const Model&) const {}
};
template <typename Model, typename AfterEdge = NoProbe>
StreamResult stream_axis(VerilatedHarness<Model>& harness, const std::vector<InputBeat>& beats,
                         std::size_t expected_outputs, const Traffic& traffic,
                         std::uint64_t max_cycles, AfterEdge&& after_edge = {}) {
    Model& model = harness.model();
    StreamResult result;
    std::mt19937 rng(traffic.seed);
    std::bernoulli_distribution gap(traffic.input_gap);
    std::bernoulli_distribution stall(traffic.output_stall);
    std::size_t next = 0;
    bool offering = false;     // s_axis_tvalid is up and must stay up until taken
    bool held_output = false;  // m_axis_tvalid was up without tready last cycle
    std::uint64_t held_data = 0;
    bool held_last = false;
    bool held_user = false;
    std::uint64_t cycle = 0;
    bool started = false;
    // Every cycle run, the ones before the first accepted beat included: `cycle` does not count
    // those, so with no beat ever taken (no input, or a core that never raises tready) only
    // this ends the loop (`cosim --reset-at 0` ran forever).
    std::uint64_t spent = 0;
    for (; cycle < max_cycles && spent < 2 * max_cycles && result.outputs.size() < expected_outputs;
         ++cycle, ++spent) {
        if (!offering && next < beats.size() && !gap(rng)) {
            offering = true;
        }
        model.s_axis_tvalid = offering ? 1 : 0;
        if (offering) {
            model.s_axis_tdata = beats[next].data;
            model.s_axis_tlast = beats[next].last ? 1 : 0;
            model.s_axis_tuser = beats[next].user ? 1 : 0;
        }
        model.m_axis_tready = stall(rng) ? 0 : 1;
        model.clk = 0;
        model.eval();  // combinational outputs for this cycle's inputs
        harness.dump();

        // AXI4-Stream: data and framing stay stable while valid waits for ready.
        if (held_output && result.protocol_error.empty()) {
            if (!model.m_axis_tvalid) {
                result.protocol_error = "m_axis_tvalid dropped before the beat was taken";
            } else if (model.m_axis_tdata != held_data || model.m_axis_tlast != held_last ||
                       model.m_axis_tuser != held_user) {
                result.protocol_error = "m_axis data changed while waiting for tready";
            }
        }
        const bool input_taken = offering && model.s_axis_tready;
        const bool output_taken = model.m_axis_tvalid && model.m_axis_tready;
        held_output = model.m_axis_tvalid && !model.m_axis_tready;
        held_data = model.m_axis_tdata;
        held_last = model.m_axis_tlast != 0;
        held_user = model.m_axis_tuser != 0;
        if (output_taken) {
            result.outputs.push_back(
                {model.m_axis_tdata, model.m_axis_tlast != 0, model.m_axis_tuser != 0});
        }
        if (input_taken) {
            started = true;
            ++result.input_beats;
            ++next;
            offering = false;
        }
        model.clk = 1;
        model.eval();
        harness.dump();
        after_edge(model);
        if (!started) {
            --cycle;  // count from the first accepted beat
        }
    }
    result.cycles = cycle;
    result.completed = result.outputs.size() == expected_outputs;
    return result;
}

// Two clocks of reset with the streams idle (no input offered, no output taken).
template <typename Model>
void reset_axis_core(VerilatedHarness<Model>& harness) {
    Model& model = harness.model();
    model.s_axis_tvalid = 0;
    model.m_axis_tready = 0;
    harness.pulse_reset();
}

}  // namespace stereo::sim

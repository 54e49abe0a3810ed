// The main of a co-simulation runner built on demand (sim/on_demand.cpp): one Verilated
// stereo_top of the requested parameters, driven by the requests of sim/cosim_protocol.hpp on
// standard input, answered on standard output. It owns nothing but the model: the caller computes
// the port values, the input beats and the golden model's answer.
#include <verilated.h>
#if VM_TRACE_FST
#include <verilated_fst_c.h>
#endif

#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "Vstereo_top.h"
#include "axis_driver.hpp"
#include "cosim_protocol.hpp"
#include "port_bits.hpp"
#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"
#include "verilated_harness.hpp"

// Set by on_demand.cpp for a probe build (--public-flat-rw); STEREO_PROBE_NDISP is NDISP.
#ifndef STEREO_RUNNER_PROBES
#define STEREO_RUNNER_PROBES 0
#endif
#ifndef STEREO_PROBE_NDISP
#define STEREO_PROBE_NDISP 1
#endif

#if STEREO_RUNNER_PROBES
// A probe build (--public-flat-rw): stereo_top's internal signals are members of the root.
#include "Vstereo_top___024root.h"
#endif

namespace {

using stereo::sim::VerilatedHarness;
namespace protocol = stereo::sim::protocol;

void idle_inputs(Vstereo_top& model) {
    model.s_axis_tvalid = 0;
    model.s_axis_tdata = 0;
    model.s_axis_tlast = 0;
    model.s_axis_tuser = 0;
    model.m_axis_tready = 0;
}

void set_ports(Vstereo_top& model, const protocol::PortValues& p) {
    model.cfg_width = p.width;
    model.cfg_height = p.height;
    model.cfg_ndisp = p.ndisp;
    model.cfg_min_disp = p.min_disp;
    model.cfg_use_ca = p.use_ca;
    model.cfg_uniqueness_en = p.uniqueness_en;
    model.cfg_uniqueness = p.uniqueness;
    model.cfg_lr_en = p.lr_en;
    model.cfg_lr_tolerance = p.lr_tolerance;
    model.cfg_subpixel_en = p.subpixel_en;
    model.cfg_radius = p.radius;
    for (std::size_t i = 0; i < p.kernel.size(); ++i) {
        stereo::sim::put_bits(model.cfg_kernel, static_cast<int>(i) * stereo::table::kTapBits,
                              stereo::table::kTapBits, static_cast<std::uint64_t>(p.kernel[i]));
    }
}

// The stage outputs of the watched pixels (probe builds; LANES = NDISP, so each stage's registered
// output holds all labels of one pixel, with that pixel's coordinates beside it).
class StageProbes {
  public:
    void watch(std::vector<protocol::PixelProbe> pixels) { probes_ = std::move(pixels); }
    const std::vector<protocol::PixelProbe>& probes() const { return probes_; }

    void operator()([[maybe_unused]] const Vstereo_top& model) {
#if STEREO_RUNNER_PROBES
        if (probes_.empty()) {
            return;
        }
        const auto* root = model.rootp;
        // The aggregation and CA rule 1 sit in stereo_top's generate block of the Gaussian
        // aggregation (ASW = 0), g_gaussian_ca.
        sample(0, root->stereo_top__DOT__g_gaussian_ca__DOT__agg_x,
               root->stereo_top__DOT__g_gaussian_ca__DOT__agg_y,
               root->stereo_top__DOT__g_gaussian_ca__DOT__agg_data);
        sample(1, root->stereo_top__DOT__g_gaussian_ca__DOT__rule1_x,
               root->stereo_top__DOT__g_gaussian_ca__DOT__rule1_y,
               root->stereo_top__DOT__g_gaussian_ca__DOT__rule1_data);
        sample(2, root->stereo_top__DOT__wta_in_x, root->stereo_top__DOT__wta_in_y,
               root->stereo_top__DOT__rule2_data);
#endif
    }

  private:
    template <typename Data>
    void sample(int stage, std::uint16_t x_port, std::uint16_t y_port, const Data& data) {
        const int x = static_cast<std::int16_t>(x_port);
        const int y = static_cast<std::int16_t>(y_port);
        for (protocol::PixelProbe& probe : probes_) {
            if (!probe.seen[stage] && probe.x == x && probe.y == y) {
                probe.seen[stage] = true;
                auto& values = probe.values[stage];
                values.resize(STEREO_PROBE_NDISP);
                for (int k = 0; k < STEREO_PROBE_NDISP; ++k) {
                    values[k] = static_cast<std::uint16_t>(stereo::sim::get_bits(
                        data, k * stereo::fx::kAggBits, stereo::fx::kAggBits));
                }
            }
        }
    }

    std::vector<protocol::PixelProbe> probes_;
};

// One request; false at the end of input.
bool serve(protocol::Channel& channel, VerilatedHarness<Vstereo_top>& harness,
           StageProbes& probes) {
    char tag = 0;
    if (!channel.read_bytes(&tag, 1, true)) {
        return false;
    }
    Vstereo_top& model = harness.model();
    switch (tag) {
        case protocol::kParams:
            set_ports(model, protocol::get_ports(channel));
            channel.put(protocol::kOk);
            break;
        case protocol::kReset:
            idle_inputs(model);
            harness.pulse_reset();
            channel.put(protocol::kOk);
            break;
        case protocol::kStream: {
            const auto beats = protocol::get_beats(channel, std::uint64_t{1} << 30);
            const auto expected = channel.get<std::uint64_t>();
            stereo::sim::Traffic traffic;
            traffic.input_gap = channel.get<double>();
            traffic.output_stall = channel.get<double>();
            traffic.seed = channel.get<std::uint32_t>();
            const auto max_cycles = channel.get<std::uint64_t>();
            stereo::sim::StreamResult result =
                stereo::sim::stream_axis(harness, beats, expected, traffic, max_cycles, probes);
            idle_inputs(model);
            result.status = model.status;
            channel.put(protocol::kOk);
            protocol::put_result(channel, result);
            break;
        }
        case protocol::kTrace: {
            const std::string path = channel.get_string(4096);
            try {
                harness.trace_to(path);
                channel.put(protocol::kOk);
            } catch (const std::exception& error) {
                channel.put(protocol::kError);
                channel.put_string(error.what());
            }
            break;
        }
        case protocol::kWatch: {
            const auto count = channel.get<std::uint32_t>();
            if (count > 4096) {
                throw std::runtime_error("co-simulation runner: too many pixels to watch");
            }
            std::vector<protocol::PixelProbe> pixels(count);
            for (protocol::PixelProbe& pixel : pixels) {
                pixel.x = channel.get<std::int32_t>();
                pixel.y = channel.get<std::int32_t>();
            }
            if (STEREO_RUNNER_PROBES) {
                probes.watch(std::move(pixels));
                channel.put(protocol::kOk);
            } else {
                channel.put(protocol::kError);
                channel.put_string("this runner was built without stage probes");
            }
            break;
        }
        case protocol::kGetProbes:
            channel.put(protocol::kOk);
            protocol::put_probes(channel, probes.probes());
            break;
        default:
            throw std::runtime_error("co-simulation runner: unknown request " +
                                     std::to_string(static_cast<int>(tag)));
    }
    channel.flush();
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && std::string(argv[1]) == "--protocol") {
        std::printf("%d\n", protocol::kVersion);
        return 0;
    }
    try {
        VerilatedHarness<Vstereo_top> harness("stereo_top");
        idle_inputs(harness.model());
        harness.model().clk = 0;
        harness.model().eval();
        protocol::Channel channel(0, 1);
        StageProbes probes;
        while (serve(channel, harness, probes)) {
        }
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "stereo cosim runner: %s\n", error.what());
        return 1;
    }
}

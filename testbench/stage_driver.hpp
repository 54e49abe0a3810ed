// Shared code of the stage testbenches: bit-field access to Verilated ports of any width, a
// driver that streams one frame through a Verilated stage module with the pixel-step protocol
// of docs/rtl.md, and the comparison of DSI volumes with the golden model.
//
// The driver feeds the raster (0,0) .. (W-1,H-1), then keeps stepping with random garbage whose
// coordinates continue the raster (the flush), and collects every output whose coordinates lie
// inside the frame. It drops ce at random; on those cycles it drives random coordinates and data
// and checks that no output moves. Registers and RAMs start random, so stale data must be masked.
#pragma once

#include <gtest/gtest.h>

// Verilator's runtime headers are not ours to warn about; include this header before the
// generated model headers, which include them again (guarded) without the pragma.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <verilated.h>
#include <verilated_fst_c.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "port_bits.hpp"
#include "stereo/constants.hpp"
#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_compare.hpp"
#include "tb_options.hpp"
#include "verilated_harness.hpp"

namespace stereo::tb {

// ---- Ports -----------------------------------------------------------------------------------

using sim::get_bit;
using sim::get_bits;
using sim::put_bits;
using sim::set_bit;
using sim::WidePort;  // port bit fields: sim/port_bits.hpp

// Random values on the low `bits` bits.
template <typename Port>
void randomize_bits(Port& port, int bits, std::mt19937& rng) {
    for (int offset = 0; offset < bits; offset += 32) {
        const int chunk = std::min(32, bits - offset);
        put_bits(port, offset, chunk, rng());
    }
}

// The port's storage as 32-bit words, to see whether it changed.
template <typename Port>
std::vector<std::uint32_t> port_words(const Port& port) {
    if constexpr (WidePort<Port>) {
        return {std::begin(port.m_storage), std::end(port.m_storage)};
    } else {
        const auto value = static_cast<std::uint64_t>(port);
        return {static_cast<std::uint32_t>(value), static_cast<std::uint32_t>(value >> 32)};
    }
}

// Fields of fx_pkg::config_t on a stage's `cfg` port (the configuration stereo_top hands its stages
// whole; the layout is stage_table.hpp's kConfigFields): each value's low bits at its field, a
// negative min_disp in two's complement. Fields not named keep their bits.
using table::ConfigField;
template <typename Port>
void put_config(Port& port, std::initializer_list<std::pair<ConfigField, std::int64_t>> fields) {
    for (const auto& [field, value] : fields) {
        put_bits(port, table::config_lsb(field), table::config_field(field).bits,
                 static_cast<std::uint64_t>(value));
    }
}

// Coordinates are signed 16-bit; Verilator holds them as unsigned SData.
inline std::uint16_t coordinate_port(int value) {
    return static_cast<std::uint16_t>(static_cast<std::int16_t>(value));
}
inline int coordinate_value(std::uint16_t port) {
    return static_cast<std::int16_t>(port);
}

// One DSI column: plane d of `volume` at (x, y) goes to [d*bits +: bits].
template <typename Port>
void put_column(Port& port, const Dsi& volume, int x, int y, int bits) {
    for (int d = 0; d < volume.ndisp(); ++d) {
        put_bits(port, d * bits, bits, volume.at(x, y, d));
    }
}

template <typename Port>
void get_column(const Port& port, Dsi& volume, int x, int y, int bits) {
    for (int d = 0; d < volume.ndisp(); ++d) {
        volume.at(x, y, d) = static_cast<Dsi::Value>(get_bits(port, d * bits, bits));
    }
}

// ---- The driver ------------------------------------------------------------------------------

// What the driver needs to know about a stage beyond the common ports (clk, rst, ce, in_x, in_y,
// out_x, out_y): how to put garbage on its data inputs and what its data outputs are.
template <typename Stage>
concept StagePorts = requires(typename Stage::Model& model, const typename Stage::Model& view,
                              std::mt19937& rng) {
    { Stage::kName } -> std::convertible_to<const char*>;
    Stage::scramble(model, rng);
    { Stage::outputs(view) } -> std::same_as<std::vector<std::uint32_t>>;
};

// Frames of fresh random data per test case, streamed back to back through one driver.
inline constexpr int kFramesPerCase = 8;

struct FrameStats {
    std::uint64_t steps = 0;   // cycles with ce high
    std::uint64_t cycles = 0;  // all cycles
};

template <StagePorts Stage>
class StageDriver {
  public:
    using Model = typename Stage::Model;

    // `ce_low` is the probability that a cycle does not step.
    // Registers and RAMs (--x-initial unique) start random, so unmasked stale data shows.
    StageDriver(std::uint32_t seed, double ce_low)
        : rng_(seed),
          ce_low_(ce_low),
          harness_(Stage::kName, 2, static_cast<int>(seed % 0x7FFFFFFFU) + 1),
          model_(&harness_.model()) {
        if (const std::string path = trace_path(); !path.empty()) {
            harness_.trace_to(path);
        }
        scramble_inputs();
        model_->ce = 0;
        model_->rst = 0;
        model_->clk = 0;
        model_->eval();
        reset();
    }

    Model& model() { return *model_; }
    std::mt19937& rng() { return rng_; }

    // rst high for two cycles, with ce high and garbage inputs: reset must win over ce for the
    // coordinates, and the garbage loaded into the data registers must stay masked.
    void reset() {
        model_->rst = 1;
        model_->ce = 1;
        for (int i = 0; i < 2; ++i) {
            scramble_inputs();
            tick();
        }
        model_->rst = 0;
        EXPECT_EQ(coordinate_value(model_->out_y), table::kNoPixel) << "reset must mark 'no pixel'";
    }

    // Streams one frame of `width` x `height` pixels and collects its outputs.
    // feed(model, x, y) sets the data inputs of in-frame pixel (x, y); collect(model, x, y) reads
    // the data outputs that belong to in-frame pixel (x, y). Configuration ports are the caller's.
    template <typename Feed, typename Collect>
    FrameStats run_frame(int width, int height, Feed&& feed, Collect&& collect) {
        const auto pixels = static_cast<std::size_t>(width) * height;
        std::vector<bool> seen(pixels, false);
        std::size_t seen_count = 0;
        // The deepest stage (aggregate, R = 2) needs 2W + 4 flush steps; be generous.
        const std::uint64_t step_limit = pixels + 8 * static_cast<std::uint64_t>(width) + 64;
        std::bernoulli_distribution skip(ce_low_);
        FrameStats stats;
        int next_x = 0;
        int next_y = 0;
        int protocol_errors = 0;
        auto report = [&](const std::string& message) {
            if (protocol_errors++ < kListed) {
                ADD_FAILURE() << message;
            }
        };
        while (seen_count < pixels) {
            if (stats.steps >= step_limit) {
                ADD_FAILURE() << "only " << seen_count << " of " << pixels
                              << " in-frame outputs after " << stats.steps << " steps";
                break;
            }
            const bool step = !skip(rng_);
            ++stats.cycles;
            if (!step) {
                // Whatever the inputs do while ce is low must not matter.
                scramble_inputs();
                model_->ce = 0;
                const auto before = output_state();
                tick();
                if (output_state() != before) {
                    report("outputs changed on a cycle with ce low (step " +
                           std::to_string(stats.steps) + ")");
                }
                continue;
            }
            model_->ce = 1;
            model_->in_x = coordinate_port(next_x);
            model_->in_y = coordinate_port(next_y);
            if (next_y < height) {
                feed(*model_, next_x, next_y);
            } else {
                Stage::scramble(*model_, rng_);  // flush: garbage that must stay masked
            }
            if constexpr (kAnnouncesNextRow) {
                // The row of the following step in the raster (the driver's next frame starts
                // at row 0 instead: that only concerns outputs above the frame, see the stage).
                Stage::announce_next_row(
                    *model_, coordinate_port(next_x + 1 == width ? next_y + 1 : next_y));
            }
            tick();
            ++stats.steps;
            if (++next_x == width) {
                next_x = 0;
                ++next_y;
            }
            const int x = coordinate_value(model_->out_x);
            const int y = coordinate_value(model_->out_y);
            if (x < 0 || x >= width || y < 0 || y >= height) {
                continue;
            }
            const auto index = static_cast<std::size_t>(y) * width + x;
            if (seen[index]) {
                report("output (" + std::to_string(x) + ", " + std::to_string(y) +
                       ") appeared twice");
                continue;
            }
            seen[index] = true;
            ++seen_count;
            collect(*model_, x, y);
        }
        return stats;
    }

  private:
    static constexpr int kListed = 5;
    // Stages whose row flags are computed a step ahead (stereo_aggregate's in_next_y).
    static constexpr bool kAnnouncesNextRow = requires(Model & model) {
        Stage::announce_next_row(model, std::uint16_t{0});
    };

    void scramble_inputs() {
        model_->in_x = static_cast<std::uint16_t>(rng_());
        model_->in_y = static_cast<std::uint16_t>(rng_());
        Stage::scramble(*model_, rng_);
    }

    std::vector<std::uint32_t> output_state() const {
        auto state = Stage::outputs(*model_);
        state.push_back(model_->out_x);
        state.push_back(model_->out_y);
        return state;
    }

    void tick() { harness_.tick(); }

    std::mt19937 rng_;
    double ce_low_;
    sim::VerilatedHarness<Model> harness_;
    Model* model_;
};

// kFramesPerCase frames of fresh input through one driver: the test's seed seeds the driver and
// `rng`, from which check(driver, rng, frame) draws the frame's input before checking it.
template <typename Driver, typename Check>
void check_frames(double ce_low, Check&& check) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Driver driver(seed, ce_low);
    for (int frame = 0; frame < kFramesPerCase; ++frame) {
        check(driver, rng, frame);
    }
}

// The ports of a stage whose data output is out_data (a DSI column), for StageDriver: the
// stage's Ports derive from it and add kName and scramble().
template <typename VerilatedModel>
struct ColumnOutputPorts {
    using Model = VerilatedModel;
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return port_words(model.out_data);
    }
};

// ---- Parameterised cases ---------------------------------------------------------------------

// A case type with a describe(case) beside it (found by argument-dependent lookup) prints and
// names its tests by it. GoogleTest finds PrintTo by argument-dependent lookup too: a testbench
// brings this one into its case type's namespace with `using tb::PrintTo;`.
template <typename Case>
concept Described = requires(const Case& c) {
    { describe(c) } -> std::convertible_to<std::string>;
};

template <Described Case>
void PrintTo(const Case& c, std::ostream* os) {
    *os << describe(c);
}

template <Described Case>
std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    return describe(info.param);
}

// ---- Volumes ---------------------------------------------------------------------------------

// The first `planes` planes of a volume (the model's view when cfg_ndisp < NDISP).
inline Dsi truncated(const Dsi& volume, int planes) {
    Dsi out(volume.width(), volume.height(), planes);
    for (int d = 0; d < planes; ++d) {
        const auto source = volume.plane(d);
        std::copy(source.begin(), source.end(), out.plane(d).begin());
    }
    return out;
}

// Uniformly random values in [low, high].
inline Dsi uniform_volume(int width, int height, int ndisp, int low, int high, std::mt19937& rng) {
    Dsi volume(width, height, ndisp);
    std::uniform_int_distribution<int> value(low, high);
    for (int d = 0; d < ndisp; ++d) {
        for (auto& cell : volume.plane(d)) {
            cell = static_cast<Dsi::Value>(value(rng));
        }
    }
    return volume;
}

// Costs of a random pair whose right image is the left shifted by `shift` plus noise: a volume
// with a true answer, and 765 where x - d < 0.
inline Dsi pair_cost(int width, int height, int ndisp, int shift, std::mt19937& rng) {
    const Image left = test::random_image(width, height, 3, rng);
    const Image right = test::shifted_copy(left, shift, 25, rng);
    return cost(left, right, ndisp);
}

// How many cells a rule changed: a test of a rule is only as strong as how often it fires.
inline double changed_fraction(const Dsi& before, const Dsi& after) {
    std::size_t changed = 0;
    for (std::size_t i = 0; i < before.cells().size(); ++i) {
        changed += before.cells()[i] != after.cells()[i] ? 1 : 0;
    }
    return static_cast<double>(changed) / static_cast<double>(before.cells().size());
}

}  // namespace stereo::tb

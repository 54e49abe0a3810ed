// One Verilated model with its context, an optional FST waveform and the clock: what the
// co-simulation of stereo_top (sim_configs.cpp) and the stage testbenches (testbench/) share.
// Include the Verilator runtime headers (verilated.h, verilated_fst_c.h) before this one.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

// A model Verilated without --trace-fst (VM_TRACE_FST 0: the on-demand runners, unless a trace
// is asked for) has no trace(): trace_to() then throws.
#if !defined(VM_TRACE_FST) || VM_TRACE_FST
#define STEREO_HARNESS_FST 1
#else
#define STEREO_HARNESS_FST 0
#endif

namespace stereo::sim {

template <typename Model>
class VerilatedHarness {
  public:
    // `rand_reset` (Verilator's randReset, 2: random) with `rand_seed` makes registers and RAMs
    // start random under --x-initial unique; 0 keeps Verilator's default.
    explicit VerilatedHarness(const char* name, int rand_reset = 0, int rand_seed = 0)
        : context_(std::make_unique<VerilatedContext>()) {
#if STEREO_HARNESS_FST
        context_->traceEverOn(true);
#endif
        if (rand_reset != 0) {
            context_->randReset(rand_reset);
            context_->randSeed(rand_seed);
        }
        model_ = std::make_unique<Model>(context_.get(), name);
    }
    VerilatedHarness(const VerilatedHarness&) = delete;
    VerilatedHarness& operator=(const VerilatedHarness&) = delete;
    ~VerilatedHarness() {
#if STEREO_HARNESS_FST
        if (trace_) {
            trace_->close();
        }
#endif
        model_->final();
    }

    Model& model() {
        return *model_;
    }
    const Model& model() const {
        return *model_;
    }

    // Starts writing an FST waveform of everything that follows.
    void trace_to(const std::string& path) {
#if STEREO_HARNESS_FST
        // One library holds traced and untraced models (sim/CMakeLists.txt STEREO_TRACE_CONFIGS):
        // an untraced one has no trace().
        if constexpr (requires(Model & model, VerilatedFstC * fst) { model.trace(fst, 99); }) {
            trace_ = std::make_unique<VerilatedFstC>();
            model_->trace(trace_.get(), 99);
            trace_->open(path.c_str());
            if (!trace_->isOpen()) {
                throw std::runtime_error("cannot write waveform '" + path + "'");
            }
        } else {
            throw std::runtime_error(
                "this model was Verilated without tracing (configure with "
                "-DSTEREO_TRACE_CONFIGS=all to trace every one); cannot write '" +
                path + "'");
        }
#else
        throw std::runtime_error("this model was Verilated without tracing; cannot write '" + path +
                                 "'");
#endif
    }

    // rst high for two clocks with the other inputs as they are set, then low (the cores'
    // synchronous reset).
    void pulse_reset() {
        model_->rst = 1;
        tick();
        tick();
        model_->rst = 0;
    }

    // Inputs are already set: the falling edge settles them, the rising edge steps.
    void tick() {
        model_->clk = 0;
        model_->eval();
        dump();
        model_->clk = 1;
        model_->eval();
        dump();
    }

    // Writes the current values to the waveform (if any) and advances its time.
    void dump() {
#if STEREO_HARNESS_FST
        if (trace_) {
            trace_->dump(time_);
        }
#endif
        ++time_;
    }

  private:
    std::unique_ptr<VerilatedContext> context_;
    std::unique_ptr<Model> model_;
#if STEREO_HARNESS_FST
    std::unique_ptr<VerilatedFstC> trace_;
#endif
    std::uint64_t time_ = 0;
};

}  // namespace stereo::sim

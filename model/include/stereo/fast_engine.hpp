// The fast CPU engine of the 1-D pipeline (issue 49; docs/cpu-engine.md): the same stages as
// stereo::match_validated (cost, Gaussian window, CA rules 1 and 2, stage 6), bit for bit, run in
// tiles of rows on worker threads. Each tile computes its own halo rows (the window radius plus
// the CA rules' two rows), so the seams are exact; inside a tile every plane is a few tens of
// kilobytes and stays in the core's cache, where the model streams whole-image planes through
// memory. The model (pipeline.cpp, stages/) stays the readable reference;
// tests/test_fast_engine.cpp compares the two on every scene, option and thread count.
#pragma once

#include <memory>
#include <vector>

#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"

namespace stereo::fast {

inline constexpr int kMaxThreads = 256;

// Throws std::invalid_argument (one line) unless 1 <= threads <= kMaxThreads.
void validate_threads(int threads);
// The threads a request means: 0 = every hardware thread (at most kMaxThreads); others as
// validate_threads accepts them.
int thread_count(int requested);

class Engine {
  public:
    // Validates the parameters (stereo::validate_params) and the thread count; builds the kernel
    // and the cost once.
    Engine(const MatchParams& params, int threads);
    ~Engine();
    Engine(const Engine&) = delete;
    Engine& operator=(const Engine&) = delete;

    // stereo::validate_size for this configuration.
    void validate(int width, int height) const;
    // The result of stereo::match_validated(left, right, params), bit for bit. The buffers of
    // `out` and the engine's work space are reused from one frame to the next; not reentrant
    // (one call at a time per engine).
    void match(const Image& left, const Image& right, ValidatedDisparity& out);
    ValidatedDisparity match(const Image& left, const Image& right);

    const MatchParams& params() const { return params_; }
    int threads() const { return threads_; }

  private:
    struct State;
    MatchParams params_;
    int threads_;
    std::unique_ptr<State> state_;
};

// One-shot convenience: Engine(params, threads).match(left, right).
ValidatedDisparity match_validated(const Image& left, const Image& right, const MatchParams& params,
                                   int threads = 1);

}  // namespace stereo::fast

#include "stereo_robot/slam/frontend.hpp"

#include <memory>

#include "stereo/fast_engine.hpp"
#include "stereo/matcher.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/sparse.hpp"

namespace stereo::robot::slam {
namespace {

MatchConfig config_of(const FrontendParams& params) {
    MatchConfig config;
    config.pipeline = {params.ndisp, params.window, params.sigma, false};
    config.pipeline.cost = params.cost;
    config.sparse = {params.uniqueness, params.lr_tolerance};
    return config;
}

const MatcherRegistry& registry() {
    static const MatcherRegistry models = [] {
        MatcherRegistry r;
        register_model_matchers(r);
        return r;
    }();
    return models;
}

}  // namespace

void validate_frontend(const FrontendParams& params, int width, int height) {
    registry().create("sparse", "model", config_of(params))->validate(width, height);
}

SparseDisparity sparse_disparity_model(const Image& left, const Image& right,
                                       const FrontendParams& params, ValidationCounts* counts) {
    const MatchResult result =
        registry().create("sparse", "model", config_of(params))->compute(left, right);
    SparseDisparity out(result.disparity.width, result.disparity.height);
    out.disparity = result.subpixel;
    if (counts != nullptr) {
        const auto count = [&result](const char* name) {
            return static_cast<std::size_t>(result.count(name));
        };
        *counts = {count("candidates"), count("uncertain"), count("inconsistent"), count("valid")};
    }
    return out;
}

SparseDisparity sparse_disparity(const Image& left, const Image& right,
                                 const FrontendParams& params, ValidationCounts* counts,
                                 int threads) {
    check_pair(left, right);
    const MatchConfig config = config_of(params);
    sparse::validate(config.pipeline, config.sparse, left.width, left.height);
    // One engine per calling thread, for the last parameters: a sequence's frames reuse its
    // buffers (the engine is not reentrant, hence per thread).
    struct Cached {
        FrontendParams params;
        int threads = 0;
        std::unique_ptr<fast::Engine> engine;
    };
    thread_local Cached cached;
    if (!cached.engine || !(cached.params == params) || cached.threads != threads) {
        cached.engine = std::make_unique<fast::Engine>(
            sparse::stage6_params(config.pipeline, config.sparse), fast::thread_count(threads));
        cached.params = params;
        cached.threads = threads;
    }
    thread_local ValidatedDisparity validated;
    cached.engine->match(left, right, validated);
    return sparse::from_validated(validated, counts);
}

}  // namespace stereo::robot::slam

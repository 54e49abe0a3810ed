#include "stereo_robot/slam/frontend.hpp"

#include "stereo/matcher.hpp"

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

SparseDisparity sparse_disparity(const Image& left, const Image& right,
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

}  // namespace stereo::robot::slam

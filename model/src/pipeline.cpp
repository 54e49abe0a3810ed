#include "stereo/pipeline.hpp"

#include "plane_kernels.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace stereo {
namespace {

using Value = Dsi::Value;

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

void check_kernel(const std::vector<std::int32_t>& kernel) {
    std::int64_t sum = 0;
    for (const auto tap : kernel) {
        if (tap < 0) {
            throw std::invalid_argument("kernel taps must be non-negative");
        }
        sum += tap;
    }
    if (kernel.empty() || kernel.size() % 2 == 0 || sum != fx::kKernelSum) {
        throw std::invalid_argument("kernel must have an odd number of taps summing to " +
                                    std::to_string(fx::kKernelSum));
    }
}

}  // namespace

void check_pair(const Image& left, const Image& right) {
    if (left.empty() || right.empty()) {
        throw std::invalid_argument("left and right images must not be empty");
    }
    if (left.width != right.width || left.height != right.height) {
        throw std::invalid_argument("left image is " + size_text(left.width, left.height) +
                                    " but right image is " + size_text(right.width, right.height));
    }
    if (left.channels != right.channels) {
        throw std::invalid_argument("left image has " + std::to_string(left.channels) +
                                    " channel(s) but right image has " +
                                    std::to_string(right.channels));
    }
}

InvalidBorder invalid_border(const MatchParams& params) {
    // Aggregation reaches `radius` pixels out; the CA rules one pixel more (3x3).
    return {params.window / 2 + (params.use_ca ? 1 : 0)};
}

void validate(const MatchParams& params, int width, int height) {
    if (params.ndisp < 1 || params.ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp must be in [1, " + std::to_string(fx::kMaxDisparities) +
                                    "], got " + std::to_string(params.ndisp));
    }
    if (params.ndisp >= width) {
        throw std::invalid_argument("ndisp " + std::to_string(params.ndisp) +
                                    " must be smaller than the image width " +
                                    std::to_string(width));
    }
    (void)gaussian_kernel(params.window, params.sigma);  // throws on a bad window or sigma
    const InvalidBorder border = invalid_border(params);
    if (width <= 2 * border.reach || height <= 2 * border.reach) {
        throw std::invalid_argument("image " + size_text(width, height) +
                                    " is too small for ndisp " + std::to_string(params.ndisp) +
                                    " and window " + std::to_string(params.window) +
                                    ": no pixel would be valid");
    }
}

Dsi cost(const Image& left, const Image& right, int ndisp) {
    check_pair(left, right);
    if (ndisp < 1 || ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp out of range: " + std::to_string(ndisp));
    }
    const detail::PlanarImage left_planes(left);
    const detail::PlanarImage right_planes(right);
    Dsi dsi(left.width, left.height, ndisp);
    for (int d = 0; d < ndisp; ++d) {
        detail::cost_plane(left_planes, right_planes, d, dsi.plane(d).data());
    }
    return dsi;
}

Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel) {
    check_kernel(kernel);
    Dsi out(cost.width(), cost.height(), cost.ndisp());
    detail::PlaneAggregator aggregator(kernel, cost.width(), cost.height());
    for (int d = 0; d < cost.ndisp(); ++d) {
        aggregator.run(cost.plane(d).data(), out.plane(d).data());
    }
    return out;
}

Dsi ca_rule1(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    detail::PlaneRule1 rule(dsi.width(), dsi.height());
    for (int d = 0; d < dsi.ndisp(); ++d) {
        const Value* below = d > 0 ? dsi.plane(d - 1).data() : nullptr;
        const Value* above = d + 1 < dsi.ndisp() ? dsi.plane(d + 1).data() : nullptr;
        rule.run(below, dsi.plane(d).data(), above, out.plane(d).data());
    }
    return out;
}

Dsi ca_rule2(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    for (int d = 0; d < dsi.ndisp(); ++d) {
        detail::ca_rule2_plane(dsi.plane(d).data(), dsi.width(), dsi.height(), out.plane(d).data());
    }
    return out;
}

namespace {

// The last step of wta: labels become disparities where the border rule allows.
DisparityMap finish_wta(const std::vector<std::uint8_t>& label, int width, int height,
                        const InvalidBorder& border) {
    DisparityMap map(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = map.index(x, y);
            if (border.valid(x, y, label[i], width, height)) {
                map.disparity[i] = label[i];
                map.valid[i] = 1;
            }
        }
    }
    return map;
}

}  // namespace

DisparityMap wta(const Dsi& dsi, const InvalidBorder& border) {
    std::vector<Value> best(dsi.plane(0).begin(), dsi.plane(0).end());
    std::vector<std::uint8_t> label(dsi.plane_size(), 0);
    for (int d = 1; d < dsi.ndisp(); ++d) {
        detail::wta_update(dsi.plane(d).data(), d, dsi.plane_size(), best.data(), label.data());
    }
    return finish_wta(label, dsi.width(), dsi.height(), border);
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    const int width = left.width;
    const int height = left.height;
    const int ndisp = params.ndisp;
    const std::size_t plane_size = static_cast<std::size_t>(width) * height;

    // The same kernels as the volume stages, streamed over d: plane d of the CA output needs
    // aggregated planes d-1, d and d+1 only, so three aggregated planes rotate in a ring and
    // the whole working set stays in cache. tests/test_model.cpp checks match() against the
    // composition of the volume stages and against the naive reference.
    const detail::PlanarImage left_planes(left);
    const detail::PlanarImage right_planes(right);
    detail::PlaneAggregator aggregator(gaussian_kernel(params.window, params.sigma), width, height);
    detail::PlaneRule1 rule1(width, height);
    std::vector<Value> cost_plane(plane_size);
    std::array<std::vector<Value>, 3> aggregated;  // ring: plane d lives in slot d % 3
    for (auto& slot : aggregated) {
        slot.resize(plane_size);
    }
    std::vector<Value> rule1_plane(plane_size);
    std::vector<Value> rule2_plane(plane_size);
    std::vector<Value> best(plane_size);
    std::vector<std::uint8_t> label(plane_size, 0);

    auto aggregate_into_ring = [&](int d) {
        detail::cost_plane(left_planes, right_planes, d, cost_plane.data());
        aggregator.run(cost_plane.data(), aggregated[static_cast<std::size_t>(d % 3)].data());
    };
    auto ring = [&](int d) { return aggregated[static_cast<std::size_t>(d % 3)].data(); };

    aggregate_into_ring(0);
    for (int d = 0; d < ndisp; ++d) {
        if (d + 1 < ndisp) {
            aggregate_into_ring(d + 1);
        }
        const Value* final_plane = ring(d);
        if (params.use_ca) {
            rule1.run(d > 0 ? ring(d - 1) : nullptr, ring(d), d + 1 < ndisp ? ring(d + 1) : nullptr,
                      rule1_plane.data());
            detail::ca_rule2_plane(rule1_plane.data(), width, height, rule2_plane.data());
            final_plane = rule2_plane.data();
        }
        if (d == 0) {
            std::copy_n(final_plane, plane_size, best.begin());
        } else {
            detail::wta_update(final_plane, d, plane_size, best.data(), label.data());
        }
    }
    return finish_wta(label, width, height, invalid_border(params));
}

}  // namespace stereo

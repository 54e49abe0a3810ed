#include "stereo/edge_frontend.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "edge_checks.hpp"
#include "stereo/constants.hpp"
#include "stereo/reference.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"

namespace stereo::edge_frontend {
using namespace detail;  // NOLINT: the shared checks of edge_checks.hpp

void validate(const EdgeParams& params) {
    (void)gaussian_kernel(params.log_window, params.log_sigma);  // throws on a bad window/sigma
    if (params.edge_value < 0 || params.edge_value > fx::kPixelMax) {
        throw std::invalid_argument("edge value must be in [0, 255], got " +
                                    std::to_string(params.edge_value));
    }
    check_truncation(params.truncation);
}

Response log_response(const Image& grey, const std::vector<std::int32_t>& kernel) {
    const auto [w, h, r] = log_shape(grey, kernel);
    const auto row_start = [w = w](int y) { return static_cast<std::size_t>(y) * w; };

    // Vertical pass then horizontal pass, both with replicated borders; no rounding, so the
    // result equals the direct 2-D sum with weights k[i] k[j].
    std::vector<std::int32_t> vertical(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        std::int32_t* out = vertical.data() + row_start(y);
        for (int j = -r; j <= r; ++j) {
            const std::uint8_t* in = grey.pixels.data() + row_start(std::clamp(y + j, 0, h - 1));
            const std::int32_t tap = kernel[static_cast<std::size_t>(j + r)];
            for (int x = 0; x < w; ++x) {
                out[x] += tap * in[x];
            }
        }
    }
    std::vector<std::int32_t> smooth(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        const std::int32_t* in = vertical.data() + row_start(y);
        std::int32_t* out = smooth.data() + row_start(y);
        for (int x = 0; x < w; ++x) {
            std::int32_t sum = 0;
            for (int i = -r; i <= r; ++i) {
                sum += kernel[static_cast<std::size_t>(i + r)] * in[std::clamp(x + i, 0, w - 1)];
            }
            out[x] = sum;
        }
    }

    Response response{w, h, std::vector<std::int32_t>(static_cast<std::size_t>(w) * h)};
    for (int y = 0; y < h; ++y) {
        const std::int32_t* up = smooth.data() + row_start(std::max(y - 1, 0));
        const std::int32_t* mid = smooth.data() + row_start(y);
        const std::int32_t* down = smooth.data() + row_start(std::min(y + 1, h - 1));
        std::int32_t* out = response.values.data() + row_start(y);
        for (int x = 0; x < w; ++x) {
            const std::int32_t left = mid[std::max(x - 1, 0)];
            const std::int32_t right = mid[std::min(x + 1, w - 1)];
            out[x] = up[x] + down[x] + left + right - 4 * mid[x];
        }
    }
    return response;
}

Image zero_crossings(const Response& response) {
    const int w = response.width;
    const int h = response.height;
    Image edges(w, h, 1);
    for (int y = 0; y < h; ++y) {
        const std::int32_t* row = response.values.data() + static_cast<std::size_t>(y) * w;
        const std::int32_t* below = y + 1 < h ? row + w : nullptr;
        std::uint8_t* out = edges.pixels.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            const bool right_differs = x + 1 < w && opposite(row[x], row[x + 1]);
            const bool below_differs = below != nullptr && opposite(row[x], below[x]);
            out[x] = right_differs || below_differs ? 1 : 0;
        }
    }
    return edges;
}

Image superimpose(const Image& image, const Image& edges, int value) {
    check_same_size(image, edges);
    Image out = image;
    const auto fill = static_cast<std::uint8_t>(value);
    const std::size_t count = edges.pixels.size();
    for (std::size_t i = 0; i < count; ++i) {
        if (edges.pixels[i] != 0) {
            std::fill_n(out.pixels.begin() + static_cast<std::ptrdiff_t>(i) * image.channels,
                        image.channels, fill);
        }
    }
    return out;
}

Image enhance(const Image& image, const EdgeParams& params) {
    validate(params);
    const Response response =
        log_response(luma(image), gaussian_kernel(params.log_window, params.log_sigma));
    return superimpose(image, zero_crossings(response), params.edge_value);
}

Dsi truncated_cost(const Image& left, const Image& right, int ndisp, int truncation) {
    check_cost_inputs(left, right, ndisp, truncation);
    return cost_volume(*make_truncated_ad_cost(truncation), left, right, ndisp);
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params) {
    const MatchParams plain = checked_plain_params(left, right, params, edge_params);
    return match_with(*make_truncated_ad_cost(edge_params.truncation),
                      gaussian_kernel(plain.window, plain.sigma), enhance(left, edge_params),
                      enhance(right, edge_params), plain);
}

}  // namespace stereo::edge_frontend

// Naive reference of the edge front end (docs/avoidance.md): direct 2-D sums, clamped
// coordinates, the volume stages of the naive pipeline.
#include <algorithm>
#include <cstdlib>

#include "../edge_checks.hpp"
#include "cells.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/reference.hpp"

namespace stereo::edge_frontend {
using namespace detail;  // NOLINT: the shared checks of edge_checks.hpp

namespace naive {

Image luma(const Image& image) {
    if (image.channels == 1) {
        return image;
    }
    Image grey(image.width, image.height, 1);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const int sum =
                77 * image.at(x, y, 0) + 150 * image.at(x, y, 1) + 29 * image.at(x, y, 2);
            grey.at(x, y, 0) = static_cast<std::uint8_t>((sum + 128) / 256);
        }
    }
    return grey;
}

Response log_response(const Image& grey, const std::vector<std::int32_t>& kernel) {
    // Named variables, not a structured binding: the lambdas below capture them, which clang
    // before 16 (the fuzz build, docs/reliability.md) does not allow for bindings.
    const LogShape shape = log_shape(grey, kernel);
    const int w = shape.w;
    const int h = shape.h;
    const int r = shape.r;
    const auto pixel = [&](int x, int y) {
        return static_cast<std::int64_t>(
            grey.at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1), 0));
    };
    const auto smooth = [&](int x, int y) {
        std::int64_t sum = 0;
        for (int j = -r; j <= r; ++j) {
            for (int i = -r; i <= r; ++i) {
                sum +=
                    static_cast<std::int64_t>(kernel[i + r]) * kernel[j + r] * pixel(x + i, y + j);
            }
        }
        return sum;
    };
    const auto smooth_clamped = [&](int x, int y) {
        return smooth(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1));
    };
    Response response{w, h, std::vector<std::int32_t>(static_cast<std::size_t>(w) * h)};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::int64_t laplacian = smooth_clamped(x - 1, y) + smooth_clamped(x + 1, y) +
                                           smooth_clamped(x, y - 1) + smooth_clamped(x, y + 1) -
                                           4 * smooth(x, y);
            response.values[static_cast<std::size_t>(y) * w + x] =
                static_cast<std::int32_t>(laplacian);
        }
    }
    return response;
}

Image zero_crossings(const Response& response) {
    Image edges(response.width, response.height, 1);
    for (int y = 0; y < response.height; ++y) {
        for (int x = 0; x < response.width; ++x) {
            bool edge = false;
            if (x + 1 < response.width) {
                edge = edge || opposite(response.at(x, y), response.at(x + 1, y));
            }
            if (y + 1 < response.height) {
                edge = edge || opposite(response.at(x, y), response.at(x, y + 1));
            }
            edges.at(x, y, 0) = edge ? 1 : 0;
        }
    }
    return edges;
}

Image superimpose(const Image& image, const Image& edges, int value) {
    check_same_size(image, edges);
    Image out = image;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                if (edges.at(x, y, 0) != 0) {
                    out.at(x, y, c) = static_cast<std::uint8_t>(value);
                }
            }
        }
    }
    return out;
}

Dsi truncated_cost(const Image& left, const Image& right, int ndisp, int truncation) {
    check_cost_inputs(left, right, ndisp, truncation);
    return reference::pixel_cost_volume(left, ndisp, 0, fx::kCostOutside,
                                        [&](int x, int y, int right_x) {
                                            const auto l = rgb(left, x, y);
                                            const auto r = rgb(right, right_x, y);
                                            int sum = 0;
                                            for (int c = 0; c < 3; ++c) {
                                                sum += std::abs(l[c] - r[c]);
                                            }
                                            return std::min(sum, truncation);
                                        });
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params) {
    const MatchParams plain = checked_plain_params(left, right, params, edge_params);
    const auto enhance_naive = [&](const Image& image) {
        const auto kernel = gaussian_kernel(edge_params.log_window, edge_params.log_sigma);
        return naive::superimpose(
            image, naive::zero_crossings(naive::log_response(naive::luma(image), kernel)),
            edge_params.edge_value);
    };
    const Dsi cost = naive::truncated_cost(enhance_naive(left), enhance_naive(right), plain.ndisp,
                                           edge_params.truncation);
    return stereo::naive::wta(
        stereo::naive::aggregate(cost, gaussian_kernel(plain.window, plain.sigma)),
        invalid_border(plain));
}

}  // namespace naive

}  // namespace stereo::edge_frontend

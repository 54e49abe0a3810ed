#include "stereo/edge_frontend.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "stereo/constants.hpp"
#include "stereo/reference.hpp"

namespace stereo::edge_frontend {
namespace {

using Value = Dsi::Value;

// BT.601 weights scaled to 256 (0.299, 0.587, 0.114 -> 77, 150, 29; they sum to 256).
constexpr int kLumaR = 77;
constexpr int kLumaG = 150;
constexpr int kLumaB = 29;
constexpr int kLumaShift = 8;
static_assert(kLumaR + kLumaG + kLumaB == 1 << kLumaShift);

// Widths: the smoothed image is at most 255 * 2^16 (24 bits); the Laplacian is at most 8 times
// that in magnitude, which fits a signed 32-bit value.
static_assert(static_cast<std::int64_t>(fx::kPixelMax) * fx::kKernelSum * fx::kKernelSum * 8 <
              (std::int64_t{1} << 31));

void check_grey(const Image& grey) {
    if (grey.empty() || grey.channels != 1) {
        throw std::invalid_argument("the LoG needs a non-empty grey image");
    }
}

void check_same_size(const Image& image, const Image& edges) {
    if (edges.channels != 1 || edges.width != image.width || edges.height != image.height) {
        throw std::invalid_argument("edge map must be a grey image of the same size");
    }
}

void check_truncation(int truncation) {
    if (truncation < 0 || truncation > fx::kCostMax) {
        throw std::invalid_argument("truncation must be in [0, " + std::to_string(fx::kCostMax) +
                                    "], got " + std::to_string(truncation));
    }
}

void check_cost_inputs(const Image& left, const Image& right, int ndisp, int truncation) {
    check_pair(left, right);
    if (ndisp < 1 || ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp out of range: " + std::to_string(ndisp));
    }
    check_truncation(truncation);
}

// Per-pixel colour as three values, grey repeated, so both versions count channels alike.
std::array<int, 3> rgb(const Image& image, int x, int y) {
    if (image.channels == 1) {
        const int g = image.at(x, y, 0);
        return {g, g, g};
    }
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

// Strictly opposite signs; a zero is neither, so the flat zero response beside a lobe is not a
// crossing.
bool opposite(std::int32_t a, std::int32_t b) {
    return (a < 0 && b > 0) || (a > 0 && b < 0);
}

MatchParams without_ca(MatchParams params) {
    params.use_ca = false;
    return params;
}

}  // namespace

void validate(const EdgeParams& params) {
    (void)gaussian_kernel(params.log_window, params.log_sigma);  // throws on a bad window/sigma
    if (params.edge_value < 0 || params.edge_value > fx::kPixelMax) {
        throw std::invalid_argument("edge value must be in [0, 255], got " +
                                    std::to_string(params.edge_value));
    }
    check_truncation(params.truncation);
}

Image luma(const Image& image) {
    if (image.channels == 1) {
        return image;
    }
    Image grey(image.width, image.height, 1);
    const std::size_t count = grey.pixels.size();
    const std::uint8_t* src = image.pixels.data();
    for (std::size_t i = 0; i < count; ++i, src += 3) {
        const int sum = kLumaR * src[0] + kLumaG * src[1] + kLumaB * src[2];
        grey.pixels[i] = static_cast<std::uint8_t>((sum + (1 << (kLumaShift - 1))) >> kLumaShift);
    }
    return grey;
}

Response log_response(const Image& grey, const std::vector<std::int32_t>& kernel) {
    check_grey(grey);
    const int w = grey.width;
    const int h = grey.height;
    const int r = static_cast<int>(kernel.size()) / 2;
    const auto row_start = [w](int y) { return static_cast<std::size_t>(y) * w; };

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
    const int w = left.width;
    const int h = left.height;
    const int ch = left.channels;
    // A grey difference counts three times, as if every channel held it.
    const int weight = ch == 1 ? 3 : 1;
    Dsi dsi(w, h, ndisp);
    for (int d = 0; d < ndisp; ++d) {
        Value* plane = dsi.plane(d).data();
        for (int y = 0; y < h; ++y) {
            const std::uint8_t* l = left.pixels.data() + static_cast<std::size_t>(y) * w * ch;
            const std::uint8_t* r = right.pixels.data() + static_cast<std::size_t>(y) * w * ch;
            Value* out = plane + static_cast<std::size_t>(y) * w;
            const int first = std::min(d, w);
            for (int x = 0; x < first; ++x) {
                out[x] = static_cast<Value>(fx::kCostOutside);
            }
            for (int x = first; x < w; ++x) {
                int sum = 0;
                for (int c = 0; c < ch; ++c) {
                    sum += std::abs(l[x * ch + c] - r[(x - d) * ch + c]);
                }
                out[x] = static_cast<Value>(std::min(sum * weight, truncation));
            }
        }
    }
    return dsi;
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params) {
    check_pair(left, right);
    const MatchParams plain = without_ca(params);
    stereo::validate(plain, left.width, left.height);
    validate(edge_params);
    const Dsi cost = truncated_cost(enhance(left, edge_params), enhance(right, edge_params),
                                    plain.ndisp, edge_params.truncation);
    return wta(aggregate(cost, gaussian_kernel(plain.window, plain.sigma)), invalid_border(plain));
}

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
    check_grey(grey);
    const int w = grey.width;
    const int h = grey.height;
    const int r = static_cast<int>(kernel.size()) / 2;
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
    Dsi dsi(left.width, left.height, ndisp);
    for (int d = 0; d < ndisp; ++d) {
        for (int y = 0; y < left.height; ++y) {
            for (int x = 0; x < left.width; ++x) {
                if (x - d < 0) {
                    dsi.at(x, y, d) = static_cast<Value>(fx::kCostOutside);
                    continue;
                }
                const auto l = rgb(left, x, y);
                const auto r = rgb(right, x - d, y);
                int sum = 0;
                for (int c = 0; c < 3; ++c) {
                    sum += std::abs(l[c] - r[c]);
                }
                dsi.at(x, y, d) = static_cast<Value>(std::min(sum, truncation));
            }
        }
    }
    return dsi;
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params,
                   const EdgeParams& edge_params) {
    check_pair(left, right);
    const MatchParams plain = without_ca(params);
    stereo::validate(plain, left.width, left.height);
    validate(edge_params);
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

// Naive reference of the LCDM cost (stereo/stages/lcdm.hpp): each pixel is converted again for
// every comparison, the hue sector is found by a different test order (ties give the same hue),
// the table entries come from std::cos / std::sin on the spot, every rounding is an explicit
// floor division and the square root is found bit by bit.
#include <cmath>
#include <cstdint>
#include <numbers>

#include "cells.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::lcdm::naive {
namespace {

// Floor division for any sign of the numerator (positive divisor).
std::int64_t floor_div(std::int64_t num, std::int64_t den) {
    std::int64_t q = num / den;
    if (num % den != 0 && num < 0) {
        --q;
    }
    return q;
}

std::int64_t table_entry(int h, bool sine) {
    const double angle = 2.0 * std::numbers::pi * h / kHueCount;
    return std::llround((sine ? std::sin(angle) : std::cos(angle)) * std::ldexp(1.0, kTrigBits));
}

struct Point {
    std::int64_t a;
    std::int64_t b;
};

Point convert(const Image& image, int x, int y, int dark_floor) {
    const int r = image.at(x, y, 0);
    const int g = image.at(x, y, 1);
    const int b = image.at(x, y, 2);
    int mx = r;
    int mn = r;
    for (const int v : {g, b}) {
        mx = v > mx ? v : mx;
        mn = v < mn ? v : mn;
    }
    const int c = mx - mn;
    if (c == 0) {
        return {0, 0};
    }
    int den = mx + mn;
    if (2 * fx::kPixelMax - (mx + mn) < den) {
        den = 2 * fx::kPixelMax - (mx + mn);
    }
    if (den < dark_floor) {
        den = dark_floor;
    }
    // round(C * kRadius / den), half up.
    const std::int64_t s = floor_div(2LL * c * kRadius + den, 2LL * den);
    // Hue in sixths of a turn times C: tested blue, green, red (the plug-in: red, green, blue).
    std::int64_t t = 0;
    if (b == mx) {
        t = 4LL * c + (r - g);
    } else if (g == mx) {
        t = 2LL * c + (b - r);
    } else {
        t = (g - b) >= 0 ? (g - b) : (g - b) + 6LL * c;
    }
    const auto h = static_cast<int>(floor_div(2LL * kHueSteps * t + c, 2LL * c) % kHueCount);
    const std::int64_t unit = std::int64_t{1} << kTrigBits;
    return {floor_div(s * table_entry(h, false) + unit / 2, unit),
            floor_div(s * table_entry(h, true) + unit / 2, unit)};
}

std::int64_t square_root(std::int64_t q) {
    std::int64_t root = 0;
    for (std::int64_t bit = std::int64_t{1} << 30; bit > 0; bit >>= 1) {
        if ((root + bit) * (root + bit) <= q) {
            root += bit;
        }
    }
    return root;
}

}  // namespace

int pixel_cost(const Image& left, int x, int y, const Image& right, int xr, int yr,
               int dark_floor) {
    require_colour(left);
    require_colour(right);
    const Point p = convert(left, x, y, dark_floor);
    const Point q = convert(right, xr, yr, dark_floor);
    const std::int64_t twice_distance =
        square_root(4 * ((p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b)));
    const std::int64_t value =
        floor_div(twice_distance * fx::kCostMax + 2 * kRadius, 4LL * kRadius);
    return static_cast<int>(value > fx::kCostMax ? fx::kCostMax : value);
}

Dsi cost(const Image& left, const Image& right, int ndisp, int dark_floor, int min_disp) {
    check_pair(left, right);
    require_colour(left);
    require_colour(right);
    return reference::pixel_cost_volume(
        left, ndisp, min_disp, fx::kCostOutside, [&](int x, int y, int right_x) {
            return pixel_cost(left, x, y, right, right_x, y, dark_floor);
        });
}

Dsi cost(const Image& left, const Image& right, int ndisp) {
    return cost(left, right, ndisp, kDarkFloor);
}

}  // namespace stereo::lcdm::naive

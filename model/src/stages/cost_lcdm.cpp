// LCDM cost plug-in (stereo/stages/lcdm.hpp, docs/fixed-point.md "LCDM"); naive reference in
// reference/lcdm_naive.cpp, exact-trigonometry reference lcdm::floating::cost below.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "stereo/stages.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo {
namespace lcdm {
namespace {

// cos of index h from the quarter wave, by the symmetries of the cosine (the RTL does the same
// with lcdm_quarter_cos in fx_pkg); sin(h) = cos(h + 3/4 turn).
int cos_from_quarter(int h) {
    h %= kHueCount;
    if (h <= kHueQuarter) {
        return quarter_cos(h);
    }
    if (h <= 2 * kHueQuarter) {
        return -quarter_cos(2 * kHueQuarter - h);
    }
    if (h <= 3 * kHueQuarter) {
        return -quarter_cos(h - 2 * kHueQuarter);
    }
    return quarter_cos(kHueCount - h);
}

std::array<std::int16_t, kHueCount> make_table(bool sine) {
    std::array<std::int16_t, kHueCount> table{};
    for (int h = 0; h < kHueCount; ++h) {
        table[static_cast<std::size_t>(h)] =
            static_cast<std::int16_t>(cos_from_quarter(sine ? h + 3 * kHueQuarter : h));
    }
    return table;
}

}  // namespace

int quarter_cos(int k) {
    if (k < 0 || k > kHueQuarter) {
        throw std::out_of_range("quarter_cos index " + std::to_string(k));
    }
    const double angle = 2.0 * std::numbers::pi * k / kHueCount;
    return static_cast<int>(std::lround(std::cos(angle) * (1 << kTrigBits)));
}

const std::array<std::int16_t, kHueCount>& cos_table() {
    static const auto table = make_table(false);
    return table;
}

const std::array<std::int16_t, kHueCount>& sin_table() {
    static const auto table = make_table(true);
    return table;
}

Chroma chroma(int r, int g, int b, int dark_floor) {
    const int mx = std::max({r, g, b});
    const int mn = std::min({r, g, b});
    const int c = mx - mn;
    if (c == 0) {
        return {};
    }
    const int l2 = mx + mn;
    const int den = std::max(std::min(l2, kLightSum - l2), dark_floor);
    const int s = (2 * c * kRadius + den) / (2 * den);
    // Hexagonal hue times C, in [0, 6C]: the sector of the maximum plus the signed offset.
    int t = 0;
    if (mx == r) {
        t = g - b;
        if (t < 0) {
            t += 6 * c;
        }
    } else if (mx == g) {
        t = 2 * c + b - r;
    } else {
        t = 4 * c + r - g;
    }
    const int h = ((2 * kHueSteps * t + c) / (2 * c)) % kHueCount;
    const int half = 1 << (kTrigBits - 1);
    const auto index = static_cast<std::size_t>(h);
    return {static_cast<std::int16_t>((s * cos_table()[index] + half) >> kTrigBits),
            static_cast<std::int16_t>((s * sin_table()[index] + half) >> kTrigBits)};
}

int isqrt(std::uint32_t q) {
    // A double holds q exactly and its correctly rounded square root never crosses the next
    // integer for q < 2^52, so the truncation is the floor.
    return static_cast<int>(std::sqrt(static_cast<double>(q)));
}

int cost(Chroma left, Chroma right) {
    const int da = left.a - right.a;
    const int db = left.b - right.b;
    // isqrt(4q) = floor(2 * distance): the distance to half a unit, so the final rounding is
    // to nearest rather than biased down by the floor.
    const auto q4 = static_cast<std::uint32_t>(4 * (da * da + db * db));
    const int scaled = (isqrt(q4) * fx::kCostMax + 2 * kRadius) >> (kRadiusBits + 2);
    return std::min(scaled, fx::kCostMax);
}

void require_colour(const Image& image) {
    if (image.channels != 3) {
        throw std::invalid_argument(
            "the lcdm cost compares hue and saturation, so it needs colour (RGB) images; got a "
            "grey image (" +
            std::to_string(image.channels) + " channel)");
    }
}

namespace floating {

double cost(int r1, int g1, int b1, int r2, int g2, int b2, int dark_floor) {
    const auto point = [dark_floor](double r, double g, double b) {
        const double mx = std::max({r, g, b});
        const double mn = std::min({r, g, b});
        const double c = mx - mn;
        if (c == 0.0) {
            return std::array<double, 2>{0.0, 0.0};
        }
        const double den =
            std::max(std::min(mx + mn, 2.0 * fx::kPixelMax - (mx + mn)), double(dark_floor));
        const double saturation = c / den;
        double sector = 0.0;  // HSL hue in sixths of a turn
        if (mx == r) {
            sector = std::fmod((g - b) / c + 6.0, 6.0);
        } else if (mx == g) {
            sector = (b - r) / c + 2.0;
        } else {
            sector = (r - g) / c + 4.0;
        }
        const double hue = sector * std::numbers::pi / 3.0;
        return std::array<double, 2>{saturation * std::cos(hue), saturation * std::sin(hue)};
    };
    const auto p = point(r1, g1, b1);
    const auto q = point(r2, g2, b2);
    const double distance = std::hypot(p[0] - q[0], p[1] - q[1]);
    return std::min(distance * fx::kCostMax / 2.0, double(fx::kCostMax));
}

}  // namespace floating
}  // namespace lcdm

namespace {

// The converted image: a + kRadius and b + kRadius (11 bits each) as low and high bytes.
// The (a, b) coordinates of `count` pixels of row y from column x0 (offset by kRadius removed).
void unpack(const PlanarImage& image, int y, int x0, int count, int* a, int* b) {
    const std::uint8_t* a_lo = image.row(0, y) + x0;
    const std::uint8_t* a_hi = image.row(1, y) + x0;
    const std::uint8_t* b_lo = image.row(2, y) + x0;
    const std::uint8_t* b_hi = image.row(3, y) + x0;
    for (int n = 0; n < count; ++n) {
        a[n] = a_lo[n] + (a_hi[n] << 8) - lcdm::kRadius;
        b[n] = b_lo[n] + (b_hi[n] << 8) - lcdm::kRadius;
    }
}

class LcdmCost final : public CostFunction {
  public:
    explicit LcdmCost(int dark_floor) : dark_floor_(dark_floor) {}

    PlanarImage prepare(const Image& image) const override {
        lcdm::require_colour(image);
        PlanarImage planes(image.width, image.height, 4);
        const std::size_t size = static_cast<std::size_t>(image.width) * image.height;
        for (std::size_t p = 0; p < size; ++p) {
            const std::uint8_t* rgb = image.pixels.data() + 3 * p;
            const lcdm::Chroma chroma = lcdm::chroma(rgb[0], rgb[1], rgb[2], dark_floor_);
            const int a = chroma.a + lcdm::kRadius;
            const int b = chroma.b + lcdm::kRadius;
            planes.planes[0][p] = static_cast<std::uint8_t>(a & 0xFF);
            planes.planes[1][p] = static_cast<std::uint8_t>(a >> 8);
            planes.planes[2][p] = static_cast<std::uint8_t>(b & 0xFF);
            planes.planes[3][p] = static_cast<std::uint8_t>(b >> 8);
        }
        return planes;
    }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        // Unpack both row segments once, then a loop the compiler vectorises (lcdm::cost
        // inlined: the double square root truncated is the integer one, see lcdm::isqrt).
        thread_local std::vector<int> buffer;
        buffer.resize(4 * static_cast<std::size_t>(count));
        int* __restrict la = buffer.data();
        int* __restrict lb = la + count;
        int* __restrict ra = lb + count;
        int* __restrict rb = ra + count;
        unpack(left, y, x0, count, la, lb);
        unpack(right, yr, x0 - shift, count, ra, rb);
        for (int n = 0; n < count; ++n) {
            const int da = la[n] - ra[n];
            const int db = lb[n] - rb[n];
            const int root =
                static_cast<int>(std::sqrt(static_cast<double>(4 * (da * da + db * db))));
            const int scaled = (root * fx::kCostMax + 2 * lcdm::kRadius) >> (lcdm::kRadiusBits + 2);
            out[n] = static_cast<CostValue>(scaled < fx::kCostMax ? scaled : fx::kCostMax);
        }
    }

  private:
    int dark_floor_;
};

}  // namespace

std::unique_ptr<CostFunction> make_lcdm_cost(int dark_floor) {
    if (dark_floor < 1 || dark_floor > fx::kPixelMax) {
        throw std::invalid_argument("the lcdm dark floor must be in [1, 255], got " +
                                    std::to_string(dark_floor));
    }
    return std::make_unique<LcdmCost>(dark_floor);
}

}  // namespace stereo

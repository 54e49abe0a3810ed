// The fast CPU engine (stereo/fast_engine.hpp, docs/cpu-engine.md). Bit-exact with the model by
// construction: every stage is the model's integer arithmetic on the same values, only the order
// of the work changes (tiles of rows with their halos, planes of a tile instead of the image),
// and every reordered sum is of integers. The cost rows come from the model's cost plug-ins.
#include "stereo/fast_engine.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "stereo/catalogue.hpp"
#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/census.hpp"
#include "stereo/stages/validate.hpp"
#include "stereo/target_clones.hpp"

namespace stereo::fast {
namespace {

constexpr CostValue kUnset = kNoCandidate;  // no cost yet: above every aggregate
// Rows per tile: its planes (40 KB each at VGA) and stage 6's state stay in L2; the halo rows
// (window radius + 2 for the CA rules, each side) cost less the taller the tile (measured: 32 and
// 48 rows equal, 16 rows 5-10 % slower at VGA).
constexpr int kTileRows = 32;

// ---- Hot loops: integer code, so every clone gives the same bits -----------------------------

// Stage 2, vertical pass: v = t0 * c + sum over j of t_j * (row above + row below) (the kernel is
// symmetric; a row outside the image is zero and passed as such).
STEREO_TARGET_CLONES
void vertical_init(std::int32_t* __restrict v, const CostValue* __restrict c, std::int32_t tap,
                   int n) {
    for (int x = 0; x < n; ++x) {
        v[x] = tap * c[x];
    }
}

STEREO_TARGET_CLONES
void vertical_pair(std::int32_t* __restrict v, const CostValue* __restrict a,
                   const CostValue* __restrict b, std::int32_t tap, int n) {
    for (int x = 0; x < n; ++x) {
        v[x] += tap * (static_cast<std::int32_t>(a[x]) + static_cast<std::int32_t>(b[x]));
    }
}

STEREO_TARGET_CLONES
void vertical_one(std::int32_t* __restrict v, const CostValue* __restrict a, std::int32_t tap,
                  int n) {
    for (int x = 0; x < n; ++x) {
        v[x] += tap * a[x];
    }
}

// Horizontal pass over the vertical sums (`v` has `radius` zeros before and after), then the one
// rounding shift.
STEREO_TARGET_CLONES
void horizontal(const std::int32_t* __restrict v, const std::int32_t* __restrict taps, int radius,
                std::int32_t* __restrict sum, CostValue* __restrict out, int n) {
    const std::int32_t t0 = taps[0];
    for (int x = 0; x < n; ++x) {
        sum[x] = t0 * v[x];
    }
    for (int i = 1; i <= radius; ++i) {
        const std::int32_t t = taps[i];
        const std::int32_t* __restrict left = v - i;
        const std::int32_t* __restrict right = v + i;
        for (int x = 0; x < n; ++x) {
            sum[x] += t * (left[x] + right[x]);
        }
    }
    constexpr std::int32_t round_half = 1 << (fx::kAggShift - 1);
    for (int x = 0; x < n; ++x) {
        out[x] = static_cast<CostValue>((sum[x] + round_half) >> fx::kAggShift);
    }
}

// Stage 2 for the common window radii (1 .. kFusedRadii), each pass once over the row with the
// taps in registers instead of one pass per tap: `rows` holds the 2R + 1 cost rows around the
// row (the zero row for those outside the image, which adds nothing, as in the model).
constexpr int kFusedRadii = 7;

template <int R>
STEREO_TARGET_CLONES void vertical_fused(std::int32_t* __restrict v,
                                         const CostValue* const* __restrict rows,
                                         const std::int32_t* __restrict taps, int n) {
    for (int x = 0; x < n; ++x) {
        std::int32_t sum = taps[0] * static_cast<std::int32_t>(rows[R][x]);
        for (int j = 1; j <= R; ++j) {
            sum += taps[j] * (static_cast<std::int32_t>(rows[R - j][x]) +
                              static_cast<std::int32_t>(rows[R + j][x]));
        }
        v[x] = sum;
    }
}

template <int R>
STEREO_TARGET_CLONES void horizontal_fused(const std::int32_t* __restrict v,
                                           const std::int32_t* __restrict taps,
                                           CostValue* __restrict out, int n) {
    constexpr std::int32_t round_half = 1 << (fx::kAggShift - 1);
    for (int x = 0; x < n; ++x) {
        std::int32_t sum = taps[0] * v[x];
        for (int i = 1; i <= R; ++i) {
            sum += taps[i] * (v[x - i] + v[x + i]);
        }
        out[x] = static_cast<CostValue>((sum + round_half) >> fx::kAggShift);
    }
}

using VerticalFused = void (*)(std::int32_t*, const CostValue* const*, const std::int32_t*, int);
using HorizontalFused = void (*)(const std::int32_t*, const std::int32_t*, CostValue*, int);
template <int... R>
constexpr std::array<std::pair<VerticalFused, HorizontalFused>, sizeof...(R)> fused_passes(
    std::integer_sequence<int, R...>) {
    return {std::pair{&vertical_fused<R + 1>, &horizontal_fused<R + 1>}...};
}
// Index radius - 1.
const auto kFusedPasses = fused_passes(std::make_integer_sequence<int, kFusedRadii>{});

// Stage 3, CA rule 1 on one row. `up`/`down`: the rows around it (zeros outside the image);
// `before`/`after`: the neighbouring labels' aggregates (kUnset where the label does not exist,
// which never agrees: 2 |65535 - c| >= c for every aggregate c <= fx::kAggMax).
STEREO_TARGET_CLONES
void ca1_row(const CostValue* __restrict up, const CostValue* __restrict mid,
             const CostValue* __restrict down, const CostValue* __restrict before,
             const CostValue* __restrict after, std::int32_t* __restrict columns,
             CostValue* __restrict out, int n) {
    // columns[-1] and columns[n] stay 0.
    for (int x = 0; x < n; ++x) {
        columns[x] = static_cast<std::int32_t>(up[x]) + mid[x] + down[x];
    }
    for (int x = 0; x < n; ++x) {
        const int value = mid[x];
        const bool fire = fx::agrees(before[x], value) || fx::agrees(after[x], value);
        const auto box = static_cast<std::uint32_t>(columns[x - 1] + columns[x] + columns[x + 1]);
        out[x] = fire ? static_cast<CostValue>(fx::mean9(box)) : static_cast<CostValue>(value);
    }
}
static_assert(fx::kAggMax * 3 < 2 * 0xFFFF, "kUnset never agrees");

// fx::agrees in 16-bit lanes: 2 |n - c| < c (2 |n - c| <= 2 fx::kAggMax fits).
inline std::uint16_t agrees_u16(std::uint16_t n, std::uint16_t c) {
    const auto difference = static_cast<std::uint16_t>(n > c ? n - c : c - n);
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(difference + difference) < c);
}
static_assert(2 * fx::kAggMax < 0xFFFF);

// fx::div13 in 16-bit lanes: (c * kDiv13Mul + 2^16) >> 17 with kDiv13Mul = 2^16 + 35289 is
// (c + 1 + ((c * 35289) >> 16)) >> 1 (the low half of c * 35289 is below 2^16: it never carries
// into the halving). Checked for every aggregate below.
constexpr std::uint32_t kDiv13Low = fx::kDiv13Mul - (1U << 16);
// The sum c + 1 + high stays below 2^16 (c <= fx::kAggMax, high < c): kept in 16 bits so that
// the compiler vectorises the multiply as a 16-bit high half (vpmulhuw), not widened to 32.
inline std::uint16_t div13_u16(std::uint16_t c) {
    const auto high = static_cast<std::uint16_t>((static_cast<std::uint32_t>(c) * kDiv13Low) >> 16);
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(c + 1 + high) >> 1);
}
constexpr bool div13_u16_exact() {
    static_assert(fx::kDiv13Shift == 17 && fx::kDiv13Mul > (1U << 16));
    for (std::uint32_t c = 0; c <= fx::kAggMax; ++c) {
        if (c + 1 + ((c * kDiv13Low) >> 16) > 0xFFFF ||
            (c + 1 + ((c * kDiv13Low) >> 16)) >> 1 != fx::div13(c)) {
            return false;
        }
    }
    return true;
}
static_assert(div13_u16_exact(), "every aggregate, checked at compile time");

// Stage 4, CA rule 2 on an inner row (the first and last pixel pass through).
STEREO_TARGET_CLONES
void ca2_row(const CostValue* __restrict up, const CostValue* __restrict mid,
             const CostValue* __restrict down, CostValue* __restrict out, int n) {
    out[0] = mid[0];
    out[n - 1] = mid[n - 1];
    for (int x = 1; x + 1 < n; ++x) {
        const std::uint16_t c = mid[x];
        const auto count = static_cast<std::uint16_t>(
            agrees_u16(up[x - 1], c) + agrees_u16(up[x], c) + agrees_u16(up[x + 1], c) +
            agrees_u16(mid[x - 1], c) + agrees_u16(mid[x + 1], c) + agrees_u16(down[x - 1], c) +
            agrees_u16(down[x], c) + agrees_u16(down[x + 1], c));
        out[x] = count >= fx::kRule2MinCount ? div13_u16(c) : c;
    }
}

// Stage 6's per-label update in 16-bit lanes. ValidatingSelector keeps the four smallest
// (cost, label) keys to find C2, the best cost of a label outside the winner w and its two
// neighbours: that is min over |k - w| > 1 of C(k) (the smallest such key is among the four, as
// only w - 1 and w + 1 can come before it). Streamed in label order it is min(left, right): left,
// the smallest cost of the labels up to w - 2 (the prefix minimum two labels behind, taken when
// w wins), and right, the smallest from w + 2 on (restarted when a label wins). Ties keep the
// smaller label (strict <), like the keys. Bitwise blends: full stores, no masked ones.
inline CostValue blend(CostValue mask, CostValue yes, CostValue no) {
    return static_cast<CostValue>((yes & mask) | (no & ~mask));
}

STEREO_TARGET_CLONES
void update_best(std::size_t size, int k, const CostValue* __restrict costs,
                 CostValue* __restrict best_cost, CostValue* __restrict best_label,
                 CostValue* __restrict left, CostValue* __restrict right,
                 CostValue* __restrict before, CostValue* __restrict after,
                 CostValue* __restrict previous, CostValue* __restrict lagging) {
    const auto label = static_cast<CostValue>(k);
    for (std::size_t q = 0; q < size; ++q) {
        const CostValue c = costs[q];
        const CostValue w = best_label[q];
        const CostValue p = previous[q];
        const CostValue lag = lagging[q];
        // All ones where true.
        const auto new_winner = static_cast<CostValue>(-static_cast<int>(c < best_cost[q]));
        const auto far_right = static_cast<CostValue>(-static_cast<int>(label >= w + 2));
        const auto next = static_cast<CostValue>(-static_cast<int>(label == w + 1));
        const CostValue r = right[q];
        left[q] = blend(new_winner, lag, left[q]);
        right[q] = blend(new_winner, kUnset, blend(far_right, std::min(r, c), r));
        before[q] = blend(new_winner, p, before[q]);
        after[q] = blend(new_winner, kUnset, blend(next, c, after[q]));
        best_cost[q] = blend(new_winner, c, best_cost[q]);
        best_label[q] = blend(new_winner, label, w);
        lagging[q] = std::min(lag, p);
        previous[q] = c;
    }
}
static_assert(fx::kAggMax < kUnset && fx::kMaxDisparities <= 0xFFFF);

STEREO_TARGET_CLONES
void update_right(std::size_t size, std::uint16_t label, const CostValue* __restrict costs,
                  CostValue* __restrict right_cost, std::uint16_t* __restrict right_label) {
    for (std::size_t x = 0; x < size; ++x) {
        const CostValue c = costs[x];
        const bool better = c < right_cost[x];
        right_cost[x] = better ? c : right_cost[x];
        right_label[x] = better ? label : right_label[x];
    }
}

// Stage 1, census: the Hamming distance of two 24-bit codes (a SWAR popcount, which vectorises)
// times the census weight.
STEREO_TARGET_CLONES
void census_row(const std::uint32_t* __restrict l, const std::uint32_t* __restrict r, int n,
                CostValue* __restrict out) {
    for (int x = 0; x < n; ++x) {
        std::uint32_t v = l[x] ^ r[x];
        v = v - ((v >> 1) & 0x55555555U);
        v = (v & 0x33333333U) + ((v >> 2) & 0x33333333U);
        v = (v + (v >> 4)) & 0x0F0F0F0FU;
        v = v + (v >> 8);
        v = (v + (v >> 16)) & 0x3FU;
        out[x] = static_cast<CostValue>(v * census::kWeight);
    }
}

// Stage 1, AD over three planar channels.
STEREO_TARGET_CLONES
void ad_row3(const std::uint8_t* __restrict l0, const std::uint8_t* __restrict l1,
             const std::uint8_t* __restrict l2, const std::uint8_t* __restrict r0,
             const std::uint8_t* __restrict r1, const std::uint8_t* __restrict r2, int n,
             CostValue* __restrict out) {
    for (int x = 0; x < n; ++x) {
        const int d0 = l0[x] - r0[x];
        const int d1 = l1[x] - r1[x];
        const int d2 = l2[x] - r2[x];
        out[x] =
            static_cast<CostValue>((d0 < 0 ? -d0 : d0) + (d1 < 0 ? -d1 : d1) + (d2 < 0 ? -d2 : d2));
    }
}

// Stage 1, AD of a grey pair: the three equal channel differences of (g, g, g).
STEREO_TARGET_CLONES
void ad_row1(const std::uint8_t* __restrict l, const std::uint8_t* __restrict r, int n,
             CostValue* __restrict out) {
    for (int x = 0; x < n; ++x) {
        const int d = l[x] - r[x];
        out[x] = static_cast<CostValue>(fx::kChannels * (d < 0 ? -d : d));
    }
}

// The census codes of an image: the luma padded by 2 pixels of 255 (a neighbour outside the
// image is never darker than the centre: bit clear), then one pass per neighbour in the code's
// bit order (census::transform's: rows, then columns, first neighbour in the highest bit).
STEREO_TARGET_CLONES
void census_codes_row(const std::uint8_t* __restrict padded, int stride, int n,
                      std::uint32_t* __restrict codes) {
    const std::uint8_t* __restrict centre = padded + 2 * stride + 2;
    for (int x = 0; x < n; ++x) {
        codes[x] = 0;
    }
    for (int dy = -census::kRadius; dy <= census::kRadius; ++dy) {
        for (int dx = -census::kRadius; dx <= census::kRadius; ++dx) {
            if (dx == 0 && dy == 0) {
                continue;
            }
            const std::uint8_t* __restrict nb = centre + dy * stride + dx;
            for (int x = 0; x < n; ++x) {
                codes[x] = (codes[x] << 1) | (nb[x] < centre[x] ? 1U : 0U);
            }
        }
    }
}
static_assert(census::kRadius == 2, "the padding above is two pixels");

// One worker's planes and stage-6 state for one tile, reused from tile to tile and frame to frame.
struct Workspace {
    std::vector<CostValue> cost;                // cost rows of the tile and its halo
    std::array<std::vector<CostValue>, 3> agg;  // aggregates of labels k - 1, k, k + 1 (ring)
    std::vector<CostValue> ca1;
    std::vector<CostValue> ca2;
    std::vector<std::int32_t> vertical;  // one row, `radius` zeros each side
    std::vector<std::int32_t> sum;
    std::vector<std::int32_t> columns;  // one zero each side
    // Stage 6 per pixel of the tile (update_best): C1, w, left, right, C(w - 1), C(w + 1),
    // C(k - 1), the lagging prefix minimum; the left-right check's best per right pixel.
    std::array<std::vector<CostValue>, 8> best;
    std::vector<CostValue> right_cost;
    std::vector<std::uint16_t> right_label;
    int width = 0;  // the image width the buffers are for; 0: not allocated yet

    void resize(int image_width, int radius, int ca) {
        width = image_width;
        const auto w = static_cast<std::size_t>(width);
        const auto rows = [&](int n) { return static_cast<std::size_t>(n) * w; };
        cost.resize(rows(kTileRows + 2 * (radius + 2 * ca)));
        for (auto& plane : agg) {
            plane.resize(rows(kTileRows + 4 * ca));
        }
        ca1.resize(rows(kTileRows + 2 * ca));
        ca2.resize(rows(kTileRows));
        vertical.assign(w + 2 * static_cast<std::size_t>(radius), 0);
        sum.resize(w);
        columns.assign(w + 2, 0);
        for (auto& values : best) {
            values.resize(rows(kTileRows));
        }
        right_cost.resize(rows(kTileRows));
        right_label.resize(rows(kTileRows));
    }
};

// What the cost reads of one image, reused from frame to frame.
struct Prepared {
    std::vector<std::uint8_t> grey;                     // census: the luma
    std::vector<std::uint8_t> padded;                   // census: the luma, 2 pixels of 255 around
    std::vector<std::uint32_t> codes;                   // census: one code per pixel
    std::array<std::vector<std::uint8_t>, 3> channels;  // ad: the planar channels
    int channel_count = 0;
    PlanarImage planes;  // the other costs: their plug-in's prepare()
};

void prepare(catalogue::Cost kind, const CostFunction& cost, const Image& image, Prepared& out) {
    const int width = image.width;
    const int height = image.height;
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    if (kind == catalogue::Cost::census) {
        const std::uint8_t* grey = image.pixels.data();
        if (image.channels != 1) {  // stereo::luma's arithmetic, into a reused buffer
            out.grey.resize(pixels);
            const std::uint8_t* src = image.pixels.data();
            for (std::size_t i = 0; i < pixels; ++i, src += 3) {
                const int sum = fx::kLumaR * src[0] + fx::kLumaG * src[1] + fx::kLumaB * src[2];
                out.grey[i] = static_cast<std::uint8_t>((sum + (1 << (fx::kLumaShift - 1))) >>
                                                        fx::kLumaShift);
            }
            grey = out.grey.data();
        }
        const int stride = width + 2 * census::kRadius;
        out.padded.assign(static_cast<std::size_t>(stride) * (height + 2 * census::kRadius), 255);
        for (int y = 0; y < height; ++y) {
            std::copy_n(grey + static_cast<std::size_t>(y) * width, width,
                        out.padded.data() + static_cast<std::size_t>(y + census::kRadius) * stride +
                            census::kRadius);
        }
        out.codes.resize(pixels);
        for (int y = 0; y < height; ++y) {
            census_codes_row(out.padded.data() + static_cast<std::size_t>(y) * stride, stride,
                             width, out.codes.data() + static_cast<std::size_t>(y) * width);
        }
    } else if (kind == catalogue::Cost::ad) {
        out.channel_count = image.channels;
        for (int c = 0; c < image.channels; ++c) {
            auto& plane = out.channels[static_cast<std::size_t>(c)];
            plane.resize(pixels);
            for (std::size_t i = 0; i < pixels; ++i) {
                plane[i] = image.pixels[i * static_cast<std::size_t>(image.channels) +
                                        static_cast<std::size_t>(c)];
            }
        }
    } else {
        out.planes = cost.prepare(image);
    }
}

}  // namespace

struct Engine::State {
    std::vector<std::int32_t> kernel;     // full kernel, as gaussian_kernel gives it
    std::vector<std::int32_t> half_taps;  // taps[radius + i], i = 0 .. radius
    std::unique_ptr<CostFunction> cost;
    std::vector<Workspace> workspaces;  // one per thread
    std::vector<CostValue> zeros;       // a row outside the image
    std::vector<CostValue> unset;       // a label outside the range
    catalogue::Cost kind = catalogue::Cost::ad;
    std::array<Prepared, 2> prepared;  // left, right
    int width = 0;
};

void validate_threads(int threads) {
    if (threads < 1 || threads > kMaxThreads) {
        throw std::invalid_argument("threads must be in [1, " + std::to_string(kMaxThreads) +
                                    "], got " + std::to_string(threads));
    }
}

int thread_count(int requested) {
    if (requested == 0) {
        return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, kMaxThreads);
    }
    validate_threads(requested);
    return requested;
}

Engine::Engine(const MatchParams& params, int threads)
    : params_(params), threads_(threads), state_(std::make_unique<State>()) {
    validate_threads(threads);
    validate_params(params);
    state_->kernel = gaussian_kernel(params.window, params.sigma);
    const int radius = params.window / 2;
    for (int i = 0; i <= radius; ++i) {
        const std::int32_t tap = state_->kernel[static_cast<std::size_t>(radius + i)];
        if (tap != state_->kernel[static_cast<std::size_t>(radius - i)]) {
            throw std::logic_error("fast engine: the Gaussian kernel is not symmetric");
        }
        state_->half_taps.push_back(tap);
    }
    state_->cost = make_cost(params.cost);
    state_->kind = catalogue::cost(params.cost).id;
    state_->workspaces.resize(static_cast<std::size_t>(threads));
}

Engine::~Engine() = default;

void Engine::validate(int width, int height) const {
    validate_size(params_, width, height);
}

namespace {

struct Frame {
    const MatchParams& params;
    const CostFunction& cost;
    catalogue::Cost kind;
    const Prepared& left;
    const Prepared& right;
    int width;
    int height;
    const std::vector<std::int32_t>& half_taps;
    const CostValue* zeros;
    const CostValue* unset;
    InvalidBorder border;
    ValidatedDisparity& out;
};

// Cost row of label d (disparity `d`) into `row`: the model's cost_plane for one row.
void cost_row(const Frame& f, int y, int d, CostValue* row) {
    const int width = f.width;
    constexpr auto outside = static_cast<CostValue>(fx::kCostOutside);
    const int first = std::clamp(d, 0, width);
    const int last = std::clamp(width + d, 0, width);
    if (first >= last) {
        std::fill_n(row, width, outside);
        return;
    }
    std::fill(row, row + first, outside);
    const int n = last - first;
    const std::size_t at = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(first);
    const std::size_t at_right = at - static_cast<std::size_t>(d);
    if (f.kind == catalogue::Cost::census) {
        census_row(f.left.codes.data() + at, f.right.codes.data() + at_right, n, row + first);
    } else if (f.kind == catalogue::Cost::ad && f.left.channel_count == 3) {
        ad_row3(f.left.channels[0].data() + at, f.left.channels[1].data() + at,
                f.left.channels[2].data() + at, f.right.channels[0].data() + at_right,
                f.right.channels[1].data() + at_right, f.right.channels[2].data() + at_right, n,
                row + first);
    } else if (f.kind == catalogue::Cost::ad) {
        ad_row1(f.left.channels[0].data() + at, f.right.channels[0].data() + at_right, n,
                row + first);
    } else {
        f.cost.row(f.left.planes, f.right.planes, y, y, first, n, d, row + first);
    }
    std::fill(row + last, row + width, outside);
}

void run_tile(const Frame& f, Workspace& ws, int y0, int y1) {
    const MatchParams& p = f.params;
    const int width = f.width;
    const int height = f.height;
    const auto w = static_cast<std::size_t>(width);
    const int radius = p.window / 2;
    const int ca = p.use_ca ? 1 : 0;
    // Row ranges (clipped to the image) and the first row of each buffer (unclipped).
    const int a0 = std::max(0, y0 - ca);  // CA rule 1 rows
    const int a1 = std::min(height, y1 + ca);
    const int g0 = std::max(0, a0 - ca);  // aggregate rows
    const int g1 = std::min(height, a1 + ca);
    const int c0 = std::max(0, g0 - radius);  // cost rows
    const int c1 = std::min(height, g1 + radius);
    const int cost_base = y0 - radius - 2 * ca;
    const int agg_base = y0 - 2 * ca;
    const int ca1_base = y0 - ca;
    const auto row_of = [w](std::vector<CostValue>& plane, int y, int base) {
        return plane.data() + static_cast<std::size_t>(y - base) * w;
    };

    const std::size_t size = static_cast<std::size_t>(y1 - y0) * w;
    for (auto& values : ws.best) {
        std::fill_n(values.begin(), size, kUnset);
    }
    std::fill_n(ws.best[1].begin(), size, CostValue{0});  // the label
    std::fill_n(ws.right_cost.begin(), size, kUnset);
    std::fill_n(ws.right_label.begin(), size, std::uint16_t{0});
    CostValue* const best_cost = ws.best[0].data();
    CostValue* const best_label = ws.best[1].data();
    CostValue* const left_min = ws.best[2].data();
    CostValue* const right_min = ws.best[3].data();
    CostValue* const before = ws.best[4].data();
    CostValue* const after = ws.best[5].data();

    std::int32_t* const vertical = ws.vertical.data() + radius;
    const std::int32_t* const taps = f.half_taps.data();
    // Cost and aggregate of label k into ring slot k % 3.
    const auto aggregate = [&](int k) {
        const int d = p.min_disp + k;
        for (int y = c0; y < c1; ++y) {
            cost_row(f, y, d, row_of(ws.cost, y, cost_base));
        }
        std::vector<CostValue>& plane = ws.agg[static_cast<std::size_t>(k % 3)];
        if (radius >= 1 && radius <= kFusedRadii) {
            const auto [vertical_pass, horizontal_pass] =
                kFusedPasses[static_cast<std::size_t>(radius - 1)];
            std::array<const CostValue*, 2 * kFusedRadii + 1> rows{};
            for (int y = g0; y < g1; ++y) {
                for (int j = -radius; j <= radius; ++j) {
                    rows[static_cast<std::size_t>(j + radius)] =
                        y + j >= 0 && y + j < height ? row_of(ws.cost, y + j, cost_base) : f.zeros;
                }
                vertical_pass(vertical, rows.data(), taps, width);
                horizontal_pass(vertical, taps, row_of(plane, y, agg_base), width);
            }
            return;
        }
        for (int y = g0; y < g1; ++y) {
            vertical_init(vertical, row_of(ws.cost, y, cost_base), taps[0], width);
            for (int j = 1; j <= radius; ++j) {
                const bool has_up = y - j >= 0;
                const bool has_down = y + j < height;
                if (has_up && has_down) {
                    vertical_pair(vertical, row_of(ws.cost, y - j, cost_base),
                                  row_of(ws.cost, y + j, cost_base), taps[j], width);
                } else if (has_up) {
                    vertical_one(vertical, row_of(ws.cost, y - j, cost_base), taps[j], width);
                } else if (has_down) {
                    vertical_one(vertical, row_of(ws.cost, y + j, cost_base), taps[j], width);
                }
            }
            horizontal(vertical, taps, radius, ws.sum.data(), row_of(plane, y, agg_base), width);
        }
    };

    if (ca != 0) {
        aggregate(0);
    }
    for (int k = 0; k < p.ndisp; ++k) {
        const CostValue* final_rows = nullptr;  // rows y0 .. y1 - 1 of label k
        if (ca == 0) {
            aggregate(k);
            final_rows = row_of(ws.agg[static_cast<std::size_t>(k % 3)], y0, agg_base);
        } else {
            if (k + 1 < p.ndisp) {
                aggregate(k + 1);
            }
            std::vector<CostValue>& centre = ws.agg[static_cast<std::size_t>(k % 3)];
            std::vector<CostValue>* const before =
                k > 0 ? &ws.agg[static_cast<std::size_t>((k + 2) % 3)] : nullptr;
            std::vector<CostValue>* const after =
                k + 1 < p.ndisp ? &ws.agg[static_cast<std::size_t>((k + 1) % 3)] : nullptr;
            for (int y = a0; y < a1; ++y) {
                ca1_row(y > 0 ? row_of(centre, y - 1, agg_base) : f.zeros,
                        row_of(centre, y, agg_base),
                        y + 1 < height ? row_of(centre, y + 1, agg_base) : f.zeros,
                        before != nullptr ? row_of(*before, y, agg_base) : f.unset,
                        after != nullptr ? row_of(*after, y, agg_base) : f.unset,
                        ws.columns.data() + 1, row_of(ws.ca1, y, ca1_base), width);
            }
            // A border row passes rule 2 unchanged (at most 5 neighbours inside).
            static_assert(fx::kRule2MinCount > 5);
            for (int y = y0; y < y1; ++y) {
                CostValue* dst = row_of(ws.ca2, y, y0);
                if (y == 0 || y + 1 == height) {
                    std::copy_n(row_of(ws.ca1, y, ca1_base), w, dst);
                } else {
                    ca2_row(row_of(ws.ca1, y - 1, ca1_base), row_of(ws.ca1, y, ca1_base),
                            row_of(ws.ca1, y + 1, ca1_base), dst, width);
                }
            }
            final_rows = ws.ca2.data();
        }
        update_best(size, k, final_rows, best_cost, best_label, left_min, right_min, before, after,
                    ws.best[6].data(), ws.best[7].data());
        if (p.validation.left_right) {
            const int d = p.min_disp + k;
            const int x_begin = std::max(0, d);
            const int x_end = std::min(width, width + d);
            if (x_end > x_begin) {
                for (int y = y0; y < y1; ++y) {
                    const std::size_t row = static_cast<std::size_t>(y - y0) * w;
                    const std::size_t right_begin = row + static_cast<std::size_t>(x_begin - d);
                    update_right(
                        static_cast<std::size_t>(x_end - x_begin), static_cast<std::uint16_t>(k),
                        final_rows + row + static_cast<std::size_t>(x_begin),
                        ws.right_cost.data() + right_begin, ws.right_label.data() + right_begin);
                }
            }
        }
    }

    // ValidatingSelector::result for the tile's rows.
    const ValidationParams& v = p.validation;
    ValidatedDisparity& out = f.out;
    for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t q =
                static_cast<std::size_t>(y - y0) * w + static_cast<std::size_t>(x);
            const std::size_t o = out.index(x, y);
            const int winner = best_label[q];
            const int c1 = best_cost[q];
            const int second = std::min(left_min[q], right_min[q]);
            const int c2 = second == kUnset ? fx::kNoSecondCost : second;
            out.certainty[o] = static_cast<std::uint8_t>(validation::certainty(c1, c2));
            const int d = p.min_disp + winner;
            std::uint8_t reason = fx::kReasonValid;
            if (!f.border.valid(x, y, d, width, height)) {
                reason = fx::kReasonBorder;
            } else if (v.uniqueness && !validation::unique(c1, c2, v.uniqueness_ratio)) {
                reason = fx::kReasonUniqueness;
            } else if (v.left_right &&
                       std::abs(winner - ws.right_label[static_cast<std::size_t>(y - y0) * w +
                                                        static_cast<std::size_t>(x - d)]) >
                           v.lr_tolerance) {
                reason = fx::kReasonLeftRight;
            }
            out.reason[o] = reason;
            out.fixed[o] = 0;
            if (reason != fx::kReasonValid) {
                continue;
            }
            int offset = 0;
            if (v.subpixel && winner > 0 && winner < p.ndisp - 1 && before[q] != kUnset &&
                after[q] != kUnset) {
                offset = validation::subpixel_offset(before[q], c1, after[q]);
            }
            out.fixed[o] = static_cast<std::int16_t>(d * fx::kSubpixelScale + offset);
        }
    }
}

// Runs job(t) for t = 0 .. threads - 1, job 0 on the calling thread; the first exception a job
// throws is rethrown here once every job has finished.
template <typename Job>
void on_threads(int threads, const Job& job) {
    std::mutex mutex;
    std::exception_ptr failure;
    const auto guarded = [&](int t) {
        try {
            job(t);
        } catch (...) {
            const std::lock_guard lock(mutex);
            if (!failure) {
                failure = std::current_exception();
            }
        }
    };
    {
        std::vector<std::jthread> workers;
        workers.reserve(static_cast<std::size_t>(threads - 1));
        for (int t = 1; t < threads; ++t) {
            workers.emplace_back(guarded, t);
        }
        guarded(0);
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
}

}  // namespace

void Engine::match(const Image& left, const Image& right, ValidatedDisparity& out) {
    check_pair(left, right);
    validate_size(params_, left.width, left.height);
    const int width = left.width;
    const int height = left.height;
    State& s = *state_;
    const int radius = params_.window / 2;
    const int ca = params_.use_ca ? 1 : 0;
    if (s.width != width) {
        s.zeros.assign(static_cast<std::size_t>(width), 0);
        s.unset.assign(static_cast<std::size_t>(width), kUnset);
        s.width = width;
    }
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    if (out.width != width || out.height != height || out.fixed.size() != pixels) {
        out = ValidatedDisparity(width, height);
    }

    {
        const Image* images[2] = {&left, &right};
        const int workers = std::min(threads_, 2);
        on_threads(workers, [&](int t) {
            for (int i = t; i < 2; i += workers) {
                prepare(s.kind, *s.cost, *images[i], s.prepared[static_cast<std::size_t>(i)]);
            }
        });
    }
    const Frame frame{
        params_, *s.cost,     s.kind,         s.prepared[0],  s.prepared[1],           width,
        height,  s.half_taps, s.zeros.data(), s.unset.data(), invalid_border(params_), out};
    // A multiple of the thread count of tiles of at most kTileRows rows, as equal as the rows
    // allow: the threads finish together (15 tiles of 32 rows on two threads left one idle for
    // the last tile of a VGA frame).
    const int workers = std::max(1, std::min(threads_, (height + kTileRows - 1) / kTileRows));
    const int rounds = (height + workers * kTileRows - 1) / (workers * kTileRows);
    const int tile_rows = (height + workers * rounds - 1) / (workers * rounds);
    const int tiles = (height + tile_rows - 1) / tile_rows;
    std::atomic<int> next{0};
    on_threads(std::min(threads_, tiles), [&](int t) {
        Workspace& ws = s.workspaces[static_cast<std::size_t>(t)];
        if (ws.width != width) {  // only the workers a frame uses get buffers
            ws.resize(width, radius, ca);
        }
        for (int tile = next.fetch_add(1); tile < tiles; tile = next.fetch_add(1)) {
            const int y0 = tile * tile_rows;
            run_tile(frame, ws, y0, std::min(height, y0 + tile_rows));
        }
    });
}

ValidatedDisparity Engine::match(const Image& left, const Image& right) {
    ValidatedDisparity out;
    match(left, right, out);
    return out;
}

ValidatedDisparity match_validated(const Image& left, const Image& right, const MatchParams& params,
                                   int threads) {
    Engine engine(params, threads);
    return engine.match(left, right);
}

}  // namespace stereo::fast

#include "stereo_robot/decision.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace stereo::robot {
namespace {

constexpr int kLeft = static_cast<int>(Side::left);
constexpr int kCentre = static_cast<int>(Side::centre);
constexpr int kRight = static_cast<int>(Side::right);

// Centroid of `membership` sampled on lo, lo + step, ..., hi (the last point is hi itself);
// the midpoint when the set is empty (all memberships zero).
template <typename Membership>
double centroid(double lo, double hi, double step, Membership membership) {
    const long long steps = std::llround((hi - lo) / step);
    double weighted = 0.0;
    double total = 0.0;
    for (long long i = 0; i <= steps; ++i) {
        const double x = i == steps ? hi : lo + static_cast<double>(i) * step;
        const double mu = membership(x);
        weighted += mu * x;
        total += mu;
    }
    return total > 0.0 ? weighted / total : 0.5 * (lo + hi);
}

// The centroid of one turn's whole output MF (-18.70 / +18.70 degrees with the defaults): the
// angle the FIS gives when only that turn rule fires.
double turn_angle(const FisParams& params, Direction side) {
    const Gaussian& mf = side == Direction::left ? params.left : params.right;
    return centroid(params.angle_min, params.angle_max, params.angle_step,
                    [&](double a) { return mf(a); });
}

void check_params(const FisParams& params) {
    if (!(params.angle_min < params.angle_max) || !(params.angle_step > 0.0) ||
        !(params.backwards_step > 0.0)) {
        throw std::invalid_argument("FIS output ranges and grid steps must be positive");
    }
    if (!(params.forward_band >= 0.0 && params.forward_band <= 90.0)) {  // NaN fails too
        throw std::invalid_argument("--forward-band must be in [0, 90] degrees");
    }
    check_fraction(params.rate, "rate");
}

}  // namespace

std::optional<Direction> freer_side(const std::array<WindowStats, 3>& stats, double rate) {
    const double left = stats[kLeft].free_disparity(rate);
    const double right = stats[kRight].free_disparity(rate);
    if (left == right) {
        return std::nullopt;
    }
    return left < right ? Direction::left : Direction::right;
}

std::string to_string(Direction direction) {
    // In the order of the enumerators.
    constexpr std::array<const char*, 4> kNames = {"forward", "left", "right", "backwards"};
    const auto index = static_cast<std::size_t>(direction);
    return index < kNames.size() ? kNames[index] : kNames[0];
}

ThresholdDecision decide_threshold(const DisparityMap& map, double threshold, int ndisp,
                                   const ThresholdParams& params, const GroundModel* ground) {
    if (!(params.rate >= 0.0 && params.rate <= 1.0)) {
        throw std::invalid_argument("rate r must be in [0, 1], got " + std::to_string(params.rate));
    }
    ThresholdDecision decision;
    decision.stats = all_window_stats(map, threshold, params.border, ground);
    for (int i = 0; i < 3; ++i) {
        decision.mean[i] = decision.stats[i].mean_disparity(ndisp);
    }
    if (decision.stats[kCentre].occupancy() < params.rate) {
        decision.direction = Direction::forward;
        return decision;
    }
    const double av_left = decision.mean[kLeft];
    const double av_right = decision.mean[kRight];
    // The thesis' rule: the side with the smaller mean disparity (ties left) ...
    decision.direction = av_left <= av_right ? Direction::left : Direction::right;
    // ... unless that side's free distance is the smaller one (issue 50: never turn towards it).
    if (const auto safer = freer_side(decision.stats, params.rate);
        safer && *safer != decision.direction) {
        decision.direction = *safer;
        decision.safety_override = true;
    }
    const double chosen = decision.direction == Direction::left ? av_left : av_right;
    const double other = decision.direction == Direction::left ? av_right : av_left;
    decision.certainty = other > 0.0 ? std::max(0.0, (other - chosen) / other) : 0.0;
    return decision;
}

double Gaussian::operator()(double x) const {
    const double z = (x - centre) / sigma;
    return std::exp(-0.5 * z * z);
}

void check_fraction(double value, const std::string& name) {
    if (!(value >= 0.0 && value <= 1.0)) {  // also rejects NaN
        throw std::invalid_argument(name + " must be a fraction in [0, 1], got " +
                                    std::to_string(value));
    }
}

FisResult evaluate_fis(double left, double centre, double right, const FisParams& params) {
    check_fraction(left, "left");
    check_fraction(centre, "centre");
    check_fraction(right, "right");
    check_params(params);

    // Rule strengths (min for AND).
    const double w_forward = params.free(centre);
    const double w_left = std::min(params.occupied(centre), params.free(left));
    const double w_right = std::min(params.occupied(centre), params.free(right));
    const double w_back =
        std::min({params.occupied(left), params.occupied(centre), params.occupied(right)});

    FisResult result;
    result.firing = {w_forward, w_left, w_right, w_back};
    // Min implication, max aggregation.
    result.angle_deg =
        centroid(params.angle_min, params.angle_max, params.angle_step, [&](double a) {
            return std::max({std::min(w_forward, params.forward(a)),
                             std::min(w_left, params.left(a)), std::min(w_right, params.right(a))});
        });
    result.backwards = centroid(0.0, 1.0, params.backwards_step, [&](double b) {
        return std::min(w_back, params.backwards_yes(b));
    });

    result.mamdani_angle_deg = result.angle_deg;

    // A turn rule "fires" when its clipped output set is not flat across the opposite third of
    // the angle range (the other side's window): strength >= the turn MF at that third's inner
    // edge (left MF at +10 degrees, right MF at -10: exp(-29^2 / (2 5.5^2)) = 9.2e-7). Weaker
    // rules carry no direction; their centroid is noise around 0.
    const double third = (params.angle_max - params.angle_min) / 3.0;
    const bool left_fires = w_left >= params.left(params.angle_max - third);
    const bool right_fires = w_right >= params.right(params.angle_min + third);
    if (result.backwards > params.backwards_threshold) {
        result.decision = Direction::backwards;
    } else if (result.angle_deg < -params.forward_band && left_fires) {
        result.decision = Direction::left;
    } else if (result.angle_deg > params.forward_band && right_fires) {
        result.decision = Direction::right;
    } else if (centre < params.rate) {
        result.decision = Direction::forward;
    } else {
        // Rule 5: the centre is blocked but no turn rule is decisive (the dead zone where every
        // rule fires at ~1e-19, or opposing turns cancelling).
        result.default_rule = true;
        const bool go_left = left <= right;
        const double freer = go_left ? left : right;
        if (freer >= params.rate) {
            result.decision = Direction::backwards;
        } else {
            result.decision = go_left ? Direction::left : Direction::right;
            result.angle_deg = turn_angle(params, result.decision);
        }
    }
    return result;
}

FuzzyDecision decide_fuzzy(const DisparityMap& map, double threshold, const FisParams& params,
                           int border, const GroundModel* ground) {
    FuzzyDecision decision;
    decision.stats = all_window_stats(map, threshold, border, ground);
    decision.fis =
        evaluate_fis(decision.stats[kLeft].occupancy(), decision.stats[kCentre].occupancy(),
                     decision.stats[kRight].occupancy(), params);
    FisResult& fis = decision.fis;
    const bool turning = fis.decision == Direction::left || fis.decision == Direction::right;
    // A turn towards the side with the smaller free distance (issue 50) goes the other way, or
    // backs off when that side is blocked too.
    if (const auto safer = freer_side(decision.stats, params.rate);
        turning && safer && *safer != fis.decision) {
        decision.safety_override = true;
        const WindowStats& side = decision.stats[*safer == Direction::left ? kLeft : kRight];
        if (side.occupancy() >= params.rate) {
            fis.decision = Direction::backwards;
        } else {
            fis.decision = *safer;
            fis.angle_deg = turn_angle(params, *safer);
        }
    }
    return decision;
}

}  // namespace stereo::robot

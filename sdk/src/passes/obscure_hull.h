// LSAO's obscure hull (Timonen, "Line-Sweep Ambient Obscurance", sec. 4, Algorithm 1) on the CPU: the
// same arithmetic as sdk/glsl/line_sweep.comp, for the tests and as the readable statement of the
// algorithm. Points are 2D coordinates in the plane of a sweep line (the slice through the eye), the zenith
// u points from the receiver towards the eye, and occlusion() uses a fixed tangent (strategy 3).
#ifndef OBSCURA_OBSCURE_HULL_H
#define OBSCURA_OBSCURE_HULL_H

#include <cmath>
#include <vector>

#include "falloff.h"

namespace obscura {

struct SlicePoint {
    double x = 0.0, y = 0.0;
};

struct ObscuranceModel {
    double sin_t = -0.85;      // the fixed tangent
    double decay_rate = 1.0;   // r of the falloff
    double falloff_c = 0.0;    // C: 0 gives r / (r + d^2) (LSAO eq. 2), > 0 gives rho0 (LSAO eq. 3)

    double falloff(double distance_sq) const { return rho0(decay_rate, falloff_c, distance_sq); }
    // Algorithm 1's occlusion(): sin t + max(0, sin h - sin t) rho(|h|), h from the receiver to the occluder.
    double occlusion(SlicePoint h, SlicePoint u) const {
        const double length_sq = h.x * h.x + h.y * h.y;
        if (length_sq <= 0.0) return sin_t;
        const double sin_h = (h.x * u.x + h.y * u.y) / std::sqrt(length_sq);
        const double above = sin_h - sin_t;
        return sin_t + (above > 0.0 ? above : 0.0) * falloff(length_sq);
    }
    double sin_h(SlicePoint h, SlicePoint u) const {
        const double length = std::sqrt(h.x * h.x + h.y * h.y);
        return length > 0.0 ? (h.x * u.x + h.y * u.y) / length : -1.0;
    }
};

// The stack of Algorithm 1 with a bounded capacity: when full, the oldest point (the farthest behind the
// sweep, weighted least by the falloff) is dropped.
class ObscureHull {
public:
    ObscureHull(const ObscuranceModel& model, int capacity) : model_(model), capacity_(capacity) {}

    // Pops the points that cast less obscurance on `p` than the one below them and are below its horizon,
    // returns the occlusion of the top (the largest occluder; `empty` when there is none), then pushes p.
    double step(SlicePoint p, SlicePoint u, bool* empty) {
        while (points_.size() >= 2) {
            const SlicePoint& a = points_[points_.size() - 1];
            const SlicePoint& b = points_[points_.size() - 2];
            const SlicePoint h1{a.x - p.x, a.y - p.y}, h2{b.x - p.x, b.y - p.y};
            if (!(model_.occlusion(h1, u) < model_.occlusion(h2, u) && model_.sin_h(h1, u) < model_.sin_h(h2, u))) break;
            points_.pop_back();
            ++pops_;
        }
        *empty = points_.empty();
        double value = model_.sin_t;
        if (!points_.empty()) {
            const SlicePoint& a = points_.back();
            value = model_.occlusion(SlicePoint{a.x - p.x, a.y - p.y}, u);
        }
        if (int(points_.size()) == capacity_) {
            points_.erase(points_.begin());
            ++dropped_;
        }
        points_.push_back(p);
        return value;
    }
    int size() const { return int(points_.size()); }
    long pops() const { return pops_; }
    long dropped() const { return dropped_; }

private:
    ObscuranceModel model_;
    int capacity_;
    std::vector<SlicePoint> points_;
    long pops_ = 0;
    long dropped_ = 0;
};

// The exact answer the hull approximates: the largest occlusion any earlier point casts on `p`.
inline double largest_occlusion(const ObscuranceModel& model, const std::vector<SlicePoint>& earlier, SlicePoint p,
                                SlicePoint u, bool* empty) {
    *empty = earlier.empty();
    double best = model.sin_t;
    for (const SlicePoint& q : earlier) {
        const double o = model.occlusion(SlicePoint{q.x - p.x, q.y - p.y}, u);
        if (o > best) best = o;
    }
    return best;
}

}  // namespace obscura

#endif  // OBSCURA_OBSCURE_HULL_H

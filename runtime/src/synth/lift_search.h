// Private: the one-dimensional search shared by point and curve lifts (s5.1 with the finest levels
// free). A lift is added to a constraint's target on the constrained levels; the residual is how far
// the finished height lands from the asked one.
#pragma once

#include <algorithm>

namespace terrasynth::synth {

// The finished height moves with the lift between steps where a discrete candidate choice flips,
// and other lifts shift it a little too (no coherence: s5.3, fig. 7b). The search takes secant
// steps until the residual changes sign, then narrows the bracket by false position (bisection when
// that stalls against one end).
struct LiftSearch {
    struct Sample {
        float lift = 0.0f, residual = 0.0f;
        int round = -1;
    };
    Sample last, previous, opposite;  // opposite: the latest sample on the other side of the target
    // A bracket older than this many rounds is dropped: other lifts have moved the site since.
    static constexpr int kBracketRounds = 3;

    void record(float lift, float residual, int round) {
        const Sample now{lift, residual, round};
        if (last.round >= 0 && (residual < 0.0f) != (last.residual < 0.0f)) opposite = last;
        previous = last;
        last = now;
    }
    float next() const {
        if (opposite.round >= 0 && last.round - opposite.round <= kBracketRounds) {
            const float lo = std::min(last.lift, opposite.lift), hi = std::max(last.lift, opposite.lift);
            float lift = last.lift - last.residual * (opposite.lift - last.lift) / (opposite.residual - last.residual);
            if (!(lift > lo + 0.1f * (hi - lo) && lift < hi - 0.1f * (hi - lo))) lift = 0.5f * (lo + hi);
            return lift;
        }
        float slope = 1.0f;  // a lift of the target moves the site about as much
        if (previous.round >= 0 && previous.lift != last.lift) {
            const float measured = (last.residual - previous.residual) / (last.lift - previous.lift);
            if (measured > 0.3f && measured < 3.0f) slope = measured;
        }
        return last.lift - last.residual / slope;
    }
};

}  // namespace terrasynth::synth

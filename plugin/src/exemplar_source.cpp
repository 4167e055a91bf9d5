// An exemplar DEM as an unbounded, seamless, multi-level height source (mirror tiling plus box
// averaging through a summed-area table, so every level-k sample costs O(1)).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth_plugin/height_source.h"

namespace terrasynth::plugin {
namespace {

// Summed-area table of one mirror period (2w x 2h) of the exemplar, in double so that block sums
// are exact enough and, above all, the same whichever window asks.
class MirroredField {
public:
    explicit MirroredField(const Heightfield& f)
        : pw_(2 * f.width), ph_(2 * f.height), mpp_(f.meters_per_pixel_x),
          sat_(static_cast<size_t>(pw_ + 1) * (ph_ + 1), 0.0) {
        for (int y = 0; y < ph_; ++y) {
            double row = 0.0;
            const int sy = y < f.height ? y : ph_ - 1 - y;
            for (int x = 0; x < pw_; ++x) {
                const int sx = x < f.width ? x : pw_ - 1 - x;
                row += f.at(sx, sy);
                sat(x + 1, y + 1) = sat(x + 1, y) + row;
            }
        }
    }

    int maxLevel() const {
        int k = 0;
        while ((2 << k) <= std::min(pw_, ph_)) ++k;
        return k;
    }
    double spacing() const { return mpp_; }

    // Mean of the level-0 block of side n = 2^level whose corner is (x0, y0).
    float blockMean(int64_t x0, int64_t y0, int n) const {
        double sum = 0.0;
        forSpans(x0, n, pw_, [&](int ax, int bx) {
            forSpans(y0, n, ph_, [&](int ay, int by) { sum += rect(ax, ay, bx, by); });
        });
        return static_cast<float>(sum / (static_cast<double>(n) * n));
    }

private:
    double& sat(int x, int y) { return sat_[static_cast<size_t>(y) * (pw_ + 1) + x]; }
    double sat(int x, int y) const { return sat_[static_cast<size_t>(y) * (pw_ + 1) + x]; }
    double rect(int ax, int ay, int bx, int by) const {
        return sat(bx, by) - sat(ax, by) - sat(bx, ay) + sat(ax, ay);
    }
    // Splits [start, start+n) (n <= period) into at most two spans inside one period.
    template <class F>
    static void forSpans(int64_t start, int n, int period, F&& f) {
        int a = static_cast<int>(((start % period) + period) % period);
        if (a + n <= period) {
            f(a, a + n);
        } else {
            f(a, period);
            f(0, a + n - period);
        }
    }

    int pw_, ph_;
    double mpp_;
    std::vector<double> sat_;
};

}  // namespace

HeightSource mirroredExemplarSource(const Heightfield& exemplar) {
    auto field = std::make_shared<const MirroredField>(exemplar);
    return [field](const PixelWindow& w, int level) -> Result<Heightfield> {
        if (level < 0 || level > field->maxLevel())
            return Status::error("exemplar source: level " + std::to_string(level) + " outside 0.." +
                                 std::to_string(field->maxLevel()));
        if (w.width < 1 || w.height < 1) return Status::error("exemplar source: empty window");
        const int n = 1 << level;
        Heightfield out(w.width, w.height, std::ldexp(field->spacing(), level));
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x)
                out.at(x, y) = field->blockMean((w.x + x) * n, (w.y + y) * n, n);
        return out;
    };
}

HeightSource editedSource(HeightSource base,
                          std::function<void(const PixelWindow&, int level, Heightfield&)> edit) {
    return [base = std::move(base), edit = std::move(edit)](const PixelWindow& w, int level) -> Result<Heightfield> {
        auto r = base(w, level);
        if (r) edit(w, level, *r);
        return r;
    };
}

}  // namespace terrasynth::plugin

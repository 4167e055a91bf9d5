// terrasynth/synthesizer.h: parallel pixel-based terrain synthesis (Gain et al. 2015, section 4).
//
// The terrain is a pure function of (database, parameters, seed, pixel): synthesizing any window
// gives bit-identical heights to synthesizing a larger window that contains it, on the same device
// and backend. Windows are addressed in the global pixel grid of the output level, so the world is
// unbounded in every direction and adjacent tiles meet without stitching.
//
// Threading: a Synthesizer owns an OpenCL queue and scratch buffers and is not thread-safe; create
// one per worker thread. Several synthesizers may share one database.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "terrasynth/constraints.h"
#include "terrasynth/database.h"
#include "terrasynth/grid.h"
#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// Coherence (paper s5.3): the results of a previous synthesis, every level and every pass, kept so
// the next synthesis can prefer them. Recorded when SynthesisParams::record_history is set.
// Memory: 8 bytes per pixel per pass per level (about 21 bytes per output pixel for 2 passes; one
// more pass each with offset relaxation and with drainage).
struct SynthesisHistory {
    struct Pass {
        std::vector<uint32_t> index;  // chosen atlas pixel per region pixel
        std::vector<float> v;         // height offset V per region pixel, metres
    };
    struct Level {
        int x = 0, y = 0, width = 0, height = 0;  // region of the global grid at this level
        // One per correction pass; with offset relaxation, one more: the relaxed state; with
        // drainage, one more: the state after breaching. Frozen pixels take these so they stay
        // bit-identical.
        std::vector<Pass> passes;
    };
    std::vector<Level> levels;  // indexed by level; empty levels were not synthesized
    size_t memoryBytes() const;
};

// Per-pixel coherence weight W^0 over a rectangle of the level-0 grid (s5.3): Free (W = 1) inside
// the area of influence of the constraint being manipulated, Coherent (0.25) elsewhere, Frozen (0)
// under the freeze brush. Coarser levels take Frozen if any pixel of the 2x2 block is frozen, else
// the most frequent weight.
enum class Coherence : uint8_t { Frozen = 0, Coherent = 1, Free = 2 };
struct CoherenceMap {
    int64_t x = 0, y = 0;
    int width = 0, height = 0;
    std::vector<Coherence> weights;           // width*height
    Coherence outside = Coherence::Coherent;  // weight of pixels outside the rectangle
};
constexpr float kCoherentWeight = 0.25f;

// Automatic coarsest level (SynthesisParams::coarsest_level = -1): exemplars must still be this many
// pixels on their shorter side there.
constexpr int kMinCoarsestSide = 40;
// Level M starts from irregular patches (cells of about this many pixels across, one random
// exemplar position each, wrapped around the exemplar's interior) instead of independent random
// pixels.
constexpr int kInitialPatchSize = 24;
// Median offset (beyond the paper): at the two finest levels the height offset a candidate brings
// (eq. 7's h) is the median of its four diagonal neighbours' gaps, not their mean, so a pixel whose
// neighbours come from two patches follows the three that agree instead of settling between them.
// Unjittered finest levels: levels 0 and 1 are upsampled without eq. 1's jitter (SynthesisParams::
// jitter applies from level 2 up), so the runs of exemplar coordinates the coarser levels settled
// reach the output as runs; the correction passes still change what does not fit.
// Level ground (beyond the paper): a pixel whose source is level (its 8 exemplar neighbours within
// tan 0.5 degrees times the database's spacing of it: lakes, sea, flat floors) goes no higher than
// its lowest neighbour copied from the same level ground, so copied water settles level instead of
// being tilted by the offsets V. Nor does an unconstrained pixel go below the lowest height of the
// level's exemplar pixels (their sea or lowest lake), except in channels the drainage carved at a
// coarser level: copied water below it is level at it. Always on; local rules, so windows stay exact.

// Drainage (beyond the paper, whose s6 notes that pixel-based synthesis drains
// unrealistically). Breach: after the correction passes of every level, each closed pit looks for the
// cheapest path to a lower pixel within breachRadius(level) pixels and the path is carved to a
// straight profile descending most of the way to that pixel (least-cost breaching, Lindsay 2016;
// cells already below it stay), by lowering V; the carved
// heights become a ceiling the next level's correction may not exceed (the channel is re-detailed
// from the exemplars below it). At levels 2-4 a pit with no lower pixel within the radius (a
// regional low) is carved to the cheapest pixel on the edge of its search window instead, which
// ends below it, unless it was copied from an exemplar with real basins (at least 4% of its own
// pixels in closed depressions: lava plains, salars, karst, dunes), whose regional lows are kept.
// Bounded reach: a pixel depends on heights within 2 * breachRadius(level) + 1
// pixels, which the window plan adds to that level's margin, so windows stay bit-identical to
// larger windows. Frozen pixels and pixels under point or curve constraints are never carved (a
// path may end at a lower one), nor is the level ground the pit lies in (a lake stays level and the
// path cuts its rim); a diagonal step also carves one cell beside it, so channels are 4-connected.
// Breach is the default: without it, one-exemplar syntheses of
// fluvial terrain leave 8-27 percentage points more of their area in closed depressions than their
// exemplars (docs/realism.md). Cost: every level's region grows by the reach, and the breach's
// search runs on the OpenCL device (on a CPU device, the same search on the host; both backends
// give the same bits): docs/benchmarks.md, "Drainage cost", has the figures on CPUs and on a GPU.
// Off: no drainage step; everything else (where synthesis starts, kInitialPatchSize above) is the
// same for both.
enum class Drainage : uint8_t { Off = 0, Breach = 1 };
// Search radius of the breach at `level`, in pixels of that level (docs/realism.md, "Drainage").
int breachRadius(int level);

struct SynthesisParams {
    uint32_t seed = 1;
    float jitter = 0.4f;        // r of eq. 1, in pixels of each level from 2 up (levels 0-1: none); 0..1
    int correction_passes = 2;  // passes per level, each of 4 subpasses (paper: 2); 0..4
    // Coarsest synthesis level M (paper s4), where synthesis starts from patches of exemplar
    // coordinates. -1 (automatic): the coarsest level at which exemplars holding at least half of
    // the database's pixels are still kMinCoarsestSide pixels on their shorter side; coarser
    // levels hold too few pixels to synthesize from (a 648-pixel exemplar is 10x10 at level 6).
    // Output levels above M are block averages of level M.
    int coarsest_level = -1;
    // Point and type constraints (paper s5); null = none. Shared, immutable while synthesizing.
    std::shared_ptr<const SynthesisConstraints> constraints;
    // Finest level on which constraints act. The paper disables them on the finest two levels
    // (default 2) so they do not look intrusive; point sites still land on their heights when the
    // points are lifted (liftPointConstraints below).
    int first_constrained_level = kFirstConstrainedLevel;
    // Hold the geometric constraints' own pixels on the free finest levels: a curve's course (the
    // pixels next to it) and a point's site (its 7x7 pixels) are still pulled towards their targets
    // with phi_d there, everything around them stays free. With the lifts below this makes finished
    // courses land on their widgets' heights and sites on their slopes (docs/curves.md). Projects
    // set it with hold_point_heights; false = the paper's free finest levels.
    bool hold_on_free_levels = false;
    // Coherence (s5.3): the previous results are offered as an extra candidate whose cost is
    // multiplied by W; frozen pixels keep their previous S and V exactly. With unchanged inputs the
    // result is bit-identical to the previous one. `coherence` null = Coherent everywhere.
    std::shared_ptr<const SynthesisHistory> previous;
    std::shared_ptr<const CoherenceMap> coherence;
    bool record_history = false;  // fill SynthesisOutput::history
    // Drag preview (an editor's intermediate steps, IncrementalTerrain::setPreviewLevels): the finest
    // `preview_levels` levels of the output are upsampled and jittered (eq. 1-2), snapped to whole
    // exemplar pixels, but not corrected, so they cost a read-back instead of their passes (the
    // finest level is about three quarters of a synthesis). Pixels that are not Free keep their previous result exactly (with `previous`),
    // so only the Free area changes; constraints and drainage do not act on those levels; the
    // recorded history holds the uncorrected state for each of their passes. 0 (default) = a full
    // synthesis; 0..16.
    int preview_levels = 0;
    Drainage drainage = Drainage::Breach;  // Off: no drainage step (above)
    // Offset relaxation (beyond the paper): after each level's correction passes, and before its
    // drainage, the offsets V (eq. 1-2) are re-chosen with the sources S fixed so that every pixel's
    // height steps to its 8 neighbours are the exemplar's own steps at their sources, gentle steps
    // weighted most. The paper's V, carried smoothly through a patch, tilts what the patch copies
    // (flat valley floors, lakes and fjords gain a few degrees of slope) and leaves the height step
    // between two patches' sources as a seam; relaxed, flats stay flat across patches and steep
    // ground keeps its own relief. Pixels under point or curve constraints, frozen pixels and
    // drainage channels from the level above are not moved. Bounded reach: 4 to 8 pixels of
    // each level, added to its margin (windows stay bit-identical to larger windows); it runs on
    // the host and adds about a tenth to the synthesis time on CPUs (docs/realism.md, "Offset
    // relaxation"; docs/benchmarks.md). Off by default: it makes
    // close-ups harder to tell from the exemplar on most exemplars, but at 512^2 it moves
    // orom_andes-chile's slopes and orom_appalachians' closed depressions out of the realism
    // suite's bounds. false: the paper's V.
    bool relax_offsets = false;
};

struct SynthesisOutput {
    // Heights in metres: exemplar height at S plus V (s4), spacing = database spacing * 2^level.
    Heightfield heights;
    // Filled when requested: per pixel the exemplar coordinate it draws from, in pixels of that
    // exemplar at this level (x, y), and the exemplar index (database order).
    std::vector<float> source_x, source_y;
    std::vector<uint8_t> source_exemplar;
    // Every level and pass of this synthesis, when SynthesisParams::record_history was set.
    std::shared_ptr<SynthesisHistory> history;
};

enum class SynthesisBackend {
    OpenCL,     // kernels/*.cl on the first OpenCL device (PoCL on CPUs)
    Reference,  // plain C++ (runtime/src/synth), the executable specification of the kernels
};

struct SynthesizerOptions {
    SynthesisBackend backend = SynthesisBackend::OpenCL;
    // OpenCL device selection: "" = first GPU if any, else first device; otherwise a substring of
    // the platform or device name. TERRASYNTH_OPENCL_DEVICE overrides it.
    std::string device;
    // A user's request to stop (the Python module's Ctrl-C; a program's SIGINT handler could set
    // one too). Asked on the synthesizing thread before each pyramid level of every synthesize()
    // call, so a call stops within one level's work; when it returns true, that call returns the
    // error kSynthesisStopped with no output, and what called it (Terrain, EditSession, the lifts)
    // fails the same way with nothing changed. Called from every thread that synthesizes (tile and
    // export workers too): it must be thread-safe and cheap (it runs about L + 1 times per call).
    // Null: never stops.
    std::function<bool()> stop_requested;
};

// The message of a synthesis stopped by SynthesizerOptions::stop_requested.
constexpr const char* kSynthesisStopped = "synthesis stopped on request";

class Synthesizer {
public:
    // Uploads the database to the device (OpenCL) and compiles the kernels. Errors: no OpenCL
    // platform/device, kernel build log, out of device memory.
    static Result<std::unique_ptr<Synthesizer>> create(std::shared_ptr<const ExemplarDatabase> db,
                                                       const SynthesizerOptions& options = {});
    virtual ~Synthesizer() = default;

    // Synthesizes `window` of the given output level: 0 = finest, up to the database's coarsest level
    // (up to coarsest_level when that is set); levels above the coarsest synthesized one are block
    // averages of it. Preconditions: 1 <= width, height <= 16384, and at most 16384 pixels per side
    // of the coarsest synthesized level (an error otherwise).
    virtual Result<SynthesisOutput> synthesize(const PixelWindow& window, const SynthesisParams& params,
                                               int output_level = 0, bool want_sources = false) = 0;

    // Device name, e.g. "pthread-skylake-avx512" or "reference C++".
    virtual std::string deviceName() const = 0;
    // Peak bytes of synthesis state (all levels, including margins) used by the last call,
    // divided by the output pixels.
    virtual double lastBytesPerPixel() const = 0;

    const ExemplarDatabase& database() const { return *db_; }

protected:
    explicit Synthesizer(std::shared_ptr<const ExemplarDatabase> db) : db_(std::move(db)) {}
    std::shared_ptr<const ExemplarDatabase> db_;
    // SynthesizerOptions::stop_requested, set by create(); the backends hand it to the level loop.
    std::function<bool()> stop_requested_;
};

// The coarsest level synthesize() runs for `params` on `db`: params.coarsest_level, or the automatic
// one when that is -1 (kMinCoarsestSide). Output levels above it are block averages of 2^d x 2^d of
// its pixels, so a window there costs 4^d times its pixel count: viewers that page tiles may stop
// refining coarser than this level (the editor does). Thread-safe; db must be a built database.
int coarsestSynthesizedLevel(const ExemplarDatabase& db, const SynthesisParams& params);

// Point heights that hold (s5.1 with the finest levels free). The paper leaves the finest two levels
// unconstrained, and their detail moves the finished site away from the asked height (typically by
// 1-5% of the relief, docs/project-format.md). This returns the constraints with every
// PointConstraint::lift_m set so the finished level-0 height at each site is within tolerance_m of
// height_m, found by synthesizing a 2x2 window at each site (equal to the full synthesis, see above)
// up to max_rounds times and correcting the lift by the residual; if the tolerance is not reached,
// the best round is kept.
// With hold_on_free_levels the slope is held over the site's own 7x7 pixels too (points asked at
// 5 degrees or more): the tilts (PointConstraint::tilt_east/south) are searched the same way until
// the plane fitted over the finished 7x7 pixels rises within 10% of the asked rise, and the wide
// tilts (wide_tilt_east/south) while the plane fitted over half the radius misses by more (tested:
// 5-40 degrees, direction within 15 degrees over both; docs/project-format.md has the measured
// figures). Such a point's site is then synthesized over half its radius each round.
// Pass the same params (coherence, history) as the synthesis that will use the result; existing
// lifts are the starting point, so re-lifting after a small edit usually takes one or two rounds.
// Cost: per round, the sites are synthesized in windows grouped by a cost model (one window where
// the sites are dense, one small window per scattered site), so 10000 points over a 1024^2 extent
// cost a few whole-extent syntheses per round. Errors: those of synthesize().
struct PointLiftOptions {
    float tolerance_m = 0.5f;
    int max_rounds = 10;  // >= 1; 1 only measures
    // Lift only the points whose site lies in this level-0 window (an edit's area); the others keep
    // their lift. Unset = all points.
    std::optional<PixelWindow> sites_within;
};
Result<std::shared_ptr<const SynthesisConstraints>> liftPointConstraints(Synthesizer& synthesizer,
                                                                         const SynthesisParams& params,
                                                                         const PointLiftOptions& options = {});

// Curve heights that hold, the curve equivalent of liftPointConstraints. Every curve gets a lift
// profile (CurveConstraint::lift_m, stations about station_spacing_px apart along the course) so
// the finished level-0 heights along the course land on the widgets' heights (junctions pinned,
// terrasynth/curve_course.h): each station's residual is the mean of the finished course's
// residuals around it (weighted like the linear interpolation between stations), measured by
// synthesizing small windows along the course (equal to the full synthesis), and each station is
// searched like a point's lift. What is left is the detail of the free finest levels, which the lift
// cannot follow (docs/curves.md: measured figures). The round with the smallest mean |residual|
// along the moving part of the courses is kept; when that is the first round and the lifts kept
// their station counts, the given constraints are returned (the same pointer). Existing lift
// profiles are the starting point (resampled to the station count). Pass the same params
// (coherence, history, point lifts) as the synthesis that will use the result.
// Cost: per round, windows of 64 px of course plus the synthesis margins along every moving course
// (about a quarter of a synthesis of the courses' bounding boxes). Errors: those of synthesize().
struct CurveLiftOptions {
    // Stop once the median |finished - asked| along the moving courses is within this (metres);
    // 0 = search max_rounds.
    float tolerance_m = 0.0f;
    int max_rounds = 6;               // >= 1; 1 only measures
    double station_spacing_px = 8.0;  // > 0, level-0 pixels of arc length between stations
    // Lift only the stations that lie in this level-0 window (an edit's area); the others keep
    // their lift. Unset = all stations.
    std::optional<PixelWindow> stations_within;
    // Finished level-0 heights already synthesized with `params` (an edit's window; pixel (0, 0) is
    // global pixel (measured_x, measured_y)): the first round reads the course from them where they
    // hold it instead of synthesizing. Not owned; may be null.
    const Heightfield* measured = nullptr;
    int64_t measured_x = 0, measured_y = 0;
};
Result<std::shared_ptr<const SynthesisConstraints>> liftCurveConstraints(Synthesizer& synthesizer,
                                                                         const SynthesisParams& params,
                                                                         const CurveLiftOptions& options = {});

}  // namespace terrasynth

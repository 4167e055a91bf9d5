// Private: level ground (lakes, sea, fjord and flood-plain floors) is copied level.
//
// Why: the paper's height is E(S) + V (Gain et al. 2015 s3, eq. 1-7), and inside a patch the
// correction makes V the mean of its neighbours' (close to harmonic), so V is a smooth warp that
// tilts what a patch copies. Level sources suffer most: on orom_norway 9% of the output copies
// ground under 0.5 degrees, as much as the exemplar has, yet only 8% of it stays under 0.5 degrees
// (docs/realism.md, "Offset relaxation"), and the exemplar's lakes and fjords, which drain only as
// flats, became tilted hollows. So in the correction (kernel correct, referenceCorrect) a pixel
// whose chosen source is level ground goes no higher than its lowest neighbour copied from the
// same level ground (a level source of the same height, within the tolerance): a connected flat
// settles at the height of its lowest pixel, as water does, within the reach of the passes at each
// level (coarse levels level wide flats, finer ones their edges). Neighbours of another height do
// not count: DEMs stored in whole metres (wn_big_butte) are staircases of level terraces, and
// letting each terrace sink to the one below flattened the whole staircase into one closed plain.
// The drainage breach does not carve the level ground its pit lies in (drainage_breach.h): the path
// still cuts the rim, so the flat drains over it as the exemplar's lakes do.
//
// "Level" is a source whose 8 neighbours in the atlas are all within the tolerance of it: a slope
// under kLevelGroundSlopeDegrees at the database's finest spacing, at every level. Water is level
// at every scale, gentle ground is not: a tolerance growing with each level's spacing levelled
// orom_sahara's dune field at the coarse levels.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrasynth/database.h"

namespace terrasynth::synth {

constexpr double kLevelGroundSlopeDegrees = 0.5;

// Metres by which a level source's 8 neighbours may differ from it, at every level of a database
// whose finest spacing is `meters_per_pixel0`.
inline float levelGroundTolerance(double meters_per_pixel0) {
    return static_cast<float>(std::tan(kLevelGroundSlopeDegrees * M_PI / 180.0) * meters_per_pixel0);
}

// Per atlas pixel of `db`: 1 where it is level ground (its 8 neighbours within `tolerance` metres
// of it), 0 elsewhere and on the atlas's outer ring. The kernels and the reference read these flags,
// one byte per source: testing nine heights per source cost the correction kernel 7% more
// instructions.
std::vector<uint8_t> levelGroundFlags(const DatabaseLevel& db, float tolerance);

// The lowest height of the level's exemplar pixels (inside their atlas rectangles), metres: the
// floor of what the correction copies (kernel correct, referenceCorrect). Sources are copied as
// E(S) + V, and level ground settles to its lowest neighbour, so with nothing below it a sea or a
// lake at the exemplar's lowest height sank with whatever offset its neighbours had: orom_norway's
// sea at 0 m came out on 10% of a 1024^2 synthesis, down to -523 m, and osge_mt_fuji_90m had 4-7%
// of its output under its lowest height (issue 57, item 3). An unconstrained pixel's V is raised so
// that E(S) + V is at least this: what lies below the lowest ground the exemplars show (their base
// level, a sea or a lowest lake) is level at that height, as water is. Point and curve constraints
// may still ask for lower ground, and a channel carved at a coarser level (its ceiling) may cut
// below it. Held at the floor, or at most 1 m under it, those channels left orom_norway's closed
// depressions over the breach's check (ExemplarRealism: 0.0135-0.0138 against 0.0130); left free,
// they reach -332 m there on 0.75% of the output (docs/realism.md, "Known weaknesses").
float lowestExemplarHeight(const DatabaseLevel& db);

// levelGroundFlags and lowestExemplarHeight of each level (the flags at the database's tolerance),
// computed on first use (a synthesizer owns one; not thread-safe).
class LevelGround {
public:
    const std::vector<uint8_t>& flags(const ExemplarDatabase& db, int level);
    float lowest(const ExemplarDatabase& db, int level);
    static float tolerance(const ExemplarDatabase& db) { return levelGroundTolerance(db.meters_per_pixel); }

private:
    std::vector<std::vector<uint8_t>> flags_;
    std::vector<uint8_t> known_;
    std::vector<float> lowest_;
    std::vector<uint8_t> lowest_known_;
};

}  // namespace terrasynth::synth

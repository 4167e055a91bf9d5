// Builds the exemplar database (Gain et al. 2015 s4; type pyramid s5.2): read and resample the
// exemplars, build their Gaussian pyramids, fit one appearance-space PCA per level, pack each
// level into an atlas, find similar neighbourhoods with PatchMatch, derive the type pyramid, and
// mark each exemplar's own closed depressions (for drainage, issue 17). NoData voids (and their
// kInteriorMargin) become kNoType pixels that nothing is copied from (db/voids.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unistd.h>

#include "core/hash.h"
#include "core/number_text.h"
#include "db/db_internal.h"
#include "terrasynth/limits.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {
namespace {

using db::kMatchModes;

Status checkOptions(const DatabaseBuildOptions& o) {
    if (o.levels < 1 || o.levels > 12) return Status::error("levels must be 1..12, got " + std::to_string(o.levels));
    if (o.meters_per_pixel < 0.0 || o.meters_per_pixel > 1e5 || !std::isfinite(o.meters_per_pixel))
        return Status::error("meters_per_pixel must be 0 (automatic) or in (0, 100000]");
    if (o.patchmatch_iterations < 1 || o.patchmatch_iterations > 32)
        return Status::error("patchmatch_iterations must be 1..32");
    return Status::ok();
}

void report(const DatabaseBuildOptions& o, const std::string& stage, double progress) {
    if (o.progress) o.progress(stage, progress);
}

// Default type of each exemplar = its terrain_class (s5.2); painted masks add their own names.
void assignTypes(const std::vector<Exemplar>& exemplars, ExemplarDatabase& database,
                 std::vector<std::vector<uint8_t>>& base_types) {
    std::map<std::string, int> ids;
    auto typeId = [&](const std::string& name) {
        auto it = ids.find(name);
        if (it != ids.end()) return it->second;
        const int id = static_cast<int>(database.type_names.size());
        database.type_names.push_back(name);
        ids.emplace(name, id);
        return id;
    };
    for (const Exemplar& e : exemplars) {
        const std::string cls = e.info.terrain_class.empty() ? e.info.name : e.info.terrain_class;
        const int default_type = typeId(cls);
        database.exemplar_type.push_back(default_type);
        std::vector<uint8_t> types(e.field.size(), static_cast<uint8_t>(default_type));
        for (size_t i = 0; i < e.type_mask.size() && i < types.size(); ++i) {
            const uint8_t v = e.type_mask[i];
            const std::string name = v < e.type_mask_names.size() && !e.type_mask_names[v].empty()
                                         ? e.type_mask_names[v]
                                         : cls + "/" + std::to_string(v);
            types[i] = static_cast<uint8_t>(typeId(name));
        }
        base_types.push_back(std::move(types));
    }
}

// T^i(p): the most frequent type of the 2^i x 2^i block of T^0 (ties: lowest id).
std::vector<uint8_t> typeLevel(const std::vector<uint8_t>& base, int base_w, int base_h, int level, int w, int h) {
    std::vector<uint8_t> out(static_cast<size_t>(w) * h);
    const int block = 1 << level;
    int counts[256] = {};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int best = 255;  // no pixel in the block (cannot happen for in-range levels): type 0 below
            for (int by = y * block; by < std::min(base_h, (y + 1) * block); ++by)
                for (int bx = x * block; bx < std::min(base_w, (x + 1) * block); ++bx) {
                    const uint8_t t = base[static_cast<size_t>(by) * base_w + bx];
                    ++counts[t];
                    if (best == 255 || counts[t] > counts[best] || (counts[t] == counts[best] && t < best)) best = t;
                }
            // Reset only what this block touched (clearing all 256 counters per pixel dominated).
            for (int by = y * block; by < std::min(base_h, (y + 1) * block); ++by)
                for (int bx = x * block; bx < std::min(base_w, (x + 1) * block); ++bx)
                    counts[base[static_cast<size_t>(by) * base_w + bx]] = 0;
            out[static_cast<size_t>(y) * w + x] = static_cast<uint8_t>(best == 255 ? 0 : best);
        }
    return out;
}

// A void mask, when there is one, has one byte per height.
Status checkVoidMask(const Exemplar& ex) {
    if (!ex.nodata.empty() && ex.nodata.size() != ex.field.size())
        return Status::error(ex.info.path + ": the NoData mask has " + std::to_string(ex.nodata.size()) + " values for " +
                             std::to_string(ex.field.size()) + " heights");
    return Status::ok();
}

uint16_t quantise(float value, float offset, float scale) {
    const float q = std::round((value - offset) / scale);
    return static_cast<uint16_t>(std::clamp(q, 0.0f, 65535.0f));
}

// DatabaseLevel::closed of one exemplar: the pixels Priority-Flood raises (its edge drains out);
// never a pixel that synthesis cannot copy (`blocked`: a void's fill says nothing about basins).
void markClosedDepressions(const Heightfield& field, const std::vector<uint8_t>& blocked, const AtlasRect& r,
                           DatabaseLevel& out) {
    const Heightfield filled = fillDepressions(field, false);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const size_t i = static_cast<size_t>(y) * r.width + x;
            const bool raised = filled.heights[i] > field.heights[i] && (blocked.empty() || !blocked[i]);
            out.closed[static_cast<size_t>(r.y + y) * out.width + r.x + x] = raised ? 1 : 0;
        }
}

struct LevelInputs {
    std::vector<Heightfield> fields;                 // per exemplar (empty when too small)
    std::vector<db::NeighbourhoodFeatures> features;
    std::vector<std::vector<uint8_t>> types;
    std::vector<std::vector<uint8_t>> blocked;       // voids and their margin (db::voidMargins), or empty
};

// `coarser` is level + 1 when already built: its matches, carried down, start PatchMatch here.
void buildLevel(int level, LevelInputs& in, const DatabaseBuildOptions& options, const DatabaseLevel* coarser,
                DatabaseLevel& out) {
    const size_t count = in.fields.size();
    std::vector<const db::NeighbourhoodFeatures*> usable;
    for (const auto& f : in.features)
        if (!f.mean.empty()) usable.push_back(&f);
    const db::PcaBasis basis = db::fitPca(usable);

    std::vector<std::pair<int, int>> sizes;
    for (const Heightfield& f : in.fields) sizes.emplace_back(f.width, f.height);
    const db::AtlasLayout layout = db::packAtlas(sizes);
    out.width = layout.width;
    out.height = layout.height;
    out.rects = layout.rects;
    const size_t n = out.pixelCount();
    out.height_m.assign(n, 0.0f);
    out.appearance.assign(n * 4, 0);
    out.type.assign(n, kNoType);
    out.exemplar.assign(n, kNoExemplar);
    out.closed.assign(n, 0);
    std::vector<float> match_features(n * kMatchModes, 0.0f);
    std::vector<uint8_t> eligible(n, 0);
    // Which exemplar each pixel is for PatchMatch: its own inside its rectangle, kNoExemplar in the
    // gutters (which keep the exemplar id in `out.exemplar`, so coordinates jittered slightly outside
    // stay attributable). Void pixels are matched (their C_2 leads out of the void) but never matches.
    std::vector<uint8_t> match_exemplar(n, kNoExemplar);

    // Quantisation ranges: mode 0 spans all mean heights; modes 1..3 are symmetric.
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    float extent[4] = {0, 0, 0, 0};
    std::vector<std::vector<float>> projections(count);
    for (size_t e = 0; e < count; ++e) {
        if (in.features[e].mean.empty()) continue;
        projections[e] = db::projectFeatures(in.features[e], basis, kMatchModes, options.threads);
        for (float m : in.features[e].mean) lo = std::min(lo, m), hi = std::max(hi, m);
        for (size_t i = 0; i < in.features[e].mean.size(); ++i)
            for (int m = 1; m < 4; ++m) extent[m] = std::max(extent[m], std::fabs(projections[e][i * kMatchModes + m - 1]));
    }
    out.appearance_offset[0] = lo;
    out.appearance_scale[0] = hi > lo ? (hi - lo) / 65535.0f : 1.0f;
    for (int m = 1; m < 4; ++m) {
        out.appearance_scale[m] = extent[m] > 0 ? extent[m] / 32767.0f : 1.0f;
        out.appearance_offset[m] = -32768.0f * out.appearance_scale[m];
    }

    for (size_t e = 0; e < count; ++e) {
        const AtlasRect& r = out.rects[e];
        if (in.features[e].mean.empty()) continue;
        // Pad the gutter with the nearest edge height so bilinear taps at the border stay sane.
        for (int y = -kAtlasGutter; y < r.height + kAtlasGutter; ++y)
            for (int x = -kAtlasGutter; x < r.width + kAtlasGutter; ++x) {
                const size_t a = static_cast<size_t>(r.y + y) * out.width + (r.x + x);
                const int cx = std::clamp(x, 0, r.width - 1), cy = std::clamp(y, 0, r.height - 1);
                const size_t i = static_cast<size_t>(cy) * r.width + cx;
                out.height_m[a] = in.fields[e].heights[i];
                out.exemplar[a] = static_cast<uint8_t>(e);
                out.appearance[a * 4 + 0] = quantise(in.features[e].mean[i], out.appearance_offset[0], out.appearance_scale[0]);
                for (int m = 1; m < 4; ++m)
                    out.appearance[a * 4 + m] = quantise(projections[e][i * kMatchModes + m - 1],
                                                         out.appearance_offset[m], out.appearance_scale[m]);
                const bool inside = x == cx && y == cy;
                if (!inside) continue;
                const bool blocked = !in.blocked[e].empty() && in.blocked[e][i];
                out.type[a] = blocked ? kNoType : in.types[e][i];
                match_exemplar[a] = static_cast<uint8_t>(e);
                std::copy_n(&projections[e][i * kMatchModes], kMatchModes, &match_features[a * kMatchModes]);
                eligible[a] = !blocked && x >= kInteriorMargin && y >= kInteriorMargin && x < r.width - kInteriorMargin &&
                              y < r.height - kInteriorMargin;
            }
    }
    for (size_t e = 0; e < count; ++e)
        if (!in.features[e].mean.empty()) markClosedDepressions(in.fields[e], in.blocked[e], out.rects[e], out);
    db::PatchMatchInput pm{out.width, out.height, kMatchModes, match_features.data(), match_exemplar.data(),
                           eligible.data(), 0x51u + static_cast<uint32_t>(level)};
    std::vector<uint32_t> prior;
    if (coarser) {
        prior = db::upsampleMatches(*coarser, out.rects, out.width, out.height);
        pm.initial = prior.data();
    }
    out.similar = db::patchMatch(pm, options.patchmatch_iterations, options.threads);

    // Per-type seed coordinates (s5.2 "randomly preselect and store a list of coordinates").
    std::vector<std::vector<uint32_t>> by_type;
    for (size_t a = 0; a < n; ++a) {
        if (!eligible[a]) continue;
        if (by_type.size() <= out.type[a]) by_type.resize(out.type[a] + 1);
        by_type[out.type[a]].push_back(static_cast<uint32_t>(a));
    }
    out.type_seeds.resize(by_type.size());
    for (size_t t = 0; t < by_type.size(); ++t) {
        if (by_type[t].empty()) continue;
        for (int k = 0; k < kTypeSeedCount; ++k)
            out.type_seeds[t].push_back(by_type[t][core::hash3(k, static_cast<int>(t), 0x7e5u + level) % by_type[t].size()]);
    }
}

}  // namespace

size_t DatabaseLevel::memoryBytes() const {
    size_t seeds = 0;
    for (const auto& s : type_seeds) seeds += s.size() * sizeof(uint32_t);
    return height_m.size() * sizeof(float) + appearance.size() * sizeof(uint16_t) + similar.size() * sizeof(uint32_t) +
           type.size() + exemplar.size() + closed.size() + rects.size() * sizeof(AtlasRect) + seeds;
}

size_t ExemplarDatabase::basePixelCount() const {
    size_t total = 0;
    if (levels.empty()) return 0;
    for (const AtlasRect& r : levels[0].rects) total += static_cast<size_t>(r.width) * r.height;
    return total;
}

size_t ExemplarDatabase::memoryBytes() const {
    size_t total = 0;
    for (const DatabaseLevel& l : levels) total += l.memoryBytes();
    return total;
}

namespace {

Result<std::shared_ptr<ExemplarDatabase>> buildFromExemplars(std::vector<Exemplar> exemplars,
                                                             const DatabaseBuildOptions& options) {
    Status ok = checkOptions(options);
    if (!ok) return ok.withContext("database options");
    if (exemplars.empty()) return Status::error("no exemplars given");
    if (exemplars.size() > static_cast<size_t>(kMaxExemplars))
        return Status::error("at most " + std::to_string(kMaxExemplars) + " exemplars per database");
    auto database = std::make_shared<ExemplarDatabase>();
    double spacing = options.meters_per_pixel;
    if (spacing == 0.0)
        for (const Exemplar& e : exemplars)
            spacing = std::max({spacing, e.field.meters_per_pixel_x, e.field.meters_per_pixel_y});
    database->meters_per_pixel = spacing;
    // What resampling to `spacing` makes of every exemplar, checked before any of it is allocated:
    // a fine spacing asked of coarse exemplars multiplies their pixels.
    double total_pixels = 0.0;
    for (const Exemplar& e : exemplars) {
        const double w = std::round(e.field.width * e.field.meters_per_pixel_x / spacing);
        const double h = std::round(e.field.height * e.field.meters_per_pixel_y / spacing);
        total_pixels += w * h;
        if (w > limits::kMaxImageSide || h > limits::kMaxImageSide ||
            total_pixels > static_cast<double>(limits::kMaxDatabasePixels))
            return Status::error(e.info.path + ": at " + detail::compactNumber(spacing) + " m/pixel the exemplars take " +
                                 detail::compactNumber(total_pixels) + " pixels (this one " + detail::compactNumber(w) + "x" +
                                 detail::compactNumber(h) + "); a database holds at most " +
                                 std::to_string(limits::kMaxDatabasePixels) + ": use a coarser --meters-per-pixel");
    }

    report(options, "resampling", 0.0);
    std::vector<std::vector<uint8_t>> base_voids(exemplars.size());
    for (size_t e = 0; e < exemplars.size(); ++e) {
        Exemplar& ex = exemplars[e];
        const int old_w = ex.field.width, old_h = ex.field.height;
        if (Status s = checkVoidMask(ex); !s) return s;
        if (!ex.nodata.empty() && options.on_voids)
            options.on_voids(ex.info, static_cast<double>(std::count(ex.nodata.begin(), ex.nodata.end(), 1)) / ex.nodata.size());
        base_voids[e] = db::resampleVoids(ex.nodata, ex.field, spacing);
        ex.field = resampleToSpacing(ex.field, spacing);
        if (!ex.type_mask.empty() && (ex.field.width != old_w || ex.field.height != old_h)) {
            std::vector<uint8_t> resized(ex.field.size());  // nearest neighbour keeps labels crisp
            for (int y = 0; y < ex.field.height; ++y)
                for (int x = 0; x < ex.field.width; ++x)
                    resized[static_cast<size_t>(y) * ex.field.width + x] =
                        ex.type_mask[static_cast<size_t>(std::min(old_h - 1, y * old_h / ex.field.height)) * old_w +
                                     std::min(old_w - 1, x * old_w / ex.field.width)];
            ex.type_mask = std::move(resized);
        }
        const int minimum = 2 * kInteriorMargin + 4;
        if (ex.field.width < minimum || ex.field.height < minimum)
            return Status::error(ex.info.path + ": only " + std::to_string(ex.field.width) + "x" +
                                 std::to_string(ex.field.height) + " pixels at " + std::to_string(spacing) +
                                 " m/pixel; too small for the database");
        database->exemplars.push_back(ex.info);
        report(options, "resampling", double(e + 1) / exemplars.size());
    }
    if (database->exemplars.size() > 0 && exemplars.size() > static_cast<size_t>(kMaxTypes))
        return Status::error("too many terrain types");
    std::vector<std::vector<uint8_t>> base_types;
    assignTypes(exemplars, *database, base_types);
    if (database->type_names.size() > static_cast<size_t>(kMaxTypes))
        return Status::error("at most " + std::to_string(kMaxTypes) + " terrain types");

    std::vector<std::vector<Heightfield>> pyramids;
    std::vector<std::vector<std::vector<uint8_t>>> blocked(exemplars.size());  // per exemplar and level
    for (size_t e = 0; e < exemplars.size(); ++e) {
        pyramids.push_back(db::buildGaussianPyramid(exemplars[e].field, options.levels));
        std::vector<uint8_t> voids = std::move(base_voids[e]);
        for (size_t level = 0; level < pyramids[e].size(); ++level) {
            const Heightfield& f = pyramids[e][level];
            if (level > 0) {
                const Heightfield& finer = pyramids[e][level - 1];
                voids = db::coarserVoids(voids, finer.width, finer.height, f.width, f.height);
            }
            blocked[e].push_back(db::voidMargins(voids, f.width, f.height));
        }
    }
    // An exemplar takes part in a level when it has interior pixels there that are not blocked by a
    // void; voids only grow towards coarser levels, so it then takes part in every finer one too.
    auto present = [&](size_t e, int level) {
        if (level >= static_cast<int>(pyramids[e].size())) return false;
        const Heightfield& f = pyramids[e][level];
        if (f.width <= 2 * kInteriorMargin || f.height <= 2 * kInteriorMargin) return false;
        const std::vector<uint8_t>& b = blocked[e][level];
        if (b.empty()) return true;
        for (int y = kInteriorMargin; y < f.height - kInteriorMargin; ++y)
            for (int x = kInteriorMargin; x < f.width - kInteriorMargin; ++x)
                if (!b[static_cast<size_t>(y) * f.width + x]) return true;
        return false;
    };
    for (size_t e = 0; e < exemplars.size(); ++e)
        if (!present(e, 0))
            return Status::error(exemplars[e].info.path + ": its NoData voids leave no pixel " + std::to_string(kInteriorMargin) +
                                 " or more pixels from a void and the edge at " + detail::compactNumber(spacing) + " m/pixel");
    // The pyramid stops below the first level where every exemplar is too small.
    int level_count = 0;
    while (level_count <= options.levels) {
        bool any = false;
        for (size_t e = 0; e < exemplars.size(); ++e) any = any || present(e, level_count);
        if (!any) break;
        ++level_count;
    }
    // Coarsest first, so each level's PatchMatch starts from the matches of the level above.
    database->levels.resize(level_count);
    for (int level = level_count - 1; level >= 0; --level) {
        LevelInputs in;
        for (size_t e = 0; e < exemplars.size(); ++e) {
            const bool present_here = present(e, level);
            in.fields.push_back(present_here ? pyramids[e][level] : Heightfield());
            in.features.push_back(present_here ? db::extractNeighbourhoods(pyramids[e][level], options.threads) : db::NeighbourhoodFeatures());
            in.types.push_back(present_here ? typeLevel(base_types[e], exemplars[e].field.width, exemplars[e].field.height,
                                                        level, pyramids[e][level].width, pyramids[e][level].height)
                                            : std::vector<uint8_t>());
            in.blocked.push_back(present_here ? blocked[e][level] : std::vector<uint8_t>());
        }
        const DatabaseLevel* coarser = level + 1 < level_count ? &database->levels[level + 1] : nullptr;
        buildLevel(level, in, options, coarser, database->levels[level]);
        report(options, "level " + std::to_string(level), double(level_count - level) / level_count);
    }
    return database;
}

}  // namespace

Result<std::shared_ptr<const ExemplarDatabase>> buildDatabase(std::vector<Exemplar> exemplars,
                                                              const DatabaseBuildOptions& options) {
    auto built = buildFromExemplars(std::move(exemplars), options);
    if (!built) return built.status();
    return std::shared_ptr<const ExemplarDatabase>(std::move(built.value()));
}

Result<std::shared_ptr<const ExemplarDatabase>> buildDatabase(const std::vector<std::string>& inputs,
                                                              const DatabaseBuildOptions& options) {
    std::vector<std::string> files;
    for (const std::string& input : inputs) {
        if (::access((input + "/.").c_str(), F_OK) == 0) {
            auto listed = listExemplarFiles(input);
            if (!listed) return listed.status();
            files.insert(files.end(), listed->begin(), listed->end());
        } else {
            files.push_back(input);
        }
    }
    std::vector<Exemplar> exemplars;
    for (size_t i = 0; i < files.size(); ++i) {
        report(options, "reading", double(i) / files.size());
        auto exemplar = readExemplar(files[i]);
        if (!exemplar) return exemplar.status();
        exemplars.push_back(std::move(exemplar.value()));
    }
    auto digest = digestInputs(inputs, options);
    if (!digest) return digest.status();
    auto built = buildFromExemplars(std::move(exemplars), options);
    if (!built) return built.status();
    built.value()->input_digest = digest.value();
    return std::shared_ptr<const ExemplarDatabase>(std::move(built.value()));
}

}  // namespace terrasynth

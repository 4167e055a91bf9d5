// CULL: which tiles to draw and which to want, by screen-space error around the camera.
#include <algorithm>
#include <cmath>
#include <limits>

#include <osgUtil/CullVisitor>

#include "terrasynth_plugin/terrain_node.h"
#include "tile_store.h"

namespace terrasynth::plugin {
namespace {

// Missing root tiles are holes, so they outrank every refinement.
constexpr double kRootPriority = -1e12;
// A visible tile whose heights were edited is the next most urgent (the old one is on screen).
constexpr double kDirtyPriority = -1e9;

double distanceToBox(const osg::Vec3d& p, const osg::BoundingBox& b) {
    const double dx = std::max({double(b.xMin()) - p.x(), 0.0, p.x() - double(b.xMax())});
    const double dy = std::max({double(b.yMin()) - p.y(), 0.0, p.y() - double(b.yMax())});
    const double dz = std::max({double(b.zMin()) - p.z(), 0.0, p.z() - double(b.zMax())});
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double horizontalDistance(double px, double py, double x0, double y0, double x1, double y1) {
    const double dx = std::max({x0 - px, 0.0, px - x1});
    const double dy = std::max({y0 - py, 0.0, py - y1});
    return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

double TerrainNode::screenPixelsPerMeter(osgUtil::CullVisitor& cv, double distance) const {
    const osg::Viewport* vp = cv.getViewport();
    const osg::RefMatrix* proj = cv.getProjectionMatrix();
    const double height_px = vp ? vp->height() : 720.0;
    const double p11 = proj ? (*proj)(1, 1) : 1.0 / std::tan(0.26);
    const bool ortho = proj && (*proj)(3, 3) == 1.0;
    const double scale = height_px * 0.5 * p11;
    return ortho ? scale : scale / std::max(distance * cv.getLODScale(), 1e-3);
}

void TerrainNode::want(const TileKey& key, double priority) {
    if (failed_.count(key)) return;
    auto [it, inserted] = wanted_.emplace(key, priority);
    if (!inserted) it->second = std::min(it->second, priority);
}

bool TerrainNode::wantDrawnDirtyTiles() {
    bool any = false;
    for (const TileKey& key : drawn_keys_) {
        const ResidentTile* tile = store_->find(key);
        if (!tile || !tile->dirty) continue;
        want(key, kDirtyPriority + tile->drawn_distance);
        any = true;
    }
    return any;
}

void TerrainNode::cull(osgUtil::CullVisitor& cv) {
    std::lock_guard<std::mutex> lock(mutex_);
    const unsigned frame = cv.getFrameStamp() ? cv.getFrameStamp()->getFrameNumber() : frame_counter_;
    if (frame != cull_frame_) {
        // A new frame: start the wish list and the drawn set afresh (several cameras add to them).
        cull_frame_ = frame;
        wanted_.clear();
        drawn_.clear();
        drawn_keys_.clear();
        stats_.drawn_triangles = 0;
        stats_.drawn_min_height = std::numeric_limits<float>::max();
        stats_.drawn_max_height = std::numeric_limits<float>::lowest();
    }
    {
        const osg::RefMatrix* proj = cv.getProjectionMatrix();
        if (!(proj && (*proj)(3, 3) == 1.0)) pixels_per_meter_at_1m_ = screenPixelsPerMeter(cv, 1.0);
    }
    // The morph shader's distance scale for this camera (see terrain_shader.cpp).
    osg::ref_ptr<osg::StateSet> lod_state;
    if (options_.geomorph) {
        const double k = screenPixelsPerMeter(cv, 1.0) / options_.pixel_error;
        const osg::RefMatrix* proj = cv.getProjectionMatrix();
        const bool ortho = proj && (*proj)(3, 3) == 1.0;
        lod_state = new osg::StateSet;
        lod_state->addUniform(new osg::Uniform("ts_lod_k", ortho ? 0.0f : static_cast<float>(k)));
        lod_states_.erase(std::remove_if(lod_states_.begin(), lod_states_.end(),
                                         [frame](const auto& s) { return s.first + 4 < frame || s.first > frame; }),
                          lod_states_.end());
        lod_states_.emplace_back(frame, lod_state);
        cv.pushStateSet(lod_state.get());
    }
    cullFrom(cv, frame);
    if (lod_state) cv.popStateSet();
}

void TerrainNode::cullFrom(osgUtil::CullVisitor& cv, unsigned frame) {
    const osg::Vec3d eye = cv.getEyeLocal();
    const int root = options_.max_level;
    const double m = layout_.tileMeters(root);
    const double radius = options_.view_radius_m, load_radius = 1.5 * radius;

    const TileKey nw = layout_.keyAt(eye.x() - load_radius, eye.y() + load_radius, root);
    const TileKey se = layout_.keyAt(eye.x() + load_radius, eye.y() - load_radius, root);
    for (int64_t ty = nw.y; ty <= se.y; ++ty) {
        for (int64_t tx = nw.x; tx <= se.x; ++tx) {
            const TileKey key{root, tx, ty};
            const double x0 = layout_.westX(key), y1 = layout_.northY(key);
            const double d = horizontalDistance(eye.x(), eye.y(), x0, y1 - m, x0 + m, y1);
            if (d > load_radius) continue;
            ResidentTile* tile = store_->find(key);
            if (!tile) {
                want(key, kRootPriority + d);
                continue;
            }
            tile->last_used_frame = frame;
            if (d <= radius) selectTile(cv, key, *tile);
        }
    }
}

void TerrainNode::selectTile(osgUtil::CullVisitor& cv, const TileKey& key, ResidentTile& tile) {
    const unsigned frame = cull_frame_;
    tile.last_used_frame = frame;
    const osg::Vec3d eye = cv.getEyeLocal();
    const double d = distanceToBox(eye, tile.box);
    // Edited tiles on screen are rebuilt first; those refined away or out of view (kept for when
    // the view changes) after the missing tiles nearer than them.
    const double hidden_priority = d / layout_.tileMeters(key.level);
    if (cv.isCulled(tile.box)) {
        if (tile.dirty) want(key, hidden_priority);
        return;
    }

    const bool refine = key.level > options_.min_level &&
                        layout_.spacing(key.level) * screenPixelsPerMeter(cv, d) > options_.pixel_error;
    if (refine) {
        ResidentTile* children[4] = {};
        bool all = true;
        for (int j = 0; j < 2; ++j) {
            for (int i = 0; i < 2; ++i) {
                const TileKey ck = key.child(i, j);
                ResidentTile* child = store_->find(ck);
                if (!child) {
                    all = false;
                    want(ck, d / layout_.tileMeters(ck.level));
                } else {
                    // Keep the partial set: evicting it would restart the refinement.
                    child->last_used_frame = frame;
                    children[2 * j + i] = child;
                }
            }
        }
        if (all) {
            if (tile.dirty) want(key, hidden_priority);
            for (int c = 0; c < 4; ++c) selectTile(cv, key.child(c % 2, c / 2), *children[c]);
            return;
        }
    }
    tile.drawn_distance = d;
    if (tile.dirty) want(key, kDirtyPriority + d);
    tile.node->accept(cv);
    drawn_.push_back(tile.node);
    drawn_keys_.push_back(key);
    stats_.drawn_triangles += tile.triangles;
    stats_.drawn_min_height = std::min(stats_.drawn_min_height, tile.data->min_height);
    stats_.drawn_max_height = std::max(stats_.drawn_max_height, tile.data->max_height);
}

}  // namespace terrasynth::plugin

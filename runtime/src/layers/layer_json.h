// JSON form of layers (docs/layers.md), shared by parse/serialise and the content cache keys.
#pragma once

#include <nlohmann/json.hpp>

#include "terrasynth/layers.h"

namespace terrasynth::layers {

nlohmann::json editLayerToJson(const EditLayer& layer);
nlohmann::json toolToJson(const ToolParams& tool);  // without name, visibility and weights
nlohmann::json baseToJson(const BaseLayer& base, const BandSplit& split);
// `where` prefixes error messages, e.g. "layers[3]".
Result<EditLayer> parseEditLayer(const nlohmann::json& j, const std::string& where);

// parseLayerStack / layerStackToJson (layers.h) on parsed JSON.
Result<LayerStack> parseLayerStackJson(const nlohmann::json& layers, const std::string& base_dir);
// At most limits::kMaxLayers layers (children of groups included), groups nested at most
// limits::kMaxGroupDepth deep.
Status checkStackSize(const std::vector<EditLayer>& layers);
nlohmann::json layerStackJson(const LayerStack& stack);

// FNV-1a over bytes: a stable fingerprint for cache keys.
uint64_t fingerprint(const std::string& bytes, uint64_t seed = 1469598103934665603ull);

}  // namespace terrasynth::layers

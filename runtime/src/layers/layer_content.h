// Turns each tool's parameters into the cached pyramid content the compositor blends.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "layers/compositor.h"
#include "terrasynth/layers.h"

namespace terrasynth::layers {

// Layers whose content is computed from the terrain below them.
bool readsBelow(const ToolParams& tool);

// Additive relief of peak, ridge, perspective and noise layers (others: programmer error).
Result<Heightfield> toolRelief(const ToolParams& tool, const Heightfield& grid);

std::shared_ptr<LayerContent> additiveContent(const Heightfield& relief, const BandSplit& split);
std::shared_ptr<LayerContent> blendedContent(const Heightfield& content, const std::vector<float>& mask, OpKind kind,
                                             const BandSplit& split);

Result<std::shared_ptr<LayerContent>> pasteContent(const PasteParams& p, const Heightfield& below, const BandSplit& split,
                                                   const std::string& base_dir);
Result<std::shared_ptr<LayerContent>> holeFillContent(const HoleFillParams& p, const Heightfield& below,
                                                      const BandSplit& split);

// The base heights on the grid of `synthesized` (which is returned for BaseSource::Synthesized).
Result<Heightfield> baseHeights(const BaseLayer& base, const Heightfield& synthesized, const std::string& base_dir);

}  // namespace terrasynth::layers

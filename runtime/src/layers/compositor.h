// Recomposition of a layer stack in the Laplacian pyramid (Bradbury et al. 2014, s3.2): every layer's
// pyramid is combined level by level with its band weight, and the combined pyramid is collapsed in
// the same pass, coarse to fine, so a weight change costs one sweep over the cached pyramids.
#pragma once

#include <memory>
#include <vector>

#include "layers/pyramid.h"
#include "terrasynth/layers_bands.h"

namespace terrasynth::layers {

enum class OpKind {
    Add,          // R += w * C
    Replace,      // R += w * M * (C - R)
    MaxGradient,  // R += w * M * (S - R), S = the larger-magnitude of C and R per detail coefficient
};

// The cached, weight-independent part of one layer.
struct LayerContent {
    OpKind kind = OpKind::Add;
    Pyramid coeffs;             // Laplacian pyramid of the content (relief for Add, heights otherwise)
    Pyramid mask;               // Gaussian pyramid of coverage in [0,1]; empty for Add
    std::vector<Box> support;   // per level, where the layer can change anything
    size_t bytes() const;
};
// Fills `support` from the coefficients (Add) or the mask.
void computeSupport(LayerContent& content);

struct PlannedOp {
    std::shared_ptr<const LayerContent> content;
    BandWeights weights;
};
// Everything one recomposition reads; holds its inputs alive.
struct CompositionPlan {
    BandSplit split;
    std::shared_ptr<const Pyramid> base;  // Laplacian pyramid of the base heights
    BandWeights base_weights;
    std::vector<PlannedOp> ops;           // visible layers, bottom to top
};

// Owns the per-level scratch reused between recompositions. Not thread-safe; uses all cores.
class Compositor {
public:
    // The composed heights (level 0 of the collapsed pyramid).
    void compose(const CompositionPlan& plan, Plane& out);
    // The combined, not collapsed, pyramid (collapse() of it equals compose()).
    Pyramid combine(const CompositionPlan& plan);

private:
    std::vector<Plane> levels_;
};

}  // namespace terrasynth::layers

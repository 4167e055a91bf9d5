// terrasynth/layers.h: non-destructive, frequency-banded layer editing (Bradbury et al. 2014).
//
// A LayerStack is a base layer (the synthesized terrain, an imported heightmap, a blank plane or
// seeded fractal noise) plus edit layers, bottom to top, each made by one tool (layers_tools.h).
// Every layer is held as a Laplacian pyramid and contributes three bands (layers_bands.h) scaled by
// its BandWeights; the stack is recomposed by blending the pyramids level by level and collapsing
// once (gradient-domain "Laplacian blending", s3.2), so edits merge without seams and a weight change
// only recombines cached pyramids.
//
// How an edit layer combines with the stack below it, per pyramid level with weight w of that
// level's band:
//   additive (peak, ridge, perspective, noise, group, hole fill):  R += w * C
//     (a hole fill's C is the pyramid of its change, chosen variant minus the terrain below)
//   paste, with mask pyramid M:                                    R += w * M * (S - R)
//     where S = C for "replace" pastes, and for max-gradient pastes S keeps, per
//     detail coefficient, whichever of C and R is larger in magnitude (the low band always takes C).
// Layers that read the terrain below them (paste from "terrain", hole fill, group) are computed
// from the composition of the visible layers below, including their weights.
//
// JSON (the `layers` array of a .tsyn project; docs/layers.md): element 0 may be
// {"type":"base", ...}; without it the base is the synthesized terrain. Layer geometry is in
// pixels of the terrain grid, heights in metres.
//
// Threading: LayerStack is a value; the free functions are re-entrant. A LayerEditor is not
// thread-safe (one UI thread); it uses all cores internally.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth/layers_bands.h"
#include "terrasynth/layers_tools.h"
#include "terrasynth/status.h"

namespace terrasynth {

enum class BaseSource {
    Synthesized,  // the terrain handed to applyLayerStack (the synthesizer's output)
    Heightmap,    // `path`, any format readExemplar() reads, resampled to the grid size
    Blank,        // constant `height_m`
    Fractal,      // `fractal` (fBm or diamond-square), seeded
};

struct BaseLayer {
    BaseSource source = BaseSource::Synthesized;
    std::string path;       // Heightmap: as written in the project (relative to LayerStack::base_dir)
    double height_m = 0.0;  // Blank
    FractalParams fractal;  // Fractal
    BandWeights weights;
};

// Fractal detail as an edit layer (Figures 1 and 12 of the paper), optionally confined to a region.
struct NoiseParams {
    FractalParams fractal;
    std::optional<Region> region;  // none = the whole grid
    double feather_px = 32.0;      // ramp inside the region's edge
};

// Perspective canvas sketch (s4.1): strokes over a reference image become ridges.
struct PerspectiveParams {
    std::string reference_image;  // informational (the UI shows it); not read by the runtime
    PerspectiveCanvas canvas;
    std::vector<SilhouetteStroke> strokes;
};

struct EditLayer;
// Merged layers (LayerEditor::mergeDown): the children are composed in order over the terrain
// below, and that combined change acts as one additive layer with the group's weights.
struct GroupParams {
    std::vector<EditLayer> children;
};

using ToolParams =
    std::variant<PeakParams, RidgeParams, PasteParams, HoleFillParams, PerspectiveParams, NoiseParams, GroupParams>;

struct EditLayer {
    std::string name;  // free text shown in the layer panel
    bool visible = true;
    BandWeights weights;  // use defaultWeights(tool) for a fresh layer
    ToolParams tool;
};

// Paper defaults: ridges and perspective sketches affect only the low band (s4.2: "by default,
// affect only the low-frequency content ... higher frequencies are taken from the original
// terrain"); everything else starts with all bands at 1.
BandWeights defaultWeights(const ToolParams& tool);
// "peak", "ridge", "paste", "hole_fill", "perspective", "noise", "group".
const char* toolTypeName(const ToolParams& tool);

struct LayerStack {
    BandSplit bands;
    BaseLayer base;
    std::vector<EditLayer> layers;  // bottom to top
    std::string base_dir;           // folder relative paths are resolved against ("" = cwd)
};

// Parses the `layers` array (JSON text). `base_dir` resolves relative paths (heightmaps, external
// DEMs). Errors name the element and field: "layers[2].spread_px: must be > 0".
Result<LayerStack> parseLayerStack(const std::string& layers_json, const std::string& base_dir);
// The inverse of parseLayerStack, as compact JSON text: parse(layerStackToJson(s)) == s.
std::string layerStackToJson(const LayerStack& stack);
// The stack of a project file's "layers" array, or of a file holding a bare layers array; relative
// paths resolve against the file's folder. Errors name the file.
Result<LayerStack> readLayerStack(const std::string& path);
// The heightmap of a BaseSource::Heightmap base on its own grid (size and spacing of the file), for
// tools that apply a stack without synthesis. Errors name "layers[0].path" and the file.
Result<Heightfield> readBaseHeightmap(const LayerStack& stack);
// Checks one layer as parseLayerStack would (message prefixed with `context`).
Status validateEditLayer(const EditLayer& layer, const std::string& context = "layer");

// Composes the stack. `base` is the synthesized terrain when stack.base is Synthesized; otherwise
// only its size and spacing are used and the stack's base replaces it. An empty stack (no visible
// layer, unit base weights) over the synthesized terrain returns `base` bit for bit. Errors:
// unreadable files, parameters that do not fit the grid (e.g. a paste source outside the DEM), hole
// fill failures; they name the layer as "layers[i]" with i its index in layerStackToJson() (the
// base is element 0). Cost: a few ms per layer plus its tool (hole fill ~0.1-1 s).
Result<Heightfield> applyLayerStack(const LayerStack& stack, const Heightfield& base);

// One line per layer, bottom to top: index, type, name, visibility, band weights, key parameters.
std::string describeLayerStack(const LayerStack& stack);

// Interactive editing session over one stack: every operation is undoable, layer pyramids are cached
// (keyed by the layer's parameters and, for layers that read the terrain below, by everything below),
// so changing a weight or visibility only recombines pyramids, and undo/redo restore bit-identical
// heights. Not thread-safe.
class LayerEditor {
public:
    // `base` as for applyLayerStack. Fails when the stack does not validate or the grid is empty.
    static Result<LayerEditor> create(LayerStack stack, Heightfield base);
    LayerEditor(LayerEditor&&) noexcept;
    LayerEditor& operator=(LayerEditor&&) noexcept;
    ~LayerEditor();

    const LayerStack& stack() const;
    // The composed terrain for the current stack (recomputes what changed since the last call).
    Result<Heightfield> heights();
    // The same without a copy: the editor's own buffer, reused between recompositions (the path for
    // following slider drags). Valid until the next call that edits or recomposes.
    Result<const Heightfield*> currentHeights();
    // The full-resolution bands of one layer's content as it is blended (index -1 = base), for the
    // sub-layer view. Additive layers show their relief, paste and hole fill their masked content.
    Result<BandDecomposition> layerBands(int index);

    // Edits. Indices are 0-based into stack().layers (bottom to top); index -1 for addLayer appends.
    // Each successful edit is one undo step; a failed one changes nothing.
    Status addLayer(EditLayer layer, int index = -1);
    Status removeLayer(int index);
    Status moveLayer(int from, int to);
    Status setVisible(int index, bool visible);
    Status setWeights(int index, BandWeights weights);
    Status setBaseWeights(BandWeights weights);
    Status replaceLayer(int index, EditLayer layer);  // change a layer's tool parameters or name
    Status setBase(BaseLayer base);
    Status setBandSplit(BandSplit split);
    // Replaces the whole stack (validated like parseLayerStack) as one undo step.
    Status setStack(LayerStack stack);
    // Replaces the synthesized terrain the stack is composed over (BaseSource::Synthesized), e.g.
    // after a constraint edit; same size and spacing. Not an undo step: the terrain is not part of the
    // stack. Layers that do not read the terrain below keep their cached content.
    Status setSynthesizedTerrain(Heightfield terrain);
    // Merges layers[index] into the layer below it (index-1) as one group layer with unit weights,
    // which composes to the same terrain as the two did (up to float rounding).
    Status mergeDown(int index);

    // The three variants generation `generation` of the hole-fill layer at `index` offers, computed
    // over the terrain below it: generation 0 from scratch, generation g guided by the pick its
    // choices[0..g-1] lineage makes. 0 <= generation <= choices.size(). The UI shows them, then
    // replaceLayer()s the layer with the artist's pick appended to (or replacing) its choices.
    Result<std::vector<Heightfield>> holeFillPreviews(int index, int generation);

    bool canUndo() const;
    bool canRedo() const;
    bool undo();  // false when there is nothing to undo
    bool redo();

private:
    struct Impl;
    explicit LayerEditor(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace terrasynth

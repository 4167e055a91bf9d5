// The non-destructive layer stack (Bradbury et al. 2014 s3, s3.2): JSON form, editing operations,
// undo/redo, merge, on real terrain.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "terrasynth/layers.h"
#include "test_support.h"

namespace terrasynth {
namespace {

using nlohmann::json;

std::string richStack() {
    return json::parse(R"([
      {"type": "base", "source": "fbm", "seed": 9, "amplitude_m": 400, "wavelength_px": 128,
       "band_cuts_px": [8, 32], "weights": {"low": 1, "mid": 0.8, "high": 1.2}},
      {"type": "peak", "name": "summit", "center": [60, 70], "height_m": 500, "spread_px": 14,
       "skewness": 0.4, "kurtosis": 1.0, "skew_azimuth_deg": 30},
      {"type": "ridge", "points": [[10, 100], [60, 90], [120, 110]], "profile_m": [100, 300, 150], "width_px": 12},
      {"type": "paste", "source": "terrain", "source_xy": [0, 0], "dest": {"shape": "rect", "rect": [80, 10, 40, 40]},
       "blend": "replace", "match_height": false, "weights": {"low": 0}},
      {"type": "hole_fill", "hole": {"rect": [30, 20, 24, 24]}, "patch_px": 12, "overlap_px": 4, "seed": 3,
       "candidates": 64, "choices": [2, 0]},
      {"type": "noise", "noise": "diamond_square", "seed": 4, "amplitude_m": 20, "roughness": 0.7,
       "region": {"shape": "ellipse", "rect": [0, 0, 64, 64]}, "visible": false},
      {"type": "perspective", "image_size": [800, 600], "horizon": [[0, 200], [800, 200]],
       "grid": {"left": [[100, 600], [380, 220]], "right": [[700, 600], [420, 220]],
                "near": [[0, 560], [800, 560]], "far": [[0, 300], [800, 300]]},
       "ground": [[20, 140], [130, 140], [130, 20], [20, 20]], "camera_height_m": 150,
       "strokes": [{"points": [[250, 330], [350, 300], [450, 320]], "base_v": 360, "width_px": 6}]},
      {"type": "group", "name": "merged", "layers": [
        {"type": "peak", "center": [100, 100], "height_m": -80, "spread_px": 8}]}
    ])").dump();
}

TEST(LayersStack, JsonRoundTripsEveryLayerType) {
    auto stack = parseLayerStack(richStack(), "/tmp");
    ASSERT_TRUE(stack) << stack.message();
    ASSERT_EQ(stack->layers.size(), 7u);
    EXPECT_EQ(stack->bands.mid_low_cut_px, 32);
    EXPECT_EQ(stack->layers[1].weights, (BandWeights{1, 0, 0}));  // ridge default: low band only
    EXPECT_EQ(stack->layers[2].weights.low, 0.0f);
    EXPECT_FALSE(stack->layers[4].visible);
    const std::string once = layerStackToJson(*stack);
    auto again = parseLayerStack(once, "/tmp");
    ASSERT_TRUE(again) << again.message();
    EXPECT_EQ(layerStackToJson(*again), once);
    // The description names every layer.
    const std::string text = describeLayerStack(*stack);
    for (const char* word : {"fractal", "peak", "ridge", "paste", "hole_fill", "noise", "(hidden)", "perspective", "group"})
        EXPECT_NE(text.find(word), std::string::npos) << word << "\n" << text;
}

TEST(LayersStack, ParseErrorsNameTheField) {
    auto expectError = [](const char* text, const char* fragment) {
        auto r = parseLayerStack(text, "");
        ASSERT_FALSE(r) << text;
        EXPECT_NE(r.message().find(fragment), std::string::npos) << r.message();
    };
    expectError(R"([{"type":"base"},{"type":"peak","center":[1,2],"height_m":5},{"type":"peak","center":[1,2],"height_m":5,"spread_px":0}])",
                "layers[2].spread_px: must be > 0");
    expectError(R"([{"type":"peak","center":[1,2],"height_m":5,"sprad_px":3}])", "layers[0].sprad_px: unknown field");
    expectError(R"([{"type":"volcano"}])", "layers[0].type: unknown layer type");
    expectError(R"([{"type":"peak","center":[1,2],"height_m":5},{"type":"base"}])", "layers[1].type: the base layer must be the first");
    expectError(R"([{"type":"peak","center":[1,2],"height_m":5,"weights":{"low":7}}])", "layers[0].weights.low: must be in [0, 4]");
    expectError(R"([{"type":"base","band_cuts_px":[8,60]}])", "layers[0].band_cuts_px");
    expectError(R"([{"type":"ridge","points":[[0,0]],"profile_m":3}])", "layers[0].points");
    expectError(R"([{"type":"hole_fill","hole":{"rect":[0,0,10,10]},"choices":[3]}])", "layers[0].choices");
    expectError(R"([{"type":"group","layers":[{"type":"peak","center":[0,0]}]}])", "layers[0].layers[0].height_m: is required");
    expectError(R"([{"type":"base","source":"fbm","octaves":40}])", "layers[0].octaves");
    expectError(R"({"type":"peak"})", "layers: must be an array");
}

class LayersEditor : public ::testing::Test {
protected:
    void SetUp() override { terrain = test::crop(test::loadExemplarField("orom_alaska"), 150, 150, 256, 256); }
    static EditLayer peak(double x, double y, double h) {
        PeakParams p;
        p.center_x = x, p.center_y = y, p.height_m = h, p.spread_px = 15;
        EditLayer l;
        l.name = "peak";
        l.tool = p;
        return l;
    }
    static EditLayer ridge() {
        RidgeParams r;
        r.points = {{20, 200}, {120, 150}, {230, 190}};
        r.profile_m = {200, 500, 250};
        r.width_px = 20;
        EditLayer l;
        l.name = "ridge";
        l.tool = r;
        l.weights = defaultWeights(l.tool);
        return l;
    }
    static EditLayer paste() {
        PasteParams p;
        p.source = "terrain";
        p.source_x = 10, p.source_y = 10;
        p.dest = Region{RegionShape::Ellipse, 140, 30, 80, 80};
        EditLayer l;
        l.name = "paste";
        l.tool = p;
        return l;
    }
    Heightfield terrain;
};

TEST_F(LayersEditor, UndoAndRedoRestoreBitIdenticalHeights) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor) << editor.message();
    std::vector<std::vector<float>> states;
    auto record = [&] {
        auto h = editor->heights();
        ASSERT_TRUE(h) << h.message();
        states.push_back(h->heights);
    };
    record();
    ASSERT_TRUE(editor->addLayer(peak(80, 80, 400)));
    record();
    ASSERT_TRUE(editor->addLayer(ridge()));
    record();
    ASSERT_TRUE(editor->addLayer(paste()));
    record();
    ASSERT_TRUE(editor->setWeights(0, BandWeights{1, 0.5f, 2}));
    record();
    ASSERT_TRUE(editor->moveLayer(2, 0));  // the paste now reads only the bare terrain
    record();
    ASSERT_TRUE(editor->setVisible(1, false));
    record();
    ASSERT_TRUE(editor->setBaseWeights(BandWeights{1, 1, 0}));
    record();
    ASSERT_TRUE(editor->replaceLayer(2, peak(200, 200, -150)));
    record();
    ASSERT_TRUE(editor->mergeDown(2));
    record();
    ASSERT_TRUE(editor->removeLayer(0));
    record();
    // Every step changed the terrain, except the merge (step 9), which must not.
    for (size_t i = 1; i < states.size(); ++i) {
        if (i == 9) continue;
        EXPECT_NE(states[i], states[i - 1]) << "step " << i;
    }
    for (int i = static_cast<int>(states.size()) - 2; i >= 0; --i) {
        ASSERT_TRUE(editor->undo());
        EXPECT_EQ(editor->heights()->heights, states[i]) << "undo to state " << i;
    }
    EXPECT_FALSE(editor->undo());
    for (size_t i = 1; i < states.size(); ++i) {
        ASSERT_TRUE(editor->redo());
        EXPECT_EQ(editor->heights()->heights, states[i]) << "redo to state " << i;
    }
    EXPECT_FALSE(editor->redo());
    // A new edit clears the redo history.
    ASSERT_TRUE(editor->undo());
    ASSERT_TRUE(editor->addLayer(peak(30, 30, 100)));
    EXPECT_FALSE(editor->canRedo());
}

TEST_F(LayersEditor, InteractiveResultEqualsApplyingTheSavedStack) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor);
    ASSERT_TRUE(editor->addLayer(peak(80, 80, 400)));
    ASSERT_TRUE(editor->addLayer(paste()));
    ASSERT_TRUE(editor->addLayer(ridge()));
    ASSERT_TRUE(editor->heights());
    ASSERT_TRUE(editor->setWeights(0, BandWeights{0.3f, 1, 1}));  // below the paste: it is rebuilt
    auto interactive = editor->heights();
    auto saved = parseLayerStack(layerStackToJson(editor->stack()), "");
    ASSERT_TRUE(saved) << saved.message();
    auto batch = applyLayerStack(*saved, terrain);
    ASSERT_TRUE(batch) << batch.message();
    EXPECT_EQ(interactive->heights, batch->heights);
}

TEST_F(LayersEditor, HiddenEqualsAbsentAndAdditiveLayersCommute) {
    LayerStack with, without;
    with.layers = {peak(80, 80, 400), ridge(), peak(150, 120, 300)};
    with.layers[1].visible = false;
    without.layers = {with.layers[0], with.layers[2]};
    EXPECT_EQ(applyLayerStack(with, terrain)->heights, applyLayerStack(without, terrain)->heights);
    LayerStack swapped = without;
    std::swap(swapped.layers[0], swapped.layers[1]);
    const auto a = applyLayerStack(without, terrain), b = applyLayerStack(swapped, terrain);
    for (size_t i = 0; i < a->heights.size(); ++i) ASSERT_NEAR(a->heights[i], b->heights[i], 1e-2);
    // Order matters once a layer reads the terrain below.
    LayerStack p1, p2;
    p1.layers = {peak(50, 50, 600), paste()};
    p2.layers = {paste(), peak(50, 50, 600)};
    auto r1 = applyLayerStack(p1, terrain), r2 = applyLayerStack(p2, terrain);
    double diff = 0;
    for (size_t i = 0; i < r1->heights.size(); ++i) diff = std::max(diff, double(std::fabs(r1->heights[i] - r2->heights[i])));
    EXPECT_GT(diff, 50.0);  // the cloned area (10..90) holds the peak only in p1
}

TEST_F(LayersEditor, MergeDownKeepsTheTerrainAndBecomesOneLayer) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor);
    ASSERT_TRUE(editor->addLayer(peak(80, 80, 400)));
    ASSERT_TRUE(editor->addLayer(ridge()));
    ASSERT_TRUE(editor->addLayer(paste()));
    ASSERT_TRUE(editor->setWeights(0, BandWeights{1, 0.5f, 0}));
    const std::vector<float> before = editor->heights()->heights;
    ASSERT_TRUE(editor->mergeDown(2));
    ASSERT_TRUE(editor->mergeDown(1));
    ASSERT_EQ(editor->stack().layers.size(), 1u);
    EXPECT_STREQ(toolTypeName(editor->stack().layers[0].tool), "group");
    const std::vector<float> after = editor->heights()->heights;
    for (size_t i = 0; i < before.size(); ++i) ASSERT_NEAR(before[i], after[i], 1e-2) << i;
    // The merged layer has one set of band sliders: halving it halves the whole edit.
    ASSERT_TRUE(editor->setWeights(0, BandWeights{0.5f, 0.5f, 0.5f}));
    const std::vector<float> half = editor->heights()->heights;
    for (size_t i = 0; i < half.size(); i += 97)
        ASSERT_NEAR(half[i] - terrain.heights[i], 0.5 * (before[i] - terrain.heights[i]), 0.5) << i;
    EXPECT_FALSE(editor->mergeDown(0));  // nothing below the bottom layer
}

TEST_F(LayersEditor, InvalidEditsChangeNothing) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor);
    EditLayer bad = peak(10, 10, 100);
    std::get<PeakParams>(bad.tool).spread_px = -1;
    const Status s = editor->addLayer(bad);
    EXPECT_FALSE(s);
    EXPECT_NE(s.message().find("spread_px"), std::string::npos) << s.message();
    EXPECT_FALSE(editor->removeLayer(0));
    EXPECT_FALSE(editor->setWeights(0, BandWeights{}));
    EXPECT_FALSE(editor->canUndo());
    EXPECT_EQ(editor->heights()->heights, terrain.heights);
}

TEST_F(LayersEditor, SubLayerBandsOfALayerAddUpToItsRelief) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor);
    ASSERT_TRUE(editor->addLayer(peak(100, 90, 300)));
    auto bands = editor->layerBands(0);
    ASSERT_TRUE(bands) << bands.message();
    auto relief = peakRelief(std::get<PeakParams>(editor->stack().layers[0].tool), 256, 256, terrain.meters_per_pixel_x);
    for (size_t i = 0; i < relief->heights.size(); ++i)
        ASSERT_NEAR(bands->low.heights[i] + bands->mid.heights[i] + bands->high.heights[i], relief->heights[i], 1e-2);
    auto base = editor->layerBands(-1);
    ASSERT_TRUE(base);
    EXPECT_NEAR(base->low.at(5, 5) + base->mid.at(5, 5) + base->high.at(5, 5), terrain.at(5, 5), 1e-2);
}

TEST_F(LayersEditor, HoleFillPreviewsOfferThreeVariantsAndThePickIsApplied) {
    auto editor = LayerEditor::create(LayerStack{}, terrain);
    ASSERT_TRUE(editor);
    HoleFillParams h;
    h.hole = Region{RegionShape::Ellipse, 100, 100, 48, 48};
    h.choices = {0};
    EditLayer layer;
    layer.tool = h;
    ASSERT_TRUE(editor->addLayer(layer));
    auto previews = editor->holeFillPreviews(0, 0);
    ASSERT_TRUE(previews) << previews.message();
    ASSERT_EQ(previews->size(), 3u);
    EXPECT_NE((*previews)[0].heights, (*previews)[2].heights);
    // Picking variant 2 makes the layer show it in the middle of the hole.
    h.choices = {2};
    layer.tool = h;
    ASSERT_TRUE(editor->replaceLayer(0, layer));
    auto out = editor->heights();
    EXPECT_NEAR(out->at(124, 124), (*previews)[2].at(124, 124), 1e-2);
    EXPECT_TRUE(editor->holeFillPreviews(0, 1));  // re-synthesis from the pick
    EXPECT_FALSE(editor->holeFillPreviews(0, 2));
}

TEST(LayersStackBase, FractalAndBlankBasesReplaceTheSynthesizedTerrain) {
    const Heightfield grid(128, 96, 30.0, 123.0f);
    LayerStack s;
    s.base.source = BaseSource::Blank;
    s.base.height_m = 250;
    auto blank = applyLayerStack(s, grid);
    ASSERT_TRUE(blank);
    EXPECT_NEAR(blank->at(64, 48), 250.0f, 1e-3);
    s.base.source = BaseSource::Fractal;
    s.base.fractal.kind = FractalKind::DiamondSquare;
    auto ds = applyLayerStack(s, grid);
    ASSERT_TRUE(ds);
    EXPECT_EQ(ds->width, 128);
    const Heightfield expected = fractalHeightfield(s.base.fractal, 128, 96, 30.0);
    for (size_t i = 0; i < expected.heights.size(); ++i) ASSERT_NEAR(ds->heights[i], expected.heights[i], 1e-3);
    s.base.source = BaseSource::Heightmap;
    s.base.path = "no/such/file.png";
    auto missing = applyLayerStack(s, grid);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.message().find("layers[0].path"), std::string::npos) << missing.message();
}

}  // namespace
}  // namespace terrasynth

namespace terrasynth {
namespace {
TEST(LayersStackBase, EmptyStackReturnsTheSynthesizedTerrainBitForBit) {
    const Heightfield t = test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 200, 150);
    auto out = applyLayerStack(LayerStack{}, t);
    ASSERT_TRUE(out);
    EXPECT_EQ(out->heights, t.heights);
    // With base weights it goes through the pyramid, and unit weights still reproduce it closely.
    LayerStack s;
    s.base.weights = BandWeights{1, 1, 1.0001f};
    auto near = applyLayerStack(s, t);
    ASSERT_TRUE(near);
    for (size_t i = 0; i < t.heights.size(); ++i) ASSERT_NEAR(near->heights[i], t.heights[i], 0.05);
}
}  // namespace
}  // namespace terrasynth

// The tile mesher on real DEMs: geometry, normals, winding, seams between tiles, LODs and skirts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <meshoptimizer.h>

#include "terrasynth/mesh.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

Heightfield alaska() {
    static const Heightfield field = test::loadExemplarField("orom_alaska");
    return field;
}

// Cross product z of triangle t (seen from above; > 0 is counter-clockwise).
double windingZ(const TileMesh& m, size_t t) {
    const float* a = &m.positions[3 * m.indices[3 * t]];
    const float* b = &m.positions[3 * m.indices[3 * t + 1]];
    const float* c = &m.positions[3 * m.indices[3 * t + 2]];
    return double(b[0] - a[0]) * (c[1] - a[1]) - double(b[1] - a[1]) * (c[0] - a[0]);
}

// Surface vertices lying on the line x == x_m (within 1 mm), keyed by y, with height and normal.
std::map<long, std::array<float, 4>> verticesOnX(const TileMesh& m, double x_m) {
    std::map<long, std::array<float, 4>> out;
    for (size_t v = 0; v < m.skirt_first_vertex; ++v) {
        if (std::fabs(m.positions[3 * v] - x_m) > 1e-3) continue;
        out[std::lround(m.positions[3 * v + 1] * 1000.0)] = {m.positions[3 * v + 2], m.normals[3 * v],
                                                             m.normals[3 * v + 1], m.normals[3 * v + 2]};
    }
    return out;
}

}  // namespace

TEST(MeshGrid, VerticesSitOnTheSamplesWithTrueSpacing) {
    const Heightfield tile = test::crop(alaska(), 100, 200, 65, 33);
    MeshOptions options;
    options.optimize_order = false;  // keep row-major so vertex (i, j) is j*65+i
    options.origin_x_m = 1000.0;
    options.origin_y_m = -500.0;
    const TileMesh m = meshHeightfield(tile, options);
    ASSERT_EQ(m.vertexCount(), 65u * 33u);
    ASSERT_EQ(m.triangleCount(), 2u * 64u * 32u);
    EXPECT_EQ(m.skirt_first_vertex, m.vertexCount());
    EXPECT_EQ(m.geometric_error_m, 0.0f);
    const double mpp = tile.meters_per_pixel_x;
    for (int j = 0; j < 33; j += 8) {
        for (int i = 0; i < 65; i += 16) {
            const size_t v = size_t(j) * 65 + i;
            EXPECT_NEAR(m.positions[3 * v], 1000.0 + i * mpp, 1e-3);
            EXPECT_NEAR(m.positions[3 * v + 1], -500.0 - j * mpp, 1e-3);
            EXPECT_EQ(m.positions[3 * v + 2], tile.at(i, j));
            EXPECT_NEAR(m.uvs[2 * v], i / 64.0, 1e-6);
            EXPECT_NEAR(m.uvs[2 * v + 1], j / 32.0, 1e-6);
        }
    }
}

TEST(MeshGrid, TrianglesAreCounterClockwiseFromAboveAndNormalsUnitAndUphillAware) {
    const Heightfield tile = test::crop(alaska(), 300, 300, 129, 129);
    const TileMesh m = meshHeightfield(tile);
    for (size_t t = 0; t < m.triangleCount(); ++t) ASSERT_GT(windingZ(m, t), 0.0) << "triangle " << t;
    for (size_t v = 0; v < m.vertexCount(); ++v) {
        const float* n = &m.normals[3 * v];
        ASSERT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);
        ASSERT_GT(n[2], 0.0f);
    }
    // The normal at an interior sample is the central difference at the true spacing.
    const TileMesh plain = meshHeightfield(tile, [] { MeshOptions o; o.optimize_order = false; return o; }());
    const int x = 60, y = 70;
    const double mpp = tile.meters_per_pixel_x;
    const double dzdx = (tile.at(x + 1, y) - tile.at(x - 1, y)) / (2 * mpp);
    const double dzdn = (tile.at(x, y - 1) - tile.at(x, y + 1)) / (2 * mpp);
    const double len = std::sqrt(dzdx * dzdx + dzdn * dzdn + 1.0);
    const float* n = &plain.normals[3 * (size_t(y) * 129 + x)];
    EXPECT_NEAR(n[0], -dzdx / len, 1e-5);
    EXPECT_NEAR(n[1], -dzdn / len, 1e-5);
    EXPECT_NEAR(n[2], 1.0 / len, 1e-5);
    // Alaska is mountainous: real slopes, not a flat field.
    EXPECT_GT(std::fabs(dzdx) + std::fabs(dzdn), 0.01);
}

TEST(MeshSeams, NeighbouringTilesWithApronShareEdgeVerticesAndNormals) {
    // Two 128-quad tiles side by side, each with a 1-pixel apron; the shared edge is column 128.
    const Heightfield field = alaska();
    const double mpp = field.meters_per_pixel_x;
    for (int step : {1, 4}) {
        MeshOptions options;
        options.border = step;
        options.step = step;
        const Heightfield west = test::crop(field, 100 - step, 100 - step, 129 + 2 * step, 129 + 2 * step);
        const Heightfield east = test::crop(field, 228 - step, 100 - step, 129 + 2 * step, 129 + 2 * step);
        const TileMesh a = meshHeightfield(west, options);
        MeshOptions east_options = options;
        east_options.origin_x_m = 128 * mpp;
        const TileMesh b = meshHeightfield(east, east_options);
        const auto edge_a = verticesOnX(a, 128 * mpp), edge_b = verticesOnX(b, 128 * mpp);
        ASSERT_EQ(edge_a.size(), size_t(128 / step + 1));
        EXPECT_EQ(edge_a, edge_b) << "step " << step;
    }
}

TEST(MeshSeams, WithoutApronEdgeNormalsAreOneSidedAndDiffer) {
    const Heightfield field = alaska();
    const double mpp = field.meters_per_pixel_x;
    const TileMesh a = meshHeightfield(test::crop(field, 100, 100, 129, 129));
    MeshOptions east;
    east.origin_x_m = 128 * mpp;
    const TileMesh b = meshHeightfield(test::crop(field, 228, 100, 129, 129), east);
    const auto edge_a = verticesOnX(a, 128 * mpp), edge_b = verticesOnX(b, 128 * mpp);
    ASSERT_EQ(edge_a.size(), edge_b.size());
    int differing = 0;
    for (const auto& [y, va] : edge_a) {
        EXPECT_EQ(va[0], edge_b.at(y)[0]);  // heights still meet
        differing += va[1] != edge_b.at(y)[1];
    }
    EXPECT_GT(differing, 64);  // which is why exporters pass an apron
}

TEST(MeshLods, SimplifiedLodsKeepTheFullResolutionBorder) {
    const Heightfield field = alaska();
    const double mpp = field.meters_per_pixel_x;
    const Heightfield tile = test::crop(field, 199, 199, 259, 259);  // 256 quads + 1-pixel apron
    float previous_error = 0.0f;
    size_t previous_triangles = SIZE_MAX;
    std::map<long, std::array<float, 4>> fine_edge;
    for (int lod = 0; lod < 4; ++lod) {
        MeshOptions options;
        options.border = 1;
        options.simplify_ratio = lodSimplifyRatio(lod);
        const TileMesh m = meshHeightfield(tile, options);
        EXPECT_LT(m.triangleCount(), previous_triangles);
        if (lod > 0) {
            // Locked borders cost some reduction, but the target ratio is roughly met.
            EXPECT_LT(m.triangleCount(), 2 * 256 * 256 * options.simplify_ratio * 1.5 + 4 * 256);
            EXPECT_GT(m.geometric_error_m, previous_error);
        }
        EXPECT_LT(m.geometric_error_m, heightRange(tile).max - heightRange(tile).min);
        // meshoptimizer is not height-field aware (see mesh.h): most triangles keep their winding,
        // a few fold over or stand as vertical slivers along the locked border.
        size_t upward = 0;
        for (size_t t = 0; t < m.triangleCount(); ++t) upward += windingZ(m, t) > 0.0;
        EXPECT_GT(upward, m.triangleCount() * 8 / 10) << "lod " << lod;
        for (double x : {0.0, 256 * mpp}) {
            const auto edge = verticesOnX(m, x);
            ASSERT_EQ(edge.size(), 257u) << "lod " << lod;
            if (lod == 0 && x > 0) {
                fine_edge = edge;
            } else if (x > 0) {
                EXPECT_EQ(edge, fine_edge) << "lod " << lod;
            }
        }
        previous_error = m.geometric_error_m;
        previous_triangles = m.triangleCount();
    }
}

TEST(MeshLods, GridStepsSubsampleAndMeasureTheirError) {
    const Heightfield tile = test::crop(alaska(), 0, 0, 257, 257);
    float previous = 0.0f;
    for (int lod = 1; lod < 4; ++lod) {
        MeshOptions options;
        options.step = lodStep(lod);
        const TileMesh m = meshHeightfield(tile, options);
        const size_t side = 256 / options.step + 1;
        EXPECT_EQ(m.vertexCount(), side * side);
        EXPECT_GT(m.geometric_error_m, previous);
        previous = m.geometric_error_m;
        // Every vertex is still a sample of the field.
        for (size_t v = 0; v < m.vertexCount(); v += 97) {
            const int x = int(std::lround(m.positions[3 * v] / tile.meters_per_pixel_x));
            const int y = int(std::lround(-m.positions[3 * v + 1] / tile.meters_per_pixel_y));
            ASSERT_EQ(x % options.step, 0);
            ASSERT_EQ(m.positions[3 * v + 2], tile.at(x, y));
        }
    }
}

TEST(MeshLods, StitchedGridLodsMeetAnyNeighbourLodWithoutCracks) {
    // West tile at every LOD against the east tile at full resolution: with full_res_border the
    // shared edge has the same 257 vertices (heights and normals) whatever the LODs.
    const Heightfield field = alaska();
    const double mpp = field.meters_per_pixel_x;
    const Heightfield west = test::crop(field, 99, 149, 259, 259), east = test::crop(field, 355, 149, 259, 259);
    MeshOptions fine;
    fine.border = 1;
    fine.origin_x_m = 256 * mpp;
    const auto east_edge = verticesOnX(meshHeightfield(east, fine), 256 * mpp);
    ASSERT_EQ(east_edge.size(), 257u);
    float previous_error = 0.0f;
    size_t previous_triangles = SIZE_MAX;
    for (int lod = 0; lod < 5; ++lod) {
        MeshOptions options;
        options.border = 1;
        options.step = lodStep(lod);
        options.full_res_border = true;
        const TileMesh m = meshHeightfield(west, options);
        EXPECT_EQ(verticesOnX(m, 256 * mpp), east_edge) << "lod " << lod;
        EXPECT_EQ(verticesOnX(m, 0.0).size(), 257u);
        for (size_t t = 0; t < m.triangleCount(); ++t) ASSERT_GT(windingZ(m, t), 0.0) << "lod " << lod << " t " << t;
        const size_t side = 256 / options.step + 1;
        EXPECT_EQ(m.vertexCount(), side * side + 4 * (256 - (side - 1)));
        EXPECT_LT(m.triangleCount(), previous_triangles);
        if (lod > 0) {
            EXPECT_GT(m.geometric_error_m, previous_error);
        }
        previous_error = m.geometric_error_m;
        previous_triangles = m.triangleCount();
    }
}

TEST(MeshLods, StitchingCoversTheTileExactly) {
    // The plan-view area of all triangles equals the tile's area: no holes, no overlaps (all CCW).
    const Heightfield tile = test::crop(alaska(), 20, 30, 83, 47);  // sides not multiples of the step
    for (int step : {2, 8, 64}) {
        MeshOptions options;
        options.step = step;
        options.full_res_border = true;
        const TileMesh m = meshHeightfield(tile, options);
        double area = 0.0;
        for (size_t t = 0; t < m.triangleCount(); ++t) area += 0.5 * windingZ(m, t);
        const double expected = 82 * tile.meters_per_pixel_x * 46 * tile.meters_per_pixel_y;
        EXPECT_NEAR(area, expected, 1e-6 * expected) << "step " << step;  // float positions
    }
}

TEST(MeshSkirts, HangBelowTheRingAndFaceOutwards) {
    const Heightfield tile = test::crop(alaska(), 50, 60, 33, 17);
    MeshOptions options;
    options.skirt_depth_m = 250.0f;
    options.step = 4;
    const TileMesh m = meshHeightfield(tile, options);
    const size_t ring = 2 * (8 + 4);  // 9x5 grid samples
    ASSERT_EQ(m.vertexCount() - m.skirt_first_vertex, ring);
    ASSERT_EQ((m.indices.size() - m.skirt_first_index) / 3, 2 * ring);
    // Tile centre in metres; each skirt triangle's normal must point away from it, horizontally.
    const double cx = 16 * tile.meters_per_pixel_x, cy = -8 * tile.meters_per_pixel_y;
    for (size_t i = m.skirt_first_index; i < m.indices.size(); i += 3) {
        const float* a = &m.positions[3 * m.indices[i]];
        const float* b = &m.positions[3 * m.indices[i + 1]];
        const float* c = &m.positions[3 * m.indices[i + 2]];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const double out = n[0] * (a[0] - cx) + n[1] * (a[1] - cy);
        EXPECT_GT(out, 0.0) << "skirt triangle " << i / 3 << " faces inwards";
    }
    for (size_t v = m.skirt_first_vertex; v < m.vertexCount(); ++v) {
        // The skirt vertex is 250 m below some surface vertex at the same place.
        bool found = false;
        for (size_t s = 0; s < m.skirt_first_vertex && !found; ++s)
            found = m.positions[3 * s] == m.positions[3 * v] && m.positions[3 * s + 1] == m.positions[3 * v + 1] &&
                    std::fabs(m.positions[3 * s + 2] - 250.0f - m.positions[3 * v + 2]) < 1e-3f;
        EXPECT_TRUE(found) << "skirt vertex " << v;
    }
}

TEST(MeshOrder, OptimisedOrderKeepsTheSameSurface) {
    const Heightfield tile = test::crop(alaska(), 10, 10, 65, 65);
    MeshOptions plain;
    plain.optimize_order = false;
    const TileMesh a = meshHeightfield(tile, plain);
    const TileMesh b = meshHeightfield(tile);
    ASSERT_EQ(a.vertexCount(), b.vertexCount());
    ASSERT_EQ(a.triangleCount(), b.triangleCount());
    auto triangles = [](const TileMesh& m) {
        std::vector<std::array<float, 9>> out;
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            std::array<std::array<float, 3>, 3> corners;
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) corners[k][c] = m.positions[3 * m.indices[3 * t + k] + c];
            // Rotate so the smallest corner is first (winding preserved).
            const int first = int(std::min_element(corners.begin(), corners.end()) - corners.begin());
            std::array<float, 9> key;
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) key[3 * k + c] = corners[(first + k) % 3][c];
            out.push_back(key);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(triangles(a), triangles(b));
}

TEST(MeshOrder, GridOrderIsCacheFriendly) {
    // Row-major triangles miss the post-transform cache on every new row (ACMR ~1); the banded order
    // must come close to the ideal 0.5 of a regular grid.
    const Heightfield tile = test::crop(alaska(), 0, 0, 257, 257);
    MeshOptions options;
    options.full_res_border = true;
    for (int step : {1, 2}) {
        options.step = step;
        const TileMesh m = meshHeightfield(tile, options);
        const auto stats = meshopt_analyzeVertexCache(m.indices.data(), m.indices.size(), m.vertexCount(), 16, 0, 0);
        EXPECT_LT(stats.acmr, 0.65f) << "step " << step;
        // Vertices follow first use, so fetches walk memory forwards.
        uint32_t highest = 0;
        for (uint32_t i : m.indices) {
            ASSERT_LE(i, highest + 1);
            highest = std::max(highest, i);
        }
    }
}

// heightOnGridCell is the surface of the mesh's own triangles: any point inside a cell lies on the
// triangle of the index buffer that contains it, at the height heightOnGridCell gives.
TEST(MeshGrid, HeightOnGridCellIsTheMeshTrianglesSurface) {
    const Heightfield field = test::crop(alaska(), 100, 200, 9, 9);
    MeshOptions o;
    o.optimize_order = false;
    const TileMesh mesh = meshHeightfield(field, o);
    const double s = field.meters_per_pixel_x;
    int checked = 0;
    for (double u = 0.05; u < 8.0; u += 0.37) {
        for (double w = 0.03; w < 8.0; w += 0.41) {
            const double x = u * s, y = -w * s;
            // The triangle containing (x, y) in plan view, by barycentric coordinates.
            for (size_t t = 0; t < mesh.triangleCount(); ++t) {
                const float* a = &mesh.positions[3 * mesh.indices[3 * t]];
                const float* b = &mesh.positions[3 * mesh.indices[3 * t + 1]];
                const float* c = &mesh.positions[3 * mesh.indices[3 * t + 2]];
                const double det = double(b[0] - a[0]) * (c[1] - a[1]) - double(c[0] - a[0]) * (b[1] - a[1]);
                const double l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det;
                const double l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det;
                if (l1 < -1e-9 || l2 < -1e-9 || l1 + l2 > 1.0 + 1e-9) continue;
                const double on_mesh = a[2] + l1 * (b[2] - a[2]) + l2 * (c[2] - a[2]);
                const int i = static_cast<int>(u), j = static_cast<int>(w);
                const double expected = heightOnGridCell(field.at(i, j), field.at(i + 1, j), field.at(i, j + 1),
                                                         field.at(i + 1, j + 1), u - i, w - j);
                EXPECT_NEAR(expected, on_mesh, 1e-3) << "at " << u << "," << w;
                ++checked;
                break;
            }
        }
    }
    EXPECT_GT(checked, 300);
}
